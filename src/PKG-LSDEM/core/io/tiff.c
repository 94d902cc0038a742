/* tiff.c -- 3-D images from TIFF files through libtiff (Debian libtiff-dev).
 *
 * libtiff decodes what CT software exports: every compression it is built with (LZW,
 * Deflate, PackBits, JPEG, ZSTD, ...), strips or tiles, classic or BigTIFF, either byte
 * order; a scan is one page per z slice, or a volume in one page (ImageDepth, in tiles one
 * plane deep: libtiff reads no deeper tiles), or pages of volumes stacked in z. This file only walks the pages, checks that they fit
 * together and within the size limits, and copies the decoded samples into place. libtiff's
 * own messages are caught per file (TIFFOpenExt error handler, no global state) and
 * returned with the file, page and what was wrong; its warnings (unknown tags, ...) are
 * not errors and are dropped. */
#define _POSIX_C_SOURCE 200809L /* fseeko, ftello */
#include "lsdem_io.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <tiffio.h>

/* Largest single buffer libtiff may allocate for one file (a strip or tile, a tag array):
 * a hostile header cannot make it reserve more than a slice of the largest volume. */
#define TIFF_MAX_ALLOC ((tmsize_t)1 << 30)

typedef struct {
  const char *path; /* libtiff gives it as the module of some messages: not repeated */
  int failed;
  char msg[200];
} tiff_errors;

static int on_error(TIFF *tif, void *user, const char *module, const char *fmt, va_list ap)
{
  (void)tif;
  tiff_errors *e = user;
  if (!e->failed) { /* the first is the cause; libtiff's module names the codec or step */
    char what[150];
    vsnprintf(what, sizeof what, fmt, ap);
    if (module && *module && strcmp(module, e->path) != 0 &&
        strncmp(what, module, strlen(module)) != 0)
      snprintf(e->msg, sizeof e->msg, "%.40s: %s", module, what);
    else
      snprintf(e->msg, sizeof e->msg, "%s", what);
  }
  e->failed = 1;
  return 1; /* handled: libtiff prints nothing */
}

static int on_warning(TIFF *tif, void *user, const char *module, const char *fmt, va_list ap)
{
  (void)tif, (void)user, (void)module, (void)fmt, (void)ap;
  return 1;
}

/* One page as far as the reader needs it. */
typedef struct {
  uint32_t w, h, d;  /* width, length, depth (ImageDepth, 1 for a slice) */
  uint16_t bits, format, spp;
  int tiled;
  uint32_t tw, th, td; /* tile size */
} tiff_page;

static const char *format_name(uint16_t f)
{
  return f == SAMPLEFORMAT_INT ? "signed" : f == SAMPLEFORMAT_IEEEFP ? "floating-point"
                                                                     : "unsigned";
}

/* Read the current directory's layout; a page this reader cannot use is named. */
static lsdem_status read_page(TIFF *tif, const char *path, int page, tiff_page *p,
                              lsdem_error *err)
{
  memset(p, 0, sizeof *p);
  uint16_t planar = PLANARCONFIG_CONTIG;
  TIFFGetField(tif, TIFFTAG_IMAGEWIDTH, &p->w);
  TIFFGetField(tif, TIFFTAG_IMAGELENGTH, &p->h);
  TIFFGetFieldDefaulted(tif, TIFFTAG_IMAGEDEPTH, &p->d);
  TIFFGetFieldDefaulted(tif, TIFFTAG_BITSPERSAMPLE, &p->bits);
  TIFFGetFieldDefaulted(tif, TIFFTAG_SAMPLEFORMAT, &p->format);
  TIFFGetFieldDefaulted(tif, TIFFTAG_SAMPLESPERPIXEL, &p->spp);
  TIFFGetFieldDefaulted(tif, TIFFTAG_PLANARCONFIG, &planar);
  if (p->format == SAMPLEFORMAT_VOID) p->format = SAMPLEFORMAT_UINT;
  p->tiled = TIFFIsTiled(tif);
  if (p->tiled) {
    p->td = 1;
    TIFFGetField(tif, TIFFTAG_TILEWIDTH, &p->tw);
    TIFFGetField(tif, TIFFTAG_TILELENGTH, &p->th);
    TIFFGetFieldDefaulted(tif, TIFFTAG_TILEDEPTH, &p->td);
  }
  char why[120] = "";
  const int is_int = p->format == SAMPLEFORMAT_UINT || p->format == SAMPLEFORMAT_INT;
  if (p->spp != 1)
    snprintf(why, sizeof why, "%u samples per pixel (a grey-level or label image has 1; "
             "colour images are not read)", p->spp);
  else if (!(is_int && (p->bits == 8 || p->bits == 16 || p->bits == 32)) &&
           !(p->format == SAMPLEFORMAT_IEEEFP && (p->bits == 32 || p->bits == 64)))
    snprintf(why, sizeof why, "%u-bit %s samples (8, 16 or 32-bit integers and 32 or 64-bit "
             "floats are read)", p->bits, p->format <= 3 ? format_name(p->format) : "complex");
  else if (p->w < 1 || p->h < 1 || p->d < 1 || p->w > INT32_MAX || p->h > INT32_MAX)
    snprintf(why, sizeof why, "image size %u x %u x %u", p->w, p->h, p->d);
  else if (p->tiled && (p->tw < 1 || p->th < 1 || p->td < 1 ||
                        (double)p->tw * p->th * p->td > (double)LSDEM_IMAGE_MAX_VOXELS))
    snprintf(why, sizeof why, "tile size %u x %u x %u", p->tw, p->th, p->td);
  else if (!p->tiled && p->d > 1)
    snprintf(why, sizeof why, "a volume of depth %u in strips (volumes are read from tiles, "
             "or from one page per slice)", p->d);
  else if (p->td > 1) /* libtiff sizes and reads a tile as one plane */
    snprintf(why, sizeof why, "tiles %u planes deep (libtiff reads tiles one plane deep)",
             p->td);
  (void)planar; /* with one sample per pixel, contiguous and separate planes are the same */
  if (why[0])
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: page %d: unsupported TIFF: %s", path, page,
                      why);
  return LSDEM_OK;
}

/* Decode the current page into `dst` (w*h*d samples of `bytes` bytes, x fastest). */
static lsdem_status decode_page(TIFF *tif, const tiff_page *p, const char *path, int page,
                                unsigned char *dst, tiff_errors *te, lsdem_error *err)
{
  const size_t bytes = p->bits / 8, row = (size_t)p->w * bytes;
  if (!p->tiled) {
    uint32_t rps = p->h;
    TIFFGetFieldDefaulted(tif, TIFFTAG_ROWSPERSTRIP, &rps);
    if (rps == 0 || rps > p->h) rps = p->h;
    const uint32_t nstrips = TIFFNumberOfStrips(tif), want = (p->h - 1) / rps + 1;
    if (nstrips < want)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: page %d: %u strips for %u rows of %u: "
                        "damaged strip tags", path, page, nstrips, p->h, rps);
    for (uint32_t s = 0; s < want; s++) {
      const uint32_t rows = s + 1 < want ? rps : p->h - s * rps;
      const tmsize_t need = (tmsize_t)(row * rows);
      const tmsize_t got = TIFFReadEncodedStrip(tif, s, dst + row * (size_t)s * rps, need);
      if (got != need || te->failed)
        return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: page %d strip %u: %s", path, page, s,
                          te->failed ? te->msg : "fewer bytes than its rows need (truncated)");
    }
    return LSDEM_OK;
  }
  const tmsize_t tile = TIFFTileSize(tif);
  const size_t want = (size_t)p->tw * p->th * p->td * bytes;
  unsigned char *buf = tile > 0 && (size_t)tile >= want ? malloc((size_t)tile) : NULL;
  if (!buf)
    return lsdem_fail(err, tile > 0 && (size_t)tile >= want ? LSDEM_ERR_NOMEM : LSDEM_ERR_FORMAT,
                      "%s: page %d: tiles of %u x %u x %u samples (%lld bytes): %s", path, page,
                      p->tw, p->th, p->td, (long long)tile,
                      tile > 0 && (size_t)tile >= want ? "out of memory" : "inconsistent");
  lsdem_status st = LSDEM_OK;
  for (uint32_t z0 = 0; st == LSDEM_OK && z0 < p->d; z0 += p->td)
    for (uint32_t y0 = 0; st == LSDEM_OK && y0 < p->h; y0 += p->th)
      for (uint32_t x0 = 0; st == LSDEM_OK && x0 < p->w; x0 += p->tw) {
        if (TIFFReadTile(tif, buf, x0, y0, z0, 0) != tile || te->failed) {
          st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: page %d: tile at (%u, %u, %u): %s", path,
                          page, x0, y0, z0, te->failed ? te->msg : "truncated");
          break;
        }
        const size_t nx = (p->w - x0 < p->tw ? p->w - x0 : p->tw) * bytes;
        for (uint32_t dz = 0; dz < p->td && z0 + dz < p->d; dz++)
          for (uint32_t dy = 0; dy < p->th && y0 + dy < p->h; dy++)
            memcpy(dst + (((size_t)(z0 + dz) * p->h + y0 + dy) * p->w + x0) * bytes,
                   buf + ((size_t)dz * p->th + dy) * p->tw * bytes, nx);
      }
  free(buf);
  return st;
}

void lsdem_volume_free(lsdem_volume *v)
{
  if (!v) return;
  free(v->data);
  memset(v, 0, sizeof *v);
}

const char *lsdem_volume_type_name(const lsdem_volume *v)
{
  static const char *names[3][4] = {{"u8", "u16", "?", "u32"}, {"i8", "i16", "?", "i32"},
                                    {"?", "?", "?", "f32"}};
  if (v->kind == LSDEM_SAMPLE_FLOAT && v->bytes == 8) return "f64";
  return v->bytes >= 1 && v->bytes <= 4 ? names[v->kind][v->bytes - 1] : "?";
}

/* libtiff takes a directory whose link to the next one is cut off for the last page, so
 * a stack truncated there would lose its later slices without a word: check that the
 * current directory, link included, lies within the file. */
static int directory_complete(TIFF *tif, FILE *f, long long file_size)
{
  const int big = TIFFIsBigTIFF(tif);
  const uint64_t off = TIFFCurrentDirOffset(tif), count_bytes = big ? 8 : 2;
  unsigned char c[8];
  if (off + count_bytes > (uint64_t)file_size || fseeko(f, (off_t)off, SEEK_SET) != 0 ||
      fread(c, 1, count_bytes, f) != count_bytes)
    return 0;
  uint64_t n = 0;
  for (uint64_t i = 0; i < count_bytes; i++) /* the count in the file's byte order */
    n |= (uint64_t)c[TIFFIsBigEndian(tif) ? count_bytes - 1 - i : i] << (8 * i);
  const uint64_t end = off + count_bytes + n * (big ? 20 : 12) + (big ? 8 : 4);
  return n < (1u << 20) && end <= (uint64_t)file_size;
}

/* Walk all pages once for their layout: same slice size and sample type everywhere, the
 * stack within the limits. */
static lsdem_status scan_pages(TIFF *tif, FILE *f, long long file_size, const char *path,
                               tiff_errors *te, tiff_page *first, int *npages,
                               long long *depth, lsdem_error *err)
{
  *npages = 0, *depth = 0;
  do {
    tiff_page p;
    if (!directory_complete(tif, f, file_size))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: page %d: its directory runs past the end "
                        "of the file (%lld bytes): truncated", path, *npages, file_size);
    if (*npages == LSDEM_IMAGE_MAX_PAGES)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: more than %d pages (z slices): the page "
                        "chain loops or exceeds the limit", path, LSDEM_IMAGE_MAX_PAGES);
    lsdem_status st = read_page(tif, path, *npages, &p, err);
    if (st != LSDEM_OK) return st;
    if (*npages == 0) *first = p;
    else if (p.w != first->w || p.h != first->h)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: page %d is %u x %u, page 0 is %u x %u: all "
                        "z slices must have the same size", path, *npages, p.w, p.h, first->w,
                        first->h);
    else if (p.bits != first->bits || p.format != first->format)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: page %d has %u-bit %s samples, page 0 "
                        "%u-bit %s: all slices must have one sample type", path, *npages,
                        p.bits, format_name(p.format), first->bits, format_name(first->format));
    *depth += p.d;
    (*npages)++;
    if ((double)first->w * first->h * (double)*depth > (double)LSDEM_IMAGE_MAX_VOXELS)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: %u x %u x %lld voxels (after %d pages) "
                        "exceed the limit of %ld", path, first->w, first->h, *depth, *npages,
                        LSDEM_IMAGE_MAX_VOXELS);
  } while (TIFFReadDirectory(tif));
  /* the chain ended where no further page is announced, or else it broke or looped */
  if (te->failed || !TIFFLastDirectory(tif))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: page %d: %s", path, *npages,
                      te->failed ? te->msg : "cannot be read: the page chain loops or points "
                                             "past the end of the file");
  return LSDEM_OK;
}

/* Open path for reading with this file's handlers: errors into te, warnings dropped,
 * single allocations capped. */
static lsdem_status open_tiff(const char *path, tiff_errors *te, TIFF **tif, lsdem_error *err)
{
  TIFFOpenOptions *opts = TIFFOpenOptionsAlloc();
  if (!opts) return lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: out of memory", path);
  TIFFOpenOptionsSetErrorHandlerExtR(opts, on_error, te);
  TIFFOpenOptionsSetWarningHandlerExtR(opts, on_warning, NULL);
  TIFFOpenOptionsSetMaxSingleMemAlloc(opts, TIFF_MAX_ALLOC);
  *tif = TIFFOpenExt(path, "r", opts);
  TIFFOpenOptionsFree(opts);
  if (!*tif)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: not a readable TIFF file: %s", path,
                      te->failed ? te->msg : "unknown reason");
  return LSDEM_OK;
}

lsdem_status lsdem_tiff_read_volume(const char *path, lsdem_volume *v, lsdem_error *err)
{
  if (!path || !v) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  memset(v, 0, sizeof *v);
  FILE *f = fopen(path, "rb");
  if (!f) return lsdem_fail(err, LSDEM_ERR_IO, "%s: cannot open", path);
  long long file_size = -1;
  if (fseeko(f, 0, SEEK_END) == 0) file_size = (long long)ftello(f);
  tiff_errors te = {path, 0, ""};
  if (file_size < 0) {
    fclose(f);
    return lsdem_fail(err, LSDEM_ERR_IO, "%s: cannot find the file size", path);
  }
  TIFF *tif = NULL;
  const lsdem_status opened = open_tiff(path, &te, &tif, err);
  if (opened != LSDEM_OK) {
    fclose(f);
    return opened;
  }
  tiff_page first = {0}, p = {0};
  int npages = 0;
  long long depth = 0;
  lsdem_status st = scan_pages(tif, f, file_size, path, &te, &first, &npages, &depth, err);
  fclose(f);
  const size_t bytes = first.bits / 8, slice = (size_t)first.w * first.h;
  if (st == LSDEM_OK && !(v->data = malloc(slice * (size_t)depth * bytes)))
    st = lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: cannot allocate %u x %u x %lld samples", path,
                    first.w, first.h, depth);
  size_t z = 0;
  for (int k = 0; st == LSDEM_OK && k < npages; k++) {
    if (!TIFFSetDirectory(tif, (tdir_t)k) || te.failed)
      st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: page %d: %s", path, k,
                      te.failed ? te.msg : "cannot be read again");
    if (st == LSDEM_OK) st = read_page(tif, path, k, &p, err);
    if (st == LSDEM_OK)
      st = decode_page(tif, &p, path, k, (unsigned char *)v->data + z * slice * bytes, &te, err);
    z += p.d;
  }
  TIFFClose(tif);
  if (st != LSDEM_OK) {
    lsdem_volume_free(v);
    return st;
  }
  v->n[0] = (int)first.w, v->n[1] = (int)first.h, v->n[2] = (int)depth;
  v->kind = first.format == SAMPLEFORMAT_INT      ? LSDEM_SAMPLE_INT
            : first.format == SAMPLEFORMAT_IEEEFP ? LSDEM_SAMPLE_FLOAT
                                                  : LSDEM_SAMPLE_UINT;
  v->bytes = (int)bytes;
  return LSDEM_OK;
}

/* Labels from integer samples; unsigned 32-bit values above INT32_MAX fit no label. */
lsdem_status lsdem_image_read_tiff(const char *path, lsdem_label_image *img, lsdem_error *err)
{
  if (!path || !img) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  memset(img, 0, sizeof *img);
  lsdem_volume v;
  lsdem_status st = lsdem_tiff_read_volume(path, &v, err);
  if (st != LSDEM_OK) return st;
  if (v.kind == LSDEM_SAMPLE_FLOAT) {
    st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: %d-bit floating-point samples: a label image "
                    "holds integers (a grey-level scan is segmented first: lsdem-segment)", path,
                    8 * v.bytes);
    lsdem_volume_free(&v);
    return st;
  }
  const size_t count = (size_t)v.n[0] * v.n[1] * v.n[2];
  int32_t *label = v.bytes == 4 ? (int32_t *)v.data : malloc(count * sizeof *label);
  if (!label) st = lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: cannot allocate %zu labels", path, count);
  for (size_t i = 0; st == LSDEM_OK && i < count; i++) {
    const unsigned char *s = (const unsigned char *)v.data + i * v.bytes;
    if (v.bytes == 1) label[i] = v.kind == LSDEM_SAMPLE_INT ? *(const int8_t *)s : *s;
    else if (v.bytes == 2) {
      uint16_t u;
      memcpy(&u, s, 2);
      label[i] = v.kind == LSDEM_SAMPLE_INT ? (int16_t)u : (int32_t)u;
    } else if (v.kind == LSDEM_SAMPLE_UINT && (uint32_t)label[i] > (uint32_t)INT32_MAX)
      st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: voxel value %lu does not fit a label (max "
                      "%ld): wrong type?", path, (unsigned long)(uint32_t)label[i],
                      (long)INT32_MAX);
  }
  if (st == LSDEM_OK) {
    memcpy(img->n, v.n, sizeof img->n);
    img->label = label;
    v.data = label == v.data ? NULL : v.data;
  } else if (label != v.data)
    free(label);
  lsdem_volume_free(&v);
  return st;
}

int lsdem_image_is_tiff(const char *path)
{
  FILE *f = path ? fopen(path, "rb") : NULL;
  if (!f) return 0;
  unsigned char m[4] = {0, 0, 0, 0};
  const size_t got = fread(m, 1, 4, f);
  fclose(f);
  return got == 4 && ((m[0] == 'I' && m[1] == 'I' && (m[2] == 42 || m[2] == 43) && m[3] == 0) ||
                      (m[0] == 'M' && m[1] == 'M' && m[2] == 0 && (m[3] == 42 || m[3] == 43)));
}

/* ------------------------------------------------------ GeoTIFF georeferencing ---- */

/* An array tag of the first page, of `type`, whatever way libtiff knows it: as a field
 * with a 16- or 32-bit count, or (GeoTIFF and GDAL tags, unknown to libtiff) as an
 * anonymous field read with a 32-bit count. 0 when absent or of another type. */
static int tag_array(TIFF *tif, uint32_t tag, TIFFDataType type, uint32_t *count, void **data)
{
  const TIFFField *f = TIFFFindField(tif, tag, TIFF_ANY);
  *count = 0, *data = NULL;
  if (!f || TIFFFieldDataType(f) != type) return 0;
  int ok;
  if (!TIFFFieldPassCount(f)) {
    ok = TIFFGetField(tif, tag, data);
    *count = ok && *data && type == TIFF_ASCII ? (uint32_t)strlen((const char *)*data) + 1 : 0;
  } else if (TIFFFieldReadCount(f) == TIFF_VARIABLE2) {
    ok = TIFFGetField(tif, tag, count, data);
  } else {
    uint16_t c16 = 0;
    ok = TIFFGetField(tif, tag, &c16, data);
    *count = c16;
  }
  return ok && *data && *count > 0;
}

lsdem_status lsdem_tiff_read_georef(const char *path, lsdem_tiff_georef *g, lsdem_error *err)
{
  if (!path || !g) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  memset(g, 0, sizeof *g);
  tiff_errors te = {path, 0, ""};
  TIFF *tif = NULL;
  lsdem_status st = open_tiff(path, &te, &tif, err);
  if (st != LSDEM_OK) return st;
  uint32_t n;
  void *d;
  if (tag_array(tif, 33550, TIFF_DOUBLE, &n, &d) && n >= 2) { /* ModelPixelScaleTag */
    g->has_scale = 1;
    memcpy(g->scale, d, (n < 3 ? n : 3) * sizeof(double));
  }
  if (tag_array(tif, 33922, TIFF_DOUBLE, &n, &d) && n >= 6) { /* ModelTiepointTag */
    g->has_tiepoint = 1;
    memcpy(g->tiepoint, d, 6 * sizeof(double));
  }
  g->has_transform = tag_array(tif, 34264, TIFF_DOUBLE, &n, &d); /* ModelTransformationTag */
  /* GeoKeyDirectoryTag: header of 4 shorts, then (key, location, count, value) quadruples;
   * GTRasterTypeGeoKey (1025) = 2 is PixelIsPoint (1, the default, PixelIsArea) */
  if (tag_array(tif, 34735, TIFF_SHORT, &n, &d) && n >= 4) {
    const uint16_t *k = (const uint16_t *)d;
    for (uint32_t i = 4; i + 3 < n && (i - 4) / 4 < k[3]; i += 4)
      if (k[i] == 1025 && k[i + 1] == 0 && k[i + 3] == 2) g->pixel_is_point = 1;
  }
  if (tag_array(tif, 42113, TIFF_ASCII, &n, &d)) { /* GDAL_NODATA: the value as text */
    char text[64];
    snprintf(text, sizeof text, "%.*s", (int)(n < sizeof text ? n : sizeof text - 1),
             (const char *)d);
    char *end;
    const double v = strtod(text, &end);
    while (*end == ' ') end++;
    if (end == text || *end != '\0') {
      TIFFClose(tif);
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: GDAL_NODATA tag (42113) '%s' is not a "
                        "number", path, text);
    }
    g->has_nodata = 1;
    g->nodata = v;
  }
  TIFFClose(tif);
  return LSDEM_OK;
}
