/* test_imageio.c -- raw and TIFF label readers: round trips through writers in this test,
 * and rejection of truncated, mismatched, unsupported and hostile files. */
#include "lsdem.h"
#include "file_writers.h"
#include "lsdem_test.h"

#include <stdint.h>
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
  expect_tiff_error(b.b, b.n - 10, "past the end", "truncated directory");
  /* loops in the IFD chain */
  bytes l = {malloc(b.n), b.n, b.n, 0};
  memcpy(l.b, b.b, b.n);
  uint32_t first = l.b[4] | l.b[5] << 8 | l.b[6] << 16 | (uint32_t)l.b[7] << 24;
  set32(&l, next_last, first);
  expect_tiff_error(l.b, l.n, "loops", "IFD loop");
  memcpy(l.b, b.b, b.n);
  set32(&l, next_first, first);
  expect_tiff_error(l.b, l.n, "points to itself", "IFD self loop");
  memcpy(l.b, b.b, b.n);
  set32(&l, 4, 0x7ffffff0u);
  expect_tiff_error(l.b, l.n, "runs past the end", "IFD past EOF");
  memcpy(l.b, b.b, b.n);
  l.b[2] = 43;
  expect_tiff_error(l.b, l.n, "BigTIFF", "BigTIFF");
  memcpy(l.b, b.b, b.n);
  l.b[0] = l.b[1] = 'X';
  expect_tiff_error(l.b, l.n, "not a TIFF", "magic");
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
  expect_tiff_error(b.b, b.n, "truncated", "strip past EOF");
  free(b.b);
  /* unsupported content, named */
  const struct {
    tiff_opts o;
    const char *what;
  } unsup[] = {{{0, 8, 5, 5, 1}, "compression 5"}, {{0, 32, 5, 1, 3}, "sample format 3"},
               {{0, 16, 5, 1, 2}, "sample format 2"}, {{1, 8, 5, 32773, 1}, "compression 32773"}};
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

int main(void)
{
  test_raw_round_trip();
  test_raw_errors();
  test_tiff_round_trip();
  test_tiff_errors();
  return lsdem_test_summary();
}
