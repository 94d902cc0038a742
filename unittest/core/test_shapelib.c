/* test_shapelib.c -- the shape-library file (doc/shape_library.rst): exact round trip of
 * grid and analytic shapes, header fields at their documented offsets, an independent
 * FNV-1a checksum of the header/TOC, rejection of every truncation, of bad magic and
 * version, of hostile TOC entries, detection of a corrupt section by verify, and refusal of
 * shapes a grain cannot use (no solid, centroid outside the grid, bad node areas or radius)
 * by the writer and by verify. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define LIB "test_shapelib.lslib"
#define BAD "test_shapelib_bad.lslib"

/* FNV-1a 64 written from its definition (offset basis, prime), independent of the core. */
static uint64_t fnv1a(const unsigned char *p, size_t n, uint64_t h)
{
  for (size_t i = 0; i < n; i++) {
    h ^= p[i];
    h *= 1099511628211ULL;
  }
  return h;
}
static const uint64_t FNV0 = 14695981039346656037ULL;

static uint32_t rd32(const unsigned char *p) { return p[0] | p[1] << 8 | p[2] << 16 | (uint32_t)p[3] << 24; }
static uint64_t rd64(const unsigned char *p) { return rd32(p) | (uint64_t)rd32(p + 4) << 32; }
static void wr64(unsigned char *p, uint64_t v)
{
  for (int i = 0; i < 8; i++) p[i] = (unsigned char)(v >> (8 * i));
}

/* The whole file, or NULL; the core's reader (no size limit needed for test files). */
static unsigned char *slurp(const char *path, size_t *n)
{
  unsigned char *b = NULL;
  *n = 0;
  return lsdem_read_file(path, SIZE_MAX, &b, n, NULL) == LSDEM_OK ? b : NULL;
}

static void spill(const char *path, const unsigned char *b, size_t n)
{
  FILE *f = fopen(path, "wb");
  fwrite(b, 1, n, f);
  fclose(f);
}

/* Re-seal the header/TOC checksum after editing a TOC field, as a hostile writer would. */
static void reseal(unsigned char *b)
{
  const size_t toc = 64 + 360 * (size_t)rd32(b + 20);
  uint64_t h = fnv1a(b, 56, FNV0);
  h = fnv1a(b + 64, toc - 64, h);
  wr64(b + 56, h);
}

/* Open bytes b (n long) as a library; expect failure `want` with `needle` in the message. */
static void expect_open_fails(const unsigned char *b, size_t n, lsdem_status want,
                              const char *needle, const char *what)
{
  spill(BAD, b, n);
  lsdem_library *lib = NULL;
  lsdem_error err = {{0}};
  const lsdem_status st = lsdem_library_open(BAD, &lib, &err);
  CHECK(st == want, "%s: status %s, expected %s (%s)", what, lsdem_status_name(st),
        lsdem_status_name(want), err.msg);
  CHECK(lib == NULL, "%s: library returned on failure", what);
  CHECK(!needle || strstr(err.msg, needle), "%s: message '%s' lacks '%s'", what, err.msg,
        needle);
  if (lib) lsdem_library_close(lib);
}

/* ------------------------------------------------------------ test shapes ---- */

typedef struct {
  float phi[5 * 6 * 7];
  double nodes[3 * 10], area[10], sphere[4 * 3];
  int start[4];
} grid_store;

static void make_grid_shape(grid_store *g, lsdem_shape *s)
{
  memset(s, 0, sizeof *s);
  s->sdf.kind = LSDEM_SDF_GRID;
  s->sdf.grid.n[0] = 5, s->sdf.grid.n[1] = 6, s->sdf.grid.n[2] = 7; /* odd float count */
  s->sdf.grid.h = 0.37;
  s->sdf.grid.origin[0] = -0.74, s->sdf.grid.origin[1] = -0.925, s->sdf.grid.origin[2] = -1.11;
  for (int i = 0; i < 5 * 6 * 7; i++) g->phi[i] = (float)(0.1 * i - 7.3) / 3.0f;
  s->sdf.grid.phi = g->phi;
  for (int i = 0; i < 30; i++) g->nodes[i] = 1.0 / (i + 3) - 0.2;
  for (int i = 0; i < 10; i++) g->area[i] = 0.01 * (i + 1) / 3.0;
  for (int i = 0; i < 12; i++) g->sphere[i] = 0.5 + i / 7.0;
  g->start[0] = 0, g->start[1] = 4, g->start[2] = 7, g->start[3] = 10;
  s->nnodes = 10;
  s->nodes = g->nodes;
  s->node_area = g->area;
  s->nclusters = 3;
  s->cluster_start = g->start;
  s->cluster_sphere = g->sphere;
  s->radius = 1.7320508075688772;
  s->volume = 0.4188790204786391;
  s->inertia[0] = 0.1 / 3, s->inertia[1] = 0.2 / 3, s->inertia[2] = 0.3 / 7;
}

static void make_sphere(lsdem_shape *s, double r)
{
  static double node[3] = {0.0, 0.0, 1.0}, area[1] = {12.566370614359172};
  static int start[2] = {0, 1};
  static double sphere[4] = {0.0, 0.0, 1.0, 0.0};
  memset(s, 0, sizeof *s);
  s->sdf.kind = LSDEM_SDF_SPHERE;
  s->sdf.a[0] = r;
  s->nnodes = 1;
  s->nodes = node;
  s->node_area = area;
  s->nclusters = 1;
  s->cluster_start = start;
  s->cluster_sphere = sphere;
  s->radius = r;
  s->volume = 4.0 / 3.0 * 3.141592653589793 * r * r * r;
  for (int k = 0; k < 3; k++) s->inertia[k] = 0.4 * s->volume * r * r;
}

static int same_bits(const void *a, const void *b, size_t n)
{
  if (n == 0) return 1;
  if (!a || !b) return 0;
  return memcmp(a, b, n) == 0;
}

/* Every field of a read-back shape equals the written one, bit for bit. */
static void compare_shapes(const lsdem_shape *a, const lsdem_shape *b, int i)
{
  CHECK(a->sdf.kind == b->sdf.kind && a->sdf.inverted == b->sdf.inverted, "shape %d kind", i);
  CHECK(same_bits(a->sdf.a, b->sdf.a, sizeof a->sdf.a), "shape %d params", i);
  CHECK(same_bits(a->sdf.grid.n, b->sdf.grid.n, sizeof a->sdf.grid.n), "shape %d dims", i);
  const int grid = a->sdf.kind == LSDEM_SDF_GRID;
  if (grid) {
    CHECK(same_bits(&a->sdf.grid.h, &b->sdf.grid.h, 8), "shape %d spacing", i);
    CHECK(same_bits(a->sdf.grid.origin, b->sdf.grid.origin, 24), "shape %d origin", i);
    const size_t ns = (size_t)a->sdf.grid.n[0] * a->sdf.grid.n[1] * a->sdf.grid.n[2];
    CHECK(same_bits(a->sdf.grid.phi, b->sdf.grid.phi, 4 * ns), "shape %d phi", i);
    CHECK((uintptr_t)b->sdf.grid.phi % 8 == 0, "shape %d phi misaligned", i);
  } else {
    CHECK(b->sdf.grid.phi == NULL, "shape %d: analytic shape has a grid", i);
  }
  CHECK(a->nnodes == b->nnodes && a->nclusters == b->nclusters, "shape %d counts", i);
  CHECK(same_bits(a->nodes, b->nodes, 24 * (size_t)a->nnodes), "shape %d nodes", i);
  CHECK(same_bits(a->node_area, b->node_area, 8 * (size_t)a->nnodes), "shape %d areas", i);
  if (a->nclusters)
    CHECK(same_bits(a->cluster_start, b->cluster_start, 4 * (size_t)(a->nclusters + 1)),
          "shape %d cluster starts", i);
  else
    CHECK(b->cluster_start && b->cluster_start[0] == 0, "shape %d: empty cluster table", i);
  CHECK(same_bits(a->cluster_sphere, b->cluster_sphere, 32 * (size_t)a->nclusters),
        "shape %d cluster spheres", i);
  CHECK(same_bits(&a->radius, &b->radius, 8) && same_bits(&a->volume, &b->volume, 8),
        "shape %d radius/volume", i);
  CHECK(same_bits(a->inertia, b->inertia, 24), "shape %d inertia", i);
  const void *p[4] = {b->nodes, b->node_area, b->cluster_sphere, b->cluster_start};
  for (int k = 0; k < 4; k++) CHECK((uintptr_t)p[k] % 8 == 0, "shape %d array %d misaligned", i, k);
}

/* ---------------------------------------------------------------- tests ---- */

static grid_store store_a, store_b;
static lsdem_shape shapes[4];
static const char *names[4] = {"grain_a", "", "ellipsoid analytic", "grain_b"};

static void build_shapes(void)
{
  make_grid_shape(&store_a, &shapes[0]);
  make_sphere(&shapes[1], 2.5);
  memset(&shapes[2], 0, sizeof shapes[2]); /* analytic, no nodes */
  shapes[2].sdf.kind = LSDEM_SDF_ELLIPSOID;
  shapes[2].sdf.a[0] = 1.0, shapes[2].sdf.a[1] = 2.0, shapes[2].sdf.a[2] = 3.0;
  shapes[2].radius = 3.0;
  shapes[2].volume = 25.132741228718345;
  shapes[2].inertia[0] = 65.34512719466769;
  shapes[2].inertia[1] = 50.26548245743669;
  shapes[2].inertia[2] = 25.132741228718345;
  make_grid_shape(&store_b, &shapes[3]);
  store_b.phi[17] = -0.0f; /* the sign bit must survive */
  shapes[3].sdf.grid.n[2] = 3;
  shapes[3].sdf.grid.origin[2] = -0.37; /* the centroid stays inside the shorter grid */
  shapes[3].sdf.inverted = 1;
}

static void test_round_trip(void)
{
  lsdem_error err = {{0}};
  lsdem_status st = lsdem_library_write(LIB, shapes, names, 4, &err);
  CHECK(st == LSDEM_OK, "write: %s", err.msg);
  lsdem_library *lib = NULL;
  st = lsdem_library_open(LIB, &lib, &err);
  CHECK(st == LSDEM_OK && lib, "open: %s", err.msg);
  if (!lib) return;
  CHECK(lsdem_library_count(lib) == 4, "count %d", lsdem_library_count(lib));
  for (int i = 0; i < 4; i++) {
    compare_shapes(&shapes[i], lsdem_library_shape(lib, i), i);
    CHECK(strcmp(lsdem_library_name(lib, i), names[i]) == 0, "name %d '%s'", i,
          lsdem_library_name(lib, i));
  }
  CHECK(lsdem_library_shape(lib, 4) == NULL && lsdem_library_shape(lib, -1) == NULL,
        "out-of-range index");
  CHECK(lsdem_library_verify(lib, -1, &err) == LSDEM_OK, "verify: %s", err.msg);
  lsdem_library_close(lib);

  /* names == NULL gives empty names; an empty library is valid. */
  st = lsdem_library_write(LIB, shapes, NULL, 2, &err);
  CHECK(st == LSDEM_OK && lsdem_library_open(LIB, &lib, &err) == LSDEM_OK, "%s", err.msg);
  if (lib) {
    CHECK(strcmp(lsdem_library_name(lib, 1), "") == 0, "NULL names");
    lsdem_library_close(lib);
  }
  st = lsdem_library_write(LIB, NULL, NULL, 0, &err);
  CHECK(st == LSDEM_OK && lsdem_library_open(LIB, &lib, &err) == LSDEM_OK, "%s", err.msg);
  if (lib) {
    CHECK(lsdem_library_count(lib) == 0, "empty library");
    lsdem_library_close(lib);
  }
}

/* Header fields sit where doc/shape_library.rst puts them, and the stored header/TOC
 * checksum equals FNV-1a 64 over header bytes 0..55 followed by the TOC. */
static void test_documented_layout(void)
{
  lsdem_error err;
  lsdem_library_write(LIB, shapes, names, 4, &err);
  size_t n = 0;
  unsigned char *b = slurp(LIB, &n);
  CHECK(b && n > 64 + 4 * 360, "library file missing");
  if (!b || n <= 64 + 4 * 360) return;
  CHECK(memcmp(b, "LSDEMLIB", 8) == 0, "magic");
  CHECK(rd32(b + 8) == 1 && rd32(b + 12) == 64 && rd32(b + 16) == 360, "version/sizes");
  CHECK(rd32(b + 20) == 4 && rd64(b + 24) == 64 && rd64(b + 32) == n, "count/toc/size");
  CHECK(fnv1a((const unsigned char *)"a", 1, FNV0) == 0xaf63dc4c8601ec8cULL, "FNV vector");
  uint64_t h = fnv1a(b, 56, FNV0);
  h = fnv1a(b + 64, 4 * 360, h);
  CHECK(h == rd64(b + 56), "header checksum %llx vs %llx", (unsigned long long)h,
        (unsigned long long)rd64(b + 56));
  /* Shape 0: kind, dims, nnodes; its section checksum; its phi at the stated offset. */
  const unsigned char *e = b + 64;
  CHECK(rd32(e + 0) == LSDEM_SDF_GRID && rd32(e + 32) == 5 && rd32(e + 44) == 10, "entry 0");
  const uint64_t so = rd64(e + 128), sl = rd64(e + 136);
  CHECK(so == 64 + 4 * 360 && so + sl <= n, "section 0 extent");
  CHECK(fnv1a(b + so, sl, FNV0) == rd64(e + 144), "section 0 checksum");
  const uint64_t po = rd64(e + 152 + 16 * 4), pl = rd64(e + 152 + 16 * 4 + 8);
  CHECK(pl == 4 * 5 * 6 * 7 && po % 8 == 0 && memcmp(b + po, store_a.phi, pl) == 0, "phi 0");
  CHECK(strcmp((const char *)e + 232, "grain_a") == 0, "name 0");
  free(b);
}

static void test_truncation(void)
{
  size_t n = 0;
  unsigned char *b = slurp(LIB, &n);
  CHECK(b && n > 64 + 4 * 360, "library file missing");
  if (!b || n <= 64 + 4 * 360) return;
  int rejected = 0, tried = 0;
  for (size_t cut = 0; cut < n; cut += (cut < 128 ? 1 : 5)) {
    spill(BAD, b, cut);
    lsdem_library *lib = NULL;
    lsdem_error err;
    const lsdem_status st = lsdem_library_open(BAD, &lib, &err);
    tried++;
    rejected += st == LSDEM_ERR_FORMAT && lib == NULL;
    if (lib) lsdem_library_close(lib);
  }
  CHECK(rejected == tried, "%d of %d truncations rejected with a format error", rejected, tried);
  expect_open_fails(b, n - 1, LSDEM_ERR_FORMAT, "truncated", "one byte short");
  free(b);
}

static void test_header_errors(void)
{
  size_t n = 0;
  unsigned char *b = slurp(LIB, &n);
  CHECK(b && n > 64 + 4 * 360, "library file missing");
  if (!b || n <= 64 + 4 * 360) return;
  unsigned char *c = malloc(n);
  memcpy(c, b, n);
  c[3] = 'X';
  expect_open_fails(c, n, LSDEM_ERR_FORMAT, "magic", "bad magic");
  memcpy(c, b, n);
  c[8] = 2;
  expect_open_fails(c, n, LSDEM_ERR_FORMAT, "version 2", "bad version");
  memcpy(c, b, n);
  c[64 + 100] ^= 0x10; /* a TOC byte without resealing */
  expect_open_fails(c, n, LSDEM_ERR_FORMAT, "checksum", "TOC corruption");
  memcpy(c, b, n);
  c[20] = 200; /* a TOC of 200 entries cannot fit: rejected before the checksum */
  expect_open_fails(c, n, LSDEM_ERR_FORMAT, "count", "count too large");
  free(c);
  free(b);

  lsdem_library *lib = NULL;
  lsdem_error err;
  CHECK(lsdem_library_open("no/such/file.lslib", &lib, &err) == LSDEM_ERR_IO, "missing file");
}

/* TOC entries that a resealed (checksum-consistent) hostile file could carry. */
static void test_hostile_toc(void)
{
  size_t n = 0;
  unsigned char *b = slurp(LIB, &n);
  CHECK(b && n > 64 + 4 * 360, "library file missing");
  if (!b || n <= 64 + 4 * 360) return;
  unsigned char *c = malloc(n);
  unsigned char *e1 = c + 64 + 360, *e3 = c + 64 + 3 * 360;
  struct {
    size_t field;
    uint64_t value;
    const char *needle;
  } cases[] = {
    {64 + 3 * 360 + 152 + 64, 3, "shape 3: field phi"},                 /* misaligned */
    {64 + 3 * 360 + 152 + 64, UINT64_MAX - 7, "shape 3: field phi"},    /* overflow */
    {64 + 3 * 360 + 152 + 72, 8, "shape 3: field phi"},                 /* wrong length */
    {64 + 3 * 360 + 152 + 32, 0, "shape 3: field nodes"},               /* before section */
    {64 + 3 * 360 + 136, UINT64_MAX, "shape 3: field section"},         /* huge section */
    {64 + 3 * 360 + 128, 64, "shape 3: field section"},                 /* over the TOC */
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    memcpy(c, b, n);
    wr64(c + cases[k].field, cases[k].value);
    reseal(c);
    expect_open_fails(c, n, LSDEM_ERR_FORMAT, cases[k].needle, cases[k].needle);
  }
  /* Two arrays of shape 3 on top of each other. */
  memcpy(c, b, n);
  memcpy(e3 + 152 + 32, e3 + 152 + 48, 8); /* nodes offset := area offset */
  reseal(c);
  expect_open_fails(c, n, LSDEM_ERR_FORMAT, "overlap", "overlapping arrays");
  /* Shape 3's section moved onto shape 0's (sections must follow each other). */
  memcpy(c, b, n);
  memcpy(c + 64 + 3 * 360 + 128, c + 64 + 128, 8);
  reseal(c);
  expect_open_fails(c, n, LSDEM_ERR_FORMAT, "shape 3: field section", "overlapping sections");
  /* Negative node count, kind out of range, a name without NUL, unordered clusters. */
  memcpy(c, b, n);
  e1[44] = 0xff, e1[45] = 0xff, e1[46] = 0xff, e1[47] = 0xff;
  reseal(c);
  expect_open_fails(c, n, LSDEM_ERR_FORMAT, "shape 1: bad nnodes", "negative nnodes");
  memcpy(c, b, n);
  e1[0] = 77;
  reseal(c);
  expect_open_fails(c, n, LSDEM_ERR_FORMAT, "shape 1: bad kind", "bad kind");
  memcpy(c, b, n);
  memset(e1 + 232, 'x', 128);
  reseal(c);
  expect_open_fails(c, n, LSDEM_ERR_FORMAT, "shape 1: field name", "name without NUL");
  memcpy(c, b, n);
  const uint64_t cs = rd64(c + 64 + 152); /* shape 0 cluster_start[1] := 9 > [2] = 7 */
  c[cs + 4] = 9;
  expect_open_fails(c, n, LSDEM_ERR_FORMAT, "shape 0: field cluster_start", "cluster order");
  free(c);
  free(b);
}

static void test_corrupt_section(void)
{
  size_t n = 0;
  unsigned char *b = slurp(LIB, &n);
  CHECK(b && n > 64 + 4 * 360, "library file missing");
  if (!b || n <= 64 + 4 * 360) return;
  const uint64_t po = rd64(b + 64 + 3 * 360 + 152 + 64); /* shape 3's phi */
  b[po + 13] ^= 0x01;
  spill(BAD, b, n);
  lsdem_library *lib = NULL;
  lsdem_error err;
  CHECK(lsdem_library_open(BAD, &lib, &err) == LSDEM_OK, "lazy open: %s", err.msg);
  if (lib) {
    CHECK(lsdem_library_verify(lib, 0, &err) == LSDEM_OK, "shape 0 intact: %s", err.msg);
    const lsdem_status st = lsdem_library_verify(lib, -1, &err);
    CHECK(st == LSDEM_ERR_FORMAT && strstr(err.msg, "shape 3 ('grain_b')"), "verify: %s",
          err.msg);
    CHECK(lsdem_library_verify(lib, 3, &err) == LSDEM_ERR_FORMAT, "verify 3");
    CHECK(lsdem_library_verify(lib, 4, &err) == LSDEM_ERR_ARG, "verify bad index");
    lsdem_library_close(lib);
  }
  free(b);
}

static void test_writer_rejects(void)
{
  lsdem_error err;
  char longname[200];
  memset(longname, 'n', sizeof longname - 1);
  longname[sizeof longname - 1] = 0;
  const char *nm[1] = {longname};
  CHECK(lsdem_library_write(BAD, shapes, nm, 1, &err) == LSDEM_ERR_ARG, "long name");
  lsdem_shape s = shapes[0];
  int bad_start[4] = {0, 7, 4, 10};
  s.cluster_start = bad_start;
  CHECK(lsdem_library_write(BAD, &s, NULL, 1, &err) == LSDEM_ERR_ARG, "cluster order");
  s = shapes[0];
  s.volume = NAN;
  CHECK(lsdem_library_write(BAD, &s, NULL, 1, &err) == LSDEM_ERR_ARG, "NaN volume");
  s = shapes[0];
  s.volume = 0.0;
  CHECK(lsdem_library_write(BAD, &s, NULL, 1, &err) == LSDEM_ERR_ARG &&
            strstr(err.msg, "volume (finite, > 0)"), "zero volume: %s", err.msg);
  s = shapes[0];
  s.inertia[2] = 0.0;
  CHECK(lsdem_library_write(BAD, &s, NULL, 1, &err) == LSDEM_ERR_ARG &&
            strstr(err.msg, "inertia"), "zero moment: %s", err.msg);
  s = shapes[0];
  s.sdf.grid.n[1] = 1;
  CHECK(lsdem_library_write(BAD, &s, NULL, 1, &err) == LSDEM_ERR_ARG && strstr(err.msg, "dims"),
        "flat grid: %s", err.msg);
  s = shapes[1];
  s.sdf.a[0] = 0.0;
  CHECK(lsdem_library_write(BAD, &s, NULL, 1, &err) == LSDEM_ERR_ARG, "sphere of radius 0");
  s = shapes[2];
  s.sdf.a[2] = -1.0;
  CHECK(lsdem_library_write(BAD, &s, NULL, 1, &err) == LSDEM_ERR_ARG, "negative semi-axis");
  CHECK(lsdem_library_write("no/such/dir/x.lslib", shapes, NULL, 1, &err) == LSDEM_ERR_IO,
        "unwritable path");
  CHECK(lsdem_library_write(".", shapes, NULL, 1, &err) == LSDEM_ERR_IO &&
            strstr(err.msg, "not a regular file"), "a folder as the output: %s", err.msg);
}

/* Content a grain cannot use, refused by the writer with the shape's index and name:
 * a grid without a negative value, a centroid (origin) outside the grid box, a node area
 * of 0, a node beyond the bounding radius. */
static void test_writer_rejects_content(void)
{
  static const struct {
    const char *what, *needle;
  } cases[] = {{"no solid", "shape 0 ('grain_a'): no level-set value is negative"},
               {"centroid above the grid", "shape 0 ('grain_a'): its centroid (the origin of "
                                           "its principal frame) is at grid coordinates (2, "
                                           "2.5, -1)"},
               {"zero node area", "shape 0 ('grain_a'): node 4 has area 0"},
               {"node beyond the radius", "shape 0 ('grain_a'): node 0 lies 0.5 from the "
                                          "centroid, beyond the bounding radius 0.4"}};
  for (int c = 0; c < 4; c++) {
    grid_store g;
    lsdem_shape s;
    make_grid_shape(&g, &s);
    if (c == 0)
      for (int i = 0; i < 5 * 6 * 7; i++) g.phi[i] = 0.25f;
    if (c == 1) s.sdf.grid.origin[2] = 0.37; /* grid z from 0.37 to 2.59 */
    if (c == 2) g.area[4] = 0.0;
    if (c == 3) {
      g.nodes[0] = 0.3, g.nodes[1] = 0.0, g.nodes[2] = -0.4; /* |node 0| = 0.5 */
      s.radius = 0.4;
    }
    lsdem_error err = {{0}};
    const lsdem_status st = lsdem_library_write(BAD, &s, names, 1, &err);
    CHECK(st == LSDEM_ERR_NUMERIC && strstr(err.msg, cases[c].needle), "%s: %s (%s)",
          cases[c].what, lsdem_status_name(st), err.msg);
  }
}

/* The same checks in verify, for a file whose TOC says so (resealed): shape 1's bounding
 * radius 2.5 lowered to 0.5, below its node at distance 1. */
static void test_verify_content(void)
{
  size_t n = 0;
  unsigned char *b = slurp(LIB, &n);
  CHECK(b && n > 64 + 4 * 360, "library file missing");
  if (!b || n <= 64 + 4 * 360) return;
  double r = 0.5;
  memcpy(b + 64 + 360 + 88, &r, 8);
  reseal(b);
  spill(BAD, b, n);
  lsdem_library *lib = NULL;
  lsdem_error err = {{0}};
  CHECK(lsdem_library_open(BAD, &lib, &err) == LSDEM_OK, "open: %s", err.msg);
  if (lib) {
    CHECK(lsdem_library_verify(lib, 0, &err) == LSDEM_OK, "shape 0 intact: %s", err.msg);
    const lsdem_status st = lsdem_library_verify(lib, -1, &err);
    CHECK(st == LSDEM_ERR_NUMERIC && strstr(err.msg, "shape 1 (''): node 0 lies 1 from the "
                                            "centroid, beyond the bounding radius 0.5"),
          "verify: %s", err.msg);
    lsdem_library_close(lib);
  }
  free(b);
}

int main(void)
{
  build_shapes();
  test_round_trip();
  test_documented_layout();
  test_truncation();
  test_header_errors();
  test_hostile_toc();
  test_corrupt_section();
  test_writer_rejects();
  test_writer_rejects_content();
  test_verify_content();
  remove(LIB);
  remove(BAD);
  return lsdem_test_summary();
}
