/* levelset.c -- signed-distance grids: trilinear value and gradient (report Algorithm 1),
 * validation, freeing (grids are made in prep/grid_sample.c).
 *
 * Grid coordinates: u = (p - origin) / h, sample (i,j,k) at u = (i,j,k), index
 * i + n0*(j + n1*k) (x fastest). The interpolation box is [0, n-1] on each axis. */
#include "lsdem_geom.h"
#include "trilinear.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

/* The cell of grid coordinates u inside [0, n-1]^3: its (0,0,0) sample's index, and the
 * fractions f within it. The cell index is clamped to n-2 so points on the upper face
 * use the last cell with fraction 1. */
static inline size_t cell_of(const lsdem_grid *g, const double u[3], double f[3])
{
  const int n0 = g->n[0], n1 = g->n[1];
  int i = (int)u[0], j = (int)u[1], k = (int)u[2];
  i = i > n0 - 2 ? n0 - 2 : i;
  j = j > n1 - 2 ? n1 - 2 : j;
  k = k > g->n[2] - 2 ? g->n[2] - 2 : k;
  f[0] = u[0] - i;
  f[1] = u[1] - j;
  f[2] = u[2] - k;
  return (size_t)i + (size_t)n0 * ((size_t)j + (size_t)n1 * (size_t)k);
}

/* The 8 samples of the cell whose (0,0,0) sample is at index c. */
static inline void load_cell(const lsdem_grid *g, size_t c, float v[8])
{
  load_cell_strided(g->phi + c, (size_t)g->n[0], (size_t)g->n[0] * (size_t)g->n[1], v);
}

/* Trilinear interpolation at grid coordinates u inside [0, n-1]^3. */
static inline double trilinear(const lsdem_grid *g, const double u[3], double du[3])
{
  double f[3];
  float v[8];
  load_cell(g, cell_of(g, u, f), v);
  return trilinear_cell(v, f, du);
}

/* Grid coordinates of p, inv_h = 1 / h (a caller doing many lookups divides once);
 * returns nonzero when p lies in the interpolation box. A NaN coordinate fails every
 * comparison and so counts as outside. */
static inline int grid_coords(const lsdem_grid *g, double inv_h, const double p[3],
                              double u[3])
{
  u[0] = (p[0] - g->origin[0]) * inv_h;
  u[1] = (p[1] - g->origin[1]) * inv_h;
  u[2] = (p[2] - g->origin[2]) * inv_h;
  return u[0] >= 0.0 && u[0] <= g->n[0] - 1 && u[1] >= 0.0 && u[1] <= g->n[1] - 1 &&
         u[2] >= 0.0 && u[2] <= g->n[2] - 1;
}

/* Outside rule: phi(clamp(p)) + |p - clamp(p)|; grad is the unit vector from clamp(p)
 * towards p. Correct for a grid with positive values on its boundary: it is a lower
 * bound of the distance and never negative there. */
static double outside_value(const lsdem_grid *g, const double u[3], double grad[3])
{
  double uc[3], d[3];
  for (int a = 0; a < 3; a++) {
    uc[a] = lsdem_min(lsdem_max(u[a], 0.0), (double)(g->n[a] - 1));
    d[a] = (u[a] - uc[a]) * g->h;
  }
  const double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (grad) {
    for (int a = 0; a < 3; a++) grad[a] = d[a] / dist;
  }
  return trilinear(g, uc, NULL) + dist;
}

/* lsdem_grid_eval with 1/h given. */
static inline double grid_eval(const lsdem_grid *g, double inv_h, const double p[3],
                               double grad[3])
{
  double u[3];
  if (!grid_coords(g, inv_h, p, u)) return outside_value(g, u, grad);
  double du[3];
  const double phi = trilinear(g, u, du);
  unit_gradient(du, grad);
  return phi;
}

/* grid_eval with the cell's samples taken from `cell` when it holds p's cell, else read
 * from the grid into it (index -1 outside the box). */
static inline double grid_eval_cached(const lsdem_grid *g, double inv_h, const double p[3],
                                      double grad[3], lsdem_grid_cell *cell)
{
  double u[3];
  if (!grid_coords(g, inv_h, p, u)) {
    cell->index = -1;
    return outside_value(g, u, grad);
  }
  double f[3], du[3];
  const size_t c = cell_of(g, u, f);
  if (cell->index != (int64_t)c) {
    load_cell(g, c, cell->v);
    cell->index = (int64_t)c;
  }
  const double phi = trilinear_cell(cell->v, f, du);
  unit_gradient(du, grad);
  return phi;
}

void lsdem_grid_eval_many_cached(const lsdem_grid *g, int n, const double *p, double *phi,
                                 double *grad, lsdem_grid_cell *cells)
{
  const double inv_h = 1.0 / g->h;
  for (int m = 0; m < n; m++)
    phi[m] = grid_eval_cached(g, inv_h, &p[3 * m], &grad[3 * m], &cells[m]);
}

double lsdem_grid_eval(const lsdem_grid *g, const double p[3], double grad[3])
{
  return grid_eval(g, 1.0 / g->h, p, grad);
}

/* The lookups of a batch are independent of each other: done back to back (not
 * interleaved with the contact forces of the penetrating ones) their cache misses
 * overlap in the out-of-order window. 1/h is computed once. (Explicit prefetching of the
 * cells first measured no further gain on the reference benchmark.) */
void lsdem_grid_eval_many(const lsdem_grid *g, int n, const double *p, double *phi,
                          double *grad)
{
  const double inv_h = 1.0 / g->h;
  for (int m = 0; m < n; m++) phi[m] = grid_eval(g, inv_h, &p[3 * m], &grad[3 * m]);
}

int lsdem_grid_box_contains(const lsdem_grid *g, const double p[3])
{
  for (int a = 0; a < 3; a++) {
    const double u = (p[a] - g->origin[a]) / g->h;
    if (!(u >= 0.0 && u <= (double)(g->n[a] - 1))) return 0;
  }
  return 1;
}

double lsdem_grid_value(const lsdem_grid *g, const double p[3])
{
  double u[3];
  if (!grid_coords(g, 1.0 / g->h, p, u)) return outside_value(g, u, NULL);
  return trilinear(g, u, NULL);
}

void lsdem_grid_gradient_raw(const lsdem_grid *g, const double p[3], double grad[3])
{
  double u[3];
  const double inv_h = 1.0 / g->h;
  if (!grid_coords(g, inv_h, p, u)) {
    grad[0] = grad[1] = grad[2] = 0.0;
    return;
  }
  double du[3];
  trilinear(g, u, du);
  for (int a = 0; a < 3; a++) grad[a] = du[a] * inv_h;
}

static inline float absdiff(float a, float b) { return a > b ? a - b : b - a; }

static inline float max2f(float a, float b) { return a > b ? a : b; }

/* The largest b_x^2 + b_y^2 + b_z^2 over the cells of one row of cells (j,k fixed, x
 * varying) that have a corner with phi >= 0, b_a being the cell's largest |edge
 * difference| along axis a; r00, r10, r01, r11 are the sample rows (j,k), (j+1,k),
 * (j,k+1), (j+1,k+1). */
static double row_worst_edges(const float *r00, const float *r10, const float *r01,
                              const float *r11, int ncells)
{
  double worst = 0.0;
  for (int i = 0; i < ncells; i++) {
    const float v000 = r00[i], v100 = r00[i + 1], v010 = r10[i], v110 = r10[i + 1];
    const float v001 = r01[i], v101 = r01[i + 1], v011 = r11[i], v111 = r11[i + 1];
    const float hi = max2f(max2f(max2f(v000, v100), max2f(v010, v110)),
                           max2f(max2f(v001, v101), max2f(v011, v111)));
    if (hi < 0.0f) continue; /* phi < 0 throughout */
    const double bx = max2f(max2f(absdiff(v100, v000), absdiff(v110, v010)),
                            max2f(absdiff(v101, v001), absdiff(v111, v011)));
    const double by = max2f(max2f(absdiff(v010, v000), absdiff(v110, v100)),
                            max2f(absdiff(v011, v001), absdiff(v111, v101)));
    const double bz = max2f(max2f(absdiff(v001, v000), absdiff(v101, v100)),
                            max2f(absdiff(v011, v010), absdiff(v111, v110)));
    const double b2 = bx * bx + by * by + bz * bz;
    worst = b2 > worst ? b2 : worst;
  }
  return worst;
}

/* Smallest sample on the grid box's six faces. */
static double boundary_min(const lsdem_grid *g)
{
  const int n0 = g->n[0], n1 = g->n[1], n2 = g->n[2];
  double lo = HUGE_VAL;
  for (int k = 0; k < n2; k++)
    for (int j = 0; j < n1; j++)
      for (int i = 0; i < n0; i++) {
        if (i && j && k && i < n0 - 1 && j < n1 - 1 && k < n2 - 1) continue;
        lo = fmin(lo, (double)g->phi[i + (size_t)n0 * (j + (size_t)n1 * k)]);
      }
  return lo;
}

double lsdem_grid_outer_lipschitz(const lsdem_grid *g, double *reach_limit)
{
  const size_t sy = (size_t)g->n[0], sz = sy * (size_t)g->n[1];
  double worst = 0.0;
  for (size_t k = 0; k + 1 < (size_t)g->n[2]; k++)
    for (size_t j = 0; j + 1 < (size_t)g->n[1]; j++) {
      const float *r00 = g->phi + j * sy + k * sz;
      worst = fmax(worst, row_worst_edges(r00, r00 + sy, r00 + sz, r00 + sz + sy, g->n[0] - 1));
    }
  const double edge = boundary_min(g);
  *reach_limit = edge > 0.0 ? edge : 0.0;
  return sqrt(worst) / g->h;
}

/* Validation: every condition the lookups rely on, each with its own message. */
lsdem_status lsdem_grid_check(const lsdem_grid *g, lsdem_error *err)
{
  if (!g) return lsdem_fail(err, LSDEM_ERR_ARG, "grid is NULL");
  for (int a = 0; a < 3; a++) {
    if (g->n[a] < 2)
      return lsdem_fail(err, LSDEM_ERR_ARG,
                        "grid size n[%d] = %d: need at least 2 samples per axis", a, g->n[a]);
  }
  const size_t limit = SIZE_MAX / sizeof(float);
  const size_t n01 = (size_t)g->n[0] * (size_t)g->n[1];
  if (n01 > limit / (size_t)g->n[2])
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "grid size %d x %d x %d overflows", g->n[0],
                      g->n[1], g->n[2]);
  if (!(g->h > 0.0) || !isfinite(g->h))
    return lsdem_fail(err, LSDEM_ERR_ARG, "grid spacing h = %g: must be positive and finite",
                      g->h);
  for (int a = 0; a < 3; a++) {
    if (!isfinite(g->origin[a]))
      return lsdem_fail(err, LSDEM_ERR_NUMERIC, "grid origin[%d] is not finite", a);
  }
  if (!g->phi) return lsdem_fail(err, LSDEM_ERR_ARG, "grid values are NULL");
  const size_t count = n01 * (size_t)g->n[2];
  for (size_t m = 0; m < count; m++) {
    if (!isfinite(g->phi[m])) {
      const size_t i = m % (size_t)g->n[0], j = (m / (size_t)g->n[0]) % (size_t)g->n[1];
      const size_t k = m / n01;
      return lsdem_fail(err, LSDEM_ERR_NUMERIC, "grid value at (%zu, %zu, %zu) is %g", i, j,
                        k, (double)g->phi[m]);
    }
  }
  return LSDEM_OK;
}

void lsdem_grid_free(lsdem_grid *g)
{
  if (!g) return;
  free((void *)g->phi);
  g->phi = NULL;
}

double lsdem_grid_spacing_limit(double volume)
{
  return 0.1 * cbrt(3.0 * volume / (4.0 * 3.14159265358979323846));
}

int lsdem_grid_is_coarse(double h, double volume)
{
  return h > lsdem_grid_spacing_limit(volume) * (1.0 + 1e-5);
}

int lsdem_grid_has_solid(const lsdem_grid *g)
{
  const size_t ns = (size_t)g->n[0] * (size_t)g->n[1] * (size_t)g->n[2];
  for (size_t k = 0; k < ns; k++)
    if (g->phi[k] < 0.0f) return 1;
  return 0;
}
