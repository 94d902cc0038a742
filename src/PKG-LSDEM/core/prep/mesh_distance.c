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

lsdem_status mesh_pseudonormals_build(const lsdem_mesh *m, mesh_pseudonormals *pn,
                                      lsdem_mesh_topology *topo, lsdem_error *err)
{
  pn->face = malloc(3 * (size_t)m->ntris * sizeof(double));
  pn->vertex = calloc(3 * (size_t)m->nverts, sizeof(double));
  pn->nbr = malloc(3 * (size_t)m->ntris * sizeof(int));
  if (!pn->face || !pn->vertex || !pn->nbr)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate mesh normals");
  lsdem_mesh_topology local;
  lsdem_status st = mesh_edges(m, topo ? topo : &local, pn->nbr, err);
  if (st != LSDEM_OK) return st;
  for (int t = 0; t < m->ntris; t++) {
    double *n = pn->face + 3 * t;
    mesh_tri_normal(m, t, n);
    const double len = sqrt(lsdem_dot3(n, n));
    for (int k = 0; k < 3; k++) n[k] = len > 0.0 ? n[k] / len : 0.0;
    for (int c = 0; c < 3; c++) { /* interior angle at corner c */
      double u[3], w[3];
      lsdem_sub3(mesh_vert(m, t, (c + 1) % 3), mesh_vert(m, t, c), u);
      lsdem_sub3(mesh_vert(m, t, (c + 2) % 3), mesh_vert(m, t, c), w);
      const double nu = sqrt(lsdem_dot3(u, u)), nw = sqrt(lsdem_dot3(w, w));
      const double angle =
          nu > 0.0 && nw > 0.0 ? acos(fmax(-1.0, fmin(1.0, lsdem_dot3(u, w) / (nu * nw)))) : 0.0;
      double *vn = pn->vertex + 3 * m->tris[3 * t + c];
      for (int k = 0; k < 3; k++) vn[k] += angle * n[k];
    }
  }
  return LSDEM_OK;
}

void mesh_pseudonormals_free(mesh_pseudonormals *pn)
{
  free(pn->face), free(pn->vertex), free(pn->nbr);
  pn->face = pn->vertex = NULL;
  pn->nbr = NULL;
}

static void feature_normal(const lsdem_mesh *m, const mesh_pseudonormals *pn, int t, int feat,
                           double n[3])
{
  const double *f = pn->face + 3 * t;
  if (feat >= FEAT_VERTEX) {
    memcpy(n, pn->vertex + 3 * m->tris[3 * t + feat - FEAT_VERTEX], 3 * sizeof(double));
  } else if (feat >= FEAT_EDGE) {
    const int o = pn->nbr[3 * t + feat - FEAT_EDGE];
    for (int k = 0; k < 3; k++) n[k] = f[k] + (o >= 0 ? pn->face[3 * o + k] : f[k]);
  } else {
    memcpy(n, f, 3 * sizeof(double));
  }
}

double mesh_signed_distance_to(const lsdem_mesh *m, const mesh_pseudonormals *pn,
                               const double p[3], int t)
{
  double q[3], d[3], n[3];
  int feat;
  lsdem_closest_on_triangle(p, mesh_vert(m, t, 0), mesh_vert(m, t, 1), mesh_vert(m, t, 2), q,
                           &feat);
  lsdem_sub3(p, q, d);
  feature_normal(m, pn, t, feat, n);
  const double dist = sqrt(lsdem_dot3(d, d));
  return lsdem_dot3(d, n) < 0.0 ? -dist : dist;
}
