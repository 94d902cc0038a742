/* mesh_distance.c -- exact signed distance to a triangle mesh: pseudonormals and the
 * signed distance to one triangle (mesh_distance.h), for lsdem_mesh_sdf_grid and the
 * narrow band of a wall (band_build.c). */
#include "mesh_distance.h"

#include <math.h>
#include <stdlib.h>

void mesh_tri_normal(const lsdem_mesh *m, int t, double n[3])
{
  double e1[3], e2[3];
  lsdem_sub3(mesh_vert(m, t, 1), mesh_vert(m, t, 0), e1);
  lsdem_sub3(mesh_vert(m, t, 2), mesh_vert(m, t, 0), e2);
  lsdem_cross3(e1, e2, n);
}

double mesh_winding_number(const lsdem_mesh *m, const double p[3])
{
  double sum = 0.0;
  for (int t = 0; t < m->ntris; t++) {
    double a[3], b[3], c[3], bc[3];
    lsdem_sub3(mesh_vert(m, t, 0), p, a);
    lsdem_sub3(mesh_vert(m, t, 1), p, b);
    lsdem_sub3(mesh_vert(m, t, 2), p, c);
    const double la = sqrt(lsdem_dot3(a, a)), lb = sqrt(lsdem_dot3(b, b)), lc = sqrt(lsdem_dot3(c, c));
    lsdem_cross3(b, c, bc);
    /* tan(Omega / 2) = a . (b x c) / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|) */
    const double den = la * lb * lc + lsdem_dot3(a, b) * lc + lsdem_dot3(a, c) * lb +
                       lsdem_dot3(b, c) * la;
    sum += 2.0 * atan2(lsdem_dot3(a, bc), den);
  }
  return sum / (4.0 * M_PI);
}

lsdem_status mesh_pseudonormals_build(const lsdem_mesh *m, mesh_pseudonormals *pn,
                                      lsdem_mesh_topology *topo, lsdem_error *err)
{
  pn->nbr = malloc(3 * (size_t)m->ntris * sizeof(int) + 1);
  if (!pn->nbr) return lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate mesh edges");
  lsdem_mesh_topology local;
  lsdem_status st = mesh_edges(m, topo ? topo : &local, pn->nbr, err);
  if (st != LSDEM_OK) return st;
  return lsdem_pseudonormals_make(m->verts, m->nverts, m->tris, m->ntris, pn->nbr, &pn->pn, err);
}

void mesh_pseudonormals_free(mesh_pseudonormals *pn)
{
  lsdem_pseudonormals_free(&pn->pn);
  free(pn->nbr);
  pn->nbr = NULL;
}

double mesh_signed_distance_to(const lsdem_mesh *m, const mesh_pseudonormals *pn,
                               const double p[3], int t)
{
  return lsdem_signed_distance_to_triangle(m->verts, m->tris, &pn->pn, p, t, NULL);
}
