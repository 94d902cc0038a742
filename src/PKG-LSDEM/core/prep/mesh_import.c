/* mesh_import.c -- triangle meshes (STL, OBJ) to signed-distance grids, with the checks a mesh
 * must pass first: closed and consistently oriented (every edge shared by exactly two
 * triangles traversing it in opposite directions) and free of self-intersections.
 *
 * Signed distance: the distance to the closest triangle signed by the pseudonormal of its
 * closest feature (mesh_distance.h, shared with the narrow bands of walls). The sign is
 * exact for a closed, consistently oriented mesh. */
#include "lsdem_prep.h"
#include "mesh_distance.h"
#include "../io/text_lexer.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MESH_MAX_FILE_BYTES (1L << 30)

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

/* ----------------------------------------------------------------- reading ---- */

/* A growing triangle soup: 9 coordinates per triangle. */
typedef struct {
  double *xyz;
  size_t n, cap;
} soup;

static int soup_push(soup *s, const double v[9])
{
  if (s->n == s->cap) {
    const size_t cap = s->cap ? 2 * s->cap : 256;
    double *p = realloc(s->xyz, cap * 9 * sizeof(double));
    if (!p) return 0;
    s->xyz = p, s->cap = cap;
  }
  memcpy(s->xyz + 9 * s->n++, v, 9 * sizeof(double));
  return 1;
}

/* A corner of the soup with its position in the soup, sorted to find equal vertices. */
typedef struct {
  double p[3];
  size_t at;
} corner;

static int cmp_corner(const void *a, const void *b)
{
  const corner *x = a, *y = b;
  for (int k = 0; k < 3; k++)
    if (x->p[k] != y->p[k]) return x->p[k] < y->p[k] ? -1 : 1;
  return 0;
}

/* Shared vertices from a soup: corners with identical coordinates become one vertex. */
static lsdem_status weld(const soup *s, lsdem_mesh *m, const char *path, lsdem_error *err)
{
  const size_t nc = 3 * s->n;
  corner *c = malloc(nc * sizeof *c + 1);
  m->verts = malloc(3 * nc * sizeof(double) + 1);
  m->tris = malloc(nc * sizeof(int) + 1);
  if (!c || !m->verts || !m->tris) {
    free(c);
    lsdem_mesh_free(m);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: out of memory for %zu triangles", path, s->n);
  }
  for (size_t i = 0; i < nc; i++) {
    memcpy(c[i].p, s->xyz + 3 * i, sizeof c[i].p);
    c[i].at = i;
  }
  qsort(c, nc, sizeof *c, cmp_corner);
  int nv = -1;
  for (size_t i = 0; i < nc; i++) {
    if (i == 0 || cmp_corner(&c[i], &c[i - 1]) != 0) {
      nv++;
      memcpy(m->verts + 3 * nv, c[i].p, 3 * sizeof(double));
    }
    m->tris[c[i].at] = nv;
  }
  m->nverts = nv + 1;
  m->ntris = (int)s->n;
  free(c);
  return LSDEM_OK;
}

static float load_f32le(const unsigned char *p)
{
  const uint32_t u = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
                     (uint32_t)p[3] << 24;
  float f;
  memcpy(&f, &u, sizeof f);
  return f;
}

/* Binary STL: 80-byte header, uint32 count, then 50 bytes per triangle (normal, three
 * vertices as little-endian float32, 2 attribute bytes). The caller checked the size. */
static lsdem_status read_stl_binary(const unsigned char *b, size_t count, soup *s,
                                    const char *path, lsdem_error *err)
{
  for (size_t t = 0; t < count; t++) {
    double v[9];
    for (int k = 0; k < 9; k++) {
      v[k] = load_f32le(b + 84 + 50 * t + 12 + 4 * k);
      if (!isfinite(v[k]))
        return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: triangle %zu has a non-finite coordinate",
                          path, t);
    }
    if (!soup_push(s, v)) return lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: out of memory", path);
  }
  return LSDEM_OK;
}

/* ASCII STL: "vertex x y z" three times inside each "outer loop" ... "endloop". */
static lsdem_status read_stl_ascii(const char *text, soup *s, const char *path, lsdem_error *err)
{
  text_lexer lx = {text, 1};
  const char *tok;
  size_t len;
  double v[9];
  int nv = -1; /* vertices in the current loop, -1 outside a loop */
  while (lexer_next(&lx, &tok, &len)) {
    if (token_is(tok, len, "outer")) nv = 0;
    else if (token_is(tok, len, "vertex")) {
      if (nv < 0 || nv >= 3)
        return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: vertex %s", path, lx.line,
                          nv < 0 ? "outside an 'outer loop'" : "beyond the third of a facet");
      for (int k = 0; k < 3; k++)
        if (!lexer_next(&lx, &tok, &len) || !token_number(tok, len, &v[3 * nv + k]))
          return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: vertex needs three finite "
                            "numbers", path, lx.line);
      nv++;
    } else if (token_is(tok, len, "endloop")) {
      if (nv != 3)
        return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: a facet with %d vertices "
                          "(STL facets are triangles)", path, lx.line, nv < 0 ? 0 : nv);
      if (s->n >= LSDEM_MESH_MAX_TRIS)
        return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: more than %d triangles", path,
                          LSDEM_MESH_MAX_TRIS);
      if (!soup_push(s, v)) return lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: out of memory", path);
      nv = -1;
    }
  }
  if (nv >= 0)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: file ends inside a facet", path,
                      lx.line);
  return LSDEM_OK;
}

/* A vertex reference of an OBJ face ("i", "i/t", "i//n", "i/t/n"; negative = relative to
 * the vertices read so far) as a 0-based index. */
static int obj_index(const char *tok, size_t len, long nverts, long *idx)
{
  char buf[32];
  size_t n = 0;
  while (n < len && tok[n] != '/') n++;
  if (n == 0 || n >= sizeof buf) return 0;
  memcpy(buf, tok, n);
  buf[n] = '\0';
  char *end;
  const long i = strtol(buf, &end, 10);
  if (*end != '\0' || i == 0) return 0;
  *idx = i > 0 ? i - 1 : nverts + i;
  return *idx >= 0;
}

/* Append triangle (a, b, c) to a growing index array. */
static int push_tri(int **t, long *nt, long *cap, long a, long b, long c)
{
  if (*nt == *cap) {
    const long nc = *cap ? 2 * *cap : 256;
    int *q = realloc(*t, 3 * (size_t)nc * sizeof(int));
    if (!q) return 0;
    *t = q, *cap = nc;
  }
  int *o = *t + 3 * (*nt)++;
  o[0] = (int)a, o[1] = (int)b, o[2] = (int)c;
  return 1;
}

/* One "f" line (after the keyword): fan triangles (v0, v[i-1], v[i]). */
static lsdem_status obj_face(text_lexer *lx, long nv, int **t, long *nt, long *cap,
                             const char *path, long line, lsdem_error *err)
{
  const char *tok;
  size_t len;
  long first = -1, prev = -1, idx, corners = 0;
  while (lexer_next(lx, &tok, &len)) {
    if (!obj_index(tok, len, nv, &idx) || idx >= nv)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: face vertex '%.*s' is not one of "
                        "the %ld vertices defined so far", path, line, (int)(len < 40 ? len : 40),
                        tok, nv);
    if (corners >= 2) {
      if (*nt >= LSDEM_MESH_MAX_TRIS)
        return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: more than %d triangles", path,
                          LSDEM_MESH_MAX_TRIS);
      if (!push_tri(t, nt, cap, first, prev, idx))
        return lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: out of memory", path);
    }
    if (corners == 0) first = idx;
    prev = idx;
    corners++;
  }
  if (corners < 3)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: a face needs at least 3 vertices, "
                      "has %ld", path, line, corners);
  return LSDEM_OK;
}

/* Wavefront OBJ: "v x y z" and "f a b c ..." (fan-triangulated); other lines ignored.
 * The text is split into lines in place. */
static lsdem_status read_obj(char *text, lsdem_mesh *m, const char *path, lsdem_error *err)
{
  double *v = NULL;
  int *t = NULL;
  long nv = 0, nt = 0, cap_v = 0, cap_t = 0, line = 0;
  lsdem_status st = LSDEM_OK;
  for (char *p = text; *p && st == LSDEM_OK;) {
    char *eol = strchr(p, '\n');
    if (eol) *eol = '\0';
    line++;
    text_lexer lx = {p, 0};
    const char *tok = NULL;
    size_t len = 0;
    const int any = lexer_next(&lx, &tok, &len);
    if (any && token_is(tok, len, "v")) {
      if (nv >= 3L * LSDEM_MESH_MAX_TRIS)
        st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: more than %ld vertices", path,
                        3L * LSDEM_MESH_MAX_TRIS);
      if (st == LSDEM_OK && nv == cap_v) {
        cap_v = cap_v ? 2 * cap_v : 256;
        double *q = realloc(v, 3 * (size_t)cap_v * sizeof(double));
        if (!q) st = lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: out of memory", path);
        else v = q;
      }
      for (int k = 0; st == LSDEM_OK && k < 3; k++)
        if (!lexer_next(&lx, &tok, &len) || !token_number(tok, len, &v[3 * nv + k]))
          st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: 'v' needs three finite numbers",
                          path, line);
      nv++;
    } else if (any && token_is(tok, len, "f")) {
      st = obj_face(&lx, nv, &t, &nt, &cap_t, path, line, err);
    }
    p = eol ? eol + 1 : p + strlen(p);
  }
  if (st == LSDEM_OK && nt == 0) st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: no faces", path);
  if (st != LSDEM_OK) {
    free(v);
    free(t);
    return st;
  }
  m->verts = v, m->nverts = (int)nv, m->tris = t, m->ntris = (int)nt;
  return LSDEM_OK;
}

/* Binary STL when the size is 84 + 50 * count and the file does not read as ASCII STL
 * (text that starts with "solid" and has a "facet" in its first line or two). */
static int looks_binary_stl(const char *b, size_t size)
{
  if (size < 84) return 0;
  const unsigned char *u = (const unsigned char *)b;
  const uint64_t count = (uint64_t)u[80] | (uint64_t)u[81] << 8 | (uint64_t)u[82] << 16 |
                         (uint64_t)u[83] << 24;
  if (84 + 50 * count != size) return 0;
  if (strncmp(b, "solid", 5) != 0) return 1;
  const size_t head = size < 512 ? size : 512;
  for (size_t i = 0; i + 5 <= head; i++)
    if (memcmp(b + i, "facet", 5) == 0 || memcmp(b + i, "endso", 5) == 0) return 0;
  return 1;
}

static lsdem_status read_stl(char *data, size_t size, lsdem_mesh *m, const char *path,
                             lsdem_error *err)
{
  soup s = {0};
  lsdem_status st;
  if (looks_binary_stl(data, size)) {
    const size_t count = (size - 84) / 50;
    if (count > LSDEM_MESH_MAX_TRIS)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: %zu triangles: above the limit %d", path,
                        count, LSDEM_MESH_MAX_TRIS);
    st = read_stl_binary((const unsigned char *)data, count, &s, path, err);
  } else if (size >= 5 && strncmp(data, "solid", 5) == 0) {
    if (memchr(data, '\0', size))
      st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: binary bytes in an ASCII STL, or a binary STL "
                      "whose size does not match its triangle count (84 + 50 n bytes)", path);
    else st = read_stl_ascii(data, &s, path, err);
  } else
    st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: not an STL file: no 'solid' header and the size "
                    "%zu is not 84 + 50 n (binary STL)", path, size);
  if (st == LSDEM_OK && s.n == 0) st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: no triangles", path);
  if (st == LSDEM_OK) st = weld(&s, m, path, err);
  free(s.xyz);
  return st;
}

lsdem_status lsdem_mesh_read(const char *path, lsdem_mesh *m, lsdem_error *err)
{
  if (!path || !m) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  memset(m, 0, sizeof *m);
  char *data = NULL;
  size_t size = 0;
  lsdem_status st = lsdem_read_file(path, MESH_MAX_FILE_BYTES, (unsigned char **)&data, &size, err);
  if (st != LSDEM_OK) return st;
  const int obj = lsdem_path_has_extension(path, ".obj") ||
                  (!lsdem_path_has_extension(path, ".stl") && !looks_binary_stl(data, size) &&
                   strncmp(data, "solid", 5) != 0);
  if (obj && memchr(data, '\0', size))
    st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: binary bytes in an OBJ file", path);
  else st = obj ? read_obj(data, m, path, err) : read_stl(data, size, m, path, err);
  free(data);
  if (st != LSDEM_OK) lsdem_mesh_free(m);
  return st;
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

/* Does segment pq cross triangle abc (Moller-Trumbore, closed segment and triangle)? */
static int segment_hits_triangle(const double *p, const double *q, const double *a,
                                 const double *b, const double *c)
{
  double d[3], e1[3], e2[3], pv[3], tv[3], qv[3];
  lsdem_sub3(q, p, d), lsdem_sub3(b, a, e1), lsdem_sub3(c, a, e2);
  lsdem_cross3(d, e2, pv);
  const double det = lsdem_dot3(e1, pv);
  const double scale = sqrt(lsdem_dot3(e1, e1) * lsdem_dot3(e2, e2) * lsdem_dot3(d, d));
  if (fabs(det) <= 1e-12 * scale) return 0; /* parallel: coplanar contacts are not tested */
  const double inv = 1.0 / det;
  lsdem_sub3(p, a, tv);
  const double u = lsdem_dot3(tv, pv) * inv;
  if (u < 0.0 || u > 1.0) return 0;
  lsdem_cross3(tv, e1, qv);
  const double v = lsdem_dot3(d, qv) * inv;
  if (v < 0.0 || u + v > 1.0) return 0;
  const double t = lsdem_dot3(e2, qv) * inv;
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

/* ------------------------------------------------------------ signed distance ---- */

/* The sampler's state: per sample the smallest |distance| found, its triangle (-1: none
 * yet) and the signed value. */
typedef struct {
  const lsdem_mesh *m;
  const mesh_pseudonormals *pn;
  const lsdem_grid *g;
  double *best;
  int *tri;
  float *phi;
} sdf_work;

static size_t sample_index(const lsdem_grid *g, int i, int j, int k)
{
  return ((size_t)k * g->n[1] + j) * g->n[0] + i;
}

static void try_triangle(sdf_work *w, size_t q, int i, int j, int k, int t)
{
  const lsdem_grid *g = w->g;
  const double p[3] = {g->origin[0] + g->h * i, g->origin[1] + g->h * j, g->origin[2] + g->h * k};
  const double s = mesh_signed_distance_to(w->m, w->pn, p, t);
  if (fabs(s) < w->best[q]) w->best[q] = fabs(s), w->tri[q] = t, w->phi[q] = (float)s;
}

/* Exact distances in a band: each triangle visits the samples within `band` of its
 * bounding box, so a sample closer than `band` to the mesh meets its closest triangle. */
static void rasterize(sdf_work *w, double band)
{
  const lsdem_grid *g = w->g;
  for (int t = 0; t < w->m->ntris; t++) {
    int lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
      double bmin = HUGE_VAL, bmax = -HUGE_VAL;
      for (int c = 0; c < 3; c++) bmin = fmin(bmin, mesh_vert(w->m, t, c)[a]), bmax = fmax(bmax, mesh_vert(w->m, t, c)[a]);
      lo[a] = (int)fmax(ceil((bmin - band - g->origin[a]) / g->h), 0.0);
      hi[a] = (int)fmin(floor((bmax + band - g->origin[a]) / g->h), g->n[a] - 1.0);
    }
    for (int k = lo[2]; k <= hi[2]; k++)
      for (int j = lo[1]; j <= hi[1]; j++)
        for (int i = lo[0]; i <= hi[0]; i++) try_triangle(w, sample_index(g, i, j, k), i, j, k, t);
  }
}

/* Closest-triangle propagation (Bridson's sweeps, as in his makelevelset3): each sample
 * tries the closest triangles of its 7 neighbours behind it in sweep order (di, dj, dk). */
static void sweep(sdf_work *w, int di, int dj, int dk)
{
  const lsdem_grid *g = w->g;
  for (int kk = 0; kk < g->n[2]; kk++)
    for (int jj = 0; jj < g->n[1]; jj++)
      for (int ii = 0; ii < g->n[0]; ii++) {
        const int i = di > 0 ? ii : g->n[0] - 1 - ii, j = dj > 0 ? jj : g->n[1] - 1 - jj;
        const int k = dk > 0 ? kk : g->n[2] - 1 - kk;
        const size_t q = sample_index(g, i, j, k);
        for (int c = 1; c < 8; c++) {
          const int ni = i - (c & 1 ? di : 0), nj = j - (c & 2 ? dj : 0), nk = k - (c & 4 ? dk : 0);
          if (ni < 0 || nj < 0 || nk < 0 || ni >= g->n[0] || nj >= g->n[1] || nk >= g->n[2])
            continue;
          const int t = w->tri[sample_index(g, ni, nj, nk)];
          if (t >= 0 && t != w->tri[q]) try_triangle(w, q, i, j, k, t);
        }
      }
}

/* Signs away from the band by flood fill: the band (every sample within `band` >= h of
 * the mesh, signed exactly) separates inside from outside, so each far sample takes the
 * sign of the band samples its 6-connected region touches. */
static lsdem_status fill_signs(sdf_work *w, double band, lsdem_error *err)
{
  const lsdem_grid *g = w->g;
  const size_t total = (size_t)g->n[0] * g->n[1] * g->n[2];
  size_t *queue = malloc(total * sizeof(size_t));
  signed char *sign = malloc(total);
  if (!queue || !sign) {
    free(queue), free(sign);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate the sign fill");
  }
  size_t head = 0, tail = 0;
  for (size_t q = 0; q < total; q++) {
    sign[q] = w->best[q] <= band ? (w->phi[q] < 0.0f ? -1 : 1) : 0;
    if (sign[q]) queue[tail++] = q;
  }
  const size_t stride[3] = {1, (size_t)g->n[0], (size_t)g->n[0] * g->n[1]};
  while (head < tail) {
    const size_t q = queue[head++];
    const int c[3] = {(int)(q % stride[1]), (int)(q / stride[1] % g->n[1]), (int)(q / stride[2])};
    for (int a = 0; a < 3; a++)
      for (int dir = -1; dir <= 1; dir += 2) {
        if (c[a] + dir < 0 || c[a] + dir >= g->n[a]) continue;
        const size_t r = dir < 0 ? q - stride[a] : q + stride[a];
        if (sign[r]) continue;
        sign[r] = sign[q];
        queue[tail++] = r;
      }
  }
  for (size_t q = 0; q < total; q++)
    if (w->best[q] > band) w->phi[q] = (float)(sign[q] < 0 ? -w->best[q] : w->best[q]);
  free(queue), free(sign);
  return LSDEM_OK;
}

lsdem_status lsdem_mesh_sdf_grid(const lsdem_mesh *m, double h, int margin, lsdem_grid *g,
                                 lsdem_error *err)
{
  if (!m || !g || m->ntris < 1 || m->nverts < 3)
    return lsdem_fail(err, LSDEM_ERR_ARG, "NULL or empty mesh");
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (int v = 0; v < m->nverts; v++)
    for (int a = 0; a < 3; a++)
      lo[a] = fmin(lo[a], m->verts[3 * v + a]), hi[a] = fmax(hi[a], m->verts[3 * v + a]);
  float *phi;
  lsdem_status st = lsdem_grid_alloc(lo, hi, h, margin, g, &phi, err);
  if (st != LSDEM_OK) return st;
  const size_t total = (size_t)g->n[0] * g->n[1] * g->n[2];
  mesh_pseudonormals pn = {0};
  sdf_work w = {m, &pn, g, malloc(total * sizeof(double)), malloc(total * sizeof(int)), phi};
  if (!w.best || !w.tri) st = lsdem_fail(err, LSDEM_ERR_NOMEM, "out of memory");
  if (st == LSDEM_OK) st = mesh_pseudonormals_build(m, &pn, NULL, err);
  if (st == LSDEM_OK) {
    const double band = 2.0 * h;
    for (size_t q = 0; q < total; q++) w.best[q] = HUGE_VAL, w.tri[q] = -1;
    rasterize(&w, band);
    for (int pass = 0; pass < 2; pass++)
      for (int d = 0; d < 8; d++) sweep(&w, d & 1 ? -1 : 1, d & 2 ? -1 : 1, d & 4 ? -1 : 1);
    st = fill_signs(&w, band, err);
  }
  mesh_pseudonormals_free(&pn);
  free(w.best), free(w.tri);
  if (st != LSDEM_OK) lsdem_grid_free(g);
  return st;
}
