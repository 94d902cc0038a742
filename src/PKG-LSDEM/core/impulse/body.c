/* body.c -- the island's bodies and contacts: world inverse inertia, point velocities,
 * impulses (report eqs 4.2-4.13, 4.31-4.32), validation. World frame throughout. */
#include "lsdem_impulse.h"

#include <math.h>
#include <string.h>

static int finite3(const double a[3])
{
  return isfinite(a[0]) && isfinite(a[1]) && isfinite(a[2]);
}

lsdem_status lsdem_impulse_body_grain(lsdem_impulse_body *b, int64_t id, double mass,
                                      const double inertia[3], const double q[4],
                                      const double x[3], const double v[3],
                                      const double omega[3], lsdem_error *err)
{
  if (!(mass > 0.0) || !isfinite(mass))
    return lsdem_fail(err, LSDEM_ERR_NUMERIC, "impulse body %lld: mass %g is not positive",
                      (long long)id, mass);
  for (int k = 0; k < 3; k++)
    if (!(inertia[k] > 0.0) || !isfinite(inertia[k]))
      return lsdem_fail(err, LSDEM_ERR_NUMERIC,
                        "impulse body %lld: principal moment %d = %g is not positive",
                        (long long)id, k, inertia[k]);
  if (!finite3(x) || !finite3(v) || !finite3(omega) || !isfinite(q[0]) || !finite3(q + 1))
    return lsdem_fail(err, LSDEM_ERR_NUMERIC, "impulse body %lld: non-finite state",
                      (long long)id);
  double R[9];
  lsdem_quat_to_matrix(q, R);
  /* eq 4.13's I = R I0 R^T, inverted in the principal frame: I^-1 = R I0^-1 R^T */
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double s = 0.0;
      for (int k = 0; k < 3; k++) s += R[3 * i + k] * R[3 * j + k] / inertia[k];
      b->inv_inertia[3 * i + j] = s;
    }
  b->id = id;
  b->inv_mass = 1.0 / mass;
  memcpy(b->x, x, sizeof b->x);
  memcpy(b->v, v, sizeof b->v);
  memcpy(b->omega, omega, sizeof b->omega);
  return LSDEM_OK;
}

lsdem_status lsdem_impulse_body_wall(lsdem_impulse_body *b, int64_t id, const double x[3],
                                     const double v[3], const double omega[3],
                                     lsdem_error *err)
{
  if (!finite3(x) || !finite3(v) || !finite3(omega))
    return lsdem_fail(err, LSDEM_ERR_NUMERIC, "impulse wall %lld: non-finite state",
                      (long long)id);
  memset(b, 0, sizeof *b);
  b->id = id;
  memcpy(b->x, x, sizeof b->x);
  memcpy(b->v, v, sizeof b->v);
  memcpy(b->omega, omega, sizeof b->omega);
  return LSDEM_OK;
}

void lsdem_impulse_apply(lsdem_impulse_body *b, const double p[3], const double P[3])
{
  if (lsdem_impulse_body_is_wall(b)) return;
  double r[3], rxP[3], dw[3];
  lsdem_sub3(p, b->x, r);
  lsdem_cross3(r, P, rxP);
  lsdem_mat_vec(b->inv_inertia, rxP, dw);
  for (int i = 0; i < 3; i++) {
    b->v[i] += b->inv_mass * P[i]; /* eq 4.31 */
    b->omega[i] += dw[i];          /* eq 4.32 */
  }
}

double lsdem_impulse_work(const lsdem_impulse_body *b, const double J[3], const double L[3])
{
  if (lsdem_impulse_body_is_wall(b)) return 0.0;
  double dw[3];
  lsdem_mat_vec(b->inv_inertia, L, dw); /* eq 4.32 */
  /* 1/2 m |v + J/m|^2 - 1/2 m |v|^2 and 1/2 (w + dw) . I (w + dw) - 1/2 w . I w, I dw = L */
  return lsdem_dot3(J, b->v) + 0.5 * b->inv_mass * lsdem_dot3(J, J) + lsdem_dot3(L, b->omega) +
         0.5 * lsdem_dot3(L, dw);
}

double lsdem_impulse_apply_work(lsdem_impulse_body *b, const double p[3], const double P[3])
{
  double r[3], L[3];
  lsdem_sub3(p, b->x, r);
  lsdem_cross3(r, P, L);
  const double work = lsdem_impulse_work(b, P, L);
  lsdem_impulse_apply(b, p, P);
  return work;
}

/* Column j of eq 4.8's (1/m - r~ I^-1 r~) is the point velocity change of a unit impulse
 * e_j: e_j/m + (I^-1 (r x e_j)) x r. Symmetrised, so that K is exactly symmetric. */
void lsdem_impulse_point_response(const lsdem_impulse_body *b, const double p[3],
                                  double M[9])
{
  double r[3], C[9];
  lsdem_sub3(p, b->x, r);
  for (int j = 0; j < 3; j++) {
    const double e[3] = {j == 0, j == 1, j == 2};
    double rxe[3], dw[3], col[3];
    lsdem_cross3(r, e, rxe);
    lsdem_mat_vec(b->inv_inertia, rxe, dw);
    lsdem_cross3(dw, r, col);
    for (int i = 0; i < 3; i++) C[3 * i + j] = col[i] + b->inv_mass * e[i];
  }
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) M[3 * i + j] = 0.5 * (C[3 * i + j] + C[3 * j + i]);
}

void lsdem_impulse_collision_matrix(const lsdem_impulse_body *a,
                                    const lsdem_impulse_body *b, const double p[3],
                                    double K[9])
{
  double Ma[9], Mb[9];
  lsdem_impulse_point_response(a, p, Ma);
  lsdem_impulse_point_response(b, p, Mb);
  for (int i = 0; i < 9; i++) K[i] = Ma[i] + Mb[i]; /* eq 4.13 */
}

double lsdem_impulse_normal_velocity(const lsdem_impulse_body *bodies,
                                     const lsdem_impulse_contact *c)
{
  double u[3];
  return lsdem_impulse_relative_velocity(bodies, c, u);
}

static lsdem_status validate_body(const lsdem_impulse_body *b, int k, lsdem_error *err)
{
  int ok = isfinite(b->inv_mass) && b->inv_mass >= 0.0 && finite3(b->x) && finite3(b->v) &&
           finite3(b->omega);
  for (int i = 0; i < 9; i++) ok = ok && isfinite(b->inv_inertia[i]);
  if (!ok)
    return lsdem_fail(
        err, LSDEM_ERR_NUMERIC,
        "impulse island: body %d (id %lld) has a non-finite or negative state", k,
        (long long)b->id);
  return LSDEM_OK;
}

static lsdem_status validate_contact(const lsdem_impulse_body *bodies, int nbodies,
                                     const lsdem_impulse_contact *c, int k,
                                     lsdem_error *err)
{
  if (c->a < 0 || c->a >= nbodies || c->b < 0 || c->b >= nbodies || c->a == c->b)
    return lsdem_fail(err, LSDEM_ERR_ARG,
                      "impulse island: contact %d joins bodies %d and %d (of %d)", k,
                      (int)c->a, (int)c->b, nbodies);
  const lsdem_impulse_body *a = &bodies[c->a], *b = &bodies[c->b];
  if (lsdem_impulse_body_is_wall(a) && lsdem_impulse_body_is_wall(b))
    return lsdem_fail(err, LSDEM_ERR_ARG,
                      "impulse island: contact %d joins two walls (ids %lld, %lld)", k,
                      (long long)a->id, (long long)b->id);
  const double nn = lsdem_dot3(c->normal, c->normal);
  if (!finite3(c->point) || !isfinite(nn) || !isfinite(c->depth) ||
      !(fabs(nn - 1.0) < 2e-6))
    return lsdem_fail(
        err, LSDEM_ERR_NUMERIC,
        "impulse island: contact %d (ids %lld, %lld) has a non-finite point or "
        "a normal of length %g",
        k, (long long)a->id, (long long)b->id, sqrt(nn));
  if (!(c->mu >= 0.0) || !isfinite(c->mu) ||
      !(c->restitution >= 0.0 && c->restitution <= 1.0))
    return lsdem_fail(
        err, LSDEM_ERR_NUMERIC,
        "impulse island: contact %d has friction %g, restitution %g (need mu >= "
        "0, 0 <= e <= 1)",
        k, c->mu, c->restitution);
  return LSDEM_OK;
}

lsdem_status lsdem_impulse_validate(const lsdem_impulse_body *bodies, int nbodies,
                                    const lsdem_impulse_contact *contacts, int ncontacts,
                                    lsdem_error *err)
{
  if (nbodies < 0 || ncontacts < 0 || (nbodies > 0 && !bodies) ||
      (ncontacts > 0 && !contacts))
    return lsdem_fail(err, LSDEM_ERR_ARG, "impulse island: %d bodies, %d contacts", nbodies,
                      ncontacts);
  for (int k = 0; k < nbodies; k++) {
    const lsdem_status s = validate_body(&bodies[k], k, err);
    if (s != LSDEM_OK) return s;
  }
  for (int k = 0; k < ncontacts; k++) {
    const lsdem_status s = validate_contact(bodies, nbodies, &contacts[k], k, err);
    if (s != LSDEM_OK) return s;
  }
  return LSDEM_OK;
}

int lsdem_impulse_approaching(const lsdem_impulse_body *bodies, const lsdem_impulse_contact *c,
                              double floor, double *u_n)
{
  double ua[3], ub[3], u[3];
  const double un = lsdem_impulse_contact_velocities(bodies, c, ua, ub, u);
  const double noise = 1e-12 * (sqrt(lsdem_dot3(ua, ua)) + sqrt(lsdem_dot3(ub, ub)));
  if (u_n) *u_n = un;
  return un < -lsdem_max(noise, floor);
}
