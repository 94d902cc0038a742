/* band_terrain.c -- lsdem-bench-band: time and memory of a terrain's narrow band
 * (lsdem_heightmap_mesh + lsdem_band_from_mesh) on a synthetic N x N height map, spacing =
 * cell size, width 2 h (the target: 1000 x 1000 in under a minute on one core).
 *
 *   lsdem-bench-band [N] [RELIEF] [heights]
 *
 * Heights: RELIEF cells of long waves plus 3 cells of short ones. Prints the grid, the
 * stored bricks, the band's memory against the dense grid's, the build time, the
 * process's peak resident memory (getrusage), and the lookup time of the band against a
 * dense grid holding the same samples (lsdem_grid_eval; 2^20 random points within the
 * band, value and gradient, three alternating rounds; the values must agree bit for bit,
 * the "same bits as the dense path where both exist"); and the same terrain kept
 * as heights (lsdem_band_from_heights): its memory and its lookups against the bricks'
 * trilinear and exact mode at the same points, with the largest difference from exact
 * mode. `heights`: the heights alone (for terrains too large for bricks, e.g. 4000). */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "lsdem.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The band's lookups against a dense grid of the same samples (the band's own values at
 * the grid's points). */
static void compare_lookups(const lsdem_band *b)
{
  const size_t total = (size_t)b->n[0] * b->n[1] * b->n[2];
  float *phi = malloc(total * sizeof(float));
  enum { NPTS = 1 << 20 };
  double *p = malloc(3 * (size_t)NPTS * sizeof(double));
  if (!phi || !p) {
    printf("lookups: not enough memory for the dense grid (%.0f MB)\n", total * 4.0 / 1048576.0);
    free(phi), free(p);
    return;
  }
  for (int k = 0; k < b->n[2]; k++)
    for (int j = 0; j < b->n[1]; j++)
      for (int i = 0; i < b->n[0]; i++) {
        const double q[3] = {b->origin[0] + b->h * i, b->origin[1] + b->h * j,
                             b->origin[2] + b->h * k};
        double g[3];
        phi[i + (size_t)b->n[0] * (j + (size_t)b->n[1] * k)] = (float)lsdem_band_eval(b, q, g);
      }
  lsdem_grid dense = {{b->n[0], b->n[1], b->n[2]}, b->h, {b->origin[0], b->origin[1], b->origin[2]},
                      phi, 0.0, 0.0};
  uint64_t rng = 12345;
  int m = 0;
  while (m < NPTS) { /* random points with |phi| < width, inside the box */
    double q[3], g[3];
    for (int a = 0; a < 3; a++)
      q[a] = b->origin[a] + (b->n[a] - 1) * b->h * lsdem_uniform01(&rng);
    if (fabs(lsdem_band_eval(b, q, g)) < b->width) {
      for (int a = 0; a < 3; a++) p[3 * (size_t)m + a] = q[a];
      m++;
    }
  }
  double t_band = HUGE_VAL, t_dense = HUGE_VAL, sum_b = 0.0, sum_d = 0.0;
  long differ = 0;
  for (int round = 0; round < 3; round++) {
    double t = now();
    for (int k = 0; k < NPTS; k++) {
      double g[3];
      sum_b += lsdem_band_eval(b, &p[3 * (size_t)k], g);
    }
    t_band = fmin(t_band, now() - t);
    t = now();
    for (int k = 0; k < NPTS; k++) {
      double g[3];
      sum_d += lsdem_grid_eval(&dense, &p[3 * (size_t)k], g);
    }
    t_dense = fmin(t_dense, now() - t);
  }
  for (int k = 0; k < NPTS; k++) {
    double g1[3], g2[3];
    differ += lsdem_band_eval(b, &p[3 * (size_t)k], g1) != lsdem_grid_eval(&dense, &p[3 * (size_t)k], g2);
  }
  printf("lookups (value and gradient, random order, best of 3): band %.0f ns, dense grid %.0f ns "
         "(%.2fx); %ld of %d values differ (checksums %.6g %.6g)\n", 1e9 * t_band / NPTS,
         1e9 * t_dense / NPTS, t_band / t_dense, differ, NPTS, sum_b, sum_d);
  free(phi), free(p);
}

/* 2^20 random points of b's box nearer than width to its surface (b's own lookups). */
static double *points_in_band(const lsdem_band *b, int npts)
{
  double *p = malloc(3 * (size_t)npts * sizeof(double));
  uint64_t rng = 777;
  double lo[3], span[3];
  for (int a = 0; a < 3; a++) lo[a] = b->origin[a], span[a] = (b->n[a] - 1) * b->h;
  if (b->heights) { /* columns: z over the heights' range and the band */
    float zl = INFINITY, zh = -INFINITY;
    for (size_t k = 0; k < (size_t)b->n[0] * b->n[1]; k++)
      zl = fminf(zl, b->heights[k]), zh = fmaxf(zh, b->heights[k]);
    lo[2] = zl - b->width, span[2] = (double)zh - zl + 2.0 * b->width;
  }
  for (int m = 0; p && m < npts;) {
    double q[3], g[3];
    for (int a = 0; a < 3; a++) q[a] = lo[a] + span[a] * lsdem_uniform01(&rng);
    if (fabs(lsdem_band_eval(b, q, g)) < b->width) {
      for (int a = 0; a < 3; a++) p[3 * (size_t)m + a] = q[a];
      m++;
    }
  }
  return p;
}

/* Best of 3 rounds of n lookups (value and gradient), ns per lookup. */
static double time_lookups(const lsdem_band *b, const double *p, int n, double *sum)
{
  double best = HUGE_VAL;
  for (int round = 0; round < 3; round++) {
    const double t = now();
    for (int k = 0; k < n; k++) {
      double g[3];
      *sum += lsdem_band_eval(b, &p[3 * (size_t)k], g);
    }
    best = fmin(best, now() - t);
  }
  return 1e9 * best / n;
}

/* The terrain kept as heights against the brick band (trilinear and exact mode) at the
 * same points in the band: lookup times and the largest difference from exact mode. */
static void compare_heights(const lsdem_band *hb, lsdem_band *bricks)
{
  enum { NPTS = 1 << 20 };
  double *p = points_in_band(hb, NPTS), sum = 0.0;
  if (!p) return;
  const double t_heights = time_lookups(hb, p, NPTS, &sum);
  if (!bricks) {
    printf("heights lookups (value and gradient, random order in the band, best of 3): %.0f ns\n",
           t_heights);
    free(p);
    return;
  }
  const double t_bricks = time_lookups(bricks, p, NPTS, &sum);
  lsdem_pseudonormals pn;
  lsdem_error err;
  double t_exact = NAN, worst = 0.0;
  if (lsdem_pseudonormals_make(bricks->verts, bricks->nverts, bricks->tris, bricks->ntris,
                               bricks->nbr, &pn, &err) == LSDEM_OK) {
    bricks->exact = &pn;
    t_exact = time_lookups(bricks, p, NPTS, &sum);
    for (int k = 0; k < NPTS; k++) {
      double g1[3], g2[3];
      worst = fmax(worst, fabs(lsdem_band_eval(hb, &p[3 * (size_t)k], g1) -
                               lsdem_band_eval(bricks, &p[3 * (size_t)k], g2)));
    }
    bricks->exact = NULL;
    lsdem_pseudonormals_free(&pn);
  }
  printf("heights lookups (random order in the band, best of 3): %.0f ns; bricks %.0f ns "
         "(trilinear), %.0f ns (exact mode); heights - exact mode: at most %.2g\n", t_heights,
         t_bricks, t_exact, worst);
  free(p);
}

int main(int argc, char **argv)
{
  const int n = argc > 1 ? atoi(argv[1]) : 1000;
  const double relief = argc > 2 ? atof(argv[2]) : 20.0;
  const int heights_only = argc > 3 && !strcmp(argv[3], "heights");
  if (n < 2 || n > 20000 || !(relief >= 0.0) || (argc > 3 && !heights_only)) {
    fprintf(stderr, "usage: lsdem-bench-band [N (2..20000)] [RELIEF (cells, >= 0)] [heights]\n");
    return 2;
  }
  lsdem_heightmap hm = {n, n, 0.0, 0.0, 1.0, malloc((size_t)n * n * sizeof(float))};
  if (!hm.z) return 1;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++)
      hm.z[(size_t)j * n + i] = (float)(relief * sin(0.02 * i) * cos(0.015 * j) +
                                        3.0 * sin(0.3 * i + 0.2 * j));
  lsdem_band hb;
  lsdem_error err;
  float *tiles = NULL;
  const double th = now();
  if (lsdem_band_from_heights(&hm, 2.0, &hb, &err) != LSDEM_OK ||
      lsdem_heights_tiles(&hb, &tiles, hb.nt, &err) != LSDEM_OK) {
    fprintf(stderr, "%s\n", err.msg);
    return 1;
  }
  hb.tile_range = tiles;
  printf("terrain %d x %d (relief %g cells), h = cell = 1, width 2 h\n", n, n, relief);
  printf("kept as heights: %.1f MB, made in %.2f s\n", lsdem_band_bytes(&hb) / 1048576.0,
         now() - th);
  if (heights_only) {
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    compare_heights(&hb, NULL);
    printf("peak resident memory %.0f MB (the height map read, and the heights)\n",
           ru.ru_maxrss / 1024.0);
    lsdem_band_free(&hb);
    free(tiles), free(hm.z);
    return 0;
  }
  lsdem_mesh m;
  lsdem_band b;
  const double t0 = now();
  if (lsdem_heightmap_mesh(&hm, &m, &err) != LSDEM_OK) {
    fprintf(stderr, "%s\n", err.msg);
    return 1;
  }
  const double t1 = now();
  if (lsdem_band_from_mesh(&m, 1.0, 2.0, LSDEM_BAND_TERRAIN, &b, &err) != LSDEM_OK) {
    fprintf(stderr, "%s\n", err.msg);
    return 1;
  }
  const double t2 = now();
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  const double dense = 4.0 * b.n[0] * (double)b.n[1] * b.n[2];
  printf("%d triangles; grid %d x %d x %d, stored bricks %lld of %lld\n", m.ntris, b.n[0],
         b.n[1], b.n[2], (long long)b.nbricks, (long long)b.nb[0] * b.nb[1] * b.nb[2]);
  lsdem_band level = b; /* the level set alone: the band without its kept surface */
  level.ntris = level.nverts = 0;
  const double mb_level = lsdem_band_bytes(&level) / 1048576.0;
  printf("band %.1f MB: level set %.1f MB (index and bricks, %.1f %% of the dense grid's "
         "%.1f MB) + surface for maps %.1f MB; heights %.2f %% of the dense grid\n",
         lsdem_band_bytes(&b) / 1048576.0, mb_level, 100.0 * mb_level * 1048576.0 / dense,
         dense / 1048576.0, lsdem_band_bytes(&b) / 1048576.0 - mb_level,
         100.0 * lsdem_band_bytes(&hb) / dense);
  printf("time: mesh %.2f s, band %.2f s; peak resident memory %.0f MB\n", t1 - t0, t2 - t1,
         ru.ru_maxrss / 1024.0);
  compare_lookups(&b);
  compare_heights(&hb, &b);
  lsdem_band_free(&b);
  lsdem_band_free(&hb);
  lsdem_mesh_free(&m);
  free(tiles), free(hm.z);
  return 0;
}
