/* test_morph.c -- Kawamoto/Tan text inputs (doc/morphology_format.rst): exact morph round
 * trip, a hand-written file in gen_morph.py's number formats, one specific error per kind
 * of broken input, every truncation rejected, positions/rotations readers, and the import
 * of an analytic ellipsoid checked against its closed-form volume, inertia and area. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define TMP "test_morph_tmp.dat"

static const double PI = 3.14159265358979323846;

static void spill(const char *path, const char *text, size_t n)
{
  FILE *f = fopen(path, "wb");
  fwrite(text, 1, n, f);
  fclose(f);
}

static char *slurp(const char *path, size_t *n)
{
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  *n = (size_t)ftell(f);
  fseek(f, 0, SEEK_SET);
  char *b = malloc(*n + 1);
  if (fread(b, 1, *n, f) != *n) *n = 0;
  b[*n] = 0;
  fclose(f);
  return b;
}

/* Read `text` as a morph file: expect status `want` and `needle` in the message. */
static void expect_morph(const char *text, lsdem_status want, const char *needle,
                         const char *what)
{
  spill(TMP, text, strlen(text));
  lsdem_morph m;
  lsdem_error err = {{0}};
  const lsdem_status st = lsdem_morph_read(TMP, &m, &err);
  CHECK(st == want, "%s: status '%s', expected '%s' (%s)", what, lsdem_status_name(st),
        lsdem_status_name(want), err.msg);
  CHECK(!needle || strstr(err.msg, needle), "%s: message '%s' lacks '%s'", what, err.msg, needle);
  CHECK(st == LSDEM_OK || (m.nodes == NULL && m.phi == NULL), "%s: arrays left on failure", what);
  CHECK(st == LSDEM_OK || strstr(err.msg, TMP), "%s: message '%s' does not name the file",
        what, err.msg);
  lsdem_morph_free(&m);
}

/* A small valid file in the number formats of gen_morph.py (%.10g, %.7f, %.6f). */
static const char *SMALL =
    "33.51032164\n"
    "53.61651463 53.61651463 53.61651463\n"
    "1 1.5 2\n"
    "2\n"
    "2.0000000 0.0000000 0.0000000 -0.5000000 1.2500000 0.0000000\n"
    "2.0000000\n"
    "2 2 3\n"
    "-1.000000 0.500000 1.250000 -0.000001 2.000000 3.000000 4.000000 5.000000 6.000000 7.000000 "
    "8.000000 9.000000\n";

static void test_small_file(void)
{
  spill(TMP, SMALL, strlen(SMALL));
  lsdem_morph m;
  lsdem_error err;
  CHECK(lsdem_morph_read(TMP, &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(m.mass == 33.51032164 && m.inertia[2] == 53.61651463, "lines 1-2");
  CHECK(m.cm_grid[0] == 1 && m.cm_grid[1] == 1.5 && m.cm_grid[2] == 2, "line 3");
  CHECK(m.nnodes == 2 && m.nodes[0] == 2.0 && m.nodes[3] == -0.5 && m.nodes[4] == 1.25, "nodes");
  CHECK(m.radius == 2.0 && m.n[0] == 2 && m.n[1] == 2 && m.n[2] == 3, "lines 6-7");
  CHECK(m.phi[0] == -1.0f && m.phi[3] == -0.000001f && m.phi[11] == 9.0f, "line 8");
  lsdem_morph_free(&m);
  CHECK(m.nodes == NULL && m.phi == NULL, "free empties the morph");

  /* CRLF line endings, tabs and a missing final newline are accepted. */
  char crlf[2048];
  size_t k = 0;
  for (const char *p = SMALL; *p; p++) {
    if (*p == '\n') crlf[k++] = '\r';
    crlf[k++] = *p == ' ' ? '\t' : *p;
  }
  crlf[k - 2] = 0;
  expect_morph(crlf, LSDEM_OK, NULL, "CRLF and tabs");
}

/* Replace the k-th line (1-based) of SMALL by `line`. */
static void with_line(int k, const char *line, char *out)
{
  const char *p = SMALL;
  out[0] = 0;
  for (int i = 1; *p; i++) {
    const char *e = strchr(p, '\n');
    if (i == k) {
      strcat(out, line);
      strcat(out, "\n");
    } else {
      strncat(out, p, (size_t)(e - p + 1));
    }
    p = e + 1;
  }
}

static void test_bad_inputs(void)
{
  char t[4096];
  expect_morph("", LSDEM_ERR_FORMAT, "line 1", "empty file");
  with_line(2, "53.6 abc 53.6", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 2: 'abc' is not a number", "non-numeric");
  with_line(2, "53.6 53.6x 53.6", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 2: '53.6x'", "trailing characters");
  with_line(2, "53.6 53.6", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 2: expected 3 value(s)", "short line 2");
  with_line(3, "1 nan 2", t);
  expect_morph(t, LSDEM_ERR_NUMERIC, "line 3", "NaN");
  with_line(1, "1e999", t);
  expect_morph(t, LSDEM_ERR_NUMERIC, "line 1", "double overflow");
  with_line(1, "0", t);
  expect_morph(t, LSDEM_ERR_NUMERIC, "line 1: mass", "zero mass");
  with_line(2, "1 -2 3", t);
  expect_morph(t, LSDEM_ERR_NUMERIC, "line 2: principal moment I2", "negative moment");
  with_line(4, "-2", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 4: node count is -2", "negative node count");
  with_line(4, "2.5", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 4: '2.5' is not an integer", "fractional count");
  with_line(4, "3", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 5: expected 9 value(s)", "node count mismatch");
  with_line(4, "1", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 5: more than the 3 value(s)", "too many nodes");
  with_line(4, "99999999999", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 4", "huge node count");
  with_line(7, "2 -2 3", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 7: grid dims nx ny nz is -2", "negative dim");
  with_line(7, "0 2 3", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 7", "zero dim");
  with_line(7, "600 600 600", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 7: grid 600 x 600 x 600", "over the 512^3 cap");
  with_line(7, "2147483647 2147483647 2", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 7", "int overflow of dims");
  with_line(7, "2 2 2", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 8: more than the 8 value(s)", "too many phi");
  with_line(7, "2 2 4", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 8: expected 16 value(s)", "too few phi");
  with_line(8, "1 2 3 4 5 6 7 8 9 10 11 inf", t);
  expect_morph(t, LSDEM_ERR_NUMERIC, "line 8", "inf in phi");
  with_line(8, "1 2 3 4 5 6 7 8 9 10 11 1e39", t);
  expect_morph(t, LSDEM_ERR_NUMERIC, "line 8", "float overflow in phi");
  with_line(6, "-1", t);
  expect_morph(t, LSDEM_ERR_NUMERIC, "line 6", "negative radius");
  with_line(8, "1 2 3 4 5 6 7 8 9 10 11 0", t); /* 0 is on the surface, not inside */
  expect_morph(t, LSDEM_ERR_NUMERIC, "line 8: no level-set value is negative: the grid has no "
               "solid voxel", "no solid");
  with_line(6, "00000000000000000000000000000000000000000000000000000000000000000001", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "longer than", "over-long token");
  snprintf(t, sizeof t, "%s9\n", SMALL);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 9: unexpected content", "a ninth line");
  snprintf(t, sizeof t, "%s\n\n  \n", SMALL);
  expect_morph(t, LSDEM_OK, NULL, "trailing blank lines");
  with_line(2, "", t);
  expect_morph(t, LSDEM_ERR_FORMAT, "line 2: expected 3 value(s)", "blank line 2");
  char bin[64] = "33.5\n1 2\0003\n"; /* a NUL byte inside a token */
  spill(TMP, bin, 12);
  lsdem_morph m;
  lsdem_error err;
  CHECK(lsdem_morph_read(TMP, &m, &err) == LSDEM_ERR_FORMAT && strstr(err.msg, "line 2"),
        "NUL byte: %s", err.msg);
  CHECK(lsdem_morph_read("no/such/morph.dat", &m, &err) == LSDEM_ERR_IO, "missing file");
}

/* Every cut before the start of the last value leaves values missing. */
static void test_truncation(void)
{
  const size_t n = strlen(SMALL);
  const size_t last = (size_t)(strrchr(SMALL, ' ') - SMALL) + 1;
  int rejected = 0, tried = 0;
  for (size_t cut = 0; cut < last; cut++) {
    spill(TMP, SMALL, cut);
    lsdem_morph m;
    lsdem_error err;
    const lsdem_status st = lsdem_morph_read(TMP, &m, &err);
    tried++;
    rejected += st == LSDEM_ERR_FORMAT;
    if (st != LSDEM_ERR_FORMAT) fprintf(stderr, "cut %zu: %s\n", cut, lsdem_status_name(st));
    lsdem_morph_free(&m);
  }
  CHECK(rejected == tried, "%d of %d truncations rejected", rejected, tried);
  (void)n;
}

/* Values with every bit pattern class (negative zero, denormal, 1/3, large) come back
 * bit for bit through %.17g / %.9g. */
static void test_round_trip(void)
{
  lsdem_morph a = {0};
  a.mass = 1.0 / 3.0;
  a.inertia[0] = 2.0 / 7.0, a.inertia[1] = 1e-300, a.inertia[2] = 6.02214076e23;
  a.cm_grid[0] = 12.5, a.cm_grid[1] = -0.1, a.cm_grid[2] = 1e-17;
  a.nnodes = 5;
  double nodes[15];
  for (int i = 0; i < 15; i++) nodes[i] = sin(1.0 + i) * pow(10.0, i % 5 - 2);
  nodes[3] = -0.0;
  a.nodes = nodes;
  a.radius = 9.999999999999998;
  a.n[0] = 3, a.n[1] = 4, a.n[2] = 5;
  float phi[60];
  uint32_t x = 12345;
  for (int i = 0; i < 60; i++) {
    x = x * 1664525u + 1013904223u;
    phi[i] = (float)((double)x / 4294967296.0 - 0.5) * (float)pow(10.0, i % 7 - 3);
  }
  phi[7] = -0.0f;
  phi[8] = 1.4e-45f; /* the smallest denormal */
  phi[9] = 3.4028235e38f;
  a.phi = phi;
  lsdem_error err;
  CHECK(lsdem_morph_write(TMP, &a, &err) == LSDEM_OK, "write: %s", err.msg);
  lsdem_morph b;
  CHECK(lsdem_morph_read(TMP, &b, &err) == LSDEM_OK, "read back: %s", err.msg);
  if (b.phi) {
    CHECK(memcmp(&a.mass, &b.mass, 8) == 0 && memcmp(a.inertia, b.inertia, 24) == 0 &&
          memcmp(a.cm_grid, b.cm_grid, 24) == 0 && memcmp(&a.radius, &b.radius, 8) == 0,
          "scalars");
    CHECK(b.nnodes == 5 && memcmp(a.nodes, b.nodes, sizeof nodes) == 0, "nodes");
    CHECK(memcmp(a.n, b.n, sizeof a.n) == 0 && memcmp(a.phi, b.phi, sizeof phi) == 0, "phi");
  }
  lsdem_morph_free(&b);
  size_t n = 0;
  char *text = slurp(TMP, &n);
  int lines = 0;
  for (size_t i = 0; i < n; i++) lines += text[i] == '\n';
  CHECK(lines == 8 && text[n - 1] == '\n', "%d lines", lines);
  free(text);
  a.n[2] = 1;
  CHECK(lsdem_morph_write(TMP, &a, &err) == LSDEM_ERR_ARG, "flat grid refused");
}

static void test_positions_rotations(void)
{
  const char *pos = "1 2 3\n\n  4.5 -6 7e2  \n8 9 10";
  spill(TMP, pos, strlen(pos));
  double *v = NULL;
  int n = 0;
  lsdem_error err;
  CHECK(lsdem_read_positions(TMP, &v, &n, &err) == LSDEM_OK && n == 3, "positions: %s", err.msg);
  if (v) CHECK(v[3] == 4.5 && v[4] == -6 && v[5] == 700 && v[8] == 10, "position values");
  free(v);
  const char *bad = "1 2 3\n4 5\n";
  spill(TMP, bad, strlen(bad));
  CHECK(lsdem_read_positions(TMP, &v, &n, &err) == LSDEM_ERR_FORMAT && strstr(err.msg, "line 2"),
        "short row: %s", err.msg);
  CHECK(v == NULL && n == 0, "nothing returned on error");
  bad = "1 2 3\n\n4 5 6 7\n";
  spill(TMP, bad, strlen(bad));
  CHECK(lsdem_read_positions(TMP, &v, &n, &err) == LSDEM_ERR_FORMAT && strstr(err.msg, "line 3"),
        "long row: %s", err.msg);
  bad = "1 2 3\n4 -nan 6\n";
  spill(TMP, bad, strlen(bad));
  CHECK(lsdem_read_positions(TMP, &v, &n, &err) == LSDEM_ERR_NUMERIC && strstr(err.msg, "line 2"),
        "nan: %s", err.msg);
  spill(TMP, "\n \n", 3);
  CHECK(lsdem_read_positions(TMP, &v, &n, &err) == LSDEM_ERR_FORMAT, "no rows");

  const char *rot = "0.000000000 0.000000000 0.000000000 1.000000000\n"
                    "0.5 0.5 0.5 0.5\n";
  spill(TMP, rot, strlen(rot));
  CHECK(lsdem_read_rotations(TMP, &v, &n, &err) == LSDEM_OK && n == 2, "rotations: %s", err.msg);
  if (v) CHECK(v[3] == 1.0 && v[4] == 0.5, "rotation values (stored order)");
  free(v);
  rot = "0 0 0 1\n\n0.5 0.5 0.5 0.6\n";
  spill(TMP, rot, strlen(rot));
  CHECK(lsdem_read_rotations(TMP, &v, &n, &err) == LSDEM_ERR_NUMERIC && strstr(err.msg, "line 3"),
        "non-unit quaternion: %s", err.msg);
  spill(TMP, "1 2 3\n", 6);
  CHECK(lsdem_read_rotations(TMP, &v, &n, &err) == LSDEM_ERR_FORMAT, "positions as rotations");
}

/* ------------------------------------------------------- ellipsoid import ---- */

/* An ellipsoid morph as gen_morph.py writes it: exact SDF on a grid with odd dims and a
 * 3-voxel margin, centroid at the grid centre, Fibonacci nodes projected radially onto the
 * surface, closed-form volume and inertia. Caller frees. */
static void make_ellipsoid_morph(const double e[3], int nnodes, lsdem_morph *m)
{
  memset(m, 0, sizeof *m);
  lsdem_sdf s = {0};
  s.kind = LSDEM_SDF_ELLIPSOID;
  for (int k = 0; k < 3; k++) {
    s.a[k] = e[k];
    m->n[k] = 2 * (int)ceil(e[k]) + 2 * 3 + 1;
    m->cm_grid[k] = (m->n[k] - 1) / 2.0;
  }
  m->phi = malloc(sizeof(float) * (size_t)m->n[0] * m->n[1] * m->n[2]);
  size_t idx = 0;
  for (int k = 0; k < m->n[2]; k++)
    for (int j = 0; j < m->n[1]; j++)
      for (int i = 0; i < m->n[0]; i++) {
        const double p[3] = {i - m->cm_grid[0], j - m->cm_grid[1], k - m->cm_grid[2]};
        double g[3];
        m->phi[idx++] = (float)lsdem_sdf_eval(&s, p, g);
      }
  const double a = e[0], b = e[1], c = e[2];
  m->mass = 4.0 / 3.0 * PI * a * b * c;
  m->inertia[0] = m->mass * (b * b + c * c) / 5.0;
  m->inertia[1] = m->mass * (a * a + c * c) / 5.0;
  m->inertia[2] = m->mass * (a * a + b * b) / 5.0;
  m->nnodes = nnodes;
  m->nodes = malloc(sizeof(double) * 3 * (size_t)nnodes);
  for (int q = 0; q < nnodes; q++) {
    const double z = 1.0 - 2.0 * (q + 0.5) / nnodes, r = sqrt(fmax(0.0, 1.0 - z * z));
    const double t = (q + 0.5) * PI * (3.0 - sqrt(5.0));
    const double d[3] = {r * cos(t), r * sin(t), z};
    const double scale = 1.0 / sqrt(d[0] * d[0] / (a * a) + d[1] * d[1] / (b * b) + d[2] * d[2] / (c * c));
    for (int k = 0; k < 3; k++) m->nodes[3 * q + k] = d[k] * scale;
  }
  m->radius = c; /* deliberately too small: the import recomputes it */
}

static int cmp_node(const void *x, const void *y)
{
  const double *a = x, *b = y;
  for (int k = 0; k < 3; k++)
    if (a[k] != b[k]) return a[k] < b[k] ? -1 : 1;
  return 0;
}

static void test_ellipsoid_import(void)
{
  const double e[3] = {10.5, 8.25, 6.0};
  const int nn = 300;
  lsdem_morph w, m;
  make_ellipsoid_morph(e, nn, &w);
  lsdem_error err;
  CHECK(lsdem_morph_write(TMP, &w, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_morph_read(TMP, &m, &err) == LSDEM_OK, "%s", err.msg);
  double *nodes = malloc(sizeof(double) * 3 * nn), *area = malloc(sizeof(double) * nn);
  double *sph = malloc(sizeof(double) * 4 * nn);
  int *start = malloc(sizeof(int) * (nn + 1));
  lsdem_shape s;
  CHECK(lsdem_morph_to_shape(&m, nodes, area, start, sph, &s, &err) == LSDEM_OK, "%s", err.msg);

  /* Mass properties of the imported grid against the file's closed-form values (1%). */
  lsdem_massprops mp;
  CHECK(lsdem_massprops_grid(&s.sdf.grid, 2, &mp, &err) == LSDEM_OK, "%s", err.msg);
  CHECK_REL(mp.volume, w.mass, 0.01);
  for (int k = 0; k < 3; k++) {
    CHECK_NEAR(mp.centroid[k], 0.0, 0.01); /* origin = -cm_grid puts the centroid at 0 */
    CHECK_REL(mp.inertia[4 * k], w.inertia[k], 0.01);
  }
  printf("ellipsoid import: grid volume %+.3f%%, inertia %+.3f%% %+.3f%% %+.3f%% vs closed "
         "form\n", 100 * (mp.volume / w.mass - 1), 100 * (mp.inertia[0] / w.inertia[0] - 1),
         100 * (mp.inertia[4] / w.inertia[1] - 1), 100 * (mp.inertia[8] / w.inertia[2] - 1));
  CHECK(s.volume == w.mass && s.inertia[0] == w.inertia[0], "shape keeps the file's values");
  CHECK(s.sdf.grid.h == 1.0 && s.sdf.grid.origin[0] == -w.cm_grid[0], "grid frame");

  /* Areas: equal shares of the surface; Thomsen's formula (p = 1.6075, within 1.1%). */
  const double p = 1.6075, a = e[0], b = e[1], c = e[2];
  const double area_ref = 4.0 * PI * pow((pow(a * b, p) + pow(a * c, p) + pow(b * c, p)) / 3.0, 1.0 / p);
  double total = 0.0;
  for (int i = 0; i < nn; i++) total += area[i];
  printf("ellipsoid import: node areas sum %+.3f%% vs Thomsen's surface area\n",
         100 * (total / area_ref - 1));
  CHECK_REL(total, area_ref, 0.03);
  CHECK_NEAR(area[0], area[nn - 1], 1e-12 * area_ref);

  /* Clusters partition the same node set, each node inside its cluster sphere; the radius
   * bounds the solid (max semi-axis), not the file's line 6. */
  CHECK(s.nclusters >= 1 && start[0] == 0 && start[s.nclusters] == nn, "clusters");
  for (int c = 0; c < s.nclusters; c++)
    for (int i = start[c]; i < start[c + 1]; i++) {
      const double *q = &nodes[3 * i], *cs = &sph[4 * c];
      const double d = sqrt(pow(q[0] - cs[0], 2) + pow(q[1] - cs[1], 2) + pow(q[2] - cs[2], 2));
      CHECK(d <= cs[3] * (1 + 1e-12) + 1e-12, "node %d outside cluster %d", i, c);
    }
  double *orig = malloc(sizeof(double) * 3 * nn);
  memcpy(orig, m.nodes, sizeof(double) * 3 * nn);
  qsort(orig, nn, 3 * sizeof(double), cmp_node);
  double *mine = malloc(sizeof(double) * 3 * nn);
  memcpy(mine, nodes, sizeof(double) * 3 * nn);
  qsort(mine, nn, 3 * sizeof(double), cmp_node);
  CHECK(memcmp(orig, mine, sizeof(double) * 3 * nn) == 0, "node set preserved by clustering");
  CHECK(s.radius >= e[0] && s.radius < e[0] + 3.0, "radius %g", s.radius);

  /* Through a library and back: the stored shape equals the imported one. */
  const char *name = "ellipsoid";
  CHECK(lsdem_library_write("test_morph.lslib", &s, &name, 1, &err) == LSDEM_OK, "%s", err.msg);
  lsdem_library *lib = NULL;
  CHECK(lsdem_library_open("test_morph.lslib", &lib, &err) == LSDEM_OK, "%s", err.msg);
  if (lib) {
    const lsdem_shape *t = lsdem_library_shape(lib, 0);
    CHECK(t->nnodes == nn && memcmp(t->nodes, nodes, sizeof(double) * 3 * nn) == 0 &&
          memcmp(t->sdf.grid.phi, m.phi, sizeof(float) * m.n[0] * m.n[1] * m.n[2]) == 0,
          "library copy");
    lsdem_library_close(lib);
  }
  remove("test_morph.lslib");
  free(orig);
  free(mine);
  free(nodes);
  free(area);
  free(sph);
  free(start);
  lsdem_morph_free(&m);
  lsdem_morph_free(&w);
}

int main(void)
{
  test_small_file();
  test_bad_inputs();
  test_truncation();
  test_round_trip();
  test_positions_rotations();
  test_ellipsoid_import();
  remove(TMP);
  return lsdem_test_summary();
}
