/* surfsdf.c -- star-shaped solids given by a radius function r(u): mass properties by
 * quadrature over directions, bounding boxes, and a true signed-distance grid from a dense
 * sampling of the surface (superellipsoids, random grains). */
#include "lsdem_prep.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

enum {
  STAR_MAX_SAMPLES = 4000000, /* surface samples of one grid (memory ~ 200 MB) */
  STAR_REFINE_MAX = 4         /* refinements of the direction grid */
};

/* Unit direction of polar angle theta (from +z) and azimuth phi. */
static void direction(double theta, double phi, double u[3])
{
  u[0] = sin(theta) * cos(phi);
  u[1] = sin(theta) * sin(phi);
  u[2] = cos(theta);
}

static int valid_radius(double r)
{
  return r > 0.0 && isfinite(r);
}

/* ----------------------------------------------------------- mass properties ---- */

lsdem_status lsdem_star_massprops(lsdem_radius_fn radius, const void *ctx, int n,
                                  lsdem_massprops *mp, lsdem_error *err)
{
  if (!radius || !mp || n < 4) return lsdem_fail(err, LSDEM_ERR_ARG, "bad star quadrature");
  const double dt = PI / n, dp = PI / n; /* 2n azimuthal cells of width pi/n */
  double v = 0.0, m1[3] = {0, 0, 0}, m2[9] = {0};
  for (int i = 0; i < n; i++) {
    const double theta = (i + 0.5) * dt, w = sin(theta) * dt * dp;
    for (int j = 0; j < 2 * n; j++) {
      double u[3];
      direction(theta, (j + 0.5) * dp, u);
      const double r = radius(u, ctx);
      if (!valid_radius(r))
        return lsdem_fail(err, LSDEM_ERR_NUMERIC, "radius %g in direction (%g, %g, %g)", r,
                          u[0], u[1], u[2]);
      const double r3 = r * r * r, r4 = r3 * r, r5 = r4 * r;
      v += w * r3 / 3.0;
      for (int a = 0; a < 3; a++) {
        m1[a] += w * r4 / 4.0 * u[a];
        for (int b = 0; b < 3; b++) m2[3 * a + b] += w * r5 / 5.0 * u[a] * u[b];
      }
    }
  }
  memset(mp, 0, sizeof *mp);
  mp->volume = v;
  for (int a = 0; a < 3; a++) mp->centroid[a] = m1[a] / v;
  /* central second moments, then I = tr(M) 1 - M */
  double mc[9], tr = 0.0;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      mc[3 * a + b] = m2[3 * a + b] - v * mp->centroid[a] * mp->centroid[b];
  for (int a = 0; a < 3; a++) tr += mc[4 * a];
  for (int k = 0; k < 9; k++) mp->inertia[k] = (k % 4 == 0 ? tr : 0.0) - mc[k];
  lsdem_sym_eigen(mp->inertia, mp->principal, mp->axes);
  return LSDEM_OK;
}

lsdem_status lsdem_star_bounds(lsdem_radius_fn radius, const void *ctx, double lo[3],
                               double hi[3], lsdem_error *err)
{
  if (!radius || !lo || !hi) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  const int n = 96;
  double rmax = 0.0;
  for (int a = 0; a < 3; a++) lo[a] = hi[a] = 0.0;
  for (int i = 0; i <= n; i++) /* poles and the equator included */
    for (int j = 0; j < 2 * n; j++) {
      double u[3];
      direction(PI * i / n, PI * j / n, u);
      const double r = radius(u, ctx);
      if (!valid_radius(r))
        return lsdem_fail(err, LSDEM_ERR_NUMERIC, "radius %g in direction (%g, %g, %g)", r,
                          u[0], u[1], u[2]);
      rmax = fmax(rmax, r);
      for (int a = 0; a < 3; a++) {
        lo[a] = fmin(lo[a], r * u[a]);
        hi[a] = fmax(hi[a], r * u[a]);
      }
    }
  for (int a = 0; a < 3; a++) {
    lo[a] -= 0.02 * rmax;
    hi[a] += 0.02 * rmax;
  }
  return LSDEM_OK;
}

/* ------------------------------------------------------------ surface samples ---- */

/* Surface points on an nt x 2nt latitude-longitude grid of directions (cell centres in
 * theta, so no sample sits on a pole), outward normals from central differences along
 * both grid lines, and rho = the largest distance between grid neighbours. */
typedef struct {
  int nt, np;
  double *x, *nrm;
  double rho;
} star_samples;

static lsdem_status sample_points(lsdem_radius_fn radius, const void *ctx, star_samples *S,
                                  lsdem_error *err)
{
  const size_t m = (size_t)S->nt * S->np;
  S->x = malloc(3 * m * sizeof(double));
  S->nrm = malloc(3 * m * sizeof(double));
  if (!S->x || !S->nrm) return lsdem_fail(err, LSDEM_ERR_NOMEM, "%zu surface samples", m);
  for (int i = 0; i < S->nt; i++)
    for (int j = 0; j < S->np; j++) {
      double u[3];
      direction(PI * (i + 0.5) / S->nt, 2.0 * PI * j / S->np, u);
      const double r = radius(u, ctx);
      if (!valid_radius(r))
        return lsdem_fail(err, LSDEM_ERR_NUMERIC, "radius %g in direction (%g, %g, %g)", r,
                          u[0], u[1], u[2]);
      double *p = S->x + 3 * ((size_t)i * S->np + j);
      for (int a = 0; a < 3; a++) p[a] = r * u[a];
    }
  return LSDEM_OK;
}

static double dist3(const double *a, const double *b)
{
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
              (a[2] - b[2]) * (a[2] - b[2]));
}

/* Normals n ~ (x_theta) x (x_phi), oriented so that n . x > 0 (outward for a star-shaped
 * surface); rho from the same neighbours. */
static void sample_normals(star_samples *S)
{
  S->rho = 0.0;
  for (int i = 0; i < S->nt; i++)
    for (int j = 0; j < S->np; j++) {
      const size_t c = (size_t)i * S->np + j;
      const double *x = S->x + 3 * c;
      const double *tn = S->x + 3 * ((size_t)(i + 1 < S->nt ? i + 1 : i) * S->np + j);
      const double *ts = S->x + 3 * ((size_t)(i > 0 ? i - 1 : i) * S->np + j);
      const double *pe = S->x + 3 * ((size_t)i * S->np + (j + 1) % S->np);
      const double *pw = S->x + 3 * ((size_t)i * S->np + (j + S->np - 1) % S->np);
      double a[3], b[3], n[3];
      for (int k = 0; k < 3; k++) {
        a[k] = tn[k] - ts[k];
        b[k] = pe[k] - pw[k];
      }
      n[0] = a[1] * b[2] - a[2] * b[1];
      n[1] = a[2] * b[0] - a[0] * b[2];
      n[2] = a[0] * b[1] - a[1] * b[0];
      double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (n[0] * x[0] + n[1] * x[1] + n[2] * x[2] < 0.0) len = -len;
      for (int k = 0; k < 3; k++) S->nrm[3 * c + k] = len != 0.0 ? n[k] / len : 0.0;
      S->rho = fmax(S->rho, fmax(dist3(x, tn), dist3(x, pe)));
    }
}

static void samples_free(star_samples *S)
{
  free(S->x);
  free(S->nrm);
  S->x = S->nrm = NULL;
}

/* Sample densely enough that neighbours are at most `spacing` apart: start from the
 * largest radius, then refine by the measured ratio (a few rounds at most). */
static lsdem_status sample_surface(lsdem_radius_fn radius, const void *ctx, double rmax,
                                   double spacing, star_samples *S, lsdem_error *err)
{
  int nt = (int)ceil(PI * rmax / spacing) + 2;
  for (int round = 0; round <= STAR_REFINE_MAX; round++) {
    if ((double)nt * 2.0 * nt > STAR_MAX_SAMPLES)
      return lsdem_fail(err, LSDEM_ERR_NOMEM, "the surface needs more than %d samples at "
                        "spacing %g (grid spacing too fine for the shape's detail?)",
                        STAR_MAX_SAMPLES, spacing);
    S->nt = nt, S->np = 2 * nt;
    lsdem_status st = sample_points(radius, ctx, S, err);
    if (st != LSDEM_OK) return st;
    sample_normals(S);
    if (S->rho <= spacing) return LSDEM_OK;
    samples_free(S);
    nt = (int)ceil(nt * 1.1 * S->rho / spacing);
  }
  return lsdem_fail(err, LSDEM_ERR_NUMERIC, "surface sampling did not reach spacing %g",
                    spacing);
}

/* ------------------------------------------------------------ distance field ---- */

/* Distance from p to the disc of radius rho about sample point x with unit normal n:
 * t = (p - x) . n, r = in-plane distance; |t| over the disc, else to its rim. */
static double disc_distance(const double p[3], const double *x, const double *n, double rho)
{
  double d[3];
  for (int a = 0; a < 3; a++) d[a] = p[a] - x[a];
  const double t = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
  const double r2 = fmax(0.0, d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - t * t);
  if (r2 <= rho * rho) return fabs(t);
  const double e = sqrt(r2) - rho;
  return sqrt(t * t + e * e);
}

/* Nearest disc of every grid sample: `dist` and `near` (sample index, -1 = none). */
typedef struct {
  const star_samples *S;
  const lsdem_grid *g;
  double *dist;
  int *near;
} nearest_field;

static void grid_point(const lsdem_grid *g, int i, int j, int k, double p[3])
{
  p[0] = g->origin[0] + g->h * i;
  p[1] = g->origin[1] + g->h * j;
  p[2] = g->origin[2] + g->h * k;
}

static void try_sample(nearest_field *F, size_t m, const double p[3], int s)
{
  const double d = disc_distance(p, F->S->x + 3 * (size_t)s, F->S->nrm + 3 * (size_t)s, F->S->rho);
  if (d < F->dist[m]) {
    F->dist[m] = d;
    F->near[m] = s;
  }
}

/* Exact nearest disc for every grid sample within `band` of a surface sample: each
 * surface sample visits the grid samples in its band box. */
static void splat_band(nearest_field *F, double band)
{
  const lsdem_grid *g = F->g;
  const size_t m = (size_t)F->S->nt * F->S->np;
  for (size_t s = 0; s < m; s++) {
    const double *x = F->S->x + 3 * s;
    int lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
      lo[a] = (int)ceil((x[a] - band - g->origin[a]) / g->h);
      hi[a] = (int)floor((x[a] + band - g->origin[a]) / g->h);
      lo[a] = lo[a] < 0 ? 0 : lo[a];
      hi[a] = hi[a] >= g->n[a] ? g->n[a] - 1 : hi[a];
    }
    for (int k = lo[2]; k <= hi[2]; k++)
      for (int j = lo[1]; j <= hi[1]; j++)
        for (int i = lo[0]; i <= hi[0]; i++) {
          double p[3];
          grid_point(g, i, j, k, p);
          try_sample(F, (size_t)i + (size_t)g->n[0] * ((size_t)j + (size_t)g->n[1] * k), p,
                     (int)s);
        }
  }
}

/* Closest-point propagation away from the band: eight sweeps (one per octant
 * direction), each sample trying the nearest discs of its seven upwind neighbours
 * (Danielsson-style vector distance transform, carried with the disc distance). */
static void propagate(nearest_field *F)
{
  const lsdem_grid *g = F->g;
  const int *n = g->n;
  for (int oct = 0; oct < 8; oct++) {
    const int sx = oct & 1 ? -1 : 1, sy = oct & 2 ? -1 : 1, sz = oct & 4 ? -1 : 1;
    for (int kk = 0; kk < n[2]; kk++)
      for (int jj = 0; jj < n[1]; jj++)
        for (int ii = 0; ii < n[0]; ii++) {
          const int i = sx > 0 ? ii : n[0] - 1 - ii, j = sy > 0 ? jj : n[1] - 1 - jj,
                    k = sz > 0 ? kk : n[2] - 1 - kk;
          const size_t m = (size_t)i + (size_t)n[0] * ((size_t)j + (size_t)n[1] * k);
          double p[3];
          grid_point(g, i, j, k, p);
          for (int t = 1; t < 8; t++) {
            const int q[3] = {i - (t & 1 ? sx : 0), j - (t & 2 ? sy : 0), k - (t & 4 ? sz : 0)};
            if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= n[0] || q[1] >= n[1] || q[2] >= n[2])
              continue;
            const size_t mq = (size_t)q[0] + (size_t)n[0] * ((size_t)q[1] + (size_t)n[1] * q[2]);
            const int s = F->near[mq];
            if (s >= 0 && s != F->near[m]) try_sample(F, m, p, s);
          }
        }
  }
}

/* Star test: inside when |p| < radius(p / |p|) (the origin is inside). */
static int star_inside(lsdem_radius_fn radius, const void *ctx, const double p[3])
{
  const double d = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  if (d == 0.0) return 1;
  const double u[3] = {p[0] / d, p[1] / d, p[2] / d};
  return d < radius(u, ctx);
}

/* Inside or not: the side of the nearest disc's plane, (p - x) . n < 0, when p is more
 * than `band` from the surface and p - x lies along the disc's normal (within ~11 deg):
 * then x is the nearest surface point and its normal decides. Otherwise (near the
 * surface, or near an edge or a vertex, where sampled normals are unreliable) the exact
 * star test. */
static int inside(const nearest_field *F, size_t m, const double p[3], lsdem_radius_fn radius,
                  const void *ctx, double band)
{
  if (F->dist[m] > band) {
    const double *x = F->S->x + 3 * (size_t)F->near[m], *n = F->S->nrm + 3 * (size_t)F->near[m];
    const double d[3] = {p[0] - x[0], p[1] - x[1], p[2] - x[2]};
    const double t = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    if (t * t >= 0.96 * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2])) return t < 0.0;
  }
  return star_inside(radius, ctx, p);
}

lsdem_status lsdem_grid_from_star(lsdem_radius_fn radius, const void *ctx, const double lo[3],
                                  const double hi[3], double h, int margin, lsdem_grid *g,
                                  lsdem_error *err)
{
  if (!radius || !g || !(h > 0.0)) return lsdem_fail(err, LSDEM_ERR_ARG, "bad star grid");
  double blo[3], bhi[3], rmax = 0.0;
  lsdem_status st = lsdem_star_bounds(radius, ctx, blo, bhi, err);
  if (st != LSDEM_OK) return st;
  for (int a = 0; a < 3; a++) rmax = fmax(rmax, fmax(-blo[a], bhi[a]));
  star_samples S = {0};
  lsdem_grid out = {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0};
  float *phi = NULL;
  nearest_field F = {&S, &out, NULL, NULL};
  st = sample_surface(radius, ctx, rmax, h / 3.0, &S, err);
  if (st == LSDEM_OK) st = lsdem_grid_alloc(lo, hi, h, margin, &out, &phi, err);
  if (st == LSDEM_OK) {
    const size_t ns = (size_t)out.n[0] * out.n[1] * out.n[2];
    F.dist = malloc(ns * sizeof(double));
    F.near = malloc(ns * sizeof(int));
    if (!F.dist || !F.near) {
      st = lsdem_fail(err, LSDEM_ERR_NOMEM, "distance field of %zu samples", ns);
      lsdem_grid_free(&out);
    } else {
      for (size_t m = 0; m < ns; m++) F.dist[m] = HUGE_VAL, F.near[m] = -1;
      splat_band(&F, 1.5 * h);
      propagate(&F);
      propagate(&F);
      size_t m = 0;
      for (int k = 0; k < out.n[2]; k++)
        for (int j = 0; j < out.n[1]; j++)
          for (int i = 0; i < out.n[0]; i++, m++) {
            double p[3];
            grid_point(&out, i, j, k, p);
            phi[m] = (float)(inside(&F, m, p, radius, ctx, 2.0 * h) ? -F.dist[m] : F.dist[m]);
          }
      *g = out;
    }
  }
  free(F.dist);
  free(F.near);
  samples_free(&S);
  return st;
}
