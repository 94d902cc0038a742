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
#include "filemap.h"
#include "shapelib_format.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

static const char *const ARRAY_NAME[LIB_NARRAYS] = {"cluster_start", "cluster_sphere", "nodes",
                                                    "node_area", "phi"};

struct lsdem_library {
  void *map;
  size_t size;
  int count;
  lsdem_shape *shapes;
  const char **names;
  uint64_t *sec_off, *sec_len, *sec_sum;
};

/* ------------------------------------------------------------------ reader ---- */

static void library_free(lsdem_library *lib)
{
  if (!lib) return;
  lsdem_unmap_file(lib->map, lib->size);
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

lsdem_status lsdem_library_open(const char *path, lsdem_library **out, lsdem_error *err)
{
  if (!path || !out) return lsdem_fail(err, LSDEM_ERR_ARG, "shape library: NULL argument");
  *out = NULL;
  if (!host_is_little_endian())
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "shape library '%s': this big-endian host cannot "
                      "map the little-endian format", path);
  lsdem_library *lib = (lsdem_library *)calloc(1, sizeof *lib);
  if (!lib) return lsdem_fail(err, LSDEM_ERR_NOMEM, "shape library '%s': out of memory", path);
  lsdem_status st = lsdem_map_file(path, "shape library", LIB_HEADER_SIZE, &lib->map, &lib->size, err);
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
  return lsdem_shape_validate(&lib->shapes[i], i, lib->names[i], err);
}

/* ----------------------------------------------------------- shape content ---- */

/* A failed content check of shape `index`: "shape library: shape I ('NAME'): WHY". */
static lsdem_status invalid_shape(lsdem_error *err, int index, const char *name,
                                  const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static lsdem_status invalid_shape(lsdem_error *err, int index, const char *name,
                                  const char *fmt, ...)
{
  char why[sizeof err->msg];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(why, sizeof why, fmt, ap);
  va_end(ap);
  return lsdem_fail(err, LSDEM_ERR_NUMERIC, "shape library: shape %d ('%s'): %s", index,
                    name ? name : "", why);
}

/* The grid's values finite, one of them negative, and the origin inside the grid box. */
static lsdem_status validate_grid(const lsdem_shape *s, int index, const char *name,
                                  lsdem_error *err)
{
  const lsdem_grid *g = &s->sdf.grid;
  const uint64_t ns = grid_samples(s);
  for (uint64_t k = 0; k < ns; k++)
    if (!isfinite(g->phi[k]))
      return invalid_shape(err, index, name, "level-set value %llu is not finite",
                           (unsigned long long)k);
  if (!lsdem_grid_has_solid(g))
    return invalid_shape(err, index, name, "no level-set value is negative: the grid holds "
                         "no solid");
  for (int a = 0; a < 3; a++)
    if (!(g->origin[a] <= 0.0 && 0.0 <= g->origin[a] + g->h * (g->n[a] - 1)))
      return invalid_shape(err, index, name, "its centroid (the origin of its principal "
                           "frame) is at grid coordinates (%g, %g, %g), outside the grid "
                           "of %d x %d x %d samples", -g->origin[0] / g->h,
                           -g->origin[1] / g->h, -g->origin[2] / g->h, g->n[0], g->n[1],
                           g->n[2]);
  return LSDEM_OK;
}

lsdem_status lsdem_shape_validate(const lsdem_shape *s, int index, const char *name,
                                  lsdem_error *err)
{
  if (!all_finite(s->nodes, 3 * s->nnodes) || !all_finite(s->node_area, s->nnodes) ||
      !all_finite(s->cluster_sphere, 4 * s->nclusters))
    return invalid_shape(err, index, name, "NaN or inf in its nodes, node areas or cluster "
                         "spheres");
  if (s->sdf.kind == LSDEM_SDF_GRID) {
    const lsdem_status st = validate_grid(s, index, name, err);
    if (st != LSDEM_OK) return st;
  }
  for (int k = 0; k < s->nnodes; k++)
    if (!(s->node_area[k] > 0.0))
      return invalid_shape(err, index, name, "node %d has area %g: each node stands for a "
                           "part of the surface (area > 0)", k, s->node_area[k]);
  int far = -1;
  double r2 = 0.0;
  for (int k = 0; k < s->nnodes; k++) {
    const double *p = s->nodes + 3 * k, d2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
    if (d2 > r2) r2 = d2, far = k;
  }
  if (far >= 0 && sqrt(r2) > s->radius * (1.0 + 1e-9))
    return invalid_shape(err, index, name, "node %d lies %g from the centroid, beyond the "
                         "bounding radius %g (contacts beyond the radius are missed)", far,
                         sqrt(r2), s->radius);
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
