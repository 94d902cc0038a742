/* bandfile_format.h -- the band file format (a wall's narrow-band level set, lsdem_band)
 * shared by its reader (geom/bandfile.c, the kernel) and its writer (prep/band_write.c):
 * field offsets and sizes. Byte access and the checksum are the shape library's
 * (shapelib_format.h). Private to the core. Layout (little-endian, doc/wall_band.rst):
 *
 *   [0, 128)        header: fields below
 *   [128, ...)      index: int32 per brick slot, nb[0] nb[1] nb[2] of them, x fastest
 *   [phi_off, end)  samples: float32, LSDEM_BAND_BRICK_SAMPLES per stored brick;
 *                   phi_off = the index's end rounded up to 64 bytes
 *
 * The header checksum (FNV-1a 64) covers bytes [0, BF_HSUM); the payload checksum
 * bytes [128, end). */
#ifndef LSDEM_BANDFILE_FORMAT_H
#define LSDEM_BANDFILE_FORMAT_H
#include "shapelib_format.h"

static const char BAND_MAGIC[8] __attribute__((unused)) = {'L', 'S', 'D', 'E', 'M', 'B', 'N', 'D'};
enum {
  BAND_VERSION = 1,
  BAND_HEADER_SIZE = 128,
  /* header fields: magic, version (u32), source (u32: lsdem_band_source), n[3] (i32),
   * nb[3] (i32), nbricks (u64), h, origin[3], width (f64), payload checksum (u64),
   * header checksum (u64) */
  BF_MAGIC = 0, BF_VERSION = 8, BF_SOURCE = 12, BF_N = 16, BF_NB = 28, BF_NBRICKS = 40,
  BF_H = 48, BF_ORIGIN = 56, BF_WIDTH = 80, BF_PSUM = 88, BF_HSUM = 96
};

/* Bytes of the index of nb bricks per axis, and where the samples start. */
static inline uint64_t band_index_bytes(const int nb[3])
{
  return 4u * (uint64_t)nb[0] * (uint64_t)nb[1] * (uint64_t)nb[2];
}
static inline uint64_t band_phi_offset(const int nb[3])
{
  return (BAND_HEADER_SIZE + band_index_bytes(nb) + 63u) & ~(uint64_t)63u;
}
/* Bricks per axis for n samples: enough bricks of LSDEM_BAND_BRICK cells for n - 1
 * cells. */
static inline int band_bricks_for(int n) { return (n - 2) / LSDEM_BAND_BRICK + 1; }

#endif /* LSDEM_BANDFILE_FORMAT_H */
