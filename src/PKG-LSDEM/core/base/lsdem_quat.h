/* lsdem_quat.h -- the core's small quaternion operations and the shear springs' rotation,
 * inline (a grain's step and each contact's law call them every time step: the sphere
 * paths run them without a call). Quaternions are
 * scalar-first (w, x, y, z), body -> world (rotation.c). Declared through lsdem_base.h. */
#ifndef LSDEM_QUAT_H
#define LSDEM_QUAT_H

#include <math.h>

#include "lsdem_vec3.h"

/* q / |q|. After a time step |q|^2 = 1 + d with |d| ~ 1e-16 (round-off): then 1/sqrt(1 + d)
 * is 1 - d/2 to within 3/8 d^2 (a Newton step from 1), below the rounding of the product;
 * further from 1, sqrt. */
static inline void lsdem_quat_normalize(double q[4])
{
  const double n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  if (!(n2 > 0.0) || !isfinite(n2)) { /* a zero or broken quaternion becomes identity */
    q[0] = 1.0;
    q[1] = q[2] = q[3] = 0.0;
    return;
  }
  const double s = fabs(n2 - 1.0) < 1e-9 ? 1.5 - 0.5 * n2 : 1.0 / sqrt(n2);
  for (int i = 0; i < 4; i++) q[i] *= s;
}

/* a * b */
static inline void lsdem_quat_multiply(const double a[4], const double b[4], double out[4])
{
  const double w = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  const double x = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  const double y = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
  const double z = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
  out[0] = w;
  out[1] = x;
  out[2] = y;
  out[3] = z;
}

/* Report eq 2.28 solved exactly for constant omega over dt: dq/dt = q (0, omega_body)/2
 * => q(t+dt) = q(t) exp((0, omega_body) dt/2), and exp((0, a)) = (cos|a|, sin|a| a/|a|);
 * the same rotation from the left with the world-frame omega = R omega_body, q(t+dt) =
 * exp((0, omega) dt/2) q(t). A stable step turns a grain by far less than 0.02 rad: for
 * |a| < 0.01, cos and sin(x)/x are their Taylor series in x^2 to x^6 (the next terms,
 * x^8/8! and x^8/9!, are below 3e-21: the double result), with no sqrt or trigonometry. */
static inline void lsdem_quat_exp_half(const double omega[3], double dt, double e[4])
{
  const double half = 0.5 * dt;
  const double a[3] = {omega[0] * half, omega[1] * half, omega[2] * half};
  const double t = lsdem_dot3(a, a);
  double c, sinc;
  if (t < 1e-4) {
    c = 1.0 - t * (1.0 / 2.0 - t * (1.0 / 24.0 - t * (1.0 / 720.0)));
    sinc = 1.0 - t * (1.0 / 6.0 - t * (1.0 / 120.0 - t * (1.0 / 5040.0)));
  } else {
    const double th = sqrt(t);
    c = cos(th);
    sinc = sin(th) / th;
  }
  e[0] = c;
  for (int i = 0; i < 3; i++) e[i + 1] = sinc * a[i];
}

/* q <- exp(omega dt / 2) q (world-frame omega; see lsdem_quat_exp_half) */
static inline void lsdem_quat_turn(double q[4], const double omega[3], double dt)
{
  double e[4], r[4];
  lsdem_quat_exp_half(omega, dt, e);
  lsdem_quat_multiply(e, q, r);
  for (int i = 0; i < 4; i++) q[i] = r[i];
  lsdem_quat_normalize(q);
}

/* Minimal rotation taking unit a onto unit b, applied to v, in the division-free-axis
 * form  R v = c v + k x v + (k.v) k / (1 + c),  k = a x b, c = a.b  (Rodrigues with
 * sin(theta) k_hat = k). Its round-off grows like eps/(1 + c), so when a and b are
 * nearly opposite we instead compose a half-turn about an axis u perpendicular to a
 * (taking a to -a exactly) with the well-conditioned minimal rotation from -a to b. */
static inline void lsdem_rotate_minimal(const double v[3], const double a[3],
                                        const double b[3], double out[3])
{
  const double c = lsdem_dot3(a, b);
  double k[3], kxv[3];
  lsdem_cross3(a, b, k);
  lsdem_cross3(k, v, kxv);
  const double f = lsdem_dot3(k, v) / (1.0 + c);
  for (int i = 0; i < 3; i++) out[i] = c * v[i] + kxv[i] + f * k[i];
}

/* a unit vector perpendicular to unit a */
static inline void lsdem_perpendicular_unit(const double a[3], double u[3])
{
  /* cross a with the coordinate axis it is least aligned with */
  const double ax = fabs(a[0]), ay = fabs(a[1]), az = fabs(a[2]);
  const double e[3] = {(double)(ax <= ay && ax <= az), (double)(ay < ax && ay <= az),
                       (double)(az < ax && az < ay)};
  lsdem_cross3(a, e, u);
  const double n = sqrt(lsdem_dot3(u, u));
  for (int i = 0; i < 3; i++) u[i] /= n;
}

/* The operator Z of report eq 2.8 (lsdem_base.h): the minimal rotation taking n_old onto
 * n_new, applied to v (every shear spring, every step). */
static inline void lsdem_rotate_between(const double v[3], const double n_old[3],
                                        const double n_new[3], double out[3])
{
  const double c = lsdem_dot3(n_old, n_new);
  if (1.0 + c > 1e-6) {
    lsdem_rotate_minimal(v, n_old, n_new, out);
    return;
  }
  double u[3], w[3];
  lsdem_perpendicular_unit(n_old, u);
  const double uv = lsdem_dot3(u, v);
  for (int i = 0; i < 3; i++) w[i] = 2.0 * uv * u[i] - v[i]; /* half-turn about u */
  const double m[3] = {-n_old[0], -n_old[1], -n_old[2]};
  lsdem_rotate_minimal(w, m, n_new, out);
}

#endif /* LSDEM_QUAT_H */
