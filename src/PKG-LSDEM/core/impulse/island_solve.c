/* island_solve.c -- one contact island's velocity solve, in two stages: the resting
 * contacts as warm-started constraints (resting.c), then the collisions by the Energy
 * Tracking Method (etm.c). The rule is in lsdem_impulse.h (lsdem_island_solve). */
#include "lsdem_impulse.h"

#include <stdint.h>
#include <string.h>
#include <time.h>

void lsdem_island_params_default(lsdem_island_params *p)
{
  lsdem_etm_params_default(&p->etm);
  lsdem_resting_params_default(&p->rest);
  p->approach_floor = 0.0;
  p->collide_speed = 0.0;
}

static size_t align64(size_t n) { return (n + 63) & ~(size_t)63; }

/* Wall-clock seconds (C11 timespec_get), for the stages' time split. */
static double seconds_now(void)
{
  struct timespec ts;
  timespec_get(&ts, TIME_UTC);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The collision stage's scratch (method split): per contact its place in the subset (-1:
 * out), per body whether its contacts are in, the bodies' contacts (CSR), and the subset's
 * contacts, resting flags and collision impulses. */
typedef struct {
  int32_t *place, *start, *adj, *list;
  char *body_in;
  lsdem_impulse_contact *sub;
  uint8_t *sub_resting;
  double *sub_impulse;
} collide_ws;

static size_t collide_ws_size(int nbodies, int ncontacts)
{
  const size_t nb = (size_t)(nbodies > 0 ? nbodies : 0), nc = (size_t)(ncontacts > 0 ? ncontacts : 0);
  return align64(nc * sizeof(int32_t)) + align64((nb + 1) * sizeof(int32_t)) +
         align64(2 * nc * sizeof(int32_t)) + align64(nc * sizeof(int32_t)) + align64(nb) +
         align64(nc * sizeof(lsdem_impulse_contact)) + align64(nc) +
         align64(3 * nc * sizeof(double));
}

size_t lsdem_island_workspace_size(int nbodies, int ncontacts)
{
  const size_t rest = lsdem_resting_workspace_size(nbodies, ncontacts);
  const size_t etm = lsdem_etm_workspace_size(nbodies, ncontacts);
  return align64((size_t)(ncontacts > 0 ? ncontacts : 0) * sizeof(int32_t)) +
         collide_ws_size(nbodies, ncontacts) + (rest > etm ? rest : etm) + 64;
}

static char *carve(char **at, size_t bytes)
{
  char *p = *at;
  *at += align64(bytes);
  return p;
}

/* Stage 2's trigger for contact k: a colliding contact approaching faster than the floor,
 * or a resting one approaching faster than collide_speed. */
static int collides_at(const lsdem_impulse_body *bodies, const lsdem_impulse_contact *contacts,
                       const uint8_t *resting, const lsdem_island_params *p, int k)
{
  const double un = lsdem_impulse_normal_velocity(bodies, &contacts[k]);
  const double limit = (resting && resting[k]) ? p->collide_speed : p->approach_floor;
  return un < -limit;
}

static int collides(const lsdem_impulse_body *bodies, const lsdem_impulse_contact *contacts,
                    int ncontacts, const uint8_t *resting, const lsdem_island_params *p)
{
  for (int k = 0; k < ncontacts; k++)
    if (collides_at(bodies, contacts, resting, p, k)) return 1;
  return 0;
}

/* Body b's contacts join the subset (a wall's do not: a wall joins no island). */
static void add_body(const lsdem_impulse_body *bodies, int32_t b, const collide_ws *w, int *n)
{
  if (w->body_in[b] || lsdem_impulse_body_is_wall(&bodies[b])) return;
  w->body_in[b] = 1;
  for (int32_t e = w->start[b]; e < w->start[b + 1]; e++) {
    const int32_t k = w->adj[e];
    if (w->place[k] >= 0) continue;
    w->place[k] = *n;
    w->list[(*n)++] = k;
  }
}

/* Stage 2 of method split: ETM on the collisions and the contacts of their bodies (the
 * resting contacts that may take their impulse), grown by the contacts of the bodies at
 * both ends of any contact outside that the solve made collide, and solved again, until
 * none does; the subset in island order (ETM's tie order). */
static lsdem_status collide_locally(lsdem_impulse_body *bodies, int nbodies,
                                    const lsdem_impulse_contact *contacts, int ncontacts,
                                    const uint8_t *resting, double (*collision)[3],
                                    const lsdem_island_params *p, const collide_ws *w,
                                    void *ews, size_t ewsize, lsdem_island_result *res,
                                    lsdem_error *err)
{
  for (int i = 0; i <= nbodies; i++) w->start[i] = 0;
  for (int k = 0; k < ncontacts; k++) {
    w->start[contacts[k].a + 1]++;
    w->start[contacts[k].b + 1]++;
    w->place[k] = -1;
  }
  for (int i = 0; i < nbodies; i++) w->start[i + 1] += w->start[i];
  memset(w->body_in, 0, (size_t)(nbodies > 0 ? nbodies : 0));
  for (int i = 0; i < nbodies; i++) w->list[i] = w->start[i]; /* fill cursors */
  for (int k = 0; k < ncontacts; k++) {
    w->adj[w->list[contacts[k].a]++] = k;
    w->adj[w->list[contacts[k].b]++] = k;
  }
  int n = 0;
  for (int k = 0; k < ncontacts; k++)
    if (collides_at(bodies, contacts, resting, p, k)) {
      add_body(bodies, contacts[k].a, w, &n);
      add_body(bodies, contacts[k].b, w, &n);
    }
  lsdem_etm_params etm = p->etm;
  etm.resting = w->sub_resting;
  etm.resting_speed = p->collide_speed;
  etm.impulse = w->sub_impulse;
  int solved = 0;
  while (n > solved) {
    /* the subset in island order */
    int m = 0;
    for (int k = 0; k < ncontacts; k++)
      if (w->place[k] >= 0) w->list[m++] = k;
    for (int j = 0; j < m; j++) {
      w->sub[j] = contacts[w->list[j]];
      w->sub_resting[j] = resting[w->list[j]];
    }
    memset(w->sub_impulse, 0, sizeof(double) * 3 * (size_t)m);
    lsdem_etm_result r;
    const lsdem_status st =
        lsdem_etm_solve(bodies, nbodies, w->sub, m, &etm, ews, ewsize, &r, err);
    res->etm.iterations += r.iterations;
    res->etm.rounds = r.rounds > res->etm.rounds ? r.rounds : res->etm.rounds;
    res->etm.absorbed += r.absorbed;
    res->etm.dissipated += r.dissipated;
    res->etm.released += r.released;
    res->etm.truncated += r.truncated;
    res->etm.converged = r.converged;
    if (collision)
      for (int j = 0; j < m; j++)
        for (int i = 0; i < 3; i++) collision[w->list[j]][i] += w->sub_impulse[3 * j + i];
    if (st != LSDEM_OK) return st;
    for (int j = 0; j < m; j++) w->place[w->list[j]] = j;
    solved = n = m;
    /* grow by the contacts outside that now collide */
    for (int k = 0; k < ncontacts; k++)
      if (w->place[k] < 0 && collides_at(bodies, contacts, resting, p, k)) {
        add_body(bodies, contacts[k].a, w, &n);
        add_body(bodies, contacts[k].b, w, &n);
      }
  }
  res->etm.ncontacts = solved;
  return LSDEM_OK;
}

lsdem_status lsdem_island_solve(lsdem_impulse_body *bodies, int nbodies,
                                const lsdem_impulse_contact *contacts, int ncontacts,
                                const uint8_t *resting, double (*impulse)[3],
                                double (*collision)[3], int warm_start,
                                const lsdem_island_params *p, void *ws, size_t wsize,
                                lsdem_island_result *res, lsdem_error *err)
{
  memset(res, 0, sizeof *res);
  if (collision) memset(collision, 0, sizeof(double) * 3 * (size_t)(ncontacts > 0 ? ncontacts : 0));
  if (!ws || wsize < lsdem_island_workspace_size(nbodies, ncontacts))
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "island solve: workspace of %zu bytes, %zu needed",
                      wsize, lsdem_island_workspace_size(nbodies, ncontacts));
  char *at = (char *)(((uintptr_t)ws + 63) & ~(uintptr_t)63);
  const size_t nc = (size_t)(ncontacts > 0 ? ncontacts : 0);
  const size_t nb = (size_t)(nbodies > 0 ? nbodies : 0);
  int32_t *which = (int32_t *)carve(&at, nc * sizeof(int32_t));
  collide_ws cw;
  cw.place = (int32_t *)carve(&at, nc * sizeof(int32_t));
  cw.start = (int32_t *)carve(&at, (nb + 1) * sizeof(int32_t));
  cw.adj = (int32_t *)carve(&at, 2 * nc * sizeof(int32_t));
  cw.list = (int32_t *)carve(&at, (nc > nb ? nc : nb) * sizeof(int32_t));
  cw.body_in = carve(&at, nb);
  cw.sub = (lsdem_impulse_contact *)carve(&at, nc * sizeof(lsdem_impulse_contact));
  cw.sub_resting = (uint8_t *)carve(&at, nc);
  cw.sub_impulse = (double *)carve(&at, 3 * nc * sizeof(double));
  char *rest_ws = at;
  const size_t rest_size = wsize - (size_t)(rest_ws - (char *)ws);

  /* stage 1: resting contacts (e = 0), in the island's contact order */
  int nrest = 0;
  for (int k = 0; resting && k < ncontacts; k++)
    if (resting[k]) which[nrest++] = k;
  res->nresting = nrest;
  if (nrest > 0) {
    const double t0 = seconds_now();
    const lsdem_status st =
        lsdem_resting_solve(bodies, nbodies, contacts, ncontacts, which, nrest, impulse,
                            warm_start, &p->rest, rest_ws, rest_size, &res->rest, err);
    res->rest_seconds = seconds_now() - t0;
    if (st != LSDEM_OK) return st;
  }
  /* stage 2: collisions, ETM over the whole island; the resting contacts a collision makes
   * approach faster than the resting speed take their pair's restitution, so impulses
   * travel through a pile (lsdem_etm_params.resting), the others are inelastic */
  if (!collides(bodies, contacts, ncontacts, resting, p)) return LSDEM_OK;
  res->etm_ran = 1;
  if (nrest > 0)
    return collide_locally(bodies, nbodies, contacts, ncontacts, resting, collision, p, &cw,
                           rest_ws, rest_size, res, err);
  lsdem_etm_params etm = p->etm;
  etm.resting = nrest > 0 ? resting : NULL;
  etm.resting_speed = p->collide_speed;
  etm.impulse = collision ? &collision[0][0] : NULL;
  return lsdem_etm_solve(bodies, nbodies, contacts, ncontacts, &etm, rest_ws, rest_size,
                         &res->etm, err);
}
