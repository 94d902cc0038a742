/* test_render.c -- the level-set ray marcher and the PNG writer (render.c).
 * Pictures are checked against projected geometry (a sphere covers pi r^2 / s^2 pixels, a
 * box its projected rectangle, a nearer grain hides a farther one); the PNG file is read
 * back here with its own CRC-32, Adler-32 and inflate (stored and fixed-Huffman blocks). */
#include "lsdem.h"
#include "lsdem_test.h"

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

/* ---- PNG read-back ---- */

static uint32_t crc_table_driven(const unsigned char *p, size_t n)
{
  uint32_t table[256];
  for (uint32_t i = 0; i < 256; i++) {
    uint32_t c = i;
    for (int k = 0; k < 8; k++) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    table[i] = c;
  }
  uint32_t c = 0xffffffffu;
  for (size_t i = 0; i < n; i++) c = table[(c ^ p[i]) & 0xff] ^ (c >> 8);
  return ~c;
}

static uint32_t be32(const unsigned char *p)
{
  return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* ---- an inflater for what the writer emits: stored and fixed-Huffman blocks ---- */

typedef struct {
  const unsigned char *p;
  size_t n, pos; /* bytes, next bit (absolute bit index) */
  int bad;
} bit_reader;

static unsigned get_bits(bit_reader *r, int n) /* least significant bit first */
{
  unsigned v = 0;
  for (int i = 0; i < n; i++, r->pos++) {
    if (r->pos / 8 >= r->n) {
      r->bad = 1;
      return 0;
    }
    v |= (unsigned)(r->p[r->pos / 8] >> (r->pos % 8) & 1) << i;
  }
  return v;
}

/* Fixed literal/length code, read most significant bit first (RFC 1951 §3.2.6). */
static int get_fixed_symbol(bit_reader *r)
{
  unsigned code = 0;
  for (int len = 1; len <= 9 && !r->bad; len++) {
    code = code << 1 | get_bits(r, 1);
    if (len == 7 && code <= 23) return 256 + (int)code;
    if (len == 8 && code >= 0x30 && code <= 0xbf) return (int)code - 0x30;
    if (len == 8 && code >= 0xc0 && code <= 0xc7) return 280 + (int)code - 0xc0;
    if (len == 9 && code >= 0x190) return 144 + (int)code - 0x190;
  }
  r->bad = 1;
  return -1;
}

/* Inflate a raw deflate stream into out (capacity cap); returns the size or -1. */
static long inflate_simple(bit_reader *r, unsigned char *out, size_t cap)
{
  static const int lbase[29] = {3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31, 35,
                                43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
  size_t o = 0;
  int final = 0;
  while (!final && !r->bad) {
    final = (int)get_bits(r, 1);
    const unsigned type = get_bits(r, 2);
    if (type == 0) {
      r->pos = (r->pos + 7) / 8 * 8;
      const unsigned len = get_bits(r, 16), nlen = get_bits(r, 16);
      if ((len ^ 0xffffu) != nlen || o + len > cap) return -1;
      for (unsigned k = 0; k < len; k++) out[o++] = (unsigned char)get_bits(r, 8);
      continue;
    }
    if (type != 1) return -1;
    for (;;) {
      const int sym = get_fixed_symbol(r);
      if (sym < 0 || r->bad) return -1;
      if (sym < 256) {
        if (o >= cap) return -1;
        out[o++] = (unsigned char)sym;
        continue;
      }
      if (sym == 256) break;
      if (sym > 285) return -1;
      const int li = sym - 257;
      const int lextra = li < 8 || li == 28 ? 0 : li / 4 - 1;
      const size_t len = (size_t)lbase[li] + get_bits(r, lextra);
      unsigned dcode = 0;
      for (int k = 0; k < 5; k++) dcode = dcode << 1 | get_bits(r, 1);
      if (dcode > 29) return -1;
      const int dextra = dcode < 4 ? 0 : (int)dcode / 2 - 1;
      const size_t dbase = dcode < 4 ? dcode + 1 : ((size_t)(2 + (dcode & 1)) << dextra) + 1;
      const size_t dist = dbase + get_bits(r, dextra);
      if (dist > o || o + len > cap) return -1;
      for (size_t k = 0; k < len; k++, o++) out[o] = out[o - dist];
    }
  }
  return r->bad ? -1 : (long)o;
}

/* Parse the PNG: signature, chunk CRCs, IHDR; inflate IDAT, check its Adler-32 and
 * compare the scanlines (filter byte 0 + RGB) with rgb. Returns the compressed size. */
static size_t check_png(const char *path, int w, int h, const unsigned char *rgb)
{
  FILE *f = fopen(path, "rb");
  CHECK(f != NULL, "cannot open %s", path);
  if (!f) return 0;
  fseek(f, 0, SEEK_END);
  const long size = ftell(f);
  rewind(f);
  unsigned char *d = malloc((size_t)size);
  CHECK(fread(d, 1, (size_t)size, f) == (size_t)size, "short read");
  fclose(f);
  static const unsigned char sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
  CHECK(memcmp(d, sig, 8) == 0, "bad PNG signature");
  unsigned char *z = malloc((size_t)size);
  size_t zlen = 0, pos = 8;
  int bad_crc = 0, seen_end = 0;
  while (pos + 12 <= (size_t)size && !seen_end) {
    const uint32_t n = be32(d + pos);
    const unsigned char *type = d + pos + 4, *data = d + pos + 8;
    if (pos + 12 + n > (size_t)size) break;
    if (crc_table_driven(type, 4 + (size_t)n) != be32(data + n)) bad_crc++;
    if (!memcmp(type, "IHDR", 4))
      CHECK(be32(data) == (uint32_t)w && be32(data + 4) == (uint32_t)h && data[8] == 8 &&
            data[9] == 2, "IHDR");
    if (!memcmp(type, "IDAT", 4)) memcpy(z + zlen, data, n), zlen += n;
    seen_end = !memcmp(type, "IEND", 4);
    pos += 12 + n;
  }
  CHECK(bad_crc == 0 && seen_end && pos == (size_t)size, "%d bad CRCs, end %d at %zu of %ld",
        bad_crc, seen_end, pos, size);
  CHECK(zlen > 6 && (z[0] * 256 + z[1]) % 31 == 0 && (z[0] & 15) == 8, "zlib header");
  const size_t rowlen = 3 * (size_t)w + 1;
  unsigned char *raw = malloc(rowlen * h);
  bit_reader br = {z + 2, zlen > 6 ? zlen - 6 : 0, 0, 0};
  const long got = inflate_simple(&br, raw, rowlen * h);
  CHECK(got == (long)(rowlen * h), "inflated %ld of %zu bytes", got, rowlen * h);
  if (got == (long)(rowlen * h)) {
    uint32_t s1 = 1, s2 = 0;
    for (size_t i = 0; i < rowlen * h; i++) s1 = (s1 + raw[i]) % 65521, s2 = (s2 + s1) % 65521;
    CHECK(be32(z + zlen - 4) == (s2 << 16 | s1), "Adler-32 mismatch");
    int diff = 0;
    for (int r = 0; r < h; r++)
      diff += raw[r * rowlen] != 0 || memcmp(raw + r * rowlen + 1, rgb + 3 * (size_t)r * w,
                                             3 * (size_t)w) != 0;
    CHECK(diff == 0, "%d scanlines differ from the image", diff);
  }
  free(raw);
  free(z);
  free(d);
  return zlen;
}

/* Round trips: a pseudo-random image (literals of every value, few matches), a periodic
 * one (long matches at many distances) and a rendered scene; a flat image must shrink to
 * a small fraction of its raw size (so the data really is compressed). */
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
    printf("png pattern %d: %zu bytes compressed of %zu\n", pattern, z, n + h);
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
