/* Pivoting platen (core/pivot.c): torque shift, the tilt step against closed-form rigid
 * rotation about a fixed axis, damping's terminal rate, and the plate pose. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <math.h>

static void test_torque_about(void)
{
  /* a downward unit force at (1,0,0) with no torque about there: about the origin the
   * torque is (1,0,0) x (0,0,-1) = (0,1,0); about the point of application it stays 0 */
  const double t0[3] = {0.0, 0.0, 0.0}, o[3] = {1.0, 0.0, 0.0}, f[3] = {0.0, 0.0, -1.0};
  const double p[3] = {0.0, 0.0, 0.0};
  double t[3];
  lsdem_torque_about(t0, o, f, p, t);
  CHECK_NEAR(t[0], 0.0, 1e-15);
  CHECK_NEAR(t[1], 1.0, 1e-15);
  CHECK_NEAR(t[2], 0.0, 1e-15);
  /* shifting there and back is the identity (random data) */
  double ta[3], o2[3], f2[3], back[3], mid[3];
  for (int i = 0; i < 3; i++) {
    ta[i] = srand1();
    o2[i] = srand1();
    f2[i] = srand1();
  }
  lsdem_torque_about(ta, o2, f2, p, mid);
  lsdem_torque_about(mid, p, f2, o2, back);
  for (int i = 0; i < 3; i++) CHECK_NEAR(back[i], ta[i], 1e-14);
}

/* constant torque T about x (ram axis z), from rest, no damping: omega_n = n dt T / I
 * exactly, and the plate turns about x by theta_n = dt^2 T/I n(n+1)/2; the normal
 * e_z goes to (0, -sin theta, cos theta) (right-hand rule about +x). An added torque
 * component along the ram axis changes nothing. */
static void test_constant_torque(void)
{
  const double axis[3] = {0.0, 0.0, 1.0}, T[3] = {0.3, 0.0, 5.0};
  const double I = 2.0, dt = 1e-3;
  const int nstep = 1000;
  double q[4] = {1.0, 0.0, 0.0, 0.0}, w[3] = {0.0, 0.0, 0.0};
  for (int n = 0; n < nstep; n++) lsdem_step_pivot(q, w, T, axis, I, 0.0, dt);
  CHECK_REL(w[0], nstep * dt * T[0] / I, 1e-12);
  CHECK_NEAR(w[1], 0.0, 1e-15);
  CHECK_NEAR(w[2], 0.0, 1e-15);
  const double theta = dt * dt * T[0] / I * 0.5 * nstep * (nstep + 1.0);
  const double ez[3] = {0.0, 0.0, 1.0};
  double nrm[3];
  lsdem_quat_rotate(q, ez, nrm);
  CHECK_NEAR(nrm[0], 0.0, 1e-14);
  CHECK_REL(nrm[1], -sin(theta), 1e-10);
  CHECK_REL(nrm[2], cos(theta), 1e-10);
  CHECK_REL(lsdem_tilt_angle(nrm, ez), theta, 1e-10);
  /* and the closed form of a constant angular acceleration, 0.5 T/I t^2, within O(dt) */
  CHECK_REL(theta, 0.5 * T[0] / I * (nstep * dt) * (nstep * dt), 2e-3);
}

/* with damping c the rate tends to T / c; an initial spin about the ram axis is removed */
static void test_damping(void)
{
  const double axis[3] = {0.0, 0.0, 1.0}, T[3] = {0.0, -0.4, 0.0};
  const double I = 1.0, c = 20.0, dt = 1e-3;
  double q[4] = {1.0, 0.0, 0.0, 0.0}, w[3] = {0.0, 0.0, 3.0};
  for (int n = 0; n < 5000; n++) lsdem_step_pivot(q, w, T, axis, I, c, dt);
  CHECK_REL(w[1], T[1] / c, 1e-9);
  CHECK_NEAR(w[2], 0.0, 1e-15);
}

/* plate tilted by 90 degrees about y: its normal is +x, so x = P + h (1,0,0); turning at
 * omega = (0,2,0) about the pivot its point moves at v_p + omega x (h,0,0) */
static void test_pose(void)
{
  const double P[3] = {1.0, 2.0, 3.0}, vp[3] = {0.0, 0.0, -0.5}, h = 0.25;
  const double q[4] = {cos(M_PI / 4), 0.0, sin(M_PI / 4), 0.0};
  const double w[3] = {0.0, 2.0, 0.0};
  lsdem_pose pose;
  lsdem_pivot_pose(P, vp, q, w, h, &pose);
  CHECK_NEAR(pose.x[0], 1.25, 1e-15);
  CHECK_NEAR(pose.x[1], 2.0, 1e-15);
  CHECK_NEAR(pose.x[2], 3.0, 1e-15);
  /* (0,2,0) x (0.25,0,0) = (0,0,-0.5) */
  CHECK_NEAR(pose.v[0], 0.0, 1e-15);
  CHECK_NEAR(pose.v[1], 0.0, 1e-15);
  CHECK_NEAR(pose.v[2], -1.0, 1e-15);
  CHECK_NEAR(pose.R[2], 1.0, 1e-15); /* body z -> world x */
  CHECK_NEAR(pose.omega[1], 2.0, 0.0);
}

int main(void)
{
  test_torque_about();
  test_constant_torque();
  test_damping();
  test_pose();
  return lsdem_test_summary();
}
