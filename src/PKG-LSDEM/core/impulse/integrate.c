/* integrate.c -- time integration of impulse mode (report §4.3.4): symplectic Euler,
 * eqs 4.37-4.40, and global damping, eqs 4.44-4.46. World frame; the orientation q is
 * body (principal) -> world, scalar first. */
#include "lsdem_impulse.h"

#include <math.h>

void lsdem_impulse_kick(lsdem_impulse_body *b, const double force[3],
                        const double torque[3], double dt)
{
  if (lsdem_impulse_body_is_wall(b)) return;
  double dw[3];
  lsdem_mat_vec(b->inv_inertia, torque, dw);
  for (int i = 0; i < 3; i++) {
    b->v[i] += dt * b->inv_mass * force[i]; /* eq 4.37 */
    b->omega[i] += dt * dw[i];              /* eq 4.39 */
  }
}

lsdem_status lsdem_impulse_damp(lsdem_impulse_body *b, double xi, double dt,
                                lsdem_error *err)
{
  const double h = xi * dt;
  if (!(h >= 0.0 && h <= 1.0))
    return lsdem_fail(err, LSDEM_ERR_ARG,
                      "global damping: xi dt = %g * %g = %g, eq 4.46 needs 0 <= xi dt <= 1",
                      xi, dt, h);
  if (lsdem_impulse_body_is_wall(b)) return LSDEM_OK;
  for (int i = 0; i < 3; i++) {
    b->v[i] *= 1.0 - h;     /* eq 4.44 */
    b->omega[i] *= 1.0 - h; /* eq 4.45 */
  }
  return LSDEM_OK;
}

/* omega of angular momentum L at orientation q: R I0^-1 R^T L */
static void omega_of_momentum(const double q[4], const double inertia[3], const double L[3],
                              double omega[3])
{
  double w[3];
  lsdem_quat_rotate_inv(q, L, w);
  for (int i = 0; i < 3; i++) w[i] /= inertia[i];
  lsdem_quat_rotate(q, w, omega);
}

/* q advanced by the rotation of the world angular velocity omega over dt (eq 4.40). */
static void advance_world(double q[4], const double omega[3], double dt)
{
  double wb[3];
  lsdem_quat_rotate_inv(q, omega, wb);
  lsdem_quat_advance(q, wb, dt);
}

/* The torque-free rotation over dt of a body of principal moments `inertia` whose
 * angular velocity is omega now: L = R I0 R^T omega is kept, and q turns by the angular
 * velocity of L at mid-step (explicit midpoint; a constant omega for the whole step
 * drifts the energy secularly, 20 % in 2e5 steps of a tumbling top, the midpoint keeps it
 * within 1e-7). omega becomes that of L at the new orientation. Returns the kinetic energy
 * change, 1/2 L . (omega' - omega) (L kept: 1/2 omega . I omega = 1/2 L . omega at either
 * orientation): the midpoint's truncation error, 0 to round-off for an isotropic body or
 * a spin about a principal axis. */
static double rotate_free(double q[4], double omega[3], const double inertia[3], double dt)
{
  const double w0[3] = {omega[0], omega[1], omega[2]};
  double wb[3], L[3], qh[4] = {q[0], q[1], q[2], q[3]}, wh[3];
  lsdem_quat_rotate_inv(q, omega, wb);
  for (int i = 0; i < 3; i++) wb[i] *= inertia[i];
  lsdem_quat_rotate(q, wb, L);
  advance_world(qh, omega, 0.5 * dt);
  omega_of_momentum(qh, inertia, L, wh);
  advance_world(q, wh, dt);
  omega_of_momentum(q, inertia, L, omega);
  const double dw[3] = {omega[0] - w0[0], omega[1] - w0[1], omega[2] - w0[2]};
  return 0.5 * lsdem_dot3(L, dw);
}

double lsdem_impulse_drift(double x[3], double q[4], double omega[3], const double v[3],
                           const double inertia[3], double dt)
{
  for (int i = 0; i < 3; i++) x[i] += dt * v[i]; /* eq 4.38 */
  return rotate_free(q, omega, inertia, dt);     /* eq 4.40 */
}

void lsdem_impulse_predict_pose(const double x[3], const double q[4], const double v[3],
                                const double omega[3], const double inertia[3], double dt,
                                lsdem_pose *pose)
{
  double qp[4] = {q[0], q[1], q[2], q[3]}, wp[3] = {omega[0], omega[1], omega[2]};
  rotate_free(qp, wp, inertia, dt);
  lsdem_quat_to_matrix(qp, pose->R);
  for (int i = 0; i < 3; i++) {
    pose->x[i] = x[i] + dt * v[i];
    pose->v[i] = v[i];
    pose->omega[i] = omega[i];
  }
}
