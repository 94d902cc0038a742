/* band_build.c -- the narrow band of a wall (lsdem_band, lsdem_geom.h) from a triangle
 * mesh: a closed mesh (its inside solid) or a terrain surface (solid below).
 *
 * Layout: the mesh's bounding box grown by width + h on every side (a terrain's: only
 * below and above; across, its xy extent), spacing h, cut into bricks of LSDEM_BAND_BRICK
 * cells. A brick is stored when the bounding box of some
 * triangle grown by width touches it (conservative: every sample nearer than width to
 * the surface lies in a stored brick).
 *
 * Distances: each triangle visits the samples within width of its bounding box and keeps,
 * per sample, the least squared distance (the closest triangle: Ericson's closest point,
 * mesh_distance.h). A sample whose least distance is below width has met its true closest
 * triangle: it is "reached", its distance is exact. While building, the stored bricks hold
 * their own 8^3 samples (the "owned" samples: local 0..7 per axis); the 9th layer of a
 * brick, shared with its neighbour, is copied from the neighbour's owned sample at the end.
 *
 * Signs. Terrain: above (+) or below (-) the triangulated surface at the sample's (x, y),
 * looked up in a 2-D bucket grid of the triangles; a reached sample outside the terrain's
 * xy extent or over a hole takes the pseudonormal sign of its closest feature, an
 * unreached one the height at its (x, y) clamped to the extent (+ over a hole). A brick
 * that no triangle touches is background with the sign its 729 samples share; one whose
 * samples differ (beside the terrain's edge, or straddling a hole's border) is stored.
 * Closed mesh: a reached sample by the pseudonormal of its closest feature (exact: it is
 * the closest); the rest by flood fill over the samples, where a background brick stands
 * for all its samples (no surface within width of its box, so one sign). The fill is
 * sound because width >= h: along a grid edge (length h) from a reached sample (distance
 * d > 0) or an unreached one (distance >= width) to an unreached one, the surface cannot
 * pass, so the sign carries over. Seeds: the reached samples and everything outside the
 * mesh's bounding box (outside the solid: + for an outward-oriented mesh, - for an
 * inward-oriented one, whose solid is its outside). The fill runs brick by brick: inside a
 * stored brick a local search (a stack of 512), across bricks a work list of brick slots,
 * re-queued when a neighbour gains signs. Its memory: 1 sign byte per owned sample plus 5
 * bytes per brick slot (queue and flag) -- nothing of the size of the dense grid.
 *
 * Memory while building: per owned sample a double (least squared distance, then the
 * value), an int32 (closest triangle) and, for a closed mesh, a sign byte: 12 or 13 x 512
 * bytes per stored brick, then the result's 729 floats per brick and an int32 per slot;
 * besides, the mesh's pseudonormals (60 bytes a triangle while they are made). */
#include "lsdem_prep.h"
#include "mesh_distance.h"
#include "../geom/bandfile_format.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { BRICK = LSDEM_BAND_BRICK, SIDE = LSDEM_BAND_BRICK_SIDE, OWN = BRICK * BRICK * BRICK };
enum { BG_UNKNOWN = -3 }; /* a background slot whose sign the fill has not found yet */

/* Sign codes of owned samples (closed meshes): unknown, negative, positive, and on the
 * surface (distance 0: known, but carries no sign to its neighbours). */
enum { S_UNKNOWN = 0, S_NEG = -1, S_POS = 1, S_ZERO = 2 };

/* ------------------------------------------------------ terrain height lookup ---- */

/* Triangles bucketed by their xy bounding boxes on a uniform 2-D grid (CSR lists). */
typedef struct {
  double lo[2], hi[2], cs; /* the terrain's xy extent, bucket size */
  int n[2];
  int *start, *items;
} terrain_grid;

static void terrain_grid_free(terrain_grid *g)
{
  free(g->start), free(g->items);
  g->start = g->items = NULL;
}

static int bucket_of(const terrain_grid *g, double x, int a)
{
  const double c = floor((x - g->lo[a]) / g->cs);
  return c < 0.0 ? 0 : c >= g->n[a] ? g->n[a] - 1 : (int)c;
}

/* Bucket size: the side of a square holding two triangles on average (a height map's
 * cell), at most 8192 buckets per axis. */
static lsdem_status terrain_grid_build(const lsdem_mesh *m, const double lo[3],
                                       const double hi[3], terrain_grid *g, lsdem_error *err)
{
  memset(g, 0, sizeof *g);
  const double ex = hi[0] - lo[0], ey = hi[1] - lo[1], span = fmax(ex, ey);
  g->cs = fmax(sqrt(2.0 * fmax(ex, 1e-9 * span) * fmax(ey, 1e-9 * span) / m->ntris),
               span / 8192.0);
  if (!(g->cs > 0.0) || !isfinite(g->cs)) g->cs = 1.0;
  size_t nbuckets = 1;
  for (int a = 0; a < 2; a++) {
    g->lo[a] = lo[a], g->hi[a] = hi[a];
    g->n[a] = (int)floor((hi[a] - lo[a]) / g->cs) + 1;
    nbuckets *= (size_t)g->n[a];
  }
  g->start = calloc(nbuckets + 1, sizeof(int));
  if (!g->start) return lsdem_fail(err, LSDEM_ERR_NOMEM, "band: cannot allocate the terrain grid");
  for (int pass = 0; pass < 2; pass++) { /* count, then fill (counting sort) */
    for (int t = 0; t < m->ntris; t++) {
      int c0[2], c1[2];
      for (int a = 0; a < 2; a++) {
        const double x0 = mesh_vert(m, t, 0)[a], x1 = mesh_vert(m, t, 1)[a];
        const double x2 = mesh_vert(m, t, 2)[a];
        c0[a] = bucket_of(g, fmin(x0, fmin(x1, x2)), a);
        c1[a] = bucket_of(g, fmax(x0, fmax(x1, x2)), a);
      }
      for (int j = c0[1]; j <= c1[1]; j++)
        for (int i = c0[0]; i <= c1[0]; i++) {
          const size_t c = (size_t)j * g->n[0] + i;
          if (pass == 0) g->start[c + 1]++;
          else g->items[g->start[c]++] = t;
        }
    }
    if (pass == 0) {
      for (size_t c = 0; c < nbuckets; c++) g->start[c + 1] += g->start[c];
      g->items = malloc((size_t)g->start[nbuckets] * sizeof(int) + 1);
      if (!g->items) return lsdem_fail(err, LSDEM_ERR_NOMEM, "band: cannot allocate the "
                                       "terrain grid");
    }
  }
  for (size_t c = nbuckets; c > 0; c--) g->start[c] = g->start[c - 1]; /* undo the fill shift */
  g->start[0] = 0;
  return LSDEM_OK;
}

/* Height of the terrain at (x, y) clamped to its extent: the first triangle whose xy
 * projection holds the point (edges included, to a relative 1e-9), NaN over a hole.
 * *inside: (x, y) lies within the extent (not clamped). */
static double terrain_height(const lsdem_mesh *m, const terrain_grid *g, double x, double y,
                             int *inside)
{
  *inside = x >= g->lo[0] && x <= g->hi[0] && y >= g->lo[1] && y <= g->hi[1];
  x = fmin(fmax(x, g->lo[0]), g->hi[0]);
  y = fmin(fmax(y, g->lo[1]), g->hi[1]);
  const size_t c = (size_t)bucket_of(g, y, 1) * g->n[0] + bucket_of(g, x, 0);
  for (int k = g->start[c]; k < g->start[c + 1]; k++) {
    const int t = g->items[k];
    const double *a = mesh_vert(m, t, 0), *b = mesh_vert(m, t, 1), *d = mesh_vert(m, t, 2);
    const double ux = b[0] - a[0], uy = b[1] - a[1], vx = d[0] - a[0], vy = d[1] - a[1];
    const double px = x - a[0], py = y - a[1];
    const double det = ux * vy - uy * vx;
    if (det == 0.0) continue; /* a vertical triangle */
    const double s = (px * vy - py * vx) / det, r = (ux * py - uy * px) / det;
    const double tol = 1e-9;
    if (s >= -tol && r >= -tol && s + r <= 1.0 + tol)
      return a[2] + s * (b[2] - a[2]) + r * (d[2] - a[2]);
  }
  return NAN;
}

/* Sign of an unreached terrain sample at height z over a column of height H. */
static int terrain_sign(double z, double H) { return isnan(H) || z >= H ? S_POS : S_NEG; }

/* --------------------------------------------------------------- the builder ---- */

typedef struct {
  const lsdem_mesh *m;
  lsdem_band_source src;
  double h, w, origin[3];
  double lo[3], hi[3]; /* the mesh's bounding box */
  int n[3], nb[3];
  int64_t nslots, nbricks;
  int32_t *index;      /* per slot: brick number, LSDEM_BAND_OUTSIDE/INSIDE, BG_UNKNOWN */
  int32_t *slot_of;    /* per brick: its slot */
  double *best;        /* per owned sample: least squared distance, then the value */
  int32_t *tri;        /* per owned sample: the closest triangle (-1: none) */
  signed char *sign;   /* per owned sample (closed meshes): S_* */
  int outside;         /* sign outside the mesh's box: S_POS, or S_NEG for a closed mesh
                          whose faces point inwards (its solid is the outside) */
  int open;            /* a mesh with holes: signs near its open edges by winding number */
  mesh_pseudonormals pn;
  terrain_grid tg;
} builder;

/* Position of sample g along axis a: the format's origin + h g, computed one way only. */
static double sample_pos(const builder *B, int a, int64_t g)
{
  return B->origin[a] + B->h * (double)g;
}

static int64_t slot_index(const builder *B, int bx, int by, int bz)
{
  return bx + (int64_t)B->nb[0] * (by + (int64_t)B->nb[1] * bz);
}

static void slot_coords(const builder *B, int64_t s, int c[3])
{
  c[0] = (int)(s % B->nb[0]);
  c[1] = (int)(s / B->nb[0] % B->nb[1]);
  c[2] = (int)(s / ((int64_t)B->nb[0] * B->nb[1]));
}

static int local_index(int a, int b, int c) { return a + BRICK * (b + BRICK * c); }

static void builder_free(builder *B)
{
  free(B->index), free(B->slot_of), free(B->best), free(B->tri), free(B->sign);
  mesh_pseudonormals_free(&B->pn);
  terrain_grid_free(&B->tg);
}

/* Arguments, the mesh's box, and the grid and brick counts (named errors). */
static lsdem_status plan(builder *B, const lsdem_mesh *m, double h, double width,
                         lsdem_band_source src, lsdem_error *err)
{
  if (!m || !m->verts || !m->tris || m->ntris < 1 || m->nverts < 3)
    return lsdem_fail(err, LSDEM_ERR_ARG, "band: empty mesh (no triangles)");
  if (src != LSDEM_BAND_MESH && src != LSDEM_BAND_TERRAIN)
    return lsdem_fail(err, LSDEM_ERR_ARG, "band: source %d is neither a mesh (%d) nor a "
                      "terrain (%d)", (int)src, LSDEM_BAND_MESH, LSDEM_BAND_TERRAIN);
  if (!(h > 0.0) || !isfinite(h))
    return lsdem_fail(err, LSDEM_ERR_ARG, "band: spacing h = %g is not > 0", h);
  if (!(width >= h) || !isfinite(width))
    return lsdem_fail(err, LSDEM_ERR_ARG, "band: width %g is below the spacing h = %g (the "
                      "band needs width >= h)", width, h);
  if (width > LSDEM_BAND_MAX_WIDTH_CELLS * h)
    return lsdem_fail(err, LSDEM_ERR_ARG, "band: width %g is above %g h = %g", width,
                      LSDEM_BAND_MAX_WIDTH_CELLS, LSDEM_BAND_MAX_WIDTH_CELLS * h);
  for (int a = 0; a < 3; a++) B->lo[a] = HUGE_VAL, B->hi[a] = -HUGE_VAL;
  for (int v = 0; v < m->nverts; v++)
    for (int a = 0; a < 3; a++) {
      const double x = m->verts[3 * v + a];
      if (!isfinite(x))
        return lsdem_fail(err, LSDEM_ERR_ARG, "band: vertex %d is not finite", v);
    }
  for (int t = 0; t < m->ntris; t++)
    for (int c = 0; c < 3; c++) {
      const int v = m->tris[3 * t + c];
      if (v < 0 || v >= m->nverts)
        return lsdem_fail(err, LSDEM_ERR_ARG, "band: triangle %d has vertex %d, not one of "
                          "the %d", t, v, m->nverts);
      for (int a = 0; a < 3; a++) {
        B->lo[a] = fmin(B->lo[a], m->verts[3 * v + a]);
        B->hi[a] = fmax(B->hi[a], m->verts[3 * v + a]);
      }
    }
  B->m = m, B->src = src, B->h = h, B->w = width;
  B->nslots = 1;
  for (int a = 0; a < 3; a++) {
    /* a terrain's box ends at its xy extent, where its last sample columns still see the
     * surface above or below them: beyond, the lookup's outside rule repeats those columns
     * (the ground continues flat at its edge heights; lsdem-shape terrain pads the raster
     * with edge heights first, so that the columns near the border are flat too) */
    const int flush = src == LSDEM_BAND_TERRAIN && a < 2;
    const double margin = flush ? 0.0 : width + h;
    B->origin[a] = B->lo[a] - margin;
    const double span = (B->hi[a] - B->lo[a] + 2.0 * margin) / h;
    double cells = flush ? fmax(floor(span * (1.0 + 1e-12)), 1.0) : ceil(span * (1.0 - 1e-12));
    /* the last sample n - 1 must be a stored brick's own (local 0..7): a multiple of 8
     * would be the first sample of a brick beyond the grid, which gets no distance */
    if (flush && cells > 1.0 && fmod(cells, LSDEM_BAND_BRICK) == 0.0) cells -= 1.0;
    if (!(cells + 1.0 <= (double)(INT32_MAX - 2 * BRICK)))
      return lsdem_fail(err, LSDEM_ERR_NOMEM, "band: %.0f samples along axis %d (the box %g "
                        "wide at spacing %g): above 2^31; use a coarser spacing", cells + 1.0,
                        a, B->hi[a] - B->lo[a] + 2.0 * (width + h), h);
    B->n[a] = (int)cells + 1;
    B->nb[a] = band_bricks_for(B->n[a]);
    B->nslots *= B->nb[a];
    if (B->nslots > INT32_MAX)
      return lsdem_fail(err, LSDEM_ERR_NOMEM, "band: more than 2^31 - 1 brick slots (bricks "
                        "of %d cells at spacing %g over the box %g x %g x %g); use a coarser "
                        "spacing", BRICK, h, B->hi[0] - B->lo[0], B->hi[1] - B->lo[1],
                        B->hi[2] - B->lo[2]);
  }
  B->outside = S_POS;
  if (src == LSDEM_BAND_MESH) {
    const double v = lsdem_mesh_volume(m);
    if (!(v != 0.0) || !isfinite(v))
      return lsdem_fail(err, LSDEM_ERR_ARG, "band: the closed mesh encloses no volume (%g)", v);
    B->outside = v > 0.0 ? S_POS : S_NEG;
  }
  return LSDEM_OK;
}

/* Bricks slot range touched by [x0, x1] along axis a (clipped to the grid). */
static void brick_range(const builder *B, int a, double x0, double x1, int *b0, int *b1)
{
  const double s = BRICK * B->h;
  *b0 = (int)fmax(floor((x0 - B->origin[a]) / s), 0.0);
  *b1 = (int)fmin(floor((x1 - B->origin[a]) / s), B->nb[a] - 1.0);
}

/* Bounding box of triangle t grown by g. */
static void grown_box(const lsdem_mesh *m, int t, double g, double lo[3], double hi[3])
{
  for (int a = 0; a < 3; a++) {
    const double x0 = mesh_vert(m, t, 0)[a], x1 = mesh_vert(m, t, 1)[a], x2 = mesh_vert(m, t, 2)[a];
    lo[a] = fmin(x0, fmin(x1, x2)) - g;
    hi[a] = fmax(x0, fmax(x1, x2)) + g;
  }
}

/* Mark (index 0) every slot some triangle's box grown by width (and a hair) touches. */
static void select_bricks(builder *B)
{
  for (int64_t s = 0; s < B->nslots; s++) B->index[s] = BG_UNKNOWN;
  const double g = B->w * (1.0 + 1e-9) + 1e-9 * B->h;
  for (int t = 0; t < B->m->ntris; t++) {
    double lo[3], hi[3];
    int b0[3], b1[3];
    grown_box(B->m, t, g, lo, hi);
    for (int a = 0; a < 3; a++) brick_range(B, a, lo[a], hi[a], &b0[a], &b1[a]);
    for (int bz = b0[2]; bz <= b1[2]; bz++)
      for (int by = b0[1]; by <= b1[1]; by++)
        for (int bx = b0[0]; bx <= b1[0]; bx++) B->index[slot_index(B, bx, by, bz)] = 0;
  }
}

/* The heights of a column of bricks' 9 x 9 sample columns (clamped to the extent), and
 * whether each lies within it. */
static void column_heights(const builder *B, int bx, int by, double H[SIDE * SIDE],
                           int inside[SIDE * SIDE])
{
  for (int b = 0; b < SIDE; b++)
    for (int a = 0; a < SIDE; a++)
      H[a + SIDE * b] = terrain_height(B->m, &B->tg, sample_pos(B, 0, (int64_t)BRICK * bx + a),
                                       sample_pos(B, 1, (int64_t)BRICK * by + b),
                                       &inside[a + SIDE * b]);
}

/* column_heights for the column of bricks (bx, by) when one of its slots is stored
 * (stored = 1) or still unmarked (0); returns 0, computing nothing, when none is. */
static int column_heights_for(const builder *B, int bx, int by, int stored,
                              double H[SIDE * SIDE], int inside[SIDE * SIDE])
{
  for (int bz = 0; bz < B->nb[2]; bz++) {
    const int32_t ix = B->index[slot_index(B, bx, by, bz)];
    if (stored ? ix >= 0 : ix == BG_UNKNOWN) {
      column_heights(B, bx, by, H, inside);
      return 1;
    }
  }
  return 0;
}

/* Terrain: an unmarked slot is background when its 729 samples share one sign (that
 * sign), else it is stored (index 0). */
static void terrain_backgrounds(builder *B)
{
  double H[SIDE * SIDE];
  int inside[SIDE * SIDE];
  for (int by = 0; by < B->nb[1]; by++)
    for (int bx = 0; bx < B->nb[0]; bx++) {
      if (!column_heights_for(B, bx, by, 0, H, inside)) continue;
      for (int bz = 0; bz < B->nb[2]; bz++) {
        int32_t *ix = &B->index[slot_index(B, bx, by, bz)];
        if (*ix != BG_UNKNOWN) continue;
        int pos = 0, neg = 0;
        for (int c = 0; c < SIDE; c++) {
          const double z = sample_pos(B, 2, (int64_t)BRICK * bz + c);
          for (int q = 0; q < SIDE * SIDE; q++) {
            if (terrain_sign(z, H[q]) == S_POS) pos++;
            else neg++;
          }
        }
        *ix = pos && neg ? 0 : pos ? LSDEM_BAND_OUTSIDE : LSDEM_BAND_INSIDE;
      }
    }
}

/* Number the stored slots (x fastest) and allocate the per-sample work. */
static lsdem_status number_bricks(builder *B, lsdem_error *err)
{
  B->nbricks = 0;
  for (int64_t s = 0; s < B->nslots; s++)
    if (B->index[s] >= 0) {
      if (B->nbricks == INT32_MAX)
        return lsdem_fail(err, LSDEM_ERR_NOMEM, "band: more than 2^31 - 1 stored bricks; use "
                          "a coarser spacing or a narrower band");
      B->index[s] = (int32_t)B->nbricks++;
    }
  const size_t owned = (size_t)B->nbricks * OWN;
  B->slot_of = malloc((size_t)B->nbricks * sizeof(int32_t) + 1);
  B->best = malloc(owned * sizeof(double) + 1);
  B->tri = malloc(owned * sizeof(int32_t) + 1);
  if (B->src == LSDEM_BAND_MESH) B->sign = calloc(owned + 1, 1);
  if (!B->slot_of || !B->best || !B->tri || (B->src == LSDEM_BAND_MESH && !B->sign))
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "band: cannot allocate the work for %lld bricks "
                      "(%.0f MB)", (long long)B->nbricks, owned * 13.0 / 1048576.0);
  for (int64_t s = 0; s < B->nslots; s++)
    if (B->index[s] >= 0) B->slot_of[B->index[s]] = (int32_t)s;
  for (size_t q = 0; q < owned; q++) B->best[q] = HUGE_VAL, B->tri[q] = -1;
  return LSDEM_OK;
}

/* Sample index range [i0, i1] within g of [x0, x1] along axis a (owned samples only). */
static void sample_range(const builder *B, int a, double x0, double x1, int *i0, int *i1)
{
  *i0 = (int)fmax(ceil((x0 - B->origin[a]) / B->h - 1e-9), 0.0);
  *i1 = (int)fmin(floor((x1 - B->origin[a]) / B->h + 1e-9), (double)BRICK * B->nb[a] - 1.0);
}

/* Each triangle visits the samples within width of its bounding box. The distance to
 * its plane bounds the distance to it from below: a sample already nearer to another
 * triangle than to the plane is skipped without the closest-point test. */
static void rasterise(builder *B)
{
  const lsdem_mesh *m = B->m;
  for (int t = 0; t < m->ntris; t++) {
    double lo[3], hi[3], n[3];
    int i0[3], i1[3];
    grown_box(m, t, B->w, lo, hi);
    for (int a = 0; a < 3; a++) sample_range(B, a, lo[a], hi[a], &i0[a], &i1[a]);
    mesh_tri_normal(m, t, n);
    const double len = sqrt(lsdem_dot3(n, n)), *v0 = mesh_vert(m, t, 0);
    for (int a = 0; a < 3; a++) n[a] = len > 0.0 ? n[a] / len : 0.0; /* 0: no bound */
    for (int k = i0[2]; k <= i1[2]; k++)
      for (int j = i0[1]; j <= i1[1]; j++) {
        const double p1 = sample_pos(B, 1, j), p2 = sample_pos(B, 2, k);
        const double plane12 = n[1] * (p1 - v0[1]) + n[2] * (p2 - v0[2]);
        for (int i = i0[0]; i <= i1[0]; i++) {
          const int32_t brick = B->index[slot_index(B, i >> 3, j >> 3, k >> 3)];
          if (brick < 0) continue; /* a hair beyond the selection: farther than width */
          const size_t q = (size_t)brick * OWN + local_index(i & 7, j & 7, k & 7);
          const double p[3] = {sample_pos(B, 0, i), p1, p2};
          const double plane = n[0] * (p[0] - v0[0]) + plane12;
          if (plane * plane * (1.0 - 1e-12) >= B->best[q]) continue;
          const double d2 = mesh_distance2_to(m, p, t);
          if (d2 < B->best[q]) B->best[q] = d2, B->tri[q] = t;
        }
      }
  }
}

/* The value of a sample at distance d (>= 0) with sign s: clamped to the band in float. */
static double band_value(const builder *B, double d, int s)
{
  const float w = (float)B->w;
  float v = (float)d;
  v = v > w ? w : v;
  return s == S_NEG ? -(double)v : (double)v;
}

/* Terrain: the value of every owned sample of the stored bricks. */
static void terrain_values(builder *B)
{
  const double w2 = B->w * B->w;
  double H[SIDE * SIDE];
  int inside[SIDE * SIDE];
  for (int by = 0; by < B->nb[1]; by++)
    for (int bx = 0; bx < B->nb[0]; bx++) {
      if (!column_heights_for(B, bx, by, 1, H, inside)) continue;
      for (int bz = 0; bz < B->nb[2]; bz++) {
        const int32_t brick = B->index[slot_index(B, bx, by, bz)];
        if (brick < 0) continue;
        for (int c = 0; c < BRICK; c++)
          for (int b = 0; b < BRICK; b++)
            for (int a = 0; a < BRICK; a++) {
              const size_t q = (size_t)brick * OWN + local_index(a, b, c);
              const double p[3] = {sample_pos(B, 0, (int64_t)BRICK * bx + a),
                                   sample_pos(B, 1, (int64_t)BRICK * by + b),
                                   sample_pos(B, 2, (int64_t)BRICK * bz + c)};
              const double Hc = H[a + SIDE * b];
              if (B->best[q] >= w2) { /* unreached */
                B->best[q] = band_value(B, B->w, terrain_sign(p[2], Hc));
                continue;
              }
              const double s = mesh_signed_distance_to(B->m, &B->pn, p, B->tri[q]);
              const int sgn = inside[a + SIDE * b] && !isnan(Hc) ? terrain_sign(p[2], Hc)
                              : s < 0.0 ? S_NEG : S_POS;
              B->best[q] = band_value(B, fabs(s), sgn);
            }
      }
    }
}

/* ------------------------------------------------- closed meshes: the sign fill ---- */

/* Whether triangle t has an open edge (a hole's rim). */
static int on_rim(const builder *B, int t)
{
  return B->pn.nbr[3 * t] < 0 || B->pn.nbr[3 * t + 1] < 0 || B->pn.nbr[3 * t + 2] < 0;
}

/* The side of p by the generalised winding number w: enclosed (|w| > 1/2: the solid of
 * an outward-oriented mesh, the grains' side of an inward-oriented one) or not. */
static int winding_sign(const builder *B, const double p[3])
{
  const int enclosed = fabs(mesh_winding_number(B->m, p)) > 0.5;
  return enclosed ? -B->outside : B->outside;
}

/* Closed mesh: values of the reached samples, signs of the reached samples and of the
 * unreached ones outside the mesh's box (seeds of the fill). A mesh with holes (B->open):
 * a reached sample whose closest triangle lies on a hole's rim takes the winding number's
 * side, so that a hole narrower than about 2 width is closed as the winding number spans
 * it (the fill then cannot pass it). */
static void mesh_reached(builder *B)
{
  const double w2 = B->w * B->w, eps = 1e-9 * B->h;
  for (int64_t brick = 0; brick < B->nbricks; brick++) {
    int bc[3];
    slot_coords(B, B->slot_of[brick], bc);
    for (int l = 0; l < OWN; l++) {
      const size_t q = (size_t)brick * OWN + l;
      const int loc[3] = {l % BRICK, l / BRICK % BRICK, l / (BRICK * BRICK)};
      double p[3];
      int out = 0;
      for (int a = 0; a < 3; a++) {
        p[a] = sample_pos(B, a, (int64_t)BRICK * bc[a] + loc[a]);
        out |= p[a] < B->lo[a] - eps || p[a] > B->hi[a] + eps;
      }
      if (B->best[q] >= w2) {
        B->best[q] = NAN; /* unreached: value from the sign after the fill */
        B->sign[q] = out ? (signed char)B->outside : S_UNKNOWN;
        continue;
      }
      const double s = mesh_signed_distance_to(B->m, &B->pn, p, B->tri[q]);
      B->sign[q] = s > 0.0 ? S_POS : s < 0.0 ? S_NEG : S_ZERO;
      if (B->sign[q] != S_ZERO && B->open && on_rim(B, B->tri[q])) B->sign[q] = winding_sign(B, p);
      B->best[q] = band_value(B, fabs(s), B->sign[q]);
    }
  }
}

/* The sign a node at global sample (g[0], g[1], g[2]) passes on: its own when known and
 * not on the surface; beyond the grid's last brick (outside the mesh's box) the outside. */
static int node_sign(const builder *B, const int64_t g[3])
{
  for (int a = 0; a < 3; a++) {
    if (g[a] < 0) return S_UNKNOWN;
    if (g[a] >= (int64_t)BRICK * B->nb[a]) return B->outside;
  }
  const int32_t ix = B->index[slot_index(B, (int)(g[0] >> 3), (int)(g[1] >> 3), (int)(g[2] >> 3))];
  if (ix == LSDEM_BAND_OUTSIDE) return S_POS;
  if (ix == LSDEM_BAND_INSIDE) return S_NEG;
  if (ix < 0) return S_UNKNOWN;
  const int s = B->sign[(size_t)ix * OWN + local_index(g[0] & 7, g[1] & 7, g[2] & 7)];
  return s == S_ZERO ? S_UNKNOWN : s;
}

static const int DIRS[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};

/* Flood fill inside one stored brick from its known samples and its neighbours' nodes.
 * Returns whether any sample gained a sign. */
static int fill_brick(builder *B, int32_t brick)
{
  signed char *s = B->sign + (size_t)brick * OWN;
  int bc[3], stack[OWN], top = 0, changed = 0;
  slot_coords(B, B->slot_of[brick], bc);
  for (int l = 0; l < OWN; l++) {
    if (s[l] != S_UNKNOWN) continue;
    const int loc[3] = {l % BRICK, l / BRICK % BRICK, l / (BRICK * BRICK)};
    for (int d = 0; d < 6; d++) {
      int64_t g[3];
      for (int a = 0; a < 3; a++) g[a] = (int64_t)BRICK * bc[a] + loc[a] + DIRS[d][a];
      const int v = node_sign(B, g);
      if (v == S_POS || v == S_NEG) {
        s[l] = (signed char)v;
        stack[top++] = l;
        changed = 1;
        break;
      }
    }
    while (top > 0) { /* spread inside the brick */
      const int k = stack[--top];
      const int kl[3] = {k % BRICK, k / BRICK % BRICK, k / (BRICK * BRICK)};
      for (int d = 0; d < 6; d++) {
        int nl[3], ok = 1;
        for (int a = 0; a < 3; a++) nl[a] = kl[a] + DIRS[d][a], ok &= nl[a] >= 0 && nl[a] < BRICK;
        if (!ok) continue;
        const int n = local_index(nl[0], nl[1], nl[2]);
        if (s[n] == S_UNKNOWN) s[n] = s[k], stack[top++] = n;
      }
    }
  }
  return changed;
}

/* A background slot of unknown sign takes one from a neighbour across a face: a known
 * background slot, a known sample of a stored one next to the face, or the outside beyond
 * the grid. Returns whether it found one. */
static int fill_background(builder *B, int64_t slot)
{
  int bc[3];
  slot_coords(B, slot, bc);
  for (int d = 0; d < 6; d++) {
    const int axis = d / 2, dir = DIRS[d][axis];
    /* the neighbour's samples next to the face: its local layer 7 (below) or 0 (above) */
    const int layer = dir < 0 ? BRICK - 1 : 0;
    for (int u = 0; u < BRICK; u++)
      for (int v = 0; v < BRICK; v++) {
        int64_t g[3];
        const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
        g[axis] = (int64_t)BRICK * (bc[axis] + dir) + layer;
        g[ua] = (int64_t)BRICK * bc[ua] + u;
        g[va] = (int64_t)BRICK * bc[va] + v;
        const int s = node_sign(B, g);
        if (s == S_POS || s == S_NEG) {
          B->index[slot] = s == S_POS ? LSDEM_BAND_OUTSIDE : LSDEM_BAND_INSIDE;
          return 1;
        }
      }
  }
  return 0;
}

/* After the fill of a mesh with holes: whether two neighbours across a grid edge that no
 * surface crosses (an unreached sample and a signed neighbour; two background slots)
 * have opposite signs -- the fill went through a hole from both sides. *at: where. */
static int fill_conflict(const builder *B, double at[3])
{
  for (int64_t brick = 0; brick < B->nbricks; brick++) {
    int bc[3];
    slot_coords(B, B->slot_of[brick], bc);
    for (int l = 0; l < OWN; l++) {
      const size_t q = (size_t)brick * OWN + l;
      if (!isnan(B->best[q])) continue; /* reached: the surface may pass next to it */
      const int loc[3] = {l % BRICK, l / BRICK % BRICK, l / (BRICK * BRICK)};
      for (int d = 0; d < 6; d++) {
        int64_t g[3];
        for (int a = 0; a < 3; a++) g[a] = (int64_t)BRICK * bc[a] + loc[a] + DIRS[d][a];
        const int v = node_sign(B, g);
        if ((v == S_POS || v == S_NEG) && v != B->sign[q]) {
          for (int a = 0; a < 3; a++) at[a] = sample_pos(B, a, (int64_t)BRICK * bc[a] + loc[a]);
          return 1;
        }
      }
    }
  }
  for (int64_t s = 0; s < B->nslots; s++) {
    if (B->index[s] >= 0) continue;
    int bc[3];
    slot_coords(B, s, bc);
    for (int d = 0; d < 6; d++) {
      int nc[3], ok = 1;
      for (int a = 0; a < 3; a++) nc[a] = bc[a] + DIRS[d][a], ok &= nc[a] >= 0 && nc[a] < B->nb[a];
      const int32_t other = ok ? B->index[slot_index(B, nc[0], nc[1], nc[2])] : 0;
      if (ok && other < 0 && other != B->index[s]) {
        for (int a = 0; a < 3; a++) at[a] = sample_pos(B, a, (int64_t)BRICK * bc[a] + BRICK / 2);
        return 1;
      }
    }
  }
  return 0;
}

/* Signs of the unreached samples and the background slots of a closed mesh. */
static lsdem_status mesh_fill(builder *B, lsdem_error *err)
{
  /* background slots reaching outside the mesh's box are outside the solid */
  for (int64_t s = 0; s < B->nslots; s++) {
    if (B->index[s] != BG_UNKNOWN) continue;
    int bc[3], out = 0;
    slot_coords(B, s, bc);
    for (int a = 0; a < 3; a++)
      out |= sample_pos(B, a, (int64_t)BRICK * bc[a]) < B->lo[a] ||
             sample_pos(B, a, (int64_t)BRICK * (bc[a] + 1)) > B->hi[a];
    if (out) B->index[s] = B->outside == S_POS ? LSDEM_BAND_OUTSIDE : LSDEM_BAND_INSIDE;
  }
  int32_t *queue = malloc((size_t)B->nslots * sizeof(int32_t) + 1);
  unsigned char *queued = calloc((size_t)B->nslots + 1, 1);
  if (!queue || !queued) {
    free(queue), free(queued);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "band: cannot allocate the sign fill (%lld slots)",
                      (long long)B->nslots);
  }
  size_t head = 0, count = 0; /* a ring of at most nslots entries: each slot queued once */
  const size_t cap = (size_t)B->nslots;
  for (int64_t s = 0; s < B->nslots; s++)
    if (B->index[s] >= 0 || B->index[s] == BG_UNKNOWN)
      queue[(head + count++) % cap] = (int32_t)s, queued[s] = 1;
  while (count > 0) {
    const int64_t s = queue[head];
    head = (head + 1) % cap, count--;
    queued[s] = 0;
    int changed = 0;
    if (B->index[s] >= 0) changed = fill_brick(B, B->index[s]);
    else if (B->index[s] == BG_UNKNOWN) changed = fill_background(B, s);
    if (!changed) continue;
    int bc[3];
    slot_coords(B, s, bc);
    for (int d = 0; d < 6; d++) {
      int nc[3], ok = 1;
      for (int a = 0; a < 3; a++) nc[a] = bc[a] + DIRS[d][a], ok &= nc[a] >= 0 && nc[a] < B->nb[a];
      if (!ok) continue;
      const int64_t n = slot_index(B, nc[0], nc[1], nc[2]);
      if (queued[n] || (B->index[n] < 0 && B->index[n] != BG_UNKNOWN)) continue;
      if (B->index[n] >= 0) { /* only a brick that still has unknown samples */
        const signed char *sg = B->sign + (size_t)B->index[n] * OWN;
        int unknown = 0;
        for (int l = 0; l < OWN && !unknown; l++) unknown = sg[l] == S_UNKNOWN;
        if (!unknown) continue;
      }
      queue[(head + count++) % cap] = (int32_t)n, queued[n] = 1;
    }
  }
  free(queue), free(queued);
  if (B->open) {
    double at[3];
    if (fill_conflict(B, at))
      return lsdem_fail(err, LSDEM_ERR_ARG, "band: the mesh's holes are too wide to close: its "
                        "inside and outside meet through a hole near (%g, %g, %g); close the "
                        "holes, or make the band wider than half the widest hole", at[0], at[1],
                        at[2]);
  }
  /* whatever no seed reached (a mesh too small to reach any sample) is outside */
  for (int64_t s = 0; s < B->nslots; s++)
    if (B->index[s] == BG_UNKNOWN)
      B->index[s] = B->outside == S_POS ? LSDEM_BAND_OUTSIDE : LSDEM_BAND_INSIDE;
  const size_t owned = (size_t)B->nbricks * OWN;
  for (size_t q = 0; q < owned; q++) {
    if (B->sign[q] == S_UNKNOWN) B->sign[q] = (signed char)B->outside;
    if (isnan(B->best[q])) B->best[q] = band_value(B, B->w, B->sign[q]);
  }
  return LSDEM_OK;
}

/* ---------------------------------------------------------------- assembly ---- */

/* A sample beyond the last brick (the 9th layer of the grid's last bricks): farther than
 * width + h from the mesh's box, so +-width by the outside rule. */
static float beyond_value(const builder *B, const int64_t g[3])
{
  if (B->src == LSDEM_BAND_MESH) return (float)band_value(B, B->w, B->outside);
  int inside;
  const double H = terrain_height(B->m, &B->tg, sample_pos(B, 0, g[0]), sample_pos(B, 1, g[1]),
                                  &inside);
  return (float)band_value(B, B->w, terrain_sign(sample_pos(B, 2, g[2]), H));
}

/* The stored bricks' 729 samples each, from their owners. */
static void assemble(const builder *B, float *phi)
{
  const float w = (float)B->w;
  for (int64_t brick = 0; brick < B->nbricks; brick++) {
    int bc[3];
    slot_coords(B, B->slot_of[brick], bc);
    float *out = phi + (size_t)brick * LSDEM_BAND_BRICK_SAMPLES;
    for (int c = 0; c < SIDE; c++)
      for (int b = 0; b < SIDE; b++)
        for (int a = 0; a < SIDE; a++) {
          const int64_t g[3] = {(int64_t)BRICK * bc[0] + a, (int64_t)BRICK * bc[1] + b,
                                (int64_t)BRICK * bc[2] + c};
          float v;
          if (g[0] >= (int64_t)BRICK * B->nb[0] || g[1] >= (int64_t)BRICK * B->nb[1] ||
              g[2] >= (int64_t)BRICK * B->nb[2]) {
            v = beyond_value(B, g);
          } else {
            const int32_t ix = B->index[slot_index(B, (int)(g[0] >> 3), (int)(g[1] >> 3),
                                                   (int)(g[2] >> 3))];
            const int l = local_index(g[0] & 7, g[1] & 7, g[2] & 7);
            v = ix >= 0 ? (float)B->best[(size_t)ix * OWN + l] : ix == LSDEM_BAND_OUTSIDE ? w : -w;
          }
          out[a + SIDE * (b + SIDE * c)] = v;
        }
  }
}

/* The surface kept with band b (its index set): a copy of the mesh, and per stored brick
 * the triangles whose box grown by width touches it (select_bricks' rule, so the lists cover every
 * point of a brick nearer than width to the surface), counted then filled. */
static lsdem_status keep_surface(const builder *B, lsdem_band *b, lsdem_error *err)
{
  const lsdem_mesh *m = B->m;
  double *verts = malloc((size_t)m->nverts * 3 * sizeof(double));
  int32_t *tris = malloc((size_t)m->ntris * 3 * sizeof(int32_t));
  int64_t *start = calloc((size_t)B->nbricks + 1, sizeof(int64_t));
  b->verts = verts, b->tris = tris, b->brick_tri_start = start;
  if (!verts || !tris || !start)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "band: cannot allocate the surface's copy");
  int32_t *nbr = malloc((size_t)m->ntris * 3 * sizeof(int32_t));
  b->nbr = nbr;
  if (!nbr) return lsdem_fail(err, LSDEM_ERR_NOMEM, "band: cannot allocate the surface's copy");
  memcpy(verts, m->verts, (size_t)m->nverts * 3 * sizeof(double));
  for (int64_t k = 0; k < 3 * (int64_t)m->ntris; k++) tris[k] = m->tris[k], nbr[k] = B->pn.nbr[k];
  const double g = B->w * (1.0 + 1e-9) + 1e-9 * B->h;
  int32_t *list = NULL;
  for (int pass = 0; pass < 2; pass++) {
    for (int t = 0; t < m->ntris; t++) {
      double lo[3], hi[3];
      int b0[3], b1[3];
      grown_box(m, t, g, lo, hi);
      for (int a = 0; a < 3; a++) brick_range(B, a, lo[a], hi[a], &b0[a], &b1[a]);
      for (int bz = b0[2]; bz <= b1[2]; bz++)
        for (int by = b0[1]; by <= b1[1]; by++)
          for (int bx = b0[0]; bx <= b1[0]; bx++) {
            const int32_t k = b->index[slot_index(B, bx, by, bz)];
            if (k < 0) continue;
            if (pass == 0) start[k + 1]++;
            else list[start[k]++] = t;
          }
    }
    if (pass == 0) { /* counts -> starts */
      for (int64_t k = 0; k < B->nbricks; k++) start[k + 1] += start[k];
      list = malloc((size_t)start[B->nbricks] * sizeof(int32_t) + 1);
      b->brick_tris = list;
      if (!list)
        return lsdem_fail(err, LSDEM_ERR_NOMEM, "band: cannot allocate %lld brick list entries",
                          (long long)start[B->nbricks]);
    }
  }
  for (int64_t k = B->nbricks; k > 0; k--) start[k] = start[k - 1]; /* filled: shift back */
  start[0] = 0;
  b->nverts = m->nverts, b->ntris = m->ntris;
  return LSDEM_OK;
}

/* Stored bricks whose 729 samples are all +width or all -width read exactly as background
 * (a constant): they become background (LSDEM_BAND_OUTSIDE / INSIDE) and the rest are
 * renumbered in order, their samples moved down. Returns the bricks kept. (About a tenth
 * of a terrain's bricks: the conservative selection by grown triangle boxes.) */
static int64_t drop_flat_bricks(int32_t *index, int64_t nslots, float *phi, int64_t nbricks,
                                float w)
{
  int64_t kept = 0;
  int32_t *renumber = malloc((size_t)nbricks * sizeof(int32_t) + 1);
  if (!renumber) return nbricks; /* keep them all: correct, a little larger */
  for (int64_t k = 0; k < nbricks; k++) {
    const float *v = phi + (size_t)k * LSDEM_BAND_BRICK_SAMPLES;
    int pos = 1, neg = 1;
    for (int q = 0; q < LSDEM_BAND_BRICK_SAMPLES; q++) pos &= v[q] == w, neg &= v[q] == -w;
    if (pos || neg) {
      renumber[k] = pos ? LSDEM_BAND_OUTSIDE : LSDEM_BAND_INSIDE;
      continue;
    }
    if (kept != k)
      memmove(phi + (size_t)kept * LSDEM_BAND_BRICK_SAMPLES, v,
              LSDEM_BAND_BRICK_SAMPLES * sizeof(float));
    renumber[k] = (int32_t)kept++;
  }
  for (int64_t s = 0; s < nslots; s++)
    if (index[s] >= 0) index[s] = renumber[index[s]];
  free(renumber);
  return kept;
}

void lsdem_band_free(lsdem_band *b)
{
  if (!b) return;
  free((void *)b->index), free((void *)b->phi);
  free((void *)b->verts), free((void *)b->tris);
  free((void *)b->brick_tri_start), free((void *)b->brick_tris), free((void *)b->nbr);
  free((void *)b->heights);
  memset(b, 0, sizeof *b);
}

lsdem_status lsdem_band_from_heights(const lsdem_heightmap *hm, double width, lsdem_band *b,
                                     lsdem_error *err)
{
  if (!b || !hm || !hm->z) return lsdem_fail(err, LSDEM_ERR_ARG, "band: NULL argument");
  memset(b, 0, sizeof *b);
  if (hm->nx < 2 || hm->ny < 2 || !(hm->cell > 0.0) || !isfinite(hm->cell) ||
      !(width >= hm->cell && width <= LSDEM_BAND_MAX_WIDTH_CELLS * hm->cell))
    return lsdem_fail(err, LSDEM_ERR_ARG, "band: %d x %d heights at cell %g, width %g (at "
                      "least 2 x 2 heights, cell > 0, cell <= width <= %g cells)", hm->nx,
                      hm->ny, hm->cell, width, LSDEM_BAND_MAX_WIDTH_CELLS);
  const size_t count = (size_t)hm->nx * (size_t)hm->ny;
  for (size_t k = 0; k < count; k++)
    if (isnan(hm->z[k]))
      return lsdem_fail(err, LSDEM_ERR_ARG, "band: height (%zu, %zu) is nodata: a terrain kept "
                        "as heights has no holes (fill them, or keep it as bricks)",
                        k % (size_t)hm->nx, k / (size_t)hm->nx);
  float *z = (float *)malloc(count * sizeof *z);
  if (!z) return lsdem_fail(err, LSDEM_ERR_NOMEM, "band: cannot allocate %zu heights", count);
  memcpy(z, hm->z, count * sizeof *z);
  b->heights = z;
  b->n[0] = hm->nx, b->n[1] = hm->ny, b->n[2] = 1;
  b->h = hm->cell;
  b->origin[0] = hm->x0, b->origin[1] = hm->y0, b->origin[2] = 0.0;
  b->width = width;
  return LSDEM_OK;
}

/* The band of m (lsdem_band_from_mesh; open: holes allowed, lsdem_band_from_open_mesh). */
static lsdem_status build_band(const lsdem_mesh *m, double h, double width, lsdem_band_source src,
                               int open, lsdem_band *b, lsdem_error *err)
{
  if (!b) return lsdem_fail(err, LSDEM_ERR_ARG, "band: NULL output");
  memset(b, 0, sizeof *b);
  builder B;
  memset(&B, 0, sizeof B);
  B.open = open;
  lsdem_status st = plan(&B, m, h, width, src, err);
  if (st == LSDEM_OK) {
    B.index = malloc((size_t)B.nslots * sizeof(int32_t));
    if (!B.index) st = lsdem_fail(err, LSDEM_ERR_NOMEM, "band: cannot allocate the index of "
                                  "%lld slots", (long long)B.nslots);
  }
  lsdem_mesh_topology topo;
  if (st == LSDEM_OK) st = mesh_pseudonormals_build(m, &B.pn, &topo, err);
  if (st == LSDEM_OK && src == LSDEM_BAND_MESH &&
      ((topo.boundary_edges && !open) || topo.nonmanifold_edges || topo.misoriented_edges ||
       topo.degenerate_tris))
    st = lsdem_fail(err, LSDEM_ERR_ARG, "band: the mesh is not closed (%d boundary edges, %d "
                    "non-manifold, %d with inconsistent orientation, %d degenerate triangles; "
                    "first near (%g, %g, %g)): a wall from a mesh needs a closed surface, "
                    "or one with holes but otherwise manifold and consistently oriented "
                    "(zero-area triangles leave the sign undefined near them)",
                    topo.boundary_edges, topo.nonmanifold_edges, topo.misoriented_edges,
                    topo.degenerate_tris, topo.where[0], topo.where[1], topo.where[2]);
  if (st == LSDEM_OK) {
    select_bricks(&B);
    if (src == LSDEM_BAND_TERRAIN) {
      st = terrain_grid_build(m, B.lo, B.hi, &B.tg, err);
      if (st == LSDEM_OK) terrain_backgrounds(&B);
    }
  }
  if (st == LSDEM_OK) st = number_bricks(&B, err);
  if (st == LSDEM_OK) {
    rasterise(&B);
    if (src == LSDEM_BAND_TERRAIN) terrain_values(&B);
    else {
      mesh_reached(&B);
      st = mesh_fill(&B, err);
    }
  }
  float *phi = NULL;
  if (st == LSDEM_OK) {
    free(B.tri), free(B.sign);
    B.tri = NULL, B.sign = NULL;
    phi = malloc((size_t)B.nbricks * LSDEM_BAND_BRICK_SAMPLES * sizeof(float) + 1);
    if (!phi) st = lsdem_fail(err, LSDEM_ERR_NOMEM, "band: cannot allocate %lld bricks (%.0f MB)",
                              (long long)B.nbricks,
                              B.nbricks * LSDEM_BAND_BRICK_SAMPLES * 4.0 / 1048576.0);
  }
  if (st == LSDEM_OK) {
    assemble(&B, phi);
    B.nbricks = drop_flat_bricks(B.index, B.nslots, phi, B.nbricks, (float)width);
    float *fit = realloc(phi, (size_t)B.nbricks * LSDEM_BAND_BRICK_SAMPLES * sizeof(float) + 1);
    if (fit) phi = fit;
    for (int a = 0; a < 3; a++) b->n[a] = B.n[a], b->nb[a] = B.nb[a], b->origin[a] = B.origin[a];
    b->h = h, b->width = width, b->nbricks = B.nbricks;
    b->index = B.index, b->phi = phi;
    B.index = NULL; /* now the band's */
    st = keep_surface(&B, b, err);
  } else {
    free(phi);
  }
  builder_free(&B);
  if (st != LSDEM_OK) lsdem_band_free(b);
  return st;
}

lsdem_status lsdem_band_from_mesh(const lsdem_mesh *m, double h, double width,
                                  lsdem_band_source src, lsdem_band *b, lsdem_error *err)
{
  return build_band(m, h, width, src, 0, b, err);
}

lsdem_status lsdem_band_from_open_mesh(const lsdem_mesh *m, double h, double width,
                                       lsdem_band *b, lsdem_error *err)
{
  return build_band(m, h, width, LSDEM_BAND_MESH, 1, b, err);
}
