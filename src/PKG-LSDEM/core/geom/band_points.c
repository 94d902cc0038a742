/* band_points.c -- a band's sharp convex edges as points (lsdem_geom.h,
 * lsdem_band_points), numbered brick by brick, made once when a wall is set up. */
#include "lsdem_geom.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

void lsdem_band_slot_range(const lsdem_band *b, const double c[3], double r, int lo[3],
                           int hi[3])
{
  for (int a = 0; a < 3; a++) {
    const double top = (double)(b->n[a] - 2);
    for (int side = 0; side < 2; side++) {
      double u = (c[a] + (side ? r : -r) - b->origin[a]) / b->h;
      u = u < 0.0 ? 0.0 : (u > top ? top : u); /* also maps a NaN to 0 */
      const int slot = (int)u >> LSDEM_BAND_BRICK_LOG2;
      if (side) hi[a] = slot;
      else lo[a] = slot;
    }
  }
}

static void tri_unit_normal(const lsdem_band *b, int64_t t, double n[3])
{
  const double *p0 = &b->verts[3 * b->tris[3 * t]], *p1 = &b->verts[3 * b->tris[3 * t + 1]];
  const double *p2 = &b->verts[3 * b->tris[3 * t + 2]];
  double e1[3], e2[3];
  lsdem_sub3(p1, p0, e1);
  lsdem_sub3(p2, p0, e2);
  lsdem_cross3(e1, e2, n);
  const double len = sqrt(lsdem_dot3(n, n));
  for (int a = 0; a < 3; a++) n[a] = len > 0.0 ? n[a] / len : 0.0;
}

/* Edge e of triangle t (vertices tris[3t+e], tris[3t+(e+1)%3]) is sharp, taken from the
 * lower-numbered of its two triangles (an open edge: never). */
static int sharp_edge(const lsdem_band *b, int64_t t, int e)
{
  const int64_t o = b->nbr[3 * t + e];
  if (o < 0 || o < t) return 0;
  const int32_t va = b->tris[3 * t + e], vb = b->tris[3 * t + (e + 1) % 3];
  int32_t far = b->tris[3 * o];
  for (int k = 1; k < 3 && (far == va || far == vb); k++) far = b->tris[3 * o + k];
  double nt[3], no[3], d[3];
  tri_unit_normal(b, t, nt);
  tri_unit_normal(b, o, no);
  lsdem_sub3(&b->verts[3 * far], &b->verts[3 * va], d);
  const double convex = lsdem_dot3(nt, d) < 0.0;
  return convex && lsdem_dot3(nt, no) <= cos(LSDEM_BAND_SHARP_DEG * M_PI / 180.0);
}

/* Pieces of edge (va, vb) at most spacing long. */
static int64_t edge_pieces(const lsdem_band *b, int32_t va, int32_t vb, double spacing)
{
  double d[3];
  lsdem_sub3(&b->verts[3 * vb], &b->verts[3 * va], d);
  const double pieces = ceil(sqrt(lsdem_dot3(d, d)) / spacing);
  return pieces < 1.0 ? 1 : (int64_t)pieces;
}

/* The stored brick holding point x, or -1. */
static int32_t brick_of(const lsdem_band *b, const double x[3])
{
  int lo[3], hi[3];
  lsdem_band_slot_range(b, x, 0.0, lo, hi);
  return b->index[lo[0] + (int64_t)b->nb[0] * (lo[1] + (int64_t)b->nb[1] * lo[2])];
}

/* The points of the sharp edges in generation order (pass x == NULL: count only): the
 * edges' vertices the first time they are met (seen[] marks them), then each edge's
 * interior samples. Returns the count. */
static int64_t edge_points(const lsdem_band *b, double spacing, uint8_t *seen, double *x)
{
  int64_t n = 0;
  for (int64_t t = 0; t < b->ntris; t++)
    for (int e = 0; e < 3; e++) {
      if (!sharp_edge(b, t, e)) continue;
      const int32_t v[2] = {b->tris[3 * t + e], b->tris[3 * t + (e + 1) % 3]};
      for (int k = 0; k < 2; k++) {
        if (seen[v[k]]) continue;
        seen[v[k]] = 1;
        if (x) memcpy(&x[3 * n], &b->verts[3 * v[k]], 3 * sizeof(double));
        n++;
      }
      const int64_t pieces = edge_pieces(b, v[0], v[1], spacing);
      for (int64_t s = 1; s < pieces; s++, n++) {
        const double f = (double)s / (double)pieces;
        for (int a = 0; x && a < 3; a++)
          x[3 * n + a] = (1.0 - f) * b->verts[3 * v[0] + a] + f * b->verts[3 * v[1] + a];
      }
    }
  return n;
}

static int64_t count_sharp_edges(const lsdem_band *b)
{
  int64_t n = 0;
  for (int64_t t = 0; t < b->ntris; t++)
    for (int e = 0; e < 3; e++) n += sharp_edge(b, t, e);
  return n;
}

/* Points in generation order (tmp) into p, grouped by brick (counting sort, stable). */
static lsdem_status sort_by_brick(const lsdem_band *b, const double *tmp, int64_t n,
                                  lsdem_band_points *p, lsdem_error *err)
{
  int32_t *brick = malloc((size_t)n * sizeof(int32_t) + 1);
  p->brick_start = calloc((size_t)b->nbricks + 2, sizeof(int64_t));
  p->x = malloc((size_t)n * 3 * sizeof(double) + 1);
  if (!brick || !p->brick_start || !p->x) {
    free(brick);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "band points: cannot allocate %lld points",
                      (long long)n);
  }
  for (int64_t k = 0; k < n; k++) {
    brick[k] = brick_of(b, &tmp[3 * k]);
    if (brick[k] < 0) {
      const double *x = &tmp[3 * k];
      free(brick);
      return lsdem_fail(err, LSDEM_ERR_ARG, "band points: the surface point (%g, %g, %g) lies "
                        "in a brick the band does not store (a band narrower than its cells)",
                        x[0], x[1], x[2]);
    }
    p->brick_start[brick[k] + 2]++;
  }
  for (int64_t k = 2; k <= b->nbricks + 1; k++) p->brick_start[k] += p->brick_start[k - 1];
  /* brick_start[k + 1] is now where brick k's points go; filling moves it to its end */
  for (int64_t k = 0; k < n; k++)
    memcpy(&p->x[3 * p->brick_start[brick[k] + 1]++], &tmp[3 * k], 3 * sizeof(double));
  free(brick);
  return LSDEM_OK;
}

lsdem_status lsdem_band_points_make(const lsdem_band *b, double spacing, lsdem_band_points *p,
                                    lsdem_error *err)
{
  memset(p, 0, sizeof *p);
  if (b->heights || b->ntris == 0 || !b->nbr)
    return lsdem_fail(err, LSDEM_ERR_ARG, "band points: the band keeps no surface (a terrain "
                      "kept as heights, or a file without its triangles)");
  if (!(spacing > 0.0))
    return lsdem_fail(err, LSDEM_ERR_ARG, "band points: spacing %g is not > 0", spacing);
  uint8_t *seen = calloc((size_t)b->nverts + 1, 1);
  if (!seen) return lsdem_fail(err, LSDEM_ERR_NOMEM, "band points: no memory");
  const int64_t n = edge_points(b, spacing, seen, NULL);
  double *tmp = n <= INT32_MAX ? malloc((size_t)n * 3 * sizeof(double) + 1) : NULL;
  lsdem_status st = LSDEM_OK;
  if (n > INT32_MAX) st = lsdem_fail(err, LSDEM_ERR_ARG, "band points: %lld points (numbered "
                                     "as 32-bit nodes); a coarser spacing", (long long)n);
  else if (!tmp)
    st = lsdem_fail(err, LSDEM_ERR_NOMEM, "band points: no memory for %lld", (long long)n);
  if (st == LSDEM_OK) {
    memset(seen, 0, (size_t)b->nverts + 1);
    edge_points(b, spacing, seen, tmp);
    st = sort_by_brick(b, tmp, n, p, err);
  }
  free(tmp);
  free(seen);
  p->n = n;
  p->nedges = count_sharp_edges(b);
  if (st != LSDEM_OK) lsdem_band_points_free(p);
  return st;
}

void lsdem_band_points_free(lsdem_band_points *p)
{
  free(p->x);
  free(p->brick_start);
  memset(p, 0, sizeof *p);
}

int64_t lsdem_band_points_within(const lsdem_band *b, const lsdem_band_points *p, double r)
{
  /* a ball of radius r reaches at most k slots along an axis; any such window of slots
   * that holds a point lies within k - 1 slots of that point's slot */
  const int k = (int)(2.0 * r / (LSDEM_BAND_BRICK * b->h)) + 2;
  int64_t most = 0;
  for (int64_t s = 0; s < (int64_t)b->nb[0] * b->nb[1] * b->nb[2]; s++) {
    const int32_t brick = b->index[s];
    if (brick < 0 || p->brick_start[brick] == p->brick_start[brick + 1]) continue;
    const int c[3] = {(int)(s % b->nb[0]), (int)(s / b->nb[0] % b->nb[1]),
                      (int)(s / b->nb[0] / b->nb[1])};
    int64_t sum = 0;
    for (int z = c[2] - k + 1; z <= c[2] + k - 1; z++)
      for (int y = c[1] - k + 1; y <= c[1] + k - 1; y++)
        for (int x = c[0] - k + 1; x <= c[0] + k - 1; x++) {
          if (x < 0 || y < 0 || z < 0 || x >= b->nb[0] || y >= b->nb[1] || z >= b->nb[2])
            continue;
          const int32_t o = b->index[x + (int64_t)b->nb[0] * (y + (int64_t)b->nb[1] * z)];
          if (o >= 0) sum += p->brick_start[o + 1] - p->brick_start[o];
        }
    most = sum > most ? sum : most;
  }
  return most;
}
