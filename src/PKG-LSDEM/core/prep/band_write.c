/* band_write.c -- writing a band file (a wall's narrow band; format in doc/wall_band.rst,
 * layout geom/bandfile_format.h; the reader is the kernel's geom/bandfile.c). */
#include "lsdem_prep.h"
#include "replace_file.h"
#include "../geom/bandfile_format.h"

#include <stdio.h>

lsdem_status lsdem_band_write(const char *path, const lsdem_band *b, lsdem_band_source src,
                              lsdem_error *err)
{
  const int heights = src == LSDEM_BAND_HEIGHTS;
  if (!path || !b || (!heights && !b->index) || (b->nbricks > 0 && !b->phi) || b->nbricks < 0 ||
      b->nbricks > INT32_MAX || heights != (b->heights != NULL))
    return lsdem_fail(err, LSDEM_ERR_ARG, "band file: bad arguments (path %s)",
                      path ? path : "NULL");
  if (src != LSDEM_BAND_MESH && src != LSDEM_BAND_TERRAIN && !heights)
    return lsdem_fail(err, LSDEM_ERR_ARG, "band file '%s': source %d is neither a mesh nor a "
                      "terrain", path, (int)src);
  if (!host_is_little_endian())
    return lsdem_fail(err, LSDEM_ERR_ARG, "band file: a big-endian host cannot write the "
                      "little-endian format");
  lsdem_error inner;
  lsdem_status st = lsdem_band_check(b, &inner);
  if (st != LSDEM_OK) return lsdem_fail(err, LSDEM_ERR_ARG, "band file '%s': %s", path, inner.msg);
  const uint64_t nlist = b->ntris ? (uint64_t)b->brick_tri_start[b->nbricks] : 0;
  uint64_t off[BS_COUNT];
  const uint64_t nverts = b->ntris ? (uint64_t)b->nverts : 0;
  const uint64_t samples = band_samples(b->n, (uint64_t)b->nbricks, heights);
  band_layout(b->nb, samples, (uint64_t)b->nbricks, nverts, (uint64_t)b->ntris, nlist, off);
  /* the sections in order, each after zero padding up to its offset */
  const void *data[BS_COUNT] = {heights ? b->heights : b->phi, b->verts, b->tris,
                                b->brick_tri_start, b->brick_tris, b->nbr};
  const size_t bytes[BS_COUNT] = {(size_t)samples * sizeof(float),
                                  (size_t)nverts * 24u,
                                  (size_t)b->ntris * 12u,
                                  b->ntris ? ((size_t)b->nbricks + 1u) * 8u : 0,
                                  (size_t)nlist * 4u, (size_t)b->ntris * 12u};
  size_t pad[BS_COUNT];
  uint64_t at = BAND_HEADER_SIZE + band_index_bytes(b->nb);
  for (int k = 0; k < BS_COUNT; k++) {
    pad[k] = (size_t)(off[k] - at);
    at = off[k] + bytes[k];
  }
  static const unsigned char zeros[64] = {0};
  const size_t index_bytes = (size_t)band_index_bytes(b->nb);
  unsigned char head[BAND_HEADER_SIZE];
  memset(head, 0, sizeof head);
  memcpy(head + BF_MAGIC, BAND_MAGIC, sizeof BAND_MAGIC);
  put_u32(head + BF_VERSION, BAND_VERSION);
  put_u32(head + BF_SOURCE, (uint32_t)src);
  for (int a = 0; a < 3; a++) {
    put_i32(head + BF_N + 4 * a, b->n[a]);
    put_i32(head + BF_NB + 4 * a, b->nb[a]);
    put_f64(head + BF_ORIGIN + 8 * a, b->origin[a]);
  }
  put_u64(head + BF_NBRICKS, (uint64_t)b->nbricks);
  put_f64(head + BF_H, b->h);
  put_f64(head + BF_WIDTH, b->width);
  put_u64(head + BF_NVERTS, nverts);
  put_u64(head + BF_NTRIS, (uint64_t)b->ntris);
  put_u64(head + BF_NLIST, nlist);
  uint64_t sum = index_bytes ? fnv1a_update(FNV_BASIS, b->index, index_bytes) : FNV_BASIS;
  for (int k = 0; k < BS_COUNT; k++) {
    sum = fnv1a_update(sum, zeros, pad[k]);
    if (bytes[k]) sum = fnv1a_update(sum, data[k], bytes[k]);
  }
  put_u64(head + BF_PSUM, sum);
  put_u64(head + BF_HSUM, fnv1a_update(FNV_BASIS, head, BF_HSUM));
  replace_file out;
  st = replace_file_open(&out, path, "band file", err);
  if (st != LSDEM_OK) return st;
  int ok = fwrite(head, 1, sizeof head, out.f) == sizeof head &&
           (index_bytes == 0 || fwrite(b->index, 1, index_bytes, out.f) == index_bytes);
  for (int k = 0; k < BS_COUNT && ok; k++)
    ok = fwrite(zeros, 1, pad[k], out.f) == pad[k] &&
         (bytes[k] == 0 || fwrite(data[k], 1, bytes[k], out.f) == bytes[k]);
  return replace_file_close(&out, ok, err);
}
