/* test_band.c -- narrow-band level sets (geom/band.c) and band walls (core/boundary):
 * lookups against the analytic plane they sample, the same bits as a dense grid of the
 * same samples, the coarse level as a lower bound of the distance, the outside rule,
 * tunnelling, the checks, and a band wall's may-touch and crossing tests. */
#include "lsdem_test.h"

#include <stdlib.h>
#include <string.h>

/* A tilted plane n.x = c (solid below), its exact signed distance. */
static const double N[3] = {0.2, -0.3, 0.9327379053088815}; /* unit: 0.04+0.09+0.87 = 1 */
static const double C = 0.37;
static double plane_distance(const double p[3]) { return N[0] * p[0] + N[1] * p[1] + N[2] * p[2] - C; }

static double clampw(double d, double w) { return d < -w ? -w : (d > w ? w : d); }

/* A band over [0, 2.4]^2 x [0, 1.6] with h = 0.05 sampling the plane; `all`: every brick
 * stored, else only those within width of it (by the brick box's corners), the rest
 * background by the sign of their centre. Also the dense grid of the same samples. */
typedef struct {
  lsdem_band band;
  int32_t *index;
  float *phi;
  lsdem_grid dense;
  float *dense_phi;
} test_band;

static void sample_point(const lsdem_band *b, int i, int j, int k, double p[3])
{
  p[0] = b->origin[0] + b->h * i, p[1] = b->origin[1] + b->h * j, p[2] = b->origin[2] + b->h * k;
}

static void make_band(test_band *t, double width, int all)
{
  memset(t, 0, sizeof *t);
  lsdem_band *b = &t->band;
  b->h = 0.05;
  b->width = width;
  const int n[3] = {49, 49, 33};
  for (int a = 0; a < 3; a++) {
    b->n[a] = n[a];
    b->origin[a] = 0.0;
    b->nb[a] = (n[a] - 2) / LSDEM_BAND_BRICK + 1;
  }
  const int slots = b->nb[0] * b->nb[1] * b->nb[2];
  t->index = malloc(slots * sizeof(int32_t));
  t->phi = malloc((size_t)slots * LSDEM_BAND_BRICK_SAMPLES * sizeof(float));
  int nbricks = 0;
  for (int bz = 0; bz < b->nb[2]; bz++)
    for (int by = 0; by < b->nb[1]; by++)
      for (int bx = 0; bx < b->nb[0]; bx++) {
        const int s = bx + b->nb[0] * (by + b->nb[1] * bz);
        double lo = HUGE_VAL, hi = -HUGE_VAL, p[3];
        for (int c = 0; c < 8; c++) {
          sample_point(b, 8 * (bx + (c & 1)), 8 * (by + (c >> 1 & 1)), 8 * (bz + (c >> 2)), p);
          lo = fmin(lo, plane_distance(p)), hi = fmax(hi, plane_distance(p));
        }
        if (!all && (lo > width || hi < -width)) {
          t->index[s] = lo > 0.0 ? LSDEM_BAND_OUTSIDE : LSDEM_BAND_INSIDE;
          continue;
        }
        t->index[s] = nbricks;
        float *v = t->phi + (size_t)nbricks++ * LSDEM_BAND_BRICK_SAMPLES;
        for (int c = 0; c < 9; c++)
          for (int bb = 0; bb < 9; bb++)
            for (int a = 0; a < 9; a++) {
              sample_point(b, 8 * bx + a, 8 * by + bb, 8 * bz + c, p);
              v[a + 9 * (bb + 9 * c)] = (float)clampw(plane_distance(p), width);
            }
      }
  b->nbricks = nbricks;
  b->index = t->index;
  b->phi = t->phi;
  /* the dense grid of the same (clamped) samples */
  lsdem_grid *g = &t->dense;
  const size_t total = (size_t)n[0] * n[1] * n[2];
  t->dense_phi = malloc(total * sizeof(float));
  for (int k = 0; k < n[2]; k++)
    for (int j = 0; j < n[1]; j++)
      for (int i = 0; i < n[0]; i++) {
        double p[3];
        sample_point(b, i, j, k, p);
        t->dense_phi[i + n[0] * ((size_t)j + n[1] * (size_t)k)] = (float)clampw(plane_distance(p), width);
      }
  for (int a = 0; a < 3; a++) g->n[a] = n[a], g->origin[a] = 0.0;
  g->h = b->h;
  g->phi = t->dense_phi;
}

static void free_band(test_band *t)
{
  free(t->index), free(t->phi), free(t->dense_phi);
  free((void *)t->band.far);
}

/* make_band's near-plane band (width 0.1) with its coarse level on */
static void make_band_with_far(test_band *t)
{
  make_band(t, 0.1, 0);
  lsdem_error err;
  uint16_t *far = NULL;
  CHECK(lsdem_band_far(&t->band, &far, &err) == LSDEM_OK, "%s", err.msg);
  t->band.far = far;
}

static void random_point(double p[3])
{
  p[0] = 2.4 * urand(), p[1] = 2.4 * urand(), p[2] = 1.6 * urand();
}

/* Inside the band: the interpolated plane (linear, so trilinear is exact up to float
 * samples) and its normal; bit for bit the dense grid's lookup of the same samples. */
static void test_lookup_matches_plane_and_dense(void)
{
  test_band t;
  make_band(&t, 0.1, 0);
  lsdem_error err;
  CHECK(lsdem_band_check(&t.band, &err) == LSDEM_OK, "%s", err.msg);
  int inside = 0, same = 0, near = 0;
  for (int m = 0; m < 200000; m++) {
    double p[3], g[3], gd[3];
    random_point(p);
    const double d = plane_distance(p);
    if (fabs(d) > 0.1 - 0.05 * sqrt(3.0)) continue; /* cells whose samples are unclamped */
    inside++;
    const double phi = lsdem_band_eval(&t.band, p, g);
    const double dense = lsdem_grid_eval(&t.dense, p, gd);
    same += phi == dense && g[0] == gd[0] && g[1] == gd[1] && g[2] == gd[2];
    near += fabs(phi - d) < 1e-6 && fabs(g[0] - N[0]) < 1e-5 && fabs(g[2] - N[2]) < 1e-5;
  }
  CHECK(inside > 1000, "%d points in the band", inside);
  CHECK(same == inside, "%d of %d lookups are the dense grid's bits", same, inside);
  CHECK(near == inside, "%d of %d lookups within 1e-6 of the plane", near, inside);
  /* the batch path gives the same bits */
  double p[30], phi[10], g[30];
  for (int m = 0; m < 10; m++) random_point(&p[3 * m]);
  lsdem_band_eval_many(&t.band, 10, p, phi, g);
  int batch_same = 0;
  for (int m = 0; m < 10; m++) {
    double g1[3];
    batch_same += lsdem_band_eval(&t.band, &p[3 * m], g1) == phi[m];
  }
  CHECK(batch_same == 10, "batch and single lookups differ (%d same)", batch_same);
  free_band(&t);
}

/* Background and coarse level: every value (band or background, inside or beyond the
 * box) is at most L times the distance to the solid where it is >= 0, and has the sign
 * of the side; a point far above reads more than the width once the coarse level is on. */
static void test_background_is_a_lower_bound(void)
{
  test_band t;
  make_band_with_far(&t);
  CHECK(t.band.nbricks < t.band.nb[0] * t.band.nb[1] * t.band.nb[2] / 2,
        "%lld bricks stored: the band should leave most slots empty", (long long)t.band.nbricks);
  int bad = 0, sign = 0, beyond = 0;
  for (int m = 0; m < 20000; m++) {
    double p[3], g[3];
    random_point(p);
    for (int a = 0; a < 3; a++) p[a] = 1.4 * p[a] - 0.2 * (a < 2 ? 2.4 : 1.6); /* some outside */
    /* beyond the box the band continues as its boundary values: the clamped point's */
    double q[3];
    for (int a = 0; a < 3; a++) q[a] = fmin(fmax(p[a], 0.0), (t.band.n[a] - 1) * t.band.h);
    const double d = plane_distance(q), phi = lsdem_band_eval(&t.band, p, g);
    if (fabs(d) > 0.11) sign += (phi > 0.0) != (d > 0.0);
    if (phi >= 0.0) bad += phi > LSDEM_BAND_LIPSCHITZ * fmax(d, 0.0) + 1e-6;
    beyond += phi > 0.1 + 1e-9;
  }
  CHECK(sign == 0, "%d points off the band read the wrong side", sign);
  CHECK(bad == 0, "%d values exceed L times the distance to the solid", bad);
  CHECK(beyond > 1000, "%d points read beyond the width: the coarse level is unused", beyond);
  /* a slot adjacent to the band reads exactly the width */
  double top[3] = {0.02, 0.02, 1.55}, g[3];
  const double dtop = plane_distance(top);
  const double vtop = lsdem_band_eval(&t.band, top, g);
  CHECK(vtop >= 0.1 && vtop <= dtop, "far above: %g, not in [width, distance %g]", vtop, dtop);
  free_band(&t);
}

static void test_tunnelled_and_checks(void)
{
  test_band t;
  make_band(&t, 0.1, 1);
  CHECK(lsdem_band_tunnelled(&t.band, 0.1), "%s", "a node at the width's depth tunnelled");
  CHECK(!lsdem_band_tunnelled(&t.band, 0.05), "%s", "half the width is not tunnelling");
  lsdem_error err;
  t.index[3] = (int32_t)t.band.nbricks;
  CHECK(lsdem_band_check(&t.band, &err) == LSDEM_ERR_FORMAT && strstr(err.msg, "index entry 3"),
        "bad index entry: %s", err.msg);
  t.index[3] = 3;
  t.phi[100] = 0.2f;
  CHECK(lsdem_band_check(&t.band, &err) == LSDEM_ERR_FORMAT && strstr(err.msg, "outside"),
        "sample beyond the width: %s", err.msg);
  t.phi[100] = 0.0f;
  t.band.width = 100.0;
  CHECK(lsdem_band_check(&t.band, &err) == LSDEM_ERR_FORMAT && strstr(err.msg, "width"),
        "width of 2000 h: %s", err.msg);
  free_band(&t);
}

/* A band wall: rejection by one lookup at the centre, crossing by the sign only beyond
 * the band's width (the value there is a bound, not a distance), with the velocity
 * prediction inside it. */
static void test_band_wall(void)
{
  test_band t;
  make_band_with_far(&t);
  lsdem_boundary w;
  lsdem_boundary_band(&w, &t.band);
  /* 1.3 above the plane where it is lowest, two brick layers from the stored ones */
  double above[3] = {2.2, 0.2, (C - N[0] * 2.2 - N[1] * 0.2) / N[2] + 1.3 / N[2]};
  /* L r > width: only the coarse level rejects it */
  double ga[3];
  CHECK(!lsdem_boundary_may_touch(&w, &w.pose, above, 0.1), "far grain rejected (phi %g at z %g)",
        lsdem_band_eval(&t.band, above, ga), above[2]);
  CHECK(lsdem_boundary_may_touch(&w, &w.pose, above, 0.95), "%s", "grain reaching it kept");
  const double down[3] = {0.0, 0.0, -1000.0};
  double d, vn;
  CHECK(!lsdem_boundary_crossing(&w, &w.pose, above, down, 1e-3, &d, &vn),
        "beyond the band a fast grain is not predicted through (d %g vn %g)", d, vn);
  double close[3] = {1.2, 1.2, (C - N[0] * 1.2 - N[1] * 1.2) / N[2] + 0.05 / N[2]};
  CHECK(lsdem_boundary_crossing(&w, &w.pose, close, down, 1e-3, &d, &vn),
        "in the band the prediction holds (d %g vn %g)", d, vn);
  const double slow[3] = {0.0, 0.0, -1.0};
  CHECK(!lsdem_boundary_crossing(&w, &w.pose, close, slow, 1e-3, &d, &vn), "%s",
        "a slow grain in the band does not cross");
  CHECK(lsdem_boundary_tunnelled(&w, 0.1) && !lsdem_boundary_tunnelled(&w, 0.01), "%s",
        "tunnelling at the width");
  free_band(&t);
}

int main(void)
{
  test_lookup_matches_plane_and_dense();
  test_background_is_a_lower_bound();
  test_tunnelled_and_checks();
  test_band_wall();
  return lsdem_test_summary();
}
