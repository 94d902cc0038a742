/* test_render.c -- the level-set ray marcher (render.c) and the PNG writer (png.c).
 * Pictures are checked against projected geometry (a sphere covers pi r^2 / s^2 pixels, a
 * box its projected rectangle, a nearer grain hides a farther one); the PNG file (png.c,
 * libpng) is read back through libpng's reading side and compared pixel by pixel. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <png.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;
enum { W = 200, H = 160 };

static lsdem_shape analytic_shape(lsdem_sdf_kind kind, double a0, double a1, double a2)
{
  lsdem_shape s;
  memset(&s, 0, sizeof s);
  s.sdf.kind = kind;
  s.sdf.a[0] = a0, s.sdf.a[1] = a1, s.sdf.a[2] = a2;
  s.radius = lsdem_sdf_bound_radius(&s.sdf);
  return s;
}

static lsdem_render_grain grain(int shape, int64_t id, double x, double y, double z)
{
  lsdem_render_grain g = {shape, id, {x, y, z}, {1, 0, 0, 0}};
  return g;
}

/* Looking down -z with +y up (so +x is to the right), centre at the origin. */
static lsdem_render_view top_view(double pixel)
{
  lsdem_render_view v;
  memset(&v, 0, sizeof v);
  v.width = W, v.height = H;
  v.view[2] = -1.0, v.up[1] = 1.0;
  v.pixel = pixel;
  return v;
}

typedef struct {
  int count;
  double col, row;        /* centroid of the covered pixels */
  int cmin, cmax, rmin, rmax;
} coverage;

static coverage cover(const unsigned char *rgb)
{
  coverage c = {0, 0.0, 0.0, W, -1, H, -1};
  for (int r = 0; r < H; r++)
    for (int k = 0; k < W; k++) {
      const unsigned char *p = rgb + 3 * (r * W + k);
      if (p[0] == LSDEM_RENDER_BACKGROUND && p[1] == LSDEM_RENDER_BACKGROUND &&
          p[2] == LSDEM_RENDER_BACKGROUND)
        continue;
      c.count++, c.col += k + 0.5, c.row += r + 0.5;
      if (k < c.cmin) c.cmin = k;
      if (k > c.cmax) c.cmax = k;
      if (r < c.rmin) c.rmin = r;
      if (r > c.rmax) c.rmax = r;
    }
  if (c.count) c.col /= c.count, c.row /= c.count;
  return c;
}

static unsigned char *render(const lsdem_shape *const *shapes, int nshapes,
                             const lsdem_render_grain *g, int n, const lsdem_render_view *v)
{
  unsigned char *rgb = malloc(3 * (size_t)v->width * v->height);
  lsdem_error err;
  CHECK(lsdem_render(shapes, nshapes, g, n, v, rgb, &err) == LSDEM_OK, "%s", err.msg);
  return rgb;
}

/* A sphere of radius R at pixel size s covers pi (R/s)^2 pixels, centred on its centre. */
static void test_sphere_coverage(const lsdem_shape *sphere, const char *what)
{
  const double s = 0.02, R = 1.0;
  const lsdem_shape *shapes[1] = {sphere};
  const lsdem_render_view v = top_view(s);
  lsdem_render_grain g = grain(0, 7, 0.0, 0.0, 0.3);
  unsigned char *rgb = render(shapes, 1, &g, 1, &v);
  coverage c = cover(rgb);
  const double expect = PI * R * R / (s * s);
  printf("%s centred: %d pixels, expected %.0f (%+.2f%%)\n", what, c.count, expect,
         100.0 * (c.count / expect - 1.0));
  CHECK_REL(c.count, expect, 0.02);
  CHECK_NEAR(c.col, 0.5 * W, 0.5);
  CHECK_NEAR(c.row, 0.5 * H, 0.5);
  free(rgb);
  /* off centre: +x right, +y up (smaller rows) */
  g = grain(0, 7, 0.9, 0.5, -2.0); /* still inside the 4 x 3.2 frame */
  rgb = render(shapes, 1, &g, 1, &v);
  c = cover(rgb);
  CHECK_NEAR(c.col, 0.5 * W + 0.9 / s, 0.5);
  CHECK_NEAR(c.row, 0.5 * H - 0.5 / s, 0.5);
  CHECK_REL(c.count, expect, 0.02);
  free(rgb);
}

/* A box of half-extents (1, 0.5, 0.25) seen from +z: a 2 x 1 rectangle; turned 90 degrees
 * about z by its quaternion, a 1 x 2 rectangle. */
static void test_box_orientation(void)
{
  const double s = 0.02;
  lsdem_shape box = analytic_shape(LSDEM_SDF_BOX, 1.0, 0.5, 0.25);
  const lsdem_shape *shapes[1] = {&box};
  const lsdem_render_view v = top_view(s);
  lsdem_render_grain g = grain(0, 1, 0, 0, 0);
  unsigned char *rgb = render(shapes, 1, &g, 1, &v);
  coverage c = cover(rgb);
  CHECK_NEAR(c.cmax - c.cmin + 1, 2.0 / s, 1.5);
  CHECK_NEAR(c.rmax - c.rmin + 1, 1.0 / s, 1.5);
  CHECK_REL(c.count, 2.0 / (s * s), 0.02);
  free(rgb);
  const double h = sqrt(0.5);
  g.q[0] = h, g.q[3] = h; /* 90 degrees about z */
  rgb = render(shapes, 1, &g, 1, &v);
  c = cover(rgb);
  CHECK_NEAR(c.cmax - c.cmin + 1, 1.0 / s, 1.5);
  CHECK_NEAR(c.rmax - c.rmin + 1, 2.0 / s, 1.5);
  free(rgb);
}

/* A grain in front hides one behind it, whichever order they are listed in; the centre
 * pixel shows the front grain's colour as it appears alone. */
static void test_occlusion(void)
{
  lsdem_shape sphere = analytic_shape(LSDEM_SDF_SPHERE, 1.0, 0, 0);
  lsdem_shape small = analytic_shape(LSDEM_SDF_SPHERE, 0.5, 0, 0);
  const lsdem_shape *shapes[2] = {&sphere, &small};
  const lsdem_render_view v = top_view(0.02);
  const lsdem_render_grain front = grain(1, 11, 0, 0, 3.0), back = grain(0, 12, 0, 0, 0);
  const lsdem_render_grain both[2][2] = {{front, back}, {back, front}};
  unsigned char *alone_front = render(shapes, 2, &front, 1, &v);
  unsigned char *alone_back = render(shapes, 2, &back, 1, &v);
  const size_t mid = 3 * ((size_t)(H / 2) * W + W / 2);
  CHECK(memcmp(alone_front + mid, alone_back + mid, 3) != 0, "ids 11, 12 have one colour");
  for (int order = 0; order < 2; order++) {
    unsigned char *rgb = render(shapes, 2, both[order], 2, &v);
    CHECK(memcmp(rgb + mid, alone_front + mid, 3) == 0, "order %d: centre not the front grain",
          order);
    CHECK(cover(rgb).count == cover(alone_back).count, "order %d: silhouette changed", order);
    free(rgb);
  }
  free(alone_front);
  free(alone_back);
}

/* Automatic framing puts every grain inside the picture; the same scene renders the same
 * bytes twice. */
static void test_autoframe_and_determinism(void)
{
  lsdem_shape box = analytic_shape(LSDEM_SDF_BOX, 1.0, 0.6, 0.4);
  const lsdem_shape *shapes[1] = {&box};
  lsdem_render_grain g[20];
  for (int i = 0; i < 20; i++) {
    g[i] = grain(0, i + 1, 2.5 * (i % 5), 2.5 * (i / 5), 0.3 * i);
    g[i].q[0] = cos(0.3 * i), g[i].q[1] = sin(0.3 * i) * 0.6, g[i].q[2] = sin(0.3 * i) * 0.8;
  }
  lsdem_render_view v = top_view(0.0);
  v.view[0] = -1.0, v.view[1] = 1.0, v.view[2] = -1.0, v.up[1] = 0.0, v.up[2] = 1.0;
  unsigned char *a = render(shapes, 1, g, 20, &v);
  unsigned char *b = render(shapes, 1, g, 20, &v);
  CHECK(memcmp(a, b, 3 * (size_t)W * H) == 0, "two renders differ");
  const coverage c = cover(a);
  CHECK(c.count > W * H / 10, "auto frame: only %d pixels covered", c.count);
  CHECK(c.cmin > 0 && c.rmin > 0 && c.cmax < W - 1 && c.rmax < H - 1,
        "auto frame: grains touch the edge (%d..%d, %d..%d)", c.cmin, c.cmax, c.rmin, c.rmax);
  free(a);
  free(b);
}

static void test_errors(void)
{
  lsdem_shape plane = analytic_shape(LSDEM_SDF_PLANE, 0, 0, 0),
              ball = analytic_shape(LSDEM_SDF_SPHERE, 1.0, 0, 0);
  const lsdem_shape *shapes[1] = {&plane}, *balls[1] = {&ball};
  lsdem_render_grain g = grain(0, 1, 0, 0, 0);
  lsdem_render_view v = top_view(0.1);
  unsigned char rgb[3 * W * H];
  lsdem_error err;
  CHECK(lsdem_render(shapes, 1, &g, 1, &v, rgb, &err) == LSDEM_ERR_ARG, "plane rendered");
  g.shape = 1;
  CHECK(lsdem_render(shapes, 1, &g, 1, &v, rgb, &err) == LSDEM_ERR_ARG, "shape 1 of 1");
  g.shape = 0, g.q[0] = 2.0;
  CHECK(lsdem_render(balls, 1, &g, 1, &v, rgb, &err) == LSDEM_ERR_ARG, "quaternion |q| = 2");
  g.q[0] = 1.0, g.x[1] = NAN;
  CHECK(lsdem_render(balls, 1, &g, 1, &v, rgb, &err) == LSDEM_ERR_ARG, "NaN position");
  g.x[1] = 0.0;
  v.up[1] = 0.0, v.up[2] = 1.0; /* parallel to view */
  CHECK(lsdem_render(balls, 1, &g, 1, &v, rgb, &err) == LSDEM_ERR_ARG, "up parallel to view");
  CHECK(strstr(err.msg, "parallel") != NULL, "message: %s", err.msg);
}

/* ---- PNG read-back through libpng's reading side (simplified API) ---- */

/* Read the PNG back, compare its pixels with rgb; returns the file size (0 on failure). */
static size_t check_png(const char *path, int w, int h, const unsigned char *rgb)
{
  png_image im;
  memset(&im, 0, sizeof im);
  im.version = PNG_IMAGE_VERSION;
  CHECK(png_image_begin_read_from_file(&im, path), "%s: %s", path, im.message);
  CHECK(im.width == (png_uint_32)w && im.height == (png_uint_32)h &&
            im.format == PNG_FORMAT_RGB, "%s: %ux%u format %u", path, im.width, im.height,
        im.format);
  im.format = PNG_FORMAT_RGB;
  unsigned char *back = malloc(PNG_IMAGE_SIZE(im));
  CHECK(back && png_image_finish_read(&im, NULL, back, 0, NULL), "%s: %s", path, im.message);
  CHECK(back && memcmp(back, rgb, 3 * (size_t)w * h) == 0, "%s: pixels differ", path);
  free(back);
  png_image_free(&im);
  FILE *f = fopen(path, "rb");
  long size = 0;
  if (f && fseek(f, 0, SEEK_END) == 0) size = ftell(f);
  if (f) fclose(f);
  return size > 0 ? (size_t)size : 0;
}

/* Round trips: a pseudo-random image, a periodic one and a rendered scene; a flat image
 * must shrink to a small fraction of its raw size (so the data really is compressed). */
static void test_png(void)
{
  const int w = 300, h = 120;
  const size_t n = 3 * (size_t)w * h;
  unsigned char *rgb = malloc(n);
  lsdem_error err;
  uint32_t x = 12345;
  for (int pattern = 0; pattern < 3; pattern++) {
    for (size_t i = 0; i < n; i++) {
      x = x * 1103515245u + 12345u;
      rgb[i] = pattern == 0 ? (unsigned char)(x >> 23)
               : pattern == 1 ? (unsigned char)(i * 7 + i / 913)
                              : (unsigned char)(i < n / 2 ? 40 : 200);
    }
    CHECK(lsdem_png_write("render_test.png", w, h, rgb, &err) == LSDEM_OK, "%s", err.msg);
    const size_t z = check_png("render_test.png", w, h, rgb);
    printf("png pattern %d: %zu bytes for %zu of pixels\n", pattern, z, n);
    if (pattern == 2) CHECK(z < n / 50, "flat image compressed to %zu of %zu bytes", z, n);
  }
  free(rgb);
  lsdem_shape box = analytic_shape(LSDEM_SDF_BOX, 1.0, 0.6, 0.4);
  const lsdem_shape *shapes[1] = {&box};
  lsdem_render_grain g[6];
  for (int i = 0; i < 6; i++) {
    g[i] = grain(0, i + 1, 2.5 * i, 0.0, 0.0);
    g[i].q[0] = cos(0.4 * i), g[i].q[1] = sin(0.4 * i);
  }
  lsdem_render_view v = top_view(0.0);
  unsigned char *img = render(shapes, 1, g, 6, &v);
  CHECK(lsdem_png_write("render_scene.png", W, H, img, &err) == LSDEM_OK, "%s", err.msg);
  check_png("render_scene.png", W, H, img);
  CHECK(lsdem_png_write("/nonexistent-dir/x.png", W, H, img, &err) == LSDEM_ERR_IO, "no error");
  free(img);
}

int main(void)
{
  lsdem_shape sphere = analytic_shape(LSDEM_SDF_SPHERE, 1.0, 0, 0);
  test_sphere_coverage(&sphere, "analytic sphere");
  /* the same sphere as a grid at R/10 */
  lsdem_shape gs = sphere;
  const double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
  lsdem_error err;
  lsdem_grid g;
  CHECK(lsdem_grid_sample(&sphere.sdf, lo, hi, 0.1, 3, &g, &err) == LSDEM_OK, "%s", err.msg);
  memset(&gs.sdf, 0, sizeof gs.sdf);
  gs.sdf.kind = LSDEM_SDF_GRID;
  gs.sdf.grid = g;
  test_sphere_coverage(&gs, "grid sphere R/10");
  lsdem_grid_free(&g);
  test_box_orientation();
  test_occlusion();
  test_autoframe_and_determinism();
  test_errors();
  test_png();
  return lsdem_test_summary();
}
