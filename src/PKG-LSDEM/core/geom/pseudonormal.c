/* pseudonormal.c -- angle-weighted pseudonormals of a triangle surface and the signed
 * distance to one triangle (lsdem_geom.h): one implementation for the preparation library
 * (meshes to grids and bands, prep/mesh_distance.c) and the kernel (a band wall's exact
 * mode, band.c). */
#include "closest_triangle.h"
#include "lsdem_geom.h"

#include <math.h>
#include <stdlib.h>

static const double *corner(const double *verts, const int *tris, int64_t t, int c)
{
  return verts + 3 * (int64_t)tris[3 * t + c];
}

lsdem_status lsdem_pseudonormals_make(const double *verts, int64_t nverts, const int *tris,
                                      int64_t ntris, const int *nbr, lsdem_pseudonormals *pn,
                                      lsdem_error *err)
{
  pn->face = malloc(3 * (size_t)ntris * sizeof(double) + 1);
  pn->vertex = calloc(3 * (size_t)nverts + 1, sizeof(double));
  pn->sphere = malloc(4 * (size_t)ntris * sizeof(double) + 1);
  pn->nbr = nbr;
  if (!pn->face || !pn->vertex || !pn->sphere)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate the normals of %lld triangles",
                      (long long)ntris);
  for (int64_t t = 0; t < ntris; t++) {
    double *sph = pn->sphere + 4 * t;
    sph[3] = 0.0;
    for (int k = 0; k < 3; k++)
      sph[k] = (corner(verts, tris, t, 0)[k] + corner(verts, tris, t, 1)[k] +
                corner(verts, tris, t, 2)[k]) / 3.0;
    for (int c = 0; c < 3; c++) {
      double d[3];
      lsdem_sub3(corner(verts, tris, t, c), sph, d);
      sph[3] = fmax(sph[3], sqrt(lsdem_dot3(d, d)));
    }
    double *n = pn->face + 3 * t, e1[3], e2[3];
    lsdem_sub3(corner(verts, tris, t, 1), corner(verts, tris, t, 0), e1);
    lsdem_sub3(corner(verts, tris, t, 2), corner(verts, tris, t, 0), e2);
    lsdem_cross3(e1, e2, n);
    const double len = sqrt(lsdem_dot3(n, n));
    for (int k = 0; k < 3; k++) n[k] = len > 0.0 ? n[k] / len : 0.0;
    for (int c = 0; c < 3; c++) { /* interior angle at corner c */
      double u[3], w[3];
      lsdem_sub3(corner(verts, tris, t, (c + 1) % 3), corner(verts, tris, t, c), u);
      lsdem_sub3(corner(verts, tris, t, (c + 2) % 3), corner(verts, tris, t, c), w);
      const double nu = sqrt(lsdem_dot3(u, u)), nw = sqrt(lsdem_dot3(w, w));
      const double angle =
          nu > 0.0 && nw > 0.0 ? acos(fmax(-1.0, fmin(1.0, lsdem_dot3(u, w) / (nu * nw)))) : 0.0;
      double *vn = pn->vertex + 3 * (int64_t)tris[3 * t + c];
      for (int k = 0; k < 3; k++) vn[k] += angle * n[k];
    }
  }
  return LSDEM_OK;
}

void lsdem_pseudonormals_free(lsdem_pseudonormals *pn)
{
  free(pn->face), free(pn->vertex), free(pn->sphere);
  pn->face = pn->vertex = pn->sphere = NULL;
  pn->nbr = NULL;
}

/* The pseudonormal of feature feat (closest_triangle.h's FEAT_*) of triangle t. */
static void feature_normal(const int *tris, const lsdem_pseudonormals *pn, int64_t t, int feat,
                           double n[3])
{
  const double *f = pn->face + 3 * t;
  if (feat >= FEAT_VERTEX) {
    memcpy(n, pn->vertex + 3 * (int64_t)tris[3 * t + feat - FEAT_VERTEX], 3 * sizeof(double));
  } else if (feat >= FEAT_EDGE) {
    const int o = pn->nbr[3 * t + feat - FEAT_EDGE];
    for (int k = 0; k < 3; k++) n[k] = f[k] + (o >= 0 ? pn->face[3 * (int64_t)o + k] : f[k]);
  } else {
    memcpy(n, f, 3 * sizeof(double));
  }
}

double lsdem_signed_distance_to_triangle(const double *verts, const int *tris,
                                         const lsdem_pseudonormals *pn, const double p[3],
                                         int64_t t, double grad[3])
{
  double q[3], d[3], n[3];
  int feat;
  lsdem_closest_on_triangle(p, corner(verts, tris, t, 0), corner(verts, tris, t, 1),
                            corner(verts, tris, t, 2), q, &feat);
  lsdem_sub3(p, q, d);
  feature_normal(tris, pn, t, feat, n);
  const double dist = sqrt(lsdem_dot3(d, d));
  const double sign = lsdem_dot3(d, n) < 0.0 ? -1.0 : 1.0;
  if (grad) {
    if (dist > 0.0)
      for (int k = 0; k < 3; k++) grad[k] = sign * d[k] / dist;
    else
      memcpy(grad, pn->face + 3 * t, 3 * sizeof(double));
  }
  return sign * dist;
}
