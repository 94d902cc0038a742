/* band_write.c -- writing a band file (a wall's narrow band; format in doc/wall_band.rst,
 * layout geom/bandfile_format.h; the reader is the kernel's geom/bandfile.c). */
#include "lsdem_prep.h"
#include "replace_file.h"
#include "../geom/bandfile_format.h"

#include <stdio.h>

lsdem_status lsdem_band_write(const char *path, const lsdem_band *b, lsdem_band_source src,
                              lsdem_error *err)
{
  if (!path || !b || !b->index || (b->nbricks > 0 && !b->phi) || b->nbricks < 0 ||
      b->nbricks > INT32_MAX)
    return lsdem_fail(err, LSDEM_ERR_ARG, "band file: bad arguments (path %s)",
                      path ? path : "NULL");
  if (src != LSDEM_BAND_MESH && src != LSDEM_BAND_TERRAIN)
    return lsdem_fail(err, LSDEM_ERR_ARG, "band file '%s': source %d is neither a mesh nor a "
                      "terrain", path, (int)src);
  if (!host_is_little_endian())
    return lsdem_fail(err, LSDEM_ERR_ARG, "band file: a big-endian host cannot write the "
                      "little-endian format");
  lsdem_error inner;
  lsdem_status st = lsdem_band_check(b, &inner);
  if (st != LSDEM_OK) return lsdem_fail(err, LSDEM_ERR_ARG, "band file '%s': %s", path, inner.msg);
  static const unsigned char zeros[64] = {0};
  const size_t index_bytes = (size_t)band_index_bytes(b->nb);
  const size_t pad = (size_t)(band_phi_offset(b->nb) - BAND_HEADER_SIZE) - index_bytes;
  const size_t phi_bytes = (size_t)b->nbricks * LSDEM_BAND_BRICK_SAMPLES * sizeof(float);
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
  uint64_t sum = fnv1a_update(FNV_BASIS, b->index, index_bytes);
  sum = fnv1a_update(sum, zeros, pad);
  if (phi_bytes) sum = fnv1a_update(sum, b->phi, phi_bytes);
  put_u64(head + BF_PSUM, sum);
  put_u64(head + BF_HSUM, fnv1a_update(FNV_BASIS, head, BF_HSUM));
  replace_file out;
  st = replace_file_open(&out, path, "band file", err);
  if (st != LSDEM_OK) return st;
  const int ok = fwrite(head, 1, sizeof head, out.f) == sizeof head &&
                 fwrite(b->index, 1, index_bytes, out.f) == index_bytes &&
                 fwrite(zeros, 1, pad, out.f) == pad &&
                 (phi_bytes == 0 || fwrite(b->phi, 1, phi_bytes, out.f) == phi_bytes);
  return replace_file_close(&out, ok, err);
}
