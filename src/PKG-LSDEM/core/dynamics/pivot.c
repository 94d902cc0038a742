/* pivot.c -- a platen that pivots about the ram contact point (report §3.2.1): torque
 * about the pivot, the centred-difference step of its two tilt degrees of freedom and the
 * pose the contact kernel sees. World frame throughout; quaternions scalar-first,
 * body -> world (rotation.c). */
#include "lsdem_dynamics.h"

#include <math.h>

/* v minus its component along the unit vector a */
static void remove_along(double v[3], const double a[3])
{
  const double s = v[0] * a[0] + v[1] * a[1] + v[2] * a[2];
  for (int i = 0; i < 3; i++) v[i] -= s * a[i];
}

void lsdem_torque_about(const double t_o[3], const double o[3], const double f[3],
                        const double p[3], double t_p[3])
{
  const double arm[3] = {o[0] - p[0], o[1] - p[1], o[2] - p[2]};
  double m[3];
  lsdem_cross3(arm, f, m);
  for (int i = 0; i < 3; i++) t_p[i] = t_o[i] + m[i];
}

void lsdem_step_pivot(double q[4], double omega[3], const double torque_p[3],
                      const double axis[3], double inertia, double damping, double dt)
{
  double t[3] = {torque_p[0], torque_p[1], torque_p[2]};
  remove_along(t, axis);
  remove_along(omega, axis);
  /* omega^{n+1/2} = [(1 - c dt / 2I) omega^{n-1/2} + dt T / I] / (1 + c dt / 2I) */
  const lsdem_damped_step k = lsdem_damped_step_of(damping / inertia, dt);
  lsdem_step_spin(q, omega, t, inertia, &k);
}

void lsdem_pivot_pose(const double pivot[3], const double v_p[3], const double q[4],
                      const double omega[3], double h, lsdem_pose *pose)
{
  const double ez[3] = {0.0, 0.0, 1.0};
  double n[3], spin[3];
  lsdem_quat_rotate(q, ez, n);
  lsdem_quat_to_matrix(q, pose->R);
  for (int i = 0; i < 3; i++) {
    n[i] *= h; /* x - P */
    pose->x[i] = pivot[i] + n[i];
    pose->omega[i] = omega[i];
  }
  lsdem_cross3(omega, n, spin);
  for (int i = 0; i < 3; i++) pose->v[i] = v_p[i] + spin[i];
}

double lsdem_tilt_angle(const double n[3], const double a[3])
{
  double c[3];
  lsdem_cross3(n, a, c);
  return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
               n[0] * a[0] + n[1] * a[1] + n[2] * a[2]);
}
