/* imageio.c -- labelled 3-D images from raw binary files and multi-page TIFF.
 *
 * Both readers face files from elsewhere: every size is checked against the file before
 * it is used, every offset before it is dereferenced, and every failure names the file
 * and what was wrong. The TIFF reader implements the baseline subset a segmentation
 * export uses (uncompressed strips of 8/16/32-bit unsigned grey, one page per z slice). */
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

/* ------------------------------------------------------------------ TIFF ---- */

enum {
  TAG_WIDTH = 256, TAG_LENGTH = 257, TAG_BITS = 258, TAG_COMPRESSION = 259,
  TAG_STRIP_OFFSETS = 273, TAG_SAMPLES = 277, TAG_ROWS_PER_STRIP = 278,
  TAG_STRIP_BYTES = 279, TAG_PLANAR = 284, TAG_TILE_WIDTH = 322, TAG_SAMPLE_FORMAT = 339
};
enum { TIFF_SHORT = 3, TIFF_LONG = 4 };

/* The whole file in memory with its byte order: all reads go through `fetch`. */
typedef struct {
  const unsigned char *b;
  size_t size;
  int big;
  const char *path;
} tiff_file;

static int fetch(const tiff_file *t, size_t off, size_t bytes, uint32_t *v)
{
  if (off > t->size || bytes > t->size - off) return 0;
  *v = load_uint(t->b + off, bytes, t->big);
  return 1;
}

/* One directory entry's field: type, count and where its values are. */
typedef struct {
  uint32_t tag, type, count;
  size_t at; /* offset of the first value */
} tiff_field;

typedef struct {
  uint32_t width, length, bits, compression, samples, rows_per_strip, planar, format;
  tiff_field offsets, bytecounts;
  int have_offsets, have_bytecounts, tiled;
  uint32_t next; /* offset of the next IFD, 0 at the end */
} tiff_page;

/* Value i of a SHORT or LONG field. */
static lsdem_status field_value(const tiff_file *t, const tiff_field *f, uint32_t i, uint32_t *v,
                                lsdem_error *err)
{
  const size_t sz = f->type == TIFF_SHORT ? 2 : 4;
  if (f->type != TIFF_SHORT && f->type != TIFF_LONG)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: tag %u has type %u, expected SHORT or LONG",
                      t->path, f->tag, f->type);
  if (i >= f->count || !fetch(t, f->at + sz * i, sz, v))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: tag %u value %u lies past the end of the "
                      "file", t->path, f->tag, i);
  return LSDEM_OK;
}

/* Read the entry at `off`: values of <= 4 bytes sit inline, others at a checked offset. */
static lsdem_status read_field(const tiff_file *t, size_t off, tiff_field *f, lsdem_error *err)
{
  uint32_t tag, type, count, ptr;
  if (!fetch(t, off, 2, &tag) || !fetch(t, off + 2, 2, &type) || !fetch(t, off + 4, 4, &count) ||
      !fetch(t, off + 8, 4, &ptr))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: directory entry at byte %zu is truncated",
                      t->path, off);
  f->tag = tag, f->type = type, f->count = count;
  const uint64_t sz = type == TIFF_SHORT ? 2 : 4;
  const uint64_t bytes = sz * count;
  f->at = bytes <= 4 ? off + 8 : ptr;
  if ((type == TIFF_SHORT || type == TIFF_LONG) && (f->at > t->size || bytes > t->size - f->at))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: tag %u: %u values at byte %zu run past the "
                      "end of the file (%zu bytes)", t->path, tag, count, f->at, t->size);
  return LSDEM_OK;
}

/* A scalar tag (count 1) into *v. */
static lsdem_status scalar(const tiff_file *t, const tiff_field *f, uint32_t *v, lsdem_error *err)
{
  if (f->count != 1)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: tag %u has %u values, expected 1%s", t->path,
                      f->tag, f->count, f->tag == TAG_BITS ? " (one sample per pixel)" : "");
  return field_value(t, f, 0, v, err);
}

static lsdem_status parse_ifd(const tiff_file *t, uint32_t off, tiff_page *p, lsdem_error *err)
{
  memset(p, 0, sizeof *p);
  p->compression = p->samples = p->planar = p->format = 1;
  p->rows_per_strip = UINT32_MAX;
  uint32_t n;
  if (!fetch(t, off, 2, &n) || (uint64_t)off + 2 + 12ull * n + 4 > t->size)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: image directory at byte %u runs past the end "
                      "of the file (%zu bytes)", t->path, off, t->size);
  for (uint32_t e = 0; e < n; e++) {
    tiff_field f;
    lsdem_status st = read_field(t, (size_t)off + 2 + 12 * (size_t)e, &f, err);
    if (st != LSDEM_OK) return st;
    uint32_t *dst = NULL;
    switch (f.tag) {
    case TAG_WIDTH: dst = &p->width; break;
    case TAG_LENGTH: dst = &p->length; break;
    case TAG_BITS: dst = &p->bits; break;
    case TAG_COMPRESSION: dst = &p->compression; break;
    case TAG_SAMPLES: dst = &p->samples; break;
    case TAG_ROWS_PER_STRIP: dst = &p->rows_per_strip; break;
    case TAG_PLANAR: dst = &p->planar; break;
    case TAG_SAMPLE_FORMAT: dst = &p->format; break;
    case TAG_STRIP_OFFSETS: p->offsets = f, p->have_offsets = 1; break;
    case TAG_STRIP_BYTES: p->bytecounts = f, p->have_bytecounts = 1; break;
    case TAG_TILE_WIDTH: p->tiled = 1; break;
    default: break;
    }
    if (dst && (st = scalar(t, &f, dst, err)) != LSDEM_OK) return st;
  }
  fetch(t, (size_t)off + 2 + 12 * (size_t)n, 4, &p->next);
  return LSDEM_OK;
}

/* Reject what this reader does not decode, naming it. */
static lsdem_status check_page(const tiff_file *t, const tiff_page *p, int page,
                               lsdem_error *err)
{
  const char *why = NULL;
  char buf[96];
  if (p->compression != 1)
    snprintf(buf, sizeof buf, "compression %u (only uncompressed, 1, is read)", p->compression),
        why = buf;
  else if (p->tiled) why = "tiled layout (only strips are read)";
  else if (p->samples != 1)
    snprintf(buf, sizeof buf, "%u samples per pixel (labels need 1)", p->samples), why = buf;
  else if (p->bits != 8 && p->bits != 16 && p->bits != 32)
    snprintf(buf, sizeof buf, "%u bits per sample (8, 16 or 32 are read)", p->bits), why = buf;
  else if (p->format != 1)
    snprintf(buf, sizeof buf, "sample format %u (only unsigned integers, 1, are read)",
             p->format), why = buf;
  else if (p->width < 1 || p->length < 1 || p->width > INT32_MAX || p->length > INT32_MAX)
    snprintf(buf, sizeof buf, "image size %u x %u", p->width, p->length), why = buf;
  else if (!p->have_offsets || !p->have_bytecounts)
    why = "no strip offsets or strip byte counts";
  if (why) return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: page %d: unsupported TIFF: %s", t->path,
                             page, why);
  return LSDEM_OK;
}

/* Decode one page's strips into slice z of the image. */
static lsdem_status decode_page(const tiff_file *t, const tiff_page *p, int page,
                                int32_t *slice, lsdem_error *err)
{
  const uint32_t rps = p->rows_per_strip == 0 || p->rows_per_strip > p->length
                           ? p->length : p->rows_per_strip;
  const uint32_t nstrips = (p->length - 1) / rps + 1;
  if (p->offsets.count != nstrips || p->bytecounts.count != nstrips)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: page %d: %u strip offsets and %u byte counts "
                      "for %u strips", t->path, page, p->offsets.count, p->bytecounts.count,
                      nstrips);
  const lsdem_voxel_type type = p->bits == 8 ? LSDEM_VOXEL_U8 : p->bits == 16 ? LSDEM_VOXEL_U16
                                                                              : LSDEM_VOXEL_U32;
  const size_t row_bytes = (size_t)p->width * (p->bits / 8);
  for (uint32_t s = 0; s < nstrips; s++) {
    uint32_t off, bytes;
    lsdem_status st = field_value(t, &p->offsets, s, &off, err);
    if (st == LSDEM_OK) st = field_value(t, &p->bytecounts, s, &bytes, err);
    if (st != LSDEM_OK) return st;
    const uint32_t rows = s + 1 < nstrips ? rps : p->length - s * rps;
    const size_t need = row_bytes * rows;
    if (bytes < need || off > t->size || need > t->size - off)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: page %d strip %u: %zu bytes needed at byte "
                        "%u, the strip holds %u and the file %zu: truncated", t->path, page, s,
                        need, off, bytes, t->size);
    st = decode_values(t->b + off, (size_t)p->width * rows, type, t->big,
                       slice + (size_t)s * rps * p->width, t->path, err);
    if (st != LSDEM_OK) return st;
  }
  return LSDEM_OK;
}

/* Walk the IFD chain: every page checked, equal sizes; offsets of the pages into *ifds. */
static lsdem_status list_pages(const tiff_file *t, uint32_t first, uint32_t **ifds, int *npages,
                               lsdem_error *err)
{
  /* a directory takes >= 18 bytes, so a longer chain than this must revisit one */
  const size_t limit_file = t->size / 18 + 1;
  const size_t limit = limit_file < LSDEM_IMAGE_MAX_PAGES ? limit_file : LSDEM_IMAGE_MAX_PAGES;
  *ifds = malloc(limit * sizeof(uint32_t));
  if (!*ifds) return lsdem_fail(err, LSDEM_ERR_NOMEM, "out of memory");
  tiff_page first_page, p;
  size_t n = 0;
  for (uint32_t off = first; off != 0; off = p.next) {
    if (n == limit)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: more than %zu image directories: the chain "
                        "loops or exceeds the page limit", t->path, limit);
    if (n > 0 && off == (*ifds)[n - 1])
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: image directory at byte %u points to "
                        "itself", t->path, off);
    lsdem_status st = parse_ifd(t, off, &p, err);
    if (st == LSDEM_OK) st = check_page(t, &p, (int)n, err);
    if (st != LSDEM_OK) return st;
    if (n == 0) first_page = p;
    else if (p.width != first_page.width || p.length != first_page.length)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: page %zu is %u x %u, page 0 is %u x %u: all "
                        "z slices must have the same size", t->path, n, p.width, p.length,
                        first_page.width, first_page.length);
    (*ifds)[n++] = off;
  }
  if (n == 0) return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: no image directory", t->path);
  *npages = (int)n;
  return LSDEM_OK;
}

static lsdem_status read_tiff_data(const tiff_file *t, lsdem_label_image *img, lsdem_error *err)
{
  uint32_t magic, first;
  if (!fetch(t, 2, 2, &magic) || !fetch(t, 4, 4, &first))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: truncated TIFF header", t->path);
  if (magic == 43)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: BigTIFF is not supported", t->path);
  if (magic != 42) return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: not a TIFF file", t->path);
  uint32_t *ifds = NULL;
  int npages = 0;
  lsdem_status st = list_pages(t, first, &ifds, &npages, err);
  tiff_page p;
  if (st == LSDEM_OK) st = parse_ifd(t, ifds[0], &p, err);
  if (st == LSDEM_OK) {
    const int n[3] = {(int)p.width, (int)p.length, npages};
    st = alloc_image(img, n, t->path, err);
  }
  const size_t slice = st == LSDEM_OK ? (size_t)img->n[0] * img->n[1] : 0;
  for (int z = 0; st == LSDEM_OK && z < npages; z++) {
    st = parse_ifd(t, ifds[z], &p, err);
    if (st == LSDEM_OK) st = decode_page(t, &p, z, img->label + slice * z, err);
  }
  free(ifds);
  return st;
}

int lsdem_image_is_tiff(const char *path)
{
  FILE *f = path ? fopen(path, "rb") : NULL;
  if (!f) return 0;
  unsigned char m[4] = {0, 0, 0, 0};
  const size_t got = fread(m, 1, 4, f);
  fclose(f);
  return got == 4 && ((m[0] == 'I' && m[1] == 'I' && m[2] == 42 && m[3] == 0) ||
                      (m[0] == 'M' && m[1] == 'M' && m[2] == 0 && m[3] == 42));
}

lsdem_status lsdem_image_read_tiff(const char *path, lsdem_label_image *img, lsdem_error *err)
{
  if (!path || !img) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  memset(img, 0, sizeof *img);
  unsigned char *data = NULL;
  size_t size = 0;
  lsdem_status st =
      lsdem_read_file(path, 4 * (size_t)LSDEM_IMAGE_MAX_VOXELS + (1u << 24), &data, &size, err);
  if (st != LSDEM_OK) return st;
  tiff_file t = {data, size, 0, path};
  if (size < 8 || !((data[0] == 'I' && data[1] == 'I') || (data[0] == 'M' && data[1] == 'M')))
    st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: not a TIFF file (no II/MM byte-order mark)", path);
  else {
    t.big = data[0] == 'M';
    st = read_tiff_data(&t, img, err);
  }
  free(data);
  if (st != LSDEM_OK) lsdem_label_image_free(img);
  return st;
}
