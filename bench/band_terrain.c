/* band_terrain.c -- lsdem-bench-band: time and memory of a terrain's narrow band
 * (lsdem_heightmap_mesh + lsdem_band_from_mesh) on a synthetic N x N height map, spacing =
 * cell size, width 2 h (the target: 1000 x 1000 in under a minute on one core).
 *
 *   lsdem-bench-band [N] [RELIEF]
 *
 * Heights: RELIEF cells of long waves plus 3 cells of short ones. Prints the grid, the
 * stored bricks, the band's memory against the dense grid's, the build time, the
 * process's peak resident memory (getrusage), and the lookup time of the band against a
 * dense grid holding the same samples (lsdem_grid_eval; 2^20 random points within the
 * band, value and gradient, three alternating rounds; the values must agree bit for bit,
 * the "same bits as the dense path where both exist"). */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "lsdem.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
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

int main(int argc, char **argv)
{
  const int n = argc > 1 ? atoi(argv[1]) : 1000;
  const double relief = argc > 2 ? atof(argv[2]) : 20.0;
  if (n < 2 || n > 20000 || !(relief >= 0.0)) {
    fprintf(stderr, "usage: lsdem-bench-band [N (2..20000)] [RELIEF (cells, >= 0)]\n");
    return 2;
  }
  lsdem_heightmap hm = {n, n, 0.0, 0.0, 1.0, malloc((size_t)n * n * sizeof(float))};
  if (!hm.z) return 1;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++)
      hm.z[(size_t)j * n + i] = (float)(relief * sin(0.02 * i) * cos(0.015 * j) +
                                        3.0 * sin(0.3 * i + 0.2 * j));
  lsdem_mesh m;
  lsdem_band b;
  lsdem_error err;
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
  printf("terrain %d x %d (relief %g cells, %d triangles), h = cell = 1, width 2 h\n", n, n,
         relief, m.ntris);
  printf("grid %d x %d x %d, stored bricks %lld of %lld\n", b.n[0], b.n[1], b.n[2],
         (long long)b.nbricks, (long long)b.nb[0] * b.nb[1] * b.nb[2]);
  lsdem_band level = b; /* the level set alone: the band without its kept surface */
  level.ntris = level.nverts = 0;
  const double mb_level = lsdem_band_bytes(&level) / 1048576.0;
  printf("band %.1f MB: level set %.1f MB (index and bricks, %.1f %% of the dense grid's "
         "%.1f MB) + surface for maps %.1f MB\n", lsdem_band_bytes(&b) / 1048576.0, mb_level,
         100.0 * mb_level * 1048576.0 / dense, dense / 1048576.0,
         lsdem_band_bytes(&b) / 1048576.0 - mb_level);
  printf("time: mesh %.2f s, band %.2f s; peak resident memory %.0f MB\n", t1 - t0, t2 - t1,
         ru.ru_maxrss / 1024.0);
  compare_lookups(&b);
  lsdem_band_free(&b);
  lsdem_mesh_free(&m);
  free(hm.z);
  return 0;
}
