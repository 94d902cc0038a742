/* test_impulse_cap.c -- the manifold cap of impulse contacts (lsdem_impulse_cap_contacts,
 * issue 33 item 4) against expectations worked out by hand on grids (the picks are
 * spelled out at each case) and against properties that do not depend on the
 * implementation: the kept contacts are originals, unchanged and in order; the deepest
 * and the farthest from it are among them; the kept set is the same whatever the order
 * of the input; n <= max leaves the contacts byte-identical. */
#include <string.h>

#include "lsdem.h"
#include "lsdem_test.h"

enum { MAXN = 64 };

static lsdem_impulse_contact contact_at(double x, double y, double z,
                                        const double normal[3], double depth)
{
  lsdem_impulse_contact c;
  memset(&c, 0, sizeof c);
  c.a = 0;
  c.b = 1;
  c.point[0] = x;
  c.point[1] = y;
  c.point[2] = z;
  for (int i = 0; i < 3; i++) c.normal[i] = normal[i];
  c.depth = depth;
  c.mu = 0.5;
  c.restitution = 0.25;
  return c;
}

/* Caps a copy of orig[0..n) and checks that the result is exactly the originals with the
 * given indices (increasing), byte for byte. */
static void check_kept(const char *what, const lsdem_impulse_contact *orig, int n, int max,
                       const int *expected, int nexpected)
{
  lsdem_impulse_contact c[MAXN];
  int32_t scratch[MAXN];
  memcpy(c, orig, (size_t)n * sizeof *c);
  const int m = lsdem_impulse_cap_contacts(c, n, max, scratch);
  CHECK(m == nexpected, "%s: kept %d, expected %d", what, m, nexpected);
  for (int k = 0; k < m && k < nexpected; k++)
    CHECK(memcmp(&c[k], &orig[expected[k]], sizeof c[k]) == 0,
          "%s: kept contact %d is not original %d (%g, %g, %g)", what, k, expected[k],
          c[k].point[0], c[k].point[1], c[k].point[2]);
}

/* ---------------------------------------------------------- the 5 x 5 face ---- */

/* A square face of 5 x 5 contacts, index 5 j + i at (i h, j h, z_ij), normal +z, depth
 * 0.01 except the interior contact (1, 1) (index 6), 0.02. lift: z_ij = -depth - a
 * curvature, out of the plane: the projection on the plane normal to +z must ignore it. */
static void face_5x5(lsdem_impulse_contact *c, int lift)
{
  const double h = 0.25, up[3] = {0, 0, 1};
  for (int j = 0; j < 5; j++)
    for (int i = 0; i < 5; i++) {
      const double depth = (i == 1 && j == 1) ? 0.02 : 0.01;
      const double z = lift ? -depth - 0.05 * ((i - 2) * (i - 2) + (j - 1) * (j - 1)) : 0.0;
      c[5 * j + i] = contact_at(i * h, j * h, z, up, depth);
    }
}

/* Area of the convex hull of four points of the plane z = 0: the largest of the four
 * triangles (one point inside) and of the three quadrilaterals' shoelace areas (a convex
 * one is the hull; concave or crossed ones are smaller). */
static double tri_area(const double *a, const double *b, const double *c)
{
  return 0.5 * fabs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}
static double quad_area(const double *a, const double *b, const double *c, const double *d)
{
  return 0.5 * fabs((c[0] - a[0]) * (d[1] - b[1]) - (c[1] - a[1]) * (d[0] - b[0]));
}
static double hull_area4(const double *p, const double *q, const double *r, const double *s)
{
  double A = fmax(fmax(tri_area(p, q, r), tri_area(p, q, s)),
                  fmax(tri_area(p, r, s), tri_area(q, r, s)));
  A = fmax(A, fmax(quad_area(p, q, r, s),
                   fmax(quad_area(p, r, q, s), quad_area(p, q, s, r))));
  return A;
}

/* Four kept of the 5 x 5 face: the deepest (1,1) [6]; the farthest from it, (4,4) [24]
 * (distance^2 18 h^2, the next 13 h^2); the largest triangle with those two,
 * 3 |j - i| h^2 / 2: (4,0) [4] and (0,4) [20] tie, both at the same distance from the
 * kept, so the lower index 4; then the largest area added to that triangle: (0,4) adds
 * 6 h^2 (the next, (0,3), 4.5 h^2). The deepest and the three corners that span, with it,
 * 12 h^2 -- checked against every set of four contacts containing the deepest. */
static void test_face_four(void)
{
  lsdem_impulse_contact face[25];
  const int expected[4] = {4, 6, 20, 24};
  for (int lift = 0; lift < 2; lift++) {
    face_5x5(face, lift);
    check_kept(lift ? "5x5 face, lifted" : "5x5 face", face, 25, 4, expected, 4);
  }
  face_5x5(face, 0);
  double best = 0.0;
  int nbest = 0;
  for (int a = 0; a < 25; a++)
    for (int b = a + 1; b < 25; b++)
      for (int d = b + 1; d < 25; d++) {
        if (a == 6 || b == 6 || d == 6) continue;
        const double A =
            hull_area4(face[6].point, face[a].point, face[b].point, face[d].point);
        if (A > best + 1e-12) {
          best = A;
          nbest = 1;
        } else if (fabs(A - best) <= 1e-12) {
          nbest++;
        }
      }
  const double h = 0.25;
  CHECK_NEAR(best, 12.0 * h * h, 1e-15);
  CHECK(nbest == 1, "%d sets of four span the largest area", nbest);
  CHECK_NEAR(hull_area4(face[4].point, face[6].point, face[20].point, face[24].point),
             best, 1e-15);
}

/* Other caps of the same face. max 2: the deepest and the farthest. max 6, past the area
 * rule, farthest-point sampling: the distances^2 (h^2 units) to the four kept are at
 * most 5, reached by (3,2) [13] and (2,3) [17] (lower index 13); with (3,2) kept, the
 * largest is 4, at (2,4) [22] alone. */
static void test_face_other_caps(void)
{
  lsdem_impulse_contact face[25];
  face_5x5(face, 0);
  const int two[2] = {6, 24}, three[3] = {4, 6, 24}, six[6] = {4, 6, 13, 20, 22, 24};
  check_kept("5x5 face, max 2", face, 25, 2, two, 2);
  check_kept("5x5 face, max 3", face, 25, 3, three, 3);
  check_kept("5x5 face, max 6", face, 25, 6, six, 6);
}

/* The area rule is not farthest-point sampling: deepest P0 (0,0) [1], farthest P1 (10,0)
 * [4]; the largest triangle with them P2 (5,5) [3] (twice its area 50; X 45, Y 10); then
 * X (5,-4.5) [0] adds 45 (twice the area), Y (-7.5,-1) [2] only 42.5 though farther from
 * the kept (distance^2 57.25 against 45.25): Y is dropped. With max 3 the farthest from
 * the kept, Y, loses to P2 too. */
static void test_area_beats_distance(void)
{
  const double up[3] = {0, 0, 1};
  const lsdem_impulse_contact s[5] = {
      contact_at(5, -4.5, 0, up, 0.01), contact_at(0, 0, 0, up, 0.02),
      contact_at(-7.5, -1, 0, up, 0.01), contact_at(5, 5, 0, up, 0.01),
      contact_at(10, 0, 0, up, 0.01)};
  const int three[3] = {1, 3, 4}, four[4] = {0, 1, 3, 4};
  check_kept("area against distance, max 3", s, 5, 3, three, 3);
  check_kept("area against distance, max 4", s, 5, 4, four, 4);
}

/* ---------------------------------------------------------- n <= max ---- */

static void random_contacts(lsdem_impulse_contact *c, int n)
{
  for (int k = 0; k < n; k++) {
    double nrm[3] = {0.1 * srand1(), 0.1 * srand1(), 1.0};
    const double len = sqrt(lsdem_dot3(nrm, nrm));
    for (int i = 0; i < 3; i++) nrm[i] /= len;
    c[k] = contact_at(srand1(), srand1(), 0.01 * srand1(), nrm, 0.01 * urand());
    c[k].a = k % 3;
    c[k].b = 3 + k % 2;
    c[k].mu = urand();
    c[k].restitution = urand();
  }
}

static void test_few_contacts_untouched(void)
{
  lsdem_impulse_contact orig[4], c[4];
  int32_t scratch[4] = {-7, -7, -7, -7};
  random_contacts(orig, 4);
  const int cases[][2] = {{0, 4}, {1, 4}, {3, 4}, {4, 4}, {4, 5}, {1, 1}};
  for (size_t t = 0; t < sizeof cases / sizeof cases[0]; t++) {
    const int n = cases[t][0], max = cases[t][1];
    memcpy(c, orig, sizeof c);
    const int m = lsdem_impulse_cap_contacts(c, n, max, scratch);
    CHECK(m == n, "n %d max %d: returned %d", n, max, m);
    CHECK(memcmp(c, orig, sizeof c) == 0, "n %d max %d: contacts changed", n, max);
  }
}

/* ---------------------------------------------------------- ties ---- */

/* A 3 x 3 grid, index 3 j + i at (i, j), every depth equal: the deepest is index 0 (0,0),
 * the farthest (2,2) [8]; the triangles with them tie between (2,0) [2] and (0,2) [6],
 * equally far from the kept: 2; the area added is then largest at (0,2) [6] (2, against 1
 * at (1,2) and (0,1)): the four corners. */
static void test_ties_grid(void)
{
  lsdem_impulse_contact g[9];
  const double up[3] = {0, 0, 1};
  for (int j = 0; j < 3; j++)
    for (int i = 0; i < 3; i++) g[3 * j + i] = contact_at(i, j, 0.0, up, 0.01);
  const int three[3] = {0, 2, 8}, four[4] = {0, 2, 6, 8};
  check_kept("3x3 ties, max 3", g, 9, 3, three, 3);
  check_kept("3x3 ties, max 4", g, 9, 4, four, 4);
}

/* The centre of a square first, then its corners counter-clockwise from (0,0), all depths
 * equal: the deepest is the centre [0]; the four corners are equally far: (0,0) [1]; the
 * triangles with those tie between (2,0) [2] and (0,2) [4]: 2; then (2,2) [3] and (0,2)
 * [4] add the same area, 1, at the same distance: 3. */
static void test_ties_centre_first(void)
{
  const double up[3] = {0, 0, 1};
  const lsdem_impulse_contact s[5] = {
      contact_at(1, 1, 0, up, 0.01), contact_at(0, 0, 0, up, 0.01),
      contact_at(2, 0, 0, up, 0.01), contact_at(2, 2, 0, up, 0.01),
      contact_at(0, 2, 0, up, 0.01)};
  const int two[2] = {0, 1}, three[3] = {0, 1, 2}, four[4] = {0, 1, 2, 3};
  check_kept("centre first, max 2", s, 5, 2, two, 2);
  check_kept("centre first, max 3", s, 5, 3, three, 3);
  check_kept("centre first, max 4", s, 5, 4, four, 4);
}

/* Contacts in a line (an edge on a face): every area is 0, so the picks go to the
 * distance to the kept set. Nine at x = 0..8, deepest x = 3: the farthest x = 8, then x =
 * 0 (3 from the kept), then x = 5 and x = 6 tie at 2: 5. Both ends kept. */
static void test_edge_keeps_both_ends(void)
{
  lsdem_impulse_contact e[9];
  const double up[3] = {0, 0, 1};
  for (int i = 0; i < 9; i++) e[i] = contact_at(i, 0.0, 0.0, up, i == 3 ? 0.02 : 0.01);
  const int four[4] = {0, 3, 5, 8};
  check_kept("edge, max 4", e, 9, 4, four, 4);
}

/* Contacts that coincide in the plane (stacked along the normal): every distance and area
 * is 0, the picks go by index: the deepest [1], then [0]; the count is still max. */
static void test_stacked_along_normal(void)
{
  const double up[3] = {0, 0, 1};
  const lsdem_impulse_contact s[3] = {contact_at(0, 0, 0, up, 0.01),
                                      contact_at(0, 0, -0.1, up, 0.02),
                                      contact_at(0, 0, 0.1, up, 0.01)};
  const int two[2] = {0, 1};
  check_kept("stacked, max 2", s, 3, 2, two, 2);
}

/* ---------------------------------------------------------- invariance ---- */

/* A random pair's contacts: n points of a tilted plane (random unit normal nrm), within
 * [-1,1]^2 of it, up to 0.02 off it, normals within about 6 degrees of nrm, random
 * depths. */
static void random_manifold(lsdem_impulse_contact *c, int n, double nrm[3])
{
  double t1[3], t2[3];
  do {
    for (int i = 0; i < 3; i++) nrm[i] = srand1();
  } while (lsdem_dot3(nrm, nrm) < 0.1);
  const double len = sqrt(lsdem_dot3(nrm, nrm));
  for (int i = 0; i < 3; i++) nrm[i] /= len;
  const double other[3] = {fabs(nrm[0]) < 0.6 ? 1.0 : 0.0, fabs(nrm[0]) < 0.6 ? 0.0 : 1.0,
                           0.0};
  lsdem_cross3(nrm, other, t1);
  const double l1 = sqrt(lsdem_dot3(t1, t1));
  for (int i = 0; i < 3; i++) t1[i] /= l1;
  lsdem_cross3(nrm, t1, t2);
  for (int k = 0; k < n; k++) {
    const double u = srand1(), v = srand1(), w = 0.02 * srand1();
    double cn[3];
    for (int i = 0; i < 3; i++)
      cn[i] = nrm[i] + 0.1 * (srand1() * t1[i] + srand1() * t2[i]);
    const double cl = sqrt(lsdem_dot3(cn, cn));
    for (int i = 0; i < 3; i++) cn[i] /= cl;
    double p[3];
    for (int i = 0; i < 3; i++) p[i] = u * t1[i] + v * t2[i] + w * nrm[i];
    c[k] = contact_at(p[0], p[1], p[2], cn, 0.01 * urand());
    c[k].a = k; /* tells the contacts apart */
  }
}

/* The index in orig of a contact equal to c byte for byte, or -1. */
static int original_index(const lsdem_impulse_contact *orig, int n,
                          const lsdem_impulse_contact *c)
{
  for (int k = 0; k < n; k++)
    if (memcmp(&orig[k], c, sizeof *c) == 0) return k;
  return -1;
}

/* Kept contacts are originals, unchanged, in increasing original order; the deepest is
 * kept and, for max >= 2, so is the contact farthest from it in the plane normal to its
 * normal. Reversed and shuffled inputs keep the same contacts. */
static void test_invariance(void)
{
  const int maxes[] = {1, 2, 3, 4, 5, 8};
  for (int trial = 0; trial < 40; trial++) {
    const int n = 10 + trial;
    lsdem_impulse_contact orig[MAXN], c[MAXN], rev[MAXN], shuf[MAXN];
    int32_t scratch[MAXN];
    double nrm[3];
    random_manifold(orig, n, nrm);
    int deepest = 0;
    for (int k = 1; k < n; k++)
      if (orig[k].depth > orig[deepest].depth) deepest = k;
    int farthest = -1;
    double far2 = -1.0;
    for (int k = 0; k < n; k++) {
      double d[3];
      lsdem_sub3(orig[k].point, orig[deepest].point, d);
      const double dn = lsdem_dot3(d, orig[deepest].normal);
      const double d2 = lsdem_dot3(d, d) - dn * dn;
      if (d2 > far2) {
        far2 = d2;
        farthest = k;
      }
    }
    for (size_t t = 0; t < sizeof maxes / sizeof maxes[0]; t++) {
      const int max = maxes[t];
      memcpy(c, orig, (size_t)n * sizeof *c);
      const int m = lsdem_impulse_cap_contacts(c, n, max, scratch);
      CHECK(m == max, "trial %d max %d: kept %d", trial, max, m);
      int prev = -1, has_deepest = 0, has_farthest = 0;
      for (int k = 0; k < m; k++) {
        const int o = original_index(orig, n, &c[k]);
        CHECK(o > prev, "trial %d max %d: kept %d is original %d after %d", trial, max, k,
              o, prev);
        prev = o;
        has_deepest |= o == deepest;
        has_farthest |= o == farthest;
      }
      CHECK(has_deepest, "trial %d max %d: deepest %d dropped", trial, max, deepest);
      CHECK(max < 2 || has_farthest, "trial %d max %d: farthest %d dropped", trial, max,
            farthest);

      for (int k = 0; k < n; k++) rev[k] = orig[n - 1 - k];
      memcpy(shuf, orig, (size_t)n * sizeof *c);
      for (int k = n - 1; k > 0; k--) {
        const int j = (int)(urand() * (k + 1)) % (k + 1);
        const lsdem_impulse_contact tmp = shuf[k];
        shuf[k] = shuf[j];
        shuf[j] = tmp;
      }
      const int mr = lsdem_impulse_cap_contacts(rev, n, max, scratch);
      const int ms = lsdem_impulse_cap_contacts(shuf, n, max, scratch);
      CHECK(mr == m && ms == m, "trial %d max %d: kept %d, reversed %d, shuffled %d", trial,
            max, m, mr, ms);
      for (int k = 0; k < m && k < mr && k < ms; k++) {
        CHECK(original_index(c, m, &rev[k]) >= 0,
              "trial %d max %d: reversed input keeps another contact", trial, max);
        CHECK(original_index(c, m, &shuf[k]) >= 0,
              "trial %d max %d: shuffled input keeps another contact", trial, max);
      }
      /* reversed, the kept contacts come in reversed order */
      for (int k = 0; k < m && mr == m; k++)
        CHECK(memcmp(&rev[k], &c[m - 1 - k], sizeof c[k]) == 0,
              "trial %d max %d: reversed order", trial, max);
    }
  }
}

/* ---------------------------------------------------------- max = 1 ---- */

/* max 1 keeps the deepest alone (ties: the first); max < 1 is taken as 1. */
static void test_max_one(void)
{
  lsdem_impulse_contact orig[12], c[12];
  int32_t scratch[12];
  random_contacts(orig, 12);
  orig[7].depth = 0.5;
  for (int max = 1; max >= -1; max--) {
    memcpy(c, orig, sizeof c);
    CHECK(lsdem_impulse_cap_contacts(c, 12, max, scratch) == 1, "max %d", max);
    CHECK(memcmp(&c[0], &orig[7], sizeof c[0]) == 0, "max %d: not the deepest", max);
  }
  orig[3].depth = 0.5; /* a tie: the lower index wins */
  const int three[1] = {3};
  check_kept("max 1, tie", orig, 12, 1, three, 1);
}

int main(void)
{
  test_face_four();
  test_face_other_caps();
  test_area_beats_distance();
  test_few_contacts_untouched();
  test_ties_grid();
  test_ties_centre_first();
  test_edge_keeps_both_ends();
  test_stacked_along_normal();
  test_invariance();
  test_max_one();
  return lsdem_test_summary();
}
