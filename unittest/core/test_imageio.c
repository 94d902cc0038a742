/* test_imageio.c -- raw and TIFF label readers and the grey-volume reader (tiff.c, through
 * libtiff): round trips through a hand-written baseline TIFF writer and through libtiff's
 * own writer (LZW, Deflate, PackBits, tiles, BigTIFF, both byte orders, 8/16/32-bit,
 * signed, float, ImageDepth volumes), and rejection of truncated, mismatched, unsupported,
 * damaged and hostile files with a message naming what is wrong. */
#include "lsdem.h"
#include "file_writers.h"
#include "lsdem_test.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------- tests ---- */

static const int DIMS[3] = {7, 5, 4};

static void fill_values(uint32_t *v, uint32_t maxval)
{
  for (int i = 0; i < DIMS[0] * DIMS[1] * DIMS[2]; i++) v[i] = (uint32_t)(i * 2654435761u) % (maxval + 1u);
}

static int same_labels(const lsdem_label_image *img, const uint32_t *v)
{
  if (img->n[0] != DIMS[0] || img->n[1] != DIMS[1] || img->n[2] != DIMS[2]) return 0;
  for (int i = 0; i < DIMS[0] * DIMS[1] * DIMS[2]; i++)
    if (img->label[i] != (int32_t)v[i]) return 0;
  return 1;
}

static void test_raw_round_trip(void)
{
  const lsdem_voxel_type types[4] = {LSDEM_VOXEL_U8, LSDEM_VOXEL_U16, LSDEM_VOXEL_U32,
                                     LSDEM_VOXEL_I32};
  const int size[4] = {1, 2, 4, 4};
  const uint32_t maxv[4] = {255, 65535, 2000000000u, 2000000000u};
  uint32_t v[7 * 5 * 4];
  for (int t = 0; t < 4; t++)
    for (int big = 0; big < 2; big++) {
      fill_values(v, maxv[t]);
      bytes b = {NULL, 0, 0, big};
      for (int i = 0; i < 140; i++) put(&b, v[i], size[t]);
      write_file_bytes("raw.bin", b.b, b.n);
      lsdem_label_image img;
      lsdem_error err;
      CHECK(lsdem_image_read_raw("raw.bin", DIMS, types[t], big, &img, &err) == LSDEM_OK,
            "type %d big %d: %s", t, big, err.msg);
      CHECK(same_labels(&img, v), "type %d big %d: labels differ", t, big);
      lsdem_label_image_free(&img);
      /* the other byte order reads other values (16/32 bit) */
      if (t > 0) {
        CHECK(lsdem_image_read_raw("raw.bin", DIMS, types[t], !big, &img, &err) != LSDEM_OK ||
                  !same_labels(&img, v), "byte order ignored");
        lsdem_label_image_free(&img);
      }
      free(b.b);
    }
}

static void test_raw_errors(void)
{
  uint32_t v[140];
  fill_values(v, 255);
  bytes b = {NULL, 0, 0, 0};
  for (int i = 0; i < 140; i++) put(&b, v[i], 2);
  write_file_bytes("raw16.bin", b.b, b.n - 1); /* truncated */
  lsdem_label_image img;
  lsdem_error err;
  CHECK(lsdem_image_read_raw("raw16.bin", DIMS, LSDEM_VOXEL_U16, 0, &img, &err) == LSDEM_ERR_FORMAT &&
            strstr(err.msg, "truncated") && strstr(err.msg, "279 bytes") && !img.label,
        "truncated: %s", err.msg);
  write_file_bytes("raw16.bin", b.b, b.n);
  const int bigger[3] = {7, 5, 5};
  CHECK(lsdem_image_read_raw("raw16.bin", bigger, LSDEM_VOXEL_U16, 0, &img, &err) == LSDEM_ERR_FORMAT &&
            strstr(err.msg, "wrong dimensions or type"), "dims: %s", err.msg);
  CHECK(lsdem_image_read_raw("raw16.bin", DIMS, LSDEM_VOXEL_U32, 0, &img, &err) == LSDEM_ERR_FORMAT &&
            strstr(err.msg, "too long") == NULL && strstr(err.msg, "truncated"),
        "type too wide: %s", err.msg);
  CHECK(lsdem_image_read_raw("raw16.bin", DIMS, LSDEM_VOXEL_U8, 0, &img, &err) == LSDEM_ERR_FORMAT &&
            strstr(err.msg, "too long"), "type too narrow: %s", err.msg);
  free(b.b);
  /* a u32 value that is no label */
  bytes c = {NULL, 0, 0, 0};
  for (int i = 0; i < 140; i++) put(&c, i == 77 ? 0xfffffff0u : 1u, 4);
  write_file_bytes("raw32.bin", c.b, c.n);
  CHECK(lsdem_image_read_raw("raw32.bin", DIMS, LSDEM_VOXEL_U32, 0, &img, &err) == LSDEM_ERR_FORMAT &&
            strstr(err.msg, "does not fit a label"), "u32: %s", err.msg);
  free(c.b);
  const int zero[3] = {7, 0, 4};
  CHECK(lsdem_image_read_raw("raw32.bin", zero, LSDEM_VOXEL_U32, 0, &img, &err) == LSDEM_ERR_ARG,
        "zero dim");
  const int huge[3] = {2000000000, 2000000000, 2000000000};
  CHECK(lsdem_image_read_raw("raw32.bin", huge, LSDEM_VOXEL_U8, 0, &img, &err) == LSDEM_ERR_ARG &&
            strstr(err.msg, "exceed"), "huge: %s", err.msg);
  CHECK(lsdem_image_read_raw("no-such-file.raw", DIMS, LSDEM_VOXEL_U8, 0, &img, &err) == LSDEM_ERR_IO,
        "missing file");
}

static void test_tiff_round_trip(void)
{
  const int bits[3] = {8, 16, 32};
  const uint32_t maxv[3] = {255, 65535, 3000000};
  uint32_t v[140];
  for (int t = 0; t < 3; t++)
    for (int big = 0; big < 2; big++)
      for (int rps = 1; rps <= 5; rps += 2) {
        fill_values(v, maxv[t]);
        const tiff_opts o = {big, bits[t], rps, 1, 1};
        bytes b = make_tiff(DIMS, v, o, NULL, NULL);
        write_file_bytes("img.tif", b.b, b.n);
        CHECK(lsdem_image_is_tiff("img.tif"), "magic");
        lsdem_label_image img;
        lsdem_error err;
        CHECK(lsdem_image_read_tiff("img.tif", &img, &err) == LSDEM_OK, "bits %d big %d rps %d: %s",
              bits[t], big, rps, err.msg);
        CHECK(same_labels(&img, v), "bits %d big %d rps %d: labels differ", bits[t], big, rps);
        lsdem_label_image_free(&img);
        free(b.b);
      }
}

/* Read `b` (n bytes) as TIFF: must fail with LSDEM_ERR_FORMAT and a message holding `what`. */
static void expect_tiff_error(const unsigned char *b, size_t n, const char *what, const char *label)
{
  write_file_bytes("bad.tif", b, n);
  lsdem_label_image img;
  lsdem_error err = {{0}};
  const lsdem_status st = lsdem_image_read_tiff("bad.tif", &img, &err);
  CHECK(st == LSDEM_ERR_FORMAT && strstr(err.msg, what) && img.label == NULL,
        "%s: status %d, message '%s' (expected '%s')", label, st, err.msg, what);
}

static void test_tiff_errors(void)
{
  uint32_t v[140];
  fill_values(v, 255);
  size_t next_first, next_last;
  const tiff_opts ok = {0, 16, 2, 1, 1};
  bytes b = make_tiff(DIMS, v, ok, &next_first, &next_last);
  /* every truncation is rejected */
  int all = 1;
  for (size_t cut = 0; cut < b.n; cut++) {
    write_file_bytes("cut.tif", b.b, cut);
    lsdem_label_image img;
    lsdem_error err = {{0}};
    all &= lsdem_image_read_tiff("cut.tif", &img, &err) == LSDEM_ERR_FORMAT && err.msg[0];
  }
  CHECK(all, "a truncated TIFF was accepted");
  expect_tiff_error(b.b, b.n - 10, "directory", "truncated directory");
  expect_tiff_error(b.b, b.n - 2, "runs past the end", "truncated link to the next page");
  /* loops in the IFD chain */
  bytes l = {malloc(b.n), b.n, b.n, 0};
  memcpy(l.b, b.b, b.n);
  uint32_t first = l.b[4] | l.b[5] << 8 | l.b[6] << 16 | (uint32_t)l.b[7] << 24;
  set32(&l, next_last, first);
  expect_tiff_error(l.b, l.n, "loops", "IFD loop");
  memcpy(l.b, b.b, b.n);
  set32(&l, next_first, first);
  expect_tiff_error(l.b, l.n, "loops", "IFD self loop");
  memcpy(l.b, b.b, b.n);
  set32(&l, 4, 0x7ffffff0u);
  expect_tiff_error(l.b, l.n, "directory", "IFD past EOF");
  memcpy(l.b, b.b, b.n);
  l.b[2] = 43;
  expect_tiff_error(l.b, l.n, "not a readable TIFF", "BigTIFF magic on a classic file");
  memcpy(l.b, b.b, b.n);
  l.b[0] = l.b[1] = 'X';
  expect_tiff_error(l.b, l.n, "not a readable TIFF", "magic");
  free(l.b);
  free(b.b);
  /* strip offsets past the end: a one-strip file whose strip offset is moved */
  const tiff_opts one = {1, 8, 5, 1, 1};
  b = make_tiff(DIMS, v, one, NULL, NULL);
  for (size_t at = 8; at + 12 <= b.n; at++) /* find entry 273 and move its value */
    if (b.b[at] == 0x01 && b.b[at + 1] == 0x11 && b.b[at + 2] == 0 && b.b[at + 3] == 4) {
      set32(&b, at + 8, (uint32_t)b.n - 3);
      break;
    }
  expect_tiff_error(b.b, b.n, "strip 0", "strip past EOF");
  free(b.b);
  /* content that is not what the tags say (raw data declared LZW or PackBits), and float
   * samples given as labels, named */
  const struct {
    tiff_opts o;
    const char *what;
  } unsup[] = {{{0, 8, 5, 5, 1}, "LZWDecode"}, {{0, 32, 5, 1, 3}, "floating-point"},
               {{1, 8, 5, 32773, 1}, "PackBits"}, {{0, 8, 5, 34000, 1}, "Compression scheme 34000"}};
  for (size_t k = 0; k < sizeof unsup / sizeof unsup[0]; k++) {
    b = make_tiff(DIMS, v, unsup[k].o, NULL, NULL);
    expect_tiff_error(b.b, b.n, unsup[k].what, unsup[k].what);
    free(b.b);
  }
  /* pages of different sizes: page 1 of a 2-page file made 1 row shorter */
  const int two[3] = {7, 5, 2};
  b = make_tiff(two, v, ok, &next_first, NULL);
  uint32_t ifd1 = b.b[next_first] | b.b[next_first + 1] << 8 | b.b[next_first + 2] << 16 |
                  (uint32_t)b.b[next_first + 3] << 24;
  set32(&b, ifd1 + 2 + 12 + 8, 4); /* entry 257 value */
  expect_tiff_error(b.b, b.n, "same size", "page size mismatch");
  free(b.b);
  CHECK(!lsdem_image_is_tiff("raw16.bin"), "raw detected as TIFF");
}

/* ---------------------------------------------------- files libtiff wrote ---- */

static const int VOL[3] = {37, 21, 9}; /* several 16 x 16 tiles, partial at the edges */

static void fill_volume(uint32_t *v, uint32_t maxval)
{
  for (int i = 0; i < VOL[0] * VOL[1] * VOL[2]; i++) v[i] = (uint32_t)(i * 2654435761u) % (maxval + 1u);
}

/* Every compression, layout, container and byte order, as labels. */
static void test_libtiff_labels(void)
{
  const int comp[4] = {COMPRESSION_NONE, COMPRESSION_LZW, COMPRESSION_ADOBE_DEFLATE,
                       COMPRESSION_PACKBITS};
  const int bits[3] = {8, 16, 32};
  const uint32_t maxv[3] = {255, 65535, 2000000000u};
  const size_t count = (size_t)VOL[0] * VOL[1] * VOL[2];
  uint32_t *v = malloc(count * sizeof *v);
  int read = 0;
  for (int c = 0; c < 4; c++)
    for (int b = 0; b < 3; b++)
      for (int layout = 0; layout < 3; layout++) /* strips, tiles, tiled volume */
        for (int big = 0; big < 2; big++)
          for (int bigtiff = 0; bigtiff < 2; bigtiff++) {
            fill_volume(v, maxv[b]);
            const libtiff_opts o = {bits[b], SAMPLEFORMAT_UINT, comp[c], layout > 0, bigtiff,
                                    big, layout == 2};
            CHECK(write_tiff_libtiff("lib.tif", VOL, v, o), "libtiff refused to write");
            CHECK(lsdem_image_is_tiff("lib.tif"), "magic (bigtiff %d)", bigtiff);
            lsdem_label_image img;
            lsdem_error err = {{0}};
            const int ok = lsdem_image_read_tiff("lib.tif", &img, &err) == LSDEM_OK;
            CHECK(ok, "compression %d bits %d layout %d big %d bigtiff %d: %s", comp[c], bits[b],
                  layout, big, bigtiff, err.msg);
            int same = ok && img.n[0] == VOL[0] && img.n[1] == VOL[1] && img.n[2] == VOL[2];
            for (size_t i = 0; same && i < count; i++) same = img.label[i] == (int32_t)v[i];
            CHECK(same, "compression %d bits %d layout %d big %d bigtiff %d: labels differ",
                  comp[c], bits[b], layout, big, bigtiff);
            read += same;
            lsdem_label_image_free(&img);
          }
  printf("libtiff-written label files read back: %d of %d\n", read, 4 * 3 * 3 * 2 * 2);
  free(v);
}

/* Signed labels (negative = background) are read as they are; float samples are a grey
 * volume, read exactly by the volume reader and refused as labels. */
static void test_libtiff_types(void)
{
  const size_t count = (size_t)VOL[0] * VOL[1] * VOL[2];
  uint32_t *v = malloc(count * sizeof *v);
  for (size_t i = 0; i < count; i++) v[i] = (uint32_t)((int)(i % 7) - 3);
  const libtiff_opts i16 = {16, SAMPLEFORMAT_INT, COMPRESSION_LZW, 0, 0, 1, 0};
  CHECK(write_tiff_libtiff("i16.tif", VOL, v, i16), "write i16");
  lsdem_label_image img;
  lsdem_error err = {{0}};
  CHECK(lsdem_image_read_tiff("i16.tif", &img, &err) == LSDEM_OK, "i16: %s", err.msg);
  int same = img.label != NULL;
  for (size_t i = 0; same && i < count; i++) same = img.label[i] == (int)(i % 7) - 3;
  CHECK(same, "signed 16-bit labels differ");
  lsdem_label_image_free(&img);
  fill_volume(v, 1u << 20);
  const int fbits[2] = {32, 64};
  for (int k = 0; k < 2; k++) {
    const libtiff_opts f = {fbits[k], SAMPLEFORMAT_IEEEFP, COMPRESSION_ADOBE_DEFLATE, k, 0, 0, 0};
    CHECK(write_tiff_libtiff("f.tif", VOL, v, f), "write f%d", fbits[k]);
    lsdem_volume vol;
    CHECK(lsdem_tiff_read_volume("f.tif", &vol, &err) == LSDEM_OK, "f%d: %s", fbits[k], err.msg);
    CHECK(vol.kind == LSDEM_SAMPLE_FLOAT && vol.bytes == fbits[k] / 8 &&
              !strcmp(lsdem_volume_type_name(&vol), k ? "f64" : "f32"), "f%d: kind %d bytes %d",
          fbits[k], vol.kind, vol.bytes);
    same = vol.data != NULL;
    for (size_t i = 0; same && i < count; i++)
      same = k ? ((double *)vol.data)[i] == (double)v[i] : ((float *)vol.data)[i] == (float)v[i];
    CHECK(same, "f%d samples differ", fbits[k]);
    lsdem_volume_free(&vol);
  }
  lsdem_volume vol;
  const libtiff_opts f = {32, SAMPLEFORMAT_IEEEFP, COMPRESSION_NONE, 0, 0, 0, 0};
  write_tiff_libtiff("f32.tif", VOL, v, f);
  CHECK(lsdem_image_read_tiff("f32.tif", &img, &err) == LSDEM_ERR_FORMAT &&
            strstr(err.msg, "floating-point") && !img.label, "float labels: %s", err.msg);
  /* u16 volume: type name and exact samples */
  fill_volume(v, 65535);
  const libtiff_opts u16 = {16, SAMPLEFORMAT_UINT, COMPRESSION_PACKBITS, 1, 1, 1, 1};
  write_tiff_libtiff("u16.tif", VOL, v, u16);
  CHECK(lsdem_tiff_read_volume("u16.tif", &vol, &err) == LSDEM_OK &&
            !strcmp(lsdem_volume_type_name(&vol), "u16"), "u16 volume: %s", err.msg);
  same = vol.data != NULL;
  for (size_t i = 0; same && i < count; i++) same = ((uint16_t *)vol.data)[i] == v[i];
  CHECK(same, "u16 volume samples differ");
  lsdem_volume_free(&vol);
  free(v);
}

/* A byte of Deflate-compressed data changed: zlib's check names the codec; a file cut in
 * the middle of its data, or pages of different sample types, are named too. */
static void test_libtiff_damage(void)
{
  const size_t count = (size_t)VOL[0] * VOL[1] * VOL[2];
  uint32_t *v = malloc(count * sizeof *v);
  fill_volume(v, 255);
  const libtiff_opts zip = {8, SAMPLEFORMAT_UINT, COMPRESSION_ADOBE_DEFLATE, 0, 0, 0, 0};
  write_tiff_libtiff("zip.tif", VOL, v, zip);
  TIFF *t = TIFFOpen("zip.tif", "r");
  uint64_t *offsets = NULL;
  TIFFGetField(t, TIFFTAG_STRIPOFFSETS, &offsets);
  const uint64_t at = offsets[0] + 5;
  TIFFClose(t);
  unsigned char *b = NULL;
  size_t n = 0;
  CHECK(lsdem_read_file("zip.tif", SIZE_MAX, &b, &n, NULL) == LSDEM_OK, "read back");
  b[at] ^= 0x5a;
  expect_tiff_error(b, n, "ZIPDecode", "damaged Deflate data");
  b[at] ^= 0x5a;
  expect_tiff_error(b, n / 2, "page", "Deflate file cut in half");
  free(b);
  /* 2 pages: u8, then u16 */
  TIFF *w = TIFFOpen("mixed.tif", "w");
  for (int z = 0; z < 2; z++) {
    TIFFSetField(w, TIFFTAG_IMAGEWIDTH, 4u);
    TIFFSetField(w, TIFFTAG_IMAGELENGTH, 3u);
    TIFFSetField(w, TIFFTAG_BITSPERSAMPLE, (uint16_t)(8 << z));
    TIFFSetField(w, TIFFTAG_SAMPLESPERPIXEL, (uint16_t)1);
    TIFFSetField(w, TIFFTAG_PHOTOMETRIC, (uint16_t)PHOTOMETRIC_MINISBLACK);
    TIFFSetField(w, TIFFTAG_ROWSPERSTRIP, 3u);
    unsigned char px[24] = {0};
    TIFFWriteEncodedStrip(w, 0, px, 12 << z);
    TIFFWriteDirectory(w);
  }
  TIFFClose(w);
  lsdem_label_image img;
  lsdem_error err = {{0}};
  CHECK(lsdem_image_read_tiff("mixed.tif", &img, &err) == LSDEM_ERR_FORMAT &&
            strstr(err.msg, "one sample type"), "mixed types: %s", err.msg);
  /* 3 samples per pixel (RGB) */
  w = TIFFOpen("rgb.tif", "w");
  TIFFSetField(w, TIFFTAG_IMAGEWIDTH, 4u);
  TIFFSetField(w, TIFFTAG_IMAGELENGTH, 3u);
  TIFFSetField(w, TIFFTAG_BITSPERSAMPLE, (uint16_t)8);
  TIFFSetField(w, TIFFTAG_SAMPLESPERPIXEL, (uint16_t)3);
  TIFFSetField(w, TIFFTAG_PHOTOMETRIC, (uint16_t)PHOTOMETRIC_RGB);
  TIFFSetField(w, TIFFTAG_PLANARCONFIG, (uint16_t)PLANARCONFIG_CONTIG);
  TIFFSetField(w, TIFFTAG_ROWSPERSTRIP, 3u);
  unsigned char px[36] = {0};
  TIFFWriteEncodedStrip(w, 0, px, 36);
  TIFFClose(w);
  CHECK(lsdem_image_read_tiff("rgb.tif", &img, &err) == LSDEM_ERR_FORMAT &&
            strstr(err.msg, "3 samples per pixel"), "rgb: %s", err.msg);
  CHECK(lsdem_image_read_tiff("no-such.tif", &img, &err) == LSDEM_ERR_IO &&
            strstr(err.msg, "cannot open"), "missing: %s", err.msg);
  free(v);
}

int main(void)
{
  test_raw_round_trip();
  test_raw_errors();
  test_tiff_round_trip();
  test_tiff_errors();
  test_libtiff_labels();
  test_libtiff_types();
  test_libtiff_damage();
  return lsdem_test_summary();
}
