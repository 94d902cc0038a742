/* library_write.c -- writing a shape-library file (format in doc/shape_library.rst; the
 * reader is the kernel's geom/shapelib.c, the shared layout geom/shapelib_format.h). */
#include "lsdem_prep.h"
#include "replace_file.h"
#include "../geom/shapelib_format.h"

#include <stdio.h>
#include <stdlib.h>

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
  return lsdem_shape_validate(s, i, name, err);
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

/* Written to a temporary file renamed over `path` at the end (replace_file.h), so
 * processes that have the old library mapped keep a consistent copy; a path that exists as
 * anything but a regular file (a device, a pipe) is refused. Every shape must pass
 * lsdem_shape_validate. */
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
  if (!buf) return lsdem_fail(err, LSDEM_ERR_NOMEM, "shape library '%s': out of memory", path);
  encode_header_toc(buf, shapes, names, count);
  replace_file out;
  lsdem_status st = replace_file_open(&out, path, "shape library", err);
  if (st == LSDEM_OK) {
    int ok = fwrite(buf, 1, head, out.f) == head;
    for (int i = 0; ok && i < count; i++) {
      uint64_t unused = FNV_BASIS;
      ok = emit_section(&shapes[i], out.f, &unused);
    }
    st = replace_file_close(&out, ok, err);
  }
  free(buf);
  return st;
}
