/* bandfile.c -- band files (a wall's narrow band, lsdem_band) mapped read-only: ranks on
 * one machine share one copy through the page cache (format: bandfile_format.h,
 * doc/wall_band.rst; writer prep/band_write.c). */
#include "bandfile_format.h"
#include "filemap.h"
#include "lsdem_geom.h"

#include <stdlib.h>

struct lsdem_band_file {
  void *map;
  size_t size;
  uint16_t *far; /* the band's coarse level, made at open (per process, 2 bytes a slot) */
  float *tiles;  /* heights: the tiles' height ranges, made at open */
  lsdem_band band;
  lsdem_band_source source;
};

/* The header's fields into f->band (pointers not yet set), checked against the file's
 * size: magic, version, header checksum, counts, the arrays' extents. */
static lsdem_status read_header(lsdem_band_file *f, const char *path, lsdem_error *err)
{
  const unsigned char *m = (const unsigned char *)f->map;
  if (memcmp(m + BF_MAGIC, BAND_MAGIC, sizeof BAND_MAGIC) != 0)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "band file '%s': not a band file (no LSDEMBND "
                      "magic; made by lsdem-shape wall or terrain)", path);
  if (get_u32(m + BF_VERSION) != BAND_VERSION)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "band file '%s': version %u, this reader knows %d",
                      path, get_u32(m + BF_VERSION), BAND_VERSION);
  if (fnv1a_update(FNV_BASIS, m, BF_HSUM) != get_u64(m + BF_HSUM))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "band file '%s': header checksum mismatch (the "
                      "file is damaged; make it again)", path);
  lsdem_band *b = &f->band;
  const uint32_t source = get_u32(m + BF_SOURCE);
  if (source > LSDEM_BAND_HEIGHTS)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "band file '%s': unknown source %u", path, source);
  f->source = (lsdem_band_source)source;
  const int heights = source == LSDEM_BAND_HEIGHTS;
  for (int a = 0; a < 3; a++) {
    b->n[a] = get_i32(m + BF_N + 4 * a);
    b->nb[a] = get_i32(m + BF_NB + 4 * a);
    b->origin[a] = get_f64(m + BF_ORIGIN + 8 * a);
    const int n_ok = heights ? (a < 2 ? b->n[a] >= 2 : b->n[a] == 1) : b->n[a] >= 2;
    if (!n_ok || b->nb[a] != (heights ? 0 : band_bricks_for(b->n[a])))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "band file '%s': %d samples and %d bricks along "
                        "axis %d do not match", path, b->n[a], b->nb[a], a);
  }
  b->h = get_f64(m + BF_H);
  b->width = get_f64(m + BF_WIDTH);
  const uint64_t nbricks = get_u64(m + BF_NBRICKS), nverts = get_u64(m + BF_NVERTS);
  const uint64_t ntris = get_u64(m + BF_NTRIS), nlist = get_u64(m + BF_NLIST);
  if (nbricks > (uint64_t)INT32_MAX || nverts > (uint64_t)INT32_MAX ||
      ntris > (uint64_t)INT32_MAX || nlist > ((uint64_t)1 << 40) || (ntris == 0) != (nlist == 0) ||
      (heights && (nbricks || ntris)))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "band file '%s': counts out of range (%llu "
                      "bricks, %llu vertices, %llu triangles, %llu list entries)", path,
                      (unsigned long long)nbricks, (unsigned long long)nverts,
                      (unsigned long long)ntris, (unsigned long long)nlist);
  uint64_t off[BS_COUNT];
  const uint64_t end = band_layout(b->nb, band_samples(b->n, nbricks, heights), nbricks, nverts,
                                   ntris, nlist, off);
  if (end != (uint64_t)f->size)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "band file '%s': %zu bytes, expected %llu for "
                      "%llu bricks and %llu triangles (truncated or damaged)", path, f->size,
                      (unsigned long long)end, (unsigned long long)nbricks,
                      (unsigned long long)ntris);
  b->nbricks = (int64_t)nbricks;
  b->index = heights ? NULL : (const int32_t *)(m + BAND_HEADER_SIZE);
  b->phi = heights ? NULL : (const float *)(m + off[BS_PHI]);
  b->heights = heights ? (const float *)(m + off[BS_PHI]) : NULL;
  b->nverts = (int64_t)nverts;
  b->ntris = (int64_t)ntris;
  b->verts = ntris ? (const double *)(m + off[BS_VERTS]) : NULL;
  b->tris = ntris ? (const int32_t *)(m + off[BS_TRIS]) : NULL;
  b->brick_tri_start = ntris ? (const int64_t *)(m + off[BS_STARTS]) : NULL;
  b->brick_tris = ntris ? (const int32_t *)(m + off[BS_LIST]) : NULL;
  b->nbr = ntris ? (const int32_t *)(m + off[BS_NBR]) : NULL;
  return LSDEM_OK;
}

lsdem_status lsdem_band_open(const char *path, lsdem_band_file **out, lsdem_error *err)
{
  if (!path || !out) return lsdem_fail(err, LSDEM_ERR_ARG, "band file: NULL argument");
  *out = NULL;
  if (!host_is_little_endian())
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "band file '%s': this big-endian host cannot map "
                      "the little-endian format", path);
  lsdem_band_file *f = (lsdem_band_file *)calloc(1, sizeof *f);
  if (!f) return lsdem_fail(err, LSDEM_ERR_NOMEM, "band file '%s': out of memory", path);
  lsdem_status st = lsdem_map_file(path, "band file", BAND_HEADER_SIZE, &f->map, &f->size, err);
  if (st == LSDEM_OK) st = read_header(f, path, err);
  if (st == LSDEM_OK) {
    const unsigned char *m = (const unsigned char *)f->map;
    const uint64_t sum = fnv1a_update(FNV_BASIS, m + BAND_HEADER_SIZE, f->size - BAND_HEADER_SIZE);
    if (sum != get_u64(m + BF_PSUM))
      st = lsdem_fail(err, LSDEM_ERR_FORMAT, "band file '%s': payload checksum mismatch (the "
                      "file is damaged; make it again)", path);
  }
  if (st == LSDEM_OK) {
    lsdem_error inner;
    st = lsdem_band_check(&f->band, &inner);
    if (st != LSDEM_OK) st = lsdem_fail(err, st, "band file '%s': %s", path, inner.msg);
  }
  if (st == LSDEM_OK && f->band.heights)
    st = lsdem_heights_tiles(&f->band, &f->tiles, f->band.nt, err);
  else if (st == LSDEM_OK)
    st = lsdem_band_far(&f->band, &f->far, err);
  f->band.far = f->far;
  f->band.tile_range = f->tiles;
  if (st != LSDEM_OK) {
    lsdem_band_close(f);
    return st;
  }
  *out = f;
  return LSDEM_OK;
}

void lsdem_band_close(lsdem_band_file *f)
{
  if (!f) return;
  lsdem_unmap_file(f->map, f->size);
  free(f->far);
  free(f->tiles);
  free(f);
}

const lsdem_band *lsdem_band_file_band(const lsdem_band_file *f) { return &f->band; }
lsdem_band_source lsdem_band_file_source(const lsdem_band_file *f) { return f->source; }
