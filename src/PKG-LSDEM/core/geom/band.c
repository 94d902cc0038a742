/* band.c -- narrow-band level sets (lsdem_geom.h): lookup by brick, checks. Made by
 * prep/band_build.c, stored by prep/band_write.c, mapped by bandfile.c.
 *
 * Grid coordinates as for lsdem_grid: u = (p - origin) / h, sample (i,j,k) at u = (i,j,k).
 * Cell (i,j,k) lies in brick (i, j, k) >> 3 at local (i, j, k) & 7; its 8 samples are
 * the brick's samples (li..li+1, lj..lj+1, lk..lk+1) of 0..8. */
#include "lsdem_geom.h"
#include "closest_triangle.h"
#include "trilinear.h"

#include <math.h>
#include <stdlib.h>

enum { SIDE = LSDEM_BAND_BRICK_SIDE, PLANE = SIDE * SIDE, MASK = LSDEM_BAND_BRICK - 1 };

/* u clamped to the box [0, n-1]^3 (the outside rule: the boundary's values); the cell
 * index clamped to n-2 so the upper face uses the last cell at fraction 1. */
static inline void cell_of(const lsdem_band *b, const double u[3], int c[3], double f[3])
{
  for (int a = 0; a < 3; a++) {
    const double top = (double)(b->n[a] - 1);
    const double ua = u[a] < 0.0 ? 0.0 : (u[a] > top ? top : u[a]);
    int i = (int)ua;
    i = i > b->n[a] - 2 ? b->n[a] - 2 : i;
    c[a] = i;
    f[a] = ua - i;
  }
}

/* Exact mode: the signed distance to the closest triangle of brick's list and its
 * direction (the list holds every triangle nearer than width to a point of the brick). */
static double exact_value(const lsdem_band *b, int32_t brick, const double p[3], double grad[3])
{
  double best = HUGE_VAL, value = b->width;
  for (int64_t e = b->brick_tri_start[brick]; e < b->brick_tri_start[brick + 1]; e++) {
    /* a triangle whose bounding sphere is no nearer than the best so far cannot be nearer
     * (ties keep the earlier: the same triangle as without pruning) */
    const double *sph = b->exact->sphere + 4 * (int64_t)b->brick_tris[e];
    const double dc[3] = {p[0] - sph[0], p[1] - sph[1], p[2] - sph[2]};
    if (best < HUGE_VAL && sqrt(lsdem_dot3(dc, dc)) - sph[3] >= best) continue;
    double g[3];
    const double d = lsdem_signed_distance_to_triangle(b->verts, b->tris, b->exact, p,
                                                       b->brick_tris[e], g);
    if (fabs(d) < best) best = fabs(d), value = d, grad[0] = g[0], grad[1] = g[1], grad[2] = g[2];
  }
  if (best == HUGE_VAL) grad[0] = 1.0, grad[1] = grad[2] = 0.0;
  return value;
}

static inline double band_eval(const lsdem_band *b, double inv_h, const double p[3],
                               double grad[3])
{
  double u[3], f[3], du[3];
  int c[3];
  for (int a = 0; a < 3; a++) u[a] = (p[a] - b->origin[a]) * inv_h;
  if (u[0] != u[0] || u[1] != u[1] || u[2] != u[2]) { /* a NaN position stays NaN */
    grad[0] = 1.0, grad[1] = grad[2] = 0.0;
    return u[0] + u[1] + u[2];
  }
  cell_of(b, u, c, f);
  const int64_t slot = (int64_t)(c[0] >> LSDEM_BAND_BRICK_LOG2) +
                       (int64_t)b->nb[0] * ((int64_t)(c[1] >> LSDEM_BAND_BRICK_LOG2) +
                       (int64_t)b->nb[1] * (int64_t)(c[2] >> LSDEM_BAND_BRICK_LOG2));
  const int32_t brick = b->index[slot];
  if (brick < 0) { /* background: constant over the slot */
    grad[0] = 1.0, grad[1] = grad[2] = 0.0;
    const double gap = b->far ? (double)(b->far[slot] - 1) * LSDEM_BAND_BRICK * b->h : 0.0;
    const double v = gap > b->width ? gap : b->width;
    return brick == LSDEM_BAND_OUTSIDE ? v : -v;
  }
  const float *s = b->phi + (size_t)brick * LSDEM_BAND_BRICK_SAMPLES +
                   (c[0] & MASK) + SIDE * ((c[1] & MASK) + SIDE * (c[2] & MASK));
  float v[8];
  load_cell_strided(s, SIDE, PLANE, v);
  const double phi = trilinear_cell(v, f, du);
  if (b->exact && phi > -b->width && phi < b->width) return exact_value(b, brick, p, grad);
  unit_gradient(du, grad);
  return phi;
}

double lsdem_band_eval(const lsdem_band *b, const double p[3], double grad[3])
{
  if (b->heights) return lsdem_heights_eval(b, p, grad);
  return band_eval(b, 1.0 / b->h, p, grad);
}

void lsdem_band_eval_many(const lsdem_band *b, int n, const double *p, double *phi,
                          double *grad)
{
  const double inv_h = 1.0 / b->h;
  if (b->heights)
    for (int m = 0; m < n; m++) phi[m] = lsdem_heights_eval(b, &p[3 * m], &grad[3 * m]);
  else
    for (int m = 0; m < n; m++) phi[m] = band_eval(b, inv_h, &p[3 * m], &grad[3 * m]);
}

int lsdem_band_tunnelled(const lsdem_band *b, double depth)
{
  return depth >= b->width * (1.0 - 1e-6);
}

size_t lsdem_band_bytes(const lsdem_band *b)
{
  if (b->heights)
    return (size_t)b->n[0] * (size_t)b->n[1] * sizeof(float) +
           2 * (size_t)b->nt[0] * (size_t)b->nt[1] * sizeof(float);
  const size_t slots = (size_t)b->nb[0] * (size_t)b->nb[1] * (size_t)b->nb[2];
  const size_t lists = b->ntris ? (size_t)b->brick_tri_start[b->nbricks] + 3 * (size_t)b->ntris : 0;
  return slots * (sizeof(int32_t) + (b->far ? sizeof(uint16_t) : 0)) +
         (size_t)b->nbricks * LSDEM_BAND_BRICK_SAMPLES * sizeof(float) +
         (size_t)b->nverts * 3 * sizeof(double) + (size_t)b->ntris * 3 * sizeof(int32_t) +
         (b->ntris ? ((size_t)b->nbricks + 1) * sizeof(int64_t) : 0) + lists * sizeof(int32_t);
}

/* One raster pass of the chessboard distance transform: each slot takes 1 + the least
 * of its 13 neighbours already visited in this direction (dir = +1 forward, -1 back). */
static void far_pass(const int nb[3], uint16_t *d, int dir)
{
  const int64_t sy = nb[0], sz = (int64_t)nb[0] * nb[1];
  for (int kk = 0; kk < nb[2]; kk++)
    for (int jj = 0; jj < nb[1]; jj++)
      for (int ii = 0; ii < nb[0]; ii++) {
        const int i = dir > 0 ? ii : nb[0] - 1 - ii, j = dir > 0 ? jj : nb[1] - 1 - jj;
        const int k = dir > 0 ? kk : nb[2] - 1 - kk;
        uint16_t *here = &d[i + sy * j + sz * k];
        unsigned best = *here;
        /* the neighbours before (i,j,k) in this raster order: (dk < 0) or (dk = 0 and
         * dj < 0) or (dk = dj = 0 and di < 0), with d = -dir */
        for (int dk = -1; dk <= 0; dk++)
          for (int dj = -1; dj <= 1; dj++)
            for (int di = -1; di <= 1; di++) {
              if (dk == 0 && (dj > 0 || (dj == 0 && di >= 0))) continue;
              const int ni = i + dir * di, nj = j + dir * dj, nk = k + dir * dk;
              if (ni < 0 || nj < 0 || nk < 0 || ni >= nb[0] || nj >= nb[1] || nk >= nb[2])
                continue;
              const unsigned v = d[ni + sy * nj + sz * nk] + 1u;
              if (v < best) best = v;
            }
        *here = (uint16_t)best;
      }
}

lsdem_status lsdem_band_far(const lsdem_band *b, uint16_t **far, lsdem_error *err)
{
  const size_t slots = (size_t)b->nb[0] * (size_t)b->nb[1] * (size_t)b->nb[2];
  uint16_t *d = (uint16_t *)malloc(slots * sizeof *d);
  if (!d) return lsdem_fail(err, LSDEM_ERR_NOMEM, "band: cannot allocate its coarse level "
                            "(%zu slots)", slots);
  for (size_t s = 0; s < slots; s++) d[s] = b->index[s] >= 0 ? 0 : UINT16_MAX - 1;
  far_pass(b->nb, d, 1);
  far_pass(b->nb, d, -1);
  *far = d;
  return LSDEM_OK;
}

/* The surface's arrays (when kept): finite vertices, triangles naming vertices, brick
 * lists increasing from 0 and naming triangles. */
static lsdem_status check_surface(const lsdem_band *b, lsdem_error *err)
{
  if (b->ntris == 0) return LSDEM_OK;
  if (b->ntris < 0 || b->nverts < 3 || !b->verts || !b->tris || !b->brick_tri_start ||
      !b->brick_tris)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: surface of %lld triangles without its "
                      "arrays", (long long)b->ntris);
  for (int64_t k = 0; k < 3 * b->nverts; k++)
    if (!isfinite(b->verts[k]))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: surface vertex %lld is not finite",
                        (long long)(k / 3));
  for (int64_t k = 0; k < 3 * b->ntris; k++)
    if (b->tris[k] < 0 || b->tris[k] >= b->nverts)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: triangle %lld names vertex %d of %lld",
                        (long long)(k / 3), (int)b->tris[k], (long long)b->nverts);
  for (int64_t k = 0; b->nbr && k < 3 * b->ntris; k++)
    if (b->nbr[k] < -1 || b->nbr[k] >= b->ntris)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: triangle %lld's neighbour is %d of %lld",
                        (long long)(k / 3), (int)b->nbr[k], (long long)b->ntris);
  if (b->brick_tri_start[0] != 0)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: brick lists do not start at 0");
  for (int64_t k = 0; k < b->nbricks; k++) {
    const int64_t s0 = b->brick_tri_start[k], s1 = b->brick_tri_start[k + 1];
    if (s1 < s0)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: brick %lld's triangle list ends before "
                        "it starts", (long long)k);
    for (int64_t e = s0; e < s1; e++)
      if (b->brick_tris[e] < 0 || b->brick_tris[e] >= b->ntris)
        return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: brick %lld lists triangle %d of %lld",
                          (long long)k, (int)b->brick_tris[e], (long long)b->ntris);
  }
  return LSDEM_OK;
}

int64_t lsdem_band_closest_triangle(const lsdem_band *b, const double p[3], double *d2)
{
  *d2 = HUGE_VAL;
  if (b->ntris == 0) return -1;
  double u[3], f[3];
  int c[3];
  for (int a = 0; a < 3; a++) u[a] = (p[a] - b->origin[a]) / b->h;
  if (u[0] != u[0] || u[1] != u[1] || u[2] != u[2]) return -1;
  cell_of(b, u, c, f);
  const int64_t slot = (int64_t)(c[0] >> LSDEM_BAND_BRICK_LOG2) +
                       (int64_t)b->nb[0] * ((int64_t)(c[1] >> LSDEM_BAND_BRICK_LOG2) +
                       (int64_t)b->nb[1] * (int64_t)(c[2] >> LSDEM_BAND_BRICK_LOG2));
  const int32_t brick = b->index[slot];
  if (brick < 0) return -1;
  int64_t best = -1;
  for (int64_t e = b->brick_tri_start[brick]; e < b->brick_tri_start[brick + 1]; e++) {
    const int32_t t = b->brick_tris[e];
    const int32_t *v = &b->tris[3 * (int64_t)t];
    double q[3], d[3];
    int feat;
    lsdem_closest_on_triangle(p, &b->verts[3 * (int64_t)v[0]], &b->verts[3 * (int64_t)v[1]],
                              &b->verts[3 * (int64_t)v[2]], q, &feat);
    lsdem_sub3(p, q, d);
    const double dd = lsdem_dot3(d, d);
    if (dd < *d2) *d2 = dd, best = t;
  }
  return best;
}

lsdem_status lsdem_band_check(const lsdem_band *b, lsdem_error *err)
{
  if (!(b->h > 0.0) || !isfinite(b->h))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: spacing %g is not > 0", b->h);
  if (!(b->width > 0.0) || !(b->width <= LSDEM_BAND_MAX_WIDTH_CELLS * b->h))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: width %g is not in (0, %g h] (h = %g)",
                      b->width, LSDEM_BAND_MAX_WIDTH_CELLS, b->h);
  for (int a = 0; a < 3; a++)
    if (!isfinite(b->origin[a]))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: origin is not finite");
  if (b->heights) return lsdem_heights_check(b, err);
  for (int a = 0; a < 3; a++) {
    if (b->n[a] < 2)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: %d samples along axis %d (at least 2)",
                        b->n[a], a);
    if (b->nb[a] != (b->n[a] - 2) / LSDEM_BAND_BRICK + 1)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: %d bricks along axis %d for %d samples "
                        "(expected %d)", b->nb[a], a, b->n[a], (b->n[a] - 2) / LSDEM_BAND_BRICK + 1);
  }
  const int64_t slots = (int64_t)b->nb[0] * b->nb[1] * b->nb[2];
  for (int64_t s = 0; s < slots; s++)
    if (b->index[s] < LSDEM_BAND_INSIDE || b->index[s] >= b->nbricks)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: index entry %lld is %d, not a brick "
                        "(0..%lld) nor background", (long long)s, (int)b->index[s],
                        (long long)b->nbricks - 1);
  const float w = (float)b->width;
  const size_t total = (size_t)b->nbricks * LSDEM_BAND_BRICK_SAMPLES;
  for (size_t q = 0; q < total; q++)
    if (!(b->phi[q] >= -w && b->phi[q] <= w))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "band: sample %zu of brick %zu is %g, outside "
                        "[-width, width] = [%g, %g]", q % LSDEM_BAND_BRICK_SAMPLES,
                        q / LSDEM_BAND_BRICK_SAMPLES, (double)b->phi[q], -b->width, b->width);
  return check_surface(b, err);
}
