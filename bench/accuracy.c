/* accuracy.c -- error of the node-to-surface contact force against its cost.
 *
 * Two level-set spheres of radius R = 1 (grids of spacing h sampled from the exact
 * distance, N surface nodes seeded on the grid's zero set, as lsdem-shape makes every
 * grid shape) overlap by delta along the line of centres, in random orientations. The
 * contact force of A's nodes in B's level set under the traction law (report eq 2.2 with
 * each node's area, kn = 1) is compared with its continuum limit for exact spheres:
 *
 *   F = kn * integral over A's surface inside B of depth_B(x) (n_B(x) . e) dA,
 *
 * e the unit vector from B's centre to A's, depth_B = R - |x - xB|, n_B = (x - xB)/|x - xB|
 * (B's outward normal). With x at polar angle t on A measured from -e (towards B),
 * |x - xB|^2 = R^2 + D^2 - 2 R D cos t and (x - xB).e = D - R cos t, D = 2R - delta; A's
 * surface is inside B for cos t > D / (2R). The integral over u = cos t is done by
 * Gauss-Legendre quadrature (exact to round-off here). The per-node law (kn d per node,
 * the report's default) is the same sum with every area replaced by 1, so its error
 * against the same limit scaled by N / (4 pi R^2) is this one when the node areas are
 * equal.
 *
 * Printed per (h, N, delta): the exact force, the mean offset of the grid's surface from
 * the exact sphere (surface_offset), the mean and largest relative error of the force
 * along e and the largest sideways force (|F - (F.e) e| / |F|, 0 for spheres) over the
 * orientations, and the time of one contact test without node lists (every node
 * screened: the cost of a test that builds its list; a test that uses one looks up only
 * the listed nodes). One CSV row each on standard output. */
#include "lsdem.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { ORIENTATIONS = 32 };

static double now_seconds(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* 20-point Gauss-Legendre nodes and weights on [-1, 1], tabulated (by
 * symmetry: the positive half). */
static const double GL_X[10] = {0.0765265211334973, 0.2277858511416451, 0.3737060887154195,
                                0.5108670019508271, 0.6360536807265150, 0.7463319064601508,
                                0.8391169718222188, 0.9122344282513259, 0.9639719272779138,
                                0.9931285991850949};
static const double GL_W[10] = {0.1527533871307258, 0.1491729864726037, 0.1420961093183820,
                                0.1316886384491766, 0.1181945319615184, 0.1019301198172404,
                                0.0832767415767048, 0.0626720483341091, 0.0406014298003869,
                                0.0176140071391521};

/* The continuum traction force along e for two exact spheres of radius r at centre
 * distance d (kn = 1), integrated over u = cos t in [d / 2r, 1] in 64 panels. */
static double exact_force(double r, double d)
{
  const double u0 = d / (2.0 * r), panels = 64;
  double sum = 0.0;
  for (int p = 0; p < panels; p++) {
    const double a = u0 + (1.0 - u0) * p / panels, b = u0 + (1.0 - u0) * (p + 1) / panels;
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    for (int g = 0; g < 20; g++) {
      const double u = mid + (g < 10 ? -1.0 : 1.0) * half * GL_X[g % 10];
      const double rb = sqrt(r * r + d * d - 2.0 * r * d * u);
      /* dA = 2 pi r^2 sin t dt = 2 pi r^2 du */
      sum += GL_W[g % 10] * half * (r - rb) * (d - r * u) / rb * 2.0 * M_PI * r * r;
    }
  }
  return sum;
}

/* A uniformly random rotation, as a matrix. */
static void random_rotation(uint64_t *rng, double R[9])
{
  double q[4];
  lsdem_random_quat(rng, q);
  lsdem_quat_to_matrix(q, R);
}

typedef struct {
  double exact, surface, err_mean, err_max, side_max, ns_per_test;
  int nodes;
} result;

/* Mean distance of the nodes from the centre, minus R = 1: where the grid's zero level set
 * (trilinear, the nodes lie on it) sits against the exact sphere. Both grains of a pair
 * have it, so it changes the overlap a contact sees by about twice this. */
static double surface_offset(const lsdem_shape *s)
{
  double sum = 0.0;
  for (int k = 0; k < s->nnodes; k++) {
    const double *x = s->nodes + 3 * k;
    sum += sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  }
  return sum / s->nnodes - 1.0;
}

/* The errors over the orientations and the time per test for shape s at overlap delta. */
static result measure(const lsdem_shape *s, double delta, uint64_t seed)
{
  lsdem_contact_params prm;
  memset(&prm, 0, sizeof prm);
  prm.law.kn = 1.0;
  prm.law.normal = LSDEM_NORMAL_TRACTION;
  prm.detect.node_stride = 1;
  prm.dt = 1.0;
  lsdem_contact_point *points = malloc((size_t)lsdem_manifold_capacity(s) * sizeof *points);
  lsdem_manifold m = lsdem_manifold_over(points, lsdem_manifold_capacity(s));
  const double d = 2.0 - delta, exact = exact_force(1.0, d);
  result out = {exact, surface_offset(s), 0.0, 0.0, 0.0, 0.0, s->nnodes};
  lsdem_pose pa, pb;
  memset(&pa, 0, sizeof pa);
  memset(&pb, 0, sizeof pb);
  lsdem_contact_result res;
  for (int o = 0; o < ORIENTATIONS; o++) {
    /* the line of centres along a random direction (the first column of a rotation) */
    double Re[9];
    random_rotation(&seed, Re);
    const double e[3] = {Re[0], Re[3], Re[6]};
    random_rotation(&seed, pa.R);
    random_rotation(&seed, pb.R);
    for (int i = 0; i < 3; i++) pa.x[i] = d * e[i];
    lsdem_contact_penalty(s, &pa, s, &pb, &prm, 1, NULL, NULL, &m, &res);
    const double fe = res.force[0] * e[0] + res.force[1] * e[1] + res.force[2] * e[2];
    double side2 = 0.0, f2 = 0.0;
    for (int i = 0; i < 3; i++) {
      const double t = res.force[i] - fe * e[i];
      side2 += t * t;
      f2 += res.force[i] * res.force[i];
    }
    const double err = fabs(fe / exact - 1.0);
    out.err_mean += err / ORIENTATIONS;
    out.err_max = fmax(out.err_max, err);
    out.side_max = fmax(out.side_max, f2 > 0.0 ? sqrt(side2 / f2) : 1.0);
  }
  /* time: the last orientation, repeated for 20 ms, the fastest of three such runs (the
   * others lost time to the machine's other work) */
  out.ns_per_test = HUGE_VAL;
  for (int run = 0; run < 3; run++) {
    long calls = 0;
    const double t0 = now_seconds();
    double t1;
    do {
      for (int k = 0; k < 64; k++)
        lsdem_contact_penalty(s, &pa, s, &pb, &prm, 1, NULL, NULL, &m, &res);
      calls += 64;
    } while ((t1 = now_seconds()) - t0 < 0.02);
    out.ns_per_test = fmin(out.ns_per_test, 1e9 * (t1 - t0) / (double)calls);
  }
  free(points);
  return out;
}

/* A level-set sphere of radius 1 on a grid of spacing h, with about n nodes. */
static int sphere_shape(double h, int n, lsdem_built_shape *b)
{
  lsdem_sdf exact;
  memset(&exact, 0, sizeof exact);
  exact.kind = LSDEM_SDF_SPHERE;
  exact.a[0] = 1.0;
  const double lo[3] = {-1.0, -1.0, -1.0}, hi[3] = {1.0, 1.0, 1.0};
  lsdem_sdf grid;
  memset(&grid, 0, sizeof grid);
  grid.kind = LSDEM_SDF_GRID;
  lsdem_error err;
  if (lsdem_grid_sample(&exact, lo, hi, h, 3, &grid.grid, &err) != LSDEM_OK ||
      lsdem_shape_build(&grid, n, 0.0, 7, b, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-bench-accuracy: %s\n", err.msg);
    return 0;
  }
  return 1;
}

/* A comma-separated list of at most max numbers in (lo, hi] into out; its count, or 0 when
 * an entry is not such a number. */
static int parse_list(const char *arg, double lo, double hi, double *out, int max)
{
  int n = 0;
  const char *p = arg;
  while (n < max) {
    char *end;
    const double v = strtod(p, &end);
    if (end == p || !(v > lo && v <= hi) || (*end != ',' && *end != '\0')) return 0;
    out[n++] = v;
    if (*end == '\0') return n;
    p = end + 1;
  }
  return 0; /* more than max entries */
}

int main(int argc, char **argv)
{
  double inv_h[16] = {4, 6, 8, 12, 16, 24, 32}, nodes[16] = {64, 250, 1000, 4000};
  double overlaps[16] = {0.01, 0.03, 0.1};
  int nh = 7, nn = 4, nd = 3;
  for (int a = 1; a < argc; a += 2) {
    const char *val = a + 1 < argc ? argv[a + 1] : "";
    int ok = 0;
    if (!strcmp(argv[a], "--grids")) ok = (nh = parse_list(val, 1.0, 1e3, inv_h, 16)) > 0;
    if (!strcmp(argv[a], "--nodes"))
      ok = (nn = parse_list(val, 0.0, LSDEM_LIBRARY_MAX_NODES, nodes, 16)) > 0;
    if (!strcmp(argv[a], "--overlaps")) ok = (nd = parse_list(val, 0.0, 1.0, overlaps, 16)) > 0;
    if (!ok) {
      fprintf(stderr, "lsdem-bench-accuracy: bad option '%s %s'\n"
                      "usage: lsdem-bench-accuracy [--grids R/h,...] [--nodes N,...] "
                      "[--overlaps delta/R,...]\n  (at most 16 values each; R/h in (1, 1000], "
                      "N in (0, %d], delta/R in (0, 1])\n",
              argv[a], val, LSDEM_LIBRARY_MAX_NODES);
      return 2;
    }
  }
  printf("R_over_h,nodes,overlap_over_R,force_exact,surface_offset_over_R,err_mean,err_max,"
         "sideways_max,ns_per_test\n");
  for (int i = 0; i < nh; i++)
    for (int j = 0; j < nn; j++) {
      lsdem_built_shape b;
      if (!sphere_shape(1.0 / inv_h[i], (int)nodes[j], &b)) return 1;
      for (int k = 0; k < nd; k++) {
        const uint64_t seed = (uint64_t)(1000 + 100 * i + 10 * j + k);
        const result r = measure(&b.shape, overlaps[k], seed);
        printf("%g,%d,%g,%.10g,%.3g,%.6g,%.6g,%.6g,%.1f\n", inv_h[i], r.nodes, overlaps[k],
               r.exact, r.surface, r.err_mean, r.err_max, r.side_max, r.ns_per_test);
        fflush(stdout);
      }
      lsdem_built_shape_free(&b);
    }
  return 0;
}
