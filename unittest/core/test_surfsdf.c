/* Star-shaped surfaces (surfsdf.c) and the superellipsoid: the distance grid against the
 * exact ellipsoid distance, volumes against the closed-form superellipsoid volume,
 * |grad phi| near the surface, the analytic approximation's zero set. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <math.h>
#include <stdlib.h>

static const double PI = 3.14159265358979323846;

static lsdem_sdf superellipsoid(double a, double b, double c, double e1, double e2)
{
  lsdem_sdf s = {LSDEM_SDF_SUPERELLIPSOID, 0, {a, b, c, e1, e2}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL};
  return s;
}

/* Jaklic et al. (2000): V = 2 a b c e1 e2 B(e1/2 + 1, e1) B(e2/2, e2/2). */
static double beta(double x, double y)
{
  return exp(lgamma(x) + lgamma(y) - lgamma(x + y));
}

static double superellipsoid_volume(const lsdem_sdf *s)
{
  const double e1 = s->a[3], e2 = s->a[4];
  return 2.0 * s->a[0] * s->a[1] * s->a[2] * e1 * e2 * beta(0.5 * e1 + 1.0, e1) *
         beta(0.5 * e2, 0.5 * e2);
}

static lsdem_grid sample(const lsdem_sdf *s, double h)
{
  const double lo[3] = {-s->a[0], -s->a[1], -s->a[2]};
  lsdem_grid g;
  lsdem_error err;
  const lsdem_status st = lsdem_grid_sample(s, lo, s->a, h, 3, &g, &err);
  CHECK(st == LSDEM_OK, "%s", "");
  return g;
}

/* e1 = e2 = 1 is the ellipsoid: the grid must match the exact ellipsoid distance. */
static void test_ellipsoid_case(void)
{
  const lsdem_sdf se = superellipsoid(1.0, 0.7, 0.5, 1.0, 1.0);
  const lsdem_sdf el = {LSDEM_SDF_ELLIPSOID, 0, {1.0, 0.7, 0.5}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL};
  const double h = 0.05;
  lsdem_grid g = sample(&se, h);
  double band_max = 0.0, all_max = 0.0, gr[3];
  size_t m = 0;
  int sign_bad = 0;
  for (int k = 0; k < g.n[2]; k++)
    for (int j = 0; j < g.n[1]; j++)
      for (int i = 0; i < g.n[0]; i++, m++) {
        const double p[3] = {g.origin[0] + h * i, g.origin[1] + h * j, g.origin[2] + h * k};
        const double exact = lsdem_sdf_eval(&el, p, gr), err = fabs(g.phi[m] - exact);
        all_max = fmax(all_max, err);
        if (fabs(exact) < 2.0 * h) band_max = fmax(band_max, err);
        if ((g.phi[m] < 0.0f) != (exact < 0.0) && fabs(exact) > 1e-6) sign_bad++;
      }
  printf("superellipsoid(1,1) vs ellipsoid: max error %.4f h in the band, %.4f h overall\n",
         band_max / h, all_max / h);
  CHECK(sign_bad == 0, "%s", "");
  CHECK(band_max < 0.05 * h, "%s", "");
  CHECK(all_max < 0.1 * h, "%s", "");
  lsdem_grid_free(&g);
}

static void test_volumes(void)
{
  const double e[4][2] = {{1.0, 1.0}, {0.5, 0.3}, {2.0, 2.0}, {0.2, 1.5}};
  for (int c = 0; c < 4; c++) {
    const lsdem_sdf s = superellipsoid(1.0, 0.8, 0.6, e[c][0], e[c][1]);
    const double exact = superellipsoid_volume(&s);
    lsdem_massprops q, mg;
    lsdem_error err;
    CHECK(lsdem_star_massprops(lsdem_superellipsoid_radius, &s, 256, &q, &err) == LSDEM_OK, "%s", "");
    lsdem_grid g = sample(&s, 0.04);
    CHECK(lsdem_massprops_grid(&g, 2, &mg, &err) == LSDEM_OK, "%s", "");
    printf("e = (%g, %g): volume exact %.6f, quadrature %+.4f%%, grid %+.3f%%\n", e[c][0],
           e[c][1], exact, 100 * (q.volume / exact - 1), 100 * (mg.volume / exact - 1));
    CHECK_REL(q.volume, exact, 1e-3);
    CHECK_REL(mg.volume, exact, 0.01);
    /* symmetric solid: centroid at the origin, principal moments agree between paths */
    for (int a = 0; a < 3; a++) {
      CHECK(fabs(q.centroid[a]) < 1e-6, "%s", "");
      CHECK_REL(mg.principal[a], q.principal[a], 0.02);
    }
    lsdem_grid_free(&g);
  }
}

/* |grad phi| of the grid within 2 h of the surface: a distance function has 1. */
static void test_gradient_norm(void)
{
  const lsdem_sdf s = superellipsoid(1.0, 0.8, 0.6, 0.4, 0.6);
  const double h = 0.05;
  lsdem_grid g = sample(&s, h);
  double sum = 0.0;
  int n = 0;
  uint64_t state = 7;
  for (int t = 0; t < 20000; t++) {
    double p[3], gr[3];
    for (int a = 0; a < 3; a++) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      p[a] = (2.0 * (double)(state >> 11) / 9007199254740992.0 - 1.0) * 1.1 * s.a[a];
    }
    if (fabs(lsdem_grid_value(&g, p)) > 2.0 * h) continue;
    lsdem_grid_gradient_raw(&g, p, gr);
    sum += sqrt(gr[0] * gr[0] + gr[1] * gr[1] + gr[2] * gr[2]);
    n++;
  }
  printf("superellipsoid grid: mean |grad phi| = %.4f over %d band points\n", sum / n, n);
  CHECK(n > 1000, "%s", "");
  CHECK_NEAR(sum / n, 1.0, 0.03);
  lsdem_grid_free(&g);
}

/* The analytic kind's first-order distance: zero on the surface points radius(u) u,
 * negative inside, gradient along the grid's normal there. */
static void test_analytic_zero_set(void)
{
  const lsdem_sdf s = superellipsoid(1.0, 0.8, 0.6, 0.5, 0.8);
  lsdem_grid g = sample(&s, 0.04);
  double worst = 0.0, worst_dot = 1.0;
  for (int t = 0; t < 500; t++) {
    const double z = -1.0 + 2.0 * (t + 0.5) / 500.0, ph = 2.4 * t, r = sqrt(1.0 - z * z);
    const double u[3] = {r * cos(ph), r * sin(ph), z};
    const double R = lsdem_superellipsoid_radius(u, &s);
    double p[3] = {R * u[0], R * u[1], R * u[2]}, ga[3], gg[3];
    worst = fmax(worst, fabs(lsdem_sdf_eval(&s, p, ga)));
    lsdem_grid_eval(&g, p, gg);
    worst_dot = fmin(worst_dot, ga[0] * gg[0] + ga[1] * gg[1] + ga[2] * gg[2]);
    const double in[3] = {0.9 * p[0], 0.9 * p[1], 0.9 * p[2]};
    CHECK(lsdem_sdf_eval(&s, in, ga) < 0.0, "%s", "");
  }
  printf("analytic superellipsoid: |phi| on the surface <= %.2e, normal . grid normal >= %.4f\n",
         worst, worst_dot);
  CHECK(worst < 1e-12, "%s", "");
  CHECK(worst_dot > 0.95, "%s", "");
  CHECK(lsdem_sdf_bound_radius(&s) >= 1.0, "%s", "");
  lsdem_grid_free(&g);
}

/* Addition theorem: sum_m Y_lm(u)^2 = (2l+1)/(4 pi); orthonormality by quadrature. */
static void test_harmonics(void)
{
  enum { L = 8, N = (L + 1) * (L + 1) };
  double Y[N];
  const double u[3] = {0.36, -0.48, 0.8};
  double table[N], Yt[N];
  lsdem_sph_harmonics_table(L, table);
  lsdem_sph_harmonics(L, u, NULL, Y);
  lsdem_sph_harmonics(L, u, table, Yt);
  for (int a = 0; a < N; a++) CHECK(Y[a] == Yt[a], "table changes Y[%d]", a);
  for (int l = 0; l <= L; l++) {
    double s = 0.0;
    for (int m = -l; m <= l; m++) s += Y[l * l + l + m] * Y[l * l + l + m];
    CHECK_REL(s, (2.0 * l + 1.0) / (4.0 * PI), 1e-12);
  }
  static double G[N][N];
  const int nt = 60;
  for (int i = 0; i < nt; i++) /* Gauss would be exact; the midpoint rule is close enough */
    for (int j = 0; j < 2 * nt; j++) {
      const double th = PI * (i + 0.5) / nt, ph = PI * (j + 0.5) / nt;
      const double v[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
      const double w = sin(th) * (PI / nt) * (PI / nt);
      lsdem_sph_harmonics(L, v, table, Y);
      for (int a = 0; a < N; a++)
        for (int b = 0; b < N; b++) G[a][b] += w * Y[a] * Y[b];
    }
  double off = 0.0, diag = 0.0;
  for (int a = 0; a < N; a++)
    for (int b = 0; b < N; b++) {
      if (a == b) diag = fmax(diag, fabs(G[a][b] - 1.0));
      else off = fmax(off, fabs(G[a][b]));
    }
  printf("harmonics: Gram matrix |diag - 1| <= %.1e, |off-diagonal| <= %.1e\n", diag, off);
  CHECK(diag < 2e-3, "%s", "");
  CHECK(off < 2e-3, "%s", "");
}

int main(void)
{
  test_ellipsoid_case();
  test_volumes();
  test_gradient_norm();
  test_analytic_zero_set();
  test_harmonics();
  return lsdem_test_summary();
}
