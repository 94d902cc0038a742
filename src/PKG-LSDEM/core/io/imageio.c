/* imageio.c -- labelled 3-D images from raw binary files (TIFF: tiff.c, through libtiff).
 *
 * The reader faces files from elsewhere: the file size is checked against the stated
 * dimensions before anything is read, and every failure names the file and what was
 * wrong. */
#include "lsdem_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void lsdem_label_image_free(lsdem_label_image *img)
{
  if (!img) return;
  free(img->label);
  img->label = NULL;
  img->n[0] = img->n[1] = img->n[2] = 0;
}

static size_t type_bytes(lsdem_voxel_type t)
{
  return t == LSDEM_VOXEL_U8 ? 1 : t == LSDEM_VOXEL_U16 ? 2 : 4;
}

/* One value of `bytes` (1, 2, 4) bytes in the given byte order, unsigned. */
static uint32_t load_uint(const unsigned char *p, size_t bytes, int big_endian)
{
  uint32_t v = 0;
  for (size_t i = 0; i < bytes; i++) {
    const size_t at = big_endian ? i : bytes - 1 - i;
    v = v << 8 | p[at];
  }
  return v;
}

/* Convert `count` stored values to labels; u32 above INT32_MAX does not fit a label. */
static lsdem_status decode_values(const unsigned char *src, size_t count, lsdem_voxel_type t,
                                  int big_endian, int32_t *dst, const char *path,
                                  lsdem_error *err)
{
  const size_t b = type_bytes(t);
  for (size_t i = 0; i < count; i++) {
    const uint32_t v = load_uint(src + b * i, b, big_endian);
    if (t == LSDEM_VOXEL_U32 && v > (uint32_t)INT32_MAX)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: voxel value %lu does not fit a label "
                        "(max %ld): wrong type?", path, (unsigned long)v, (long)INT32_MAX);
    dst[i] = (int32_t)v; /* for I32 this is the two's-complement reinterpretation */
  }
  return LSDEM_OK;
}

/* Size of an open file; -1 if it cannot be found. */
static long long file_size(FILE *f)
{
  if (fseek(f, 0, SEEK_END) != 0) return -1;
  const long long n = ftell(f);
  if (fseek(f, 0, SEEK_SET) != 0) return -1;
  return n;
}

static lsdem_status alloc_image(lsdem_label_image *img, const int n[3], const char *path,
                                lsdem_error *err)
{
  const long long slice = (long long)n[0] * n[1]; /* n[] <= INT32_MAX: no overflow */
  const long long total = slice > LSDEM_IMAGE_MAX_VOXELS ? slice : slice * n[2];
  if (slice > LSDEM_IMAGE_MAX_VOXELS || total > LSDEM_IMAGE_MAX_VOXELS)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: %d x %d x %d = %lld voxels exceed the "
                      "limit of %ld", path, n[0], n[1], n[2], total, LSDEM_IMAGE_MAX_VOXELS);
  img->label = malloc((size_t)total * sizeof(int32_t));
  if (!img->label)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: cannot allocate %lld voxels", path, total);
  memcpy(img->n, n, sizeof img->n);
  return LSDEM_OK;
}

/* ------------------------------------------------------------------- raw ---- */

lsdem_status lsdem_image_read_raw(const char *path, const int n[3], lsdem_voxel_type type,
                                  int big_endian, lsdem_label_image *img, lsdem_error *err)
{
  if (!path || !n || !img) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  memset(img, 0, sizeof *img);
  if (type < LSDEM_VOXEL_U8 || type > LSDEM_VOXEL_I32)
    return lsdem_fail(err, LSDEM_ERR_ARG, "unknown voxel type %d", (int)type);
  for (int a = 0; a < 3; a++)
    if (n[a] < 1)
      return lsdem_fail(err, LSDEM_ERR_ARG, "image dimension %d is %d: must be >= 1", a, n[a]);
  if ((double)n[0] * n[1] * n[2] > (double)LSDEM_IMAGE_MAX_VOXELS)
    return lsdem_fail(err, LSDEM_ERR_ARG, "%d x %d x %d voxels exceed the limit of %ld", n[0],
                      n[1], n[2], LSDEM_IMAGE_MAX_VOXELS);
  FILE *f = fopen(path, "rb");
  if (!f) return lsdem_fail(err, LSDEM_ERR_IO, "%s: cannot open", path);
  const size_t b = type_bytes(type);
  const long long want = (long long)n[0] * n[1] * n[2] * (long long)b;
  const long long have = file_size(f);
  lsdem_status st = LSDEM_OK;
  if (have < 0) st = lsdem_fail(err, LSDEM_ERR_IO, "%s: cannot find the file size", path);
  else if (have != want)
    st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: %lld bytes, but %d x %d x %d voxels of %zu "
                    "byte%s need %lld (%s): wrong dimensions or type?", path, have, n[0], n[1],
                    n[2], b, b == 1 ? "" : "s", want, have < want ? "truncated" : "too long");
  if (st == LSDEM_OK) st = alloc_image(img, n, path, err);
  /* read and convert slab by slab */
  enum { CHUNK = 1 << 16 };
  unsigned char *buf = st == LSDEM_OK ? malloc(CHUNK * 4) : NULL;
  if (st == LSDEM_OK && !buf) st = lsdem_fail(err, LSDEM_ERR_NOMEM, "out of memory");
  const size_t total = st == LSDEM_OK ? (size_t)n[0] * n[1] * n[2] : 0;
  for (size_t done = 0; st == LSDEM_OK && done < total;) {
    const size_t m = total - done < CHUNK ? total - done : CHUNK;
    if (fread(buf, b, m, f) != m)
      st = lsdem_fail(err, LSDEM_ERR_IO, "%s: read failed at voxel %zu", path, done);
    else
      st = decode_values(buf, m, type, big_endian, img->label + done, path, err);
    done += m;
  }
  free(buf);
  fclose(f);
  if (st != LSDEM_OK) lsdem_label_image_free(img);
  return st;
}
