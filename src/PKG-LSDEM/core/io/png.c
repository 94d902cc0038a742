/* png.c -- 8-bit RGB pictures as PNG files through libpng (Debian libpng-dev; zlib under
 * it). libpng reports errors by calling an error function that must not return: ours keeps
 * the message and jumps back to the writer, which closes the file and returns it. */
#include "lsdem_io.h"

#include <png.h>
#include <setjmp.h>
#include <stdio.h>
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
