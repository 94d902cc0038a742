/* test_massprops.c -- volume, centroid, inertia of sampled solids against closed forms
 * (sphere, ellipsoid: V = 4/3 pi abc, I_x = V (b^2 + c^2) / 5), principal axes of a
 * rotated ellipsoid against the known rotation, and the principal-frame resampling. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <stdlib.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static double dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Grid of an ellipsoid with semi-axes a, rotated by q and centred at c (world = R body + c),
 * covering its bounding sphere plus two spacings. */
static float *rotated_ellipsoid_grid(const double a[3], const double q[4], const double c[3],
                                     double h, lsdem_grid *g)
{
  const double r = fmax(a[0], fmax(a[1], a[2])) + 2 * h;
  const int n = (int)ceil(2 * r / h) + 1;
  g->n[0] = g->n[1] = g->n[2] = n;
  g->h = h;
  for (int k = 0; k < 3; k++) g->origin[k] = c[k] - r;
  float *phi = malloc(sizeof(float) * n * n * n);
  const lsdem_sdf el = {LSDEM_SDF_ELLIPSOID, 0, {a[0], a[1], a[2]}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL};
  size_t m = 0;
  for (int k = 0; k < n; k++)
    for (int j = 0; j < n; j++)
      for (int i = 0; i < n; i++) {
        const double p[3] = {g->origin[0] + h * i - c[0], g->origin[1] + h * j - c[1],
                             g->origin[2] + h * k - c[2]};
        double b[3], grad[3];
        lsdem_quat_rotate_inv(q, p, b);
        phi[m++] = (float)lsdem_sdf_eval(&el, b, grad);
      }
  g->phi = phi;
  return phi;
}

static void ellipsoid_exact(const double a[3], double *V, double I[3])
{
  *V = 4.0 / 3.0 * M_PI * a[0] * a[1] * a[2];
  I[0] = *V * (a[1] * a[1] + a[2] * a[2]) / 5;
  I[1] = *V * (a[0] * a[0] + a[2] * a[2]) / 5;
  I[2] = *V * (a[0] * a[0] + a[1] * a[1]) / 5;
}

static void test_sphere(void)
{
  const double R = 1.0, h = R / 10;
  const double a[3] = {R, R, R}, q[4] = {1, 0, 0, 0}, c[3] = {0.013, -0.021, 0.037};
  lsdem_grid g;
  float *phi = rotated_ellipsoid_grid(a, q, c, h, &g);
  double V, I[3];
  ellipsoid_exact(a, &V, I);
  double err_prev = HUGE_VAL;
  for (int sub = 1; sub <= 4; sub *= 2) {
    lsdem_massprops mp;
    lsdem_error err;
    CHECK(lsdem_massprops_grid(&g, sub, &mp, &err) == LSDEM_OK, "%s", err.msg);
    CHECK_REL(mp.volume, V, 0.01);
    double e = 0;
    for (int k = 0; k < 3; k++) {
      CHECK_REL(mp.principal[k], I[0], 0.01);
      CHECK_REL(mp.inertia[4 * k], I[0], 0.01);
      CHECK_NEAR(mp.centroid[k], c[k], 1e-3 * h);
      e = fmax(e, fabs(mp.principal[k] / I[0] - 1));
    }
    CHECK(e < err_prev, "sub-sampling converges: sub %d error %g, previous %g", sub, e, err_prev);
    printf("sphere R/h=10 sub=%d: volume err %+.3f%%, inertia err %+.3f%%\n", sub,
           100 * (mp.volume / V - 1), 100 * (mp.principal[0] / I[0] - 1));
    err_prev = e;
  }
  free(phi);
}

static void test_rotated_ellipsoid(void)
{
  const double a[3] = {1.5, 1.0, 0.6}, h = 0.06;
  double q[4] = {0.8, 0.3, -0.4, 0.33}, R[9];
  lsdem_quat_normalize(q);
  lsdem_quat_to_matrix(q, R);
  const double c[3] = {0.31, -0.17, 0.52};
  lsdem_grid g;
  float *phi = rotated_ellipsoid_grid(a, q, c, h, &g);
  double V, I[3];
  ellipsoid_exact(a, &V, I); /* ascending already: a0 > a1 > a2 */
  lsdem_massprops mp;
  lsdem_error err;
  CHECK(lsdem_massprops_grid(&g, 2, &mp, &err) == LSDEM_OK, "%s", err.msg);
  CHECK_REL(mp.volume, V, 0.01);
  for (int k = 0; k < 3; k++) {
    CHECK_REL(mp.principal[k], I[k], 0.01);
    CHECK_NEAR(mp.centroid[k], c[k], 1e-3 * h);
    /* principal axis k is the body axis k rotated into the grid frame, up to sign */
    const double axis[3] = {mp.axes[k], mp.axes[3 + k], mp.axes[6 + k]};
    const double body[3] = {R[k], R[3 + k], R[6 + k]};
    CHECK(fabs(dot3(axis, body)) > 1 - 1e-5, "axis %d: |cos| = %.8f", k, fabs(dot3(axis, body)));
  }
  printf("ellipsoid (1.5, 1, 0.6) h=0.06 sub=2: volume err %+.3f%%, inertia err %+.3f%% %+.3f%% %+.3f%%\n",
         100 * (mp.volume / V - 1), 100 * (mp.principal[0] / I[0] - 1),
         100 * (mp.principal[1] / I[1] - 1), 100 * (mp.principal[2] / I[2] - 1));

  /* principal frame: centroid at 0, diagonal inertia, same moments, q_out = axes */
  lsdem_grid pg;
  double qo[4], Ro[9];
  const int margin = 3;
  CHECK(lsdem_grid_to_principal(&g, &mp, margin, &pg, qo, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_grid_check(&pg, &err) == LSDEM_OK, "%s", err.msg);
  lsdem_quat_to_matrix(qo, Ro);
  for (int i = 0; i < 9; i++) CHECK_NEAR(Ro[i], mp.axes[i], 1e-12);
  lsdem_massprops pp;
  CHECK(lsdem_massprops_grid(&pg, 2, &pp, &err) == LSDEM_OK, "%s", err.msg);
  for (int k = 0; k < 3; k++) {
    CHECK_NEAR(pp.centroid[k], 0.0, 0.02 * h);
    CHECK_REL(pp.principal[k], I[k], 0.01);
    CHECK_REL(pp.inertia[4 * k], pp.principal[k], 1e-3);
  }
  const double offd = fmax(fabs(pp.inertia[1]), fmax(fabs(pp.inertia[2]), fabs(pp.inertia[5])));
  CHECK(offd < 1e-3 * pp.principal[2], "off-diagonal inertia %g", offd);
  /* resampling is a trilinear interpolation: it overestimates phi of a convex solid by
   * ~h^2 k / 6 between samples, shrinking it slightly (0.2% here) */
  CHECK_REL(pp.volume, mp.volume, 5e-3);
  /* the resampled field is the ellipsoid in its own frame (symmetric under axis flips) */
  const lsdem_sdf el = {LSDEM_SDF_ELLIPSOID, 0, {a[0], a[1], a[2]}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL};
  double worst = 0;
  int near = 0;
  for (int t = 0; t < 20000; t++) { /* near the surface, away from the medial kinks */
    const double p[3] = {a[0] * (2.0 * (t % 37) / 36 - 1), a[1] * (2.0 * (t % 29) / 28 - 1),
                         a[2] * (2.0 * (t % 23) / 22 - 1)};
    double g1[3];
    const double v = lsdem_sdf_eval(&el, p, g1);
    if (fabs(v) > 2 * h) continue;
    near++;
    worst = fmax(worst, fabs(lsdem_grid_value(&pg, p) - v));
  }
  CHECK(near > 1000, "%d points near the surface", near);
  /* two interpolations (resampling, lookup) of a field with curvature <= 4.2 at h = 0.06 */
  CHECK(worst < 0.2 * h, "principal grid vs analytic ellipsoid: %g (%.3f h)", worst, worst / h);
  /* margin: the outer `margin` layers hold positive values only */
  int neg_in_margin = 0;
  size_t m = 0;
  for (int k = 0; k < pg.n[2]; k++)
    for (int j = 0; j < pg.n[1]; j++)
      for (int i = 0; i < pg.n[0]; i++, m++) {
        const int edge = i < margin || j < margin || k < margin || i >= pg.n[0] - margin ||
                         j >= pg.n[1] - margin || k >= pg.n[2] - margin;
        if (edge && !(pg.phi[m] > 0)) neg_in_margin++;
      }
  CHECK(neg_in_margin == 0, "%d non-positive samples in the margin", neg_in_margin);
  /* tight: the box is not much larger than the ellipsoid's extent plus the margin */
  for (int k = 0; k < 3; k++)
    CHECK(pg.h * (pg.n[k] - 1) < 2 * a[k] + 2 * margin * h + 6 * h, "axis %d extent %g", k,
          pg.h * (pg.n[k] - 1));
  lsdem_grid_free(&pg);
  free(phi);
}

static void test_errors(void)
{
  float vals[27];
  for (int i = 0; i < 27; i++) vals[i] = 1.0f;
  lsdem_grid g = {{3, 3, 3}, 1.0, {0, 0, 0}, vals, 0.0, 0.0};
  lsdem_massprops mp;
  lsdem_error err;
  CHECK(lsdem_massprops_grid(&g, 1, &mp, &err) == LSDEM_ERR_NUMERIC, "empty solid");
  CHECK(lsdem_massprops_grid(&g, 0, &mp, &err) == LSDEM_ERR_ARG, "sub = 0");
  g.h = -1;
  CHECK(lsdem_massprops_grid(&g, 1, &mp, &err) == LSDEM_ERR_ARG, "bad grid");
}

int main(void)
{
  test_sphere();
  test_rotated_ellipsoid();
  test_errors();
  return lsdem_test_summary();
}
