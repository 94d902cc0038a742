/* closest_triangle.h -- the closest point of a triangle to a point (Ericson, Real-Time
 * Collision Detection, 5.1.5), with the Voronoi region it lies in: one implementation for
 * the kernel (a band wall's closest triangle, geom/band.c) and the preparation library
 * (exact distances to meshes, prep/mesh_distance.h). Private to the core. */
#ifndef LSDEM_GEOM_CLOSEST_TRIANGLE_H
#define LSDEM_GEOM_CLOSEST_TRIANGLE_H

#include "../base/lsdem_base.h"

#include <string.h>

/* The Voronoi region of a closest point: the face, edge e (corner e to e+1) or corner c. */
enum { FEAT_FACE = 0, FEAT_EDGE = 1, FEAT_VERTEX = 4 }; /* + edge 0..2 / corner 0..2 */

/* Closest point on triangle abc to p (Ericson 5.1.5); *feat = the Voronoi region. Inline:
 * the band builder calls it for every sample near every triangle. */
static inline void lsdem_closest_on_triangle(const double *p, const double *a, const double *b,
                                            const double *c, double *out, int *feat)
{
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  lsdem_sub3(b, a, ab), lsdem_sub3(c, a, ac), lsdem_sub3(p, a, ap);
  const double d1 = lsdem_dot3(ab, ap), d2 = lsdem_dot3(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) { memcpy(out, a, 3 * sizeof(double)); *feat = FEAT_VERTEX; return; }
  lsdem_sub3(p, b, bp);
  const double d3 = lsdem_dot3(ab, bp), d4 = lsdem_dot3(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) { memcpy(out, b, 3 * sizeof(double)); *feat = FEAT_VERTEX + 1; return; }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    for (int k = 0; k < 3; k++) out[k] = a[k] + v * ab[k];
    *feat = FEAT_EDGE + 0;
    return;
  }
  lsdem_sub3(p, c, cp);
  const double d5 = lsdem_dot3(ab, cp), d6 = lsdem_dot3(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) { memcpy(out, c, 3 * sizeof(double)); *feat = FEAT_VERTEX + 2; return; }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    for (int k = 0; k < 3; k++) out[k] = a[k] + w * ac[k];
    *feat = FEAT_EDGE + 2;
    return;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    for (int k = 0; k < 3; k++) out[k] = b[k] + w * (c[k] - b[k]);
    *feat = FEAT_EDGE + 1;
    return;
  }
  const double den = 1.0 / (va + vb + vc), v = vb * den, w = vc * den;
  for (int k = 0; k < 3; k++) out[k] = a[k] + ab[k] * v + ac[k] * w;
  *feat = FEAT_FACE;
}

#endif /* LSDEM_GEOM_CLOSEST_TRIANGLE_H */
