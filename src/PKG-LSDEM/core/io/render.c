/* render.c -- pictures of posed level-set grains without a visualisation program:
 * an orthographic ray marcher (sphere tracing of each grain's level set in its own frame);
 * the PNG file is written by png.c.
 *
 * Camera: forward f = view / |view|, right r = f x up / |f x up|, image up u = r x f.
 * Pixel (col, row) looks along f through centre + (col + 1/2 - W/2) s r
 * + (H/2 - row - 1/2) s u, s = the pixel size; row 0 is the top of the image. */
#include "lsdem_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { BIN = 8 };                  /* broad-phase bins of BIN x BIN pixels */
static const double SAFETY = 0.9;  /* sphere-tracing step as a fraction of phi */
static const double HIT_EPS = 1e-3; /* hit when phi < HIT_EPS * grain radius */
static const int MAX_STEPS = 400;
static const double AMBIENT = 0.3;

static int normalise3(double v[3])
{
  const double n = sqrt(lsdem_dot3(v, v));
  if (!(n > 0.0) || !isfinite(n)) return 0;
  for (int k = 0; k < 3; k++) v[k] /= n;
  return 1;
}

typedef struct {
  double f[3], r[3], u[3];  /* camera basis */
  double centre[3], pixel;  /* image centre (world) and pixel size */
  double back;              /* rays start this far behind the centre along -f */
  int w, h;
} camera;

/* The frame: the given centre and pixel size, or (pixel <= 0) one that fits the grains'
 * bounding spheres with a 5% margin on each side. */
static void frame_scene(const lsdem_shape *const *shapes, const lsdem_render_grain *g, int n,
                        const lsdem_render_view *v, camera *c)
{
  double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL}, mid[3] = {0, 0, 0};
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) mid[k] += g[i].x[k] / n;
  double reach = 0.0;
  for (int i = 0; i < n; i++) {
    const double rad = shapes[g[i].shape]->radius;
    double d[3];
    for (int k = 0; k < 3; k++) d[k] = g[i].x[k] - mid[k];
    reach = fmax(reach, sqrt(lsdem_dot3(d, d)) + rad);
    const double pu = lsdem_dot3(g[i].x, c->r), pv = lsdem_dot3(g[i].x, c->u);
    lo[0] = fmin(lo[0], pu - rad), hi[0] = fmax(hi[0], pu + rad);
    lo[1] = fmin(lo[1], pv - rad), hi[1] = fmax(hi[1], pv + rad);
  }
  if (v->pixel > 0.0) {
    memcpy(c->centre, v->centre, sizeof c->centre);
    c->pixel = v->pixel;
  } else {
    const double a = 0.5 * (lo[0] + hi[0]), b = 0.5 * (lo[1] + hi[1]);
    const double fc = lsdem_dot3(mid, c->f);
    for (int k = 0; k < 3; k++) c->centre[k] = a * c->r[k] + b * c->u[k] + fc * c->f[k];
    c->pixel = 1.1 * fmax((hi[0] - lo[0]) / c->w, (hi[1] - lo[1]) / c->h);
  }
  double d[3];
  for (int k = 0; k < 3; k++) d[k] = mid[k] - c->centre[k];
  c->back = fabs(lsdem_dot3(d, c->f)) + reach + 1.0 * c->pixel;
}

/* A lower bound of the distance from p to the shape (shape frame): phi itself, except
 * outside a grid's box, where phi = phi(c) + |p - c| (c the nearest box point) may
 * overestimate; the distance is at least |(|p - c|, phi(c))| >= phi / sqrt(2) there. */
static double safe_distance(const lsdem_sdf *s, const double p[3])
{
  double grad[3];
  const double phi = lsdem_sdf_eval(s, p, grad);
  if (s->kind != LSDEM_SDF_GRID) return phi;
  for (int k = 0; k < 3; k++) {
    const double rel = (p[k] - s->grid.origin[k]) / s->grid.h;
    if (rel < 0.0 || rel > s->grid.n[k] - 1) return phi / sqrt(2.0);
  }
  return phi;
}

/* Sphere tracing of the ray o + t d (world) through grain g over [t0, t1]. Returns the
 * hit distance (HUGE_VAL for a miss) and the world normal there. */
static double trace_grain(const lsdem_shape *s, const lsdem_render_grain *g, const double o[3],
                          const double d[3], double t0, double t1, double normal[3])
{
  double rel[3], ob[3], db[3];
  for (int k = 0; k < 3; k++) rel[k] = o[k] - g->x[k];
  lsdem_quat_rotate_inv(g->q, rel, ob);
  lsdem_quat_rotate_inv(g->q, d, db);
  const double eps = HIT_EPS * s->radius;
  double t = t0;
  for (int step = 0; step < MAX_STEPS && t <= t1; step++) {
    const double p[3] = {ob[0] + t * db[0], ob[1] + t * db[1], ob[2] + t * db[2]};
    const double dist = safe_distance(&s->sdf, p);
    if (dist < eps) {
      double grad[3];
      lsdem_sdf_eval(&s->sdf, p, grad);
      lsdem_quat_rotate(g->q, grad, normal);
      return t;
    }
    t += SAFETY * dist;
  }
  return HUGE_VAL;
}

/* Ray-sphere interval of grain g's bounding sphere: 0 when missed. */
static int sphere_interval(const lsdem_shape *s, const lsdem_render_grain *g, const double o[3],
                           const double d[3], double *t0, double *t1)
{
  double rel[3];
  for (int k = 0; k < 3; k++) rel[k] = g->x[k] - o[k];
  const double tc = lsdem_dot3(rel, d), q = lsdem_dot3(rel, rel) - tc * tc, r2 = s->radius * s->radius;
  if (q > r2) return 0;
  const double half = sqrt(r2 - q);
  *t0 = fmax(tc - half, 0.0);
  *t1 = tc + half;
  return 1;
}

/* Grain colour: a fixed palette picked by a hash of the id (or of the shape index). */
static void grain_colour(const lsdem_render_grain *g, int by_shape, double rgb[3])
{
  static const unsigned char palette[10][3] = {
      {214, 96, 77},  {67, 147, 195}, {120, 180, 90}, {230, 170, 60}, {150, 110, 190},
      {90, 190, 190}, {200, 120, 160}, {170, 150, 100}, {100, 120, 200}, {190, 190, 80}};
  uint64_t z = (uint64_t)(by_shape ? g->shape : g->id) + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL; /* splitmix64 finaliser */
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  for (int k = 0; k < 3; k++) rgb[k] = palette[z % 10][k];
}

/* Broad phase: for each bin of BIN x BIN pixels, the grains whose projected bounding disc
 * touches it (CSR: start[nbins + 1], list). */
typedef struct {
  int nbx, nby;
  int *start, *list;
} bins;

static void disc_bins(const camera *c, const lsdem_shape *s, const lsdem_render_grain *g,
                      int nbx, int nby, int range[4])
{
  double d[3];
  for (int k = 0; k < 3; k++) d[k] = g->x[k] - c->centre[k];
  const double col = lsdem_dot3(d, c->r) / c->pixel + 0.5 * c->w;
  const double row = 0.5 * c->h - lsdem_dot3(d, c->u) / c->pixel;
  const double rp = s->radius / c->pixel + 1.0;
  range[0] = (int)fmax(0.0, floor((col - rp) / BIN));
  range[1] = (int)fmin(nbx - 1.0, floor((col + rp) / BIN));
  range[2] = (int)fmax(0.0, floor((row - rp) / BIN));
  range[3] = (int)fmin(nby - 1.0, floor((row + rp) / BIN));
}

static int build_bins(const camera *c, const lsdem_shape *const *shapes,
                      const lsdem_render_grain *g, int n, bins *b)
{
  b->nbx = (c->w + BIN - 1) / BIN, b->nby = (c->h + BIN - 1) / BIN;
  const int nb = b->nbx * b->nby;
  b->start = calloc((size_t)nb + 1, sizeof(int));
  if (!b->start) return 0;
  for (int pass = 0; pass < 2; pass++) { /* count, then fill */
    for (int i = 0; i < n; i++) {
      int rg[4];
      disc_bins(c, shapes[g[i].shape], &g[i], b->nbx, b->nby, rg);
      for (int by = rg[2]; by <= rg[3]; by++)
        for (int bx = rg[0]; bx <= rg[1]; bx++) {
          if (pass == 0) b->start[by * b->nbx + bx + 1]++;
          else b->list[b->start[by * b->nbx + bx]++] = i;
        }
    }
    if (pass == 0) {
      for (int k = 0; k < nb; k++) b->start[k + 1] += b->start[k];
      b->list = malloc(((size_t)b->start[nb] + 1) * sizeof(int));
      if (!b->list) return 0;
    } else {
      for (int k = nb; k > 0; k--) b->start[k] = b->start[k - 1]; /* undo the fill shift */
      b->start[0] = 0;
    }
  }
  return 1;
}

typedef struct {
  double t0, t1;
  int grain;
} candidate;

/* Nearest hit along one ray among the bin's candidates, tried in order of entry distance
 * so the march stops once the next sphere starts beyond the best hit. */
static void shade_pixel(const camera *c, const lsdem_shape *const *shapes,
                        const lsdem_render_grain *g, const int *cand, int ncand, candidate *buf,
                        int by_shape, const double o[3], unsigned char px[3])
{
  int m = 0;
  for (int k = 0; k < ncand; k++) {
    candidate cd;
    cd.grain = cand[k];
    if (!sphere_interval(shapes[g[cd.grain].shape], &g[cd.grain], o, c->f, &cd.t0, &cd.t1))
      continue;
    int j = m++;
    for (; j > 0 && buf[j - 1].t0 > cd.t0; j--) buf[j] = buf[j - 1];
    buf[j] = cd;
  }
  double best = HUGE_VAL, normal[3] = {0, 0, 0};
  int hit = -1;
  for (int k = 0; k < m && buf[k].t0 < best; k++) {
    double nk[3];
    const int i = buf[k].grain;
    const double t = trace_grain(shapes[g[i].shape], &g[i], o, c->f, buf[k].t0,
                                 fmin(buf[k].t1, best), nk);
    if (t < best) best = t, hit = i, memcpy(normal, nk, sizeof normal);
  }
  if (hit < 0) {
    px[0] = px[1] = px[2] = LSDEM_RENDER_BACKGROUND;
    return;
  }
  /* Lambert + ambient; the light comes from behind the viewer's upper left */
  double light[3], rgb[3];
  for (int k = 0; k < 3; k++) light[k] = -c->f[k] + 0.5 * c->u[k] - 0.4 * c->r[k];
  normalise3(light);
  const double shade = AMBIENT + (1.0 - AMBIENT) * fmax(0.0, lsdem_dot3(normal, light));
  grain_colour(&g[hit], by_shape, rgb);
  for (int k = 0; k < 3; k++) px[k] = (unsigned char)lround(fmin(rgb[k] * shade, 254.0));
}

lsdem_status lsdem_render(const lsdem_shape *const *shapes, int nshapes,
                          const lsdem_render_grain *grains, int ngrains,
                          const lsdem_render_view *view, unsigned char *rgb, lsdem_error *err)
{
  if (!shapes || !view || !rgb || (ngrains > 0 && !grains) || ngrains < 0)
    return lsdem_fail(err, LSDEM_ERR_ARG, "render: NULL argument");
  if (view->width < 1 || view->height < 1 || view->width > 16384 || view->height > 16384)
    return lsdem_fail(err, LSDEM_ERR_ARG, "render: image size %dx%d out of range 1..16384",
                      view->width, view->height);
  for (int i = 0; i < ngrains; i++)
    if (grains[i].shape < 0 || grains[i].shape >= nshapes || !shapes[grains[i].shape] ||
        !(shapes[grains[i].shape]->radius > 0.0) || !isfinite(shapes[grains[i].shape]->radius))
      return lsdem_fail(err, LSDEM_ERR_ARG, "render: grain %d has shape %d: not a shape in "
                        "0..%d with a finite radius", i, grains[i].shape, nshapes - 1);
  for (int i = 0; i < ngrains; i++) {
    const double *x = grains[i].x, *q = grains[i].q;
    const double qq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    if (!isfinite(x[0] + x[1] + x[2]) || !(fabs(qq - 1.0) < 1e-6))
      return lsdem_fail(err, LSDEM_ERR_ARG, "render: grain %d: position not finite or "
                        "quaternion not of unit length", i);
  }
  camera c;
  c.w = view->width, c.h = view->height;
  memcpy(c.f, view->view, sizeof c.f);
  lsdem_cross3(c.f, view->up, c.r);
  if (!normalise3(c.f) || !normalise3(c.r))
    return lsdem_fail(err, LSDEM_ERR_ARG, "render: view direction is zero or parallel to up");
  lsdem_cross3(c.r, c.f, c.u);
  const size_t npx = (size_t)c.w * c.h;
  if (ngrains == 0) {
    memset(rgb, LSDEM_RENDER_BACKGROUND, 3 * npx);
    return LSDEM_OK;
  }
  frame_scene(shapes, grains, ngrains, view, &c);
  bins b = {0, 0, NULL, NULL};
  candidate *buf = malloc((size_t)ngrains * sizeof *buf);
  if (!buf || !build_bins(&c, shapes, grains, ngrains, &b)) {
    free(buf), free(b.start), free(b.list);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "render: out of memory");
  }
  for (int row = 0; row < c.h; row++)
    for (int col = 0; col < c.w; col++) {
      const double a = (col + 0.5 - 0.5 * c.w) * c.pixel, bb = (0.5 * c.h - row - 0.5) * c.pixel;
      double o[3];
      for (int k = 0; k < 3; k++) o[k] = c.centre[k] + a * c.r[k] + bb * c.u[k] - c.back * c.f[k];
      const int bin = (row / BIN) * b.nbx + col / BIN;
      shade_pixel(&c, shapes, grains, b.list + b.start[bin], b.start[bin + 1] - b.start[bin],
                  buf, view->colour_by_shape, o, rgb + 3 * ((size_t)row * c.w + col));
    }
  free(buf);
  free(b.start);
  free(b.list);
  return LSDEM_OK;
}
