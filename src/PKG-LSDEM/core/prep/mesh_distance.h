/* mesh_distance.h -- exact signed distance to a triangle mesh, shared by the mesh's dense
 * grid (mesh_sdf.c, lsdem_mesh_sdf_grid) and the narrow band of a wall (band_build.c).
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
#include "../geom/closest_triangle.h"

#include <string.h>

/* Corner c (0..2) of triangle t. */
static inline const double *mesh_vert(const lsdem_mesh *m, int t, int c)
{
  return m->verts + 3 * m->tris[3 * t + c];
}

/* Unnormalised normal (b - a) x (c - a) of triangle t: twice its area (mesh_distance.c). */
void mesh_tri_normal(const lsdem_mesh *m, int t, double n[3]);

/* Generalised winding number of m at p (Jacobson, Kavan & Sorkine-Hornung, SIGGRAPH 2013):
 * the triangles' signed solid angles seen from p (Van Oosterom & Strackee, IEEE TBME 30(2),
 * 1983) over 4 pi: 1 inside a closed outward-oriented mesh, 0 outside, -1 inside an
 * inward-oriented one; for a mesh with holes, a smooth value between that is more than 1/2
 * in magnitude where the holes' mouths, spanned, would enclose p. O(triangles). */
double mesh_winding_number(const lsdem_mesh *m, const double p[3]);

/* Edge analysis (mesh_check.c): counts into topo, and nbr[3t+e] = the triangle across
 * edge e of t (corner e to corner e+1) when the edge is shared by exactly two triangles
 * (else -1). nbr may be NULL. */
lsdem_status mesh_edges(const lsdem_mesh *m, lsdem_mesh_topology *topo, int *nbr,
                        lsdem_error *err);

/* Squared distance from p to triangle t. */
static inline double mesh_distance2_to(const lsdem_mesh *m, const double p[3], int t)
{
  double q[3], d[3];
  int feat;
  lsdem_closest_on_triangle(p, mesh_vert(m, t, 0), mesh_vert(m, t, 1), mesh_vert(m, t, 2), q,
                           &feat);
  lsdem_sub3(p, q, d);
  return lsdem_dot3(d, d);
}

/* Pseudonormals (the kernel's lsdem_pseudonormals) with the edge neighbours they use. */
typedef struct {
  lsdem_pseudonormals pn;
  int *nbr; /* 3 per triangle: the triangle across each edge, -1 none (owned) */
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
