/* test_nodes.c -- surface node seeding, grid surface area and node clustering.
 * Expected areas are closed forms (sphere, box) or an independent parametric quadrature
 * (ellipsoid); positions are checked against the analytic SDFs. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static lsdem_sdf make(lsdem_sdf_kind kind, double a0, double a1, double a2)
{
  lsdem_sdf s = {kind, 0, {a0, a1, a2}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL};
  return s;
}

/* Ellipsoid area by midpoint quadrature of |x_theta x x_phi| on a fine parameter grid. */
static double ellipsoid_area(const double a[3])
{
  const int nt = 600, np = 1200;
  double sum = 0;
  for (int i = 0; i < nt; i++)
    for (int j = 0; j < np; j++) {
      const double t = M_PI * (i + 0.5) / nt, p = 2 * M_PI * (j + 0.5) / np;
      const double xt[3] = {a[0] * cos(t) * cos(p), a[1] * cos(t) * sin(p), -a[2] * sin(t)};
      const double xp[3] = {-a[0] * sin(t) * sin(p), a[1] * sin(t) * cos(p), 0};
      const double c[3] = {xt[1] * xp[2] - xt[2] * xp[1], xt[2] * xp[0] - xt[0] * xp[2],
                           xt[0] * xp[1] - xt[1] * xp[0]};
      sum += sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    }
  return sum * (M_PI / nt) * (2 * M_PI / np);
}

/* Nearest-neighbour distances: min and mean. */
static void spacing(const double *x, int n, double *dmin, double *dmean)
{
  *dmin = HUGE_VAL;
  *dmean = 0;
  for (int i = 0; i < n; i++) {
    double best = HUGE_VAL;
    for (int j = 0; j < n; j++) {
      if (j == i) continue;
      const double d = sqrt(pow(x[3 * i] - x[3 * j], 2) + pow(x[3 * i + 1] - x[3 * j + 1], 2) +
                            pow(x[3 * i + 2] - x[3 * j + 2], 2));
      best = fmin(best, d);
    }
    *dmin = fmin(*dmin, best);
    *dmean += best / n;
  }
}

/* Seed, then check: count, on the surface (|phi_ref| <= tol), even spacing, area sum. */
static void check_seed(const lsdem_sdf *s, const lsdem_sdf *ref, int target, double area_ref,
                       double tol, const char *what)
{
  double *x = malloc(sizeof(double) * 3 * target), *ar = malloc(sizeof(double) * target);
  int n = 0;
  lsdem_error err;
  CHECK(lsdem_nodes_seed(s, target, 42, x, ar, &n, &err) == LSDEM_OK, "%s: %s", what, err.msg);
  CHECK(n == target, "%s: %d nodes of %d", what, n, target);
  double worst = 0, worst_self = 0, total = 0, amin = HUGE_VAL, amax = 0, g[3];
  for (int i = 0; i < n; i++) {
    worst = fmax(worst, fabs(lsdem_sdf_eval(ref, x + 3 * i, g)));
    worst_self = fmax(worst_self, fabs(lsdem_sdf_eval(s, x + 3 * i, g)));
    total += ar[i];
    amin = fmin(amin, ar[i]);
    amax = fmax(amax, ar[i]);
  }
  double dmin, dmean;
  spacing(x, n, &dmin, &dmean);
  CHECK(worst <= tol, "%s: node off the surface by %g > %g", what, worst, tol);
  CHECK(worst_self <= 1e-6 * dmean, "%s: node off its own zero level by %g", what, worst_self);
  CHECK(dmin > 0.5 * dmean, "%s: min spacing %g vs mean %g", what, dmin, dmean);
  CHECK_REL(total, area_ref, 0.03);
  CHECK(amin > 0, "%s: every node has area", what);
  printf("%s: %d nodes, max |phi| %.2g, spacing min/mean %.3f, area %.4f vs %.4f (%+.2f%%), "
         "node area max/min %.2f\n",
         what, n, worst, dmin / dmean, total, area_ref, 100 * (total / area_ref - 1), amax / amin);
  free(x);
  free(ar);
}

static void test_seed_analytic(void)
{
  const lsdem_sdf sp = make(LSDEM_SDF_SPHERE, 1.0, 0, 0);
  /* mean spacing of 400 nodes on the unit sphere is ~0.18: 1e-3 of that is 1.8e-4 */
  check_seed(&sp, &sp, 400, 4 * M_PI, 1e-9, "sphere");
  const lsdem_sdf bx = make(LSDEM_SDF_BOX, 0.5, 0.7, 0.9);
  check_seed(&bx, &bx, 500, 8 * (0.5 * 0.7 + 0.7 * 0.9 + 0.5 * 0.9), 1e-9, "box");
  const double a[3] = {1.5, 1.0, 0.6};
  const lsdem_sdf el = make(LSDEM_SDF_ELLIPSOID, a[0], a[1], a[2]);
  check_seed(&el, &el, 500, ellipsoid_area(a), 1e-9, "ellipsoid");
  const lsdem_sdf cy = make(LSDEM_SDF_CYLINDER, 0.5, 0.8, 0);
  check_seed(&cy, &cy, 300, 2 * M_PI * 0.5 * 1.6 + 2 * M_PI * 0.25, 1e-9, "cylinder");
}

static void test_seed_grid(void)
{
  const double R = 1.0, h = R / 10;
  const lsdem_sdf sp = make(LSDEM_SDF_SPHERE, R, 0, 0);
  const double lo[3] = {-R, -R, -R}, hi[3] = {R, R, R};
  lsdem_sdf gs = make(LSDEM_SDF_GRID, 0, 0, 0);
  lsdem_error err;
  CHECK(lsdem_grid_sample(&sp, lo, hi, h, 2, &gs.grid, &err) == LSDEM_OK, "%s", err.msg);
  /* nodes sit on the interpolated surface, within the interpolation error of the sphere */
  check_seed(&gs, &sp, 400, 4 * M_PI, 0.05 * h, "grid sphere");
  const double A = lsdem_surface_area_grid(&gs.grid);
  CHECK_REL(A, 4 * M_PI, 0.01);
  printf("grid sphere surface area: %.4f vs %.4f (%+.2f%%)\n", A, 4 * M_PI,
         100 * (A / (4 * M_PI) - 1));
  lsdem_grid_free(&gs.grid);
  /* the ellipsoid at a_min / 10 */
  const double a[3] = {1.5, 1.0, 0.6};
  const lsdem_sdf el = make(LSDEM_SDF_ELLIPSOID, a[0], a[1], a[2]);
  const double elo[3] = {-a[0], -a[1], -a[2]}, ehi[3] = {a[0], a[1], a[2]};
  CHECK(lsdem_grid_sample(&el, elo, ehi, 0.06, 2, &gs.grid, &err) == LSDEM_OK, "%s", err.msg);
  const double Ae = lsdem_surface_area_grid(&gs.grid), Aref = ellipsoid_area(a);
  CHECK_REL(Ae, Aref, 0.01);
  printf("grid ellipsoid surface area: %.4f vs %.4f (%+.2f%%)\n", Ae, Aref, 100 * (Ae / Aref - 1));
  lsdem_grid_free(&gs.grid);
}

static void test_seed_determinism(void)
{
  const lsdem_sdf el = make(LSDEM_SDF_ELLIPSOID, 1.2, 0.9, 0.7);
  double x1[300], x2[300], x3[300], a1[100], a2[100], a3[100];
  int n1, n2, n3;
  lsdem_nodes_seed(&el, 100, 7, x1, a1, &n1, NULL);
  lsdem_nodes_seed(&el, 100, 7, x2, a2, &n2, NULL);
  lsdem_nodes_seed(&el, 100, 8, x3, a3, &n3, NULL);
  CHECK(n1 == 100 && n2 == 100 && n3 == 100, "counts");
  CHECK(memcmp(x1, x2, sizeof x1) == 0 && memcmp(a1, a2, sizeof a1) == 0, "same seed, same nodes");
  CHECK(memcmp(x1, x3, sizeof x1) != 0, "another seed, other nodes");
  /* errors */
  const lsdem_sdf pl = make(LSDEM_SDF_PLANE, 0, 0, 0);
  lsdem_error err;
  int n;
  CHECK(lsdem_nodes_seed(&pl, 10, 1, x1, a1, &n, &err) == LSDEM_ERR_ARG && n == 0, "unbounded");
  CHECK(lsdem_nodes_seed(&el, 0, 1, x1, a1, &n, &err) == LSDEM_ERR_ARG, "zero nodes");
  CHECK(lsdem_nodes_seed(&el, 10, 1, NULL, a1, &n, &err) == LSDEM_ERR_ARG, "NULL nodes");
}

static int cmp4(const void *x, const void *y)
{
  const double *a = x, *b = y;
  for (int k = 0; k < 4; k++)
    if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
  return 0;
}

static void test_cluster(void)
{
  enum { N = 1000 };
  const lsdem_sdf el = make(LSDEM_SDF_ELLIPSOID, 1.5, 1.0, 0.6);
  static double x[3 * N], ar[N], before[4 * N], after[4 * N], sph[4 * N];
  static int start[N + 1];
  int n;
  CHECK(lsdem_nodes_seed(&el, N, 3, x, ar, &n, NULL) == LSDEM_OK && n == N, "seed");
  for (int i = 0; i < N; i++) {
    memcpy(before + 4 * i, x + 3 * i, 3 * sizeof(double));
    before[4 * i + 3] = ar[i];
  }
  const int targets[4] = {1, 7, 16, 5000};
  for (int t = 0; t < 4; t++) {
    const int target = targets[t];
    const int nc = lsdem_nodes_cluster(N, x, ar, target, start, sph);
    CHECK(nc >= (N + target - 1) / target && nc <= N, "target %d: %d clusters", target, nc);
    CHECK(start[0] == 0 && start[nc] == N, "clusters cover all nodes");
    int bad_order = 0, bad_size = 0, outside = 0;
    for (int c = 0; c < nc; c++) {
      if (!(start[c] < start[c + 1])) bad_order++;
      if (start[c + 1] - start[c] > target) bad_size++;
      for (int i = start[c]; i < start[c + 1]; i++) {
        const double *p = x + 3 * i, *s = sph + 4 * c;
        const double d = sqrt(pow(p[0] - s[0], 2) + pow(p[1] - s[1], 2) + pow(p[2] - s[2], 2));
        if (d > s[3]) outside++;
      }
    }
    /* strictly increasing starts: every node in exactly one cluster */
    CHECK(bad_order == 0, "target %d: %d empty or unordered clusters", target, bad_order);
    CHECK(bad_size == 0, "target %d: %d clusters above target", target, bad_size);
    CHECK(outside == 0, "target %d: %d nodes outside their cluster sphere", target, outside);
    /* same (node, area) pairs, only reordered */
    for (int i = 0; i < N; i++) {
      memcpy(after + 4 * i, x + 3 * i, 3 * sizeof(double));
      after[4 * i + 3] = ar[i];
    }
    qsort(after, N, 4 * sizeof(double), cmp4);
    double *b = malloc(sizeof before);
    memcpy(b, before, sizeof before);
    qsort(b, N, 4 * sizeof(double), cmp4);
    CHECK(memcmp(after, b, sizeof after) == 0, "target %d: node/area pairs preserved", target);
    free(b);
    if (target == 16) {
      /* spatial coherence: a cluster sphere is much smaller than the grain */
      double rmax = 0;
      for (int c = 0; c < nc; c++) rmax = fmax(rmax, sph[4 * c + 3]);
      CHECK(rmax < 0.5, "largest cluster radius %g", rmax);
    }
  }
  CHECK(lsdem_nodes_cluster(0, x, ar, 8, start, sph) == 0 && start[0] == 0, "no nodes");
  /* area may be NULL */
  CHECK(lsdem_nodes_cluster(N, x, NULL, 10, start, sph) > 0, "no areas");
}

int main(void)
{
  test_seed_analytic();
  test_seed_grid();
  test_seed_determinism();
  test_cluster();
  return lsdem_test_summary();
}
