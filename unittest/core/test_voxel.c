/* test_voxel.c -- grains from labelled images (voxel.c) against analytic solids and a
 * brute-force distance transform. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static lsdem_label_image new_image(int nx, int ny, int nz)
{
  lsdem_label_image img = {{nx, ny, nz}, calloc((size_t)nx * ny * nz, sizeof(int32_t))};
  return img;
}

static int32_t *at(lsdem_label_image *img, int i, int j, int k)
{
  return img->label + ((size_t)k * img->n[1] + j) * img->n[0] + i;
}

/* Label every voxel centre inside the ellipsoid with semi-axes ax (voxels) along the
 * columns of R, centred at c (voxel coordinates). */
static long paint_ellipsoid(lsdem_label_image *img, int32_t label, const double c[3],
                            const double ax[3], const double R[9])
{
  long n = 0;
  for (int k = 0; k < img->n[2]; k++)
    for (int j = 0; j < img->n[1]; j++)
      for (int i = 0; i < img->n[0]; i++) {
        const double d[3] = {i - c[0], j - c[1], k - c[2]};
        double b[3], s = 0.0;
        lsdem_matT_vec(R, d, b);
        for (int a = 0; a < 3; a++) s += b[a] * b[a] / (ax[a] * ax[a]);
        if (s <= 1.0) *at(img, i, j, k) = label, n++;
      }
  return n;
}

/* phi of a grain at a scan-frame point. */
static double grain_phi(const lsdem_voxel_grain *g, const double p[3])
{
  double R[9], d[3], b[3];
  lsdem_quat_to_matrix(g->quat, R);
  for (int a = 0; a < 3; a++) d[a] = p[a] - g->position[a];
  lsdem_matT_vec(R, d, b);
  return lsdem_grid_value(&g->grid, b);
}

/* Exact EDT: brute-force distances between voxel centres agree with the transform,
 * phi = d_out - 1/2 outside and 1/2 - d_in inside, on a random blob. */
static void test_edt_exact(void)
{
  lsdem_label_image img = new_image(14, 12, 11);
  unsigned s = 12345;
  for (int k = 3; k < 8; k++)
    for (int j = 3; j < 9; j++)
      for (int i = 2; i < 11; i++) {
        s = s * 1103515245u + 12345u;
        if ((s >> 16) % 3) *at(&img, i, j, k) = 7;
      }
  *at(&img, 5, 5, 5) = 9; /* another label inside counts as outside */
  const lsdem_voxel_options o = {0.25, 1, 0, 2};
  const int lo[3] = {2, 3, 3}, hi[3] = {10, 8, 7};
  lsdem_grid g;
  lsdem_error err;
  CHECK(lsdem_voxel_label_sdf(&img, 7, lo, hi, 2, &o, &g, &err) == LSDEM_OK, "%s", err.msg);
  double worst = 0.0;
  size_t m = 0;
  for (int k = 0; k < g.n[2]; k++)
    for (int j = 0; j < g.n[1]; j++)
      for (int i = 0; i < g.n[0]; i++, m++) {
        const int c[3] = {i + lo[0] - 2, j + lo[1] - 2, k + lo[2] - 2};
        const int inside = c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < 14 && c[1] < 12 &&
                           c[2] < 11 && *at(&img, c[0], c[1], c[2]) == 7;
        double best = HUGE_VAL;
        for (int kk = -2; kk < g.n[2] - 2 + 2; kk++)
          for (int jj = -2; jj < g.n[1] - 2 + 2; jj++)
            for (int ii = -2; ii < g.n[0] - 2 + 2; ii++) {
              const int e[3] = {ii + lo[0] - 2, jj + lo[1] - 2, kk + lo[2] - 2};
              const int in2 = e[0] >= 0 && e[1] >= 0 && e[2] >= 0 && e[0] < 14 && e[1] < 12 &&
                              e[2] < 11 && *at(&img, e[0], e[1], e[2]) == 7;
              if (in2 == inside) continue;
              const double d2 = pow(e[0] - c[0], 2) + pow(e[1] - c[1], 2) + pow(e[2] - c[2], 2);
              best = fmin(best, d2);
            }
        const double expect = 0.25 * (inside ? 0.5 - sqrt(best) : sqrt(best) - 0.5);
        worst = fmax(worst, fabs(g.phi[m] - expect));
      }
  CHECK(worst < 1e-5, "EDT differs from brute force by %g", worst);
  for (int a = 0; a < 3; a++) CHECK_NEAR(g.origin[a], 0.25 * (lo[a] - 2), 1e-12);
  lsdem_grid_free(&g);
  free(img.label);
}

/* Sphere of radius 10 voxels (20 across), off-grid centre, voxel size 0.5; a tiny label. */
static void test_sphere(int smooth)
{
  lsdem_label_image img = new_image(34, 33, 35);
  const double c[3] = {16.3, 15.7, 17.2}, ax[3] = {10, 10, 10}, I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  paint_ellipsoid(&img, 3, c, ax, I3);
  for (int i = 0; i < 4; i++) *at(&img, 1 + i, 1, 1) = 5; /* 4 voxels: dropped */
  const double s = 0.5, R = 10 * s;
  const lsdem_voxel_options o = {s, 20, smooth, 2};
  lsdem_voxel_grain *gr = NULL;
  int n = 0, dropped = 0;
  lsdem_error err;
  CHECK(lsdem_voxel_grains(&img, &o, &gr, &n, &dropped, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(n == 1 && dropped == 1, "grains %d dropped %d", n, dropped);
  if (n == 1) {
    CHECK(gr[0].label == 3, "label %d", gr[0].label);
    for (int a = 0; a < 3; a++) CHECK_NEAR(gr[0].position[a], c[a] * s, 0.05 * s);
    /* zero level within half a voxel of the true sphere, over many directions */
    double worst = 0.0;
    for (int t = 0; t < 400; t++) {
      const double z = -1.0 + (t + 0.5) / 200.0, phiang = t * 2.399963229728653;
      const double r = sqrt(1.0 - z * z);
      const double p[3] = {s * c[0] + R * r * cos(phiang), s * c[1] + R * r * sin(phiang),
                           s * c[2] + R * z};
      worst = fmax(worst, fabs(grain_phi(&gr[0], p)));
    }
    CHECK(worst < 0.5 * s, "smooth %d: |phi| on the true surface up to %g voxels", smooth,
          worst / s);
    lsdem_massprops mp;
    CHECK(lsdem_massprops_grid(&gr[0].grid, 2, &mp, &err) == LSDEM_OK, "%s", err.msg);
    const double V = 4.0 / 3.0 * PI * R * R * R;
    CHECK_REL(mp.volume, V, 0.01);
    for (int a = 0; a < 3; a++) CHECK_REL(mp.principal[a], 0.4 * V * R * R, 0.01);
    printf("sphere smooth %d: surface |phi| <= %.3f voxel, volume %+.3f%%, I %+.3f%%\n", smooth,
           worst / s, 100 * (mp.volume / V - 1), 100 * (mp.principal[0] / (0.4 * V * R * R) - 1));
  }
  lsdem_voxel_grains_free(gr, n);
  free(img.label);
}

/* Rotated ellipsoid 28 x 22 x 20 voxels: moments, orientation and position recovered. */
static void test_ellipsoid(void)
{
  lsdem_label_image img = new_image(40, 38, 36);
  double q0[4] = {0.9, 0.3, -0.2, 0.25}, R0[9];
  lsdem_quat_normalize(q0);
  lsdem_quat_to_matrix(q0, R0);
  const double c[3] = {19.6, 18.4, 17.9}, ax[3] = {14, 11, 10};
  paint_ellipsoid(&img, 1, c, ax, R0);
  const double s = 1.0;
  const lsdem_voxel_options o = {s, 1, 0, 2};
  lsdem_voxel_grain *gr = NULL;
  int n = 0, dropped = 0;
  lsdem_error err;
  CHECK(lsdem_voxel_grains(&img, &o, &gr, &n, &dropped, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(n == 1 && dropped == 0, "grains %d dropped %d", n, dropped);
  if (n == 1) {
    for (int a = 0; a < 3; a++) CHECK_NEAR(gr[0].position[a], c[a], 0.05);
    lsdem_massprops mp;
    CHECK(lsdem_massprops_grid(&gr[0].grid, 2, &mp, &err) == LSDEM_OK, "%s", err.msg);
    const double V = 4.0 / 3.0 * PI * ax[0] * ax[1] * ax[2];
    CHECK_REL(mp.volume, V, 0.01);
    /* ascending moments: the longest axis has the smallest moment */
    for (int a = 0; a < 3; a++) {
      const double b = ax[(a + 1) % 3], cc = ax[(a + 2) % 3];
      CHECK_REL(mp.principal[a], V * (b * b + cc * cc) / 5.0, 0.01);
    }
    /* the principal grid's own axes are the coordinate axes */
    for (int a = 0; a < 3; a++) CHECK_NEAR(fabs(mp.axes[4 * a]), 1.0, 1e-3);
    double Rr[9];
    lsdem_quat_to_matrix(gr[0].quat, Rr);
    for (int a = 0; a < 3; a++) {
      double d = 0.0;
      for (int i = 0; i < 3; i++) d += Rr[3 * i + a] * R0[3 * i + a];
      CHECK(fabs(d) > cos(2.0 * PI / 180.0), "axis %d off by %g degrees", a,
            acos(fmin(1.0, fabs(d))) * 180.0 / PI);
    }
  }
  lsdem_voxel_grains_free(gr, n);
  free(img.label);
}

/* Two boxes sharing a face (labels 1 and 2): each grain's surface is on the shared face,
 * and neither claims the other's voxels. */
static void test_touching(void)
{
  lsdem_label_image img = new_image(24, 16, 16);
  for (int k = 3; k < 13; k++)
    for (int j = 3; j < 13; j++)
      for (int i = 2; i < 22; i++) *at(&img, i, j, k) = i < 12 ? 1 : 2;
  const double s = 0.1;
  const lsdem_voxel_options o = {s, 1, 0, 2};
  lsdem_voxel_grain *gr = NULL;
  int n = 0, dropped = 0;
  lsdem_error err;
  CHECK(lsdem_voxel_grains(&img, &o, &gr, &n, &dropped, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(n == 2, "grains %d", n);
  if (n == 2) {
    CHECK_NEAR(gr[0].position[0], 6.5 * s, 0.01 * s);
    CHECK_NEAR(gr[1].position[0], 16.5 * s, 0.01 * s);
    for (int g = 0; g < 2; g++) {
      CHECK(gr[g].nvoxels == 1000, "voxels %ld", gr[g].nvoxels);
      for (int j = 5; j < 11; j += 2)
        for (int k = 5; k < 11; k += 2) {
          const double own[3] = {(g ? 12 : 11) * s, j * s, k * s};
          const double other[3] = {(g ? 11 : 12) * s, j * s, k * s};
          const double face[3] = {11.5 * s, j * s, k * s};
          CHECK_NEAR(grain_phi(&gr[g], own), -0.5 * s, 0.02 * s);
          CHECK_NEAR(grain_phi(&gr[g], other), 0.5 * s, 0.02 * s);
          CHECK_NEAR(grain_phi(&gr[g], face), 0.0, 0.02 * s);
        }
    }
  }
  lsdem_voxel_grains_free(gr, n);
  free(img.label);
}

static void test_errors(void)
{
  lsdem_label_image img = new_image(4, 4, 4);
  img.label[5] = LSDEM_VOXEL_MAX_LABEL + 1;
  const lsdem_voxel_options o = {1.0, 1, 0, 2};
  lsdem_voxel_grain *gr = NULL;
  int n = -1, dropped = -1;
  lsdem_error err;
  CHECK(lsdem_voxel_grains(&img, &o, &gr, &n, &dropped, &err) == LSDEM_ERR_FORMAT &&
            strstr(err.msg, "relabel") && gr == NULL && n == 0,
        "huge label: %s", err.msg);
  img.label[5] = 0;
  CHECK(lsdem_voxel_grains(&img, &o, &gr, &n, &dropped, &err) == LSDEM_OK && n == 0,
        "empty image: %s", err.msg);
  lsdem_voxel_grains_free(gr, n);
  const lsdem_voxel_options bad = {0.0, 1, 0, 2};
  const int lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  lsdem_grid g;
  CHECK(lsdem_voxel_label_sdf(&img, 1, lo, hi, 1, &bad, &g, &err) == LSDEM_ERR_ARG, "voxel 0");
  free(img.label);
}

int main(void)
{
  test_edt_exact();
  test_sphere(0);
  test_sphere(2);
  test_ellipsoid();
  test_touching();
  test_errors();
  return lsdem_test_summary();
}
