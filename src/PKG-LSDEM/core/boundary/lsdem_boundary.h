/* lsdem_boundary.h -- rigid boundaries (kernel module core/boundary): one wall record for
 * every caller (fix wall/lsdem and its threaded variant, fix impulse/lsdem's wall
 * detection and correction), with the three questions they ask of a wall answered here
 * and nowhere else:
 *   lsdem_boundary_may_touch  may a grain's bounding sphere reach the wall (cheap rejection)
 *   lsdem_boundary_crossing   has a grain's centre gone, or will it go by the next step,
 *                             through the wall's surface
 *   lsdem_boundary_pose_at    where the wall is at a time s after the record's own
 * and its motion (lsdem_boundary_advance: prescribed translation, or the pivoting platen of
 * report §3.2.1). Contact itself is not here: a wall is the slave level set B of the same
 * detection and laws as a grain pair (report §4.6.3: "treated exactly as grain-grain
 * contact"), through its shape (b->shape) and a pose from lsdem_boundary_pose_at.
 *
 * Frames, units, signs:
 *   - The wall's signed distance lives in its own frame (the wall frame); pose.R maps it
 *     to the world (row-major; its columns are the wall frame's axes in the world) and
 *     pose.x is the wall frame's origin in the world. Plane: a point of the plane, body z
 *     the plane's normal. Cylinder: a point of its axis, body z the axis.
 *   - phi < 0 on the wall's solid side, > 0 on the grains' side; the normal is grad phi
 *     (unit), pointing out of the wall into the grains' side. Plane: solid is z <= 0 of
 *     its frame, the normal is the user's normal. Cylinder (a container): solid outside
 *     radius R, phi = R - rho, the normal points towards the axis.
 *   - Lengths in the unit of positions, velocities per unit of time, angles in radians,
 *     everything world-frame unless named otherwise (LAMMPS's units when called from it).
 *
 * Kinds: the shape's SDF kind (LSDEM_SDF_PLANE, LSDEM_SDF_CYLINDER, LSDEM_SDF_BAND for
 * meshes and terrain; lsdem_sdf_eval). The three questions hold for any kind with a
 * gradient bound (lsdem_sdf_lipschitz), which is what the bounding-sphere test relies on.
 *
 * Motion: pose.v is the wall's translation velocity (the caller may change it between
 * steps, e.g. from a LAMMPS variable); a pivoting platen turns about P at platen.omega
 * (pose.omega its current value); a spinning wall (lsdem_boundary_spin: a drum, a mixer)
 * turns at a prescribed angular velocity about an axis through a centre that moves with
 * pose.v. */
#ifndef LSDEM_BOUNDARY_H
#define LSDEM_BOUNDARY_H

#include "../dynamics/lsdem_dynamics.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The pivoting platen's state (report §3.2.1; core/dynamics/pivot.c): the plate tilts
 * about the ram's contact point P, h behind its face, with two rotational degrees of
 * freedom perpendicular to the ram axis. World frame. */
typedef struct {
  double h;         /* distance from P to the plane along its normal (>= 0) */
  double inertia;   /* moment of inertia about P (mass length^2, > 0) */
  double damping;   /* viscous torque per angular velocity (>= 0) */
  double axis[3];   /* ram axis: the plane's initial unit normal; no spin about it */
  double x[3];      /* P; moves with pose.v */
  double q[4];      /* plate frame (the wall frame) body -> world, scalar first */
  double omega[3];  /* angular velocity, perpendicular to axis, at step n-1/2 */
  double torque[3]; /* load about P of the last force call (lsdem_boundary_platen_load) */
} lsdem_platen;

/* A prescribed rotation (lsdem_boundary_spin): the wall turns at omega (world, radians
 * per time) about the axis through `centre`; its pose is the one it had at angle 0 (R0,
 * x0) turned by `angle` (the integral of omega . axis over time) about that axis, so no
 * rounding accumulates in R. The axis is fixed by the first non-zero omega; omega may
 * then change its rate and sign, not its direction (lsdem_boundary_spin_omega). centre
 * and x0 move with pose.v. */
typedef struct {
  int on;
  double centre[3], omega[3];
  double axis[3];      /* unit axis (0 0 0 until omega is first non-zero) */
  double angle;        /* radians turned so far, right-handed about axis */
  double R0[9], x0[3]; /* the pose at angle 0 */
} lsdem_spin;

typedef struct {
  lsdem_shape shape;   /* the signed distance (shape.sdf) in the wall frame; no nodes,
                          radius HUGE_VAL: never rejected by a bounding sphere of B */
  lsdem_pose pose;     /* the wall now: x, R (wall -> world), v (translation velocity; a
                          platen's: that of P, the ram's), omega (a platen's tilt rate) */
  int pivots;          /* 1: a plane that is a pivoting platen (platen below) */
  lsdem_platen platen;
  lsdem_spin spin;     /* spin.on: a prescribed rotation */
} lsdem_boundary;

/* A plane through `point` with normal n (any length, scaled internally; the grains' side
 * is where n points), at rest. LSDEM_ERR_ARG when n is zero or not finite. */
lsdem_status lsdem_boundary_plane(lsdem_boundary *b, const double point[3], const double n[3],
                                  lsdem_error *err);
/* An infinite cylindrical container (solid outside radius) about the world axis `axis`
 * (0, 1, 2 = x, y, z) through the point whose other two coordinates, in x, y, z order,
 * are c[0], c[1]; its frame is a cyclic permutation of x, y, z (proper), body z = axis.
 * At rest. LSDEM_ERR_ARG for a bad axis or a radius that is not > 0. */
lsdem_status lsdem_boundary_cylinder(lsdem_boundary *b, int axis, const double c[2],
                                     double radius, lsdem_error *err);
/* A wall of any shape: narrow band `band` (a mesh or a terrain, lsdem_band_open; not
 * owned, must outlive b), its frame the world's at rest (pose x = 0, R = I). */
void lsdem_boundary_band(lsdem_boundary *b, const lsdem_band *band);
/* Make a plane a pivoting platen (h, inertia, damping as in lsdem_platen), level and at
 * rest: P = x - h n, the ram axis n. LSDEM_ERR_ARG for another kind of wall or a parameter
 * out of range (the message names it). Also re-levels a platen at its current point. */
lsdem_status lsdem_boundary_pivot(lsdem_boundary *b, double h, double inertia, double damping,
                                  lsdem_error *err);
/* Make a wall spin at omega (world, radians per time; zero: at rest until it is set)
 * about the axis through centre, from its pose now (angle 0). LSDEM_ERR_ARG for a platen
 * or a non-finite omega. */
lsdem_status lsdem_boundary_spin(lsdem_boundary *b, const double centre[3],
                                 const double omega[3], lsdem_error *err);
/* A spinning wall's angular velocity from now on (e.g. a LAMMPS variable's value each
 * step): zero, or along the spin's axis with any rate and sign (the first non-zero omega
 * fixes the axis). LSDEM_ERR_ARG, omega unchanged, for another direction or a non-finite
 * value. */
lsdem_status lsdem_boundary_spin_omega(lsdem_boundary *b, const double omega[3],
                                       lsdem_error *err);
/* A spinning wall's pose (x, R, omega) from its spin record (after restoring it). */
void lsdem_boundary_place_spun(lsdem_boundary *b);
/* Whether points of the wall move differently from its point pose.x (it tilts or spins):
 * a grain list found near the wall cannot be kept by the wall point's motion alone. */
int lsdem_boundary_turns(const lsdem_boundary *b);
/* A platen's pose (x, R, omega) from its P, q and omega (after restoring them). */
void lsdem_boundary_place_platen(lsdem_boundary *b);

/* Signed distance of world point p to the wall at pose w (b's kind, w its place) and,
 * when normal is not NULL, the unit normal there (world; out of the wall). */
double lsdem_boundary_distance(const lsdem_boundary *b, const lsdem_pose *w, const double p[3],
                               double normal[3]);
/* Cheap rejection (DESIGN §3): 0 when the sphere of radius r about c cannot reach the
 * wall's solid at pose w, phi(c) >= L r (L = lsdem_sdf_lipschitz: 1 for planes and
 * cylinders); 1 when it may. */
int lsdem_boundary_may_touch(const lsdem_boundary *b, const lsdem_pose *w, const double c[3],
                             double r);
/* The same from the centre's phi(c) (lsdem_boundary_distance) already at hand. */
int lsdem_boundary_reaches(const lsdem_boundary *b, double phi, double r);
/* Has a grain crossed the wall at pose w: its centre c is behind the surface (d < 0), or
 * will be after dt when it moves at velocity v against the wall's motion at c,
 * d + vn dt < 0 with vn = n . (v - w.v - w.omega x (c - w.x)) (the relative velocity of
 * eq 2.6; vn < 0 towards the wall). A band's d beyond its width is a lower bound, not a
 * distance: only d < 0 counts there. Returns 1 if so (NaN counts as crossed); d and vn
 * out when not NULL. */
int lsdem_boundary_crossing(const lsdem_boundary *b, const lsdem_pose *w, const double c[3],
                            const double v[3], double dt, double *d, double *vn);
/* Cheap rejection for lsdem_boundary_crossing: 1 when the centre c, at phi = phi(c)
 * (lsdem_boundary_distance) and moving at v, cannot cross the wall at pose w by dt, as
 * phi > L dt (|v| + |w.v| + |w.omega| |c - w.x|) keeps phi > 0 over the step (L as in
 * lsdem_boundary_may_touch); 0 when it may, or when phi is NaN. */
int lsdem_boundary_clear_of_crossing(const lsdem_boundary *b, const lsdem_pose *w,
                                     const double c[3], double phi, const double v[3],
                                     double dt);
/* Whether a contact whose deepest node is `depth` inside the wall went through it: for a
 * band, the node read the solid-side background (lsdem_band_tunnelled); other kinds
 * never. */
int lsdem_boundary_tunnelled(const lsdem_boundary *b, double depth);
/* The wall's pose at time s after the record's (s < 0: before): the record's pose moved
 * by s v (for a platen P moved so, the tilt held; pose->v of a platen is then the velocity
 * of its point, v + omega x (x - P); a spinning wall turned on by s omega, pose->v the
 * velocity of its point, v + omega x (x - centre)). s = 0 gives the pose as stored, bit
 * for bit (a platen's from P, q, omega), except for a spinning wall's v. */
void lsdem_boundary_pose_at(const lsdem_boundary *b, double s, lsdem_pose *pose);
/* Move the wall over dt: x += dt v; a platen tilts under platen.torque
 * (lsdem_step_pivot: eqs 2.18, 2.28), P += dt v, and its pose follows; a spinning wall
 * turns by |omega| dt about its axis, whose centre moves by dt v. */
void lsdem_boundary_advance(lsdem_boundary *b, double dt);
/* A platen's load for its next step: the force f of the grains on the wall and their
 * torque t about the wall's point pose.x, moved to P (platen.torque). */
void lsdem_boundary_platen_load(lsdem_boundary *b, const double f[3], const double t[3]);

/* ------------------------------------------------------ per-triangle maps ---- */

/* What a mesh or terrain wall felt, triangle by triangle (wall_map.c): each grain's wall
 * contact is booked on the triangle nearest its contact point (lsdem_band_closest_
 * triangle; grain-scale resolution: one contact, one triangle). Sums are kept as integer
 * counts of quanta (int64), so they are exact and the same in any order, on any number
 * of ranks and across a restart:
 *   fn, ft     normal and tangential force magnitude of the wall on the grains, summed
 *              over the contacts and steps of the current interval (force quanta)
 *   contacts   contact-steps of the interval
 *   impacts    contacts that began (the grain kept no state with the wall the step
 *              before), since the start
 *   work       sum of fn |v_t| dt, the friction work measure of Archard's wear law
 *              (wear volume = K / H x work), since the start (force x length quanta)
 *   steps      steps in the interval */
enum { LSDEM_MAP_FN = 0, LSDEM_MAP_FT, LSDEM_MAP_CONTACTS, LSDEM_MAP_IMPACTS, LSDEM_MAP_WORK,
       LSDEM_MAP_FIELDS };
typedef struct {
  int64_t ntris;
  lsdem_quantum force_q, work_q;
  int64_t *sum;   /* LSDEM_MAP_FIELDS x ntris, field-major */
  int64_t steps;
} lsdem_wall_map;

/* Forces in quanta force_q (the wall's own, so the maps add up to its total force); work
 * in quanta for force_q's scale times length_scale (the largest sliding distance per
 * step). Allocates the sums (zero). */
lsdem_status lsdem_wall_map_init(lsdem_wall_map *m, int64_t ntris, lsdem_quantum force_q,
                                 double length_scale, lsdem_error *err);
void lsdem_wall_map_free(lsdem_wall_map *m);
/* Book one contact on triangle tri: force of the wall on the grain (world), the wall's
 * unit normal there (out of the wall), the grain's sliding distance |v_t| dt this step,
 * whether the contact began this step. */
void lsdem_wall_map_add(lsdem_wall_map *m, int64_t tri, const double force[3],
                        const double normal[3], double slide, int began);
/* A field's value on triangle t in its unit (force, count, force x length). */
double lsdem_wall_map_value(const lsdem_wall_map *m, int field, int64_t t);
/* Start a new interval: fn, ft, contacts and steps to zero (impacts, work kept). */
void lsdem_wall_map_new_interval(lsdem_wall_map *m);

#ifdef __cplusplus
}
#endif
#endif /* LSDEM_BOUNDARY_H */
