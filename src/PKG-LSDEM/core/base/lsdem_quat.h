/* lsdem_quat.h -- the core's small quaternion operations, inline (a grain's step calls them
 * every time step: fix nve/lsdem's sphere path runs them without a call). Quaternions are
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

#endif /* LSDEM_QUAT_H */
