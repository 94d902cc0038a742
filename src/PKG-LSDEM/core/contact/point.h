/* point.h -- one contact point, private to core/contact: the pair's relative motion and a
 * point's geometry (detect.c), and the penalty law at one point (eqs 2.2-2.16, penalty.c).
 * Inline, so that the batched loops of detection and of the law and the two-sphere kernel
 * (pair.c) run the same arithmetic, bit for bit: each formula is written once, here. */
#ifndef LSDEM_CONTACT_POINT_H
#define LSDEM_CONTACT_POINT_H

#include "lsdem_contact.h"

#include <math.h>

/* --------------------------------------------------------------- geometry ---- */

/* The pair's motion as a point's relative velocity needs it (world frame), with
 * ra = p - xA the arm of a contact point p from A's centroid: the velocity of A's material
 * point at p relative to B's is v0 + dw x ra (report eq 2.6: vA + wA x ra - vB - wB x
 * (ra + dab) with dab = xA - xB, so v0 = vA - vB - wB x dab and dw = wA - wB). */
typedef struct {
  double xa[3], dab[3], v0[3], dw[3];
} pair_motion;

static inline void pair_motion_of(const lsdem_pose *pa, const lsdem_pose *pb, pair_motion *m)
{
  double wb_dab[3];
  for (int i = 0; i < 3; i++) {
    m->xa[i] = pa->x[i];
    m->dab[i] = pa->x[i] - pb->x[i];
    m->dw[i] = pa->omega[i] - pb->omega[i];
  }
  lsdem_cross3(pb->omega, m->dab, wb_dab);
  for (int i = 0; i < 3; i++) m->v0[i] = pa->v[i] - pb->v[i] - wb_dab[i];
}

/* The relative velocity vrel of A's material point at arm r = p - xA (eq 2.6, see
 * pair_motion). */
static inline void point_velocity(const pair_motion *restrict pm, const double r[3],
                                  double vrel[3])
{
  lsdem_cross3(pm->dw, r, vrel);
  for (int i = 0; i < 3; i++) vrel[i] += pm->v0[i];
}

/* The contact point c at p (world) with B's outward normal n, depth d > 0 and area. */
static inline __attribute__((always_inline)) void point_set(lsdem_contact_point *restrict c,
                                                            const pair_motion *restrict pm,
                                                            int node, const double p[3],
                                                            const double n[3], double d,
                                                            double area)
{
  double r[3];
  c->node = node;
  for (int i = 0; i < 3; i++) {
    c->point[i] = p[i];
    c->normal[i] = n[i];
    r[i] = p[i] - pm->xa[i];
  }
  c->depth = d;
  c->area = area;
  point_velocity(pm, r, c->vrel);
}

/* Two analytic spheres in closed form (report §2.3.5): overlap d = ra + rb - |xA - xB| and
 * normal n = (xA - xB)/|xA - xB| (from B towards A; coincident centres: x). Returns 0 when
 * they do not overlap (d <= 0). */
static inline int sphere_pair_overlap(double ra, const double xa[3], double rb,
                                      const double xb[3], double n[3], double *d)
{
  double dx[3];
  for (int i = 0; i < 3; i++) dx[i] = xa[i] - xb[i];
  const double reach = ra + rb, dist2 = lsdem_dot3(dx, dx);
  if (!(dist2 < reach * reach)) return 0;
  const double dist = sqrt(dist2);
  n[0] = 1.0;
  n[1] = n[2] = 0.0; /* coincident centres: any direction will do */
  if (dist > 0.0)
    for (int i = 0; i < 3; i++) n[i] = dx[i] / dist;
  *d = reach - dist;
  return 1;
}

/* A sphere's contact point (sphere of centre xa and radius r, B's outward normal n, depth
 * d): the middle of the overlap along the normal, p = xa - (r - d/2) n, so that a normal
 * force there exerts no torque on the sphere. */
static inline void sphere_contact_point(double r, const double xa[3], const double n[3],
                                        double d, double p[3])
{
  for (int i = 0; i < 3; i++) p[i] = xa[i] - (r - 0.5 * d) * n[i];
}

/* The overlap of an analytic sphere (centre pa->x, radius) with B: B's outward normal n and
 * the depth d there (report §2.3.5: two spheres in closed form, inline, any other B with one
 * lookup of the centre in B's level set, lsdem_sphere_overlap_shape in detect.c). Returns 1
 * when they overlap; *lookups counts the level-set lookups made (0: beyond B's bounding
 * sphere; two spheres: 1 when they overlap, else 0). */
int lsdem_sphere_overlap_shape(double radius, const lsdem_pose *pa, const lsdem_shape *B,
                               const lsdem_pose *pb, double n[3], double *d, int *lookups);
static inline int lsdem_sphere_overlap(double radius, const lsdem_pose *pa,
                                       const lsdem_shape *B, const lsdem_pose *pb, double n[3],
                                       double *d, int *lookups)
{
  if (B->sdf.kind == LSDEM_SDF_SPHERE)
    return *lookups = sphere_pair_overlap(radius, pa->x, B->sdf.a[0], pb->x, n, d);
  return lsdem_sphere_overlap_shape(radius, pa, B, pb, n, d, lookups);
}

/* -------------------------------------------------------------------- law ---- */

/* Weight of a point's springs: the node stride, times the node area under the traction law
 * (eq 2.2 per node, or a stress times the node's area). */
static inline double law_weight(const lsdem_penalty_law *law, double stride, double area)
{
  return law->normal == LSDEM_NORMAL_TRACTION ? stride * area : stride;
}

/* Normal force at a point of normal n, depth d and area with relative velocity vrel (eq
 * 2.2, with damping, never attractive), returned, and what the shear needs: the relative
 * tangential velocity vt (eq 2.6; 0 when neither damping nor friction needs it), and fn n
 * in f. */
static inline double law_normal_at(const lsdem_penalty_law *restrict law, double stride,
                                   double area, double d, const double n[3],
                                   const double vrel[3], double vt[3], double f[3])
{
  const int relative = law->cn > 0.0 || law->mu > 0.0;
  double fn = law->kn * law_weight(law, stride, area) * d; /* eq 2.2: +n on A */
  double vn = 0.0;
  if (relative) vn = lsdem_dot3(vrel, n);
  if (law->cn > 0.0) {
    fn -= law->cn * stride * vn;
    if (fn < 0.0) fn = 0.0; /* a penalty contact pushes, never pulls */
  }
  for (int i = 0; i < 3; i++) {
    f[i] = fn * n[i];
    vt[i] = relative ? vrel[i] - vn * n[i] : 0.0;
  }
  return fn;
}

/* law_normal_at of contact point p, with its arm ra = p - xA (for the torques). */
static inline double law_normal(const lsdem_penalty_law *restrict law, double stride,
                                const double xa[3], const lsdem_contact_point *restrict p,
                                double ra[3], double vt[3], double f[3])
{
  for (int i = 0; i < 3; i++) ra[i] = p->point[i] - xa[i];
  return law_normal_at(law, stride, p->area, p->depth, p->normal, p->vrel, vt, f);
}

/* The shear spring carried over (report eq 2.8) into s: Z s_old, the stored spring of h
 * rotated from its normal to the current normal n; 0 for a new contact (h NULL). Returns
 * whether the spring is still to be advanced this step: 0 for an entry stamped with this
 * step (already advanced, taken as is). */
static inline int law_carried_shear(const lsdem_shear_hist *h, int64_t step, const double n[3],
                                    double s[3])
{
  const int fresh = !(h && h->stamp == lsdem_shear_stamp(step));
  if (!h) {
    s[0] = s[1] = s[2] = 0.0;
  } else if (!fresh) {
    for (int i = 0; i < 3; i++) s[i] = h->shear[i];
  } else {
    lsdem_rotate_between(h->shear, h->normal, n, s); /* eq 2.8: Z */
  }
  return fresh;
}

/* Tangential force (report eqs 2.7, 2.8, 2.10) added to f: shear spring s = Z s_old -
 * ks w dt vt (when fresh; s holds Z s_old); applied force ft = s - ct stride vt, capped at
 * mu fn, with the spring reset so that spring + damping equals the capped force. */
static inline void law_tangential(const lsdem_penalty_law *restrict law, double stride,
                                  double dt, double area, double fn, const double vt[3],
                                  double s[3], int fresh, double f[3])
{
  const double ct = law->ct * stride;
  double ft[3];
  if (fresh) {
    const double ks = law->ks * law_weight(law, stride, area);
    for (int i = 0; i < 3; i++) s[i] = s[i] - ks * dt * vt[i]; /* eqs 2.7-2.8 */
  }
  for (int i = 0; i < 3; i++) ft[i] = s[i] - ct * vt[i];
  const double cap = law->mu * fn; /* eq 2.10 */
  const double ft2 = lsdem_dot3(ft, ft);
  if (ft2 > cap * cap) {
    const double scale = cap / sqrt(ft2);
    for (int i = 0; i < 3; i++) {
      ft[i] *= scale;
      s[i] = ft[i] + ct * vt[i];
    }
  }
  for (int i = 0; i < 3; i++) f[i] += ft[i];
}

/* The history entry of a point's spring s at normal n, advanced at this step. */
static inline void law_history(lsdem_shear_hist *out, int node, int64_t step, const double s[3],
                               const double n[3])
{
  out->node = node;
  out->stamp = lsdem_shear_stamp(step);
  for (int i = 0; i < 3; i++) {
    out->shear[i] = s[i];
    out->normal[i] = n[i];
  }
}

/* A point's force f (normal part fn, arm ra, at p, depth d) into the pair's sums (eqs
 * 2.14-2.16: force and torque on A) and the normal-force weight of the mean point. */
static inline void law_sum_point(lsdem_contact_result *restrict sum, double *restrict weight,
                                 const double ra[3], const double f[3], double fn,
                                 const double p[3], double d)
{
  double ta[3];
  lsdem_cross3(ra, f, ta);
  for (int i = 0; i < 3; i++) {
    sum->force[i] += f[i];
    sum->torque_a[i] += ta[i];
    sum->point[i] += fn * p[i];
  }
  *weight += fn;
  sum->max_depth = d > sum->max_depth ? d : sum->max_depth; /* a max, not a branch */
}

/* The sums completed: B's reaction torque about its centroid, (ra + dab) x (-f) summed,
 * is -(sum of ra x f) - dab x (sum of f) (eq 2.16), and the mean point: a manifold's one
 * point itself (only, exactly: no weight to divide by, also when its force is 0), else the
 * weighted sum divided by its weight. */
static inline void law_finish(lsdem_contact_result *res, double weight, const double dab[3],
                              const double only[3])
{
  double dab_f[3];
  lsdem_cross3(dab, res->force, dab_f);
  for (int i = 0; i < 3; i++) res->torque_b[i] = -res->torque_a[i] - dab_f[i];
  if (only)
    for (int i = 0; i < 3; i++) res->point[i] = only[i];
  else if (weight > 0.0)
    for (int i = 0; i < 3; i++) res->point[i] /= weight;
}

/* The sums of a manifold of one point p, written (the sphere paths, one point every
 * contact): the bits of law_sum_point on zeroed sums then law_finish, without zeroing the
 * sums and reading them back. A sum of one term is 0 + the term (a term -0 gives +0). */
static inline void law_one_point(lsdem_contact_result *res, const double ra[3],
                                 const double f[3], const double p[3], double d,
                                 const double dab[3])
{
  double ta[3];
  lsdem_cross3(ra, f, ta); /* eq 2.16 */
  for (int i = 0; i < 3; i++) {
    res->force[i] = 0.0 + f[i]; /* eq 2.14 */
    res->torque_a[i] = 0.0 + ta[i];
  }
  res->max_depth = d > 0.0 ? d : 0.0;
  res->npen = 1;
  law_finish(res, 0.0, dab, p);
}

#endif /* LSDEM_CONTACT_POINT_H */
