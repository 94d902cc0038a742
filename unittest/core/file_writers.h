/* file_writers.h -- small writers of the binary formats the readers take (multi-page
 * TIFF by hand and through libtiff's writer, ASCII and binary STL), shared by the reader
 * tests and the mutation test (unittest/fuzz/mutate_readers.c) so that both start from the
 * same valid files. */
#ifndef LSDEM_FILE_WRITERS_H
#define LSDEM_FILE_WRITERS_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <tiffio.h>

/* ------------------------------------------------------------------ TIFF ---- */

typedef struct {
  unsigned char *b;
  size_t n, cap;
  int big;
} bytes;

static inline void put(bytes *o, uint32_t v, int size)
{
  if (o->n + 4 > o->cap) {
    o->cap = 2 * o->cap + 64;
    o->b = realloc(o->b, o->cap);
  }
  for (int i = 0; i < size; i++) {
    const int shift = 8 * (o->big ? size - 1 - i : i);
    o->b[o->n++] = (unsigned char)(v >> shift);
  }
}

static inline void set32(bytes *o, size_t at, uint32_t v)
{
  for (int i = 0; i < 4; i++) o->b[at + i] = (unsigned char)(v >> (8 * (o->big ? 3 - i : i)));
}

static inline void write_file_bytes(const char *path, const void *b, size_t n)
{
  FILE *f = fopen(path, "wb");
  fwrite(b, 1, n, f);
  fclose(f);
}

typedef struct {
  int big, bits, rows_per_strip, compression, format;
} tiff_opts;

/* A multi-page TIFF of n[0] x n[1] pages, one per z; returns the bytes; *ifd0 and *ifd_last
 * receive the offsets of the first and last directories' "next" fields. */
static inline bytes make_tiff(const int n[3], const uint32_t *v, tiff_opts o, size_t *next_first,
                       size_t *next_last)
{
  bytes t = {NULL, 0, 0, o.big};
  put(&t, o.big ? 0x4d4d : 0x4949, 2);
  put(&t, 42, 2);
  const size_t first_ptr = t.n;
  put(&t, 0, 4);
  const int bpp = o.bits / 8, rps = o.rows_per_strip;
  const int nstrips = (n[1] + rps - 1) / rps;
  size_t prev_next = first_ptr;
  for (int z = 0; z < n[2]; z++) {
    /* pixel data of this page first, strip by strip */
    uint32_t *off = malloc(sizeof(uint32_t) * nstrips), *cnt = malloc(sizeof(uint32_t) * nstrips);
    for (int s = 0; s < nstrips; s++) {
      off[s] = (uint32_t)t.n;
      const int rows = (s + 1) * rps <= n[1] ? rps : n[1] - s * rps;
      for (int j = s * rps; j < s * rps + rows; j++)
        for (int i = 0; i < n[0]; i++) put(&t, v[((size_t)z * n[1] + j) * n[0] + i], bpp);
      cnt[s] = (uint32_t)(rows * n[0] * bpp);
    }
    size_t arrays = 0;
    if (nstrips > 1) { /* out-of-line strip arrays */
      arrays = t.n;
      for (int s = 0; s < nstrips; s++) put(&t, off[s], 4);
      for (int s = 0; s < nstrips; s++) put(&t, cnt[s], 4);
    }
    if (t.n % 2) put(&t, 0, 1);
    set32(&t, prev_next, (uint32_t)t.n);
    const int nent = 10;
    put(&t, nent, 2);
#define ENTRY(tag, type, count, value)                                                  \
  do {                                                                                  \
    put(&t, tag, 2), put(&t, type, 2), put(&t, count, 4);                               \
    if (type == 3 && (count) == 1) put(&t, value, 2), put(&t, 0, 2);                    \
    else put(&t, value, 4);                                                             \
  } while (0)
    ENTRY(256, 4, 1, (uint32_t)n[0]);
    ENTRY(257, 4, 1, (uint32_t)n[1]);
    ENTRY(258, 3, 1, (uint32_t)o.bits);
    ENTRY(259, 3, 1, (uint32_t)o.compression);
    ENTRY(262, 3, 1, 1u);
    ENTRY(273, 4, (uint32_t)nstrips, nstrips > 1 ? (uint32_t)arrays : off[0]);
    ENTRY(277, 3, 1, 1u);
    ENTRY(278, 4, 1, (uint32_t)rps);
    ENTRY(279, 4, (uint32_t)nstrips, nstrips > 1 ? (uint32_t)(arrays + 4 * nstrips) : cnt[0]);
    ENTRY(339, 3, 1, (uint32_t)o.format);
#undef ENTRY
    prev_next = t.n;
    if (z == 0 && next_first) *next_first = t.n;
    put(&t, 0, 4);
    free(off);
    free(cnt);
  }
  if (next_last) *next_last = prev_next;
  return t;
}

/* A TIFF written by libtiff itself (its encoders, not ours): n[0] x n[1] x n[2] values v,
 * as `bits`-bit samples of `format` (SAMPLEFORMAT_UINT/INT/IEEEFP), compressed with
 * `compression` (COMPRESSION_NONE, _LZW, _ADOBE_DEFLATE, _PACKBITS, ...), in strips of
 * 2 rows or in 16 x 16 tiles, classic or BigTIFF, either byte
 * order; one page per z slice, or (volume) all slices in one tiled page with ImageDepth.
 * Returns 0 when libtiff refused. */
typedef struct {
  int bits, format, compression, tiled, bigtiff, big_endian, volume;
} libtiff_opts;

static inline int write_tiff_libtiff(const char *path, const int n[3], const uint32_t *v,
                                     libtiff_opts o)
{
  char mode[8] = "w";
  if (o.bigtiff) strcat(mode, "8");
  strcat(mode, o.big_endian ? "b" : "l");
  TIFF *t = TIFFOpen(path, mode);
  if (!t) return 0;
  const int bytes = o.bits / 8, pages = o.volume ? 1 : n[2], depth = o.volume ? n[2] : 1;
  const size_t slice = (size_t)n[0] * n[1];
  unsigned char *buf = malloc(slice * n[2] * bytes + 16 * 16 * 4 * 8);
  int ok = buf != NULL;
  for (int z = 0; ok && z < pages; z++) {
    TIFFSetField(t, TIFFTAG_IMAGEWIDTH, (uint32_t)n[0]);
    TIFFSetField(t, TIFFTAG_IMAGELENGTH, (uint32_t)n[1]);
    if (o.volume) TIFFSetField(t, TIFFTAG_IMAGEDEPTH, (uint32_t)depth);
    TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, (uint16_t)o.bits);
    TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, (uint16_t)o.format);
    TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, (uint16_t)1);
    TIFFSetField(t, TIFFTAG_PHOTOMETRIC, (uint16_t)PHOTOMETRIC_MINISBLACK);
    TIFFSetField(t, TIFFTAG_PLANARCONFIG, (uint16_t)PLANARCONFIG_CONTIG);
    TIFFSetField(t, TIFFTAG_COMPRESSION, (uint16_t)o.compression);
    if (o.compression == COMPRESSION_LZW || o.compression == COMPRESSION_ADOBE_DEFLATE)
      TIFFSetField(t, TIFFTAG_PREDICTOR, (uint16_t)(o.format == SAMPLEFORMAT_IEEEFP ? 1 : 2));
    /* samples of this page (or volume) in host order */
    for (size_t i = 0; i < slice * depth; i++) {
      const uint32_t x = v[(size_t)z * slice + i];
      unsigned char *d = buf + i * bytes;
      if (o.format == SAMPLEFORMAT_IEEEFP && bytes == 4) {
        const float f = (float)x;
        memcpy(d, &f, 4);
      } else if (o.format == SAMPLEFORMAT_IEEEFP) {
        const double f = (double)x;
        memcpy(d, &f, 8);
      } else if (bytes == 1) *d = (unsigned char)x;
      else if (bytes == 2) {
        const uint16_t u = (uint16_t)x;
        memcpy(d, &u, 2);
      } else memcpy(d, &x, 4);
    }
    if (o.tiled) {
      const uint32_t tw = 16, th = 16, td = 1; /* libtiff handles tiles one plane deep */
      TIFFSetField(t, TIFFTAG_TILEWIDTH, tw);
      TIFFSetField(t, TIFFTAG_TILELENGTH, th);
      unsigned char *tile = malloc((size_t)tw * th * td * bytes);
      ok = tile != NULL;
      for (uint32_t z0 = 0; ok && z0 < (uint32_t)depth; z0 += td)
        for (uint32_t y0 = 0; ok && y0 < (uint32_t)n[1]; y0 += th)
          for (uint32_t x0 = 0; ok && x0 < (uint32_t)n[0]; x0 += tw) {
            memset(tile, 0, (size_t)tw * th * td * bytes);
            for (uint32_t k = 0; k < td && z0 + k < (uint32_t)depth; k++)
              for (uint32_t j = 0; j < th && y0 + j < (uint32_t)n[1]; j++)
                for (uint32_t i = 0; i < tw && x0 + i < (uint32_t)n[0]; i++)
                  memcpy(tile + (((size_t)k * th + j) * tw + i) * bytes,
                         buf + (((size_t)(z0 + k) * n[1] + y0 + j) * n[0] + x0 + i) * bytes,
                         bytes);
            ok = TIFFWriteTile(t, tile, x0, y0, z0, 0) >= 0;
          }
      free(tile);
    } else {
      TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, (uint32_t)2);
      for (int s = 0; ok && 2 * s < n[1]; s++) {
        const int rows = 2 * s + 2 <= n[1] ? 2 : n[1] - 2 * s;
        ok = TIFFWriteEncodedStrip(t, (uint32_t)s, buf + (size_t)2 * s * n[0] * bytes,
                                   (tmsize_t)rows * n[0] * bytes) >= 0;
      }
    }
    ok = ok && TIFFWriteDirectory(t);
  }
  TIFFClose(t);
  free(buf);
  return ok;
}

/* ------------------------------------------------------------------- STL ---- */

typedef struct {
  double *t; /* 9 per triangle */
  int n, cap;
} tris;

static inline void add_tri(tris *s, const double *a, const double *b, const double *c)
{
  if (s->n == s->cap) s->cap = 2 * s->cap + 16, s->t = realloc(s->t, 9 * sizeof(double) * s->cap);
  memcpy(s->t + 9 * s->n, a, 24), memcpy(s->t + 9 * s->n + 3, b, 24);
  memcpy(s->t + 9 * s->n + 6, c, 24);
  s->n++;
}

/* Axis-aligned box [c - h, c + h], outward-facing triangles; skip_face >= 0 leaves one
 * face (two triangles) out. */
static inline void add_box(tris *s, const double c[3], const double h[3], int skip_face)
{
  for (int f = 0; f < 6; f++) {
    if (f == skip_face) continue;
    const int a = f / 2, sgn = f % 2 ? 1 : -1, u = (a + 1) % 3, v = (a + 2) % 3;
    double p[4][3];
    const int su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
    for (int k = 0; k < 4; k++) {
      p[k][a] = c[a] + sgn * h[a];
      p[k][u] = c[u] + su[k] * h[u];
      p[k][v] = c[v] + sv[k] * h[v];
    }
    /* (u, v, a) is right-handed: counter-clockwise in (u, v) faces +a */
    if (sgn > 0) add_tri(s, p[0], p[1], p[2]), add_tri(s, p[0], p[2], p[3]);
    else add_tri(s, p[0], p[2], p[1]), add_tri(s, p[0], p[3], p[2]);
  }
}

/* An icosphere of radius r: the icosahedron's faces split `level` times, vertices pushed
 * out to the sphere; outward-oriented. */
static inline void midpoint_on_sphere(const double *a, const double *b, double r, double *m)
{
  double s = 0.0;
  for (int k = 0; k < 3; k++) m[k] = a[k] + b[k], s += m[k] * m[k];
  for (int k = 0; k < 3; k++) m[k] *= r / sqrt(s);
}

static inline void subdivide(tris *s, const double *a, const double *b, const double *c, double r, int level)
{
  if (level == 0) {
    add_tri(s, a, b, c);
    return;
  }
  double ab[3], bc[3], ca[3];
  midpoint_on_sphere(a, b, r, ab), midpoint_on_sphere(b, c, r, bc), midpoint_on_sphere(c, a, r, ca);
  subdivide(s, a, ab, ca, r, level - 1);
  subdivide(s, ab, b, bc, r, level - 1);
  subdivide(s, ca, bc, c, r, level - 1);
  subdivide(s, ab, bc, ca, r, level - 1);
}

static inline void add_icosphere(tris *s, double r, int level)
{
  const double p = (1.0 + sqrt(5.0)) / 2.0;
  double v[12][3] = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                     {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  static const int f[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
                               {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                               {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
                               {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (int i = 0; i < 12; i++) {
    const double n = sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    for (int k = 0; k < 3; k++) v[i][k] *= r / n;
  }
  for (int i = 0; i < 20; i++) subdivide(s, v[f[i][0]], v[f[i][1]], v[f[i][2]], r, level);
}

static inline void write_stl_ascii(const char *path, const tris *s)
{
  FILE *fp = fopen(path, "w");
  fprintf(fp, "solid test\n");
  for (int t = 0; t < s->n; t++) {
    fprintf(fp, "  facet normal 0 0 0\n    outer loop\n");
    for (int c = 0; c < 3; c++)
      fprintf(fp, "      vertex %.17g %.17g %.17g\n", s->t[9 * t + 3 * c], s->t[9 * t + 3 * c + 1],
              s->t[9 * t + 3 * c + 2]);
    fprintf(fp, "    endloop\n  endfacet\n");
  }
  fprintf(fp, "endsolid test\n");
  fclose(fp);
}

static inline void write_stl_binary(const char *path, const tris *s, int count_delta)
{
  FILE *fp = fopen(path, "wb");
  unsigned char head[84] = "solid-looking binary header";
  const uint32_t n = (uint32_t)(s->n + count_delta);
  for (int i = 0; i < 4; i++) head[80 + i] = (unsigned char)(n >> (8 * i));
  fwrite(head, 1, 84, fp);
  for (int t = 0; t < s->n; t++) {
    float rec[12] = {0};
    for (int k = 0; k < 9; k++) rec[3 + k] = (float)s->t[9 * t + k];
    fwrite(rec, 4, 12, fp); /* little-endian host */
    fwrite("\0\0", 1, 2, fp);
  }
  fclose(fp);
}

#endif
