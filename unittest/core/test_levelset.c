/* test_levelset.c -- trilinear grid lookups (report Algorithm 1), the outside rule,
 * grid validation and sampling. Expected values come from closed-form fields. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>


/* f = c0 + c1 x + c2 y + c3 z + c4 xy + c5 xz + c6 yz + c7 xyz and its gradient */
static double trilin(const double c[8], const double p[3])
{
  const double x = p[0], y = p[1], z = p[2];
  return c[0] + c[1] * x + c[2] * y + c[3] * z + c[4] * x * y + c[5] * x * z + c[6] * y * z +
         c[7] * x * y * z;
}
static void trilin_grad(const double c[8], const double p[3], double g[3])
{
  const double x = p[0], y = p[1], z = p[2];
  g[0] = c[1] + c[4] * y + c[5] * z + c[7] * y * z;
  g[1] = c[2] + c[4] * x + c[6] * z + c[7] * x * z;
  g[2] = c[3] + c[5] * x + c[6] * y + c[7] * x * y;
}

static float *fill_grid(lsdem_grid *g, const double c[8])
{
  const size_t count = (size_t)g->n[0] * g->n[1] * g->n[2];
  float *phi = malloc(count * sizeof(float));
  size_t m = 0;
  for (int k = 0; k < g->n[2]; k++)
    for (int j = 0; j < g->n[1]; j++)
      for (int i = 0; i < g->n[0]; i++) {
        const double p[3] = {g->origin[0] + g->h * i, g->origin[1] + g->h * j,
                             g->origin[2] + g->h * k};
        phi[m++] = (float)trilin(c, p);
      }
  g->phi = phi;
  return phi;
}

static void random_inside(const lsdem_grid *g, double p[3])
{
  for (int a = 0; a < 3; a++) p[a] = g->origin[a] + g->h * (g->n[a] - 1) * urand();
}

/* Integer coefficients on a grid of spacing 1/2 at quarter-integer origin: every sample
 * is exactly representable as a float, so interpolation must reproduce the field to
 * double round-off. */
static void test_trilinear_exact(void)
{
  lsdem_grid g = {{7, 5, 9}, 0.5, {-1.5, -1.0, 0.25}, NULL, 0.0, 0.0};
  double worst_v = 0, worst_g = 0, worst_unit = 0, worst_dir = 0;
  for (int field = 0; field < 20; field++) {
    double c[8];
    for (int i = 0; i < 8; i++) c[i] = (double)((int)(9 * urand()) - 4);
    float *phi = fill_grid(&g, c);
    for (int t = 0; t < 500; t++) {
      double p[3], ga[3], gr[3], gn[3];
      random_inside(&g, p);
      const double scale = 1.0 + fabs(trilin(c, p));
      worst_v = fmax(worst_v, fabs(lsdem_grid_value(&g, p) - trilin(c, p)) / scale);
      const double v = lsdem_grid_eval(&g, p, gn);
      worst_v = fmax(worst_v, fabs(v - trilin(c, p)) / scale);
      trilin_grad(c, p, ga);
      lsdem_grid_gradient_raw(&g, p, gr);
      const double na = sqrt(ga[0] * ga[0] + ga[1] * ga[1] + ga[2] * ga[2]);
      for (int a = 0; a < 3; a++) worst_g = fmax(worst_g, fabs(gr[a] - ga[a]) / (1 + na));
      worst_unit = fmax(worst_unit, fabs(sqrt(gn[0] * gn[0] + gn[1] * gn[1] + gn[2] * gn[2]) - 1));
      if (na > 1e-6)
        for (int a = 0; a < 3; a++) worst_dir = fmax(worst_dir, fabs(gn[a] - ga[a] / na));
    }
    free(phi);
  }
  CHECK(worst_v < 1e-14, "trilinear field reproduced: rel err %g", worst_v);
  CHECK(worst_g < 1e-13, "trilinear gradient reproduced: rel err %g", worst_g);
  CHECK(worst_unit < 1e-15, "normalised gradient has unit length: %g", worst_unit);
  CHECK(worst_dir < 1e-12, "normalised gradient direction: %g", worst_dir);
}

/* General random coefficients and spacing: exact up to the float rounding of samples. */
static void test_trilinear_random(void)
{
  lsdem_grid g = {{11, 6, 8}, 0.37, {0.3, -2.1, 1.7}, NULL, 0.0, 0.0};
  double c[8];
  for (int i = 0; i < 8; i++) c[i] = 2.0 * urand() - 1.0;
  float *phi = fill_grid(&g, c);
  double fmaxabs = 0; /* largest sample: bounds float rounding */
  for (int m = 0; m < g.n[0] * g.n[1] * g.n[2]; m++) fmaxabs = fmax(fmaxabs, fabs(phi[m]));
  double worst = 0;
  for (int t = 0; t < 2000; t++) {
    double p[3];
    random_inside(&g, p);
    worst = fmax(worst, fabs(lsdem_grid_value(&g, p) - trilin(c, p)));
  }
  CHECK(worst <= 1.2e-7 * fmaxabs, "random trilinear field: err %g, float eps*max %g", worst,
        6e-8 * fmaxabs);
  free(phi);
}

static void test_linear_gradient(void)
{
  /* phi = 0.3 + 0.6x - 0.48y + 0.64z: a unit-gradient (exact SDF of a plane) */
  lsdem_grid g = {{4, 4, 4}, 0.25, {-0.5, -0.5, -0.5}, NULL, 0.0, 0.0};
  const double c[8] = {0.3, 0.6, -0.48, 0.64, 0, 0, 0, 0};
  float *phi = fill_grid(&g, c);
  for (int t = 0; t < 200; t++) {
    double p[3], gr[3], gn[3];
    random_inside(&g, p);
    lsdem_grid_gradient_raw(&g, p, gr);
    lsdem_grid_eval(&g, p, gn);
    for (int a = 0; a < 3; a++) {
      CHECK_NEAR(gr[a], c[1 + a], 1e-6); /* float samples: ~1e-7 relative */
      CHECK_NEAR(gn[a], c[1 + a], 1e-6);
    }
  }
  free(phi);
}

static void test_boundary_and_outside(void)
{
  lsdem_grid g = {{5, 6, 7}, 0.5, {-1.0, -1.5, -2.0}, NULL, 0.0, 0.0};
  const double c[8] = {2.0, 1.0, -1.0, 0.5, 0.25, 0, -0.5, 0.125};
  float *phi = fill_grid(&g, c);
  const double hi[3] = {g.origin[0] + g.h * 4, g.origin[1] + g.h * 5, g.origin[2] + g.h * 6};
  /* exactly on the upper faces, edges and corner: the last cell with fraction 1 */
  for (int mask = 1; mask < 8; mask++) {
    double p[3], gr[3], ga[3];
    for (int a = 0; a < 3; a++)
      p[a] = (mask >> a & 1) ? hi[a] : g.origin[a] + g.h * (1 + 0.37 * a);
    CHECK_NEAR(lsdem_grid_value(&g, p), trilin(c, p), 1e-13);
    lsdem_grid_gradient_raw(&g, p, gr);
    trilin_grad(c, p, ga);
    for (int a = 0; a < 3; a++) CHECK_NEAR(gr[a], ga[a], 1e-12);
  }
  CHECK_NEAR(lsdem_grid_value(&g, hi), (double)phi[5 * 6 * 7 - 1], 0.0);
  CHECK_NEAR(lsdem_grid_value(&g, g.origin), (double)phi[0], 0.0);
  /* outside: phi(clamp(p)) + |p - clamp(p)|, grad from clamp(p) towards p */
  for (int t = 0; t < 500; t++) {
    double p[3], cl[3], grad[3], d2 = 0, raw[3];
    for (int a = 0; a < 3; a++) {
      p[a] = g.origin[a] - 2.0 + (hi[a] - g.origin[a] + 4.0) * urand();
      cl[a] = p[a] < g.origin[a] ? g.origin[a] : p[a] > hi[a] ? hi[a] : p[a];
      d2 += (p[a] - cl[a]) * (p[a] - cl[a]);
    }
    if (d2 == 0.0) continue;
    const double d = sqrt(d2);
    const double v = lsdem_grid_eval(&g, p, grad);
    CHECK_NEAR(v, trilin(c, cl) + d, 1e-12);
    CHECK_NEAR(lsdem_grid_value(&g, p), trilin(c, cl) + d, 1e-12);
    for (int a = 0; a < 3; a++) CHECK_NEAR(grad[a], (p[a] - cl[a]) / d, 1e-12);
    lsdem_grid_gradient_raw(&g, p, raw);
    CHECK(raw[0] == 0 && raw[1] == 0 && raw[2] == 0, "raw gradient is zero outside");
  }
  /* NaN position: answered as outside (NaN), never an out-of-range read */
  const double pn[3] = {NAN, 0, 0};
  double gn[3];
  CHECK(isnan(lsdem_grid_eval(&g, pn, gn)), "NaN in, NaN out");
  free(phi);
  /* a constant field has zero gradient: +x by convention */
  const double c0[8] = {1, 0, 0, 0, 0, 0, 0, 0};
  phi = fill_grid(&g, c0);
  double gz[3];
  const double pc[3] = {0.1, 0.2, 0.3};
  lsdem_grid_eval(&g, pc, gz);
  CHECK(gz[0] == 1.0 && gz[1] == 0.0 && gz[2] == 0.0, "zero gradient -> +x");
  free(phi);
}

static void test_check(void)
{
  float vals[8] = {1, 1, 1, 1, 1, 1, 1, 1};
  lsdem_grid g = {{2, 2, 2}, 1.0, {0, 0, 0}, vals, 0.0, 0.0};
  lsdem_error err;
  CHECK(lsdem_grid_check(&g, &err) == LSDEM_OK, "valid grid");
  lsdem_grid b = g;
  b.n[1] = 1;
  CHECK(lsdem_grid_check(&b, &err) == LSDEM_ERR_ARG && strstr(err.msg, "n[1]"), "%s", err.msg);
  b = g;
  b.n[2] = -3;
  CHECK(lsdem_grid_check(&b, &err) == LSDEM_ERR_ARG && strstr(err.msg, "n[2]"), "%s", err.msg);
  b = g;
  b.n[0] = b.n[1] = b.n[2] = 2000000000;
  CHECK(lsdem_grid_check(&b, &err) == LSDEM_ERR_NOMEM && strstr(err.msg, "overflow"), "%s",
        err.msg);
  b = g;
  b.h = 0.0;
  CHECK(lsdem_grid_check(&b, &err) == LSDEM_ERR_ARG && strstr(err.msg, "spacing"), "%s",
        err.msg);
  b.h = INFINITY;
  CHECK(lsdem_grid_check(&b, &err) == LSDEM_ERR_ARG && strstr(err.msg, "spacing"), "%s",
        err.msg);
  b.h = NAN;
  CHECK(lsdem_grid_check(&b, &err) == LSDEM_ERR_ARG, "NaN spacing");
  b = g;
  b.origin[1] = NAN;
  CHECK(lsdem_grid_check(&b, &err) == LSDEM_ERR_NUMERIC && strstr(err.msg, "origin"), "%s",
        err.msg);
  b = g;
  b.phi = NULL;
  CHECK(lsdem_grid_check(&b, &err) == LSDEM_ERR_ARG, "NULL values");
  vals[6] = NAN; /* sample (0, 1, 1) */
  CHECK(lsdem_grid_check(&g, &err) == LSDEM_ERR_NUMERIC && strstr(err.msg, "(0, 1, 1)"), "%s",
        err.msg);
  vals[6] = INFINITY;
  CHECK(lsdem_grid_check(&g, &err) == LSDEM_ERR_NUMERIC, "infinite value");
  CHECK(lsdem_grid_check(NULL, NULL) == LSDEM_ERR_ARG, "NULL grid, NULL err");
}

static void test_sample(void)
{
  /* a half-space sampled: phi = z exactly, covering [lo, hi] plus the margin */
  lsdem_sdf plane = {LSDEM_SDF_PLANE, 0, {0, 0, 0}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL};
  const double lo[3] = {-1.0, -0.5, -0.75}, hi[3] = {1.0, 0.5, 0.75};
  lsdem_grid g;
  lsdem_error err;
  CHECK(lsdem_grid_sample(&plane, lo, hi, 0.25, 2, &g, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(g.n[0] == 9 + 4 && g.n[1] == 5 + 4 && g.n[2] == 7 + 4, "sizes %d %d %d", g.n[0],
        g.n[1], g.n[2]);
  CHECK_NEAR(g.origin[0], -1.5, 1e-15);
  CHECK_NEAR(g.origin[2], -1.25, 1e-15);
  CHECK(lsdem_grid_check(&g, &err) == LSDEM_OK, "%s", err.msg);
  for (int t = 0; t < 100; t++) {
    double p[3], grad[3];
    random_inside(&g, p);
    CHECK_NEAR(lsdem_grid_eval(&g, p, grad), p[2], 1e-6);
    CHECK_NEAR(grad[2], 1.0, 1e-6);
  }
  lsdem_grid_free(&g);
  CHECK(g.phi == NULL, "free clears phi");
  /* a box not a multiple of h still reaches hi */
  const double hi2[3] = {1.1, 0.5, 0.75};
  CHECK(lsdem_grid_sample(&plane, lo, hi2, 0.25, 0, &g, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(g.origin[0] + g.h * (g.n[0] - 1) >= 1.1, "covers hi");
  lsdem_grid_free(&g);
  CHECK(lsdem_grid_sample(&plane, lo, hi, -1.0, 0, &g, &err) == LSDEM_ERR_ARG, "negative h");
  CHECK(lsdem_grid_sample(&plane, hi, lo, 0.1, 0, &g, &err) == LSDEM_ERR_ARG, "hi < lo");
  CHECK(lsdem_grid_sample(&plane, lo, hi, 0.1, -1, &g, &err) == LSDEM_ERR_ARG, "margin < 0");
}

/* Not a pass/fail timing: prints the cost of one lookup for the record. */
static void report_speed(void)
{
  lsdem_sdf sph = {LSDEM_SDF_SPHERE, 0, {1.0, 0, 0}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL};
  const double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
  lsdem_grid g;
  if (lsdem_grid_sample(&sph, lo, hi, 0.05, 2, &g, NULL) != LSDEM_OK) return;
  enum { NP = 4096, REP = 1000 };
  static double pts[NP][3];
  for (int i = 0; i < NP; i++)
    for (int a = 0; a < 3; a++) pts[i][a] = 2.2 * urand() - 1.1;
  double sum = 0, grad[3];
  const clock_t t0 = clock();
  for (int r = 0; r < REP; r++)
    for (int i = 0; i < NP; i++) sum += lsdem_grid_eval(&g, pts[i], grad) + grad[0];
  const double sec = (double)(clock() - t0) / CLOCKS_PER_SEC;
  printf("lsdem_grid_eval: %.1f ns per call (checksum %g)\n", 1e9 * sec / ((double)NP * REP),
         sum);
  lsdem_grid_free(&g);
}

int main(void)
{
  test_trilinear_exact();
  test_trilinear_random();
  test_linear_gradient();
  test_boundary_and_outside();
  test_check();
  test_sample();
  report_speed();
  return lsdem_test_summary();
}
