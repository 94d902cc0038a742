/* membw.c -- this machine's memory speed on one core, the limit the level-set lookups run
 * against (bench/run.sh prints it beside their rate; bench/README.md).
 *
 *   membw [MB]    arrays of MB megabytes each (default 256, far beyond the caches)
 *
 * Prints one line:
 *   read_GBps=<r> copy_GBps=<c> latency_ns=<l>
 * read: a sum over one array (bytes read per second); copy: b = a (bytes read + bytes
 * written per second, STREAM's convention); each the best of 5 passes. latency: one
 * dependent load after another along a random cycle through the array (every load a cache
 * miss the hardware cannot prefetch), mean time per load. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { PASSES = 5, LINE = 64 };

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Best bytes per second of a sum over a[0..n). *sink keeps the sum alive. */
static double read_rate(const double *a, size_t n, double *sink)
{
  double best = 0.0;
  for (int p = 0; p < PASSES; p++) {
    const double t0 = now();
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    for (size_t i = 0; i + 3 < n; i += 4)
      s0 += a[i], s1 += a[i + 1], s2 += a[i + 2], s3 += a[i + 3];
    const double dt = now() - t0;
    *sink += s0 + s1 + s2 + s3;
    if ((double)(n * sizeof *a) / dt > best) best = (double)(n * sizeof *a) / dt;
  }
  return best;
}

/* Best (bytes read + bytes written) per second of b = a over n doubles. */
static double copy_rate(const double *a, double *b, size_t n)
{
  double best = 0.0;
  for (int p = 0; p < PASSES; p++) {
    const double t0 = now();
    for (size_t i = 0; i < n; i++) b[i] = a[i];
    const double dt = now() - t0;
    if ((double)(2 * n * sizeof *a) / dt > best) best = (double)(2 * n * sizeof *a) / dt;
  }
  return best;
}

/* Mean seconds per load of a dependent walk through nlines cache lines in a random cyclic
 * order (Sattolo's shuffle: one cycle through all of them), next[k * step] naming the
 * next line's first slot. */
static double latency(size_t *next, size_t nlines)
{
  const size_t step = LINE / sizeof *next;
  size_t *order = (size_t *)malloc(nlines * sizeof *order);
  if (!order) return 0.0;
  for (size_t k = 0; k < nlines; k++) order[k] = k;
  uint64_t x = 88172645463325252ULL; /* xorshift64 */
  for (size_t k = nlines - 1; k > 0; k--) {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    const size_t j = (size_t)(x % k), t = order[k];
    order[k] = order[j], order[j] = t;
  }
  for (size_t k = 0; k < nlines; k++) next[order[k] * step] = order[(k + 1) % nlines] * step;
  free(order);
  const size_t loads = nlines < 20000000 ? nlines : 20000000;
  size_t at = 0;
  const double t0 = now();
  for (size_t k = 0; k < loads; k++) at = next[at];
  const double dt = now() - t0;
  if (at == (size_t)-1) puts(""); /* keeps the walk */
  return dt / (double)loads;
}

int main(int argc, char **argv)
{
  const size_t mb = argc > 1 ? (size_t)strtoul(argv[1], NULL, 10) : 256;
  const size_t n = mb * (1u << 20) / sizeof(double);
  double *a = (double *)malloc(n * sizeof *a), *b = (double *)malloc(n * sizeof *b);
  if (!mb || !a || !b) {
    fprintf(stderr, "membw: cannot allocate 2 x %zu MB\n", mb);
    return 1;
  }
  for (size_t i = 0; i < n; i++) a[i] = (double)(i & 1023), b[i] = 0.0;
  double sink = 0.0;
  const double read = read_rate(a, n, &sink), copy = copy_rate(a, b, n);
  const double lat = latency((size_t *)b, n * sizeof *b / LINE);
  printf("read_GBps=%.2f copy_GBps=%.2f latency_ns=%.1f\n", read * 1e-9, copy * 1e-9, lat * 1e9);
  if (sink < 0.0) puts("");
  free(a);
  free(b);
  return 0;
}
