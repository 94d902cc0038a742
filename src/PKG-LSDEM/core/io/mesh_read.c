/* mesh_read.c -- triangle meshes from STL (ASCII or binary) and OBJ files, welded on exact
 * vertex equality (lsdem_mesh_read, lsdem_io.h). The checks a mesh must pass and its
 * distances are prep's (mesh_check.c, mesh_sdf.c, mesh_distance.c). */
#include "lsdem_io.h"
#include "text_lexer.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MESH_MAX_FILE_BYTES (1L << 30)

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
