/* test_sphere_grain.c -- an analytic sphere against a level-set grain whose grid it
 * overlaps from outside (radius larger than the grid's margin, so its centre lies outside
 * the grid box):
 *   - the depth is the least of |c - q| + phi(q) over the grid's box, as a brute-force
 *     search over the box's faces finds it (the descent converges);
 *   - depth and normal equal the exact sphere-box and sphere-sphere overlaps at every angle
 *     and several radii, to the grid's own interpolation error (below a tenth of its
 *     spacing in depth, a few degrees in normal at its rounded edges), where the one lookup of the centre (the grid's outside rule, an upper bound
 *     of the distance) misses the contact or tilts it. */
#include "contact_fixtures.h"
#include "lsdem_test.h"

#include <math.h>
#include <string.h>

static const double HALF[3] = {1.0, 0.6, 0.8}; /* the box */

/* exact distance from c to the box and the unit direction from its closest point to c */
static double box_distance(const double c[3], double n[3])
{
  double d[3], len2 = 0.0;
  for (int a = 0; a < 3; a++) {
    const double cl = fmin(fmax(c[a], -HALF[a]), HALF[a]);
    d[a] = c[a] - cl;
    len2 += d[a] * d[a];
  }
  const double len = sqrt(len2);
  for (int a = 0; a < 3; a++) n[a] = d[a] / len;
  return len;
}

/* the centre along dir (unit) whose box distance is `want` (bisection) */
static void centre_at(const double dir[3], double want, double c[3])
{
  double lo = 0.0, hi = 10.0, n[3];
  for (int it = 0; it < 200; it++) {
    const double t = 0.5 * (lo + hi);
    for (int a = 0; a < 3; a++) c[a] = t * dir[a];
    if (box_distance(c, n) < want) lo = t; else hi = t;
  }
  for (int a = 0; a < 3; a++) c[a] = hi * dir[a];
}

/* one sphere of radius r at centre c against B: depth and world normal of the contact */
static int sphere_contact(const lsdem_shape *B, double r, const double c[3], double *depth,
                          double n[3])
{
  lsdem_shape A = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, r, 0, 0), 0, NULL, r);
  lsdem_pose pa = fix_pose(c[0], c[1], c[2]), pb = fix_pose(0, 0, 0);
  const lsdem_detect_params every = {1, 0.0};
  lsdem_manifold *m = fix_manifold();
  if (lsdem_detect(&A, &pa, B, &pb, &every, 1, NULL, NULL, m) != 1) return 0;
  *depth = m->point[0].depth;
  memcpy(n, m->point[0].normal, 3 * sizeof(double));
  return 1;
}

static double angle_deg(const double a[3], const double b[3])
{
  const double c = lsdem_dot3(a, b) / (fix_norm(a) * fix_norm(b));
  return acos(fmax(-1.0, fmin(1.0, c))) * 180.0 / FIX_PI;
}

/* brute force: min over a fine lattice on the grid box's faces of |c - q| + phi(q) */
static double brute_distance(const lsdem_sdf *sdf, const double c[3])
{
  const lsdem_grid *g = &sdf->grid;
  double lo[3], hi[3], best = HUGE_VAL;
  for (int a = 0; a < 3; a++) {
    lo[a] = g->origin[a];
    hi[a] = lo[a] + g->h * (g->n[a] - 1);
  }
  enum { M = 240 };
  for (int axis = 0; axis < 3; axis++)
    for (int side = 0; side < 2; side++)
      for (int i = 0; i <= M; i++)
        for (int j = 0; j <= M; j++) {
          const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
          double q[3], gr[3], d[3];
          q[axis] = side ? hi[axis] : lo[axis];
          q[a1] = lo[a1] + (hi[a1] - lo[a1]) * i / M;
          q[a2] = lo[a2] + (hi[a2] - lo[a2]) * j / M;
          for (int a = 0; a < 3; a++) d[a] = c[a] - q[a];
          best = fmin(best, fix_norm(d) + lsdem_sdf_eval(sdf, q, gr));
        }
  return best;
}

int main(void)
{
  lsdem_error err;
  const double h = 0.05;
  const lsdem_sdf box = fix_sdf(LSDEM_SDF_BOX, HALF[0], HALF[1], HALF[2]);
  lsdem_sdf grid = fix_sdf(LSDEM_SDF_GRID, 0, 0, 0);
  const double lo[3] = {-HALF[0], -HALF[1], -HALF[2]};
  CHECK(lsdem_grid_sample(&box, lo, HALF, h, 3, &grid.grid, &err) == LSDEM_OK, "%s", err.msg);
  const lsdem_shape B = fix_shape(grid, 0, NULL, lsdem_sdf_bound_radius(&grid));

  /* centre lines from the top face over the edge to the side face, and oblique ones
   * towards corners; radii 2 to 10 times the grid's margin (0.15); overlaps 0.3 h to h
   * (2 % to 7 % of a radius) */
  int cases = 0, missed_by_lookup = 0, ok_depth = 1, ok_normal = 1, ok_min = 1;
  double worst_depth = 0.0, worst_angle = 0.0, worst_min = 0.0;
  const double radii[] = {0.3, 0.75, 1.5};
  const double overlap[] = {0.3 * h, 0.6 * h, h};
  for (int ri = 0; ri < 3; ri++)
    for (int oi = 0; oi < 3; oi++)
      for (int ai = 0; ai <= 18; ai++)
        for (int bi = 0; bi < 3; bi++) {
          const double r = radii[ri], delta = overlap[oi];
          const double th = FIX_PI / 2 * ai / 18.0, ph = 0.35 * bi; /* from +z towards +x */
          const double dir[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
          double c[3], nx[3];
          centre_at(dir, r - delta, c);
          box_distance(c, nx);
          double depth = 0.0, n[3];
          const int hit = sphere_contact(&B, r, c, &depth, n);
          cases++;
          /* the descent's minimum against the brute-force one (every 12th case: slow) */
          if (cases % 12 == 0) {
            const double e = fabs((hit ? r - depth : HUGE_VAL) - brute_distance(&B.sdf, c));
            worst_min = fmax(worst_min, e);
            ok_min &= e < 0.02 * h;
          }
          const double derr = hit ? fabs(depth - delta) : delta;
          worst_depth = fmax(worst_depth, derr / h);
          ok_depth &= hit && derr <= 0.08 * h;
          if (hit) {
            worst_angle = fmax(worst_angle, angle_deg(n, nx));
            ok_normal &= angle_deg(n, nx) < 6.0; /* the grid rounds the box edges over ~h */
          }
          /* what the one lookup of the centre would say */
          double g[3];
          const double d_lookup = r - lsdem_sdf_eval(&B.sdf, c, g);
          missed_by_lookup += fabs(d_lookup - delta) > 0.1 * h || angle_deg(g, nx) > 5.0;
        }
  CHECK(ok_min, "the descent's distance is off the brute-force minimum by %.3g", worst_min);
  CHECK(ok_depth, "depth off the exact overlap by up to %.3g h over %d cases", worst_depth,
        cases);
  CHECK(ok_normal, "normal off the exact one by up to %.3g degrees", worst_angle);
  CHECK(missed_by_lookup > cases / 4,
        "the one lookup of the centre errs in only %d of %d cases: the test shows nothing",
        missed_by_lookup, cases);
  printf("sphere-box: %d cases, depth error <= %.3g h, normal <= %.3g deg, minimum within "
         "%.2g of brute force (the centre lookup errs in %d)\n", cases, worst_depth,
         worst_angle, worst_min, missed_by_lookup);

  /* a level-set sphere: the exact overlap ra + rb - |c| in random directions */
  const lsdem_sdf ball = fix_sdf(LSDEM_SDF_SPHERE, 1.0, 0, 0);
  lsdem_sdf bgrid = fix_sdf(LSDEM_SDF_GRID, 0, 0, 0);
  const double blo[3] = {-1, -1, -1}, bhi[3] = {1, 1, 1};
  CHECK(lsdem_grid_sample(&ball, blo, bhi, h, 3, &bgrid.grid, &err) == LSDEM_OK, "%s", err.msg);
  const lsdem_shape S = fix_shape(bgrid, 0, NULL, lsdem_sdf_bound_radius(&bgrid));
  int ok_ball = 1;
  double worst_ball = 0.0;
  for (int t = 0; t < 200; t++) {
    double dir[3] = {srand1(), srand1(), srand1()};
    const double len = fix_norm(dir);
    const double r = 0.4 + 0.8 * urand(), delta = 0.5 * h;
    double c[3], depth = 0.0, n[3];
    for (int a = 0; a < 3; a++) c[a] = (1.0 + r - delta) * dir[a] / len;
    const int hit = sphere_contact(&S, r, c, &depth, n);
    const double e = hit ? fabs(depth - delta) : delta;
    worst_ball = fmax(worst_ball, e);
    ok_ball &= hit && e < 0.06 * h && angle_deg(n, c) < 2.0;
  }
  CHECK(ok_ball, "sphere-sphere: depth off the exact overlap by up to %.3g", worst_ball);
  lsdem_grid_free(&grid.grid);
  lsdem_grid_free(&bgrid.grid);
  return lsdem_test_summary();
}
