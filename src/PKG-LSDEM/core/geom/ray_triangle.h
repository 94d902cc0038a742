/* ray_triangle.h -- where a ray meets a triangle (Moller & Trumbore, J. Graphics Tools 2(1),
 * 1997): one implementation for the kernel (a band's thin ridges, geom/thin_features.c) and
 * the preparation library (a mesh's self-intersections, prep/mesh_check.c). Private to the
 * core. */
#ifndef LSDEM_GEOM_RAY_TRIANGLE_H
#define LSDEM_GEOM_RAY_TRIANGLE_H

#include "../base/lsdem_base.h"

#include <math.h>

/* The parameter t at which o + t d meets triangle abc (any sign of t; d need not be unit),
 * or HUGE_VAL when it misses it or runs parallel to it (|det| <= 1e-12 |ab| |ac| |d|: a
 * coplanar touch is not a crossing). */
static inline double lsdem_ray_triangle(const double o[3], const double d[3], const double *a,
                                        const double *b, const double *c)
{
  double e1[3], e2[3], pv[3], tv[3], qv[3];
  lsdem_sub3(b, a, e1), lsdem_sub3(c, a, e2);
  lsdem_cross3(d, e2, pv);
  const double det = lsdem_dot3(e1, pv);
  const double scale = sqrt(lsdem_dot3(e1, e1) * lsdem_dot3(e2, e2) * lsdem_dot3(d, d));
  if (fabs(det) <= 1e-12 * scale) return HUGE_VAL;
  const double inv = 1.0 / det;
  lsdem_sub3(o, a, tv);
  const double u = lsdem_dot3(tv, pv) * inv;
  if (u < 0.0 || u > 1.0) return HUGE_VAL;
  lsdem_cross3(tv, e1, qv);
  const double v = lsdem_dot3(d, qv) * inv;
  if (v < 0.0 || u + v > 1.0) return HUGE_VAL;
  return lsdem_dot3(e2, qv) * inv;
}

#endif /* LSDEM_GEOM_RAY_TRIANGLE_H */
