/* bandfile_format.h -- the band file format (a wall's narrow-band level set, lsdem_band)
 * shared by its reader (geom/bandfile.c, the kernel) and its writer (prep/band_write.c):
 * field offsets and sizes. Byte access and the checksum are the shape library's
 * (shapelib_format.h). Private to the core. Layout (little-endian, doc/wall_band.rst):
 *
 *   [0, 128)        header: fields below
 *   [128, ...)      index: int32 per brick slot, nb[0] nb[1] nb[2] of them, x fastest
 *                   (none for heights: nb = 0 0 0)
 *   then, each section starting at a multiple of 64 bytes (band_layout):
 *     samples: float32, LSDEM_BAND_BRICK_SAMPLES per stored brick; for a terrain kept as
 *              heights (source LSDEM_BAND_HEIGHTS) its n[0] n[1] heights, x fastest
 *     vertices: float64, 3 per vertex
 *     triangles: int32, 3 vertex indices each
 *     brick list starts: int64, nbricks + 1
 *     brick lists: int32 triangle numbers
 *     triangle neighbours: int32, 3 per triangle (the triangle across each edge, -1 none)
 * with zero bytes between sections.
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
   * nb[3] (i32), nbricks (u64), h, origin[3], width (f64), nverts, ntris, nlist (u64:
   * entries of the brick lists), payload checksum (u64), header checksum (u64) */
  BF_MAGIC = 0, BF_VERSION = 8, BF_SOURCE = 12, BF_N = 16, BF_NB = 28, BF_NBRICKS = 40,
  BF_H = 48, BF_ORIGIN = 56, BF_WIDTH = 80, BF_NVERTS = 88, BF_NTRIS = 96, BF_NLIST = 104,
  BF_PSUM = 112, BF_HSUM = 120
};

/* Bytes of the index of nb bricks per axis. */
static inline uint64_t band_index_bytes(const int nb[3])
{
  return 4u * (uint64_t)nb[0] * (uint64_t)nb[1] * (uint64_t)nb[2];
}
static inline uint64_t band_align64(uint64_t n) { return (n + 63u) & ~(uint64_t)63u; }

/* Floats in the samples section: the bricks' samples, or the heights. */
static inline uint64_t band_samples(const int n[3], uint64_t nbricks, int heights)
{
  return heights ? (uint64_t)n[0] * (uint64_t)n[1] : LSDEM_BAND_BRICK_SAMPLES * nbricks;
}
/* Where each section starts (BS_* order) and the file's size. */
enum { BS_PHI = 0, BS_VERTS, BS_TRIS, BS_STARTS, BS_LIST, BS_NBR, BS_COUNT };
static inline uint64_t band_layout(const int nb[3], uint64_t samples, uint64_t nbricks,
                                   uint64_t nverts, uint64_t ntris, uint64_t nlist,
                                   uint64_t off[BS_COUNT])
{
  const uint64_t bytes[BS_COUNT] = {4u * samples, 24u * nverts,
                                    12u * ntris, ntris ? 8u * (nbricks + 1u) : 0u, 4u * nlist,
                                    12u * ntris};
  uint64_t at = BAND_HEADER_SIZE + band_index_bytes(nb);
  for (int k = 0; k < BS_COUNT; k++) {
    off[k] = band_align64(at);
    at = off[k] + bytes[k];
  }
  return at;
}
/* Bricks per axis for n samples: enough bricks of LSDEM_BAND_BRICK cells for n - 1
 * cells. */
static inline int band_bricks_for(int n) { return (n - 2) / LSDEM_BAND_BRICK + 1; }

#endif /* LSDEM_BANDFILE_FORMAT_H */
