/* nodes.c -- surface nodes of a grain: seeding on the zero level set, the surface area
 * of a grid, and clustering into groups with bounding spheres for cheap rejection. */
#include "lsdem_prep.h"

#include <math.h>
#include <stdlib.h>

/* ------------------------------------------------------------ clustering ---- */

static void swap_nodes(double *nodes, double *area, int i, int j)
{
  for (int a = 0; a < 3; a++) {
    const double t = nodes[3 * i + a];
    nodes[3 * i + a] = nodes[3 * j + a];
    nodes[3 * j + a] = t;
  }
  if (area) {
    const double t = area[i];
    area[i] = area[j];
    area[j] = t;
  }
}

/* Reorder nodes [lo, hi) so that the node at index k has the k-th smallest coordinate
 * `axis`, smaller ones before it and larger ones after (Hoare quickselect, middle pivot). */
static void select_nth(double *nodes, double *area, int lo, int hi, int k, int axis)
{
  hi--;
  while (lo < hi) {
    const double pivot = nodes[3 * (lo + (hi - lo) / 2) + axis];
    int i = lo, j = hi;
    while (i <= j) {
      while (nodes[3 * i + axis] < pivot) i++;
      while (nodes[3 * j + axis] > pivot) j--;
      if (i <= j) swap_nodes(nodes, area, i++, j--);
    }
    if (k <= j)
      hi = j;
    else if (k >= i)
      lo = i;
    else
      return;
  }
}

static void bounding_box(const double *nodes, int lo, int hi, double bmin[3], double bmax[3])
{
  for (int a = 0; a < 3; a++) {
    bmin[a] = HUGE_VAL;
    bmax[a] = -HUGE_VAL;
  }
  for (int i = lo; i < hi; i++)
    for (int a = 0; a < 3; a++) {
      bmin[a] = fmin(bmin[a], nodes[3 * i + a]);
      bmax[a] = fmax(bmax[a], nodes[3 * i + a]);
    }
}

/* Sphere about the box centre of nodes [lo, hi) through the farthest of them. */
static void cluster_bound(const double *nodes, int lo, int hi, double sphere[4])
{
  double bmin[3], bmax[3], r2 = 0.0;
  bounding_box(nodes, lo, hi, bmin, bmax);
  for (int a = 0; a < 3; a++) sphere[a] = 0.5 * (bmin[a] + bmax[a]);
  for (int i = lo; i < hi; i++) {
    const double *p = nodes + 3 * i;
    const double d2 = (p[0] - sphere[0]) * (p[0] - sphere[0]) +
                      (p[1] - sphere[1]) * (p[1] - sphere[1]) +
                      (p[2] - sphere[2]) * (p[2] - sphere[2]);
    r2 = fmax(r2, d2);
  }
  sphere[3] = sqrt(r2);
}

/* Split [lo, hi) at the median of its longest box axis until pieces hold <= target
 * nodes; pieces are emitted left to right, so clusters are contiguous. */
static void bisect(double *nodes, double *area, int lo, int hi, int target, int *nc,
                   int *cluster_start, double *cluster_sphere)
{
  if (hi - lo <= target) {
    cluster_start[*nc] = lo;
    cluster_bound(nodes, lo, hi, cluster_sphere + 4 * *nc);
    (*nc)++;
    return;
  }
  double bmin[3], bmax[3];
  bounding_box(nodes, lo, hi, bmin, bmax);
  int axis = 0;
  for (int a = 1; a < 3; a++)
    if (bmax[a] - bmin[a] > bmax[axis] - bmin[axis]) axis = a;
  const int mid = lo + (hi - lo) / 2;
  select_nth(nodes, area, lo, hi, mid, axis);
  bisect(nodes, area, lo, mid, target, nc, cluster_start, cluster_sphere);
  bisect(nodes, area, mid, hi, target, nc, cluster_start, cluster_sphere);
}

int lsdem_nodes_cluster(int nnodes, double *nodes, double *area, int target,
                        int *cluster_start, double *cluster_sphere)
{
  if (nnodes <= 0) {
    if (cluster_start) cluster_start[0] = 0;
    return 0;
  }
  int nc = 0;
  bisect(nodes, area, 0, nnodes, target < 1 ? 1 : target, &nc, cluster_start, cluster_sphere);
  cluster_start[nc] = nnodes;
  return nc;
}

/* ---------------------------------------------------------- surface area ---- */

/* Smoothed delta of half-width eps: (1 + cos(pi x / eps)) / (2 eps). */
static double smoothed_delta(double x, double eps)
{
  if (fabs(x) >= eps) return 0.0;
  const double pi = 3.14159265358979323846;
  return 0.5 / eps * (1.0 + cos(pi * x / eps));
}

/* Co-area formula: area = integral of delta(phi) |grad phi| dV, voxel-centre rule with
 * eps = h and |grad phi| from central differences (one-sided on the grid boundary). */
double lsdem_surface_area_grid(const lsdem_grid *g)
{
  const double h = g->h, dv = h * h * h;
  const size_t sy = (size_t)g->n[0], sz = sy * (size_t)g->n[1];
  double total = 0.0;
  size_t m = 0;
  for (int k = 0; k < g->n[2]; k++)
    for (int j = 0; j < g->n[1]; j++)
      for (int i = 0; i < g->n[0]; i++, m++) {
        const double v = g->phi[m];
        const double w = smoothed_delta(v, h);
        if (w == 0.0) continue;
        const int c[3] = {i, j, k};
        const size_t stride[3] = {1, sy, sz};
        double g2 = 0.0;
        for (int a = 0; a < 3; a++) {
          const int up = c[a] < g->n[a] - 1, dn = c[a] > 0;
          const double fp = up ? g->phi[m + stride[a]] : v, fm = dn ? g->phi[m - stride[a]] : v;
          const double d = (fp - fm) / ((up + dn) * h);
          g2 += d * d;
        }
        total += w * sqrt(g2) * dv;
      }
  return total;
}

/* --------------------------------------------------------------- seeding ---- */

enum {
  SEED_CANDIDATES_PER_NODE = 40, /* candidates behind each node: sets area resolution */
  SEED_BLOCK = 8,                /* lattice cells per block side in the band search */
  SEED_NEWTON_MAX = 30
};

static uint64_t splitmix64(uint64_t *state)
{
  uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

static double uniform01(uint64_t *state)
{
  return (double)(splitmix64(state) >> 11) * (1.0 / 9007199254740992.0);
}

/* Newton projection onto phi = 0 along the (unit) gradient: p <- p - phi grad. Exact in
 * one step for a true SDF away from its medial set; a few steps for a grid. Returns
 * nonzero when |phi| <= tol was reached. */
static int project_to_surface(const lsdem_sdf *s, double p[3], double tol)
{
  double g[3];
  for (int it = 0; it < SEED_NEWTON_MAX; it++) {
    const double v = lsdem_sdf_eval(s, p, g);
    if (fabs(v) <= tol) return 1;
    for (int a = 0; a < 3; a++) p[a] -= v * g[a];
  }
  return 0;
}

/* Candidate points: one jittered point per lattice cell of side c inside [-R, R]^3,
 * kept when it lies in the band |phi| < c and then projected onto the surface. Blocks
 * of SEED_BLOCK^3 cells far from the surface are skipped (phi is 1-Lipschitz; the 1.5
 * allows for grids that are only nearly distance functions). Each kept candidate
 * stands for band volume c^3, i.e. surface area c^3 / (2c) = c^2 / 2 (co-area formula).
 * Writes up to cap points to pts (NULL: only count); returns the number found. */
typedef struct {
  const lsdem_sdf *s;
  double R, c, tol;
  uint64_t rng;
} seed_lattice;

static size_t collect_candidates(seed_lattice *L, double *pts, size_t cap)
{
  const int cells = (int)ceil(2.0 * L->R / L->c);
  const int blocks = (cells + SEED_BLOCK - 1) / SEED_BLOCK;
  const double B = SEED_BLOCK * L->c, skip = 1.5 * 0.5 * sqrt(3.0) * B + L->c;
  size_t found = 0;
  double g[3];
  for (int bk = 0; bk < blocks; bk++)
    for (int bj = 0; bj < blocks; bj++)
      for (int bi = 0; bi < blocks; bi++) {
        const double centre[3] = {-L->R + B * (bi + 0.5), -L->R + B * (bj + 0.5),
                                  -L->R + B * (bk + 0.5)};
        if (fabs(lsdem_sdf_eval(L->s, centre, g)) > skip) continue;
        for (int k = 0; k < SEED_BLOCK; k++)
          for (int j = 0; j < SEED_BLOCK; j++)
            for (int i = 0; i < SEED_BLOCK; i++) {
              const int idx[3] = {bi * SEED_BLOCK + i, bj * SEED_BLOCK + j, bk * SEED_BLOCK + k};
              if (idx[0] >= cells || idx[1] >= cells || idx[2] >= cells) continue;
              double p[3];
              for (int a = 0; a < 3; a++) p[a] = -L->R + L->c * (idx[a] + uniform01(&L->rng));
              if (!(fabs(lsdem_sdf_eval(L->s, p, g)) < L->c)) continue;
              if (!project_to_surface(L->s, p, L->tol)) continue;
              if (pts && found < cap)
                for (int a = 0; a < 3; a++) pts[3 * found + a] = p[a];
              found++;
            }
      }
  return found;
}

/* Farthest-point sampling: start from a seeded random candidate, then repeatedly take
 * the candidate farthest from all chosen ones. nearest[] ends as each candidate's
 * nearest chosen node (a Voronoi assignment). */
static void farthest_points(const double *pts, size_t m, int count, uint64_t *rng,
                            double *d2, int *nearest, size_t *chosen)
{
  size_t next = (size_t)(splitmix64(rng) % m);
  for (size_t i = 0; i < m; i++) d2[i] = HUGE_VAL;
  for (int n = 0; n < count; n++) {
    chosen[n] = next;
    const double *q = pts + 3 * next;
    double best = -1.0;
    for (size_t i = 0; i < m; i++) {
      const double *p = pts + 3 * i;
      const double dd = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                        (p[2] - q[2]) * (p[2] - q[2]);
      if (dd < d2[i]) {
        d2[i] = dd;
        nearest[i] = n;
      }
      if (d2[i] > best) {
        best = d2[i];
        next = i;
      }
    }
  }
}

lsdem_status lsdem_nodes_seed(const lsdem_sdf *s, int target_count, uint64_t seed,
                              double *nodes, double *area, int *count, lsdem_error *err)
{
  if (!s || !nodes || !area || !count) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  *count = 0;
  if (target_count < 1)
    return lsdem_fail(err, LSDEM_ERR_ARG, "node count %d: must be positive", target_count);
  if (s->kind == LSDEM_SDF_GRID) {
    const lsdem_status st = lsdem_grid_check(&s->grid, err);
    if (st != LSDEM_OK) return st;
  }
  const double R = lsdem_sdf_bound_radius(s);
  if (!(R > 0.0) || !isfinite(R))
    return lsdem_fail(err, LSDEM_ERR_ARG, "cannot seed nodes on an unbounded or empty shape");
  /* pass 1: a coarse lattice estimates the area, which sets the lattice spacing giving
   * about SEED_CANDIDATES_PER_NODE candidates per node in pass 2 */
  seed_lattice L = {s, R * 1.05, R / 24.0, 1e-9 * R, seed};
  const size_t coarse = collect_candidates(&L, NULL, 0);
  const double area_est = coarse * 0.5 * L.c * L.c;
  const double want = (double)SEED_CANDIDATES_PER_NODE * target_count;
  if (coarse > 0) L.c = fmin(L.c, sqrt(2.0 * area_est / want));
  size_t cap = (size_t)(1.5 * want) + 1024, m = 0;
  double *pts = NULL, *d2 = NULL;
  int *nearest = NULL;
  size_t *chosen = malloc(sizeof(size_t) * (size_t)target_count);
  lsdem_status st = LSDEM_OK;
  const uint64_t rng_pass2 = L.rng;
  for (;;) { /* a rerun from the same RNG state reproduces the same candidates */
    pts = malloc(sizeof(double) * 3 * cap);
    d2 = malloc(sizeof(double) * cap);
    nearest = malloc(sizeof(int) * cap);
    if (!pts || !d2 || !nearest || !chosen) {
      st = lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate %zu seeding candidates", cap);
      goto done;
    }
    L.rng = rng_pass2;
    m = collect_candidates(&L, pts, cap);
    if (m <= cap) break;
    free(pts);
    free(d2);
    free(nearest);
    cap = m;
  }
  if (m == 0) {
    st = lsdem_fail(err, LSDEM_ERR_NUMERIC, "no surface point found (spacing %g)", L.c);
    goto done;
  }
  const int n = (size_t)target_count < m ? target_count : (int)m;
  farthest_points(pts, m, n, &L.rng, d2, nearest, chosen);
  const double cand_area = 0.5 * L.c * L.c;
  for (int k = 0; k < n; k++) {
    for (int a = 0; a < 3; a++) nodes[3 * k + a] = pts[3 * chosen[k] + a];
    area[k] = 0.0;
  }
  for (size_t i = 0; i < m; i++) area[nearest[i]] += cand_area;
  *count = n;
done:
  free(pts);
  free(d2);
  free(nearest);
  free(chosen);
  return st;
}
