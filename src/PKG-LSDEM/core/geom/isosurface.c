/* isosurface.c -- triangle meshes of a shape's zero level set (marching tetrahedra),
 * written to files by io/surface_io.c.
 *
 * The SDF is sampled on a lattice of spacing h (for a grid shape at its own spacing, the
 * lattice is the grid itself). Every lattice cube is cut into the six Kuhn tetrahedra
 * around its main diagonal; neighbouring cubes then cut their shared faces along the same
 * diagonal, so the pieces fit. In each tetrahedron the surface phi = 0 is the plane of
 * linear interpolation of phi along its edges. A vertex lives on a lattice edge and is
 * keyed by (lower lattice point, edge direction), so neighbouring tetrahedra share it and
 * the mesh is closed. A sample is inside when phi < 0 (phi == 0 counts as outside), and
 * the outer lattice layer is forced outside, so the mesh is always closed. A vertex that
 * falls on a sample with phi == 0 exactly is keyed by that sample (one vertex, not one per
 * edge), and triangles it makes degenerate (a repeated vertex) are dropped. */
#include "lsdem_geom.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Kuhn tetrahedra: for each permutation (a, b, c) of the axes, the path
 * 0 -> e_a -> e_a + e_b -> (1,1,1). Corners are coded as bits x = 1, y = 2, z = 4. */
static const int KUHN[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                               {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

typedef struct {
  int n[3];          /* lattice points per axis */
  double h, lo[3];   /* spacing, position of point (0,0,0) */
  float *phi;        /* n0*n1*n2 values */
  int *edge_vertex;  /* 8 per lattice point of two z-layers (z & 1): vertex on the edge
                        to point + d (d coded 0..6), vertex at the point itself (7); -1
                        when not yet made. Cubes of layer k only touch layers k, k+1. */
  lsdem_mesh *m;
  int cap_v, cap_t;
} mesher;

static size_t point_index(const mesher *w, int i, int j, int k)
{
  return (size_t)i + (size_t)w->n[0] * ((size_t)j + (size_t)w->n[1] * (size_t)k);
}

/* First of the 8 vertex slots of lattice point p in the two-layer table. */
static size_t slot_index(const mesher *w, const int p[3])
{
  return 8 * ((size_t)p[0] + (size_t)w->n[0] * ((size_t)p[1] + (size_t)w->n[1] * (p[2] & 1)));
}

/* Lattice covering the shape: a grid shape's own samples when h <= 0, else its bounding
 * sphere's box at spacing h; plus one layer all round that is forced outside. */
static lsdem_status lattice_layout(const lsdem_sdf *s, double h, mesher *w, lsdem_error *err)
{
  if (s->kind == LSDEM_SDF_GRID && !(h > 0.0)) {
    w->h = s->grid.h;
    for (int a = 0; a < 3; a++) {
      w->n[a] = s->grid.n[a] + 2;
      w->lo[a] = s->grid.origin[a] - s->grid.h;
    }
    return LSDEM_OK;
  }
  const double r = lsdem_sdf_bound_radius(s);
  if (!isfinite(r) || !(r > 0.0))
    return lsdem_fail(err, LSDEM_ERR_ARG, "surface mesh: the shape is unbounded");
  if (!(h > 0.0)) h = r / 20.0;
  const double cells = ceil(2.0 * r / h) + 3.0; /* solid, a sample margin, the outer layer */
  if (cells > 2000.0)
    return lsdem_fail(err, LSDEM_ERR_ARG, "surface mesh: spacing %g is too fine for radius %g",
                      h, r);
  w->h = h;
  for (int a = 0; a < 3; a++) {
    w->n[a] = (int)cells + 1;
    w->lo[a] = -0.5 * cells * h;
  }
  return LSDEM_OK;
}

static void sample_lattice(const lsdem_sdf *s, mesher *w)
{
  double grad[3];
  for (int k = 0; k < w->n[2]; k++)
    for (int j = 0; j < w->n[1]; j++)
      for (int i = 0; i < w->n[0]; i++) {
        const int border = i == 0 || j == 0 || k == 0 || i == w->n[0] - 1 ||
                           j == w->n[1] - 1 || k == w->n[2] - 1;
        const double p[3] = {w->lo[0] + w->h * i, w->lo[1] + w->h * j, w->lo[2] + w->h * k};
        const double v = lsdem_sdf_eval(s, p, grad);
        w->phi[point_index(w, i, j, k)] = (float)(border ? fmax(v, w->h) : v);
      }
}

static int grow(void **p, int *cap, int need, size_t elem)
{
  if (need <= *cap) return 1;
  int c = *cap > 0 ? *cap : 1024;
  while (c < need) c *= 2;
  void *q = realloc(*p, (size_t)c * elem);
  if (!q) return 0;
  *p = q;
  *cap = c;
  return 1;
}

/* Lattice coordinates of corner c (bits x, y, z) of the cube at (i, j, k). */
static void corner(int i, int j, int k, int c, int out[3])
{
  out[0] = i + (c & 1);
  out[1] = j + ((c >> 1) & 1);
  out[2] = k + ((c >> 2) & 1);
}

/* The vertex where phi = 0 on the lattice edge a-b (phi changes sign along it), by linear
 * interpolation; created on first use. Returns its index or -1 when out of memory. */
static int edge_vertex(mesher *w, const int a[3], const int b[3])
{
  const double fa = w->phi[point_index(w, a[0], a[1], a[2])];
  const double fb = w->phi[point_index(w, b[0], b[1], b[2])];
  const int *lo = a, *hi = b;
  if (a[0] > b[0] || a[1] > b[1] || a[2] > b[2]) lo = b, hi = a;
  const int code = (hi[0] - lo[0]) + 2 * (hi[1] - lo[1]) + 4 * (hi[2] - lo[2]) - 1;
  size_t key = slot_index(w, lo) + (size_t)code;
  if (fa == 0.0) key = slot_index(w, a) + 7;
  if (fb == 0.0) key = slot_index(w, b) + 7;
  if (w->edge_vertex[key] >= 0) return w->edge_vertex[key];
  lsdem_mesh *m = w->m;
  if (!grow((void **)&m->verts, &w->cap_v, m->nverts + 1, 3 * sizeof(double))) return -1;
  const double t = fa / (fa - fb); /* fa, fb have opposite signs (one may be 0) */
  for (int d = 0; d < 3; d++)
    m->verts[3 * m->nverts + d] = w->lo[d] + w->h * (a[d] + t * (b[d] - a[d]));
  w->edge_vertex[key] = m->nverts;
  return m->nverts++;
}

static int add_triangle(mesher *w, int v0, int v1, int v2)
{
  lsdem_mesh *m = w->m;
  if (v0 < 0 || v1 < 0 || v2 < 0) return 0;
  if (v0 == v1 || v1 == v2 || v0 == v2) return 1; /* collapsed onto a zero sample */
  if (!grow((void **)&m->tris, &w->cap_t, m->ntris + 1, 3 * sizeof(int))) return 0;
  int *t = m->tris + 3 * m->ntris++;
  t[0] = v0, t[1] = v1, t[2] = v2;
  return 1;
}

/* det(b - a, c - a, d - a) of lattice points: the tetrahedron's orientation (+-1). */
static int orientation(const int *a, const int *b, const int *c, const int *d)
{
  int u[3], v[3], x[3];
  for (int k = 0; k < 3; k++) u[k] = b[k] - a[k], v[k] = c[k] - a[k], x[k] = d[k] - a[k];
  return u[0] * (v[1] * x[2] - v[2] * x[1]) - u[1] * (v[0] * x[2] - v[2] * x[0]) +
         u[2] * (v[0] * x[1] - v[1] * x[0]);
}

/* Surface pieces of one tetrahedron, oriented outward. With the corners reordered as
 * p = (inside..., outside...), a triangle of points on the edges a-b, a-c, a-d has its
 * normal pointing away from a iff det(b - a, c - a, d - a) > 0 (the points are a plus
 * positive multiples of the edge vectors), which fixes every case exactly. */
static int polygonise(mesher *w, int p[4][3], int nin)
{
  const int s = orientation(p[0], p[1], p[2], p[3]);
  if (nin == 1) { /* triangle around inside corner 0, normal away from it */
    const int e1 = edge_vertex(w, p[0], p[1]), e2 = edge_vertex(w, p[0], p[2]),
              e3 = edge_vertex(w, p[0], p[3]);
    return s > 0 ? add_triangle(w, e1, e2, e3) : add_triangle(w, e1, e3, e2);
  }
  if (nin == 3) { /* triangle around outside corner 3, normal towards it */
    const int e0 = edge_vertex(w, p[3], p[0]), e1 = edge_vertex(w, p[3], p[1]),
              e2 = edge_vertex(w, p[3], p[2]);
    const int s3 = orientation(p[3], p[0], p[1], p[2]);
    return s3 > 0 ? add_triangle(w, e0, e2, e1) : add_triangle(w, e0, e1, e2);
  }
  /* two inside (0, 1), two outside (2, 3): the quad 02, 03, 13, 12 */
  const int q[4] = {edge_vertex(w, p[0], p[2]), edge_vertex(w, p[0], p[3]),
                    edge_vertex(w, p[1], p[3]), edge_vertex(w, p[1], p[2])};
  if (s > 0) return add_triangle(w, q[0], q[1], q[2]) && add_triangle(w, q[0], q[2], q[3]);
  return add_triangle(w, q[0], q[3], q[2]) && add_triangle(w, q[0], q[2], q[1]);
}

static int march_cube(mesher *w, int i, int j, int k)
{
  for (int t = 0; t < 6; t++) {
    int p[4][3], nin = 0, order[4], lo = 0, hi = 3;
    for (int c = 0; c < 4; c++) { /* inside corners first, then the outside ones */
      int q[3];
      corner(i, j, k, KUHN[t][c], q);
      if (w->phi[point_index(w, q[0], q[1], q[2])] < 0.0f) order[lo++] = c, nin++;
      else order[hi--] = c;
      memcpy(p[c], q, sizeof q);
    }
    if (nin == 0 || nin == 4) continue;
    int r[4][3];
    for (int c = 0; c < 4; c++) memcpy(r[c], p[order[c]], sizeof r[c]);
    if (!polygonise(w, r, nin)) return 0;
  }
  return 1;
}

lsdem_status lsdem_mesh_extract(const lsdem_sdf *s, double h, lsdem_mesh *m, lsdem_error *err)
{
  if (!s || !m) return lsdem_fail(err, LSDEM_ERR_ARG, "surface mesh: NULL argument");
  memset(m, 0, sizeof *m);
  mesher w;
  memset(&w, 0, sizeof w);
  w.m = m;
  lsdem_status st = lattice_layout(s, h, &w, err);
  if (st != LSDEM_OK) return st;
  const size_t np = (size_t)w.n[0] * w.n[1] * w.n[2], layer = (size_t)w.n[0] * w.n[1];
  if (np > ((size_t)1 << 28))
    return lsdem_fail(err, LSDEM_ERR_ARG, "surface mesh: lattice of %dx%dx%d points is too "
                      "large (use a coarser spacing)", w.n[0], w.n[1], w.n[2]);
  w.phi = malloc(np * sizeof(float));
  w.edge_vertex = malloc(16 * layer * sizeof(int));
  int ok = w.phi && w.edge_vertex;
  if (ok) {
    memset(w.edge_vertex, 0xff, 16 * layer * sizeof(int)); /* all -1 */
    sample_lattice(s, &w);
  }
  for (int k = 0; ok && k + 1 < w.n[2]; k++) {
    if (k > 0) /* layer k + 1 reuses the slots of layer k - 1 */
      memset(w.edge_vertex + 8 * layer * ((k + 1) & 1), 0xff, 8 * layer * sizeof(int));
    for (int j = 0; ok && j + 1 < w.n[1]; j++)
      for (int i = 0; ok && i + 1 < w.n[0]; i++) ok = march_cube(&w, i, j, k);
  }
  free(w.phi);
  free(w.edge_vertex);
  if (!ok) {
    lsdem_mesh_free(m);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "surface mesh: out of memory");
  }
  return LSDEM_OK;
}

void lsdem_mesh_free(lsdem_mesh *m)
{
  if (!m) return;
  free(m->verts);
  free(m->tris);
  memset(m, 0, sizeof *m);
}

/* Triangle t's corners. */
static void tri_points(const lsdem_mesh *m, int t, const double *p[3])
{
  for (int c = 0; c < 3; c++) p[c] = m->verts + 3 * m->tris[3 * t + c];
}

double lsdem_mesh_area(const lsdem_mesh *m)
{
  double area = 0.0;
  for (int t = 0; t < m->ntris; t++) {
    const double *p[3];
    tri_points(m, t, p);
    double u[3], v[3];
    for (int d = 0; d < 3; d++) u[d] = p[1][d] - p[0][d], v[d] = p[2][d] - p[0][d];
    const double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2],
                 cz = u[0] * v[1] - u[1] * v[0];
    area += 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
  }
  return area;
}
