/* Random sand-like grains (randgrain.c): closed level sets, star-shaped about the
 * generation centre, a distance function near the surface, the requested size and Zingg
 * ratios measured from the grid independently of the generator's quadrature, the radius
 * spectrum's RMS, and reproducibility from the seed. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { NGRAINS = 4 };

static lsdem_randgrain_params params(uint64_t seed)
{
  lsdem_randgrain_params p = {1.0, 0.7, 0.8, 0.12, 0.02, seed};
  return p;
}

static int border_negatives(const lsdem_grid *g)
{
  int bad = 0;
  size_t m = 0;
  for (int k = 0; k < g->n[2]; k++)
    for (int j = 0; j < g->n[1]; j++)
      for (int i = 0; i < g->n[0]; i++, m++)
        if ((i == 0 || j == 0 || k == 0 || i == g->n[0] - 1 || j == g->n[1] - 1 ||
             k == g->n[2] - 1) && g->phi[m] < 0.0f)
          bad++;
  return bad;
}

/* Rays from the centre: count sign changes of the interpolated phi out to the grid's
 * far corner (steps of h/8). A star-shaped solid about the centre has exactly one. */
static int rays_not_star(const lsdem_grid *g, const double c[3], int nrays)
{
  const double far = g->h * (g->n[0] + g->n[1] + g->n[2]);
  int bad = 0;
  for (int r = 0; r < nrays; r++) {
    const double z = -1.0 + 2.0 * (r + 0.5) / nrays, ph = 2.399963 * r, s = sqrt(1 - z * z);
    const double u[3] = {s * cos(ph), s * sin(ph), z};
    int changes = 0;
    double prev = lsdem_grid_value(g, c);
    for (double t = g->h / 8; t < far; t += g->h / 8) {
      const double p[3] = {c[0] + t * u[0], c[1] + t * u[1], c[2] + t * u[2]};
      const double v = lsdem_grid_value(g, p);
      if ((v < 0.0) != (prev < 0.0)) changes++;
      prev = v;
    }
    if (changes != 1) bad++;
  }
  return bad;
}

/* Mean raw |grad phi| over grid-cell points within 2h of the zero level. */
static double mean_gradient_band(const lsdem_grid *g)
{
  double sum = 0.0;
  int n = 0;
  for (int k = 1; k < g->n[2] - 1; k++)
    for (int j = 1; j < g->n[1] - 1; j++)
      for (int i = 1; i < g->n[0] - 1; i++) {
        const double p[3] = {g->origin[0] + g->h * (i + 0.5), g->origin[1] + g->h * (j + 0.5),
                             g->origin[2] + g->h * (k + 0.5)};
        if (fabs(lsdem_grid_value(g, p)) > 2.0 * g->h) continue;
        double gr[3];
        lsdem_grid_gradient_raw(g, p, gr);
        sum += sqrt(gr[0] * gr[0] + gr[1] * gr[1] + gr[2] * gr[2]);
        n++;
      }
  return n ? sum / n : 0.0;
}

static void test_batch(void)
{
  const double h = 1.0 / 16.0;
  double sum_el = 0.0, sum_fl = 0.0;
  for (int i = 0; i < NGRAINS; i++) {
    const lsdem_randgrain_params p = params(100 + i);
    lsdem_randgrain rg;
    lsdem_grid g;
    lsdem_error err;
    double c[3];
    CHECK(lsdem_randgrain_make(&p, &rg, &err) == LSDEM_OK, "%s", err.msg);
    CHECK(lsdem_randgrain_grid(&rg, h, 3, &g, c, &err) == LSDEM_OK, "%s", err.msg);
    CHECK(border_negatives(&g) == 0, "grain %d: negative samples on the grid border", i);
    const int bad = rays_not_star(&g, c, 300);
    CHECK(bad == 0, "grain %d: %d of 300 rays from the centre cross the surface != once", i, bad);
    const double gm = mean_gradient_band(&g);
    CHECK_NEAR(gm, 1.0, 0.05);
    lsdem_massprops mp;
    CHECK(lsdem_massprops_grid(&g, 2, &mp, &err) == LSDEM_OK, "%s", err.msg);
    lsdem_shape_stats st;
    lsdem_shape_stats_compute(mp.volume, mp.principal, lsdem_surface_area_grid(&g), &st);
    printf("grain %d: d_eq %.4f, elongation %.3f, flatness %.3f, sphericity %.3f, "
           "|grad phi| %.3f, centroid in principal frame (%.1e %.1e %.1e)\n", i, st.d_eq,
           st.elongation, st.flatness, st.sphericity, gm, mp.centroid[0], mp.centroid[1],
           mp.centroid[2]);
    CHECK_REL(st.d_eq, p.size, 0.02);
    sum_el += st.elongation, sum_fl += st.flatness;
    CHECK(st.sphericity > 0.6 && st.sphericity < 1.0, "sphericity %g", st.sphericity);
    lsdem_grid_free(&g);
  }
  CHECK_NEAR(sum_el / NGRAINS, 0.7, 0.02);
  CHECK_NEAR(sum_fl / NGRAINS, 0.8, 0.02);
}

/* The radius spectrum: with the identity map, ln r = sum a_lm Y_lm has mean square
 * sum_l (2l+1) sigma_l^2 / (4 pi) = angularity^2 + roughness^2 (addition theorem),
 * averaged over grains; measured over directions. */
static void test_spectrum(void)
{
  double ms = 0.0;
  const int ng = 12;
  for (int i = 0; i < ng; i++) {
    lsdem_randgrain_params p = params(500 + i);
    lsdem_randgrain rg;
    lsdem_error err;
    CHECK(lsdem_randgrain_make(&p, &rg, &err) == LSDEM_OK, "%s", err.msg);
    for (int k = 0; k < 9; k++) rg.T[k] = rg.Tinv[k] = k % 4 == 0 ? 1.0 : 0.0;
    const int nd = 1000;
    for (int d = 0; d < nd; d++) {
      const double z = -1.0 + 2.0 * (d + 0.5) / nd, ph = 2.399963 * d, s = sqrt(1 - z * z);
      const double u[3] = {s * cos(ph), s * sin(ph), z};
      const double l = log(lsdem_randgrain_radius(u, &rg));
      ms += l * l / (nd * ng);
    }
  }
  const double want = 0.12 * 0.12 + 0.02 * 0.02;
  printf("spectrum: mean square of ln r %.5f, expected %.5f\n", ms, want);
  CHECK_REL(ms, want, 0.25);
}

static void test_reproducible(void)
{
  const double h = 1.0 / 12.0;
  lsdem_randgrain a, b, c;
  lsdem_grid ga, gb, gc;
  lsdem_error err;
  lsdem_randgrain_params p = params(42);
  CHECK(lsdem_randgrain_make(&p, &a, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_randgrain_make(&p, &b, &err) == LSDEM_OK, "%s", err.msg);
  p.seed = 43;
  CHECK(lsdem_randgrain_make(&p, &c, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_randgrain_grid(&a, h, 2, &ga, NULL, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_randgrain_grid(&b, h, 2, &gb, NULL, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_randgrain_grid(&c, h, 2, &gc, NULL, &err) == LSDEM_OK, "%s", err.msg);
  const size_t na = (size_t)ga.n[0] * ga.n[1] * ga.n[2];
  CHECK(memcmp(ga.n, gb.n, sizeof ga.n) == 0 && memcmp(ga.phi, gb.phi, na * sizeof(float)) == 0,
        "%s", "same seed, different grid");
  /* another seed: compare radii in a few directions (grids may even differ in size) */
  double diff = 0.0;
  for (int d = 0; d < 50; d++) {
    const double z = -1.0 + 2.0 * (d + 0.5) / 50, ph = 2.399963 * d, s = sqrt(1 - z * z);
    const double u[3] = {s * cos(ph), s * sin(ph), z};
    diff = fmax(diff, fabs(lsdem_randgrain_radius(u, &a) - lsdem_randgrain_radius(u, &c)));
  }
  CHECK(diff > 0.02, "seeds 42 and 43 give radii within %g", diff);
  lsdem_grid_free(&ga);
  lsdem_grid_free(&gb);
  lsdem_grid_free(&gc);
}

static void test_bad_params(void)
{
  lsdem_randgrain rg;
  lsdem_error err;
  lsdem_randgrain_params p = params(1);
  p.elongation = 1.5;
  CHECK(lsdem_randgrain_make(&p, &rg, &err) == LSDEM_ERR_ARG, "%s", "elongation 1.5 accepted");
  p = params(1);
  p.size = -1.0;
  CHECK(lsdem_randgrain_make(&p, &rg, &err) == LSDEM_ERR_ARG, "%s", "negative size accepted");
}

int main(void)
{
  test_batch();
  test_spectrum();
  test_reproducible();
  test_bad_params();
  return lsdem_test_summary();
}
