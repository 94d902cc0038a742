/* rigid.c -- rigid-body time integration (report §2.2.7, eqs 2.17-2.25).
 *
 * Time levels: positions and orientations live at whole steps n, velocities at half
 * steps n+1/2 (leapfrog). Translation is world-frame; rotation is integrated in the
 * body (principal) frame, where the inertia tensor is diagonal. */
#include "lsdem_dynamics.h"

/* dt * angular acceleration from Euler's equations with damping (eq 2.20), evaluated
 * at the body-frame angular velocity w: the bracket of eqs 2.22 and 2.24. */
static void euler_increment(const double w[3], const double torque[3],
                            const double I[3], double xi, double dt, double dw[3])
{
  dw[0] = dt * (torque[0] + w[1] * w[2] * (I[1] - I[2]) - xi * I[0] * w[0]) / I[0];
  dw[1] = dt * (torque[1] + w[2] * w[0] * (I[2] - I[0]) - xi * I[1] * w[1]) / I[1];
  dw[2] = dt * (torque[2] + w[0] * w[1] * (I[0] - I[1]) - xi * I[2] * w[2]) / I[2];
}

/* Predictor-corrector for Euler's equations (eqs 2.21-2.25). Eq 2.25 as printed adds
 * half the corrector; a leapfrog step from n-1/2 to n+1/2 must add all of it
 * (Delta omega^n = alpha^n dt), otherwise a constant torque would give half the
 * angular acceleration. We add the full increment. */
void lsdem_step_rotation(double omega[3], double dw_prev[3], const double torque[3],
                         const double inertia[3], double xi, double dt)
{
  double w_est[3], dw_pred[3], w_n[3], dw[3];
  for (int i = 0; i < 3; i++) w_est[i] = omega[i] + 0.5 * dw_prev[i]; /* eq 2.21 */
  euler_increment(w_est, torque, inertia, xi, dt, dw_pred);           /* eq 2.22 */
  for (int i = 0; i < 3; i++) w_n[i] = omega[i] + 0.5 * dw_pred[i];   /* eq 2.23 */
  euler_increment(w_n, torque, inertia, xi, dt, dw);                  /* eq 2.24 */
  for (int i = 0; i < 3; i++) {
    omega[i] += dw[i]; /* eq 2.25, full increment */
    dw_prev[i] = dw[i];
  }
}

void lsdem_step_body(double x[3], double v[3], double q[4], double omega_body[3],
                     double dw_prev[3], const double force[3], const double torque[3],
                     double mass, const double inertia[3], double xi, double dt,
                     double omega_world[3])
{
  double torque_body[3];
  const lsdem_damped_step k = lsdem_damped_step_of(xi, dt);
  lsdem_step_translation(x, v, force, mass, &k);
  lsdem_quat_rotate_inv(q, torque, torque_body); /* world -> body with q^n */
  lsdem_step_rotation(omega_body, dw_prev, torque_body, inertia, xi, dt);
  lsdem_quat_advance(q, omega_body, dt);        /* q^n -> q^{n+1} */
  lsdem_quat_rotate(q, omega_body, omega_world); /* body -> world with q^{n+1} */
}

double lsdem_kinetic_translational(double mass, const double v[3])
{
  return 0.5 * mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

double lsdem_kinetic_rotational(const double inertia[3], const double omega_body[3])
{
  return 0.5 * (inertia[0] * omega_body[0] * omega_body[0] +
                inertia[1] * omega_body[1] * omega_body[1] +
                inertia[2] * omega_body[2] * omega_body[2]);
}
