/* lsdem_dynamics.h -- rigid-body integration of grains and the pivoting platen (kernel). */
#ifndef LSDEM_DYNAMICS_H
#define LSDEM_DYNAMICS_H

#include "../contact/lsdem_contact.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- integrator ---- */

/* The integrator of a grain with one moment of inertia (translation, a sphere's spin) is
 * inline: fix nve/lsdem runs it for every sphere every step. */

/* A damped centred-difference step's factors (report eq 2.18), the same for every body with
 * the same damping xi: dt, keep = 1 - xi dt/2 and inv = 1 / (1 + xi dt/2), so that a
 * caller stepping many bodies finds them (and the division) once. */
typedef struct {
  double dt, keep, inv;
} lsdem_damped_step;

static inline lsdem_damped_step lsdem_damped_step_of(double xi, double dt)
{
  const double h = 0.5 * xi * dt;
  const lsdem_damped_step k = {dt, 1.0 - h, 1.0 / (1.0 + h)};
  return k;
}

/* The velocity half of lsdem_step_translation alone (report eq 2.18):
 * v <- [(1 - xi dt/2) v + dt f / m] / (1 + xi dt/2), the factors from k. */
static inline void lsdem_step_velocity(double v[3], const double f[3], double mass,
                                       const lsdem_damped_step *k)
{
  const double dt_m = k->dt / mass;
  for (int i = 0; i < 3; i++) v[i] = (k->keep * v[i] + dt_m * f[i]) * k->inv; /* eq 2.18 */
}

/* Centred-difference translation with global damping (report eqs 2.18-2.19, the factors
 * k = lsdem_damped_step_of(xi, dt)): the velocity of lsdem_step_velocity, then
 * x <- x + dt v. */
static inline void lsdem_step_translation(double x[3], double v[3], const double f[3],
                                          double mass, const lsdem_damped_step *k)
{
  lsdem_step_velocity(v, f, mass, k);
  for (int i = 0; i < 3; i++) x[i] += k->dt * v[i]; /* eq 2.19 */
}

/* The rotation of a body with one moment of inertia I about the axes it turns about (a
 * sphere; a pivoting platen): the centred difference of eq 2.18 in the world frame,
 * omega <- [(1 - xi dt/2) omega + dt torque / I] / (1 + xi dt/2) (Euler's equation, eq 2.20,
 * without its gyroscopic terms, which vanish for equal moments), then q (body -> world)
 * advanced from n to n+1 by omega^{n+1/2} over dt (eq 2.28). omega and torque world-frame;
 * k = lsdem_damped_step_of(xi, dt). */
static inline void lsdem_step_spin(double q[4], double omega[3], const double torque[3],
                                   double inertia, const lsdem_damped_step *k)
{
  lsdem_step_velocity(omega, torque, inertia, k); /* eq 2.18 as eq 2.20, I isotropic */
  lsdem_quat_turn(q, omega, k->dt);               /* q^n -> q^{n+1}, eq 2.28 */
}

/* One step of an analytic sphere (isotropic moment of inertia I, report §2.3.5): the
 * translation of lsdem_step_translation and the rotation of lsdem_step_spin (x, v, omega at
 * the levels of lsdem_step_body; omega and torque world-frame, as LAMMPS keeps them). */
static inline void lsdem_step_sphere(double x[3], double v[3], double q[4], double omega[3],
                                     const double force[3], const double torque[3],
                                     double mass, double inertia, const lsdem_damped_step *k)
{
  lsdem_step_translation(x, v, force, mass, k);
  lsdem_step_spin(q, omega, torque, inertia, k);
}

/* Predictor-corrector Euler equations in the principal frame (report eqs 2.21-2.25).
 * omega: body-frame angular velocity at n-1/2, updated to n+1/2.
 * dw_prev: the previous step's corrector increment (Delta omega^{n-1}), updated.
 * torque: body-frame torque at n. inertia: principal moments. */
void lsdem_step_rotation(double omega[3], double dw_prev[3], const double torque[3],
                         const double inertia[3], double xi, double dt);
/* Note on eq 2.25: the printed "1/2" is not applied; omega^{n+1/2} = omega^{n-1/2} +
 * Delta omega^n (the full corrector increment), so that a constant torque about a
 * principal axis gives omega = M t / I. Start a body with dw_prev = 0. */

/* One whole rigid-body step from world-frame force and torque at step n:
 *   x, v   world; x at n -> n+1, v at n-1/2 -> n+1/2 (eqs 2.18-2.19);
 *   q      body -> world orientation, n -> n+1 (lsdem_quat_advance with omega_body
 *          at n+1/2);
 *   omega_body, dw_prev   body-frame state for lsdem_step_rotation (n-1/2 -> n+1/2);
 *          the torque is taken to the body frame with q at n;
 *   omega_world (out)     R(q^{n+1}) omega_body^{n+1/2}, for the contact kernel.
 * A caller starting from a world angular velocity w sets omega_body = R(q)^T w and
 * dw_prev = 0. Per-grain state to keep (and migrate/restart): x, v, q, omega_body,
 * dw_prev. */
void lsdem_step_body(double x[3], double v[3], double q[4], double omega_body[3],
                     double dw_prev[3], const double force[3], const double torque[3],
                     double mass, const double inertia[3], double xi, double dt,
                     double omega_world[3]);

/* Kinetic energy of a rigid body: translational and rotational parts. */
double lsdem_kinetic_translational(double mass, const double v[3]);
double lsdem_kinetic_rotational(const double inertia[3], const double omega_body[3]);

/* Pivoting platen (report §3.2.1): a rigid plate that may rotate about a pivot point P
 * (the ram's ball joint) with the two rotational degrees of freedom perpendicular to the
 * unit ram axis a (no spin about a), scalar moment of inertia I about P, viscous
 * damping torque -c omega. All vectors world frame. */
/* Torque about point p of a force f whose torque about point o is t_o:
 * t_p = t_o + (o - p) x f. */
void lsdem_torque_about(const double t_o[3], const double o[3], const double f[3],
                        const double p[3], double t_p[3]);
/* One centred-difference step (eqs 2.18-2.19 with mass I and xi = c / I): the
 * torque about P at step n with its component along a removed drives omega (world,
 * n-1/2 -> n+1/2, kept perpendicular to a); q (plate body -> world) is advanced from n
 * to n+1 by omega over dt (eq 2.28). */
void lsdem_step_pivot(double q[4], double omega[3], const double torque_p[3],
                      const double axis[3], double inertia, double damping, double dt);
/* Pose of a plate whose frame is q, whose reference point sits at h along the plate's
 * body z axis from the pivot P (x = P + h R(q) e_z), with P moving at v_p and the plate
 * turning at omega about P: pose->v = v_p + omega x (x - P). */
void lsdem_pivot_pose(const double pivot[3], const double v_p[3], const double q[4],
                      const double omega[3], double h, lsdem_pose *pose);
/* Tilt of the plate: the angle (radians, [0, pi]) between unit vectors n and a, as
 * atan2(|n x a|, n . a) (accurate for small angles, unlike acos). */
double lsdem_tilt_angle(const double n[3], const double a[3]);

#ifdef __cplusplus
}
#endif
#endif /* LSDEM_DYNAMICS_H */
