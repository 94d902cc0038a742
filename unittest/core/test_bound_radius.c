/* test_bound_radius.c -- lsdem_sdf_bound_radius of grids: it must contain every point a
 * lookup calls solid (lsdem_grid_value < 0), inside and outside the grid box, and be tight.
 * Expectation from a second path: a brute-force march along many rays from far outside
 * towards the centre finds the outermost solid point in each direction; the largest of
 * those is a lower bound of the true extent, and the analytic semi-axis gives the scale. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <stdlib.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Outermost t in [0, tmax] with value(t u) < 0 (step h/20, then bisection), or -1. */
static double outermost_solid(const lsdem_grid *g, const double u[3], double tmax)
{
  const double step = g->h / 20.0;
  for (double t = tmax; t >= 0.0; t -= step) {
    const double p[3] = {t * u[0], t * u[1], t * u[2]};
    if (!(lsdem_grid_value(g, p) < 0.0)) continue;
    double in = t, out = t + step;
    for (int it = 0; it < 40; it++) {
      const double mid = 0.5 * (in + out), q[3] = {mid * u[0], mid * u[1], mid * u[2]};
      if (lsdem_grid_value(g, q) < 0.0)
        in = mid;
      else
        out = mid;
    }
    return in;
  }
  return -1.0;
}

/* Largest outermost solid point over the 6 axis directions and n Fibonacci directions. */
static double brute_force_extent(const lsdem_grid *g, int n, double tmax)
{
  double best = 0.0;
  for (int m = 0; m < n + 6; m++) {
    double u[3] = {0.0, 0.0, 0.0};
    if (m < 6) {
      u[m / 2] = m % 2 ? -1.0 : 1.0;
    } else {
      const int k = m - 6;
      const double z = 1.0 - (2.0 * k + 1.0) / n, rho = sqrt(1.0 - z * z);
      const double phi = k * M_PI * (3.0 - sqrt(5.0));
      u[0] = rho * cos(phi);
      u[1] = rho * sin(phi);
      u[2] = z;
    }
    best = fmax(best, outermost_solid(g, u, tmax));
  }
  return best;
}

static lsdem_sdf grid_of(lsdem_sdf_kind kind, const double a[3], const double lo[3],
                         const double hi[3], double h, int margin)
{
  lsdem_sdf s = {kind, 0, {a[0], a[1], a[2]}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL};
  lsdem_sdf g = {LSDEM_SDF_GRID, 0, {0}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL};
  lsdem_error err;
  CHECK(lsdem_grid_sample(&s, lo, hi, h, margin, &g.grid, &err) == LSDEM_OK, "%s", err.msg);
  return g;
}

/* A closed grid: bound >= brute-force extent, and within 0.03 h (refinement) + the
 * interpolation error of the tip above the analytic extent. */
static void check_closed(lsdem_sdf_kind kind, const double a[3], double h, double amax,
                         const char *what)
{
  const double lo[3] = {-a[0], -a[1], -a[2]}, hi[3] = {a[0], a[1], a[2]};
  lsdem_sdf g = grid_of(kind, a, lo, hi, h, 2);
  const double r = lsdem_sdf_bound_radius(&g);
  const double brute = brute_force_extent(&g.grid, 4000, amax + 3.0 * h);
  printf("%s h=%g: bound %.6f, brute-force extent %.6f, analytic %.6f\n", what, h, r, brute,
         amax);
  CHECK(r >= brute, "%s: bound %.9g below a solid point at %.9g", what, r, brute);
  CHECK(r - brute <= 0.05 * h, "%s: bound %.9g not tight (extent %.9g)", what, r, brute);
  CHECK(fabs(r - amax) <= 0.1 * h, "%s: bound %g vs analytic %g", what, r, amax);
  lsdem_grid_free(&g.grid);
}

/* An open grid (negative samples on its border): the outside rule extends the solid
 * beyond the box, and the bound must still contain it. */
static void check_open(void)
{
  const double a[3] = {1.0, 1.0, 1.0}, lo[3] = {-0.7, -0.7, -0.7}, hi[3] = {0.7, 0.7, 0.7};
  lsdem_sdf g = grid_of(LSDEM_SDF_SPHERE, a, lo, hi, 0.1, 0);
  const double r = lsdem_sdf_bound_radius(&g);
  const double brute = brute_force_extent(&g.grid, 2000, 3.0);
  printf("open grid: bound %.6f, brute-force extent %.6f\n", r, brute);
  CHECK(brute > 0.75, "the test needs solid outside the box (%g)", brute);
  CHECK(r >= brute, "open grid: bound %.9g below a solid point at %.9g", r, brute);
  lsdem_grid_free(&g.grid);
}

int main(void)
{
  const double sphere[3] = {1.0, 1.0, 1.0}, ell[3] = {10.0, 8.0, 6.0};
  check_closed(LSDEM_SDF_SPHERE, sphere, 0.1, 1.0, "sphere");
  check_closed(LSDEM_SDF_SPHERE, sphere, 0.37, 1.0, "coarse sphere");
  check_closed(LSDEM_SDF_ELLIPSOID, ell, 1.0, 10.0, "ellipsoid");
  check_open();
  return lsdem_test_summary();
}
