/* band_check.c -- how far a built band's zero level set is from the mesh it was made from
 * (lsdem-shape wall/terrain's report): the two one-sided distances of the Hausdorff
 * distance, each at points where it is largest for a trilinear band (vertices and
 * centroids of the mesh; zero crossings of the band's grid edges). */
#include "lsdem_prep.h"

#include <math.h>

/* Largest |phi| at the mesh's vertices and triangle centroids: how far the band's zero
 * level set can be from the surface there (0 up to interpolation). */
static double mesh_to_zero(const lsdem_band *b, const lsdem_mesh *m)
{
  double worst = 0.0, g[3];
  for (int v = 0; v < m->nverts; v++)
    worst = fmax(worst, fabs(lsdem_band_eval(b, m->verts + 3 * v, g)));
  for (int t = 0; t < m->ntris; t++) {
    double c[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < 3; k++)
      for (int a = 0; a < 3; a++) c[a] += m->verts[3 * m->tris[3 * t + k] + a] / 3.0;
    worst = fmax(worst, fabs(lsdem_band_eval(b, c, g)));
  }
  return worst;
}

/* Largest distance from a zero crossing of a stored brick's grid edge (linear between its
 * two samples, as trilinear interpolation is along an edge) to the closest triangle. */
static double zero_to_mesh(const lsdem_band *b, int64_t *ncross)
{
  enum { S = LSDEM_BAND_BRICK_SIDE, N = LSDEM_BAND_BRICK };
  const int64_t slots = (int64_t)b->nb[0] * b->nb[1] * b->nb[2];
  const int step[3] = {1, S, S * S};
  double worst = 0.0;
  *ncross = 0;
  for (int64_t s = 0; s < slots; s++) {
    const int32_t k = b->index[s];
    if (k < 0) continue;
    const int bc[3] = {(int)(s % b->nb[0]), (int)(s / b->nb[0] % b->nb[1]),
                       (int)(s / ((int64_t)b->nb[0] * b->nb[1]))};
    const float *phi = b->phi + (size_t)k * LSDEM_BAND_BRICK_SAMPLES;
    for (int z = 0; z < N; z++)
      for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++) {
          const int here = x + S * (y + S * z), loc[3] = {x, y, z};
          int inside = 1; /* samples past the grid's last (n - 1) are never looked up */
          for (int c = 0; c < 3; c++) inside &= N * bc[c] + loc[c] < b->n[c];
          for (int a = 0; a < 3 && inside; a++) {
            if (N * bc[a] + loc[a] + 1 >= b->n[a]) continue;
            const double p0 = phi[here], p1 = phi[here + step[a]];
            if ((p0 < 0.0) == (p1 < 0.0) || fabs(p0) >= b->width || fabs(p1) >= b->width)
              continue;
            double p[3], d2;
            for (int c = 0; c < 3; c++)
              p[c] = b->origin[c] + b->h * (N * bc[c] + loc[c] + (c == a ? p0 / (p0 - p1) : 0.0));
            if (lsdem_band_closest_triangle(b, p, &d2) < 0) continue;
            worst = fmax(worst, sqrt(d2));
            (*ncross)++;
          }
        }
  }
  return worst;
}

void lsdem_band_misfit(const lsdem_band *b, const lsdem_mesh *m, lsdem_band_distance *out)
{
  out->mesh_to_zero = mesh_to_zero(b, m);
  out->zero_to_mesh = b->ntris > 0 && !b->heights ? zero_to_mesh(b, &out->crossings) : 0.0;
  if (b->ntris == 0 || b->heights) out->crossings = 0;
  out->hausdorff = fmax(out->mesh_to_zero, out->zero_to_mesh);
}
