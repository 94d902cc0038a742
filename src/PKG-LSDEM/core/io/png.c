/* png.c -- 8-bit RGB pictures as PNG files, and grey-level PNG images (height maps) read,
 * through libpng (Debian libpng-dev; zlib under it). libpng reports errors by calling an
 * error function that must not return: ours keeps the message and jumps back to the
 * writer or reader, which closes the file and returns it. */
#include "lsdem_io.h"

#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  jmp_buf jump;
  char msg[160];
} png_failure;

static void on_error(png_structp png, png_const_charp msg)
{
  png_failure *f = png_get_error_ptr(png);
  snprintf(f->msg, sizeof f->msg, "%s", msg);
  longjmp(f->jump, 1);
}

static void on_warning(png_structp png, png_const_charp msg) { (void)png, (void)msg; }

lsdem_status lsdem_png_write(const char *path, int width, int height, const unsigned char *rgb,
                             lsdem_error *err)
{
  if (!path || !rgb || width < 1 || height < 1 || width > 16384 || height > 16384)
    return lsdem_fail(err, LSDEM_ERR_ARG, "png: bad image (%dx%d)", width, height);
  FILE *f = fopen(path, "wb");
  if (!f) return lsdem_fail(err, LSDEM_ERR_IO, "%s: cannot open for writing", path);
  /* set before setjmp and not changed after it, so valid after the jump; the message is
   * written through the pointer libpng holds */
  png_failure fail;
  png_failure *const pf = &fail;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, pf, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : NULL;
  if (!png || !info) {
    png_destroy_write_struct(&png, NULL);
    fclose(f);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: png: out of memory", path);
  }
  if (setjmp(pf->jump)) {
    png_destroy_write_struct(&png, &info);
    fclose(f);
    return lsdem_fail(err, LSDEM_ERR_IO, "%s: png: %s", path, pf->msg);
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int r = 0; r < height; r++) png_write_row(png, rgb + 3 * (size_t)width * r);
  png_write_end(png, NULL);
  png_destroy_write_struct(&png, &info);
  return fclose(f) == 0 ? LSDEM_OK : lsdem_fail(err, LSDEM_ERR_IO, "%s: write failed", path);
}

/* The reader's state that must survive the jump: reached through a pointer set before
 * setjmp and not changed after it. */
typedef struct {
  png_failure fail;
  uint16_t *values;
  png_bytep row;
} png_read_state;

lsdem_status lsdem_png_read_grey(const char *path, int *width, int *height, int *bits,
                                 uint16_t **values, lsdem_error *err)
{
  if (!path || !width || !height || !bits || !values)
    return lsdem_fail(err, LSDEM_ERR_ARG, "png: NULL argument");
  *values = NULL;
  FILE *f = fopen(path, "rb");
  if (!f) return lsdem_fail(err, LSDEM_ERR_IO, "%s: cannot open", path);
  unsigned char sig[8];
  if (fread(sig, 1, 8, f) != 8 || png_sig_cmp(sig, 0, 8) != 0) {
    fclose(f);
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: not a PNG file (no PNG signature)", path);
  }
  png_read_state state = {.values = NULL, .row = NULL};
  png_read_state *const rs = &state;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &rs->fail, on_error, on_warning);
  png_infop info = png ? png_create_info_struct(png) : NULL;
  if (!png || !info) {
    png_destroy_read_struct(&png, NULL, NULL);
    fclose(f);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: png: out of memory", path);
  }
  if (setjmp(rs->fail.jump)) {
    png_destroy_read_struct(&png, &info, NULL);
    fclose(f);
    free(rs->values), free(rs->row);
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: png: %s", path, rs->fail.msg);
  }
  png_init_io(png, f);
  png_set_sig_bytes(png, 8);
  png_set_user_limits(png, LSDEM_PNG_MAX_SIDE, LSDEM_PNG_MAX_SIDE);
  png_read_info(png, info);
  const png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  const int depth = png_get_bit_depth(png, info), colour = png_get_color_type(png, info);
  const char *why = NULL;
  if (colour != PNG_COLOR_TYPE_GRAY)
    why = colour == PNG_COLOR_TYPE_GRAY_ALPHA ? "grey with an alpha channel"
          : colour == PNG_COLOR_TYPE_PALETTE  ? "a palette image"
                                              : "a colour image";
  else if ((double)w * (double)h > (double)LSDEM_PNG_MAX_PIXELS)
    why = "larger than the pixel limit";
  if (why) {
    png_destroy_read_struct(&png, &info, NULL);
    fclose(f);
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: %u x %u PNG: %s (a height map is one grey "
                      "channel, 8 or 16 bits, at most %ld pixels)", path, (unsigned)w,
                      (unsigned)h, why, (long)LSDEM_PNG_MAX_PIXELS);
  }
  if (depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (depth == 16) {
    const uint16_t one = 1;
    unsigned char low;
    memcpy(&low, &one, 1);
    if (low) png_set_swap(png); /* PNG stores 16-bit samples big-endian */
  }
  const int passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  /* 16-bit rows go straight into the values; 8-bit rows into a byte image, widened after */
  const size_t rowbytes = png_get_rowbytes(png, info), count = (size_t)w * h;
  rs->values = malloc(count * sizeof(uint16_t));
  if (depth != 16) rs->row = malloc(rowbytes * (size_t)h);
  if (!rs->values || (depth != 16 && !rs->row)) png_error(png, "out of memory");
  for (int p = 0; p < passes; p++) /* interlaced images: each pass refines the rows */
    for (png_uint_32 r = 0; r < h; r++)
      png_read_row(png, depth == 16 ? (png_bytep)(rs->values + (size_t)r * w)
                                    : rs->row + (size_t)r * rowbytes, NULL);
  png_read_end(png, NULL);
  if (depth != 16)
    for (size_t i = 0; i < count; i++) rs->values[i] = rs->row[i / w * rowbytes + i % w];
  png_destroy_read_struct(&png, &info, NULL);
  fclose(f);
  free(rs->row);
  *width = (int)w, *height = (int)h, *bits = depth == 16 ? 16 : 8;
  *values = rs->values;
  return LSDEM_OK;
}
