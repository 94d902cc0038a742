/* wall.c -- resting contact of a grain on a rigid wall: the predicted-position velocity
 * correction of report §4.4.1 (Figures 4.4-4.5). The rule is in lsdem_impulse.h
 * (lsdem_wall_correct). World frame; the manifold's arms are about the grain's PREDICTED
 * centroid m->xa, and a point p of the manifold acts on the grain as the point
 * p - m->xa + grain->x does at its current pose (same arm). */
#include "lsdem_impulse.h"

#include <math.h>
#include <string.h>

void lsdem_wall_params_default(lsdem_wall_params *p, double gravity, double dt, double mu)
{
  p->rest_speed = 2.0 * fabs(gravity) * dt;
  p->depth_tol = 0.01 * fabs(gravity) * dt * dt;
  p->mu = mu;
}

double lsdem_push_out_cap(double d0, double dt, double rest_speed)
{
  const double accel = rest_speed / (2.0 * dt);
  return fmax(rest_speed, sqrt(2.0 * accel * d0));
}

int lsdem_manifold_deepest(const lsdem_manifold *m)
{
  int k = 0;
  for (int j = 1; j < m->n; j++)
    if (m->point[j].depth > m->point[k].depth) k = j;
  return k;
}

double lsdem_push_out_limit(double d, double d0, double u_n, double dt, double rest_speed)
{
  const double cap = lsdem_push_out_cap(d0, dt, rest_speed);
  return d0 / dt > cap ? fmin(d, fmax(cap - u_n, 0.0) * dt) : d; /* u_n + d' / dt = cap */
}

void lsdem_wall_limit_push_out(lsdem_manifold *m, double dt, double rest_speed)
{
  if (m->n == 0) return;
  const lsdem_contact_point *p = &m->point[lsdem_manifold_deepest(m)];
  if (!(p->depth > 0.0)) return;
  const double un = lsdem_dot3(p->vrel, p->normal);
  const double d0 = fmax(p->depth + un * dt, 0.0); /* the overlap now (§4.4.1) */
  const double d = lsdem_push_out_limit(p->depth, d0, un, dt, rest_speed);
  if (d == p->depth) return;
  const double scale = d / p->depth;
  for (int j = 0; j < m->n; j++) m->point[j].depth *= scale;
}

lsdem_wall_contact_kind lsdem_wall_classify(double u_n, double rest_speed)
{
  if (u_n < -rest_speed) return LSDEM_WALL_COLLIDING;
  if (u_n > rest_speed) return LSDEM_WALL_SEPARATING;
  return LSDEM_WALL_RESTING;
}

/* The point with the same arm from the grain's current centroid as p from the predicted. */
static void same_arm(const lsdem_impulse_body *g, const lsdem_manifold *m,
                     const double p[3], double out[3])
{
  for (int i = 0; i < 3; i++) out[i] = p[i] - m->xa[i] + g->x[i];
}

/* A distribution of normal impulse over the contact points, per unit lambda: its linear
 * part F, its angular part tau (about the predicted centroid), the weighted centre c and
 * the weighted relative velocity uc there (exact: vrel is affine in the point). */
typedef struct {
  double F[3], tau[3], c[3], uc[3];
} impulse_shape;

/* Weights w_j = area_j d_j: the overlaps' repulsive forces (report §4.4.1). */
static void overlap_shape(const lsdem_manifold *m, impulse_shape *s)
{
  double wsum = 0.0;
  memset(s, 0, sizeof *s);
  for (int j = 0; j < m->n; j++) {
    const lsdem_contact_point *pt = &m->point[j];
    const double w = pt->area * pt->depth;
    double r[3], rxn[3];
    lsdem_sub3(pt->point, m->xa, r);
    lsdem_cross3(r, pt->normal, rxn);
    for (int i = 0; i < 3; i++) {
      s->F[i] += w * pt->normal[i];
      s->tau[i] += w * rxn[i];
      s->c[i] += w * pt->point[i];
      s->uc[i] += w * pt->vrel[i];
    }
    wsum += w;
  }
  for (int i = 0; i < 3; i++) {
    s->c[i] /= wsum;
    s->uc[i] /= wsum;
  }
}

/* The deepest point k alone, with unit weight. */
static void point_shape(const lsdem_manifold *m, int k, impulse_shape *s)
{
  const lsdem_contact_point *pt = &m->point[k];
  double r[3];
  lsdem_sub3(pt->point, m->xa, r);
  lsdem_cross3(r, pt->normal, s->tau);
  memcpy(s->F, pt->normal, sizeof s->F);
  memcpy(s->c, pt->point, sizeof s->c);
  memcpy(s->uc, pt->vrel, sizeof s->uc);
}

/* Grain velocity change (dv, dw) per unit lambda of shape s, and the normal velocity
 * change it gives point k. */
static double shape_response(const lsdem_impulse_body *g, const lsdem_manifold *m, int k,
                             const impulse_shape *s, double dv[3], double dw[3])
{
  const lsdem_contact_point *pt = &m->point[k];
  double r[3], du[3];
  for (int i = 0; i < 3; i++) dv[i] = g->inv_mass * s->F[i];
  lsdem_mat_vec(g->inv_inertia, s->tau, dw);
  lsdem_sub3(pt->point, m->xa, r);
  lsdem_cross3(dw, r, du);
  for (int i = 0; i < 3; i++) du[i] += dv[i];
  return lsdem_dot3(pt->normal, du);
}

/* Coulomb friction at the shape's centre c once the normal correction (dv, dw) is made:
 * stop the slip there if that takes at most mu jn, else mu jn against it (eqs
 * 4.18-4.19). Adds the impulse to J and its work to *work; returns 1 when at the Coulomb
 * limit with slip. */
static int apply_friction(lsdem_impulse_body *g, const lsdem_manifold *m,
                          const impulse_shape *s, const double dv[3], const double dw[3],
                          double jn, double mu, double J[3], double *work)
{
  double rc[3], nbar[3], u[3], ut[3];
  const double fl = sqrt(lsdem_dot3(s->F, s->F));
  lsdem_sub3(s->c, m->xa, rc);
  lsdem_cross3(dw, rc, u);
  for (int i = 0; i < 3; i++) {
    nbar[i] = s->F[i] / fl;
    u[i] += s->uc[i] + dv[i]; /* the slip velocity at c after the normal correction */
  }
  const double un = lsdem_dot3(u, nbar);
  for (int i = 0; i < 3; i++) ut[i] = u[i] - un * nbar[i];
  const double slip = sqrt(lsdem_dot3(ut, ut));
  if (!(slip > 0.0)) return 0;
  double t[3], cp[3], M[9], Mt[3], P[3];
  for (int i = 0; i < 3; i++) t[i] = -ut[i] / slip;
  same_arm(g, m, s->c, cp);
  lsdem_impulse_point_response(g, cp, M);
  lsdem_mat_vec(M, t, Mt);
  const double need = slip / lsdem_dot3(t, Mt), jt = fmin(need, mu * jn);
  for (int i = 0; i < 3; i++) {
    P[i] = jt * t[i];
    J[i] += P[i];
  }
  *work += lsdem_impulse_apply_work(g, cp, P);
  return need > mu * jn;
}

lsdem_status lsdem_wall_correct(lsdem_impulse_body *grain, const lsdem_manifold *m,
                                double dt, const lsdem_wall_params *p,
                                lsdem_wall_result *res, lsdem_error *err)
{
  memset(res, 0, sizeof *res);
  res->deepest = -1;
  if (lsdem_impulse_body_is_wall(grain) || !(dt > 0.0) || !isfinite(dt) ||
      !(p->rest_speed >= 0.0) || !(p->depth_tol >= 0.0) || !(p->mu >= 0.0) ||
      !isfinite(p->mu))
    return lsdem_fail(err, LSDEM_ERR_ARG,
                      "wall correction of body %lld: need a grain, dt > 0 (%g), rest_speed "
                      ">= 0 (%g), depth_tol >= 0 (%g), mu >= 0 (%g)",
                      (long long)grain->id, dt, p->rest_speed, p->depth_tol, p->mu);
  res->kind = LSDEM_WALL_CLEAR;
  if (m->n == 0) return LSDEM_OK;
  const int k = lsdem_manifold_deepest(m);
  const lsdem_contact_point *deep = &m->point[k];
  res->deepest = k;
  res->depth = deep->depth;
  res->u_n = lsdem_dot3(deep->vrel, deep->normal);
  if (deep->depth <= p->depth_tol) return LSDEM_OK; /* clear */
  res->kind = lsdem_wall_classify(res->u_n, p->rest_speed);
  if (res->kind != LSDEM_WALL_RESTING) return LSDEM_OK;

  impulse_shape s;
  double dv[3], dw[3];
  overlap_shape(m, &s);
  double keff = shape_response(grain, m, k, &s, dv, dw);
  if (!(keff > 0.0)) { /* the overlaps' torque would sink the deepest point */
    point_shape(m, k, &s);
    keff = shape_response(grain, m, k, &s, dv, dw);
  }
  const double lambda = deep->depth / (dt * keff); /* deepest point: u_n += d / dt */
  const double J[3] = {lambda * s.F[0], lambda * s.F[1], lambda * s.F[2]};
  const double L[3] = {lambda * s.tau[0], lambda * s.tau[1], lambda * s.tau[2]};
  res->work = lsdem_impulse_work(grain, J, L); /* the normal impulse's, eqs 4.31-4.32 */
  for (int i = 0; i < 3; i++) {
    dv[i] *= lambda;
    dw[i] *= lambda;
    grain->v[i] += dv[i];
    grain->omega[i] += dw[i];
    res->impulse[i] = lambda * s.F[i];
  }
  const double jn = lambda * sqrt(lsdem_dot3(s.F, s.F));
  res->sliding = apply_friction(grain, m, &s, dv, dw, jn, p->mu, res->impulse, &res->work);
  return LSDEM_OK;
}
