/* mesh_check.c -- the checks a triangle mesh must pass before it becomes a grain or a wall:
 * closed and consistently oriented (every edge shared by exactly two triangles traversing it
 * in opposite directions, lsdem_mesh_check_closed), free of self-intersections
 * (lsdem_mesh_check_self_intersection), and its enclosed volume. */
#include "lsdem_prep.h"
#include "mesh_distance.h"
#include "../geom/ray_triangle.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------ small vectors ---- */

double lsdem_mesh_volume(const lsdem_mesh *m)
{
  double v = 0.0;
  for (int t = 0; t < m->ntris; t++) {
    double bc[3];
    lsdem_cross3(mesh_vert(m, t, 1), mesh_vert(m, t, 2), bc);
    v += lsdem_dot3(mesh_vert(m, t, 0), bc) / 6.0;
  }
  return v;
}

/* ---------------------------------------------------------------- topology ---- */

/* A directed edge of triangle t (corner e to corner e+1), keyed by its sorted ends. */
typedef struct {
  int lo, hi, t, e, forward; /* forward: traversed lo -> hi */
} edge_rec;

static int cmp_edge(const void *a, const void *b)
{
  const edge_rec *x = a, *y = b;
  if (x->lo != y->lo) return x->lo < y->lo ? -1 : 1;
  if (x->hi != y->hi) return x->hi < y->hi ? -1 : 1;
  return x->t < y->t ? -1 : x->t > y->t;
}

static void note_where(lsdem_mesh_topology *topo, int *first, const double *a, const double *b)
{
  if (*first) return;
  *first = 1;
  for (int k = 0; k < 3; k++) topo->where[k] = 0.5 * (a[k] + b[k]);
}

/* Edge analysis (mesh_distance.h). */
lsdem_status mesh_edges(const lsdem_mesh *m, lsdem_mesh_topology *topo, int *nbr,
                        lsdem_error *err)
{
  memset(topo, 0, sizeof *topo);
  const size_t ne = 3 * (size_t)m->ntris;
  edge_rec *E = malloc(ne * sizeof *E + 1);
  if (!E) return lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate %zu edges", ne);
  int found = 0;
  for (int t = 0; t < m->ntris; t++) {
    const int *v = m->tris + 3 * t;
    double n[3];
    mesh_tri_normal(m, t, n);
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0] || lsdem_dot3(n, n) == 0.0) {
      topo->degenerate_tris++;
      note_where(topo, &found, mesh_vert(m, t, 0), mesh_vert(m, t, 1));
    }
    for (int e = 0; e < 3; e++) {
      const int a = v[e], b = v[(e + 1) % 3];
      E[3 * t + e] = (edge_rec){a < b ? a : b, a < b ? b : a, t, e, a < b};
    }
  }
  qsort(E, ne, sizeof *E, cmp_edge);
  if (nbr)
    for (size_t i = 0; i < ne; i++) nbr[i] = -1;
  for (size_t i = 0; i < ne;) {
    size_t j = i + 1;
    while (j < ne && E[j].lo == E[i].lo && E[j].hi == E[i].hi) j++;
    const double *a = m->verts + 3 * E[i].lo, *b = m->verts + 3 * E[i].hi;
    if (j - i == 1) topo->boundary_edges++, note_where(topo, &found, a, b);
    else if (j - i > 2) topo->nonmanifold_edges++, note_where(topo, &found, a, b);
    else if (E[i].forward == E[i + 1].forward)
      topo->misoriented_edges++, note_where(topo, &found, a, b);
    if (nbr && j - i == 2) {
      nbr[3 * E[i].t + E[i].e] = E[i + 1].t;
      nbr[3 * E[i + 1].t + E[i + 1].e] = E[i].t;
    }
    i = j;
  }
  free(E);
  return LSDEM_OK;
}

lsdem_status lsdem_mesh_check_closed(const lsdem_mesh *m, lsdem_mesh_topology *topo,
                                     lsdem_error *err)
{
  if (!m || m->ntris < 1) return lsdem_fail(err, LSDEM_ERR_ARG, "empty mesh");
  lsdem_mesh_topology local;
  if (!topo) topo = &local;
  lsdem_status st = mesh_edges(m, topo, NULL, err);
  if (st != LSDEM_OK) return st;
  if (topo->boundary_edges || topo->nonmanifold_edges || topo->misoriented_edges ||
      topo->degenerate_tris)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "mesh is not closed: %d boundary edges (holes), "
                      "%d non-manifold edges, %d edges with inconsistent orientation, %d "
                      "degenerate triangles; first near (%g, %g, %g)", topo->boundary_edges,
                      topo->nonmanifold_edges, topo->misoriented_edges, topo->degenerate_tris,
                      topo->where[0], topo->where[1], topo->where[2]);
  return LSDEM_OK;
}

/* ------------------------------------------------------- uniform cell grid ---- */

/* Triangles bucketed by the cells their bounding boxes overlap (CSR lists). */
typedef struct {
  int n[3];
  double lo[3], cs;
  int *start; /* ncells + 1 */
  int *items;
  double *box; /* 6 per triangle: min xyz, max xyz */
} tri_grid;

static void tri_grid_free(tri_grid *g)
{
  free(g->start), free(g->items), free(g->box);
  memset(g, 0, sizeof *g);
}

static int cell_of(const tri_grid *g, double x, int a)
{
  const double c = floor((x - g->lo[a]) / g->cs);
  return c < 0.0 ? 0 : c >= g->n[a] ? g->n[a] - 1 : (int)c;
}

static void cell_range(const tri_grid *g, const double *box, int c0[3], int c1[3])
{
  for (int a = 0; a < 3; a++) c0[a] = cell_of(g, box[a], a), c1[a] = cell_of(g, box[3 + a], a);
}

/* Cell size: half the mean triangle extent, but no more than ~64 cells per triangle and
 * at most 129 cells per axis (cs >= span / 128). */
static lsdem_status tri_grid_build(const lsdem_mesh *m, tri_grid *g, lsdem_error *err)
{
  memset(g, 0, sizeof *g);
  g->box = malloc(6 * (size_t)m->ntris * sizeof(double));
  if (!g->box) return lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate the triangle grid");
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  double ext = 0.0;
  for (int t = 0; t < m->ntris; t++) {
    double *b = g->box + 6 * t;
    for (int a = 0; a < 3; a++) {
      const double x0 = mesh_vert(m, t, 0)[a], x1 = mesh_vert(m, t, 1)[a];
      const double x2 = mesh_vert(m, t, 2)[a];
      b[a] = fmin(x0, fmin(x1, x2));
      b[3 + a] = fmax(x0, fmax(x1, x2));
      lo[a] = fmin(lo[a], b[a]), hi[a] = fmax(hi[a], b[3 + a]);
      ext += (b[3 + a] - b[a]) / (6.0 * m->ntris);
    }
  }
  const double span = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
  const double vol = fmax(hi[0] - lo[0], span * 1e-3) * fmax(hi[1] - lo[1], span * 1e-3) *
                     fmax(hi[2] - lo[2], span * 1e-3);
  g->cs = fmax(fmax(ext, cbrt(vol / (64.0 * m->ntris))), span / 128.0);
  if (!(g->cs > 0.0) || !isfinite(g->cs)) g->cs = 1.0;
  size_t ncells = 1;
  for (int a = 0; a < 3; a++) {
    g->lo[a] = lo[a];
    g->n[a] = (int)floor((hi[a] - lo[a]) / g->cs) + 1; /* <= 129: cells cover [lo, hi] */
    ncells *= (size_t)g->n[a];
  }
  g->start = calloc(ncells + 1, sizeof(int));
  if (!g->start) return lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate the triangle grid");
  for (int pass = 0; pass < 2; pass++) { /* count, then fill (counting sort) */
    for (int t = 0; t < m->ntris; t++) {
      int c0[3], c1[3];
      cell_range(g, g->box + 6 * t, c0, c1);
      for (int k = c0[2]; k <= c1[2]; k++)
        for (int j = c0[1]; j <= c1[1]; j++)
          for (int i = c0[0]; i <= c1[0]; i++) {
            const size_t c = ((size_t)k * g->n[1] + j) * g->n[0] + i;
            if (pass == 0) g->start[c + 1]++;
            else g->items[g->start[c]++] = t;
          }
    }
    if (pass == 0) {
      for (size_t c = 0; c < ncells; c++) g->start[c + 1] += g->start[c];
      g->items = malloc((size_t)g->start[ncells] * sizeof(int) + 1);
      if (!g->items) return lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate the triangle grid");
    }
  }
  for (size_t c = ncells; c > 0; c--) g->start[c] = g->start[c - 1]; /* undo the fill shift */
  g->start[0] = 0;
  return LSDEM_OK;
}

/* ------------------------------------------------------- self-intersection ---- */

/* Whether segment pq crosses triangle abc (closed segment and triangle, not coplanar). */
static int segment_hits_triangle(const double *p, const double *q, const double *a,
                                 const double *b, const double *c)
{
  double d[3];
  lsdem_sub3(q, p, d);
  const double t = lsdem_ray_triangle(p, d, a, b, c);
  return t >= 0.0 && t <= 1.0;
}

/* Two triangles without a shared vertex intersect iff an edge of one crosses the other
 * (non-coplanar case). */
static int triangles_intersect(const lsdem_mesh *m, int s, int t)
{
  for (int pass = 0; pass < 2; pass++) {
    const int x = pass ? t : s, y = pass ? s : t;
    for (int e = 0; e < 3; e++)
      if (segment_hits_triangle(mesh_vert(m, x, e), mesh_vert(m, x, (e + 1) % 3),
                                mesh_vert(m, y, 0), mesh_vert(m, y, 1), mesh_vert(m, y, 2)))
        return 1;
  }
  return 0;
}

static int share_vertex(const lsdem_mesh *m, int s, int t)
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      if (m->tris[3 * s + i] == m->tris[3 * t + j]) return 1;
  return 0;
}

/* Test a pair once: in the cell holding the low corner of their boxes' overlap. */
static int pair_owned_here(const tri_grid *g, const double *bs, const double *bt, const int c[3])
{
  for (int a = 0; a < 3; a++) {
    if (bs[a] > bt[3 + a] || bt[a] > bs[3 + a]) return 0; /* boxes apart */
    if (cell_of(g, fmax(bs[a], bt[a]), a) != c[a]) return 0;
  }
  return 1;
}

lsdem_status lsdem_mesh_check_self_intersection(const lsdem_mesh *m, int pair[2],
                                                lsdem_error *err)
{
  if (pair) pair[0] = pair[1] = -1;
  if (!m || m->ntris < 1) return lsdem_fail(err, LSDEM_ERR_ARG, "empty mesh");
  tri_grid g;
  lsdem_status st = tri_grid_build(m, &g, err);
  int hit_s = -1, hit_t = -1;
  for (int k = 0; st == LSDEM_OK && k < g.n[2] && hit_s < 0; k++)
    for (int j = 0; j < g.n[1] && hit_s < 0; j++)
      for (int i = 0; i < g.n[0] && hit_s < 0; i++) {
        const size_t c = ((size_t)k * g.n[1] + j) * g.n[0] + i;
        const int cc[3] = {i, j, k};
        for (int x = g.start[c]; x < g.start[c + 1] && hit_s < 0; x++)
          for (int y = x + 1; y < g.start[c + 1]; y++) {
            const int s = g.items[x], t = g.items[y];
            if (!pair_owned_here(&g, g.box + 6 * s, g.box + 6 * t, cc) || share_vertex(m, s, t))
              continue;
            if (triangles_intersect(m, s, t)) {
              hit_s = s < t ? s : t, hit_t = s < t ? t : s;
              break;
            }
          }
      }
  tri_grid_free(&g);
  if (st != LSDEM_OK) return st;
  if (hit_s < 0) return LSDEM_OK;
  if (pair) pair[0] = hit_s, pair[1] = hit_t;
  const double *a = mesh_vert(m, hit_s, 0);
  return lsdem_fail(err, LSDEM_ERR_FORMAT, "mesh intersects itself: triangles %d and %d cross "
                    "(near (%g, %g, %g))", hit_s, hit_t, a[0], a[1], a[2]);
}
