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

size_t lsdem_island_workspace_size(int nbodies, int ncontacts)
{
  const size_t rest = lsdem_resting_workspace_size(nbodies, ncontacts);
  const size_t etm = lsdem_etm_workspace_size(nbodies, ncontacts);
  return align64((size_t)(ncontacts > 0 ? ncontacts : 0) * sizeof(int32_t)) +
         (rest > etm ? rest : etm) + 64;
}

/* Stage 2's trigger: a colliding contact approaching faster than the floor, or a resting
 * one the resting solve left approaching faster than collide_speed. */
static int collides(const lsdem_impulse_body *bodies, const lsdem_impulse_contact *contacts,
                    int ncontacts, const uint8_t *resting, const lsdem_island_params *p)
{
  for (int k = 0; k < ncontacts; k++) {
    const double un = lsdem_impulse_normal_velocity(bodies, &contacts[k]);
    const double limit = (resting && resting[k]) ? p->collide_speed : p->approach_floor;
    if (un < -limit) return 1;
  }
  return 0;
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
  char *base = (char *)(((uintptr_t)ws + 63) & ~(uintptr_t)63);
  int32_t *which = (int32_t *)base;
  const size_t head = align64((size_t)ncontacts * sizeof(int32_t));
  char *rest_ws = base + head;
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
  lsdem_etm_params etm = p->etm;
  etm.resting = nrest > 0 ? resting : NULL;
  etm.resting_speed = p->collide_speed;
  etm.impulse = collision ? &collision[0][0] : NULL;
  return lsdem_etm_solve(bodies, nbodies, contacts, ncontacts, &etm, rest_ws, rest_size,
                         &res->etm, err);
}
