/* contact_fixtures.h -- small shape builders shared by the contact and collision tests:
 * hand-placed surface nodes, node clusters, rotation matrices and shapes around an
 * SDF. Header-only (static functions), no allocation. */
#ifndef CONTACT_FIXTURES_H
#define CONTACT_FIXTURES_H
#include "lsdem.h"

#include <math.h>
#include <string.h>

#define FIX_PI 3.14159265358979323846

/* Nodes on a sphere of radius r in rings about the x axis: node 0 = (r,0,0), node 1 =
 * (-r,0,0), then nrings rings at polar angles pi*i/(nrings+1), nper nodes each at
 * azimuths 2*pi*j/nper. With nper even the set is symmetric under inversion and under
 * reflections through planes containing the x axis. Returns 2 + nrings*nper. */
static inline int fix_ring_nodes(double r, int nrings, int nper, double *nodes)
{
  int m = 0;
  const double poles[2][3] = {{r, 0, 0}, {-r, 0, 0}};
  for (int p = 0; p < 2; p++, m++)
    for (int i = 0; i < 3; i++) nodes[3 * m + i] = poles[p][i];
  for (int i = 1; i <= nrings; i++) {
    const double th = FIX_PI * i / (nrings + 1);
    for (int j = 0; j < nper; j++, m++) {
      const double ph = 2.0 * FIX_PI * j / nper;
      nodes[3 * m] = r * cos(th);
      nodes[3 * m + 1] = r * sin(th) * cos(ph);
      nodes[3 * m + 2] = r * sin(th) * sin(ph);
    }
  }
  return m;
}

/* n Fibonacci-sphere directions scaled by semi-axes a (points on the ellipsoid
 * x^2/a0^2 + y^2/a1^2 + z^2/a2^2 = 1). */
static inline void fix_fibonacci_ellipsoid(int n, const double a[3], double *nodes)
{
  const double golden = FIX_PI * (3.0 - sqrt(5.0));
  for (int k = 0; k < n; k++) {
    const double y = 1.0 - 2.0 * (k + 0.5) / n, rad = sqrt(1.0 - y * y);
    const double ph = golden * k;
    nodes[3 * k] = a[0] * rad * cos(ph);
    nodes[3 * k + 1] = a[1] * y;
    nodes[3 * k + 2] = a[2] * rad * sin(ph);
  }
}

/* Reorder nodes into the 8 octants (sign of x, y, z) and write one cluster per
 * non-empty octant: start indices and bounding spheres (mean centre, max distance).
 * scratch holds 3*n doubles. Returns the cluster count. */
static inline int fix_octant_clusters(int n, double *nodes, double *scratch, int *start,
                               double *sphere)
{
  int m = 0, nc = 0;
  for (int oct = 0; oct < 8; oct++) {
    const int first = m;
    for (int k = 0; k < n; k++) {
      const double *p = &nodes[3 * k];
      const int o = (p[0] < 0) | ((p[1] < 0) << 1) | ((p[2] < 0) << 2);
      if (o != oct) continue;
      memcpy(&scratch[3 * m], p, 3 * sizeof(double));
      m++;
    }
    if (m == first) continue;
    double c[3] = {0, 0, 0}, r2 = 0;
    for (int k = first; k < m; k++)
      for (int i = 0; i < 3; i++) c[i] += scratch[3 * k + i] / (m - first);
    for (int k = first; k < m; k++) {
      double d2 = 0;
      for (int i = 0; i < 3; i++) d2 += pow(scratch[3 * k + i] - c[i], 2);
      if (d2 > r2) r2 = d2;
    }
    start[nc] = first;
    for (int i = 0; i < 3; i++) sphere[4 * nc + i] = c[i];
    sphere[4 * nc + 3] = sqrt(r2);
    nc++;
  }
  start[nc] = m;
  memcpy(nodes, scratch, 3 * (size_t)n * sizeof(double));
  return nc;
}

/* Rotation matrix (row-major, body -> world) of angle th about the unit axis k,
 * written out independently of the core's quaternion code. */
static inline void fix_axis_angle(const double k[3], double th, double R[9])
{
  const double c = cos(th), s = sin(th), t = 1.0 - c;
  R[0] = t * k[0] * k[0] + c;
  R[1] = t * k[0] * k[1] - s * k[2];
  R[2] = t * k[0] * k[2] + s * k[1];
  R[3] = t * k[0] * k[1] + s * k[2];
  R[4] = t * k[1] * k[1] + c;
  R[5] = t * k[1] * k[2] - s * k[0];
  R[6] = t * k[0] * k[2] - s * k[1];
  R[7] = t * k[1] * k[2] + s * k[0];
  R[8] = t * k[2] * k[2] + c;
}

/* Rotation by th about the axis (k0, k1, k2), normalised here. */
static inline void fix_rotation_about(double k0, double k1, double k2, double th, double R[9])
{
  const double n = sqrt(k0 * k0 + k1 * k1 + k2 * k2), k[3] = {k0 / n, k1 / n, k2 / n};
  fix_axis_angle(k, th, R);
}

static inline void fix_identity(double R[9])
{
  static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  memcpy(R, I, sizeof I);
}

/* A shape around an SDF with the given nodes (no clusters, no areas). */
static inline lsdem_shape fix_shape(lsdem_sdf sdf, int nnodes, const double *nodes,
                                    double radius)
{
  lsdem_shape s;
  memset(&s, 0, sizeof s);
  s.sdf = sdf;
  s.nnodes = nnodes;
  s.nodes = nodes;
  s.radius = radius;
  return s;
}

/* Contact parameters: kn, ks, mu, dt; no damping, every node, per-node normal law. */
static inline lsdem_contact_params fix_params(double kn, double ks, double mu, double dt)
{
  lsdem_contact_params p;
  memset(&p, 0, sizeof p);
  p.law.kn = kn;
  p.law.ks = ks;
  p.law.mu = mu;
  p.law.normal = LSDEM_NORMAL_PER_NODE;
  p.detect.node_stride = 1;
  p.dt = dt;
  return p;
}

/* Manifold storage for the tests' shapes (at most FIX_MAX_POINTS nodes), reused. */
enum { FIX_MAX_POINTS = 4096 };
static inline lsdem_manifold *fix_manifold(void)
{
  static lsdem_contact_point points[FIX_MAX_POINTS];
  static lsdem_manifold m;
  m = lsdem_manifold_over(points, FIX_MAX_POINTS);
  return &m;
}

/* Node detection (A's nodes, whatever A's kind) and the penalty law with shear history
 * only: hist_in (n_in entries) the last step's, hist_out (NULL: not kept) this step's,
 * count in *n_out. */
static inline int fix_contact(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                              const lsdem_pose *pb, const lsdem_contact_params *prm,
                              int64_t step, const lsdem_shear_hist *hist_in, int n_in,
                              lsdem_shear_hist *hist_out, int *n_out, lsdem_contact_result *res)
{
  lsdem_manifold *m = fix_manifold();
  lsdem_detect_nodes(A, pa, B, pb, &prm->detect, step, NULL, NULL, m);
  int n = 0;
  lsdem_penalty_apply(m, &prm->law, prm->dt, step, hist_in, n_in, hist_out, &n, res);
  if (n_out) *n_out = n;
  return res->npen;
}

/* The same through the kernel's dispatch (lsdem_contact_penalty: a sphere A takes the
 * sphere paths). */
static inline int fix_contact_grain(const lsdem_shape *A, const lsdem_pose *pa,
                                    const lsdem_shape *B, const lsdem_pose *pb,
                                    const lsdem_contact_params *prm, int64_t step,
                                    lsdem_shear_hist *hist_out, int *n_out,
                                    lsdem_contact_result *res)
{
  lsdem_pair_state out;
  memset(&out, 0, sizeof out);
  out.shear = hist_out;
  lsdem_contact_penalty(A, pa, B, pb, prm, step, NULL, &out, fix_manifold(), res);
  if (n_out) *n_out = out.nshear;
  return res->npen;
}

static inline lsdem_sdf fix_sdf(lsdem_sdf_kind kind, double a0, double a1, double a2)
{
  lsdem_sdf s;
  memset(&s, 0, sizeof s);
  s.kind = kind;
  s.a[0] = a0;
  s.a[1] = a1;
  s.a[2] = a2;
  return s;
}

static inline lsdem_pose fix_pose(double x, double y, double z)
{
  lsdem_pose p;
  memset(&p, 0, sizeof p);
  p.x[0] = x;
  p.x[1] = y;
  p.x[2] = z;
  fix_identity(p.R);
  return p;
}

static inline void fix_cross(const double a[3], const double b[3], double out[3])
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

static inline double fix_norm(const double a[3])
{
  return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

/* The ellipsoid of semi-axes a sampled as a grid of spacing 1 with a 3-sample margin. */
static inline lsdem_status fix_ellipsoid_grid(const double a[3], lsdem_sdf *grid,
                                              lsdem_error *err)
{
  const lsdem_sdf ell = fix_sdf(LSDEM_SDF_ELLIPSOID, a[0], a[1], a[2]);
  const double lo[3] = {-a[0], -a[1], -a[2]};
  *grid = fix_sdf(LSDEM_SDF_GRID, 0, 0, 0);
  return lsdem_grid_sample(&ell, lo, a, 1.0, 3, &grid->grid, err);
}

/* An ellipsoid grain (semi-axes a) with FIX_GRAIN_NODES Fibonacci nodes clustered by the
 * core, around the level set sdf: `clustered` and `plain` (no clusters) share the nodes. */
enum { FIX_GRAIN_NODES = 400 };
typedef struct {
  double nodes[3 * FIX_GRAIN_NODES], area[FIX_GRAIN_NODES], sphere[4 * FIX_GRAIN_NODES];
  int start[FIX_GRAIN_NODES + 1];
  lsdem_shape clustered, plain;
} fix_grain;

static inline void fix_make_grain(fix_grain *g, const double a[3], const lsdem_sdf *sdf)
{
  fix_fibonacci_ellipsoid(FIX_GRAIN_NODES, a, g->nodes);
  for (int k = 0; k < FIX_GRAIN_NODES; k++) g->area[k] = 1.0;
  const int nc = lsdem_nodes_cluster(FIX_GRAIN_NODES, g->nodes, g->area, LSDEM_CLUSTER_TARGET,
                                     g->start, g->sphere);
  g->plain = fix_shape(*sdf, FIX_GRAIN_NODES, g->nodes, fmax(a[0], fmax(a[1], a[2])));
  g->clustered = g->plain;
  g->clustered.nclusters = nc;
  g->clustered.cluster_start = g->start;
  g->clustered.cluster_sphere = g->sphere;
}

#endif
