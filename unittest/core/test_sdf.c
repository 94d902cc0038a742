/* test_sdf.c -- analytic signed distances. Expectations: closed-form distances written
 * differently from the code (clamping to the solid, brute-force surface sampling for the
 * ellipsoid), finite differences for gradients, and agreement with sampled grids within
 * the trilinear interpolation error bound. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <stdint.h>
#include <stdlib.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static double len3(const double v[3]) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
static double clampd(double x, double lo, double hi) { return x < lo ? lo : x > hi ? hi : x; }

static lsdem_sdf make(lsdem_sdf_kind kind, double a0, double a1, double a2)
{
  lsdem_sdf s = {kind, 0, {a0, a1, a2}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL};
  return s;
}

/* |grad| = 1 and grad matches central differences where phi is smooth (|d| > 0 skips
 * points within 1e-3 of a kink, detected as a mismatch of one-sided differences). */
static void check_gradient(const lsdem_sdf *s, const double p[3], const char *what)
{
  double g[3], gp[3], gm[3];
  const double v = lsdem_sdf_eval(s, p, g);
  CHECK_NEAR(len3(g), 1.0, 1e-12);
  const double e = 1e-6;
  for (int a = 0; a < 3; a++) {
    double pp[3] = {p[0], p[1], p[2]}, pm[3] = {p[0], p[1], p[2]};
    pp[a] += e;
    pm[a] -= e;
    const double fp = (lsdem_sdf_eval(s, pp, gp) - v) / e;
    const double fm = (v - lsdem_sdf_eval(s, pm, gm)) / e;
    if (fabs(fp - fm) > 1e-4) return; /* on a kink of phi: no derivative to compare */
    CHECK(fabs(0.5 * (fp + fm) - g[a]) < 1e-5, "%s gradient[%d] %g vs fd %g", what, a, g[a],
          0.5 * (fp + fm));
  }
}

static void test_sphere_plane(void)
{
  lsdem_sdf s = make(LSDEM_SDF_SPHERE, 1.3, 0, 0);
  for (int t = 0; t < 500; t++) {
    const double p[3] = {3 * srand1(), 3 * srand1(), 3 * srand1()};
    double g[3];
    CHECK_NEAR(lsdem_sdf_eval(&s, p, g), len3(p) - 1.3, 1e-14);
    check_gradient(&s, p, "sphere");
  }
  lsdem_sdf pl = make(LSDEM_SDF_PLANE, 0, 0, 0);
  const double p[3] = {5, -7, -0.25};
  double g[3];
  CHECK_NEAR(lsdem_sdf_eval(&pl, p, g), -0.25, 0);
  CHECK(g[0] == 0 && g[1] == 0 && g[2] == 1, "plane normal +z");
  pl.inverted = 1;
  CHECK_NEAR(lsdem_sdf_eval(&pl, p, g), 0.25, 0);
  CHECK(g[2] == -1, "inverted plane normal -z");
  CHECK(lsdem_sdf_bound_radius(&pl) == HUGE_VAL, "plane is unbounded");
  CHECK_NEAR(lsdem_sdf_bound_radius(&s), 1.3, 0);
}

/* Box: outside distance = |p - clamp(p)|, inside = -(distance to the nearest face). */
static void test_box(void)
{
  const double a[3] = {0.5, 1.0, 1.5};
  lsdem_sdf s = make(LSDEM_SDF_BOX, a[0], a[1], a[2]);
  for (int t = 0; t < 2000; t++) {
    const double p[3] = {2 * srand1(), 2.5 * srand1(), 3 * srand1()};
    double c[3], d[3], g[3];
    for (int i = 0; i < 3; i++) {
      c[i] = clampd(p[i], -a[i], a[i]);
      d[i] = p[i] - c[i];
    }
    double expect = len3(d);
    if (expect == 0.0)
      expect = -fmin(fmin(a[0] - fabs(p[0]), a[1] - fabs(p[1])), a[2] - fabs(p[2]));
    CHECK_NEAR(lsdem_sdf_eval(&s, p, g), expect, 1e-14);
    check_gradient(&s, p, "box");
  }
  CHECK_NEAR(lsdem_sdf_bound_radius(&s), sqrt(0.25 + 1 + 2.25), 1e-15);
}

/* Cylinder: solid {rho <= r, |z| <= hl}; outside distance to the clamped point,
 * inside -(min of distances to side and caps). */
static void test_cylinder(void)
{
  const double r = 0.8, hl = 1.2;
  lsdem_sdf s = make(LSDEM_SDF_CYLINDER, r, hl, 0);
  lsdem_sdf inf = make(LSDEM_SDF_CYLINDER, r, 0.0, 0);
  for (int t = 0; t < 2000; t++) {
    const double p[3] = {2 * srand1(), 2 * srand1(), 2.5 * srand1()};
    const double rho = sqrt(p[0] * p[0] + p[1] * p[1]);
    const double rc = fmin(rho, r), zc = clampd(p[2], -hl, hl);
    const double out = sqrt((rho - rc) * (rho - rc) + (p[2] - zc) * (p[2] - zc));
    const double expect = out > 0 ? out : -fmin(r - rho, hl - fabs(p[2]));
    double g[3];
    CHECK_NEAR(lsdem_sdf_eval(&s, p, g), expect, 1e-14);
    check_gradient(&s, p, "cylinder");
    CHECK_NEAR(lsdem_sdf_eval(&inf, p, g), rho - r, 1e-14);
    if (rho > 1e-3) check_gradient(&inf, p, "infinite cylinder");
    /* a cylindrical container: inverted, phi < 0 outside the wall */
    lsdem_sdf wall = inf;
    wall.inverted = 1;
    CHECK_NEAR(lsdem_sdf_eval(&wall, p, g), r - rho, 1e-14);
  }
  CHECK_NEAR(lsdem_sdf_bound_radius(&s), sqrt(r * r + hl * hl), 1e-15);
  CHECK(lsdem_sdf_bound_radius(&inf) == HUGE_VAL, "infinite cylinder unbounded");
}

/* Brute-force distance from p to the ellipsoid surface: dense (theta, phi) sampling,
 * then a few rounds of local refinement around the best sample. */
/* The brute-force search's best surface point so far: keeps (th, ph) when the ellipsoid
 * point at those angles is nearer to p. */
typedef struct {
  double dist, th, ph;
} surface_best;

static void try_surface_point(const double a[3], const double p[3], double th, double ph,
                              surface_best *b)
{
  const double x[3] = {a[0] * sin(th) * cos(ph) - p[0], a[1] * sin(th) * sin(ph) - p[1],
                       a[2] * cos(th) - p[2]};
  const double d = len3(x);
  if (d < b->dist) *b = (surface_best){d, th, ph};
}

static double brute_ellipsoid_distance(const double a[3], const double p[3])
{
  surface_best best = {HUGE_VAL, 0.0, 0.0};
  const int nt = 200, np = 400;
  for (int i = 0; i <= nt; i++)
    for (int j = 0; j < np; j++) try_surface_point(a, p, M_PI * i / nt, 2 * M_PI * j / np, &best);
  double step_t = M_PI / nt, step_p = 2 * M_PI / np;
  for (int round = 0; round < 40; round++) {
    const double t0 = best.th, p0 = best.ph;
    for (int i = -10; i <= 10; i++)
      for (int j = -10; j <= 10; j++)
        try_surface_point(a, p, t0 + step_t * i / 5, p0 + step_p * j / 5, &best);
    step_t /= 2.5;
    step_p /= 2.5;
  }
  return best.dist;
}

static void test_ellipsoid(void)
{
  const double a[3] = {1.5, 1.0, 0.6};
  lsdem_sdf s = make(LSDEM_SDF_ELLIPSOID, a[0], a[1], a[2]);
  /* the closest point x = p - phi grad lies on the surface, with normal along grad */
  double worst_surf = 0, worst_par = 0;
  for (int t = 0; t < 5000; t++) {
    double p[3] = {2.5 * srand1(), 2 * srand1(), 1.5 * srand1()};
    if (t % 10 == 0) p[t / 10 % 3] = 0.0; /* points on the coordinate planes */
    if (t % 50 == 0) p[(t / 50 + 1) % 3] = 0.0; /* and on the axes */
    double g[3], x[3], n[3];
    const double v = lsdem_sdf_eval(&s, p, g);
    CHECK_NEAR(len3(g), 1.0, 1e-12);
    for (int i = 0; i < 3; i++) x[i] = p[i] - v * g[i];
    double e = -1;
    for (int i = 0; i < 3; i++) {
      e += (x[i] / a[i]) * (x[i] / a[i]);
      n[i] = x[i] / (a[i] * a[i]);
    }
    worst_surf = fmax(worst_surf, fabs(e));
    const double nn = len3(n);
    for (int i = 0; i < 3; i++) worst_par = fmax(worst_par, fabs(n[i] / nn - g[i]));
    /* sign: negative exactly inside */
    const double inside = (p[0] / a[0]) * (p[0] / a[0]) + (p[1] / a[1]) * (p[1] / a[1]) +
                          (p[2] / a[2]) * (p[2] / a[2]);
    CHECK((v < 0) == (inside < 1), "sign at (%g %g %g)", p[0], p[1], p[2]);
  }
  CHECK(worst_surf < 1e-12, "closest point on surface: %g", worst_surf);
  CHECK(worst_par < 1e-9, "gradient is the surface normal: %g", worst_par);
  /* global minimum: compare with brute force (inside points have several stationary
   * points; the medial region near the short axis is the hard case) */
  const double pts[][3] = {{2.0, 1.0, 0.5},  {0.1, 0.05, 0.02}, {0.3, 0.0, 0.0},
                           {0.0, 0.0, 0.0},  {1.2, 0.1, 0.05},  {0.0, 0.0, 2.0},
                           {0.0, 0.8, 0.0},  {-1.0, 0.5, -0.3}, {0.5, 0.2, 0.0},
                           {1.4, 0.0, 0.0},  {0.0, 0.3, 0.1},   {3.0, -2.0, 1.0}};
  for (size_t t = 0; t < sizeof pts / sizeof pts[0]; t++) {
    double g[3];
    const double v = lsdem_sdf_eval(&s, pts[t], g);
    const double b = brute_ellipsoid_distance(a, pts[t]);
    CHECK(fabs(fabs(v) - b) < 1e-9 * (1 + b), "ellipsoid |phi| %.15g vs brute force %.15g at %zu",
          fabs(v), b, t);
  }
  /* known values: on the axes the distance is the axis gap; the centre is -min axis */
  double g[3];
  const double px[3] = {2.0, 0, 0}, pc[3] = {0, 0, 0}, pz[3] = {0, 0, 0.1};
  CHECK_NEAR(lsdem_sdf_eval(&s, px, g), 0.5, 1e-15);
  CHECK_NEAR(lsdem_sdf_eval(&s, pc, g), -0.6, 1e-15);
  CHECK_NEAR(lsdem_sdf_eval(&s, pz, g), -0.5, 1e-15);
  CHECK_NEAR(lsdem_sdf_bound_radius(&s), 1.5, 0);
  /* a = b = c reproduces the sphere, also for permuted / spheroid cases */
  lsdem_sdf e1 = make(LSDEM_SDF_ELLIPSOID, 0.9, 0.9, 0.9), sp = make(LSDEM_SDF_SPHERE, 0.9, 0, 0);
  double worst = 0;
  for (int t = 0; t < 2000; t++) {
    const double p[3] = {2 * srand1(), 2 * srand1(), 2 * srand1()};
    double g1[3], g2[3];
    worst = fmax(worst, fabs(lsdem_sdf_eval(&e1, p, g1) - lsdem_sdf_eval(&sp, p, g2)));
    for (int i = 0; i < 3; i++) worst = fmax(worst, fabs(g1[i] - g2[i]));
  }
  CHECK(worst < 1e-12, "ellipsoid a=b=c vs sphere: %g", worst);
  /* spheroids: distance in the meridian plane from the 2D ellipse, any azimuth */
  lsdem_sdf ob = make(LSDEM_SDF_ELLIPSOID, 1.0, 0.4, 1.0), ob2 = make(LSDEM_SDF_ELLIPSOID, 1.0, 1.0, 0.4);
  for (int t = 0; t < 500; t++) {
    const double p[3] = {2 * srand1(), 1.5 * srand1(), 2 * srand1()};
    const double q[3] = {p[0], p[2], p[1]}; /* swap y and z */
    double g1[3], g2[3];
    CHECK_NEAR(lsdem_sdf_eval(&ob, p, g1), lsdem_sdf_eval(&ob2, q, g2), 1e-12);
    CHECK_NEAR(g1[1], g2[2], 1e-9);
  }
  /* a point just off the surface: phi is the offset along the normal */
  for (int t = 0; t < 200; t++) {
    const double th = M_PI * urand(), ph = 2 * M_PI * urand();
    double x[3] = {a[0] * sin(th) * cos(ph), a[1] * sin(th) * sin(ph), a[2] * cos(th)}, n[3], p[3];
    for (int i = 0; i < 3; i++) n[i] = x[i] / (a[i] * a[i]);
    const double nn = len3(n), off = 0.01 * srand1(); /* inside the smallest curvature radius */
    for (int i = 0; i < 3; i++) p[i] = x[i] + off * n[i] / nn;
    CHECK_NEAR(lsdem_sdf_eval(&s, p, g), off, 1e-12);
  }
}

/* Sampled grids of analytic SDFs agree with them within the trilinear interpolation
 * error: |f - I f| <= (h^2 / 8) sum_i max |d2f/dx_i^2| <= (3 h^2 / 8) k, where k bounds
 * the Hessian of phi in the cell. For a sphere of radius R, k = 1/rho <= 1/(R - 2h)
 * within 2h of the surface; for the ellipsoid k <= kmax / (1 - kmax 2h) with kmax the
 * largest surface curvature a_max / a_min^2. Plus float rounding of the samples. */
static void check_grid_against(const lsdem_sdf *s, double h, double bound, double band,
                               double max_angle, const char *what)
{
  const double R = lsdem_sdf_bound_radius(s);
  const double lo[3] = {-R, -R, -R}, hi[3] = {R, R, R};
  lsdem_grid g;
  lsdem_error err;
  CHECK(lsdem_grid_sample(s, lo, hi, h, 2, &g, &err) == LSDEM_OK, "%s", err.msg);
  lsdem_sdf gs = make(LSDEM_SDF_GRID, 0, 0, 0);
  gs.grid = g;
  double worst = 0, worst_angle = 0;
  int n = 0;
  for (int t = 0; t < 20000 && n < 3000; t++) {
    const double p[3] = {R * srand1(), R * srand1(), R * srand1()};
    double ga[3], gg[3];
    const double va = lsdem_sdf_eval(s, p, ga);
    if (fabs(va) > band) continue;
    n++;
    const double vg = lsdem_sdf_eval(&gs, p, gg);
    worst = fmax(worst, fabs(va - vg));
    worst_angle = fmax(worst_angle, acos(fmin(1.0, ga[0] * gg[0] + ga[1] * gg[1] + ga[2] * gg[2])));
  }
  bound += 1e-6 * R; /* float samples */
  CHECK(worst <= bound, "%s grid vs analytic: %g > bound %g", what, worst, bound);
  printf("%s h=%g: max |phi_grid - phi| = %.3g (%.3f h, bound %.3f h), max normal angle %.3g rad\n",
         what, h, worst, worst / h, bound / h, worst_angle);
  CHECK(worst_angle < max_angle, "%s normal angle %g", what, worst_angle);
  lsdem_grid_free(&g);
}

static double trilinear_bound(double h, double k) { return 3.0 * h * h / 8.0 * k; }

static void test_grids(void)
{
  const double R = 1.0, h = R / 10;
  lsdem_sdf sp = make(LSDEM_SDF_SPHERE, R, 0, 0);
  check_grid_against(&sp, h, trilinear_bound(h, 1.0 / (R - 2 * h)), 2 * h, 0.1, "sphere");
  const double a[3] = {1.5, 1.0, 0.6};
  lsdem_sdf el = make(LSDEM_SDF_ELLIPSOID, a[0], a[1], a[2]);
  const double he = 0.06, kmax = a[0] / (a[2] * a[2]);
  check_grid_against(&el, he, trilinear_bound(he, kmax / (1 - kmax * 2 * he)), 2 * he, 0.2,
                     "ellipsoid");
  /* the box SDF is piecewise linear with kinks (inside: min of face distances). The
   * trilinear interpolant of min(x, y, z) over a cell errs by at most 3h/8 (at the cell
   * centre when only the far corner differs), a documented fraction of h. */
  lsdem_sdf bx = make(LSDEM_SDF_BOX, 0.5, 0.7, 0.9);
  check_grid_against(&bx, 0.1, 0.375 * 0.1, 0.2, M_PI, "box"); /* normals jump at kinks */
}

int main(void)
{
  test_sphere_plane();
  test_box();
  test_cylinder();
  test_ellipsoid();
  test_grids();
  return lsdem_test_summary();
}
