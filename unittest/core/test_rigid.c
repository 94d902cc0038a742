/* test_rigid.c -- the rigid-body integrator (report eqs 2.18-2.25) against closed-form
 * solutions of the discrete scheme and the conservation laws of the torque-free top. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <math.h>
#include <string.h>

/* Leapfrog under a constant force F (no damping), starting from v^{-1/2} = v0:
 *   v^{n-1/2} = v0 + n a dt,   x^n = x0 + dt sum_{k=1..n} (v0 + k a dt)
 *             = x0 + v0 t + a t^2/2 + a t dt/2          (t = n dt, a = F/m).
 * The extra a t dt/2 is the half-step offset: the scheme's velocity at t = 0 is
 * v0 + a dt/2, i.e. x^n = x0 + (v0 + a dt/2) t + a t^2/2 exactly. */
static void test_translation_constant_force(void)
{
  double x[3] = {1.0, 2.0, 3.0}, v[3] = {0.5, -0.2, 0.1};
  const double x0[3] = {1.0, 2.0, 3.0}, v0[3] = {0.5, -0.2, 0.1};
  const double f[3] = {2.0, -1.0, 0.5}, m = 3.0, dt = 0.01;
  const int n = 1000;
  const lsdem_damped_step k = lsdem_damped_step_of(0.0, dt);
  for (int s = 0; s < n; s++) lsdem_step_translation(x, v, f, m, &k);
  const double t = n * dt;
  for (int i = 0; i < 3; i++) {
    const double a = f[i] / m;
    CHECK_REL(v[i], v0[i] + a * t, 1e-12);
    CHECK_REL(x[i], x0[i] + (v0[i] + 0.5 * a * dt) * t + 0.5 * a * t * t, 1e-12);
  }
  /* the same with the naive x0 + v0 t + a t^2/2 misses by exactly a t dt/2 */
  CHECK_REL(x[0] - (x0[0] + v0[0] * t + f[0] / m * t * t / 2), f[0] / m * t * dt / 2, 1e-9);
}

/* Free damped motion: eq 2.18 with F = 0 multiplies v by r = (1 - xi dt/2)/(1 + xi dt/2)
 * each step, so v^n = r^n v0 and x^n = x0 + dt v0 r (1 - r^n)/(1 - r). */
static void test_translation_damping(void)
{
  double x[3] = {0, 0, 0}, v[3] = {1.0, -2.0, 0.25};
  const double v0[3] = {1.0, -2.0, 0.25}, f[3] = {0, 0, 0};
  const double xi = 2.0, dt = 0.01, r = (1 - xi * dt / 2) / (1 + xi * dt / 2);
  const int n = 300;
  const lsdem_damped_step k = lsdem_damped_step_of(xi, dt);
  for (int s = 0; s < n; s++) lsdem_step_translation(x, v, f, 7.0, &k);
  for (int i = 0; i < 3; i++) {
    CHECK_REL(v[i], v0[i] * pow(r, n), 1e-12);
    CHECK_REL(x[i], dt * v0[i] * r * (1 - pow(r, n)) / (1 - r), 1e-12);
  }
}

/* Constant torque about a principal axis: no gyroscopic term, omega = omega0 + M t / I. */
static void test_rotation_constant_torque(void)
{
  const double I[3] = {1.0, 2.0, 3.0}, M[3] = {0.0, 0.6, 0.0};
  double w[3] = {0.0, 0.2, 0.0}, dw[3] = {0, 0, 0};
  const double dt = 0.01;
  const int n = 500;
  for (int s = 0; s < n; s++) lsdem_step_rotation(w, dw, M, I, 0.0, dt);
  CHECK_REL(w[1], 0.2 + M[1] * n * dt / I[1], 1e-12);
  CHECK(w[0] == 0.0 && w[2] == 0.0, "off-axis omega (%g, %g)", w[0], w[2]);
  CHECK_REL(dw[1], M[1] * dt / I[1], 1e-12);
}

/* Rotational damping about a principal axis: omega' = -xi omega, so omega decays like
 * exp(-xi t); the predictor-corrector is second-order accurate. */
static void test_rotation_damping(void)
{
  const double I[3] = {2.0, 1.0, 3.0}, M[3] = {0, 0, 0}, xi = 1.0, dt = 0.01;
  double w[3] = {1.0, 0, 0}, dw[3] = {0, 0, 0};
  const int n = 200;
  for (int s = 0; s < n; s++) lsdem_step_rotation(w, dw, M, I, xi, dt);
  CHECK_REL(w[0], exp(-xi * n * dt), 1e-4);
}

/* Torque-free asymmetric top: kinetic energy and |L| = |I omega| are invariants of
 * Euler's equations; the world-frame L = R I omega is constant. Body state at half
 * steps, orientation at whole steps: L^{n+1/2} ~ (R^n + R^{n+1})/2 I omega^{n+1/2}. */
static void world_L(const double q0[4], const double q1[4], const double I[3],
                    const double w[3], double L[3])
{
  const double Iw[3] = {I[0] * w[0], I[1] * w[1], I[2] * w[2]};
  double a[3], b[3];
  lsdem_quat_rotate(q0, Iw, a);
  lsdem_quat_rotate(q1, Iw, b);
  for (int i = 0; i < 3; i++) L[i] = 0.5 * (a[i] + b[i]);
}

static void run_top(const double w0[3], double dt, int nsteps, double *e_err, double *l_err,
                    double *lw_err, double *wmin_y)
{
  const double I[3] = {1.0, 2.0, 3.0}, zero[3] = {0, 0, 0};
  double x[3] = {0, 0, 0}, v[3] = {0, 0, 0}, q[4] = {1, 0, 0, 0}, qprev[4];
  double w[3], dw[3] = {0, 0, 0}, ww[3];
  memcpy(w, w0, sizeof w);
  const double e0 = lsdem_kinetic_rotational(I, w0);
  const double l0 = sqrt(pow(I[0] * w0[0], 2) + pow(I[1] * w0[1], 2) + pow(I[2] * w0[2], 2));
  double L0[3] = {I[0] * w0[0], I[1] * w0[1], I[2] * w0[2]};
  *e_err = *l_err = *lw_err = 0;
  *wmin_y = w0[1];
  for (int s = 0; s < nsteps; s++) {
    memcpy(qprev, q, sizeof q);
    lsdem_step_body(x, v, q, w, dw, zero, zero, 1.0, I, 0.0, dt, ww);
    const double e = lsdem_kinetic_rotational(I, w);
    const double l = sqrt(pow(I[0] * w[0], 2) + pow(I[1] * w[1], 2) + pow(I[2] * w[2], 2));
    double L[3];
    world_L(qprev, q, I, w, L);
    if (s == 0) memcpy(L0, L, sizeof L); /* first half-step value */
    const double dL[3] = {L[0] - L0[0], L[1] - L0[1], L[2] - L0[2]};
    *e_err = fmax(*e_err, fabs(e - e0) / e0);
    *l_err = fmax(*l_err, fabs(l - l0) / l0);
    *lw_err = fmax(*lw_err, sqrt(dL[0] * dL[0] + dL[1] * dL[1] + dL[2] * dL[2]) / l0);
    *wmin_y = fmin(*wmin_y, w[1]);
  }
}

static void test_torque_free_top(void)
{
  double e_err, l_err, lw_err, wmin_y;
  /* near the middle axis (unstable): the top tumbles, omega_y changes sign */
  const double w_mid[3] = {0.05, 1.0, 0.05};
  run_top(w_mid, 1e-3, 10000, &e_err, &l_err, &lw_err, &wmin_y);
  CHECK(wmin_y < -0.5, "middle-axis top did not flip: min omega_y %g", wmin_y);
  CHECK(e_err < 1e-6, "energy drift %.3g", e_err);
  CHECK(l_err < 1e-6, "|L| drift %.3g", l_err);
  CHECK(lw_err < 1e-6, "world L drift %.3g", lw_err);
  /* second order: halving dt cuts the world-L error about fourfold */
  double e2, l2, lw2, m2;
  run_top(w_mid, 5e-4, 20000, &e2, &l2, &lw2, &m2);
  CHECK(lw2 < 0.35 * lw_err, "world L error %.3g at dt/2 vs %.3g at dt", lw2, lw_err);

  /* near the largest axis (stable) */
  const double w_big[3] = {0.1, 0.1, 1.0};
  run_top(w_big, 1e-3, 10000, &e_err, &l_err, &lw_err, &wmin_y);
  CHECK(e_err < 1e-6, "energy drift %.3g", e_err);
  CHECK(l_err < 1e-6, "|L| drift %.3g", l_err);
  CHECK(lw_err < 1e-6, "world L drift %.3g", lw_err);
}

/* A whole body step with a constant world torque along a principal axis of a rotated
 * body: omega_world stays on that axis and grows like M t / I, and the orientation
 * advances by theta_n = dt sum_k omega^{k-1/2} = M dt^2 n (n+1) / (2 I) about it. */
static void test_body_step_frames(void)
{
  const double I[3] = {1.0, 2.0, 3.0}, m = 2.0, dt = 0.01;
  /* q0: 90 degrees about x, takes body y to world z */
  const double h = sqrt(0.5);
  double q[4] = {h, h, 0, 0}, q0[4] = {h, h, 0, 0};
  double x[3] = {0, 0, 0}, v[3] = {0, 0, 0}, w[3] = {0, 0, 0}, dw[3] = {0, 0, 0}, ww[3];
  const double F[3] = {0.2, 0, 0}, T[3] = {0, 0, 0.3};
  const int n = 400;
  for (int s = 0; s < n; s++) lsdem_step_body(x, v, q, w, dw, F, T, m, I, 0.0, dt, ww);
  CHECK_REL(ww[2], T[2] * n * dt / I[1], 1e-12);
  CHECK_NEAR(ww[0], 0.0, 1e-14);
  CHECK_NEAR(ww[1], 0.0, 1e-14);
  CHECK_REL(w[1], T[2] * n * dt / I[1], 1e-12);
  CHECK_REL(v[0], F[0] * n * dt / m, 1e-12);
  /* orientation: q = q0 * (rotation about body y by theta) */
  const double theta = T[2] * dt * dt * n * (n + 1) / (2 * I[1]);
  const double r[4] = {cos(theta / 2), 0, sin(theta / 2), 0};
  double qe[4];
  lsdem_quat_multiply(q0, r, qe);
  double dot = 0;
  for (int i = 0; i < 4; i++) dot += q[i] * qe[i];
  CHECK_NEAR(fabs(dot), 1.0, 1e-12);
}

static void test_kinetic(void)
{
  const double v[3] = {1.0, -2.0, 2.0}, I[3] = {1.0, 2.0, 3.0}, w[3] = {3.0, -1.0, 0.5};
  CHECK_NEAR(lsdem_kinetic_translational(4.0, v), 0.5 * 4.0 * 9.0, 1e-15);
  CHECK_NEAR(lsdem_kinetic_rotational(I, w), 0.5 * (9.0 + 2.0 + 0.75), 1e-15);
}

int main(void)
{
  test_translation_constant_force();
  test_translation_damping();
  test_rotation_constant_torque();
  test_rotation_damping();
  test_torque_free_top();
  test_body_step_frames();
  test_kinetic();
  return lsdem_test_summary();
}
