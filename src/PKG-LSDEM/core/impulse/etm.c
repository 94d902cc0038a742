/* etm.c -- the Energy Tracking Method on one contact island (report Algorithm 3, eqs 4.1,
 * 4.13-4.30, §4.4.3), after Tang et al. (2014) as modified in the report.
 *
 * A round is a compression phase (approaching contacts raised in small increments, the
 * kinetic energy they take stored per contact, eq 4.24), the restitution (W <- e^2 W,
 * eq 4.1) and a separation phase (stored energy released in small increments, eqs
 * 4.29-4.30); rounds repeat while a contact approaches (lines 34-35). Both phases pop
 * the extreme key of an indexed heap (queue.h) with the group Gamma of similar keys
 * (beta). The increments of a group's contacts are all computed from the velocities
 * before the group and applied together (lines 10-17), so that contacts alike in a
 * symmetric configuration stay alike (a block landing flat leaves without spin) -- which
 * is why the increment is shared out (divided by |Gamma| in line 9): a member also feels
 * the others that push on its bodies. The energy booked per contact is the work of its
 * normal impulse over the group's velocity change, P_n (u_n before + u_n after) / 2 (eq
 * 4.21 for impulses applied together): in sum exactly the kinetic energy the group
 * converted. The energy audit books more: each impulse's whole work on its body as it is
 * applied (lsdem_impulse_apply_work), friction and a moving wall's share included.
 *
 * Keys: compression u~ = w u_n, w = m_a m_b / (m_a + m_b) (§4.4.3) or 1, most negative
 * first; separation -W, largest energy first. Every velocity a key depends on is
 * refreshed after a group for the contacts of the group's bodies (a body -> contacts
 * table; walls are skipped, their velocity never changes), each contact once per group
 * (a stamp): refreshing it again, its velocities unchanged, would leave the queue as it
 * is. A round's search for approaching contacts (lines 34-35) looks only at contacts on
 * bodies that an impulse moved since the last compression ended: that compression left
 * every contact not approaching (it ends with the queue empty, every key refreshed after
 * its bodies moved), and a contact whose bodies kept their velocities still is not. Both
 * only skip work whose result is known: the queues, and so the velocities, are bit for
 * bit those of refreshing every contact every time. */
#include "lsdem_impulse.h"
#include "queue.h"

#include <assert.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* What the solver keeps per contact. */
typedef struct {
  double K[9];   /* collision matrix (eq 4.13), made when first needed (contact_K) */
  double knn;    /* n . K n; < 0 until K is made */
  double weight; /* compression key = weight u_n */
  double W;      /* stored elastic energy (eq 4.24) */
  double fastest; /* the fastest approach (-u_n) it had at a compression increment */
} etm_contact;

struct lsdem_etm {
  lsdem_impulse_body *bodies;
  const lsdem_impulse_contact *contacts;
  int nbodies, ncontacts;
  lsdem_etm_params p;
  etm_contact *c;
  int32_t *adj_start, *adj; /* contacts of body i: adj[adj_start[i] .. adj_start[i+1]) */
  int32_t *group, *stack;   /* a popped group; the heap walk's stack */
  int64_t *stamp;           /* per contact: the iteration that last refreshed it */
  char *moved;              /* per body: an impulse changed it since the last compression */
  double *du, *un0, *ub, *P; /* per group member: increment, u_n before, u before (3),
                                impulse (3) */
  double *share;            /* per group member: its share 1 / (alpha n) of the increment */
  int32_t *load;            /* per body: group members pushing on it (0 between groups) */
  lsdem_etm_queue q;
  double u0, vtol;       /* initial approach speed; approaching while u_n < -vtol */
  double round_absorbed; /* energy stored in the current round */
  double mass_ratio;
  int64_t lightest_id;
  int64_t iterations;
  int rounds;
  double absorbed, dissipated, released, truncated;
  double work; /* the kinetic energy the impulses gave the moving bodies, exact */
};

void lsdem_etm_params_default(lsdem_etm_params *p)
{
  p->alpha = 2.0;
  p->beta = 0.1;
  p->mass_weighted = 1;
  p->share = LSDEM_ETM_SHARE_BODIES;
  p->velocity_tol = 1e-6;
  p->energy_tol = 1e-12;
  p->max_iterations = 1000000;
  p->max_rounds = 1000;
  p->resting = NULL;
  p->resting_speed = 0.0;
  p->impulse = NULL;
  p->min_approach = 0.0;
}

static lsdem_status check_params(const lsdem_etm_params *p, lsdem_error *err)
{
  if (!(p->alpha >= 1.0) || !isfinite(p->alpha) || !(p->beta >= 0.0 && p->beta < 1.0) ||
      !(p->velocity_tol > 0.0 && p->velocity_tol < 1.0) ||
      !(p->energy_tol > 0.0 && p->energy_tol < 1.0) || p->max_iterations < 1 ||
      p->max_rounds < 1 || !(p->min_approach >= 0.0) || !(p->resting_speed >= 0.0) ||
      (p->share != LSDEM_ETM_SHARE_BODIES && p->share != LSDEM_ETM_SHARE_GROUP))
    return lsdem_fail(
        err, LSDEM_ERR_ARG,
        "ETM parameters: alpha %g (>= 1), beta %g ([0, 1)), velocity_tol %g and "
        "energy_tol %g ((0, 1)), caps %lld and %d (>= 1), min_approach %g and resting_speed "
        "%g (>= 0)",
        p->alpha, p->beta, p->velocity_tol, p->energy_tol, (long long)p->max_iterations,
        p->max_rounds, p->min_approach, p->resting_speed);
  return LSDEM_OK;
}

/* The most of an island's fastest approach u_0 that min_approach may leave alone. Random
 * islands (3-7 bodies, test_impulse_etm) solved with floors of 0.3 u_0 and less ended
 * without energy gain in 100,000 of 100,000 cases; at 0.6 u_0 one in ~10^5 had a
 * compression round that booked a negative total (its members' increments on shared bodies
 * overshoot) and gained energy. */
#define FLOOR_CAP 0.3

/* ------------------------------------------------------------ workspace ---- */

enum { WS_ALIGN = 16 };

static size_t round_up(size_t n) { return (n + WS_ALIGN - 1) / WS_ALIGN * WS_ALIGN; }

/* The layout of the workspace: offsets from its aligned start. */
typedef struct {
  size_t contacts, key, du, un0, ub, P, share, heap, pos, group, stack, stamp, adj_start,
      adj, load, moved, total;
} ws_layout;

static ws_layout layout_of(int nbodies, int ncontacts)
{
  const size_t nc = (size_t)ncontacts, nb = (size_t)nbodies;
  ws_layout L;
  size_t at = round_up(sizeof(struct lsdem_etm));
  L.contacts = at, at += round_up(nc * sizeof(etm_contact));
  L.key = at, at += round_up(nc * sizeof(double));
  L.du = at, at += round_up(nc * sizeof(double));
  L.un0 = at, at += round_up(nc * sizeof(double));
  L.ub = at, at += round_up(3 * nc * sizeof(double));
  L.P = at, at += round_up(3 * nc * sizeof(double));
  L.share = at, at += round_up(nc * sizeof(double));
  L.heap = at, at += round_up(nc * sizeof(int32_t));
  L.pos = at, at += round_up(nc * sizeof(int32_t));
  L.group = at, at += round_up(nc * sizeof(int32_t));
  L.stack = at, at += round_up(nc * sizeof(int32_t));
  L.stamp = at, at += round_up(nc * sizeof(int64_t));
  L.adj_start = at, at += round_up((nb + 1) * sizeof(int32_t));
  L.adj = at, at += round_up(2 * nc * sizeof(int32_t));
  L.load = at, at += round_up(nb * sizeof(int32_t));
  L.moved = at, at += round_up(nb);
  L.total = at;
  return L;
}

size_t lsdem_etm_workspace_size(int nbodies, int ncontacts)
{
  if (nbodies < 0 || ncontacts < 0) return 0;
  return layout_of(nbodies, ncontacts).total + WS_ALIGN; /* + room to align the start */
}

/* ---------------------------------------------------------- per contact ---- */

/* u = u_a - u_b at contact k (eq 4.7); returns u_n. */
static double relative_velocity(const lsdem_etm *s, int32_t k, double u[3])
{
  return lsdem_impulse_relative_velocity(s->bodies, &s->contacts[k], u);
}

/* Contact k before the solve: its key's weight, no energy stored, K not made yet. */
static void prepare_contact(lsdem_etm *s, int32_t k)
{
  const lsdem_impulse_contact *ct = &s->contacts[k];
  const lsdem_impulse_body *a = &s->bodies[ct->a], *b = &s->bodies[ct->b];
  etm_contact *c = &s->c[k];
  c->knn = -1.0;
  c->weight = s->p.mass_weighted ? 1.0 / (a->inv_mass + b->inv_mass) : 1.0; /* §4.4.3 */
  c->W = 0.0;
  c->fastest = 0.0;
}

/* Contact k's K (eq 4.13) and n . K n, made the first time an impulse needs them: most of
 * a settled island's contacts never take one in ETM (the bodies do not move in a solve,
 * so K is the same whenever it is made). */
static const etm_contact *contact_K(lsdem_etm *s, int32_t k)
{
  etm_contact *c = &s->c[k];
  if (c->knn < 0.0) {
    const lsdem_impulse_contact *ct = &s->contacts[k];
    double Kn[3];
    lsdem_impulse_collision_matrix(&s->bodies[ct->a], &s->bodies[ct->b], ct->point, c->K);
    lsdem_mat_vec(c->K, ct->normal, Kn);
    c->knn = lsdem_dot3(ct->normal, Kn);
  }
  return c;
}

/* The group's increments du[g] (0: none), each the Coulomb-limited impulse of its
 * contact (eqs 4.14-4.20) from the velocities before the group (ub[3 g], as the phase
 * measured them), removing the slip in the same shares as the increment (alpha share =
 * 1/n), applied together on a and (reaction, eq 4.6) b in the group's order. Returns in
 * du[g] the normal work of member g, P_n (u_n before + u_n after) / 2 (eq 4.21), with u_n
 * before in un0[g]. */
static void apply_group(lsdem_etm *s, int32_t ng)
{
  for (int32_t g = 0; g < ng; g++) {
    const int32_t k = s->group[g];
    double *P = &s->P[3 * g];
    if (s->du[g] > 0.0)
      lsdem_coulomb_impulse(contact_K(s, k)->K, s->contacts[k].normal, &s->ub[3 * g], s->du[g],
                            s->contacts[k].mu, s->p.alpha * s->share[g], P);
    else
      P[0] = P[1] = P[2] = 0.0;
  }
  for (int32_t g = 0; g < ng; g++) {
    const lsdem_impulse_contact *ct = &s->contacts[s->group[g]];
    const double *P = &s->P[3 * g], minus[3] = {-P[0], -P[1], -P[2]};
    /* each impulse's exact work on its body, friction included (eqs 4.31-4.32) */
    s->work += lsdem_impulse_apply_work(&s->bodies[ct->a], ct->point, P);
    s->work += lsdem_impulse_apply_work(&s->bodies[ct->b], ct->point, minus);
    s->moved[ct->a] = s->moved[ct->b] = 1;
    if (s->p.impulse)
      for (int i = 0; i < 3; i++) s->p.impulse[3 * s->group[g] + i] += P[i];
  }
  for (int32_t g = 0; g < ng; g++) {
    const int32_t k = s->group[g];
    double u[3];
    const double un1 = relative_velocity(s, k, u);
    s->du[g] = lsdem_dot3(&s->P[3 * g], s->contacts[k].normal) * 0.5 * (s->un0[g] + un1);
  }
}

/* Queue contact k for compression if it approaches, else take it out. */
static void refresh_approach(lsdem_etm *s, int32_t k)
{
  double u[3];
  const double un = relative_velocity(s, k, u);
  if (un < -s->vtol)
    lsdem_etm_queue_set(&s->q, k, s->c[k].weight * un);
  else
    lsdem_etm_queue_remove(&s->q, k);
}

/* After a group: the keys of every contact of the group's (moving) bodies, each once
 * (stamped with the iteration). */
static void refresh_group(lsdem_etm *s, int32_t ng)
{
  for (int32_t g = 0; g < ng; g++) {
    const lsdem_impulse_contact *ct = &s->contacts[s->group[g]];
    const int32_t ends[2] = {ct->a, ct->b};
    for (int e = 0; e < 2; e++) {
      if (lsdem_impulse_body_is_wall(&s->bodies[ends[e]])) continue;
      for (int32_t j = s->adj_start[ends[e]]; j < s->adj_start[ends[e] + 1]; j++) {
        const int32_t k = s->adj[j];
        if (s->stamp[k] == s->iterations) continue;
        s->stamp[k] = s->iterations;
        refresh_approach(s, k);
      }
    }
  }
}

/* -------------------------------------------------------------- set up ---- */

/* body -> contacts table, each body's contacts in increasing contact index */
static void build_adjacency(lsdem_etm *s)
{
  int32_t *start = s->adj_start;
  memset(start, 0, (size_t)(s->nbodies + 1) * sizeof *start);
  for (int k = 0; k < s->ncontacts; k++) {
    start[s->contacts[k].a + 1]++;
    start[s->contacts[k].b + 1]++;
  }
  for (int i = 0; i < s->nbodies; i++) start[i + 1] += start[i];
  for (int k = 0; k < s->ncontacts; k++) {
    s->adj[start[s->contacts[k].a]++] = k;
    s->adj[start[s->contacts[k].b]++] = k;
  }
  for (int i = s->nbodies; i > 0; i--) start[i] = start[i - 1]; /* back to the starts */
  start[0] = 0;
}

/* Mass ratio and lightest grain (ties: the smaller id, whatever the body order). */
static void mass_extremes(lsdem_etm *s)
{
  double lo = HUGE_VAL, hi = 0.0;
  s->lightest_id = -1;
  for (int i = 0; i < s->nbodies; i++) {
    const lsdem_impulse_body *b = &s->bodies[i];
    if (lsdem_impulse_body_is_wall(b)) continue;
    const double m = 1.0 / b->inv_mass;
    if (m < lo || (m == lo && b->id < s->lightest_id)) {
      lo = m;
      s->lightest_id = b->id;
    }
    if (m > hi) hi = m;
  }
  s->mass_ratio = hi > 0.0 ? hi / lo : 1.0;
}

lsdem_status lsdem_etm_begin(lsdem_etm **out, void *ws, size_t wsize,
                             lsdem_impulse_body *bodies, int nbodies,
                             const lsdem_impulse_contact *contacts, int ncontacts,
                             const lsdem_etm_params *p, lsdem_error *err)
{
  lsdem_status st = check_params(p, err);
  if (st == LSDEM_OK)
    st = lsdem_impulse_validate(bodies, nbodies, contacts, ncontacts, err);
  if (st != LSDEM_OK) return st;
  if (ncontacts > INT32_MAX / 2)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "ETM: %d contacts are too many", ncontacts);
  const size_t need = lsdem_etm_workspace_size(nbodies, ncontacts);
  if (!ws || wsize < need)
    return lsdem_fail(err, LSDEM_ERR_NOMEM,
                      "ETM: workspace of %zu bytes, %zu needed (lsdem_etm_workspace_size)",
                      ws ? wsize : 0, need);
  char *base = (char *)(((uintptr_t)ws + WS_ALIGN - 1) / WS_ALIGN * WS_ALIGN);
  const ws_layout L = layout_of(nbodies, ncontacts);
  lsdem_etm *s = (lsdem_etm *)base;
  memset(s, 0, sizeof *s);
  s->bodies = bodies;
  s->contacts = contacts;
  s->nbodies = nbodies;
  s->ncontacts = ncontacts;
  s->p = *p;
  s->c = (etm_contact *)(base + L.contacts);
  s->group = (int32_t *)(base + L.group);
  s->du = (double *)(base + L.du);
  s->un0 = (double *)(base + L.un0);
  s->P = (double *)(base + L.P);
  s->share = (double *)(base + L.share);
  s->load = (int32_t *)(base + L.load);
  memset(s->load, 0, (size_t)nbodies * sizeof *s->load);
  s->stack = (int32_t *)(base + L.stack);
  s->ub = (double *)(base + L.ub);
  s->stamp = (int64_t *)(base + L.stamp);
  memset(s->stamp, 0, (size_t)ncontacts * sizeof *s->stamp); /* iterations count from 1 */
  s->moved = base + L.moved;
  memset(s->moved, 1, (size_t)nbodies); /* the first search looks at every contact */
  s->adj_start = (int32_t *)(base + L.adj_start);
  s->adj = (int32_t *)(base + L.adj);
  lsdem_etm_queue_init(&s->q, ncontacts, (int32_t *)(base + L.heap),
                       (int32_t *)(base + L.pos), (double *)(base + L.key));
  build_adjacency(s);
  mass_extremes(s);
  for (int32_t k = 0; k < ncontacts; k++) {
    prepare_contact(s, k);
    double u[3];
    s->u0 = fmax(s->u0, -relative_velocity(s, k, u));
  }
  s->vtol = fmax(p->velocity_tol * s->u0, fmin(p->min_approach, FLOOR_CAP * s->u0));
  *out = s;
  return LSDEM_OK;
}

/* ------------------------------------------------------------- phases ---- */

static double approach_left(const lsdem_etm *s)
{
  double worst = 0.0, u[3];
  for (int32_t k = 0; k < s->ncontacts; k++)
    worst = fmax(worst, -relative_velocity(s, k, u));
  return worst;
}

/* The island report (task: never a silent NaN or a hang). */
static lsdem_status cap_failure(const lsdem_etm *s, const char *what, lsdem_error *err)
{
  char ids[160];
  size_t at = 0;
  ids[0] = '\0';
  int i = 0;
  for (; i < s->nbodies && at + 24 < sizeof ids; i++)
    at += (size_t)snprintf(ids + at, sizeof ids - at, "%s%lld", i ? " " : "",
                           (long long)s->bodies[i].id);
  if (i < s->nbodies) snprintf(ids + at, sizeof ids - at, " ...");
  return lsdem_fail(
      err, LSDEM_ERR_NUMERIC,
      "impulse island of %d bodies (ids %s), %d contacts, mass ratio %.3g: ETM not "
      "converged "
      "after %lld iterations, %d rounds (%s); approach speed left %.3g of %.3g. Try a "
      "smaller "
      "time step, a larger beta, a smaller alpha, global damping, or a smaller mass ratio "
      "(stable up to ~30); a grain trapped in or squeezed by one avatar (report Figure "
      "4.8) "
      "does not converge",
      s->nbodies, ids, s->ncontacts, s->mass_ratio, (long long)s->iterations, s->rounds,
      what, approach_left(s), s->u0);
}

static int moving(const lsdem_etm *s, int32_t body)
{
  return !lsdem_impulse_body_is_wall(&s->bodies[body]);
}

/* Each member's share of the group's increment (line 9), 1 / (alpha n): n = |Gamma| as
 * printed, or (LSDEM_ETM_SHARE_BODIES) the most members pushing on one of its two moving
 * bodies, itself included -- its velocity feels no others. */
static void group_shares(lsdem_etm *s, int32_t ng)
{
  if (s->p.share == LSDEM_ETM_SHARE_GROUP) {
    for (int32_t g = 0; g < ng; g++) s->share[g] = 1.0 / (s->p.alpha * ng);
    return;
  }
  for (int32_t g = 0; g < ng; g++) {
    const lsdem_impulse_contact *ct = &s->contacts[s->group[g]];
    s->load[ct->a] += moving(s, ct->a);
    s->load[ct->b] += moving(s, ct->b);
  }
  for (int32_t g = 0; g < ng; g++) {
    const lsdem_impulse_contact *ct = &s->contacts[s->group[g]];
    const int32_t n = s->load[ct->a] > s->load[ct->b] ? s->load[ct->a] : s->load[ct->b];
    s->share[g] = 1.0 / (s->p.alpha * n);
  }
  for (int32_t g = 0; g < ng; g++) {
    const lsdem_impulse_contact *ct = &s->contacts[s->group[g]];
    s->load[ct->a] = s->load[ct->b] = 0;
  }
}

/* The group of the queue's top: contacts with keys within beta |key_min| of it (lines 8
 * and 24). Returns its size; *kmin the top's key. */
static int32_t pop_group(lsdem_etm *s, double *kmin)
{
  *kmin = s->q.key[s->q.heap[0]];
  return lsdem_etm_queue_collect(&s->q, *kmin + s->p.beta * fabs(*kmin), s->group,
                                 s->stack);
}

/* One iteration of either phase begins: the cap, then the group of the queue's top and
 * its members' shares. Returns the group's size, or 0 with *st the island report when the
 * cap is reached. */
static int32_t next_group(lsdem_etm *s, const char *phase, double *kmin, lsdem_status *st,
                          lsdem_error *err)
{
  if (s->iterations >= s->p.max_iterations) {
    char what[48];
    snprintf(what, sizeof what, "iteration cap in %s", phase);
    *st = cap_failure(s, what, err);
    return 0;
  }
  s->iterations++;
  const int32_t ng = pop_group(s, kmin);
  group_shares(s, ng);
  return ng;
}

int lsdem_etm_approaching(lsdem_etm *s)
{
  for (int32_t k = 0; k < s->ncontacts; k++)
    if (s->moved[s->contacts[k].a] || s->moved[s->contacts[k].b]) refresh_approach(s, k);
  return s->q.n;
}

lsdem_status lsdem_etm_compress(lsdem_etm *s, lsdem_error *err)
{
  if (s->q.n == 0) return LSDEM_OK;
  s->rounds++;
  s->round_absorbed = 0.0;
  while (s->q.n > 0) {
    double kmin;
    lsdem_status st = LSDEM_OK;
    const int32_t ng = next_group(s, "compression", &kmin, &st, err);
    if (ng == 0) return st;
    for (int32_t g = 0; g < ng; g++) {
      const int32_t k = s->group[g];
      const double un = s->un0[g] = relative_velocity(s, k, &s->ub[3 * g]);
      if (-un > s->c[k].fastest) s->c[k].fastest = -un;
      double du = -kmin * s->share[g] / s->c[k].weight; /* line 9, raising u~ towards 0 */
      if (du > -un || -un - du <= s->vtol) du = -un; /* no overshoot; no tiny remainder */
      s->du[g] = du;
    }
    apply_group(s, ng);
    for (int32_t g = 0; g < ng; g++) { /* eq 4.24: kinetic -> elastic */
      s->c[s->group[g]].W -= s->du[g];
      s->round_absorbed -= s->du[g];
      s->absorbed -= s->du[g];
    }
    refresh_group(s, ng);
    assert(lsdem_etm_queue_valid(&s->q, s->ncontacts));
  }
  memset(s->moved, 0, (size_t)s->nbodies); /* no contact approaches now */
  return LSDEM_OK;
}

void lsdem_etm_restitute(lsdem_etm *s)
{
  for (int32_t k = 0; k < s->ncontacts; k++) {
    /* a resting contact that no impulse of the solve made approach faster than the
     * resting speed stays inelastic */
    const int quiet = s->p.resting && s->p.resting[k] && s->c[k].fastest <= s->p.resting_speed;
    const double e = quiet ? 0.0 : s->contacts[k].restitution, W = s->c[k].W;
    s->c[k].W = e * e * W; /* eq 4.1: W_release = e^2 W_absorbed */
    s->dissipated += W - s->c[k].W;
  }
}

/* Drop a contact's stored energy (below the truncation threshold). */
static void truncate_energy(lsdem_etm *s, int32_t k)
{
  s->truncated += s->c[k].W;
  s->c[k].W = 0.0;
  lsdem_etm_queue_remove(&s->q, k);
}

/* Member g's separation increment was 0: its share of energy is below the round-off of
 * its separating speed (-u + sqrt(u^2 + 2 W' knn) == 0), and it would be popped again
 * unchanged without end; what it stores is dropped (truncated) instead. */
static int below_round_off(const lsdem_etm *s, int32_t g)
{
  const double *P = &s->P[3 * g];
  return P[0] == 0.0 && P[1] == 0.0 && P[2] == 0.0;
}

/* The separation's truncation threshold: energy_tol of the energy this round's compression
 * stored. A compression's members push on shared bodies, so a late round can book a small
 * negative total; its threshold is then taken from all the solve's rounds (and is never
 * below 0: a threshold below 0 would queue the contacts that store nothing, W = 0, whose
 * share is 0 -- a separation that never ends, found at a large min_approach). */
static double separation_threshold(const lsdem_etm *s)
{
  const double stored = s->round_absorbed > 0.0 ? s->round_absorbed : s->absorbed;
  return s->p.energy_tol * fmax(stored, 0.0);
}

lsdem_status lsdem_etm_separate(lsdem_etm *s, lsdem_error *err)
{
  const double wtol = separation_threshold(s);
  for (int32_t k = 0; k < s->ncontacts; k++) { /* line 22 */
    lsdem_etm_queue_remove(&s->q, k);
    if (s->c[k].W > wtol)
      lsdem_etm_queue_set(&s->q, k, -s->c[k].W);
    else if (s->c[k].W != 0.0)
      truncate_energy(s, k);
  }
  while (s->q.n > 0) {
    double kmin;
    lsdem_status st = LSDEM_OK;
    const int32_t ng = next_group(s, "separation", &kmin, &st, err);
    if (ng == 0) return st;
    for (int32_t g = 0; g < ng; g++) {
      const etm_contact *c = contact_K(s, s->group[g]);
      double give = lsdem_min(-kmin * s->share[g], c->W); /* a share of the largest energy */
      if (c->W - give <= wtol) give = c->W;          /* no tiny remainder */
      /* eq 4.30 (for eq 4.29) from u_n >= 0: a contact still approaching would take the
       * elastic reversal -u_n -> u_n on top of its share, and the reversals of a group,
       * applied together, would add up on a shared body far beyond its stored energy */
      const double un =
          lsdem_max(s->un0[g] = relative_velocity(s, s->group[g], &s->ub[3 * g]), 0.0);
      s->du[g] = -un + sqrt(un * un + 2.0 * give * c->knn);
    }
    apply_group(s, ng);
    for (int32_t g = 0; g < ng; g++) { /* elastic -> kinetic */
      const int32_t k = s->group[g];
      s->c[k].W -= s->du[g];
      s->released += s->du[g];
      if (s->c[k].W <= wtol || below_round_off(s, g))
        truncate_energy(s, k);
      else
        lsdem_etm_queue_set(&s->q, k, -s->c[k].W);
    }
    assert(lsdem_etm_queue_valid(&s->q, s->ncontacts));
  }
  return LSDEM_OK;
}

double lsdem_etm_stored_energy(const lsdem_etm *s)
{
  double W = 0.0;
  for (int32_t k = 0; k < s->ncontacts; k++) W += s->c[k].W;
  return W;
}

void lsdem_etm_report(const lsdem_etm *s, lsdem_etm_result *r)
{
  memset(r, 0, sizeof *r);
  r->approach = approach_left(s);
  r->converged = !(r->approach > s->vtol) && lsdem_etm_stored_energy(s) == 0.0;
  r->iterations = s->iterations;
  r->rounds = s->rounds;
  r->nbodies = s->nbodies;
  r->ncontacts = s->ncontacts;
  r->mass_ratio = s->mass_ratio;
  r->lightest_id = s->lightest_id;
  r->initial_approach = s->u0;
  r->absorbed = s->absorbed;
  r->dissipated = s->dissipated;
  r->released = s->released;
  r->truncated = s->truncated;
  r->work = s->work;
}

/* --------------------------------------------------------------- solve ---- */

static lsdem_status run_rounds(lsdem_etm *s, lsdem_error *err)
{
  while (lsdem_etm_approaching(s) > 0) { /* lines 5 and 34-35 */
    if (s->rounds >= s->p.max_rounds) return cap_failure(s, "round cap", err);
    lsdem_status st = lsdem_etm_compress(s, err);
    if (st != LSDEM_OK) return st;
    lsdem_etm_restitute(s);
    if ((st = lsdem_etm_separate(s, err)) != LSDEM_OK) return st;
  }
  return LSDEM_OK;
}

/* Velocities that left the finite range (an ill-conditioned island) are an error, never
 * a silent NaN. */
static lsdem_status check_finite(const lsdem_etm *s, lsdem_error *err)
{
  for (int i = 0; i < s->nbodies; i++) {
    const lsdem_impulse_body *b = &s->bodies[i];
    double sum = 0.0;
    for (int d = 0; d < 3; d++) sum += b->v[d] + b->omega[d];
    if (!isfinite(sum))
      return lsdem_fail(err, LSDEM_ERR_NUMERIC,
                        "impulse island of %d bodies, mass ratio %.3g: body %lld left ETM "
                        "with a non-finite velocity",
                        s->nbodies, s->mass_ratio, (long long)b->id);
  }
  return LSDEM_OK;
}

lsdem_status lsdem_etm_solve(lsdem_impulse_body *bodies, int nbodies,
                             const lsdem_impulse_contact *contacts, int ncontacts,
                             const lsdem_etm_params *p, void *ws, size_t wsize,
                             lsdem_etm_result *res, lsdem_error *err)
{
  lsdem_etm *s;
  lsdem_status st =
      lsdem_etm_begin(&s, ws, wsize, bodies, nbodies, contacts, ncontacts, p, err);
  if (st != LSDEM_OK) return st;
  st = run_rounds(s, err);
  if (st == LSDEM_OK) st = check_finite(s, err);
  if (res) lsdem_etm_report(s, res);
  return st;
}
