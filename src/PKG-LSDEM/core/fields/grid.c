/* grid.c -- the field grid: its extent and padding, trilinear deposit, the Gaussian kernel
 * (lsdem_fields.h). */
#include "lsdem_fields.h"

#include <math.h>

size_t lsdem_field_grid_nodes(const lsdem_field_grid *g)
{
  return (size_t)g->n[0] * (size_t)g->n[1] * (size_t)g->n[2];
}

int lsdem_field_kernel_reach(double width, double h)
{
  return (int)ceil(LSDEM_FIELD_KERNEL_CUT * width / h);
}

/* the smallest m >= n whose only prime factors are 2, 3, 5, 7 (FFTW's fast sizes) */
static int fft_friendly_size(int n)
{
  for (int m = n;; m++) {
    int r = m;
    const int primes[] = {2, 3, 5, 7};
    for (int k = 0; k < 4; k++)
      while (r % primes[k] == 0) r /= primes[k];
    if (r == 1) return m;
  }
}

lsdem_status lsdem_field_grid_cover(const double lo[3], const double hi[3], double h,
                                    double width, lsdem_field_grid *g, lsdem_error *err)
{
  if (!(h > 0.0) || !(width > 0.0) || !isfinite(h) || !isfinite(width))
    return lsdem_fail(err, LSDEM_ERR_ARG, "field grid: spacing %g and width %g must be > 0",
                      h, width);
  const int pad = lsdem_field_kernel_reach(width, h) + 1;
  double total = 1.0;
  for (int k = 0; k < 3; k++) {
    if (!(hi[k] >= lo[k]) || !isfinite(hi[k] - lo[k]))
      return lsdem_fail(err, LSDEM_ERR_ARG, "field grid: empty box on axis %d", k);
    const double span = ceil((hi[k] - lo[k]) / h) + 1.0 + 2.0 * pad;
    if (span > 1 << 20)
      return lsdem_fail(err, LSDEM_ERR_NOMEM, "field grid: %.0f nodes on axis %d", span, k);
    g->n[k] = fft_friendly_size((int)span);
    g->origin[k] = lo[k] - pad * h;
    total *= g->n[k];
  }
  g->h = h;
  if (total > 2147483647.0)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "field grid: %.0f nodes (spacing %g too fine)",
                      total, h);
  return LSDEM_OK;
}

void lsdem_field_deposit(const lsdem_field_grid *g, const double x[3], int nchan,
                         const double *value, double *channels)
{
  int i0[3];
  double t[3];
  for (int k = 0; k < 3; k++) {
    const double s = (x[k] - g->origin[k]) / g->h;
    i0[k] = (int)floor(s);
    t[k] = s - i0[k];
  }
  const size_t nodes = lsdem_field_grid_nodes(g);
  for (int c = 0; c < 8; c++) {
    const int d[3] = {c & 1, (c >> 1) & 1, (c >> 2) & 1};
    const double w = (d[0] ? t[0] : 1.0 - t[0]) * (d[1] ? t[1] : 1.0 - t[1]) *
                     (d[2] ? t[2] : 1.0 - t[2]);
    const size_t node = (size_t)(i0[0] + d[0]) +
                        (size_t)g->n[0] * ((size_t)(i0[1] + d[1]) +
                                           (size_t)g->n[1] * (size_t)(i0[2] + d[2]));
    for (int ch = 0; ch < nchan; ch++) channels[(size_t)ch * nodes + node] += w * value[ch];
  }
}

void lsdem_field_kernel(const lsdem_field_grid *g, double width, double *kernel)
{
  const double cut2 = LSDEM_FIELD_KERNEL_CUT * LSDEM_FIELD_KERNEL_CUT * width * width;
  const double a = 1.0 / (2.0 * width * width);
  double sum = 0.0;
  size_t node = 0;
  for (int i2 = 0; i2 < g->n[2]; i2++)
    for (int i1 = 0; i1 < g->n[1]; i1++)
      for (int i0 = 0; i0 < g->n[0]; i0++, node++) {
        const int o[3] = {i0 <= g->n[0] / 2 ? i0 : i0 - g->n[0],
                          i1 <= g->n[1] / 2 ? i1 : i1 - g->n[1],
                          i2 <= g->n[2] / 2 ? i2 : i2 - g->n[2]};
        const double r2 = g->h * g->h * (double)(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
        kernel[node] = r2 <= cut2 ? exp(-a * r2) : 0.0;
        sum += kernel[node];
      }
  const size_t nodes = lsdem_field_grid_nodes(g);
  for (size_t k = 0; k < nodes; k++) kernel[k] /= sum;
}
