/* resting.c -- resting contacts as constraints: projected Gauss-Seidel on accumulated,
 * warm-started impulses with Coulomb's cone (the rule is in lsdem_impulse.h,
 * lsdem_resting_solve). World frame; impulses act on body a, their opposite on b. */
#include "lsdem_impulse.h"

#include <math.h>
#include <stdint.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* The sweeps' tolerance in the island's order and in colours: colour order converges
 * otherwise; at 1e-2 a column of 6 boxes at 16x the step crept sideways for ~500 steps
 * (test lmp.impulse_resting), at 1e-3 it rests. */
static const double TOLERANCE_IN_ORDER = 1e-2, TOLERANCE_IN_COLOURS = 1e-3;

void lsdem_resting_params_default(lsdem_resting_params *p)
{
  p->max_sweeps = 30;
  p->tolerance = TOLERANCE_IN_ORDER;
  p->ref_speed = 0.0;
  p->dt = 0.0;
  p->bias = 0.2;
  p->slop = 0.0;
  p->max_push = HUGE_VAL;
  p->warm = 1.0;
  p->shock = 1;
  p->threads = 1;
  p->colours = 0;
}

void lsdem_resting_set_colours(lsdem_resting_params *p, int colours)
{
  p->colours = colours != 0;
  p->tolerance = p->colours ? TOLERANCE_IN_COLOURS : TOLERANCE_IN_ORDER;
}

/* Which side of a contact an update leaves alone: none, or (shock propagation) the side
 * nearer the walls, taken as of infinite mass. */
enum { FROZEN_NONE = 0, FROZEN_A = 1, FROZEN_B = 2 };

/* per contact in the workspace: the contact's three directions (normal, two tangents) as
 * Jacobian rows -- for direction d the arms r x d and their images I^-1 (r x d) on each
 * side, with its inverse mass (all 0 on a wall or a frozen side) -- so that a relative
 * velocity along d is d . (v_a - v_b) + (r_a x d) . w_a - (r_b x d) . w_b and an impulse
 * along d changes v and w by those images: no point velocity, cross product or inertia
 * product in the sweeps. Then K's normal and tangential blocks (eq 4.13) from the rows. */
enum { DN = 0, DT1 = 1, DT2 = 2 };
typedef struct {
  double dir[3][3];   /* n, t1, t2 (world) */
  double ra[3][3], rb[3][3];  /* r_a x d, r_b x d */
  double ia[3][3], ib[3][3];  /* I_a^-1 (r_a x d), I_b^-1 (r_b x d); 0 when not moving */
  double ma, mb;      /* inverse masses of the moving sides; 0 when not moving */
  double knn, inv_knn;
  double ktt[3];     /* the tangential block, symmetric 2x2: t1t1, t1t2, t2t2 */
  double ktt_inv[3]; /* its inverse */
  double inv_kmax;   /* 1 / its largest eigenvalue */
  double vx[3];      /* for the work on the moving sides: the point velocity of an
                        excluded side (a wall, or frozen), +u_b or -u_a; else 0 */
  double target;
} row;

static size_t align64(size_t n) { return (n + 63) & ~(size_t)63; }

/* The sweeps' colours: runs of one pair's contacts coloured so that no two runs of a colour
 * share a moving body; colours 0..NCOLOURS-2 from a 64-bit mask per body, the last for the
 * runs no such colour fits (a body in ~32 pairs), swept by one thread. */
enum { NCOLOURS = 65, MAX_THREADS = 64 };
/* the colouring's int32 arrays for n contacts: seq, pos, run_first, run_place, run_colour,
 * colour_start (struct colouring) */
#define COLOURING_INTS(n) (5 * (size_t)(n) + 2 + NCOLOURS + 1)

/* rows, then (shock) per body its level, the BFS queue, its first adjacency entry and a
 * count per level, the adjacency (two entries per contact) and the contacts' order; the
 * entry state (velocities, impulses); the colouring (runs' first contacts and order,
 * colours' first runs, bodies' masks), each contact's work and each thread's residual */
size_t lsdem_resting_workspace_size(int nbodies, int ncontacts)
{
  const size_t nc = (size_t)(ncontacts > 0 ? ncontacts : 0);
  const size_t nb = (size_t)(nbodies > 0 ? nbodies : 0);
  return align64(nc * sizeof(row)) + align64((4 * nb + 4) * sizeof(int32_t)) +
         align64(3 * nc * sizeof(int32_t)) + align64(6 * nb * sizeof(double)) +
         align64(3 * nc * sizeof(double)) +
         align64(COLOURING_INTS(nc) * sizeof(int32_t)) + align64(nb * sizeof(uint64_t)) +
         align64(nc * sizeof(double)) + align64(MAX_THREADS * 8 * sizeof(double)) + 64;
}

/* The normal speed a resting contact is driven to: the part of its overlap beyond the
 * slop, taken out at the rate bias / dt (Baumgarte's stabilisation), at most max_push; on
 * a wall at most the wall guard's push-out cap for that excess (lsdem_push_out_cap:
 * max_push, or sqrt(max_push excess / dt) for a deep overlap), so that the solve and the
 * guard take a wall overlap out at the same speed and do not undo each other's pushes. */
double lsdem_resting_target(const lsdem_resting_params *p, double depth, int on_wall)
{
  if (!(p->dt > 0.0) || !(p->bias > 0.0)) return 0.0;
  const double excess = depth - p->slop;
  if (!(excess > 0.0)) return 0.0;
  const double cap = on_wall ? lsdem_push_out_cap(excess, p->dt, p->max_push) : p->max_push;
  return fmin(p->bias * excess / p->dt, cap);
}

/* Two unit tangents completing n (world), from the axis least aligned with n. */
static void tangents(const double n[3], double t1[3], double t2[3])
{
  const double ax = fabs(n[0]), ay = fabs(n[1]), az = fabs(n[2]);
  const int k = (ax <= ay && ax <= az) ? 0 : (ay <= az ? 1 : 2);
  const double e[3] = {k == 0, k == 1, k == 2};
  lsdem_cross3(n, e, t1);
  const double len = sqrt(lsdem_dot3(t1, t1));
  for (int i = 0; i < 3; i++) t1[i] /= len;
  lsdem_cross3(n, t1, t2);
}

/* K's entry for directions d, e of the row: d . K e (eq 4.13 through the arms). */
static inline double row_k(const row *r, int d, int e)
{
  return (r->ma + r->mb) * lsdem_dot3(r->dir[d], r->dir[e]) + lsdem_dot3(r->ra[d], r->ia[e]) +
         lsdem_dot3(r->rb[d], r->ib[e]);
}

/* K's blocks (eq 4.13) from the row's arms, and the point velocity of an excluded side
 * (a_out: a takes no impulse; b_out: b). */
static void row_blocks(const lsdem_impulse_body *a, const lsdem_impulse_body *b,
                       const lsdem_impulse_contact *c, int a_out, int b_out, row *r)
{
  r->knn = row_k(r, DN, DN);
  r->inv_knn = r->knn > 0.0 ? 1.0 / r->knn : 0.0;
  const double ka = row_k(r, DT1, DT1), kb = row_k(r, DT1, DT2), kd = row_k(r, DT2, DT2);
  r->ktt[0] = ka;
  r->ktt[1] = kb;
  r->ktt[2] = kd;
  const double det = ka * kd - kb * kb;
  const double kmax = 0.5 * (ka + kd) + sqrt(0.25 * (ka - kd) * (ka - kd) + kb * kb);
  r->inv_kmax = kmax > 0.0 ? 1.0 / kmax : 0.0;
  if (det > 1e-14 * (ka + kd) * (ka + kd)) {
    r->ktt_inv[0] = kd / det;
    r->ktt_inv[1] = -kb / det;
    r->ktt_inv[2] = ka / det;
  } else {
    r->ktt_inv[0] = r->ktt_inv[1] = r->ktt_inv[2] = 0.0;
  }
  r->vx[0] = r->vx[1] = r->vx[2] = 0.0;
  if (b_out) lsdem_impulse_point_velocity(b, c->point, r->vx);
  if (a_out) {
    lsdem_impulse_point_velocity(a, c->point, r->vx);
    for (int i = 0; i < 3; i++) r->vx[i] = -r->vx[i];
  }
}

/* The row of contact c; a wall takes no impulse. */
static void make_row(const lsdem_impulse_body *bodies, const lsdem_impulse_contact *c,
                     const lsdem_resting_params *p, row *r)
{
  const lsdem_impulse_body *a = &bodies[c->a], *b = &bodies[c->b];
  const int a_out = lsdem_impulse_body_is_wall(a), b_out = lsdem_impulse_body_is_wall(b);
  memcpy(r->dir[DN], c->normal, sizeof r->dir[DN]);
  tangents(c->normal, r->dir[DT1], r->dir[DT2]);
  double ra[3], rb[3];
  lsdem_sub3(c->point, a->x, ra);
  lsdem_sub3(c->point, b->x, rb);
  r->ma = a_out ? 0.0 : a->inv_mass;
  r->mb = b_out ? 0.0 : b->inv_mass;
  for (int d = 0; d < 3; d++) {
    lsdem_cross3(ra, r->dir[d], r->ra[d]);
    lsdem_cross3(rb, r->dir[d], r->rb[d]);
    if (a_out) memset(r->ia[d], 0, sizeof r->ia[d]);
    else lsdem_mat_vec(a->inv_inertia, r->ra[d], r->ia[d]);
    if (b_out) memset(r->ib[d], 0, sizeof r->ib[d]);
    else lsdem_mat_vec(b->inv_inertia, r->rb[d], r->ib[d]);
  }
  row_blocks(a, b, c, a_out, b_out, r);
  r->target = lsdem_resting_target(p, c->depth, a_out || b_out);
}

/* The shock sweep's row of contact c (FROZEN_A or FROZEN_B): its sweeps' row `from` with
 * the frozen side's impulse response taken out, its K and the frozen side's point
 * velocity (as it is now) made again. */
static void freeze_row(const lsdem_impulse_body *bodies, const lsdem_impulse_contact *c,
                       const row *from, int frozen, row *r)
{
  const lsdem_impulse_body *a = &bodies[c->a], *b = &bodies[c->b];
  *r = *from;
  if (frozen == FROZEN_A) {
    r->ma = 0.0;
    memset(r->ia, 0, sizeof r->ia);
  } else {
    r->mb = 0.0;
    memset(r->ib, 0, sizeof r->ib);
  }
  row_blocks(a, b, c, frozen == FROZEN_A || lsdem_impulse_body_is_wall(a),
             frozen == FROZEN_B || lsdem_impulse_body_is_wall(b), r);
}

/* The threads that share n items (rows, or runs of a sweep's colours): p->threads (at most
 * MAX_THREADS) with colours and at least 64 items a thread, else one. */
static int team_for(const lsdem_resting_params *p, int n)
{
  const int most = p->threads < MAX_THREADS ? p->threads : MAX_THREADS;
  return p->colours && n >= 64 * most ? most : 1;
}

/* The rows of the contacts which[seq[0..n)], in seq's order, on team_for(p, n) threads
 * (each row its own: any thread count gives the same bits). */
static void make_rows(const lsdem_impulse_body *bodies, const lsdem_impulse_contact *contacts,
                      const int32_t *which, const int32_t *seq, int n,
                      const lsdem_resting_params *p, row *rows)
{
  const int threads = team_for(p, n);
  if (threads == 1) { /* no team: one thread's loop as the compiler makes it */
    for (int k = 0; k < n; k++)
      make_row(bodies, &contacts[which[seq[k]]], p, &rows[k]);
    return;
  }
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(threads)
#endif
  for (int k = 0; k < n; k++)
    make_row(bodies, &contacts[which[seq[k]]], p, &rows[k]);
}

/* The velocities of a contact's two bodies while it is updated, copied in and out once:
 * the update's reads of its row then cannot alias its writes to the bodies, which the
 * compiler would otherwise have to assume (and reload the row after every write). */
typedef struct {
  double va[3], wa[3], vb[3], wb[3]; /* v and omega of a, then of b */
} pair_velocity;

static void pair_velocity_load(const lsdem_impulse_body *a, const lsdem_impulse_body *b,
                               pair_velocity *s)
{
  memcpy(s->va, a->v, sizeof s->va);
  memcpy(s->wa, a->omega, sizeof s->wa);
  memcpy(s->vb, b->v, sizeof s->vb);
  memcpy(s->wb, b->omega, sizeof s->wb);
}

/* A side that does not move (a wall or frozen: inverse mass 0 in the row) is not written,
 * so that threads sweeping contacts on one wall never share a write. */
static void pair_velocity_store(const row *r, const pair_velocity *s, lsdem_impulse_body *a,
                                lsdem_impulse_body *b)
{
  if (r->ma != 0.0) {
    memcpy(a->v, s->va, sizeof s->va);
    memcpy(a->omega, s->wa, sizeof s->wa);
  }
  if (r->mb != 0.0) {
    memcpy(b->v, s->vb, sizeof s->vb);
    memcpy(b->omega, s->wb, sizeof s->wb);
  }
}

/* The relative velocity of the contact along the row's direction d. */
static inline double row_velocity(const row *r, const pair_velocity *s, int d)
{
  double dv[3];
  lsdem_sub3(s->va, s->vb, dv);
  return lsdem_dot3(r->dir[d], dv) + lsdem_dot3(r->ra[d], s->wa) -
         lsdem_dot3(r->rb[d], s->wb);
}

/* An impulse lambda along the row's direction d on a (and -lambda on b); a side that does
 * not move takes none. */
static inline void row_apply(const row *r, pair_velocity *s, int d, double lambda)
{
  if (r->ma != 0.0)
    for (int i = 0; i < 3; i++) {
      s->va[i] += r->ma * lambda * r->dir[d][i];
      s->wa[i] += lambda * r->ia[d][i];
    }
  if (r->mb != 0.0)
    for (int i = 0; i < 3; i++) {
      s->vb[i] -= r->mb * lambda * r->dir[d][i];
      s->wb[i] -= lambda * r->ib[d][i];
    }
}

/* Coulomb's cone: the normal part of P kept >= 0, its tangential part clipped to mu times
 * the normal part (radially: the direction of the tangential impulse is kept). */
static void project_cone(const double n[3], double mu, double P[3])
{
  const double pn = lsdem_dot3(P, n);
  if (!(pn > 0.0)) {
    P[0] = P[1] = P[2] = 0.0;
    return;
  }
  double pt[3];
  for (int i = 0; i < 3; i++) pt[i] = P[i] - pn * n[i];
  const double t = sqrt(lsdem_dot3(pt, pt)), cap = mu * pn;
  const double s = t > cap ? cap / t : 1.0;
  for (int i = 0; i < 3; i++) P[i] = pn * n[i] + s * pt[i];
}

/* A whole impulse P (world) on the contact's moving sides through its row; returns its
 * work, P . u + P . K P / 2 + P . vx with u the relative velocity before it and K from the
 * row (the same exact work as the sweeps book per increment). */
static double apply_total(lsdem_impulse_body *bodies, const lsdem_impulse_contact *c,
                          const row *r, const double P[3])
{
  pair_velocity s;
  pair_velocity_load(&bodies[c->a], &bodies[c->b], &s);
  double p[3], u[3];
  for (int d = 0; d < 3; d++) {
    p[d] = lsdem_dot3(P, r->dir[d]);
    u[d] = row_velocity(r, &s, d);
  }
  double w = lsdem_dot3(P, r->vx);
  for (int d = 0; d < 3; d++) {
    row_apply(r, &s, d, p[d]);
    w += p[d] * u[d];
    for (int e = 0; e < 3; e++) w += 0.5 * p[d] * p[e] * row_k(r, d, e);
  }
  pair_velocity_store(r, &s, &bodies[c->a], &bodies[c->b]);
  return w;
}

/* The contact's new tangential impulse (t1, t2 components) from its accumulated one p and
 * its slip u: the stick impulse, exact for the 2x2 tangential block of K, when it lies
 * within |q| <= cap; else a slide -- the slip's own direction, p - u / k_max (the largest
 * tangential stiffness: a step that never overshoots), clipped radially to cap, so that
 * a sliding contact's friction converges to -cap u / |u|, maximum dissipation, rather
 * than to the clipped stick impulse's skewed direction. Returns 1 when sticking. */
static int friction_update(const row *r, const double p[2], const double u[2], double cap,
                           double q[2])
{
  q[0] = p[0] - (r->ktt_inv[0] * u[0] + r->ktt_inv[1] * u[1]);
  q[1] = p[1] - (r->ktt_inv[1] * u[0] + r->ktt_inv[2] * u[1]);
  if (q[0] * q[0] + q[1] * q[1] <= cap * cap) return 1;
  q[0] = p[0] - u[0] * r->inv_kmax;
  q[1] = p[1] - u[1] * r->inv_kmax;
  const double qt = sqrt(q[0] * q[0] + q[1] * q[1]);
  const double s = qt > cap ? (qt > 0.0 ? cap / qt : 0.0) : 1.0;
  q[0] *= s;
  q[1] *= s;
  return 0;
}

/* One Gauss-Seidel update of contact c (row r, accumulated impulse P, world): friction
 * first (friction_update, within |P_t| <= mu P_n), then the normal impulse that brings u_n
 * to the target, added to P's normal part and kept >= 0 (the normal row last, as it
 * matters most: Box2D's order). The work of each increment on the moving sides is exact:
 * dP . u + dP . K dP / 2 + dP . vx, u the relative velocity before it. Returns the
 * residual the contact had before the update: its normal speed's distance from the target
 * when it carries impulse or falls short of the target, plus its slip when it sticks. */
static double update_contact(lsdem_impulse_body *bodies, const lsdem_impulse_contact *c,
                             const row *r, double P[3], double *work)
{
  pair_velocity s;
  pair_velocity_load(&bodies[c->a], &bodies[c->b], &s);
  const double un = row_velocity(r, &s, DN);
  const double ut[2] = {row_velocity(r, &s, DT1), row_velocity(r, &s, DT2)};
  const double pn = lsdem_dot3(P, r->dir[DN]);
  const double pt[2] = {lsdem_dot3(P, r->dir[DT1]), lsdem_dot3(P, r->dir[DT2])};
  double q[2];
  const int sticks = friction_update(r, pt, ut, c->mu * (pn > 0.0 ? pn : 0.0), q);
  double residual = (pn > 0.0 || un < r->target) ? fabs(un - r->target) : 0.0;
  if (sticks) residual += sqrt(ut[0] * ut[0] + ut[1] * ut[1]);
  double un1 = un;
  if (q[0] != pt[0] || q[1] != pt[1]) {
    const double d1 = q[0] - pt[0], d2 = q[1] - pt[1];
    double dP[3];
    for (int i = 0; i < 3; i++) dP[i] = d1 * r->dir[DT1][i] + d2 * r->dir[DT2][i];
    row_apply(r, &s, DT1, d1);
    row_apply(r, &s, DT2, d2);
    const double dPKdP = r->ktt[0] * d1 * d1 + 2.0 * r->ktt[1] * d1 * d2 + r->ktt[2] * d2 * d2;
    *work += d1 * ut[0] + d2 * ut[1] + 0.5 * dPKdP + lsdem_dot3(dP, r->vx);
    for (int i = 0; i < 3; i++) P[i] += dP[i];
    un1 = row_velocity(r, &s, DN);
  }

  /* normal: u_n to the target, the total kept >= 0 */
  const double pn1 = lsdem_max(pn + (r->target - un1) * r->inv_knn, 0.0);
  if (pn1 != pn) {
    const double dpn = pn1 - pn;
    row_apply(r, &s, DN, dpn);
    *work += dpn * un1 + 0.5 * dpn * dpn * r->knn + dpn * lsdem_dot3(r->dir[DN], r->vx);
    for (int i = 0; i < 3; i++) P[i] += dpn * r->dir[DN][i];
  }
  pair_velocity_store(r, &s, &bodies[c->a], &bodies[c->b]);
  return residual;
}

/* The shock sweep's scratch, carved from the workspace. */
typedef struct {
  int32_t *level, *queue, *start, *count, *adj, *order;
} shock_ws;

/* Levels of the bodies by breadth-first search over the resting contacts from the walls
 * (level 0; a body no wall reaches: INT32_MAX), in body and contact order; then the
 * contacts' order for the shock sweep: by the lower level of their two bodies (ties:
 * their order in which). O(bodies + contacts). */
static void shock_order(const lsdem_impulse_body *bodies, int nbodies,
                        const lsdem_impulse_contact *contacts, const int32_t *which,
                        int nwhich, const shock_ws *w)
{
  /* adjacency: contacts of each body (CSR) */
  for (int i = 0; i <= nbodies; i++) w->start[i] = 0;
  for (int k = 0; k < nwhich; k++) {
    w->start[contacts[which[k]].a + 1]++;
    w->start[contacts[which[k]].b + 1]++;
  }
  for (int i = 0; i < nbodies; i++) w->start[i + 1] += w->start[i];
  for (int i = 0; i < nbodies; i++) w->count[i] = w->start[i];
  for (int k = 0; k < nwhich; k++) {
    const lsdem_impulse_contact *c = &contacts[which[k]];
    w->adj[w->count[c->a]++] = k;
    w->adj[w->count[c->b]++] = k;
  }
  /* breadth-first levels from the walls */
  int head = 0, tail = 0;
  for (int i = 0; i < nbodies; i++) {
    w->level[i] = lsdem_impulse_body_is_wall(&bodies[i]) ? 0 : INT32_MAX;
    if (w->level[i] == 0) w->queue[tail++] = i;
  }
  int32_t top = 0;
  while (head < tail) {
    const int32_t i = w->queue[head++];
    for (int32_t e = w->start[i]; e < w->start[i + 1]; e++) {
      const lsdem_impulse_contact *c = &contacts[which[w->adj[e]]];
      const int32_t j = c->a == i ? c->b : c->a;
      if (w->level[j] != INT32_MAX) continue;
      w->level[j] = w->level[i] + 1;
      if (w->level[j] > top) top = w->level[j];
      w->queue[tail++] = j;
    }
  }
  /* counting sort of the contacts by their lower level (stable); unreached ones last */
  const int32_t nlev = top + 2;
  for (int32_t l = 0; l <= nlev; l++) w->count[l] = 0;
  for (int k = 0; k < nwhich; k++) {
    const lsdem_impulse_contact *c = &contacts[which[k]];
    const int32_t la = w->level[c->a], lb = w->level[c->b];
    const int32_t low = la < lb ? la : lb;
    w->count[(low == INT32_MAX ? nlev - 1 : low) + 1]++;
  }
  for (int32_t l = 0; l < nlev; l++) w->count[l + 1] += w->count[l];
  for (int k = 0; k < nwhich; k++) {
    const lsdem_impulse_contact *c = &contacts[which[k]];
    const int32_t la = w->level[c->a], lb = w->level[c->b];
    const int32_t low = la < lb ? la : lb;
    w->order[w->count[low == INT32_MAX ? nlev - 1 : low]++] = k;
  }
}

/* One Gauss-Seidel sweep in the shock order, the side nearer the walls frozen (Guendelman,
 * Bridson & Fedkiw 2003; Erleben 2007): a stack stops in one sweep, whatever its height or
 * mass ratios; contacts between bodies of one level, or no wall's, are updated as usual. */
static void shock_sweep(lsdem_impulse_body *bodies, const lsdem_impulse_contact *contacts,
                        const int32_t *which, const row *rows, const int32_t *row_of,
                        const int32_t *order, int nwhich, const int32_t *level,
                        double (*impulse)[3], double *work)
{
  for (int n = 0; n < nwhich; n++) {
    const int k = order[n];
    const lsdem_impulse_contact *c = &contacts[which[k]];
    const int32_t la = level[c->a], lb = level[c->b];
    const int frozen = la < lb ? FROZEN_A : (lb < la ? FROZEN_B : FROZEN_NONE);
    if (frozen == FROZEN_NONE) { /* the sweeps' row holds: positions do not change */
      update_contact(bodies, c, &rows[row_of[k]], impulse[which[k]], work);
      continue;
    }
    row r;
    freeze_row(bodies, c, &rows[row_of[k]], frozen, &r);
    update_contact(bodies, c, &r, impulse[which[k]], work);
  }
}

/* The sweeps' order (see NCOLOURS): the contacts of which in runs of one pair (consecutive,
 * the same two bodies), the runs coloured greedily in which's order -- a run takes the
 * lowest colour neither of its moving bodies has yet -- then listed colour by colour,
 * stably: seq. The rows are made in seq's order, so that the sweeps read them in a stream.
 * The runs of one colour share no moving body: their updates commute, so threads may share
 * a colour and every thread count gives the same bits. O(contacts). */
typedef struct {
  int32_t *seq;          /* the places in which, in the sweeps' order */
  int32_t *pos;          /* per place in which: its position in seq (and its row's) */
  int32_t *run_first;    /* nruns + 1: the runs in the sweeps' order, each one's first
                            position in seq */
  int32_t *colour_start; /* NCOLOURS + 1: each colour's first run in that order */
  int32_t *run_place;    /* nruns + 1, scratch: the runs in which's order, their first places */
  int32_t *run_colour;   /* scratch: their colours */
  uint64_t *used;        /* per body: the colours of its runs so far */
  double *work;          /* per position in seq: the work of its updates in the sweeps */
  double *part;          /* per thread (8 apart): its largest residual of a sweep */
  int nruns;
} colouring;

static int moves(const lsdem_impulse_body *b) { return !lsdem_impulse_body_is_wall(b); }

static int lowest_free_colour(uint64_t used)
{
  for (int c = 0; c < NCOLOURS - 1; c++)
    if (!(used >> c & 1u)) return c;
  return NCOLOURS - 1;
}

/* The runs of which and their colours, in which's order (run_place, run_colour). Returns
 * the runs. */
static int find_runs(const lsdem_impulse_body *bodies, int nbodies,
                     const lsdem_impulse_contact *contacts, const int32_t *which, int nwhich,
                     colouring *cl)
{
  for (int i = 0; i < nbodies; i++) cl->used[i] = 0;
  int n = 0;
  for (int k = 0; k < nwhich; k++) {
    const lsdem_impulse_contact *c = &contacts[which[k]];
    if (k > 0 && c->a == contacts[which[k - 1]].a && c->b == contacts[which[k - 1]].b) continue;
    const int ma = moves(&bodies[c->a]), mb = moves(&bodies[c->b]);
    const int colour = lowest_free_colour((ma ? cl->used[c->a] : 0) | (mb ? cl->used[c->b] : 0));
    if (colour < NCOLOURS - 1) {
      if (ma) cl->used[c->a] |= (uint64_t)1 << colour;
      if (mb) cl->used[c->b] |= (uint64_t)1 << colour;
    }
    cl->run_place[n] = k;
    cl->run_colour[n++] = colour;
  }
  cl->run_place[n] = nwhich;
  return n;
}

/* The sweeps' order: seq and pos, the runs and colours (colours), or which's own order. */
static void colour_runs(const lsdem_impulse_body *bodies, int nbodies,
                        const lsdem_impulse_contact *contacts, const int32_t *which, int nwhich,
                        int colours, colouring *cl)
{
  if (!colours) {
    for (int k = 0; k < nwhich; k++) cl->seq[k] = cl->pos[k] = k;
    cl->nruns = 0;
    return;
  }
  const int n = find_runs(bodies, nbodies, contacts, which, nwhich, cl);
  cl->nruns = n;
  /* counting sort of the runs by colour, stable: runs and contacts per colour, then each
   * colour's first run and first position in seq */
  int32_t runs_in[NCOLOURS] = {0}, places_in[NCOLOURS] = {0};
  for (int r = 0; r < n; r++) {
    runs_in[cl->run_colour[r]]++;
    places_in[cl->run_colour[r]] += cl->run_place[r + 1] - cl->run_place[r];
  }
  int32_t runs = 0, places = 0;
  for (int c = 0; c < NCOLOURS; c++) {
    const int32_t nr = runs_in[c], np = places_in[c];
    cl->colour_start[c] = runs_in[c] = runs;
    places_in[c] = places;
    runs += nr;
    places += np;
  }
  cl->colour_start[NCOLOURS] = runs;
  for (int r = 0; r < n; r++) {
    const int c = cl->run_colour[r];
    cl->run_first[runs_in[c]++] = places_in[c];
    for (int k = cl->run_place[r]; k < cl->run_place[r + 1]; k++) {
      cl->pos[k] = places_in[c];
      cl->seq[places_in[c]++] = k;
    }
  }
  cl->run_first[n] = nwhich;
}

/* The updates of the run at r in the sweeps' order (its contacts in which's order); returns
 * their largest residual. */
static double update_run(lsdem_impulse_body *bodies, const lsdem_impulse_contact *contacts,
                         const int32_t *which, const row *rows, double (*impulse)[3],
                         const colouring *cl, int r)
{
  double worst = 0.0;
  for (int n = cl->run_first[r]; n < cl->run_first[r + 1]; n++) {
    const int32_t w = which[cl->seq[n]];
    worst = lsdem_max(update_contact(bodies, &contacts[w], &rows[n], impulse[w], &cl->work[n]),
                      worst);
  }
  return worst;
}

static int thread_id(void)
{
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

static int team_size(void)
{
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}

/* A barrier of the calling team; none for a team of one (libgomp's barrier makes a system
 * call even then). Every thread of a team takes the same branch. */
static void team_barrier(void)
{
  if (team_size() > 1) {
#ifdef _OPENMP
#pragma omp barrier
#endif
  }
}

/* One sweep, colour by colour, by the calling team (the last colour by one thread);
 * returns the largest residual, the same on every thread of the team. */
static double sweep_colours(lsdem_impulse_body *bodies, const lsdem_impulse_contact *contacts,
                            const int32_t *which, const row *rows, double (*impulse)[3],
                            const colouring *cl)
{
  double worst = 0.0;
  for (int c = 0; c < NCOLOURS; c++) {
    const int from = cl->colour_start[c], to = cl->colour_start[c + 1];
    if (from == to) continue;
    if (c < NCOLOURS - 1) {
#ifdef _OPENMP
#pragma omp for schedule(static) nowait
#endif
      for (int n = from; n < to; n++)
        worst = lsdem_max(update_run(bodies, contacts, which, rows, impulse, cl, n), worst);
    } else if (thread_id() == 0) {
      for (int n = from; n < to; n++)
        worst = lsdem_max(update_run(bodies, contacts, which, rows, impulse, cl, n), worst);
    }
    team_barrier();
  }
  cl->part[8 * thread_id()] = worst;
  team_barrier();
  double all = 0.0;
  for (int t = 0; t < team_size(); t++) all = lsdem_max(cl->part[8 * t], all);
  team_barrier(); /* every thread has read part before the next sweep writes it */
  return all;
}

/* The sweeps by the calling team until the residual is below stop, at most max_sweeps;
 * thread 0 writes their count and last residual. */
static void run_sweeps(lsdem_impulse_body *bodies, const lsdem_impulse_contact *contacts,
                       const int32_t *which, const row *rows, double (*impulse)[3],
                       const colouring *cl, int max_sweeps, double stop,
                       lsdem_resting_result *res)
{
  for (int s = 0; s < max_sweeps; s++) {
    const double worst = sweep_colours(bodies, contacts, which, rows, impulse, cl);
    if (thread_id() == 0) {
      res->sweeps = s + 1;
      res->residual = worst;
      res->threads = team_size();
    }
    if (worst <= stop) break;
  }
}

/* The sweeps in which's order (no colours), until the largest residual of a sweep is below
 * stop, at most max_sweeps; the work summed in the sweeps' order. */
static void sweep_in_order(lsdem_impulse_body *bodies, const lsdem_impulse_contact *contacts,
                           const int32_t *which, int nwhich, const row *rows,
                           double (*impulse)[3], int max_sweeps, double stop,
                           lsdem_resting_result *res)
{
  for (int s = 0; s < max_sweeps; s++) {
    double worst = 0.0;
    for (int k = 0; k < nwhich; k++)
      worst = lsdem_max(update_contact(bodies, &contacts[which[k]], &rows[k],
                                       impulse[which[k]], &res->work),
                        worst);
    res->sweeps = s + 1;
    res->residual = worst;
    res->threads = 1;
    if (worst <= stop) break;
  }
}

/* The sweeps (until the residual is below tolerance x ref_speed, at most max_sweeps), on
 * p->threads threads when colouring an island with enough contacts, then the shock sweep
 * if shock (one thread: its order is by level). The work is summed per contact, then in the
 * sweeps' order: the same bits on any thread count. */
static void sweep_island(lsdem_impulse_body *bodies, int nbodies,
                         const lsdem_impulse_contact *contacts, const int32_t *which, int nwhich,
                         const row *rows, double (*impulse)[3], const lsdem_resting_params *p,
                         int shock, const shock_ws *sw, colouring *cl,
                         lsdem_resting_result *res)
{
  const double stop = p->tolerance * p->ref_speed;
  if (!p->colours) {
    sweep_in_order(bodies, contacts, which, nwhich, rows, impulse, p->max_sweeps, stop, res);
  } else {
    for (int k = 0; k < nwhich; k++) cl->work[k] = 0.0;
    const int threads = team_for(p, cl->nruns);
    if (threads > 1) {
#ifdef _OPENMP
#pragma omp parallel num_threads(threads)
#endif
      run_sweeps(bodies, contacts, which, rows, impulse, cl, p->max_sweeps, stop, res);
    } else {
      run_sweeps(bodies, contacts, which, rows, impulse, cl, p->max_sweeps, stop, res);
    }
    for (int k = 0; k < nwhich; k++) res->work += cl->work[k];
  }
  if (shock) {
    shock_order(bodies, nbodies, contacts, which, nwhich, sw);
    shock_sweep(bodies, contacts, which, rows, cl->pos, sw->order, nwhich, sw->level, impulse,
                &res->work);
  }
}

/* The most kinetic energy a resting solve may add: its bias pushing overlaps out, each
 * moving body at most at the island's fastest target (never below max_push), sum m v^2
 * (twice 1/2 m v^2: a body pushed by several contacts). */
static double bias_energy_bound(const lsdem_impulse_body *bodies, int nbodies,
                                const row *rows, int nrows, const lsdem_resting_params *p)
{
  double mass = 0.0, push = p->max_push;
  for (int i = 0; i < nbodies; i++)
    if (!lsdem_impulse_body_is_wall(&bodies[i])) mass += 1.0 / bodies[i].inv_mass;
  for (int k = 0; k < nrows; k++) push = fmax(push, rows[k].target);
  return mass * push * push;
}

/* The island's state at entry: velocities (6 per body) and accumulated impulses (3 per
 * contact of which). */
static void save_state(const lsdem_impulse_body *bodies, int nbodies, const int32_t *which,
                       int nwhich, double (*impulse)[3], double *vel, double *imp)
{
  for (int i = 0; i < nbodies; i++) {
    memcpy(vel + 6 * i, bodies[i].v, 3 * sizeof(double));
    memcpy(vel + 6 * i + 3, bodies[i].omega, 3 * sizeof(double));
  }
  for (int k = 0; k < nwhich; k++) memcpy(imp + 3 * k, impulse[which[k]], 3 * sizeof(double));
}

static void restore_state(lsdem_impulse_body *bodies, int nbodies, const int32_t *which,
                          int nwhich, double (*impulse)[3], const double *vel,
                          const double *imp)
{
  for (int i = 0; i < nbodies; i++) {
    memcpy(bodies[i].v, vel + 6 * i, 3 * sizeof(double));
    memcpy(bodies[i].omega, vel + 6 * i + 3, 3 * sizeof(double));
  }
  for (int k = 0; k < nwhich; k++) memcpy(impulse[which[k]], imp + 3 * k, 3 * sizeof(double));
}

lsdem_status lsdem_resting_solve(lsdem_impulse_body *bodies, int nbodies,
                                 const lsdem_impulse_contact *contacts, int ncontacts,
                                 const int32_t *which, int nwhich, double (*impulse)[3],
                                 int warm_start, const lsdem_resting_params *p, void *ws,
                                 size_t wsize, lsdem_resting_result *res, lsdem_error *err)
{
  memset(res, 0, sizeof *res);
  if (p->max_sweeps < 0 || !(p->tolerance >= 0.0) || !(p->ref_speed >= 0.0) ||
      !(p->dt >= 0.0) || !(p->bias >= 0.0 && p->bias <= 1.0) || !(p->slop >= 0.0) ||
      !(p->max_push >= 0.0) || !(p->warm >= 0.0 && p->warm <= 1.0) || p->threads < 1)
    return lsdem_fail(err, LSDEM_ERR_ARG,
                      "resting solve: sweeps %d (>= 0), tolerance %g, ref_speed %g, dt %g, "
                      "slop %g, max_push %g (>= 0), bias %g, warm %g (in [0, 1]), threads %d "
                      "(>= 1)",
                      p->max_sweeps, p->tolerance, p->ref_speed, p->dt, p->slop, p->max_push,
                      p->bias, p->warm, p->threads);
  if (nwhich <= 0) return LSDEM_OK;
  char *base = (char *)(((uintptr_t)ws + 63) & ~(uintptr_t)63);
  if (!ws || lsdem_resting_workspace_size(nbodies, nwhich) > wsize)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "resting solve: workspace of %zu bytes, %zu needed",
                      wsize, lsdem_resting_workspace_size(nbodies, nwhich));
  row *rows = (row *)base;
  shock_ws sw;
  sw.level = (int32_t *)(base + align64((size_t)nwhich * sizeof(row)));
  sw.queue = sw.level + nbodies;
  sw.start = sw.queue + nbodies;     /* nbodies + 1 */
  sw.count = sw.start + nbodies + 1; /* nbodies + 3 >= levels + 3 */
  sw.adj = (int32_t *)((char *)sw.level + align64((4 * (size_t)nbodies + 4) * sizeof(int32_t)));
  sw.order = sw.adj + 2 * (size_t)nwhich;
  double *saved = (double *)((char *)sw.adj + align64(3 * (size_t)nwhich * sizeof(int32_t)));
  double *saved_imp = saved + align64(6 * (size_t)nbodies * sizeof(double)) / sizeof(double);
  colouring cl;
  cl.seq = (int32_t *)((char *)saved_imp + align64(3 * (size_t)nwhich * sizeof(double)));
  cl.pos = cl.seq + nwhich;
  cl.run_first = cl.pos + nwhich;       /* nwhich + 1 */
  cl.run_place = cl.run_first + nwhich + 1; /* nwhich + 1 */
  cl.run_colour = cl.run_place + nwhich + 1;
  cl.colour_start = cl.run_colour + nwhich; /* NCOLOURS + 1 */
  cl.used = (uint64_t *)((char *)cl.seq + align64(COLOURING_INTS(nwhich) * sizeof(int32_t)));
  cl.work = (double *)((char *)cl.used + align64((size_t)nbodies * sizeof(uint64_t)));
  cl.part = (double *)((char *)cl.work + align64((size_t)nwhich * sizeof(double)));
  for (int k = 0; k < nwhich; k++) {
    const int32_t w = which[k];
    if (w < 0 || w >= ncontacts)
      return lsdem_fail(err, LSDEM_ERR_ARG, "resting solve: contact index %d of %d", w,
                        ncontacts);
    const lsdem_impulse_contact *c = &contacts[w];
    if (c->a < 0 || c->a >= nbodies || c->b < 0 || c->b >= nbodies || c->a == c->b)
      return lsdem_fail(err, LSDEM_ERR_ARG, "resting solve: contact %d joins bodies %d, %d of %d",
                        w, c->a, c->b, nbodies);
  }
  colour_runs(bodies, nbodies, contacts, which, nwhich, p->colours, &cl);
  make_rows(bodies, contacts, which, cl.seq, nwhich, p, rows);

  /* warm start: last step's accumulated impulses, re-projected on this step's cones */
  save_state(bodies, nbodies, which, nwhich, impulse, saved, saved_imp);
  for (int k = 0; warm_start && k < nwhich; k++) {
    double *P = impulse[which[k]];
    for (int i = 0; i < 3; i++) P[i] *= p->warm;
    const lsdem_impulse_contact *c = &contacts[which[k]];
    project_cone(c->normal, c->mu, P);
    if (P[0] == 0.0 && P[1] == 0.0 && P[2] == 0.0) continue;
    res->warm_work += apply_total(bodies, c, &rows[cl.pos[k]], P);
  }

  sweep_island(bodies, nbodies, contacts, which, nwhich, rows, impulse, p, p->shock, &sw, &cl,
               res);
  res->work += res->warm_work;
  /* A solve that adds more energy than its bias may -- a warm start the sweeps could not
   * relax (too few sweeps for a stiff pile), or the shock sweep handing a frozen side's
   * speed up a pile (its one-sided impulses, warm-started, grow step by step) -- is done
   * again from the entry state: cold (no warm start) and without the shock sweep. */
  if (res->work > bias_energy_bound(bodies, nbodies, rows, nwhich, p)) {
    restore_state(bodies, nbodies, which, nwhich, impulse, saved, saved_imp);
    for (int k = 0; warm_start && k < nwhich; k++)
      for (int d = 0; d < 3; d++) impulse[which[k]][d] = 0.0;
    memset(res, 0, sizeof *res);
    res->cold = 1;
    sweep_island(bodies, nbodies, contacts, which, nwhich, rows, impulse, p, 0, &sw, &cl, res);
  }
  return LSDEM_OK;
}
