/* heights.c -- a terrain band kept as its heights (lsdem_band with heights != NULL; the
 * column form of a height map, 4 bytes per column): lookups are the exact signed distance
 * to the terrain's triangles, found among the cells within `width` of the point.
 *
 * The surface is lsdem_heightmap_mesh's: cell (i,j) with corners a = (i,j), b = (i+1,j),
 * d = (i,j+1), e = (i+1,j+1) is split along a-e into triangles (a,b,e) and (a,e,d), vertex
 * (i,j) at (origin[0] + h i, origin[1] + h j, z(i,j)) -- the same doubles as the mesh's
 * vertices, so a brick band of the same terrain in exact mode gives the same distances.
 * Outside: above the surface (z greater than the surface's height at p's x, y). */
#include "lsdem_geom.h"
#include "closest_triangle.h"

#include <math.h>
#include <stdlib.h>

enum { TILE = LSDEM_HEIGHTS_TILE };

/* max and min without libm's NaN rules (called per lookup: kept inline) */
static inline double maxd(double a, double b) { return a > b ? a : b; }
static inline double mind(double a, double b) { return a < b ? a : b; }

static inline double height_at(const lsdem_band *b, int i, int j)
{
  return (double)b->heights[(size_t)i + (size_t)b->n[0] * (size_t)j];
}

/* The cell holding grid coordinate u (clamped to the last cell) and the fraction in it. */
static inline int cell_along(double u, int n, double *f)
{
  const double top = (double)(n - 2);
  int i = u <= 0.0 ? 0 : (u >= top ? n - 2 : (int)u); /* (int) is the floor for u > 0 */
  *f = u - i;
  return i;
}

/* The surface's height over (x, y) in the box: the plane of the triangle holding it. */
static double surface_height(const lsdem_band *b, double x, double y)
{
  double fx, fy;
  const int i = cell_along((x - b->origin[0]) / b->h, b->n[0], &fx);
  const int j = cell_along((y - b->origin[1]) / b->h, b->n[1], &fy);
  const double za = height_at(b, i, j), ze = height_at(b, i + 1, j + 1);
  if (fx >= fy) return za + fx * (height_at(b, i + 1, j) - za) + fy * (ze - height_at(b, i + 1, j));
  return za + fy * (height_at(b, i, j + 1) - za) + fx * (ze - height_at(b, i, j + 1));
}

/* Lower bound on the distance from p (in the box) to the surface, from the height ranges
 * of p's tile and its 8 neighbours: the surface in them lies at least their vertical gap
 * away, any other at least one tile's width (TILE h) across. */
static double tile_bound(const lsdem_band *b, const double p[3])
{
  const int ti = (int)((p[0] - b->origin[0]) / (b->h * TILE));
  const int tj = (int)((p[1] - b->origin[1]) / (b->h * TILE));
  double gap = TILE * b->h;
  for (int j = tj - 1; j <= tj + 1; j++)
    for (int i = ti - 1; i <= ti + 1; i++) {
      if (i < 0 || j < 0 || i >= b->nt[0] || j >= b->nt[1]) continue;
      const float *r = &b->tile_range[2 * ((size_t)i + (size_t)b->nt[0] * (size_t)j)];
      const double g = maxd(0.0, maxd((double)r[0] - p[2], p[2] - (double)r[1]));
      if (g < gap) gap = g;
    }
  return gap;
}

/* The vertices of cell (i,j)'s triangle t (0: a b e, 1: a e d). */
static void cell_triangle(const lsdem_band *b, int i, int j, int t, double v[3][3])
{
  const int di[2][3] = {{0, 1, 1}, {0, 1, 0}}, dj[2][3] = {{0, 0, 1}, {0, 1, 1}};
  for (int k = 0; k < 3; k++) {
    const int ii = i + di[t][k], jj = j + dj[t][k];
    v[k][0] = b->origin[0] + b->h * ii;
    v[k][1] = b->origin[1] + b->h * jj;
    v[k][2] = height_at(b, ii, jj);
  }
}

/* Squared distance from p to the nearest triangle of cell (i,j) if below *best2 (then
 * *best2 and q updated, and n the triangle's upward normal). */
static inline void visit_cell(const lsdem_band *b, int i, int j, const double p[3], double *best2,
                       double q[3], double n[3])
{
  const double x0 = b->origin[0] + b->h * i, y0 = b->origin[1] + b->h * j;
  const double dx = maxd(0.0, maxd(x0 - p[0], p[0] - (x0 + b->h)));
  const double dy = maxd(0.0, maxd(y0 - p[1], p[1] - (y0 + b->h)));
  if (dx * dx + dy * dy >= *best2) return;
  const double z[4] = {height_at(b, i, j), height_at(b, i + 1, j), height_at(b, i, j + 1),
                       height_at(b, i + 1, j + 1)};
  const double lo = mind(mind(z[0], z[1]), mind(z[2], z[3]));
  const double hi = maxd(maxd(z[0], z[1]), maxd(z[2], z[3]));
  const double dz = maxd(0.0, maxd(lo - p[2], p[2] - hi));
  if (dx * dx + dy * dy + dz * dz >= *best2) return;
  for (int t = 0; t < 2; t++) {
    double v[3][3], c[3], d[3];
    int feat;
    cell_triangle(b, i, j, t, v);
    lsdem_closest_on_triangle(p, v[0], v[1], v[2], c, &feat);
    lsdem_sub3(p, c, d);
    const double d2 = lsdem_dot3(d, d);
    if (d2 < *best2) {
      double e1[3], e2[3];
      *best2 = d2;
      q[0] = c[0], q[1] = c[1], q[2] = c[2];
      lsdem_sub3(v[1], v[0], e1), lsdem_sub3(v[2], v[0], e2);
      lsdem_cross3(e1, e2, n); /* counter-clockwise from above: z > 0 */
    }
  }
}

double lsdem_heights_eval(const lsdem_band *b, const double p_in[3], double grad[3])
{
  if (p_in[0] != p_in[0] || p_in[1] != p_in[1] || p_in[2] != p_in[2]) {
    grad[0] = grad[1] = 0.0, grad[2] = 1.0;
    return p_in[0] + p_in[1] + p_in[2]; /* a NaN position stays NaN */
  }
  /* the outside rule: beyond the box, the value at the nearest point of its columns */
  const double xmax = b->origin[0] + b->h * (b->n[0] - 1);
  const double ymax = b->origin[1] + b->h * (b->n[1] - 1);
  const double p[3] = {mind(maxd(p_in[0], b->origin[0]), xmax),
                       mind(maxd(p_in[1], b->origin[1]), ymax), p_in[2]};
  const double side = p[2] >= surface_height(b, p[0], p[1]) ? 1.0 : -1.0;
  const double bound = tile_bound(b, p);
  grad[0] = grad[1] = 0.0, grad[2] = 1.0;
  if (bound >= b->width) return side * bound;
  /* p's own cell first: its nearest triangle bounds the search to r = min(width, its
   * distance); every nearer triangle has a point within r of p across, in the cells
   * overlapping that square */
  double best2 = b->width * b->width, q[3], n[3];
  const int nx = b->n[0], ny = b->n[1];
  double f;
  const int ic = cell_along((p[0] - b->origin[0]) / b->h, nx, &f);
  const int jc = cell_along((p[1] - b->origin[1]) / b->h, ny, &f);
  visit_cell(b, ic, jc, p, &best2, q, n);
  const double r = sqrt(best2);
  const int i0 = cell_along((p[0] - r - b->origin[0]) / b->h, nx, &f);
  const int i1 = cell_along((p[0] + r - b->origin[0]) / b->h, nx, &f);
  const int j0 = cell_along((p[1] - r - b->origin[1]) / b->h, ny, &f);
  const int j1 = cell_along((p[1] + r - b->origin[1]) / b->h, ny, &f);
  for (int j = j0; j <= j1; j++) {
    const double y0 = b->origin[1] + b->h * j;
    const double dy = maxd(0.0, maxd(y0 - p[1], p[1] - (y0 + b->h)));
    if (dy * dy >= best2) continue; /* the whole row is no nearer */
    for (int i = i0; i <= i1; i++)
      if (i != ic || j != jc) visit_cell(b, i, j, p, &best2, q, n);
  }
  if (best2 >= b->width * b->width) return side * b->width;
  const double d = sqrt(best2);
  if (d > 1e-12 * b->h) {
    for (int a = 0; a < 3; a++) grad[a] = side * (p[a] - q[a]) / d;
  } else {
    const double s = 1.0 / sqrt(lsdem_dot3(n, n));
    for (int a = 0; a < 3; a++) grad[a] = n[a] * s;
  }
  return side * d;
}

lsdem_status lsdem_heights_tiles(const lsdem_band *b, float **range, int nt[2],
                                 lsdem_error *err)
{
  for (int a = 0; a < 2; a++) nt[a] = (b->n[a] - 2) / TILE + 1;
  const size_t ntiles = (size_t)nt[0] * (size_t)nt[1];
  float *r = (float *)malloc(2 * ntiles * sizeof *r);
  if (!r) return lsdem_fail(err, LSDEM_ERR_NOMEM, "band: cannot allocate the height ranges "
                            "of %zu tiles", ntiles);
  for (size_t t = 0; t < ntiles; t++) r[2 * t] = INFINITY, r[2 * t + 1] = -INFINITY;
  /* height (i,j) belongs to the tiles of every cell it is a corner of */
  for (int j = 0; j < b->n[1]; j++)
    for (int i = 0; i < b->n[0]; i++) {
      const float z = b->heights[(size_t)i + (size_t)b->n[0] * (size_t)j];
      for (int tj = (j > 0 ? j - 1 : 0) / TILE; tj <= (j < b->n[1] - 1 ? j : j - 1) / TILE; tj++)
        for (int ti = (i > 0 ? i - 1 : 0) / TILE; ti <= (i < b->n[0] - 1 ? i : i - 1) / TILE;
             ti++) {
          float *rr = &r[2 * ((size_t)ti + (size_t)nt[0] * (size_t)tj)];
          rr[0] = fminf(rr[0], z), rr[1] = fmaxf(rr[1], z);
        }
    }
  *range = r;
  return LSDEM_OK;
}

lsdem_status lsdem_heights_check(const lsdem_band *b, lsdem_error *err)
{
  if (b->n[0] < 2 || b->n[1] < 2 || b->n[2] != 1 || b->nbricks != 0 || b->ntris != 0)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: heights of %d x %d x %d columns with %lld "
                      "bricks and %lld triangles (expected at least 2 x 2 x 1, none of either)",
                      b->n[0], b->n[1], b->n[2], (long long)b->nbricks, (long long)b->ntris);
  const size_t count = (size_t)b->n[0] * (size_t)b->n[1];
  for (size_t k = 0; k < count; k++)
    if (!isfinite(b->heights[k]))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: height %zu (column %zu, %zu) is not "
                        "finite", k, k % (size_t)b->n[0], k / (size_t)b->n[0]);
  return LSDEM_OK;
}
