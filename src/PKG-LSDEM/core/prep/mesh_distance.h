/* mesh_distance.h -- exact signed distance to a triangle mesh, shared by the mesh's dense
 * grid (mesh_import.c, lsdem_mesh_sdf_grid) and the narrow band of a wall (band_build.c).
 * Private to core/prep.
 *
 * The unsigned distance to the closest triangle (Ericson, Real-Time Collision Detection,
 * 5.1.5, with the Voronoi region of the closest point), signed by the angle-weighted
 * pseudonormal of that region (Baerentzen & Aanaes, IEEE TVCG 11(3), 2005): face normal,
 * sum of the two face normals for an edge, angle-weighted sum for a vertex. The sign is
 * exact for a closed, consistently oriented mesh when the triangle is the closest one. */
#ifndef LSDEM_PREP_MESH_DISTANCE_H
#define LSDEM_PREP_MESH_DISTANCE_H

#include "lsdem_prep.h"

#include <string.h>

/* Corner c (0..2) of triangle t. */
static inline const double *mesh_vert(const lsdem_mesh *m, int t, int c)
{
  return m->verts + 3 * m->tris[3 * t + c];
}

/* Unnormalised normal (b - a) x (c - a) of triangle t: twice its area (mesh_distance.c). */
void mesh_tri_normal(const lsdem_mesh *m, int t, double n[3]);

/* Edge analysis (mesh_import.c): counts into topo, and nbr[3t+e] = the triangle across
 * edge e of t (corner e to corner e+1) when the edge is shared by exactly two triangles
 * (else -1). nbr may be NULL. */
lsdem_status mesh_edges(const lsdem_mesh *m, lsdem_mesh_topology *topo, int *nbr,
                        lsdem_error *err);

/* The Voronoi region of a closest point: the face, edge e (corner e to e+1) or corner c. */
enum { FEAT_FACE = 0, FEAT_EDGE = 1, FEAT_VERTEX = 4 }; /* + edge 0..2 / corner 0..2 */

/* Closest point on triangle abc to p (Ericson 5.1.5); *feat = the Voronoi region. Inline:
 * the band builder calls it for every sample near every triangle. */
static inline void mesh_closest_on_triangle(const double *p, const double *a, const double *b,
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

/* Squared distance from p to triangle t. */
static inline double mesh_distance2_to(const lsdem_mesh *m, const double p[3], int t)
{
  double q[3], d[3];
  int feat;
  mesh_closest_on_triangle(p, mesh_vert(m, t, 0), mesh_vert(m, t, 1), mesh_vert(m, t, 2), q,
                           &feat);
  lsdem_sub3(p, q, d);
  return lsdem_dot3(d, d);
}

/* Pseudonormals: unit face normals, angle-weighted vertex normals, edge neighbours. */
typedef struct {
  double *face, *vertex;
  int *nbr;
} mesh_pseudonormals;

/* Builds them (the edges through mesh_edges, whose counts go to topo when not NULL).
 * Free with mesh_pseudonormals_free, also on failure. */
lsdem_status mesh_pseudonormals_build(const lsdem_mesh *m, mesh_pseudonormals *pn,
                                      lsdem_mesh_topology *topo, lsdem_error *err);
void mesh_pseudonormals_free(mesh_pseudonormals *pn);

/* Signed distance from p to triangle t: the distance to its closest point, signed by the
 * pseudonormal of that point's region (-0.0 never: on the surface it is +0). */
double mesh_signed_distance_to(const lsdem_mesh *m, const mesh_pseudonormals *pn,
                               const double p[3], int t);

#endif /* LSDEM_PREP_MESH_DISTANCE_H */
