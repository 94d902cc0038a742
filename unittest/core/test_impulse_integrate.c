/* test_impulse_integrate.c -- time integration of impulse mode: symplectic Euler (eqs
 * 4.37-4.40) against its closed form under constant gravity, the rotation of a body
 * spinning about a principal axis against an independent axis-angle matrix, angular
 * momentum of a free asymmetric top, global damping (eqs 4.44-4.46), the predicted pose. */
#include "impulse_fixtures.h"

/* Symplectic Euler under constant g from rest: v_n = -g n dt, x_n = x0 - g dt^2 n(n+1)/2
 * (the exact x0 - g t^2/2 plus the scheme's -g t dt/2). */
static void test_gravity_closed_form(void)
{
  const double g = 9.81, dt = 1e-3, x0[3] = {0, 0, 2.0}, z[3] = {0, 0, 0};
  fx_state s = fx_sphere(1, 0.1, x0, z);
  lsdem_impulse_body b;
  const int n = 400;
  for (int k = 0; k < n; k++) {
    fx_body_of(&s, &b);
    const double f[3] = {0, 0, -g * s.mass};
    lsdem_impulse_kick(&b, f, z, dt);
    fx_state_from(&s, &b);
    lsdem_impulse_drift(s.x, s.q, s.omega, s.v, s.inertia, dt);
  }
  CHECK_REL(s.v[2], -g * n * dt, 1e-12);
  CHECK_REL(s.x[2], 2.0 - g * dt * dt * n * (n + 1) / 2.0, 1e-12);
  CHECK(s.x[0] == 0.0 && s.x[1] == 0.0, "sideways drift");
}

/* A torque about a principal axis: omega grows by tau dt / I per kick; the orientation
 * after n steps is the rotation by the summed angles about that axis. */
static void test_spin_about_axis(void)
{
  const double x[3] = {0, 0, 0}, z[3] = {0, 0, 0}, dt = 0.01, tau = 0.3;
  const double k_axis[3] = {0.0, 0.6, 0.8};
  fx_state s = fx_grain(1, 2.0, 1.0, 1.0, 1.0, x, z, z); /* isotropic: any axis principal */
  double angle = 0.0;
  const int n = 250;
  for (int step = 0; step < n; step++) {
    lsdem_impulse_body b;
    fx_body_of(&s, &b);
    const double t[3] = {tau * k_axis[0], tau * k_axis[1], tau * k_axis[2]};
    lsdem_impulse_kick(&b, z, t, dt);
    fx_state_from(&s, &b);
    angle += dt * sqrt(lsdem_dot3(s.omega, s.omega));
    lsdem_impulse_drift(s.x, s.q, s.omega, s.v, s.inertia, dt);
  }
  CHECK_REL(sqrt(lsdem_dot3(s.omega, s.omega)), tau * n * dt / 1.0, 1e-12);
  double R[9], Rf[9];
  lsdem_quat_to_matrix(s.q, R);
  fix_axis_angle(k_axis, angle, Rf);
  double worst = 0.0;
  for (int i = 0; i < 9; i++) worst = fmax(worst, fabs(R[i] - Rf[i]));
  CHECK(worst < 1e-11, "orientation off by %g", worst);
}

/* A free asymmetric top: the world angular momentum is kept (the drift's gyroscopic
 * step), the energy stays close, omega changes direction (precession). */
static void test_free_top(void)
{
  const double x[3] = {0, 0, 0}, z[3] = {0, 0, 0}, w0[3] = {1.0, 0.2, 2.0};
  fx_state s = fx_grain(1, 1.0, 1.0, 2.0, 3.0, x, z, w0);
  fx_random_quat(s.q);
  lsdem_impulse_body b;
  fx_body_of(&s, &b);
  double L0[3] = {0, 0, 0}, p[3] = {0, 0, 0};
  fx_momenta(&s, &b, p, L0);
  const double E0 = fx_kinetic(&s, &b);
  for (int step = 0; step < 2000; step++)
    lsdem_impulse_drift(s.x, s.q, s.omega, s.v, s.inertia, 1e-3);
  fx_body_of(&s, &b);
  double L1[3] = {0, 0, 0};
  fx_momenta(&s, &b, p, L1);
  for (int i = 0; i < 3; i++) CHECK_NEAR(L1[i], L0[i], 1e-10);
  CHECK_REL(fx_kinetic(&s, &b), E0, 1e-6);
  double d[3];
  lsdem_sub3(s.omega, w0, d);
  CHECK(sqrt(lsdem_dot3(d, d)) > 0.1, "no precession");
}

/* eqs 4.44-4.46: v, omega scaled by (1 - xi dt); xi dt outside [0, 1] refused. */
static void test_damping(void)
{
  const double x[3] = {0, 0, 0}, v[3] = {1, -2, 3}, w[3] = {0.5, 0, -1};
  fx_state s = fx_sphere(1, 0.1, x, v);
  memcpy(s.omega, w, sizeof w);
  lsdem_impulse_body b, wall;
  fx_body_of(&s, &b);
  lsdem_error err;
  CHECK(lsdem_impulse_damp(&b, 50.0, 0.01, &err) == LSDEM_OK, "%s", err.msg);
  for (int i = 0; i < 3; i++) {
    CHECK_NEAR(b.v[i], 0.5 * v[i], 1e-15);
    CHECK_NEAR(b.omega[i], 0.5 * w[i], 1e-15);
  }
  CHECK(lsdem_impulse_damp(&b, 150.0, 0.01, &err) == LSDEM_ERR_ARG, "xi dt = 1.5 accepted");
  CHECK(strstr(err.msg, "4.46") != NULL, "message: %s", err.msg);
  CHECK(lsdem_impulse_damp(&b, -1.0, 0.01, &err) == LSDEM_ERR_ARG, "xi < 0 accepted");
  CHECK(lsdem_impulse_damp(&b, 100.0, 0.01, &err) == LSDEM_OK && b.v[0] == 0.0,
        "xi dt = 1 stops the body");
  fx_wall(&wall, -1, x, v);
  CHECK(lsdem_impulse_damp(&wall, 50.0, 0.01, &err) == LSDEM_OK && wall.v[1] == -2.0,
        "a wall's prescribed velocity is not damped");
}

/* The predicted pose is where the drift would take the body (x + v dt, q advanced), with
 * the current velocities. */
static void test_predict_pose(void)
{
  const double x[3] = {1, 2, 3}, v[3] = {0.1, -0.2, 0.3}, w[3] = {0.4, 0.5, -0.6};
  fx_state s =
      fx_grain(1, 1.0, 1.0, 2.0, 3.0, x, v, w); /* asymmetric: the midpoint matters */
  fx_random_quat(s.q);
  lsdem_pose pose;
  lsdem_impulse_predict_pose(s.x, s.q, s.v, s.omega, s.inertia, 0.05, &pose);
  lsdem_impulse_drift(s.x, s.q, s.omega, s.v, s.inertia, 0.05);
  double R[9];
  lsdem_quat_to_matrix(s.q, R);
  for (int i = 0; i < 3; i++) {
    CHECK(pose.x[i] == s.x[i], "x[%d]", i);
    CHECK(pose.v[i] == v[i] && pose.omega[i] == w[i], "velocities");
  }
  for (int i = 0; i < 9; i++) CHECK_NEAR(pose.R[i], R[i], 1e-15);
}

/* The sleep clock: counts dt while both the speed and the surface speed |omega| r stay
 * below the threshold, and restarts from 0 as soon as either reaches it (or is NaN). */
static void test_sleep_clock(void)
{
  const double slow_v[3] = {0.03, 0.0, -0.04}, slow_w[3] = {0.0, 0.2, 0.0}; /* 0.05, 0.04 */
  const double r = 0.2, speed = 0.05 + 1e-12, dt = 1e-3;
  double c = 0.0;
  for (int k = 0; k < 3; k++) c = lsdem_sleep_clock(c, slow_v, slow_w, r, speed, dt);
  CHECK_REL(c, 3e-3, 1e-15);
  const double fast_v[3] = {0.0, 0.0, 0.0501};
  CHECK(lsdem_sleep_clock(c, fast_v, slow_w, r, speed, dt) == 0.0, "fast translation slept");
  const double fast_w[3] = {0.0, 0.0, 0.251}; /* |omega| r = 0.0502 */
  CHECK(lsdem_sleep_clock(c, slow_v, fast_w, r, speed, dt) == 0.0, "fast spin slept");
  const double nan_v[3] = {NAN, 0.0, 0.0};
  CHECK(lsdem_sleep_clock(c, nan_v, slow_w, r, speed, dt) == 0.0, "NaN speed slept");
}

int main(void)
{
  test_gravity_closed_form();
  test_spin_about_axis();
  test_free_top();
  test_damping();
  test_predict_pose();
  test_sleep_clock();
  return lsdem_test_summary();
}
