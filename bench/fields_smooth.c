/* lsdem-bench-fields: the cost of smoothing one field channel on a grain-sized grid, FFT
 * (lsdem_field_smooth_fft) against direct summation (lsdem_field_smooth_direct), over kernel
 * widths in units of the grain size D50 (bench/README.md). Grains: N random centres in a
 * cube of side L D50 (a loose random packing's number density, 1 / D50^3), grid spacing
 * D50 / 3. Prints per width: the grid, both CPU times (best of 2), their ratio and the
 * largest difference relative to the field's peak. CPU time (clock), one thread. */
#include "fields/lsdem_fields.h"
#include "lsdem.h"

#include <math.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double cpu_seconds(void) { return (double)clock() / CLOCKS_PER_SEC; }

typedef lsdem_status (*smoother)(const lsdem_field_grid *, double, int, double *, lsdem_error *);

/* best of two runs of smooth on a copy of the deposits; the last result stays in out */
static double time_smooth(smoother smooth, const lsdem_field_grid *g, double width,
                          const double *deposits, double *out, size_t nodes)
{
  double best = 1e300;
  for (int round = 0; round < 2; round++) {
    memcpy(out, deposits, nodes * sizeof(double));
    const double t0 = cpu_seconds();
    smooth(g, width, 1, out, NULL);
    const double t = cpu_seconds() - t0;
    best = t < best ? t : best;
  }
  return best;
}

int main(int argc, char **argv)
{
  const double side = argc > 1 ? atof(argv[1]) : 10.0;  /* specimen side in D50 */
  const double max_width = argc > 2 ? atof(argv[2]) : 2.0;
  const double h = 1.0 / 3.0;
  const int n = (int)(side * side * side);
  uint64_t rng = 35;
  double *x = malloc(3 * (size_t)n * sizeof(double));
  for (int i = 0; i < 3 * n; i++) x[i] = side * lsdem_uniform01(&rng);
  const double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {side, side, side};
  printf("%d grains in a %.0f D50 cube, spacing D50/3, one channel\n", n, side);
  printf("width/D50  grid           FFT s    direct s  direct/FFT  max |diff|/peak\n");
  for (double w = 0.25; w <= max_width + 1e-9; w *= 2.0) {
    lsdem_field_grid g;
    if (lsdem_field_grid_cover(lo, hi, h, w, &g, NULL) != LSDEM_OK) return 1;
    const size_t nodes = lsdem_field_grid_nodes(&g);
    double *dep = calloc(nodes, sizeof(double)), *a = malloc(nodes * sizeof(double)),
           *b = malloc(nodes * sizeof(double));
    const double one = 1.0;
    for (int i = 0; i < n; i++) lsdem_field_deposit(&g, x + 3 * i, 1, &one, dep);
    const double tf = time_smooth(lsdem_field_smooth_fft, &g, w, dep, a, nodes);
    const double td = time_smooth(lsdem_field_smooth_direct, &g, w, dep, b, nodes);
    double diff = 0.0, peak = 0.0;
    for (size_t k = 0; k < nodes; k++) {
      diff = fabs(a[k] - b[k]) > diff ? fabs(a[k] - b[k]) : diff;
      peak = b[k] > peak ? b[k] : peak;
    }
    printf("%9.2f  %3dx%3dx%3d  %8.4f  %9.4f  %10.1f  %.2g\n", w, g.n[0], g.n[1], g.n[2], tf,
           td, td / tf, diff / peak);
    fflush(stdout);
    free(dep);
    free(a);
    free(b);
  }
  free(x);
  return 0;
}
