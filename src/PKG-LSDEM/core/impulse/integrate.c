/* integrate.c -- time integration of impulse mode (report §4.3.4): symplectic Euler,
 * eqs 4.37-4.40, and global damping, eqs 4.44-4.46. World frame; the orientation q is
 * body (principal) -> world, scalar first. */
#include "lsdem_impulse.h"

#include <math.h>
#include <string.h>

void lsdem_impulse_kick(lsdem_impulse_body *b, const double force[3], const double torque[3],
                        double dt)
{
  if (lsdem_impulse_body_is_wall(b)) return;
  double dw[3];
  lsdem_mat_vec(b->inv_inertia, torque, dw);
  for (int i = 0; i < 3; i++) {
    b->v[i] += dt * b->inv_mass * force[i]; /* eq 4.37 */
    b->omega[i] += dt * dw[i];              /* eq 4.39 */
  }
}

lsdem_status lsdem_impulse_damp(lsdem_impulse_body *b, double xi, double dt, lsdem_error *err)
{
  const double h = xi * dt;
  if (!(h >= 0.0 && h <= 1.0))
    return lsdem_fail(err, LSDEM_ERR_ARG,
                      "global damping: xi dt = %g * %g = %g, eq 4.46 needs 0 <= xi dt <= 1", xi,
                      dt, h);
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

/* q advanced by the rotation of the world angular velocity omega over dt (eq 4.40);
 * omega_body = R(q)^T omega before the step, in *wb. */
static void advance_orientation(double q[4], const double omega[3], double dt, double wb[3])
{
  lsdem_quat_rotate_inv(q, omega, wb);
  lsdem_quat_advance(q, wb, dt);
}

void lsdem_impulse_drift(double x[3], double q[4], double omega[3], const double v[3],
                         const double inertia[3], double dt)
{
  double wb[3], L[3];
  for (int i = 0; i < 3; i++) x[i] += dt * v[i]; /* eq 4.38 */
  const double q0[4] = {q[0], q[1], q[2], q[3]};
  advance_orientation(q, omega, dt, wb);
  for (int i = 0; i < 3; i++) wb[i] *= inertia[i];
  lsdem_quat_rotate(q0, wb, L); /* L = R I0 R^T omega, before the step */
  omega_of_momentum(q, inertia, L, omega);
}

void lsdem_impulse_predict_pose(const double x[3], const double q[4], const double v[3],
                                const double omega[3], double dt, lsdem_pose *pose)
{
  double qp[4], wb[3];
  memcpy(qp, q, sizeof qp);
  advance_orientation(qp, omega, dt, wb);
  lsdem_quat_to_matrix(qp, pose->R);
  for (int i = 0; i < 3; i++) {
    pose->x[i] = x[i] + dt * v[i];
    pose->v[i] = v[i];
    pose->omega[i] = omega[i];
  }
}
