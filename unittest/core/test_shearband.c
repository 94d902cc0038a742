/* test_shearband.c -- shear-band measurement (shearband.c): a synthetic band (indicator large
 * in a slab of known normal and width inside a cylinder of jittered lattice points, small
 * noise elsewhere) gives back its dip, azimuth and width; an X of two slabs gives two
 * planes; the per-point flags, determinism, the theory angles against hand values; the
 * principal sizes of a tilted lattice box against closed forms; sheets of an X, a rod and a
 * ball, and pieces of one plane joined across zones. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

#define RADIUS 8.0 /* cylinder: axis z, lattice spacing 1 */
#define HALF_HEIGHT 20.0
#define MAXPTS 10000

static double xs[3 * MAXPTS], val[MAXPTS];
static int band[MAXPTS];

/* lattice points (spacing 1, each coordinate jittered by up to 0.25) inside the cylinder */
static int cylinder_points(double *x)
{
  int n = 0;
  for (int i = -8; i <= 8; i++)
    for (int j = -8; j <= 8; j++)
      for (int k = -20; k <= 20; k++) {
        const double p[3] = {i + 0.25 * srand1(), j + 0.25 * srand1(), k + 0.25 * srand1()};
        if (p[0] * p[0] + p[1] * p[1] > RADIUS * RADIUS || fabs(p[2]) > HALF_HEIGHT) continue;
        memcpy(x + 3 * n++, p, sizeof p);
      }
  return n;
}

/* the upward unit normal of a plane of dip and azimuth (degrees), written out by hand */
static void normal_of(double dip, double azimuth, double n[3])
{
  const double d = dip * PI / 180.0, a = azimuth * PI / 180.0;
  n[0] = sin(d) * cos(a);
  n[1] = sin(d) * sin(a);
  n[2] = cos(d);
}

static int in_slab(const double *x, const double n[3], double width)
{
  return fabs(x[0] * n[0] + x[1] * n[1] + x[2] * n[2]) <= 0.5 * width;
}

/* indicator: 1 + noise inside any of the slabs (normals through the origin), noise outside */
static void band_indicator(int n, const double *x, int nslab, const double (*nrm)[3],
                           double width)
{
  for (int i = 0; i < n; i++) {
    int inside = 0;
    for (int s = 0; s < nslab; s++) inside |= in_slab(x + 3 * i, nrm[s], width);
    val[i] = inside + 0.05 * urand();
  }
}

/* |a - b| on the circle of degrees */
static double azimuth_gap(double a, double b)
{
  const double d = fmod(fabs(a - b), 360.0);
  return d > 180.0 ? 360.0 - d : d;
}

/* every field of the first np planes equal bit for bit (memcmp of the structs would also
 * compare their tail padding, which nothing sets) */
static int same_planes(const lsdem_shearband_plane *a, const lsdem_shearband_plane *b, int np)
{
  int same = 1;
  for (int q = 0; q < np; q++)
    same &= memcmp(a[q].normal, b[q].normal, sizeof a[q].normal) == 0 &&
            memcmp(a[q].centre, b[q].centre, sizeof a[q].centre) == 0 &&
            memcmp(&a[q].dip, &b[q].dip, sizeof(double)) == 0 &&
            memcmp(&a[q].azimuth, &b[q].azimuth, sizeof(double)) == 0 &&
            memcmp(&a[q].inlier_fraction, &b[q].inlier_fraction, sizeof(double)) == 0 &&
            memcmp(&a[q].thickness, &b[q].thickness, sizeof(double)) == 0 &&
            a[q].ninliers == b[q].ninliers;
  return same;
}

static void test_single_band(void)
{
  const int n = cylinder_points(xs);
  double nrm[1][3];
  /* the least-squares refit tilts by about tan(dip) w^2 / L^2 rad when the band's ends are
   * cut by the vertical wall (L ~ 28 the band's length here): 0.4 deg for w = 2 */
  const double width = 2.0;
  normal_of(55.0, 30.0, nrm[0]);
  band_indicator(n, xs, 1, (const double(*)[3]) nrm, width);
  const lsdem_shearband_params p = {2.0, 1.5, 2, 500, 7};
  lsdem_shearband_plane pl[2], again[2];
  int np = 0, np2 = 0;
  CHECK(lsdem_shearband_fit(n, xs, val, &p, pl, &np, band) == LSDEM_OK, "single band");
  CHECK(np >= 1, "a plane found (%d)", np);
  CHECK_NEAR(pl[0].dip, 55.0, 1.0);
  CHECK(azimuth_gap(pl[0].azimuth, 30.0) <= 2.0, "azimuth %g, expected 30", pl[0].azimuth);
  CHECK_REL(pl[0].thickness, width, 0.10);
  CHECK(pl[0].inlier_fraction >= 0.99, "every flagged point is in the band: %g",
        pl[0].inlier_fraction);
  CHECK_NEAR(pl[0].normal[0] * pl[0].normal[0] + pl[0].normal[1] * pl[0].normal[1] +
                 pl[0].normal[2] * pl[0].normal[2], 1.0, 1e-12);
  int inside = 0, inside_flagged = 0, outside_flagged = 0;
  for (int i = 0; i < n; i++) {
    const double d = fabs(xs[3 * i] * nrm[0][0] + xs[3 * i + 1] * nrm[0][1] +
                          xs[3 * i + 2] * nrm[0][2]);
    if (d <= 0.5 * width - 0.3) {
      inside++;
      inside_flagged += band[i] == 1;
    } else if (d >= 0.5 * width + 0.3) {
      outside_flagged += band[i] != 0 && band[i] != 2;
    }
  }
  CHECK(inside > 300 && inside_flagged >= 0.98 * inside, "band flag inside: %d of %d",
        inside_flagged, inside);
  CHECK(outside_flagged == 0, "%d points well outside the band flagged 1", outside_flagged);
  CHECK(lsdem_shearband_fit(n, xs, val, &p, again, &np2, band) == LSDEM_OK && np2 == np &&
            same_planes(pl, again, np),
        "the same input gives bit-identical planes");
}

static void test_x_bands(void)
{
  const int n = cylinder_points(xs);
  double nrm[2][3];
  normal_of(55.0, 0.0, nrm[0]);
  normal_of(55.0, 180.0, nrm[1]);
  band_indicator(n, xs, 2, (const double(*)[3]) nrm, 2.0);
  /* the two slabs hold ~16 % of the points: mean + 2 sd would be close to the band value,
   * so flag at k = 1.5 */
  lsdem_shearband_params p = {1.5, 1.5, 2, 500, 11};
  lsdem_shearband_plane pl[2];
  int np = 0;
  CHECK(lsdem_shearband_fit(n, xs, val, &p, pl, &np, band) == LSDEM_OK && np == 2,
        "X: two planes (%d)", np);
  if (np != 2) return;
  for (int q = 0; q < 2; q++) CHECK_NEAR(pl[q].dip, 55.0, 1.0);
  const int first = azimuth_gap(pl[0].azimuth, 0.0) < 90.0;
  CHECK(azimuth_gap(pl[0].azimuth, first ? 0.0 : 180.0) <= 2.0 &&
            azimuth_gap(pl[1].azimuth, first ? 180.0 : 0.0) <= 2.0,
        "X azimuths %g and %g, expected 0 and 180", pl[0].azimuth, pl[1].azimuth);
  CHECK(pl[0].inlier_fraction + pl[1].inlier_fraction >= 0.98, "X inliers %g + %g",
        pl[0].inlier_fraction, pl[1].inlier_fraction);
  int seen[3] = {0, 0, 0};
  for (int i = 0; i < n; i++) seen[band[i]]++;
  CHECK(seen[1] > 100 && seen[2] > 100, "points in both bands: %d %d", seen[1], seen[2]);
  p.planes = 1;
  CHECK(lsdem_shearband_fit(n, xs, val, &p, pl, &np, band) == LSDEM_OK && np == 1,
        "planes 1: one plane (%d)", np);
}

static void test_degenerate(void)
{
  const lsdem_shearband_params p = {2.0, 1.0, 2, 100, 1};
  lsdem_shearband_params bad = p;
  lsdem_shearband_plane pl[2];
  int np = -1;
  const double flat[4] = {1.0, 1.0, 1.0, 1.0};
  CHECK(lsdem_shearband_fit(4, xs, flat, &p, pl, &np, band) == LSDEM_OK && np == 0,
        "no point above mean + k sd: no plane (%d)", np);
  bad.planes = 3;
  CHECK(lsdem_shearband_fit(4, xs, flat, &bad, pl, &np, band) == LSDEM_ERR_ARG, "planes 3");
  bad = p;
  bad.threshold = 0.0;
  CHECK(lsdem_shearband_fit(4, xs, flat, &bad, pl, &np, band) == LSDEM_ERR_ARG, "threshold 0");
}

static void test_theory(void)
{
  double a[3];
  lsdem_shearband_theory(40.0, 10.0, a);
  CHECK_NEAR(a[0], 65.0, 1e-12); /* Coulomb 45 + 40/2 */
  CHECK_NEAR(a[1], 50.0, 1e-12); /* Roscoe 45 + 10/2 */
  CHECK_NEAR(a[2], 57.5, 1e-12); /* Arthur 45 + 50/4 */
}

/* The profile width: a Gaussian band of sigma 1 (FWHM 2 sqrt(2 ln 2) sigma) across the
 * cylinder, noise 0.02; seen through a Gaussian kernel of sigma 0.75 (a profile of sigma
 * sqrt(1 + 0.75^2)), the kernel's FWHM given back gives the band's own width. Within 5 %
 * (bins of 0.25 against a width of 2.4; the band narrow against the cylinder, so that the
 * median of all values is the background). */
static void test_profile_width(void)
{
  const int n = cylinder_points(xs);
  const double fwhm_of_sigma = 2.0 * sqrt(2.0 * log(2.0));
  lsdem_shearband_plane pl;
  memset(&pl, 0, sizeof pl);
  normal_of(55.0, 30.0, pl.normal);
  const double sk = 0.75, sb = 1.0, sseen = sqrt(sb * sb + sk * sk);
  for (int i = 0; i < n; i++) {
    const double s = lsdem_dot3(&xs[3 * i], pl.normal);
    val[i] = exp(-0.5 * s * s / (sseen * sseen)) + 0.02 * srand1();
  }
  double w = 0.0, wc = 0.0;
  CHECK(lsdem_shearband_profile(n, xs, val, &pl, 0.25, 3.0, 0.0, &w, &wc) == LSDEM_OK,
        "profile");
  CHECK_REL(w, fwhm_of_sigma * sseen, 0.05);
  CHECK(wc == w, "no kernel: corrected %g = measured %g", wc, w);
  CHECK(lsdem_shearband_profile(n, xs, val, &pl, 0.25, 3.0, fwhm_of_sigma * sk, &w, &wc) ==
            LSDEM_OK, "profile with a kernel");
  CHECK_REL(wc, fwhm_of_sigma * sb, 0.05);
  /* a flat indicator has no band: NaN */
  for (int i = 0; i < n; i++) val[i] = 1.0;
  CHECK(lsdem_shearband_profile(n, xs, val, &pl, 0.25, 3.0, 0.0, &w, &wc) == LSDEM_OK &&
            isnan(w) && isnan(wc), "flat: %g %g", w, wc);
  CHECK(lsdem_shearband_profile(n, xs, val, &pl, 0.0, 3.0, 0.0, &w, &wc) == LSDEM_ERR_ARG,
        "bin 0 accepted");
}

/* D50 by volume on hand-worked sieve curves: diameters 1 and 2 (volumes 1 : 8, midpoints
 * of their shares at 1/18 and 5/9) cross one half at 1 + (0.5 - 1/18) / (5/9 - 1/18); two
 * of each, 1 and 2 (points 1/36, 3/36, 6/18, 14/18): 2; equal grains: their diameter. */
static void test_median_diameter(void)
{
  const double v1 = PI / 6.0, v2 = 8.0 * PI / 6.0;
  const double a[2] = {v2, v1}, b[4] = {v1, v2, v1, v2}, c[3] = {v2, v2, v2};
  CHECK_REL(lsdem_median_diameter(2, a), 1.0 + (0.5 - 1.0 / 18.0) / (5.0 / 9.0 - 1.0 / 18.0),
            1e-12);
  CHECK_REL(lsdem_median_diameter(4, b), 2.0, 1e-12);
  CHECK_REL(lsdem_median_diameter(3, c), 2.0, 1e-12);
  CHECK(lsdem_median_diameter(0, a) == 0.0, "no grains");
}

/* Principal sizes: a lattice box of 21 x 11 x 3 points at spacing 1 (per axis the variance
 * of 0..n-1 is (n^2 - 1)/12, so sqrt(12 var) = sqrt(n^2 - 1)), tilted by a known rotation:
 * sizes sqrt(440), sqrt(120), sqrt(8), the normal the rotated short axis, pointing up. */
static void test_point_sizes(void)
{
  static double x[3 * 21 * 11 * 3];
  const double dip = 30.0 * PI / 180.0; /* rotation about y: z axis -> (sin, 0, cos) */
  int n = 0;
  for (int i = 0; i < 21; i++)
    for (int j = 0; j < 11; j++)
      for (int k = 0; k < 3; k++) {
        const double p[3] = {i - 10.0, j - 5.0, k - 1.0};
        x[3 * n] = cos(dip) * p[0] + sin(dip) * p[2];
        x[3 * n + 1] = p[1] + 7.0;
        x[3 * n + 2] = -sin(dip) * p[0] + cos(dip) * p[2] + 3.0;
        n++;
      }
  lsdem_shearband_plane pl;
  double sizes[3];
  CHECK(lsdem_point_sizes(n, x, &pl, sizes) == LSDEM_OK, "point sizes failed");
  CHECK_REL(sizes[0], sqrt(440.0), 1e-12);
  CHECK_REL(sizes[1], sqrt(120.0), 1e-12);
  CHECK_REL(sizes[2], sqrt(8.0), 1e-12);
  CHECK(fabs(pl.dip - 30.0) < 1e-9 && fabs(pl.azimuth - 0.0) < 1e-9 &&
            fabs(pl.centre[1] - 7.0) < 1e-12 && fabs(pl.centre[2] - 3.0) < 1e-12,
        "box: dip %g azimuth %g centre %g %g %g", pl.dip, pl.azimuth, pl.centre[0],
        pl.centre[1], pl.centre[2]);
  CHECK(lsdem_point_sizes(1, x, &pl, sizes) == LSDEM_ERR_ARG, "one point accepted");
}

/* points of a jittered lattice (spacing 1) inside a disc of radius r about c, in the plane
 * of unit normal nrm, `layers` thick; returns their count (appended at x + 3 n0) */
static int disc_points(double *x, int n0, const double c[3], const double nrm[3], double r,
                       int layers)
{
  double t1[3], t2[3];
  const double e[3] = {fabs(nrm[0]) < 0.9 ? 1.0 : 0.0, fabs(nrm[0]) < 0.9 ? 0.0 : 1.0, 0.0};
  lsdem_cross3(nrm, e, t1);
  const double l = sqrt(lsdem_dot3(t1, t1));
  for (int a = 0; a < 3; a++) t1[a] /= l;
  lsdem_cross3(nrm, t1, t2);
  int n = n0;
  for (int i = -(int) r; i <= (int) r; i++)
    for (int j = -(int) r; j <= (int) r; j++)
      for (int k = 0; k < layers; k++) {
        if (i * i + j * j > r * r) continue;
        const double u = i + 0.2 * srand1(), v = j + 0.2 * srand1();
        const double w = k - 0.5 * (layers - 1) + 0.2 * srand1();
        for (int a = 0; a < 3; a++) x[3 * n + a] = c[a] + u * t1[a] + v * t2[a] + w * nrm[a];
        n++;
      }
  return n;
}

/* Sheets: an X of two slabs (dips 55 deg, azimuths 0 and 180) is two sheets whose normals
 * and points come back, a rod and a ball none; two coplanar pieces found apart are joined
 * into one band of both pieces' points, a third one tilted 30 deg is a band of its own, a
 * short piece is none. */
static void test_sheets(void)
{
  static double x[3 * MAXPTS];
  static int label[MAXPTS], group[64];
  lsdem_sheet sheet[64], band[64];
  const lsdem_sheet_params p = {1.0, 3.0, 6.0, 2.0, 400, 7};
  double na[3], nb[3];
  normal_of(55.0, 0.0, na);
  normal_of(55.0, 180.0, nb);
  const double origin[3] = {0.0, 0.0, 0.0};
  int n = disc_points(x, 0, origin, na, 10.0, 3);
  const int first = n;
  n = disc_points(x, n, origin, nb, 10.0, 3);
  int ns = 0;
  CHECK(lsdem_sheets_fit(n, x, &p, 64, sheet, &ns, label) == LSDEM_OK && ns == 2,
        "X: %d sheets", ns);
  if (ns == 2) {
    int found_a = 0, found_b = 0, wrong = 0;
    for (int s = 0; s < 2; s++) {
      const double *m = sheet[s].plane.normal;
      const int is_a = fabs(lsdem_dot3(m, na)) > cos(1.5 * PI / 180.0);
      const int is_b = fabs(lsdem_dot3(m, nb)) > cos(1.5 * PI / 180.0);
      found_a |= is_a;
      found_b |= is_b;
      for (int i = 0; i < n; i++) /* a point labelled with a sheet lies in its slab */
        wrong += label[i] == s && ((i < first) != is_a) && fabs(x[3 * i]) > 2.0;
      /* thickness: the 3 layers' sqrt(8), and the other slab's points where they cross */
      CHECK(sheet[s].length > 12.0 && sheet[s].breadth > 12.0 && sheet[s].plane.thickness < 4.5,
            "X sheet %d: %g x %g x %g", s, sheet[s].length, sheet[s].breadth,
            sheet[s].plane.thickness);
    }
    CHECK(found_a && found_b && wrong == 0, "X: normals %d %d, %d points in the other sheet",
          found_a, found_b, wrong);
  }
  /* a rod (3 x 3 x 30) and a ball of radius 4: no sheet */
  n = 0;
  for (int k = 0; k < 30; k++)
    for (int i = -1; i <= 1; i++)
      for (int j = -1; j <= 1; j++) {
        const double q[3] = {i + 0.1 * srand1(), j + 0.1 * srand1(), k + 0.1 * srand1()};
        memcpy(x + 3 * n++, q, sizeof q);
      }
  CHECK(lsdem_sheets_fit(n, x, &p, 64, sheet, &ns, label) == LSDEM_OK && ns == 0,
        "rod: %d sheets", ns);
  n = 0;
  for (int i = -4; i <= 4; i++)
    for (int j = -4; j <= 4; j++)
      for (int k = -4; k <= 4; k++)
        if (i * i + j * j + k * k <= 16) {
          const double q[3] = {i, j, k};
          memcpy(x + 3 * n++, q, sizeof q);
        }
  CHECK(lsdem_sheets_fit(n, x, &p, 64, sheet, &ns, label) == LSDEM_OK && ns == 0,
        "ball: %d sheets", ns);

  /* joining: pieces of one plane (dip 55; discs of radius 8, 24 apart along it), a tilted
   * piece (radius 12: sqrt(3) 12 = 20.8 long), a short one (radius 4: 6.9 long, a sheet
   * of its zone, not a band) */
  double t[3], c2[3], nt[3];
  const double e[3] = {0.0, 1.0, 0.0};
  lsdem_cross3(na, e, t); /* in the plane */
  for (int a = 0; a < 3; a++) c2[a] = 24.0 * t[a];
  normal_of(25.0, 90.0, nt);
  const double c3[3] = {0.0, 40.0, 0.0};
  const double c4[3] = {10.0 * na[0], -40.0, 10.0 * na[2]}; /* parallel, 10 off the plane */
  int ends[5] = {0};
  n = disc_points(x, 0, origin, na, 8.0, 3);
  ends[1] = n;
  n = disc_points(x, n, c2, na, 8.0, 3);
  ends[2] = n;
  n = disc_points(x, n, c3, nt, 12.0, 3);
  ends[3] = n;
  n = disc_points(x, n, c4, na, 4.0, 3);
  ends[4] = n;
  /* each piece fitted apart, as zones are; labels made global */
  int total = 0;
  for (int z = 0; z < 4; z++) {
    int found = 0;
    lsdem_sheet_params pz = p;
    pz.min_length = 3.0;
    CHECK(lsdem_sheets_fit(ends[z + 1] - ends[z], x + 3 * ends[z], &pz, 64 - total,
                           sheet + total, &found, label + ends[z]) == LSDEM_OK && found == 1,
          "piece %d: %d sheets", z, found);
    for (int i = ends[z]; i < ends[z + 1]; i++)
      if (label[i] >= 0) label[i] += total;
    total += found;
  }
  int nbands = 0;
  CHECK(lsdem_sheets_join(n, x, label, total, sheet, 10.0, 2.0, 20.0, group, band, &nbands) ==
            LSDEM_OK && nbands == 2, "join: %d bands", nbands);
  if (nbands == 2 && total == 4) {
    /* the largest group first: the tilted piece */
    CHECK(group[0] == 1 && group[1] == 1 && group[2] == 0 && group[3] == -1,
          "join: groups %d %d %d %d", group[0], group[1], group[2], group[3]);
    CHECK(band[1].plane.ninliers == sheet[0].plane.ninliers + sheet[1].plane.ninliers &&
              band[1].length > 35.0 && fabs(lsdem_dot3(band[1].plane.normal, na)) >
              cos(1.0 * PI / 180.0) && fabs(band[0].plane.dip - 25.0) < 1.5,
          "join: %d points, length %g, dip %g; tilted dip %g", band[1].plane.ninliers,
          band[1].length, band[1].plane.dip, band[0].plane.dip);
  }
  CHECK(lsdem_sheets_fit(n, x, &p, 64, sheet, &ns, NULL) == LSDEM_ERR_ARG, "no labels accepted");
}

int main(void)
{
  test_single_band();
  test_x_bands();
  test_degenerate();
  test_theory();
  test_profile_width();
  test_median_diameter();
  test_point_sizes();
  test_sheets();
  return lsdem_test_summary();
}
