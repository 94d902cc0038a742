/* morph.c -- Kawamoto/Tan text inputs: morphology files (morph_<i>.dat, 8 lines, format in
 * doc/morphology_format.rst), positions_*.dat and rotations_*.dat.
 *
 * The readers treat every file as hostile: each value is a whitespace-separated token on
 * the line it belongs to, parsed whole (no trailing characters), checked finite and in
 * range before use; sizes are capped before anything is allocated and arrays grow as
 * values arrive, so a short file claiming a huge grid costs nothing. Every error names
 * the file, the line and what was expected. */
#include "lsdem_prep.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------- token reader ---- */

enum { TOKEN_MAX = 64, READ_BUF = 65536 };

typedef struct {
  FILE *f;
  const char *path;
  unsigned char buf[READ_BUF];
  size_t len, pos;
  int line; /* 1-based line of the next character */
} text_reader;

typedef enum { TOK_VALUE, TOK_EOL, TOK_EOF, TOK_LONG, TOK_IOERR } tok_kind;

typedef struct {
  char s[TOKEN_MAX + 1];
  size_t len;
} token;

static int reader_peek(text_reader *r)
{
  if (r->pos == r->len) {
    r->len = fread(r->buf, 1, sizeof r->buf, r->f);
    r->pos = 0;
    if (r->len == 0) return EOF;
  }
  return r->buf[r->pos];
}

static int is_blank(int c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/* Skip whitespace and empty lines; returns the next character (not consumed) or EOF. */
static int skip_blank_lines(text_reader *r)
{
  int c;
  while ((c = reader_peek(r)) != EOF && (is_blank(c) || c == '\n')) {
    r->pos++;
    if (c == '\n') r->line++;
  }
  return c;
}

/* Next whitespace-separated token of the current line. TOK_EOL consumes the newline
 * (the reader moves to the next line); TOK_EOF is returned at the end of the file. */
static tok_kind next_token(text_reader *r, token *t)
{
  int c;
  while ((c = reader_peek(r)) != EOF && is_blank(c)) r->pos++;
  if (c == EOF) return ferror(r->f) ? TOK_IOERR : TOK_EOF;
  if (c == '\n') {
    r->pos++;
    r->line++;
    return TOK_EOL;
  }
  t->len = 0;
  while ((c = reader_peek(r)) != EOF && c != '\n' && !is_blank(c)) {
    if (t->len == TOKEN_MAX) return TOK_LONG;
    t->s[t->len++] = (char)c;
    r->pos++;
  }
  t->s[t->len] = '\0';
  return TOK_VALUE;
}

/* Printable form of a token for messages (binary bytes become '?'). */
static const char *token_shown(token *t)
{
  for (size_t i = 0; i < t->len; i++)
    if ((unsigned char)t->s[i] < 32 || (unsigned char)t->s[i] > 126) t->s[i] = '?';
  return t->s;
}

/* Why a token could not be read as the next of `want` values on this line. */
static lsdem_status token_error(const text_reader *r, tok_kind k, const char *what, long got,
                                long want, lsdem_error *err)
{
  switch (k) {
  case TOK_EOL:
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %d: expected %ld value(s) (%s), found %ld",
                      r->path, r->line - 1, want, what, got);
  case TOK_EOF:
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %d: file ends after %ld of %ld value(s) "
                      "(%s): truncated", r->path, r->line, got, want, what);
  case TOK_LONG:
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %d: value %ld of %s is longer than %d "
                      "characters", r->path, r->line, got + 1, what, TOKEN_MAX);
  default:
    return lsdem_fail(err, LSDEM_ERR_IO, "%s: line %d: read error: %s", r->path, r->line,
                      strerror(errno));
  }
}

/* Next value token of the current line, or an error naming what was expected. */
static lsdem_status expect_token(text_reader *r, token *t, const char *what, long got, long want,
                                 lsdem_error *err)
{
  const tok_kind k = next_token(r, t);
  return k == TOK_VALUE ? LSDEM_OK : token_error(r, k, what, got, want, err);
}

/* The current line must end here (or the file). */
static lsdem_status expect_line_end(text_reader *r, const char *what, long want, lsdem_error *err)
{
  token t;
  const tok_kind k = next_token(r, &t);
  if (k == TOK_EOL || k == TOK_EOF) return LSDEM_OK;
  if (k == TOK_IOERR) return token_error(r, k, what, 0, want, err);
  return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %d: more than the %ld value(s) expected "
                    "(%s)", r->path, r->line, want, what);
}

/* A real number: as a double, or as a float (single != 0; the value is then exactly a
 * float, and a value beyond the float range is an overflow like inf). */
static lsdem_status parse_real(const text_reader *r, token *t, const char *what, int single,
                               double *v, lsdem_error *err)
{
  char *end;
  *v = single ? (double)strtof(t->s, &end) : strtod(t->s, &end);
  if (end == t->s || (size_t)(end - t->s) != t->len)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %d: '%s' is not a number (%s)", r->path,
                      r->line, token_shown(t), what);
  if (!isfinite(*v))
    return lsdem_fail(err, LSDEM_ERR_NUMERIC, "%s: line %d: %s is '%s', not a finite %snumber",
                      r->path, r->line, what, token_shown(t), single ? "single-precision " : "");
  return LSDEM_OK;
}

/* An integer in [lo, hi]. */
static lsdem_status parse_int(const text_reader *r, token *t, const char *what, long lo, long hi,
                              int *v, lsdem_error *err)
{
  char *end;
  errno = 0;
  const long x = strtol(t->s, &end, 10);
  if (end == t->s || (size_t)(end - t->s) != t->len)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %d: '%s' is not an integer (%s)",
                      r->path, r->line, token_shown(t), what);
  if (errno == ERANGE || x < lo || x > hi)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %d: %s is %s, expected %ld .. %ld",
                      r->path, r->line, what, token_shown(t), lo, hi);
  *v = (int)x;
  return LSDEM_OK;
}

/* A line of exactly `want` doubles. */
static lsdem_status read_double_line(text_reader *r, const char *what, double *v, long want,
                                     lsdem_error *err)
{
  token t;
  for (long i = 0; i < want; i++) {
    lsdem_status st = expect_token(r, &t, what, i, want, err);
    if (st == LSDEM_OK) st = parse_real(r, &t, what, 0, &v[i], err);
    if (st != LSDEM_OK) return st;
  }
  return expect_line_end(r, what, want, err);
}

/* A line of exactly `want` integers in [lo, hi]. */
static lsdem_status read_int_line(text_reader *r, const char *what, int *v, long want, long lo,
                                  long hi, lsdem_error *err)
{
  token t;
  for (long i = 0; i < want; i++) {
    lsdem_status st = expect_token(r, &t, what, i, want, err);
    if (st == LSDEM_OK) st = parse_int(r, &t, what, lo, hi, &v[i], err);
    if (st != LSDEM_OK) return st;
  }
  return expect_line_end(r, what, want, err);
}

/* Growth of an array as values arrive: capacity doubles up to `cap` elements. */
static int grow(void **p, size_t *capacity, size_t need, size_t cap, size_t elem)
{
  if (need <= *capacity) return 1;
  size_t c = *capacity ? *capacity : 4096;
  while (c < need) c *= 2;
  if (c > cap) c = cap;
  void *q = realloc(*p, c * elem);
  if (!q) return 0;
  *p = q;
  *capacity = c;
  return 1;
}

static lsdem_status no_memory(const text_reader *r, lsdem_error *err)
{
  return lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: line %d: out of memory", r->path, r->line);
}

/* ---------------------------------------------------------- morph reader ---- */

/* A line of `want` numbers into a new array of doubles, or of floats when single != 0,
 * grown as values arrive. */
static lsdem_status read_number_array(text_reader *r, const char *what, size_t want, int single,
                                      void **out, lsdem_error *err)
{
  const size_t elem = single ? sizeof(float) : sizeof(double);
  size_t cap = 0;
  token t;
  for (size_t i = 0; i < want; i++) {
    lsdem_status st = expect_token(r, &t, what, (long)i, (long)want, err);
    if (st != LSDEM_OK) return st;
    if (!grow(out, &cap, i + 1, want, elem)) return no_memory(r, err);
    double v;
    st = parse_real(r, &t, what, single, &v, err);
    if (st != LSDEM_OK) return st;
    if (single) ((float *)*out)[i] = (float)v;
    else ((double *)*out)[i] = v;
  }
  return expect_line_end(r, what, (long)want, err);
}

static lsdem_status check_grid_size(const text_reader *r, const int n[3], lsdem_error *err)
{
  const double total = (double)n[0] * (double)n[1] * (double)n[2];
  if (total > (double)LSDEM_MORPH_MAX_SAMPLES)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line 7: grid %d x %d x %d has %.0f samples, "
                      "more than the limit %d (512^3)", r->path, n[0], n[1], n[2], total,
                      LSDEM_MORPH_MAX_SAMPLES);
  return LSDEM_OK;
}

/* Lines 1..8 in order (the layout is in the header comment of lsdem.h and
 * doc/morphology_format.rst). */
static lsdem_status read_morph_lines(text_reader *r, lsdem_morph *m, lsdem_error *err)
{
  lsdem_status st = read_double_line(r, "mass = volume", &m->mass, 1, err);
  if (st == LSDEM_OK) st = read_double_line(r, "principal moments I1 I2 I3", m->inertia, 3, err);
  if (st == LSDEM_OK) st = read_double_line(r, "centroid in grid coordinates", m->cm_grid, 3, err);
  if (st == LSDEM_OK)
    st = read_int_line(r, "node count", &m->nnodes, 1, 0, LSDEM_MORPH_MAX_NODES, err);
  void *nodes = NULL, *phi = NULL; /* owned by m as soon as they exist */
  if (st == LSDEM_OK)
    st = read_number_array(r, "node coordinates x y z, 3 per node of line 4",
                           3u * (size_t)m->nnodes, 0, &nodes, err);
  m->nodes = (double *)nodes;
  if (st == LSDEM_OK) st = read_double_line(r, "bounding radius", &m->radius, 1, err);
  if (st == LSDEM_OK)
    st = read_int_line(r, "grid dims nx ny nz", m->n, 3, 2, LSDEM_MORPH_MAX_SAMPLES, err);
  if (st == LSDEM_OK) st = check_grid_size(r, m->n, err);
  if (st == LSDEM_OK)
    st = read_number_array(r, "level-set values, nx*ny*nz of line 7",
                           (size_t)m->n[0] * (size_t)m->n[1] * (size_t)m->n[2], 1, &phi, err);
  m->phi = (float *)phi;
  if (st != LSDEM_OK) return st;
  if (skip_blank_lines(r) != EOF)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %d: unexpected content after the 8 "
                      "lines of a morphology file", r->path, r->line);
  return LSDEM_OK;
}

/* Physical sanity of the parsed values; first, that the grid holds a solid at all (an
 * all-positive grid would otherwise meet the other checks, or pass them, as a grain). */
static lsdem_status check_morph_values(const char *path, const lsdem_morph *m, lsdem_error *err)
{
  const lsdem_grid g = {{m->n[0], m->n[1], m->n[2]}, 1.0, {0.0, 0.0, 0.0}, m->phi, 0.0, 0.0};
  if (!lsdem_grid_has_solid(&g))
    return lsdem_fail(err, LSDEM_ERR_NUMERIC, "%s: line 8: no level-set value is negative: "
                      "the grid has no solid voxel, so the file describes no grain (a "
                      "level set is negative inside the grain)", path);
  if (!(m->mass > 0.0))
    return lsdem_fail(err, LSDEM_ERR_NUMERIC, "%s: line 1: mass (volume) %g must be > 0", path,
                      m->mass);
  for (int k = 0; k < 3; k++)
    if (!(m->inertia[k] > 0.0))
      return lsdem_fail(err, LSDEM_ERR_NUMERIC, "%s: line 2: principal moment I%d = %g must be "
                        "> 0", path, k + 1, m->inertia[k]);
  if (!(m->radius >= 0.0))
    return lsdem_fail(err, LSDEM_ERR_NUMERIC, "%s: line 6: bounding radius %g must be >= 0",
                      path, m->radius);
  return LSDEM_OK;
}

static lsdem_status open_reader(const char *path, text_reader **r, lsdem_error *err)
{
  *r = NULL;
  if (!path) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL file name");
  FILE *f = fopen(path, "rb");
  if (!f) return lsdem_fail(err, LSDEM_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
  *r = (text_reader *)calloc(1, sizeof **r);
  if (!*r) {
    fclose(f);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: out of memory", path);
  }
  (*r)->f = f;
  (*r)->path = path;
  (*r)->line = 1;
  return LSDEM_OK;
}

static void close_reader(text_reader *r)
{
  if (!r) return;
  fclose(r->f);
  free(r);
}

lsdem_status lsdem_morph_read(const char *path, lsdem_morph *m, lsdem_error *err)
{
  if (!m) return lsdem_fail(err, LSDEM_ERR_ARG, "lsdem_morph_read: NULL morph");
  memset(m, 0, sizeof *m);
  text_reader *r;
  lsdem_status st = open_reader(path, &r, err);
  if (st != LSDEM_OK) return st;
  st = read_morph_lines(r, m, err);
  close_reader(r);
  if (st == LSDEM_OK) st = check_morph_values(path, m, err);
  if (st != LSDEM_OK) lsdem_morph_free(m);
  return st;
}

void lsdem_morph_free(lsdem_morph *m)
{
  if (!m) return;
  free(m->nodes);
  free(m->phi);
  memset(m, 0, sizeof *m);
}

/* ---------------------------------------------------------- morph writer ---- */

/* Doubles with %.17g and floats with %.9g: enough digits to read back bit for bit. */
static void write_doubles(FILE *f, const double *v, size_t n)
{
  for (size_t i = 0; i < n; i++) fprintf(f, i ? " %.17g" : "%.17g", v[i]);
  fputc('\n', f);
}

lsdem_status lsdem_morph_write(const char *path, const lsdem_morph *m, lsdem_error *err)
{
  if (!path || !m || m->nnodes < 0 || m->nnodes > LSDEM_MORPH_MAX_NODES ||
      (m->nnodes > 0 && !m->nodes) || !m->phi || m->n[0] < 2 || m->n[1] < 2 || m->n[2] < 2 ||
      (double)m->n[0] * m->n[1] * m->n[2] > (double)LSDEM_MORPH_MAX_SAMPLES)
    return lsdem_fail(err, LSDEM_ERR_ARG, "lsdem_morph_write %s: bad morphology (node count, "
                      "grid dims or NULL arrays)", path ? path : "(NULL)");
  FILE *f = fopen(path, "w");
  if (!f) return lsdem_fail(err, LSDEM_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
  write_doubles(f, &m->mass, 1);
  write_doubles(f, m->inertia, 3);
  write_doubles(f, m->cm_grid, 3);
  fprintf(f, "%d\n", m->nnodes);
  write_doubles(f, m->nodes, 3u * (size_t)m->nnodes);
  write_doubles(f, &m->radius, 1);
  fprintf(f, "%d %d %d\n", m->n[0], m->n[1], m->n[2]);
  const size_t ns = (size_t)m->n[0] * (size_t)m->n[1] * (size_t)m->n[2];
  for (size_t i = 0; i < ns; i++) fprintf(f, i ? " %.9g" : "%.9g", (double)m->phi[i]);
  fputc('\n', f);
  const int bad = ferror(f);
  if (fclose(f) != 0 || bad)
    return lsdem_fail(err, LSDEM_ERR_IO, "%s: write error: %s", path, strerror(errno));
  return LSDEM_OK;
}

/* --------------------------------------------------------- morph -> shape ---- */

lsdem_status lsdem_morph_to_shape(const lsdem_morph *m, double *nodes, double *area,
                                  int *cluster_start, double *cluster_sphere, lsdem_shape *s,
                                  lsdem_error *err)
{
  if (!m || !s || !m->phi || (m->nnodes > 0 && (!nodes || !area || !cluster_start ||
                                                !cluster_sphere || !m->nodes)))
    return lsdem_fail(err, LSDEM_ERR_ARG, "lsdem_morph_to_shape: NULL argument");
  memset(s, 0, sizeof *s);
  s->sdf.kind = LSDEM_SDF_GRID;
  s->sdf.grid.h = 1.0;
  for (int k = 0; k < 3; k++) {
    s->sdf.grid.n[k] = m->n[k];
    s->sdf.grid.origin[k] = -m->cm_grid[k];
    s->inertia[k] = m->inertia[k];
  }
  s->sdf.grid.phi = m->phi;
  lsdem_status st = lsdem_grid_check(&s->sdf.grid, err);
  if (st != LSDEM_OK) return st;
  s->volume = m->mass;
  s->nnodes = m->nnodes;
  double rmax = 0.0;
  if (m->nnodes > 0) {
    /* Each node stands for an equal share of the surface area of the solid. */
    const double total = lsdem_surface_area_grid(&s->sdf.grid);
    for (int i = 0; i < m->nnodes; i++) {
      const double *p = &m->nodes[3 * i];
      for (int k = 0; k < 3; k++) nodes[3 * i + k] = p[k];
      area[i] = total / m->nnodes;
      const double r = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      if (r > rmax) rmax = r;
    }
    s->nclusters = lsdem_nodes_cluster(m->nnodes, nodes, area, LSDEM_CLUSTER_TARGET,
                                       cluster_start, cluster_sphere);
    s->nodes = nodes;
    s->node_area = area;
    s->cluster_start = cluster_start;
    s->cluster_sphere = cluster_sphere;
  }
  /* Line 6 is not trusted (Kawamoto's code recomputes it too): bound the nodes and the
   * solid as the grid describes it. */
  const double rsolid = lsdem_sdf_bound_radius(&s->sdf);
  s->radius = rmax > rsolid ? rmax : rsolid;
  return LSDEM_OK;
}

/* ------------------------------------------------ positions and rotations ---- */

/* A check of one parsed row; `line` is where it was read. */
typedef lsdem_status (*row_check)(const char *path, int line, const double *row,
                                  lsdem_error *err);

/* Rows of `ncol` finite numbers, one per non-blank line, each passed to `check`. */
static lsdem_status read_rows(const char *path, int ncol, const char *what, row_check check,
                              double **out, int *n, lsdem_error *err)
{
  if (!out || !n) return lsdem_fail(err, LSDEM_ERR_ARG, "%s: NULL output", path ? path : "");
  *out = NULL;
  *n = 0;
  text_reader *r;
  lsdem_status st = open_reader(path, &r, err);
  if (st != LSDEM_OK) return st;
  void *buf = NULL;
  size_t cap = 0, rows = 0;
  for (;;) {
    if (skip_blank_lines(r) == EOF) {
      if (ferror(r->f)) st = token_error(r, TOK_IOERR, what, 0, ncol, err);
      break;
    }
    const int line = r->line;
    if (rows >= (size_t)LSDEM_MORPH_MAX_ROWS) {
      st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %d: more than %d rows", path, line,
                      LSDEM_MORPH_MAX_ROWS);
      break;
    }
    if (!grow(&buf, &cap, (rows + 1) * (size_t)ncol, (size_t)LSDEM_MORPH_MAX_ROWS * ncol,
              sizeof(double))) {
      st = no_memory(r, err);
      break;
    }
    double *row = (double *)buf + rows * (size_t)ncol;
    st = read_double_line(r, what, row, ncol, err);
    if (st == LSDEM_OK && check) st = check(path, line, row, err);
    if (st != LSDEM_OK) break;
    rows++;
  }
  if (st == LSDEM_OK && rows == 0)
    st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: no data lines (expected %s)", path, what);
  close_reader(r);
  if (st != LSDEM_OK) {
    free(buf);
    return st;
  }
  *out = (double *)buf;
  *n = (int)rows;
  return LSDEM_OK;
}

lsdem_status lsdem_read_positions(const char *path, double **out, int *n, lsdem_error *err)
{
  return read_rows(path, 3, "x y z", NULL, out, n, err);
}

/* Rotation rows must be unit quaternions (to 1e-3): a row of another length means the
 * wrong file or a broken one. */
static lsdem_status check_unit_quaternion(const char *path, int line, const double *q,
                                          lsdem_error *err)
{
  const double norm = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (fabs(norm - 1.0) > 1e-3)
    return lsdem_fail(err, LSDEM_ERR_NUMERIC, "%s: line %d: quaternion (%g %g %g %g) has norm "
                      "%g, expected a unit quaternion", path, line, q[0], q[1], q[2], q[3], norm);
  return LSDEM_OK;
}

/* Values are returned as stored (Tan's order, w last). */
lsdem_status lsdem_read_rotations(const char *path, double **out, int *n, lsdem_error *err)
{
  return read_rows(path, 4, "q0 q1 q2 q3", check_unit_quaternion, out, n, err);
}
