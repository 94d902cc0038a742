/* boundary.c -- the wall record (lsdem_boundary.h): planes and cylindrical containers as
 * analytic signed distances in their own frame, meshes and terrain as narrow bands, their pose and motion, the pivoting
 * platen (report §3.2.1), and the three questions every caller asks of a wall. */
#include "lsdem_boundary.h"

#include <math.h>
#include <string.h>

/* At rest, unbounded (the kernel must not reject a wall by B's bounding sphere). */
static void clear(lsdem_boundary *b, lsdem_sdf_kind kind)
{
  memset(b, 0, sizeof(*b));
  b->shape.sdf.kind = kind;
  b->shape.radius = HUGE_VAL;
}

/* Wall frame of a plane: columns (t1, t2, n), t1 perpendicular to n from the world axis
 * least aligned with n, t2 = n x t1 (proper). */
static void plane_frame(const double n[3], double R[9])
{
  double a[3] = {0.0, 0.0, 0.0};
  const int k = fabs(n[0]) < fabs(n[1]) ? (fabs(n[0]) < fabs(n[2]) ? 0 : 2)
                                        : (fabs(n[1]) < fabs(n[2]) ? 1 : 2);
  a[k] = 1.0;
  double t1[3];
  lsdem_cross3(a, n, t1);
  const double len = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
  for (int d = 0; d < 3; d++) t1[d] /= len;
  double t2[3];
  lsdem_cross3(n, t1, t2);
  for (int r = 0; r < 3; r++) {
    R[3 * r + 0] = t1[r];
    R[3 * r + 1] = t2[r];
    R[3 * r + 2] = n[r];
  }
}

lsdem_status lsdem_boundary_plane(lsdem_boundary *b, const double point[3], const double n[3],
                                  lsdem_error *err)
{
  /* scaled by its largest component first, so that no square overflows or underflows */
  const double big = fmax(fabs(n[0]), fmax(fabs(n[1]), fabs(n[2])));
  const int finite = isfinite(n[0]) && isfinite(n[1]) && isfinite(n[2]);
  if (!finite || !(big > 0.0))
    return lsdem_fail(err, LSDEM_ERR_ARG, "plane normal must be finite and not zero");
  double u[3] = {n[0] / big, n[1] / big, n[2] / big};
  const double len = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (int d = 0; d < 3; d++) u[d] /= len;
  clear(b, LSDEM_SDF_PLANE);
  for (int d = 0; d < 3; d++) b->pose.x[d] = point[d];
  plane_frame(u, b->pose.R);
  return LSDEM_OK;
}

lsdem_status lsdem_boundary_cylinder(lsdem_boundary *b, int axis, const double c[2],
                                     double radius, lsdem_error *err)
{
  if (axis < 0 || axis > 2)
    return lsdem_fail(err, LSDEM_ERR_ARG, "cylinder axis %d is not 0, 1 or 2", axis);
  if (!(radius > 0.0)) return lsdem_fail(err, LSDEM_ERR_ARG, "cylinder radius must be > 0");
  clear(b, LSDEM_SDF_CYLINDER);
  b->shape.sdf.inverted = 1; /* solid outside: a container */
  b->shape.sdf.a[0] = radius;
  b->shape.sdf.a[1] = 0.0; /* infinite */
  const int other[2] = {axis == 0 ? 1 : 0, axis == 2 ? 1 : 2};
  b->pose.x[other[0]] = c[0];
  b->pose.x[other[1]] = c[1];
  /* body x, y, z -> world axis+1, axis+2, axis */
  for (int k = 0; k < 3; k++) b->pose.R[3 * ((axis + 1 + k) % 3) + k] = 1.0;
  return LSDEM_OK;
}

void lsdem_boundary_band(lsdem_boundary *b, const lsdem_band *band)
{
  clear(b, LSDEM_SDF_BAND);
  b->shape.sdf.band = band;
  b->pose.R[0] = b->pose.R[4] = b->pose.R[8] = 1.0;
}

lsdem_status lsdem_boundary_pivot(lsdem_boundary *b, double h, double inertia, double damping,
                                  lsdem_error *err)
{
  if (b->shape.sdf.kind != LSDEM_SDF_PLANE)
    return lsdem_fail(err, LSDEM_ERR_ARG, "keyword pivot is for plane walls only, not %s",
                      lsdem_sdf_kind_name(b->shape.sdf.kind));
  if (!(h >= 0.0))
    return lsdem_fail(err, LSDEM_ERR_ARG, "pivot h = %g must be >= 0 (distance of the pivot "
                      "behind the plane)", h);
  if (!(inertia > 0.0))
    return lsdem_fail(err, LSDEM_ERR_ARG, "pivot I = %g must be > 0 (moment of inertia about "
                      "the pivot, mass*distance^2)", inertia);
  if (!(damping >= 0.0))
    return lsdem_fail(err, LSDEM_ERR_ARG, "pivot c = %g must be >= 0 (damping torque per "
                      "angular velocity)", damping);
  lsdem_platen *p = &b->platen;
  memset(p, 0, sizeof(*p));
  p->h = h;
  p->inertia = inertia;
  p->damping = damping;
  for (int d = 0; d < 3; d++) {
    p->axis[d] = b->pose.R[3 * d + 2];
    p->x[d] = b->pose.x[d] - h * p->axis[d];
  }
  lsdem_matrix_to_quat(b->pose.R, p->q);
  b->pivots = 1;
  return LSDEM_OK;
}

lsdem_status lsdem_boundary_spin(lsdem_boundary *b, const double centre[3],
                                 const double omega[3], lsdem_error *err)
{
  if (b->pivots)
    return lsdem_fail(err, LSDEM_ERR_ARG, "a pivoting platen cannot also spin");
  lsdem_spin *sp = &b->spin;
  memset(sp, 0, sizeof *sp);
  sp->on = 1;
  for (int d = 0; d < 3; d++) {
    sp->centre[d] = centre[d];
    sp->x0[d] = b->pose.x[d];
  }
  memcpy(sp->R0, b->pose.R, sizeof sp->R0);
  const lsdem_status st = lsdem_boundary_spin_omega(b, omega, err);
  if (st != LSDEM_OK) sp->on = 0;
  else lsdem_boundary_place_spun(b);
  return st;
}

lsdem_status lsdem_boundary_spin_omega(lsdem_boundary *b, const double omega[3],
                                       lsdem_error *err)
{
  lsdem_spin *sp = &b->spin;
  const double w = sqrt(lsdem_dot3(omega, omega));
  if (!isfinite(w))
    return lsdem_fail(err, LSDEM_ERR_ARG, "spin angular velocity (%g, %g, %g) is not finite",
                      omega[0], omega[1], omega[2]);
  const int has_axis = lsdem_dot3(sp->axis, sp->axis) > 0.0;
  if (w > 0.0 && !has_axis)
    for (int d = 0; d < 3; d++) sp->axis[d] = omega[d] / w;
  double off[3];
  lsdem_cross3(omega, sp->axis, off);
  if (w > 0.0 && sqrt(lsdem_dot3(off, off)) > 1e-9 * w)
    return lsdem_fail(err, LSDEM_ERR_ARG, "spin angular velocity (%g, %g, %g) is not along the "
                      "axis (%g, %g, %g) it first turned about: vary its rate (and sign), not "
                      "its direction", omega[0], omega[1], omega[2], sp->axis[0], sp->axis[1],
                      sp->axis[2]);
  for (int d = 0; d < 3; d++) sp->omega[d] = b->pose.omega[d] = omega[d];
  return LSDEM_OK;
}

/* The rotation by angle about unit axis (the identity before the axis is known). */
static void spin_matrix(const double axis[3], double angle, double M[9])
{
  const double s = sin(0.5 * angle);
  const double q[4] = {cos(0.5 * angle), axis[0] * s, axis[1] * s, axis[2] * s};
  lsdem_quat_to_matrix(q, M);
}

void lsdem_boundary_place_spun(lsdem_boundary *b)
{
  const lsdem_spin *sp = &b->spin;
  double M[9], rel[3], turned[3];
  spin_matrix(sp->axis, sp->angle, M);
  lsdem_mat_mul(M, sp->R0, b->pose.R);
  lsdem_sub3(sp->x0, sp->centre, rel);
  lsdem_mat_vec(M, rel, turned);
  for (int d = 0; d < 3; d++) {
    b->pose.x[d] = sp->centre[d] + turned[d];
    b->pose.omega[d] = sp->omega[d];
  }
}

int lsdem_boundary_turns(const lsdem_boundary *b) { return b->pivots || b->spin.on; }

/* pose.v stays the ram's velocity, the one P moves with */
void lsdem_boundary_place_platen(lsdem_boundary *b)
{
  lsdem_pose now;
  lsdem_pivot_pose(b->platen.x, b->pose.v, b->platen.q, b->platen.omega, b->platen.h, &now);
  for (int d = 0; d < 3; d++) {
    b->pose.x[d] = now.x[d];
    b->pose.omega[d] = now.omega[d];
  }
  memcpy(b->pose.R, now.R, sizeof now.R);
}

double lsdem_boundary_distance(const lsdem_boundary *b, const lsdem_pose *w, const double p[3],
                               double normal[3])
{
  double rel[3], local[3], grad[3];
  lsdem_sub3(p, w->x, rel);
  lsdem_matT_vec(w->R, rel, local); /* world -> wall frame */
  const double phi = lsdem_sdf_eval(&b->shape.sdf, local, grad);
  if (normal) lsdem_mat_vec(w->R, grad, normal);
  return phi;
}

/* phi is a distance: no point of the sphere is nearer the solid than phi(c) - r */
int lsdem_boundary_may_touch(const lsdem_boundary *b, const lsdem_pose *w, const double c[3],
                             double r)
{
  return lsdem_boundary_reaches(b, lsdem_boundary_distance(b, w, c, NULL), r);
}

int lsdem_boundary_reaches(const lsdem_boundary *b, double phi, double r)
{
  return phi < lsdem_sdf_lipschitz(&b->shape.sdf) * r;
}

int lsdem_boundary_crossing(const lsdem_boundary *b, const lsdem_pose *w, const double c[3],
                            const double v[3], double dt, double *d, double *vn)
{
  double n[3], rel[3], spin[3], vr[3];
  const double phi = lsdem_boundary_distance(b, w, c, n);
  lsdem_sub3(c, w->x, rel);
  lsdem_cross3(w->omega, rel, spin); /* the wall's velocity at c: w.v + omega x rel */
  for (int k = 0; k < 3; k++) vr[k] = v[k] - w->v[k] - spin[k];
  const double un = lsdem_dot3(vr, n);
  if (d) *d = phi;
  if (vn) *vn = un;
  const int beyond_band = b->shape.sdf.kind == LSDEM_SDF_BAND && phi >= b->shape.sdf.band->width;
  return !(phi >= 0.0 && (beyond_band || phi + un * dt >= 0.0));
}

/* phi is L-Lipschitz: over the step it falls by at most L times the distance the centre
 * moves relative to the wall, |v - w.v - w.omega x (c - w.x)| dt, itself at most
 * (|v| + |w.v| + |w.omega| |c - w.x|) dt, whose square is at most 3 times the sum of the
 * three squares (no square root) */
int lsdem_boundary_clear_of_crossing(const lsdem_boundary *b, const lsdem_pose *w,
                                     const double c[3], double phi, const double v[3],
                                     double dt)
{
  const double L = lsdem_sdf_lipschitz(&b->shape.sdf);
  if (!(L > 0.0) || !(phi > 0.0)) return 0;
  double rel[3];
  lsdem_sub3(c, w->x, rel);
  const double speed2 = 3.0 * (lsdem_dot3(v, v) + lsdem_dot3(w->v, w->v) +
                               lsdem_dot3(w->omega, w->omega) * lsdem_dot3(rel, rel));
  return phi * phi > L * L * dt * dt * speed2;
}

int lsdem_boundary_tunnelled(const lsdem_boundary *b, double depth)
{
  return b->shape.sdf.kind == LSDEM_SDF_BAND && lsdem_band_tunnelled(b->shape.sdf.band, depth);
}

void lsdem_boundary_pose_at(const lsdem_boundary *b, double s, lsdem_pose *pose)
{
  if (b->pivots) {
    double P[3];
    for (int d = 0; d < 3; d++)
      P[d] = s != 0.0 ? b->platen.x[d] + s * b->pose.v[d] : b->platen.x[d];
    lsdem_pivot_pose(P, b->pose.v, b->platen.q, b->platen.omega, b->platen.h, pose);
    return;
  }
  if (b->spin.on) {
    lsdem_boundary moved = *b;
    if (s != 0.0) lsdem_boundary_advance(&moved, s);
    *pose = moved.pose;
    double rel[3], spin_v[3];
    lsdem_sub3(pose->x, moved.spin.centre, rel);
    lsdem_cross3(moved.spin.omega, rel, spin_v);
    for (int d = 0; d < 3; d++) pose->v[d] += spin_v[d];
    return;
  }
  *pose = b->pose;
  if (s != 0.0)
    for (int d = 0; d < 3; d++) pose->x[d] += s * b->pose.v[d];
}

void lsdem_boundary_advance(lsdem_boundary *b, double dt)
{
  if (b->spin.on) {
    lsdem_spin *sp = &b->spin;
    sp->angle += lsdem_dot3(sp->omega, sp->axis) * dt;
    for (int d = 0; d < 3; d++) {
      sp->centre[d] += dt * b->pose.v[d];
      sp->x0[d] += dt * b->pose.v[d];
    }
    lsdem_boundary_place_spun(b);
    return;
  }
  if (!b->pivots) {
    for (int d = 0; d < 3; d++) b->pose.x[d] += dt * b->pose.v[d];
    return;
  }
  lsdem_platen *p = &b->platen;
  lsdem_step_pivot(p->q, p->omega, p->torque, p->axis, p->inertia, p->damping, dt);
  for (int d = 0; d < 3; d++) p->x[d] += dt * b->pose.v[d];
  lsdem_boundary_place_platen(b);
}

void lsdem_boundary_platen_load(lsdem_boundary *b, const double f[3], const double t[3])
{
  lsdem_torque_about(t, b->pose.x, f, b->platen.x, b->platen.torque);
}
