/* grid.c -- the field grid: its extent and padding, trilinear deposit, the Gaussian kernel
 * (lsdem_fields.h). */
#include "lsdem_fields.h"

#include "../base/lsdem_vec3.h"

#include <math.h>
#include <string.h>

size_t lsdem_field_grid_nodes(const lsdem_field_grid *g)
{
  return (size_t)g->n[0] * (size_t)g->n[1] * (size_t)g->n[2];
}

void lsdem_field_to_lattice(const double skew[3], const double x[3], double xi[3])
{
  const double x2 = x[2], x1 = x[1] - skew[2] * x2; /* back substitution in T xi = x */
  xi[0] = x[0] - skew[0] * x1 - skew[1] * x2;
  xi[1] = x1;
  xi[2] = x2;
}

void lsdem_field_from_lattice(const double skew[3], const double xi[3], double x[3])
{
  const double x0 = xi[0] + skew[0] * xi[1] + skew[1] * xi[2], x1 = xi[1] + skew[2] * xi[2];
  x[0] = x0;
  x[1] = x1;
  x[2] = xi[2];
}

void lsdem_field_box_skew(const lsdem_field_box *box, double skew[3])
{
  const double l[3] = {box->hi[0] - box->lo[0], box->hi[1] - box->lo[1],
                       box->hi[2] - box->lo[2]};
  skew[0] = box->tilt[0] != 0.0 ? box->tilt[0] / l[1] : 0.0; /* xy / ly */
  skew[1] = box->tilt[1] != 0.0 ? box->tilt[1] / l[2] : 0.0; /* xz / lz */
  skew[2] = box->tilt[2] != 0.0 ? box->tilt[2] / l[2] : 0.0; /* yz / lz */
}

int lsdem_field_box_rebase(const double last[3][3], const double now[3][3], double ref[3][3])
{
  /* M = now last^-1 (rows): last^-1's columns are the cross products of last's rows over
   * its determinant */
  double c[3][3];
  lsdem_cross3(last[1], last[2], c[0]);
  lsdem_cross3(last[2], last[0], c[1]);
  lsdem_cross3(last[0], last[1], c[2]);
  const double det = lsdem_dot3(last[0], c[0]);
  double M[3][3];
  int changed = 0;
  for (int k = 0; k < 3; k++)
    for (int j = 0; j < 3; j++) {
      M[k][j] = round(lsdem_dot3(now[k], c[j]) / det);
      changed |= M[k][j] != (k == j);
    }
  if (!changed) return 0;
  double r[3][3];
  for (int k = 0; k < 3; k++)
    for (int i = 0; i < 3; i++)
      r[k][i] = M[k][0] * ref[0][i] + M[k][1] * ref[1][i] + M[k][2] * ref[2][i];
  memcpy(ref, r, sizeof r);
  return 1;
}

void lsdem_field_node_position(const lsdem_field_grid *g, const int i[3], double x[3])
{
  double xi[3];
  for (int k = 0; k < 3; k++) xi[k] = g->origin[k] + g->h[k] * i[k];
  lsdem_field_from_lattice(g->skew, xi, x);
}

void lsdem_field_inverse_row(const double skew[3], int k, double row[3])
{
  /* T^-1 = [[1, -s0, s0 s2 - s1], [0, 1, -s2], [0, 0, 1]] */
  const double *s = skew;
  const double rows[3][3] = {{1.0, -s[0], s[0] * s[2] - s[1]}, {0.0, 1.0, -s[2]},
                             {0.0, 0.0, 1.0}};
  memcpy(row, rows[k], sizeof rows[k]);
}

int lsdem_field_grid_reach(const lsdem_field_grid *g, double width, int k)
{
  double row[3];
  lsdem_field_inverse_row(g->skew, k, row);
  return (int)ceil(LSDEM_FIELD_KERNEL_CUT * width * sqrt(lsdem_dot3(row, row)) / g->h[k]);
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
  return lsdem_field_grid_cover_box(NULL, lo, hi, h, width, g, err);
}

lsdem_status lsdem_field_grid_cover_box(const lsdem_field_box *box, const double lo[3],
                                        const double hi[3], double h, double width,
                                        lsdem_field_grid *g, lsdem_error *err)
{
  if (!(h > 0.0) || !(width > 0.0) || !isfinite(h) || !isfinite(width))
    return lsdem_fail(err, LSDEM_ERR_ARG, "field grid: spacing %g and width %g must be > 0",
                      h, width);
  double lattice_lo[3] = {0.0, 0.0, 0.0};
  g->skew[0] = g->skew[1] = g->skew[2] = 0.0;
  if (box) {
    lsdem_field_box_skew(box, g->skew);
    lsdem_field_to_lattice(g->skew, box->lo, lattice_lo);
  }
  for (int k = 0; k < 3; k++) g->h[k] = h; /* the open axes' (the reach's first guess) */
  double total = 1.0;
  for (int k = 0; k < 3; k++) {
    g->periodic[k] = box && box->periodic[k];
    if (g->periodic[k]) { /* one period, unpadded: the FFT's circular convolution */
      const double period = box->hi[k] - box->lo[k]; /* the period vector's lattice length */
      if (!(period > 0.0) || !isfinite(period))
        return lsdem_fail(err, LSDEM_ERR_ARG, "field grid: period %g on axis %d", period, k);
      const double span = ceil(period / h);
      if (span > 1 << 20)
        return lsdem_fail(err, LSDEM_ERR_NOMEM, "field grid: %.0f nodes on axis %d", span, k);
      g->n[k] = fft_friendly_size((int)span);
      g->h[k] = period / g->n[k];
      g->origin[k] = lattice_lo[k];
      const int reach = lsdem_field_grid_reach(g, width, k);
      if (2 * reach + 2 > g->n[k])
        return lsdem_fail(err, LSDEM_ERR_ARG, "field grid: the kernel's reach %g (3 W) is not "
                          "below half the period %g on periodic axis %d (%d + 1 of %d nodes "
                          "each way; a tilted box's skew lengthens the reach in nodes): use a "
                          "narrower kernel or a larger box",
                          LSDEM_FIELD_KERNEL_CUT * width, period, k, reach, g->n[k]);
    } else {
      if (!(hi[k] >= lo[k]) || !isfinite(hi[k] - lo[k]))
        return lsdem_fail(err, LSDEM_ERR_ARG, "field grid: empty box on axis %d", k);
      const int pad = lsdem_field_grid_reach(g, width, k) + 1;
      const double span = ceil((hi[k] - lo[k]) / h) + 1.0 + 2.0 * pad;
      if (span > 1 << 20)
        return lsdem_fail(err, LSDEM_ERR_NOMEM, "field grid: %.0f nodes on axis %d", span, k);
      g->n[k] = fft_friendly_size((int)span);
      g->origin[k] = lo[k] - pad * h;
    }
    total *= g->n[k];
  }
  if (total > 2147483647.0)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "field grid: %.0f nodes (spacing %g too fine)",
                      total, h);
  return LSDEM_OK;
}

void lsdem_field_cell(const lsdem_field_grid *g, const double x[3], size_t node[8],
                      double weight[8], double offset[8][3])
{
  int i0[3];
  double t[3], xi[3];
  lsdem_field_to_lattice(g->skew, x, xi);
  for (int k = 0; k < 3; k++) {
    const double s = (xi[k] - g->origin[k]) / g->h[k];
    i0[k] = (int)floor(s);
    t[k] = s - i0[k];
  }
  for (int c = 0; c < 8; c++) {
    const int d[3] = {c & 1, (c >> 1) & 1, (c >> 2) & 1};
    size_t index[3];
    double dxi[3];
    for (int k = 0; k < 3; k++) {
      int i = i0[k] + d[k];
      dxi[k] = xi[k] - (g->origin[k] + g->h[k] * i);
      if (g->periodic[k]) i = ((i % g->n[k]) + g->n[k]) % g->n[k]; /* the image in the period */
      index[k] = (size_t)i;
    }
    if (offset) lsdem_field_from_lattice(g->skew, dxi, offset[c]);
    weight[c] = (d[0] ? t[0] : 1.0 - t[0]) * (d[1] ? t[1] : 1.0 - t[1]) *
                (d[2] ? t[2] : 1.0 - t[2]);
    node[c] = index[0] + (size_t)g->n[0] * (index[1] + (size_t)g->n[1] * index[2]);
  }
}

void lsdem_field_deposit(const lsdem_field_grid *g, const double x[3], int nchan,
                         const double *value, double *channels)
{
  size_t node[8];
  double w[8];
  lsdem_field_cell(g, x, node, w, NULL);
  const size_t nodes = lsdem_field_grid_nodes(g);
  for (int c = 0; c < 8; c++)
    for (int ch = 0; ch < nchan; ch++) channels[(size_t)ch * nodes + node[c]] += w[c] * value[ch];
}

void lsdem_field_kernel(const lsdem_field_grid *g, double width, double *kernel)
{
  lsdem_field_kernel_moment(g, width, 0, kernel);
}

void lsdem_field_kernel_moment(const lsdem_field_grid *g, double width, int which,
                               double *kernel)
{
  static const int SYM_I[6] = {0, 0, 0, 1, 1, 2}, SYM_J[6] = {0, 1, 2, 1, 2, 2};
  const double cut2 = LSDEM_FIELD_KERNEL_CUT * LSDEM_FIELD_KERNEL_CUT * width * width;
  const double a = 1.0 / (2.0 * width * width);
  double sum = 0.0;
  size_t node = 0;
  for (int i2 = 0; i2 < g->n[2]; i2++)
    for (int i1 = 0; i1 < g->n[1]; i1++)
      for (int i0 = 0; i0 < g->n[0]; i0++, node++) {
        const int i[3] = {i0, i1, i2};
        double rxi[3], r[3]; /* r = source - target = -(the periodic offset) */
        for (int k = 0; k < 3; k++)
          rxi[k] = -(i[k] <= g->n[k] / 2 ? i[k] : i[k] - g->n[k]) * g->h[k];
        lsdem_field_from_lattice(g->skew, rxi, r);
        const double r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
        const double G = r2 <= cut2 ? exp(-a * r2) : 0.0;
        sum += G;
        kernel[node] = which == 0  ? G
                       : which < 4 ? G * r[which - 1]
                                   : G * r[SYM_I[which - 4]] * r[SYM_J[which - 4]];
      }
  const size_t nodes = lsdem_field_grid_nodes(g);
  for (size_t k = 0; k < nodes; k++) kernel[k] /= sum;
}
