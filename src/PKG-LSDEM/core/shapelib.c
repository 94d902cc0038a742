/* shapelib.c -- the shape-library file: a read-only, memory-mapped binary file of grain
 * templates (format byte by byte in doc/shape_library.rst).
 *
 * Layout: a 64-byte header, a table of contents (one fixed-size entry per shape), then
 * one section per shape holding its arrays. Everything is little-endian, every array is
 * 8-byte aligned, so the arrays are used in place: the lsdem_shape pointers point into
 * the mapping and all ranks on a node share one physical copy through the page cache.
 *
 * Opening checks the header, the header/TOC checksum and every TOC entry against the
 * file size (offsets, lengths, alignment, overlaps, counts) and each shape's cluster
 * table (small, at the start of its section). It does not read level-set grids, so only
 * shapes that are used get paged in. Per-shape section checksums are checked on demand
 * by lsdem_library_verify. */
#define _POSIX_C_SOURCE 200809L
#include "lsdem.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

/* --------------------------------------------------------------- constants ---- */

static const char LIB_MAGIC[8] = {'L', 'S', 'D', 'E', 'M', 'L', 'I', 'B'};
enum {
  LIB_VERSION = 1,
  LIB_HEADER_SIZE = 64,
  LIB_ENTRY_SIZE = 360,
  LIB_NAME_SIZE = LSDEM_LIBRARY_NAME_MAX, /* including the terminating NUL */
  LIB_NARRAYS = 5
};

/* Header field offsets. */
enum { H_MAGIC = 0, H_VERSION = 8, H_HSIZE = 12, H_ESIZE = 16, H_COUNT = 20, H_TOC = 24,
       H_FSIZE = 32, H_SUM = 56 };

/* TOC entry field offsets. */
enum { E_KIND = 0, E_INVERTED = 4, E_A = 8, E_N = 32, E_NNODES = 44, E_H = 48, E_ORIGIN = 56,
       E_NCLUSTERS = 80, E_RADIUS = 88, E_VOLUME = 96, E_INERTIA = 104, E_SEC_OFF = 128,
       E_SEC_LEN = 136, E_SEC_SUM = 144, E_ARRAYS = 152, E_NAME = 232 };

/* The arrays of a shape section, in the order the writer lays them out: the small
 * cluster tables first, the level-set grid last, so checking clusters at open time
 * leaves the grid pages untouched. */
enum { A_CSTART = 0, A_CSPHERE, A_NODES, A_AREA, A_PHI };
static const char *const ARRAY_NAME[LIB_NARRAYS] = {"cluster_start", "cluster_sphere", "nodes",
                                                    "node_area", "phi"};

_Static_assert(sizeof(int) == 4 && sizeof(double) == 8 && sizeof(float) == 4,
               "the library format stores int32, float32 and float64 arrays in place");

struct lsdem_library {
  void *map;
  size_t size;
  int count;
  lsdem_shape *shapes;
  const char **names;
  uint64_t *sec_off, *sec_len, *sec_sum;
};

/* ------------------------------------------------------ bytes and checksums ---- */

/* FNV-1a, 64-bit: h <- (h xor byte) * prime, starting from the offset basis. */
#define FNV_BASIS 0xcbf29ce484222325ULL
#define FNV_PRIME 0x100000001b3ULL

static uint64_t fnv1a_update(uint64_t h, const void *data, size_t len)
{
  const unsigned char *p = (const unsigned char *)data;
  for (size_t i = 0; i < len; i++) h = (h ^ p[i]) * FNV_PRIME;
  return h;
}

static int host_is_little_endian(void)
{
  const uint16_t one = 1;
  unsigned char b;
  memcpy(&b, &one, 1);
  return b == 1;
}

/* Field access in a byte buffer (the host is little-endian, checked before use). */
static uint32_t get_u32(const unsigned char *p) { uint32_t v; memcpy(&v, p, 4); return v; }
static int32_t get_i32(const unsigned char *p) { int32_t v; memcpy(&v, p, 4); return v; }
static uint64_t get_u64(const unsigned char *p) { uint64_t v; memcpy(&v, p, 8); return v; }
static double get_f64(const unsigned char *p) { double v; memcpy(&v, p, 8); return v; }
static void put_u32(unsigned char *p, uint32_t v) { memcpy(p, &v, 4); }
static void put_i32(unsigned char *p, int32_t v) { memcpy(p, &v, 4); }
static void put_u64(unsigned char *p, uint64_t v) { memcpy(p, &v, 8); }
static void put_f64(unsigned char *p, double v) { memcpy(p, &v, 8); }

static uint64_t pad8(uint64_t n) { return (n + 7u) & ~(uint64_t)7u; }

/* -------------------------------------------------------- shape invariants ---- */

/* Number of level-set samples of a grid shape, 0 for analytic kinds or bad dims. */
static uint64_t grid_samples(const lsdem_shape *s)
{
  if (s->sdf.kind != LSDEM_SDF_GRID) return 0;
  uint64_t total = 1;
  for (int k = 0; k < 3; k++) {
    if (s->sdf.grid.n[k] < 2) return 0;
    total *= (uint64_t)s->sdf.grid.n[k];
    if (total > LSDEM_LIBRARY_MAX_SAMPLES) return 0;
  }
  return total;
}

/* Byte length of each array of a shape, from its counts. */
static void array_lengths(const lsdem_shape *s, uint64_t len[LIB_NARRAYS])
{
  len[A_CSTART] = 4u * ((uint64_t)s->nclusters + 1u);
  len[A_CSPHERE] = 32u * (uint64_t)s->nclusters;
  len[A_NODES] = 24u * (uint64_t)s->nnodes;
  len[A_AREA] = 8u * (uint64_t)s->nnodes;
  len[A_PHI] = 4u * grid_samples(s);
}

static const void *array_data(const lsdem_shape *s, int a)
{
  static const int no_clusters[1] = {0};
  switch (a) {
  case A_CSTART: return s->cluster_start ? (const void *)s->cluster_start : no_clusters;
  case A_CSPHERE: return s->cluster_sphere;
  case A_NODES: return s->nodes;
  case A_AREA: return s->node_area;
  default: return s->sdf.grid.phi;
  }
}

static int all_finite(const double *v, int n)
{
  for (int i = 0; i < n; i++)
    if (!isfinite(v[i])) return 0;
  return 1;
}

/* Parameters a[0..n) an analytic kind uses (sphere R; cylinder R, half-length; box
 * half-extents; ellipsoid semi-axes). */
static int analytic_param_count(lsdem_sdf_kind kind)
{
  switch (kind) {
  case LSDEM_SDF_SPHERE: return 1;
  case LSDEM_SDF_CYLINDER: return 2;
  case LSDEM_SDF_BOX:
  case LSDEM_SDF_ELLIPSOID: return 3;
  default: return 0;
  }
}

/* Scalar fields shared by the writer's and the reader's checks. Returns the name of the
 * first bad field, or NULL. */
static const char *bad_scalar_field(const lsdem_shape *s)
{
  /* Planes are not grains; superellipsoids need exponents the format does not hold
   * (store them as grids). */
  if (s->sdf.kind < LSDEM_SDF_GRID || s->sdf.kind > LSDEM_SDF_ELLIPSOID ||
      s->sdf.kind == LSDEM_SDF_PLANE)
    return "kind (grid, sphere, cylinder, box or ellipsoid; a superellipsoid as a grid)";
  if (s->sdf.inverted != 0 && s->sdf.inverted != 1) return "inverted (0 or 1)";
  if (!all_finite(s->sdf.a, 3)) return "analytic parameters (not finite)";
  for (int k = 0; k < analytic_param_count(s->sdf.kind); k++)
      if (!(s->sdf.a[k] > 0.0)) return "analytic parameters (must be > 0: a bounded solid)";
  if (s->sdf.kind == LSDEM_SDF_GRID) {
    if (grid_samples(s) == 0) return "grid dims (each >= 2, product <= 2^31-1)";
    if (!(s->sdf.grid.h > 0.0) || !isfinite(s->sdf.grid.h)) return "grid spacing (> 0)";
    if (!all_finite(s->sdf.grid.origin, 3)) return "grid origin (not finite)";
  } else if (s->sdf.grid.n[0] || s->sdf.grid.n[1] || s->sdf.grid.n[2]) {
    return "grid dims (must be 0 for an analytic shape)";
  }
  if (s->nnodes < 0 || s->nnodes > LSDEM_LIBRARY_MAX_NODES) return "nnodes (0 .. 2^26)";
  if (s->nclusters < 0 || s->nclusters > s->nnodes || (s->nnodes > 0) != (s->nclusters > 0))
    return "nclusters (1..nnodes, or 0 without nodes)";
  if (!(s->radius >= 0.0) || !isfinite(s->radius)) return "radius (finite, >= 0)";
  /* a grain's mass and moments are the density times these: zero gives a NaN step */
  if (!(s->volume > 0.0) || !isfinite(s->volume)) return "volume (finite, > 0)";
  for (int k = 0; k < 3; k++)
    if (!(s->inertia[k] > 0.0) || !isfinite(s->inertia[k]))
      return "inertia (principal moments finite, > 0)";
  return NULL;
}

/* Cluster c owns nodes [start[c], start[c+1]): start[0] = 0, strictly increasing,
 * start[nclusters] = nnodes. Returns the first bad index or -1. */
static int bad_cluster_start(const int *start, int nclusters, int nnodes)
{
  if (!start) return nclusters == 0 ? -1 : 0; /* a writer may omit {0} without nodes */
  if (start[0] != 0) return 0;
  for (int c = 0; c < nclusters; c++)
    if (start[c + 1] <= start[c]) return c + 1;
  if (start[nclusters] != nnodes) return nclusters;
  return -1;
}

/* ------------------------------------------------------------------ writer ---- */

/* Layout of one section: byte offset of each array from the section start, and the
 * section length (each array padded to 8 bytes). */
static uint64_t section_layout(const lsdem_shape *s, uint64_t off[LIB_NARRAYS],
                               uint64_t len[LIB_NARRAYS])
{
  array_lengths(s, len);
  uint64_t pos = 0;
  for (int a = 0; a < LIB_NARRAYS; a++) {
    off[a] = len[a] ? pos : 0;
    pos += pad8(len[a]);
  }
  return pos;
}

/* Feed a section's bytes (arrays and zero padding, in layout order) into a checksum and,
 * when f is not NULL, into the file. Returns 0 on a write error. */
static int emit_section(const lsdem_shape *s, FILE *f, uint64_t *sum)
{
  static const unsigned char zeros[8] = {0};
  uint64_t off[LIB_NARRAYS], len[LIB_NARRAYS];
  section_layout(s, off, len);
  for (int a = 0; a < LIB_NARRAYS; a++) {
    if (!len[a]) continue;
    const size_t n = (size_t)len[a], npad = (size_t)(pad8(len[a]) - len[a]);
    *sum = fnv1a_update(*sum, array_data(s, a), n);
    *sum = fnv1a_update(*sum, zeros, npad);
    if (f && (fwrite(array_data(s, a), 1, n, f) != n || fwrite(zeros, 1, npad, f) != npad))
      return 0;
  }
  return 1;
}

static lsdem_status check_shape_for_write(const lsdem_shape *s, int i, const char *name,
                                          lsdem_error *err)
{
  const char *bad = bad_scalar_field(s);
  if (bad) return lsdem_fail(err, LSDEM_ERR_ARG, "shape library: shape %d: bad %s", i, bad);
  if (s->nnodes > 0 && (!s->nodes || !s->node_area || !s->cluster_start || !s->cluster_sphere))
    return lsdem_fail(err, LSDEM_ERR_ARG, "shape library: shape %d: NULL node arrays", i);
  if (s->sdf.kind == LSDEM_SDF_GRID && !s->sdf.grid.phi)
    return lsdem_fail(err, LSDEM_ERR_ARG, "shape library: shape %d: NULL grid", i);
  const int c = bad_cluster_start(s->cluster_start, s->nclusters, s->nnodes);
  if (c >= 0)
    return lsdem_fail(err, LSDEM_ERR_ARG,
                      "shape library: shape %d: cluster_start[%d] = %d breaks 0 = start[0] < "
                      "... < start[nclusters] = nnodes = %d", i, c, s->cluster_start[c], s->nnodes);
  if (name && strlen(name) >= LIB_NAME_SIZE)
    return lsdem_fail(err, LSDEM_ERR_ARG, "shape library: shape %d: name '%.40s...' longer "
                      "than %d bytes", i, name, LIB_NAME_SIZE - 1);
  return LSDEM_OK;
}

static void encode_entry(unsigned char *e, const lsdem_shape *s, const char *name,
                         uint64_t sec_off, uint64_t sec_len, uint64_t sec_sum)
{
  uint64_t off[LIB_NARRAYS], len[LIB_NARRAYS];
  section_layout(s, off, len);
  memset(e, 0, LIB_ENTRY_SIZE);
  put_i32(e + E_KIND, (int32_t)s->sdf.kind);
  put_i32(e + E_INVERTED, s->sdf.inverted);
  for (int k = 0; k < 3; k++) {
    put_f64(e + E_A + 8 * k, s->sdf.a[k]);
    put_i32(e + E_N + 4 * k, s->sdf.grid.n[k]);
    put_f64(e + E_ORIGIN + 8 * k, s->sdf.kind == LSDEM_SDF_GRID ? s->sdf.grid.origin[k] : 0.0);
    put_f64(e + E_INERTIA + 8 * k, s->inertia[k]);
  }
  put_i32(e + E_NNODES, s->nnodes);
  put_f64(e + E_H, s->sdf.kind == LSDEM_SDF_GRID ? s->sdf.grid.h : 0.0);
  put_i32(e + E_NCLUSTERS, s->nclusters);
  put_f64(e + E_RADIUS, s->radius);
  put_f64(e + E_VOLUME, s->volume);
  put_u64(e + E_SEC_OFF, sec_off);
  put_u64(e + E_SEC_LEN, sec_len);
  put_u64(e + E_SEC_SUM, sec_sum);
  for (int a = 0; a < LIB_NARRAYS; a++) {
    put_u64(e + E_ARRAYS + 16 * a, len[a] ? sec_off + off[a] : 0);
    put_u64(e + E_ARRAYS + 16 * a + 8, len[a]);
  }
  if (name) memcpy(e + E_NAME, name, strlen(name));
}

/* Header and TOC for `count` shapes; returns the total file size. */
static uint64_t encode_header_toc(unsigned char *buf, const lsdem_shape *shapes,
                                  const char *const *names, int count)
{
  const uint64_t toc_end = LIB_HEADER_SIZE + (uint64_t)LIB_ENTRY_SIZE * (uint64_t)count;
  uint64_t pos = toc_end;
  for (int i = 0; i < count; i++) {
    uint64_t off[LIB_NARRAYS], len[LIB_NARRAYS], sum = FNV_BASIS;
    const uint64_t sec_len = section_layout(&shapes[i], off, len);
    emit_section(&shapes[i], NULL, &sum);
    encode_entry(buf + LIB_HEADER_SIZE + (size_t)LIB_ENTRY_SIZE * (size_t)i, &shapes[i],
                 names ? names[i] : NULL, pos, sec_len, sum);
    pos += sec_len;
  }
  memset(buf, 0, LIB_HEADER_SIZE);
  memcpy(buf + H_MAGIC, LIB_MAGIC, 8);
  put_u32(buf + H_VERSION, LIB_VERSION);
  put_u32(buf + H_HSIZE, LIB_HEADER_SIZE);
  put_u32(buf + H_ESIZE, LIB_ENTRY_SIZE);
  put_u32(buf + H_COUNT, (uint32_t)count);
  put_u64(buf + H_TOC, LIB_HEADER_SIZE);
  put_u64(buf + H_FSIZE, pos);
  uint64_t sum = fnv1a_update(FNV_BASIS, buf, H_SUM);
  sum = fnv1a_update(sum, buf + LIB_HEADER_SIZE, toc_end - LIB_HEADER_SIZE);
  put_u64(buf + H_SUM, sum);
  return pos;
}

/* Written to a temporary file renamed over `path` at the end, so processes that have
 * the old library mapped keep a consistent copy. */
lsdem_status lsdem_library_write(const char *path, const lsdem_shape *shapes,
                                 const char *const *names, int count, lsdem_error *err)
{
  if (!path || count < 0 || count > LSDEM_LIBRARY_MAX_SHAPES || (count > 0 && !shapes))
    return lsdem_fail(err, LSDEM_ERR_ARG, "shape library: bad arguments (path %s, count %d)",
                      path ? path : "NULL", count);
  if (!host_is_little_endian())
    return lsdem_fail(err, LSDEM_ERR_ARG, "shape library: a big-endian host cannot write "
                      "the little-endian format");
  for (int i = 0; i < count; i++) {
    const lsdem_status st = check_shape_for_write(&shapes[i], i, names ? names[i] : NULL, err);
    if (st != LSDEM_OK) return st;
  }
  const size_t head = LIB_HEADER_SIZE + (size_t)LIB_ENTRY_SIZE * (size_t)count;
  unsigned char *buf = (unsigned char *)malloc(head);
  char *tmp = (char *)malloc(strlen(path) + 32);
  if (!buf || !tmp) {
    free(buf);
    free(tmp);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "shape library '%s': out of memory", path);
  }
  encode_header_toc(buf, shapes, names, count);
  sprintf(tmp, "%s.tmp%ld", path, (long)getpid());
  FILE *f = fopen(tmp, "wb");
  int ok = f && fwrite(buf, 1, head, f) == head;
  for (int i = 0; ok && i < count; i++) {
    uint64_t unused = FNV_BASIS;
    ok = emit_section(&shapes[i], f, &unused);
  }
  if (f && fclose(f) != 0) ok = 0;
  if (ok && rename(tmp, path) != 0) ok = 0;
  lsdem_status st = LSDEM_OK;
  if (!ok) {
    st = lsdem_fail(err, LSDEM_ERR_IO, "shape library '%s': cannot write: %s", path,
                    strerror(errno));
    remove(tmp);
  }
  free(buf);
  free(tmp);
  return st;
}

/* ------------------------------------------------------------------ reader ---- */

static void library_free(lsdem_library *lib)
{
  if (!lib) return;
  if (lib->map) munmap(lib->map, lib->size);
  free(lib->shapes);
  free(lib->names);
  free(lib->sec_off);
  free(lib->sec_len);
  free(lib->sec_sum);
  free(lib);
}

static lsdem_status check_header(const unsigned char *m, size_t size, const char *path,
                                 int *count, lsdem_error *err)
{
  if (size < LIB_HEADER_SIZE)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': %zu bytes, too short for "
                      "the %d-byte header", path, size, LIB_HEADER_SIZE);
  if (memcmp(m + H_MAGIC, LIB_MAGIC, 8) != 0)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': bad magic (not an LSDEM "
                      "shape library; expected 'LSDEMLIB')", path);
  const uint32_t version = get_u32(m + H_VERSION);
  if (version != LIB_VERSION)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': format version %u, this "
                      "build reads version %d", path, version, LIB_VERSION);
  if (get_u32(m + H_HSIZE) != LIB_HEADER_SIZE || get_u32(m + H_ESIZE) != LIB_ENTRY_SIZE ||
      get_u64(m + H_TOC) != LIB_HEADER_SIZE)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': header size %u, TOC entry "
                      "size %u, TOC offset %llu (expected %d, %d, %d)", path,
                      get_u32(m + H_HSIZE), get_u32(m + H_ESIZE),
                      (unsigned long long)get_u64(m + H_TOC), LIB_HEADER_SIZE, LIB_ENTRY_SIZE,
                      LIB_HEADER_SIZE);
  const uint64_t fsize = get_u64(m + H_FSIZE);
  if (fsize != size)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': file is %zu bytes, header "
                      "says %llu (%s)", path, size, (unsigned long long)fsize,
                      size < fsize ? "truncated" : "trailing bytes");
  const uint32_t n = get_u32(m + H_COUNT);
  if (n > LSDEM_LIBRARY_MAX_SHAPES ||
      LIB_HEADER_SIZE + (uint64_t)LIB_ENTRY_SIZE * n > size)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': shape count %u does not fit "
                      "a %zu-byte file", path, n, size);
  const uint64_t toc_end = LIB_HEADER_SIZE + (uint64_t)LIB_ENTRY_SIZE * n;
  uint64_t sum = fnv1a_update(FNV_BASIS, m, H_SUM);
  sum = fnv1a_update(sum, m + LIB_HEADER_SIZE, toc_end - LIB_HEADER_SIZE);
  if (sum != get_u64(m + H_SUM))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': header/TOC checksum "
                      "mismatch (stored %016llx, computed %016llx)", path,
                      (unsigned long long)get_u64(m + H_SUM), (unsigned long long)sum);
  *count = (int)n;
  return LSDEM_OK;
}

static void decode_entry(const unsigned char *e, lsdem_shape *s)
{
  memset(s, 0, sizeof *s);
  s->sdf.kind = (lsdem_sdf_kind)get_i32(e + E_KIND);
  s->sdf.inverted = get_i32(e + E_INVERTED);
  for (int k = 0; k < 3; k++) {
    s->sdf.a[k] = get_f64(e + E_A + 8 * k);
    s->sdf.grid.n[k] = get_i32(e + E_N + 4 * k);
    s->sdf.grid.origin[k] = get_f64(e + E_ORIGIN + 8 * k);
    s->inertia[k] = get_f64(e + E_INERTIA + 8 * k);
  }
  s->nnodes = get_i32(e + E_NNODES);
  s->sdf.grid.h = get_f64(e + E_H);
  s->nclusters = get_i32(e + E_NCLUSTERS);
  s->radius = get_f64(e + E_RADIUS);
  s->volume = get_f64(e + E_VOLUME);
}

/* Offsets and lengths of one entry's section and arrays against the file: the section
 * lies after the previous one (sections in TOC order, no overlap) and inside the file;
 * each array is 8-byte aligned, has the length its counts imply, lies inside the
 * section and overlaps no other array. */
static lsdem_status check_entry_extents(const unsigned char *e, const lsdem_shape *s, int i,
                                        uint64_t prev_end, uint64_t size, const char *path,
                                        lsdem_error *err)
{
  const uint64_t so = get_u64(e + E_SEC_OFF), sl = get_u64(e + E_SEC_LEN);
  if (so % 8 || so < prev_end || sl > size || so > size - sl)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': shape %d: field section: "
                      "offset %llu length %llu is misaligned, overlaps the previous section "
                      "(ends at %llu) or runs past the end of the file (%llu bytes)", path, i,
                      (unsigned long long)so, (unsigned long long)sl,
                      (unsigned long long)prev_end, (unsigned long long)size);
  uint64_t want[LIB_NARRAYS], off[LIB_NARRAYS], len[LIB_NARRAYS];
  array_lengths(s, want);
  for (int a = 0; a < LIB_NARRAYS; a++) {
    off[a] = get_u64(e + E_ARRAYS + 16 * a);
    len[a] = get_u64(e + E_ARRAYS + 16 * a + 8);
    if (len[a] != want[a])
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': shape %d: field %s: "
                        "length %llu, expected %llu from the counts", path, i, ARRAY_NAME[a],
                        (unsigned long long)len[a], (unsigned long long)want[a]);
    if (len[a] && (off[a] % 8 || off[a] < so || len[a] > sl || off[a] - so > sl - len[a]))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': shape %d: field %s: "
                        "offset %llu length %llu is misaligned or outside its section "
                        "[%llu, %llu)", path, i, ARRAY_NAME[a], (unsigned long long)off[a],
                        (unsigned long long)len[a], (unsigned long long)so,
                        (unsigned long long)(so + sl));
  }
  for (int a = 0; a < LIB_NARRAYS; a++)
    for (int b = a + 1; b < LIB_NARRAYS; b++)
      if (len[a] && len[b] && off[a] < off[b] + len[b] && off[b] < off[a] + len[a])
        return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': shape %d: fields %s "
                          "and %s overlap", path, i, ARRAY_NAME[a], ARRAY_NAME[b]);
  return LSDEM_OK;
}

/* Point a decoded shape's arrays into the mapping. */
static void attach_arrays(const unsigned char *m, const unsigned char *e, lsdem_shape *s)
{
  const void *p[LIB_NARRAYS];
  for (int a = 0; a < LIB_NARRAYS; a++) {
    const uint64_t off = get_u64(e + E_ARRAYS + 16 * a), len = get_u64(e + E_ARRAYS + 16 * a + 8);
    p[a] = len ? (const void *)(m + off) : NULL;
  }
  s->cluster_start = (const int *)p[A_CSTART];
  s->cluster_sphere = (const double *)p[A_CSPHERE];
  s->nodes = (const double *)p[A_NODES];
  s->node_area = (const double *)p[A_AREA];
  s->sdf.grid.phi = (const float *)p[A_PHI];
  if (s->sdf.kind == LSDEM_SDF_GRID && s->sdf.grid.phi)
    s->sdf.grid.lip = lsdem_grid_outer_lipschitz(&s->sdf.grid, &s->sdf.grid.lip_reach);
}

static lsdem_status load_entry(lsdem_library *lib, int i, uint64_t *prev_end, const char *path,
                               lsdem_error *err)
{
  const unsigned char *m = (const unsigned char *)lib->map;
  const unsigned char *e = m + LIB_HEADER_SIZE + (size_t)LIB_ENTRY_SIZE * (size_t)i;
  lsdem_shape *s = &lib->shapes[i];
  decode_entry(e, s);
  const char *bad = bad_scalar_field(s);
  if (bad)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': shape %d: bad %s", path, i,
                      bad);
  if (!memchr(e + E_NAME, 0, LIB_NAME_SIZE))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': shape %d: field name is "
                      "not NUL-terminated", path, i);
  const lsdem_status st = check_entry_extents(e, s, i, *prev_end, lib->size, path, err);
  if (st != LSDEM_OK) return st;
  attach_arrays(m, e, s);
  const int c = bad_cluster_start(s->cluster_start, s->nclusters, s->nnodes);
  if (c >= 0)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': shape %d: field "
                      "cluster_start: entry %d = %d is out of order (nnodes %d)", path, i, c,
                      s->cluster_start[c], s->nnodes);
  lib->names[i] = (const char *)(e + E_NAME);
  lib->sec_off[i] = get_u64(e + E_SEC_OFF);
  lib->sec_len[i] = get_u64(e + E_SEC_LEN);
  lib->sec_sum[i] = get_u64(e + E_SEC_SUM);
  *prev_end = lib->sec_off[i] + lib->sec_len[i];
  return LSDEM_OK;
}

static lsdem_status map_file(const char *path, lsdem_library *lib, lsdem_error *err)
{
  const int fd = open(path, O_RDONLY);
  if (fd < 0)
    return lsdem_fail(err, LSDEM_ERR_IO, "shape library '%s': cannot open: %s", path,
                      strerror(errno));
  struct stat sb;
  if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
    close(fd);
    return lsdem_fail(err, LSDEM_ERR_IO, "shape library '%s': not a regular file", path);
  }
  lib->size = (size_t)sb.st_size;
  if (lib->size < LIB_HEADER_SIZE) {
    close(fd);
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': %zu bytes, too short for "
                      "the %d-byte header", path, lib->size, LIB_HEADER_SIZE);
  }
  void *m = mmap(NULL, lib->size, PROT_READ, MAP_SHARED, fd, 0);
  close(fd);
  if (m == MAP_FAILED)
    return lsdem_fail(err, LSDEM_ERR_IO, "shape library '%s': cannot map: %s", path,
                      strerror(errno));
  lib->map = m;
  return LSDEM_OK;
}

lsdem_status lsdem_library_open(const char *path, lsdem_library **out, lsdem_error *err)
{
  if (!path || !out) return lsdem_fail(err, LSDEM_ERR_ARG, "shape library: NULL argument");
  *out = NULL;
  if (!host_is_little_endian())
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': this big-endian host cannot "
                      "map the little-endian format", path);
  lsdem_library *lib = (lsdem_library *)calloc(1, sizeof *lib);
  if (!lib) return lsdem_fail(err, LSDEM_ERR_NOMEM, "shape library '%s': out of memory", path);
  lsdem_status st = map_file(path, lib, err);
  if (st == LSDEM_OK) st = check_header((const unsigned char *)lib->map, lib->size, path,
                                        &lib->count, err);
  if (st == LSDEM_OK) {
    const size_t n = lib->count > 0 ? (size_t)lib->count : 1;
    lib->shapes = (lsdem_shape *)calloc(n, sizeof *lib->shapes);
    lib->names = (const char **)calloc(n, sizeof *lib->names);
    lib->sec_off = (uint64_t *)calloc(n, sizeof *lib->sec_off);
    lib->sec_len = (uint64_t *)calloc(n, sizeof *lib->sec_len);
    lib->sec_sum = (uint64_t *)calloc(n, sizeof *lib->sec_sum);
    if (!lib->shapes || !lib->names || !lib->sec_off || !lib->sec_len || !lib->sec_sum)
      st = lsdem_fail(err, LSDEM_ERR_NOMEM, "shape library '%s': out of memory", path);
  }
  uint64_t prev_end = LIB_HEADER_SIZE + (uint64_t)LIB_ENTRY_SIZE * (uint64_t)lib->count;
  for (int i = 0; st == LSDEM_OK && i < lib->count; i++)
    st = load_entry(lib, i, &prev_end, path, err);
  if (st != LSDEM_OK) {
    library_free(lib);
    return st;
  }
  *out = lib;
  return LSDEM_OK;
}

void lsdem_library_close(lsdem_library *lib) { library_free(lib); }

int lsdem_library_count(const lsdem_library *lib) { return lib ? lib->count : 0; }

const lsdem_shape *lsdem_library_shape(const lsdem_library *lib, int index)
{
  if (!lib || index < 0 || index >= lib->count) return NULL;
  return &lib->shapes[index];
}

const char *lsdem_library_name(const lsdem_library *lib, int index)
{
  if (!lib || index < 0 || index >= lib->count) return "";
  return lib->names[index];
}

static lsdem_status verify_shape(const lsdem_library *lib, int i, lsdem_error *err)
{
  const unsigned char *m = (const unsigned char *)lib->map;
  const uint64_t sum = fnv1a_update(FNV_BASIS, m + lib->sec_off[i], (size_t)lib->sec_len[i]);
  if (sum != lib->sec_sum[i])
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library: shape %d ('%s'): section "
                      "checksum mismatch (stored %016llx, computed %016llx): the file is "
                      "corrupt", i, lib->names[i], (unsigned long long)lib->sec_sum[i],
                      (unsigned long long)sum);
  const lsdem_shape *s = &lib->shapes[i];
  if (!all_finite(s->nodes, 3 * s->nnodes) || !all_finite(s->node_area, s->nnodes) ||
      !all_finite(s->cluster_sphere, 4 * s->nclusters))
    return lsdem_fail(err, LSDEM_ERR_NUMERIC, "shape library: shape %d ('%s'): NaN or inf in "
                      "its nodes, node areas or cluster spheres", i, lib->names[i]);
  const uint64_t ns = grid_samples(s);
  for (uint64_t k = 0; k < ns; k++)
    if (!isfinite(s->sdf.grid.phi[k]))
      return lsdem_fail(err, LSDEM_ERR_NUMERIC, "shape library: shape %d ('%s'): level-set "
                        "value %llu is not finite", i, lib->names[i], (unsigned long long)k);
  return LSDEM_OK;
}

lsdem_status lsdem_library_verify(const lsdem_library *lib, int index, lsdem_error *err)
{
  if (!lib || index < -1 || index >= lib->count)
    return lsdem_fail(err, LSDEM_ERR_ARG, "shape library: verify: no shape %d", index);
  if (index >= 0) return verify_shape(lib, index, err);
  for (int i = 0; i < lib->count; i++) {
    const lsdem_status st = verify_shape(lib, i, err);
    if (st != LSDEM_OK) return st;
  }
  return LSDEM_OK;
}
