/* pair.c -- one pair end to end: detection into a manifold, then the penalty law, with the
 * pair's node list and shear history carried from the last step to this one; and the same
 * for an analytic sphere's one contact point, without a manifold. */
#include "point.h"

#include <stddef.h>

int lsdem_contact_penalty(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                          const lsdem_pose *pb, const lsdem_contact_params *prm,
                          int64_t step, const lsdem_pair_state *in, lsdem_pair_state *out,
                          lsdem_manifold *m, lsdem_contact_result *res)
{
  lsdem_detect(A, pa, B, pb, &prm->detect, step, in ? &in->list : NULL,
               out ? &out->list : NULL, m);
  int nshear = 0;
  lsdem_penalty_apply(m, &prm->law, prm->dt, step, in ? in->shear : NULL, in ? in->nshear : 0,
                      out ? out->shear : NULL, &nshear, res);
  if (out) out->nshear = nshear;
  return res->npen;
}

/* A sphere's one point from its overlap (B's outward normal n, depth d > 0) and the law
 * there: the part of the sphere path after lsdem_sphere_overlap (below), inline in both
 * entry points. */
static inline __attribute__((always_inline)) void sphere_point_law(
    double ra, const lsdem_pose *pa, const lsdem_pose *pb, const double n[3], double d,
    const lsdem_penalty_law *law, double dt, int64_t step, const lsdem_shear_hist *hist_in,
    int n_in, lsdem_shear_hist *hist_out, int *n_out, lsdem_contact_result *res)
{
  pair_motion pm;
  double p[3], r[3], vrel[3];
  pair_motion_of(pa, pb, &pm);
  sphere_contact_point(ra, pa->x, n, d, p);
  for (int i = 0; i < 3; i++) r[i] = p[i] - pm.xa[i];
  point_velocity(&pm, r, vrel);

  const double area = lsdem_sphere_contact_area(ra);
  double vt[3], f[3];
  const double fn = law_normal_at(law, 1.0, area, d, n, vrel, vt, f); /* eq 2.2 */
  if (law->mu > 0.0) {                                         /* eqs 2.7-2.10 */
    /* the pair's one entry is node 0's (entries are sorted by node, nodes >= 0) */
    const lsdem_shear_hist *h = hist_in && n_in > 0 && hist_in[0].node == 0 ? hist_in : NULL;
    double s[3];
    const int fresh = law_carried_shear(h, step, n, s);
    law_tangential(law, 1.0, dt, area, fn, vt, s, fresh, f);
    if (hist_out) {
      law_history(hist_out, 0, step, s, n);
      if (n_out) *n_out = 1;
    }
  }
  law_one_point(res, r, f, p, d, pm.dab); /* eqs 2.14-2.16 */
}

/* The sphere path of lsdem_detect (lsdem_sphere_overlap, sphere_contact_point: one point,
 * node 0, stride 1, the cross-section as its area) and lsdem_penalty_apply on that one
 * point, formula by formula (point.h): the overlap, then its point and law. */
int lsdem_contact_sphere(double ra, const lsdem_pose *pa, const lsdem_shape *B,
                         const lsdem_pose *pb, const lsdem_penalty_law *law, double dt,
                         int64_t step, const lsdem_shear_hist *hist_in, int n_in,
                         lsdem_shear_hist *hist_out, int *n_out, lsdem_contact_result *res)
{
  static const lsdem_contact_result no_result; /* all zero */
  if (n_out) *n_out = 0;
  double n[3], d;
  int lookups;
  if (!lsdem_sphere_overlap(ra, pa, B, pb, n, &d, &lookups)) {
    *res = no_result;
    res->ntested = lookups;
    return 0;
  }
  sphere_point_law(ra, pa, pb, n, d, law, dt, step, hist_in, n_in, hist_out, n_out, res);
  res->ntested = lookups;
  return 1;
}

int lsdem_contact_sphere_overlapping(double ra, const lsdem_pose *pa, const lsdem_pose *pb,
                                     const double n[3], double d,
                                     const lsdem_penalty_law *law, double dt, int64_t step,
                                     const lsdem_shear_hist *hist_in, int n_in,
                                     lsdem_shear_hist *hist_out, int *n_out,
                                     lsdem_contact_result *res)
{
  if (n_out) *n_out = 0;
  sphere_point_law(ra, pa, pb, n, d, law, dt, step, hist_in, n_in, hist_out, n_out, res);
  res->ntested = 1;
  return 1;
}
