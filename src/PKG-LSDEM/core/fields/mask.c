/* mask.c -- the grid nodes inside a closed triangulated surface (a membrane closed at its
 * ends): ray parity along x with an exact, shared tie rule (lsdem_fields.h). */
#include "lsdem_fields.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  int a, b; /* a < b */
} edge;

typedef struct {
  size_t row;
  double x;
} crossing;

static int edge_cmp(const void *p, const void *q)
{
  const edge *e = p, *f = q;
  return e->a != f->a ? (e->a < f->a ? -1 : 1) : (e->b > f->b) - (e->b < f->b);
}

static int crossing_cmp(const void *p, const void *q)
{
  const crossing *c = p, *d = q;
  if (c->row != d->row) return c->row < d->row ? -1 : 1;
  return (c->x > d->x) - (c->x < d->x);
}

static int find_root(int *parent, int i)
{
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

/* Side of p = (u, v) from the edge a -> b in the (y, z) projection: > 0 left, < 0 right,
 * perturbed to p + (e, e^2) when on the line. Computed with the lower vertex index first,
 * so both triangles of an edge get the same number (with opposite signs when they run it
 * opposite ways): a ray meets a shared edge in exactly one of two triangles on opposite
 * sides of it, in both or neither at a fold. */
static int side(const double *V, int a, int b, const double p[2])
{
  const int flip = a > b;
  if (flip) {
    const int t = a;
    a = b;
    b = t;
  }
  const double *A = V + 3 * a + 1, *B = V + 3 * b + 1;
  const double eu = B[0] - A[0], ev = B[1] - A[1];
  const double o = eu * (p[1] - A[1]) - ev * (p[0] - A[0]);
  /* o(p + (e, e^2)) = o - ev e + eu e^2: the first non-zero term's sign */
  const double terms[3] = {o, -ev, eu};
  int s = 0;
  for (int k = 0; k < 3 && s == 0; k++) s = (terms[k] > 0.0) - (terms[k] < 0.0);
  return flip ? -s : s;
}

/* the x where the row through p = (y, z) crosses triangle (a, b, c), or 0 when it does not */
static int row_crossing(const double *V, const int t[3], const double p[2], double *x)
{
  int a = t[0], b = t[1], c = t[2];
  const double *A = V + 3 * a, *B = V + 3 * b, *C = V + 3 * c;
  const double area = (B[1] - A[1]) * (C[2] - A[2]) - (B[2] - A[2]) * (C[1] - A[1]);
  if (area == 0.0) return 0; /* edge-on: no interior to cross */
  if (area < 0.0) {          /* counter-clockwise in (y, z) */
    const int s = b;
    b = c;
    c = s;
  }
  if (side(V, a, b, p) <= 0 || side(V, b, c, p) <= 0 || side(V, c, a, p) <= 0) return 0;
  /* barycentric weights: the sub-areas opposite each vertex */
  double w[3], sum = 0.0;
  const int v[3] = {a, b, c};
  for (int k = 0; k < 3; k++) {
    const double *P = V + 3 * v[(k + 1) % 3], *Q = V + 3 * v[(k + 2) % 3];
    w[k] = (P[1] - p[0]) * (Q[2] - p[1]) - (P[2] - p[1]) * (Q[1] - p[0]);
    sum += w[k];
  }
  *x = (w[0] * V[3 * a] + w[1] * V[3 * b] + w[2] * V[3 * c]) / sum;
  return 1;
}

lsdem_status lsdem_field_inside_surface(const lsdem_field_grid *g, int nv, const double *v,
                                        int nt, const int *tri, unsigned char *inside,
                                        lsdem_error *err)
{
  for (int k = 0; k < 3 * nt; k++)
    if (tri[k] < 0 || tri[k] >= nv)
      return lsdem_fail(err, LSDEM_ERR_ARG, "surface mask: triangle %d has vertex %d of %d",
                        k / 3, tri[k], nv);
  /* boundary edges (one triangle only), their loops (union-find) and centroids */
  edge *e = malloc((size_t)(3 * nt + 1) * sizeof *e);
  int *parent = malloc((size_t)(nv + 1) * sizeof *parent);
  double *V = malloc((size_t)(2 * nv + 1) * 3 * sizeof *V);  /* the vertices, then centroids */
  int *closed = malloc((size_t)(3 * nt + 1) * 2 * 3 * sizeof *closed);
  double *count = calloc((size_t)nv + 1, sizeof *count);
  crossing *cr = NULL;
  size_t ncr = 0, cap = 0, c = 0;
  const size_t rows = (size_t)g->n[1] * (size_t)g->n[2];
  int ntri = nt;
  lsdem_status status = LSDEM_OK;
  if (!e || !parent || !V || !closed || !count) goto nomem;
  for (int k = 0; k < 3 * nt; k++) {
    const int a = tri[k], b = tri[k % 3 == 2 ? k - 2 : k + 1];
    e[k].a = a < b ? a : b;
    e[k].b = a < b ? b : a;
  }
  qsort(e, (size_t)3 * nt, sizeof *e, edge_cmp);
  /* in lattice coordinates (lsdem_field_grid), where the node rows are those of an
   * orthogonal grid along xi0 = x: inside is affine-invariant */
  for (int k = 0; k < nv; k++) lsdem_field_to_lattice(g->skew, v + 3 * k, V + 3 * k);
  memset(V + 3 * nv, 0, (size_t)nv * 3 * sizeof *V);
  for (int i = 0; i < nv; i++) parent[i] = i;
  memcpy(closed, tri, (size_t)nt * 3 * sizeof *closed);
  for (int k = 0; k < 3 * nt;) {
    int m = k + 1;
    while (m < 3 * nt && edge_cmp(e + m, e + k) == 0) m++;
    if (m == k + 1) { /* boundary edge */
      parent[find_root(parent, e[k].a)] = find_root(parent, e[k].b);
      closed[3 * ntri] = e[k].a;
      closed[3 * ntri + 1] = e[k].b;
      closed[3 * ntri + 2] = -1; /* the loop's centroid, below */
      ntri++;
    }
    k = m;
  }
  for (int t = nt; t < ntri; t++)
    for (int c = 0; c < 2; c++) {
      const int r = find_root(parent, closed[3 * t + c]);
      for (int k = 0; k < 3; k++) V[3 * (nv + r) + k] += V[3 * closed[3 * t + c] + k];
      count[r] += 1.0;
    }
  for (int r = 0; r < nv; r++)
    if (count[r] > 0.0)
      for (int k = 0; k < 3; k++) V[3 * (nv + r) + k] /= count[r];
  for (int t = nt; t < ntri; t++) closed[3 * t + 2] = nv + find_root(parent, closed[3 * t]);
  /* the rows (y, z) under each triangle's projection, and where they cross it */
  for (int t = 0; t < ntri; t++) {
    int lo[2], hi[2];
    for (int k = 0; k < 2; k++) {
      double mn = V[3 * closed[3 * t] + 1 + k], mx = mn;
      for (int c = 1; c < 3; c++) {
        const double q = V[3 * closed[3 * t + c] + 1 + k];
        mn = q < mn ? q : mn;
        mx = q > mx ? q : mx;
      }
      /* a row more each side: the exact test decides a row on the box's edge */
      const double a = ceil((mn - g->origin[1 + k]) / g->h[1 + k]) - 1.0;
      const double b = floor((mx - g->origin[1 + k]) / g->h[1 + k]) + 1.0;
      lo[k] = a < 0.0 ? 0 : a > g->n[1 + k] ? g->n[1 + k] : (int)a;
      hi[k] = b >= g->n[1 + k] ? g->n[1 + k] - 1 : b < -1.0 ? -1 : (int)b;
    }
    for (int i2 = lo[1]; i2 <= hi[1]; i2++)
      for (int i1 = lo[0]; i1 <= hi[0]; i1++) {
        const double p[2] = {g->origin[1] + g->h[1] * i1, g->origin[2] + g->h[2] * i2};
        double x;
        if (!row_crossing(V, closed + 3 * t, p, &x)) continue;
        if (ncr == cap) {
          cap = 2 * cap + 64;
          crossing *grown = realloc(cr, cap * sizeof *cr);
          if (!grown) goto nomem;
          cr = grown;
        }
        cr[ncr].row = (size_t)i1 + (size_t)g->n[1] * (size_t)i2;
        cr[ncr++].x = x;
      }
  }
  qsort(cr, ncr, sizeof *cr, crossing_cmp);
  /* parity along each row: inside after an odd number of crossings */
  for (size_t row = 0; row < rows; row++) {
    unsigned char *out = inside + row * (size_t)g->n[0];
    size_t first = c;
    while (c < ncr && cr[c].row == row) c++;
    size_t k = first;
    for (int i0 = 0; i0 < g->n[0]; i0++) {
      const double x = g->origin[0] + g->h[0] * i0;
      while (k < c && cr[k].x < x) k++;
      out[i0] = (unsigned char)((k - first) & 1);
    }
  }
  goto done;
nomem:
  status = lsdem_fail(err, LSDEM_ERR_NOMEM, "surface mask: no memory for %d triangles", nt);
done:
  free(e);
  free(parent);
  free(V);
  free(closed);
  free(count);
  free(cr);
  return status;
}
