/* mesh_sdf.c -- a closed triangle mesh to a signed-distance grid (lsdem_mesh_sdf_grid):
 * the distance to the closest triangle signed by the pseudonormal of its closest feature
 * (mesh_distance.h, shared with the narrow bands of walls), exact for a closed,
 * consistently oriented mesh. */
#include "lsdem_prep.h"
#include "mesh_distance.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------ signed distance ---- */

/* The sampler's state: per sample the smallest |distance| found, its triangle (-1: none
 * yet) and the signed value. */
typedef struct {
  const lsdem_mesh *m;
  const mesh_pseudonormals *pn;
  const lsdem_grid *g;
  double *best;
  int *tri;
  float *phi;
} sdf_work;

static size_t sample_index(const lsdem_grid *g, int i, int j, int k)
{
  return ((size_t)k * g->n[1] + j) * g->n[0] + i;
}

static void try_triangle(sdf_work *w, size_t q, int i, int j, int k, int t)
{
  const lsdem_grid *g = w->g;
  const double p[3] = {g->origin[0] + g->h * i, g->origin[1] + g->h * j, g->origin[2] + g->h * k};
  const double s = mesh_signed_distance_to(w->m, w->pn, p, t);
  if (fabs(s) < w->best[q]) w->best[q] = fabs(s), w->tri[q] = t, w->phi[q] = (float)s;
}

/* Exact distances in a band: each triangle visits the samples within `band` of its
 * bounding box, so a sample closer than `band` to the mesh meets its closest triangle. */
static void rasterize(sdf_work *w, double band)
{
  const lsdem_grid *g = w->g;
  for (int t = 0; t < w->m->ntris; t++) {
    int lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
      double bmin = HUGE_VAL, bmax = -HUGE_VAL;
      for (int c = 0; c < 3; c++) bmin = fmin(bmin, mesh_vert(w->m, t, c)[a]), bmax = fmax(bmax, mesh_vert(w->m, t, c)[a]);
      lo[a] = (int)fmax(ceil((bmin - band - g->origin[a]) / g->h), 0.0);
      hi[a] = (int)fmin(floor((bmax + band - g->origin[a]) / g->h), g->n[a] - 1.0);
    }
    for (int k = lo[2]; k <= hi[2]; k++)
      for (int j = lo[1]; j <= hi[1]; j++)
        for (int i = lo[0]; i <= hi[0]; i++) try_triangle(w, sample_index(g, i, j, k), i, j, k, t);
  }
}

/* Closest-triangle propagation (Bridson's sweeps, as in his makelevelset3): each sample
 * tries the closest triangles of its 7 neighbours behind it in sweep order (di, dj, dk). */
static void sweep(sdf_work *w, int di, int dj, int dk)
{
  const lsdem_grid *g = w->g;
  for (int kk = 0; kk < g->n[2]; kk++)
    for (int jj = 0; jj < g->n[1]; jj++)
      for (int ii = 0; ii < g->n[0]; ii++) {
        const int i = di > 0 ? ii : g->n[0] - 1 - ii, j = dj > 0 ? jj : g->n[1] - 1 - jj;
        const int k = dk > 0 ? kk : g->n[2] - 1 - kk;
        const size_t q = sample_index(g, i, j, k);
        for (int c = 1; c < 8; c++) {
          const int ni = i - (c & 1 ? di : 0), nj = j - (c & 2 ? dj : 0), nk = k - (c & 4 ? dk : 0);
          if (ni < 0 || nj < 0 || nk < 0 || ni >= g->n[0] || nj >= g->n[1] || nk >= g->n[2])
            continue;
          const int t = w->tri[sample_index(g, ni, nj, nk)];
          if (t >= 0 && t != w->tri[q]) try_triangle(w, q, i, j, k, t);
        }
      }
}

/* Signs away from the band by flood fill: the band (every sample within `band` >= h of
 * the mesh, signed exactly) separates inside from outside, so each far sample takes the
 * sign of the band samples its 6-connected region touches. */
static lsdem_status fill_signs(sdf_work *w, double band, lsdem_error *err)
{
  const lsdem_grid *g = w->g;
  const size_t total = (size_t)g->n[0] * g->n[1] * g->n[2];
  size_t *queue = malloc(total * sizeof(size_t));
  signed char *sign = malloc(total);
  if (!queue || !sign) {
    free(queue), free(sign);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate the sign fill");
  }
  size_t head = 0, tail = 0;
  for (size_t q = 0; q < total; q++) {
    sign[q] = w->best[q] <= band ? (w->phi[q] < 0.0f ? -1 : 1) : 0;
    if (sign[q]) queue[tail++] = q;
  }
  const size_t stride[3] = {1, (size_t)g->n[0], (size_t)g->n[0] * g->n[1]};
  while (head < tail) {
    const size_t q = queue[head++];
    const int c[3] = {(int)(q % stride[1]), (int)(q / stride[1] % g->n[1]), (int)(q / stride[2])};
    for (int a = 0; a < 3; a++)
      for (int dir = -1; dir <= 1; dir += 2) {
        if (c[a] + dir < 0 || c[a] + dir >= g->n[a]) continue;
        const size_t r = dir < 0 ? q - stride[a] : q + stride[a];
        if (sign[r]) continue;
        sign[r] = sign[q];
        queue[tail++] = r;
      }
  }
  for (size_t q = 0; q < total; q++)
    if (w->best[q] > band) w->phi[q] = (float)(sign[q] < 0 ? -w->best[q] : w->best[q]);
  free(queue), free(sign);
  return LSDEM_OK;
}

lsdem_status lsdem_mesh_sdf_grid(const lsdem_mesh *m, double h, int margin, lsdem_grid *g,
                                 lsdem_error *err)
{
  if (!m || !g || m->ntris < 1 || m->nverts < 3)
    return lsdem_fail(err, LSDEM_ERR_ARG, "NULL or empty mesh");
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (int v = 0; v < m->nverts; v++)
    for (int a = 0; a < 3; a++)
      lo[a] = fmin(lo[a], m->verts[3 * v + a]), hi[a] = fmax(hi[a], m->verts[3 * v + a]);
  float *phi;
  lsdem_status st = lsdem_grid_alloc(lo, hi, h, margin, g, &phi, err);
  if (st != LSDEM_OK) return st;
  const size_t total = (size_t)g->n[0] * g->n[1] * g->n[2];
  mesh_pseudonormals pn = {0};
  sdf_work w = {m, &pn, g, malloc(total * sizeof(double)), malloc(total * sizeof(int)), phi};
  if (!w.best || !w.tri) st = lsdem_fail(err, LSDEM_ERR_NOMEM, "out of memory");
  if (st == LSDEM_OK) st = mesh_pseudonormals_build(m, &pn, NULL, err);
  if (st == LSDEM_OK) {
    const double band = 2.0 * h;
    for (size_t q = 0; q < total; q++) w.best[q] = HUGE_VAL, w.tri[q] = -1;
    rasterize(&w, band);
    for (int pass = 0; pass < 2; pass++)
      for (int d = 0; d < 8; d++) sweep(&w, d & 1 ? -1 : 1, d & 2 ? -1 : 1, d & 4 ? -1 : 1);
    st = fill_signs(&w, band, err);
  }
  mesh_pseudonormals_free(&pn);
  free(w.best), free(w.tri);
  if (st != LSDEM_OK) lsdem_grid_free(g);
  return st;
}
