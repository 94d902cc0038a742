/* test_band_build.c -- narrow bands of walls (prep/band_build.c, band_write.c) and height
 * maps (io/heightmap.c): every stored sample against a closed-form distance (a flat and a
 * tilted terrain, a cube and the same cube as a container), background bricks' sides,
 * argument checks, the ESRI ASCII, GeoTIFF and PNG readers and their errors, and the band
 * file written, read back bit for bit, and refused when damaged. */
#include "lsdem.h"
#include "file_writers.h"
#include "lsdem_test.h"
#include "geom/closest_triangle.h"

#include <math.h>
#include <png.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ----------------------------------------------------------------- helpers ---- */

static void spill_text(const char *path, const char *text)
{
  FILE *fp = fopen(path, "w");
  fputs(text, fp);
  fclose(fp);
}

static int file_exists(const char *path)
{
  struct stat sb;
  return stat(path, &sb) == 0;
}

/* Position of sample (a, b, c) of the brick in slot (bx, by, bz), as the format defines it. */
static void sample_at(const lsdem_band *b, int bx, int by, int bz, int a, int bb, int c,
                      double p[3])
{
  const int g[3] = {8 * bx + a, 8 * by + bb, 8 * bz + c};
  for (int k = 0; k < 3; k++) p[k] = b->origin[k] + b->h * g[k];
}

/* Calls check(p, stored value, ctx) for every sample of every stored brick, and
 * background(p of the brick's centre, sign, ctx) for every background brick. */
typedef void (*sample_fn)(const double p[3], float v, void *ctx);
static void for_each_sample(const lsdem_band *b, sample_fn check, sample_fn background,
                            void *ctx)
{
  for (int bz = 0; bz < b->nb[2]; bz++)
    for (int by = 0; by < b->nb[1]; by++)
      for (int bx = 0; bx < b->nb[0]; bx++) {
        const int32_t ix = b->index[bx + b->nb[0] * (by + b->nb[1] * bz)];
        double p[3];
        if (ix < 0) {
          sample_at(b, bx, by, bz, 4, 4, 4, p);
          if (background) background(p, ix == LSDEM_BAND_OUTSIDE ? 1.0f : -1.0f, ctx);
          continue;
        }
        for (int c = 0; c < 9; c++)
          for (int bb = 0; bb < 9; bb++)
            for (int a = 0; a < 9; a++) {
              sample_at(b, bx, by, bz, a, bb, c, p);
              check(p, b->phi[(size_t)ix * 729 + a + 9 * (bb + 9 * c)], ctx);
            }
      }
}

static double clampd(double v, double w) { return v > w ? w : v < -w ? -w : v; }

/* ------------------------------------------------------------ flat terrain ---- */

/* z = 0.3 on [0, 1]^2 (3 x 3 heights, cell 0.5); h = 0.25, width 0.375 (both exact in
 * float), so no sample lies on the surface: z - 0.3 is at least 0.125 in size. Over the
 * terrain the distance is |z - 0.3| exactly; beside it, to the square's border. Heights
 * are floats: the surface is at Z0 = (float)0.3. */
#define Z0 ((double)0.3f)
typedef struct {
  double w, worst;
  long exact_bad, checked;
} flat_ctx;

static void flat_check(const double p[3], float v, void *vc)
{
  flat_ctx *c = vc;
  const double dz = p[2] - Z0;
  const double ox = fmax(0.0, fmax(-p[0], p[0] - 1.0)), oy = fmax(0.0, fmax(-p[1], p[1] - 1.0));
  c->checked++;
  if (ox == 0.0 && oy == 0.0) {
    if (v != (float)clampd(dz, c->w)) {
      if (c->exact_bad++ < 3)
        fprintf(stderr, "flat: at (%g, %g, %g) %.9g, expected %.9g\n", p[0], p[1], p[2], v,
                (float)clampd(dz, c->w));
    }
  } else {
    const double d = sqrt(ox * ox + oy * oy + dz * dz);
    c->worst = fmax(c->worst, fabs(v - (dz < 0 ? -1 : 1) * fmin(d, c->w)));
  }
}

static void flat_background(const double p[3], float s, void *vc)
{
  flat_ctx *c = vc;
  CHECK((p[2] > Z0) == (s > 0), "flat: background brick at z %g on the %s side", p[2],
        s > 0 ? "grains'" : "solid");
  c->checked++;
}

static void test_flat_terrain(void)
{
  float z[9];
  for (int i = 0; i < 9; i++) z[i] = 0.3f;
  const lsdem_heightmap hm = {3, 3, 0.0, 0.0, 0.5, z};
  lsdem_mesh m;
  lsdem_band b;
  lsdem_error err;
  CHECK(lsdem_heightmap_mesh(&hm, &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(m.nverts == 9 && m.ntris == 8, "%d verts %d tris", m.nverts, m.ntris);
  for (int t = 0; t < m.ntris; t++) { /* counter-clockwise from above: normals up */
    const double *a = m.verts + 3 * m.tris[3 * t], *bb = m.verts + 3 * m.tris[3 * t + 1];
    const double *c = m.verts + 3 * m.tris[3 * t + 2];
    const double nz = (bb[0] - a[0]) * (c[1] - a[1]) - (bb[1] - a[1]) * (c[0] - a[0]);
    CHECK(nz > 0.0, "triangle %d faces down (%g)", t, nz);
  }
  const double h = 0.25, w = 0.375;
  CHECK(lsdem_band_from_mesh(&m, h, w, LSDEM_BAND_TERRAIN, &b, &err) == LSDEM_OK, "%s", err.msg);
  /* the box: [0,1]^2 across (a terrain's xy extent), {0.3} grown by w + h = 0.625 in z */
  CHECK(b.origin[0] == 0.0 && b.origin[1] == 0.0 && b.origin[2] == Z0 - 0.625,
        "origin %g %g %g", b.origin[0], b.origin[1], b.origin[2]);
  CHECK(b.n[0] == 5 && b.n[1] == 5 && b.n[2] == 6, "n %d %d %d", b.n[0], b.n[1], b.n[2]);
  CHECK(b.nb[0] == 1 && b.nb[1] == 1 && b.nb[2] == 1, "nb %d %d %d", b.nb[0], b.nb[1], b.nb[2]);
  CHECK(b.h == h && b.width == w && b.far == NULL, "h %g width %g", b.h, b.width);
  CHECK(lsdem_band_check(&b, &err) == LSDEM_OK, "%s", err.msg);
  flat_ctx c = {w, 0.0, 0, 0};
  for_each_sample(&b, flat_check, flat_background, &c);
  CHECK(c.exact_bad == 0, "flat: %ld samples over the terrain differ from z - 0.3", c.exact_bad);
  CHECK(c.worst <= 1e-6, "flat: samples beside the terrain differ by %g", c.worst);
  CHECK(c.checked > 500, "flat: only %ld samples", c.checked);
  printf("flat terrain: %lld bricks, %ld samples checked, beside it max error %.2g\n",
         (long long)b.nbricks, c.checked, c.worst);
  lsdem_band_free(&b);
  lsdem_mesh_free(&m);
}

/* ---------------------------------------------------------- tilted terrain ---- */

/* z = 1 + 0.2 x + 0.1 y over [0, 2] x [0, 1.6] (cell 0.4, 6 x 5 heights), against the
 * plane through three of its (float) corner heights. A sample whose foot on the plane
 * lies over the terrain (with a margin) is at the plane distance; any other sample at
 * least that far, up to the width (the terrain is part of the plane). */
typedef struct {
  double n[4]; /* unit normal and offset of the terrain's plane: n.p + n[3] = distance */
  double w, worst, worst_bound;
  double top[2]; /* the band's box across: samples beyond it (a last brick's) are never read */
  long inner, checked;
} tilt_ctx;

static void tilt_check(const double p[3], float v, void *vc)
{
  tilt_ctx *c = vc;
  const double d = c->n[0] * p[0] + c->n[1] * p[1] + c->n[2] * p[2] + c->n[3];
  const double fx = p[0] - d * c->n[0], fy = p[1] - d * c->n[1]; /* the foot */
  if (p[0] > c->top[0] + 1e-9 || p[1] > c->top[1] + 1e-9) return;
  c->checked++;
  if (fx >= 1e-6 && fx <= 2.0 - 1e-6 && fy >= 1e-6 && fy <= 1.6 - 1e-6) {
    c->inner++;
    c->worst = fmax(c->worst, fabs(v - clampd(d, c->w)));
  } else {
    c->worst_bound = fmax(c->worst_bound, fmin(fabs(d), c->w) - fabs(v));
  }
}

static void test_tilted_terrain(void)
{
  float z[30];
  for (int j = 0; j < 5; j++)
    for (int i = 0; i < 6; i++) z[6 * j + i] = (float)(1.0 + 0.2 * (0.4 * i) + 0.1 * (0.4 * j));
  const lsdem_heightmap hm = {6, 5, 0.0, 0.0, 0.4, z};
  lsdem_mesh m;
  lsdem_band b;
  lsdem_error err;
  CHECK(lsdem_heightmap_mesh(&hm, &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(m.ntris == 40, "%d tris", m.ntris);
  /* the float heights lie on a plane to ~1e-7: fit it through three corners */
  const double *A = m.verts, *B = m.verts + 3 * 5, *C = m.verts + 3 * 24;
  double e1[3], e2[3], n[3];
  for (int k = 0; k < 3; k++) e1[k] = B[k] - A[k], e2[k] = C[k] - A[k];
  lsdem_cross3(e1, e2, n);
  const double len = sqrt(lsdem_dot3(n, n));
  tilt_ctx c = {{n[0] / len, n[1] / len, n[2] / len, 0.0}, 0.25, 0.0, 0.0, {0.0, 0.0}, 0, 0};
  c.n[3] = -(c.n[0] * A[0] + c.n[1] * A[1] + c.n[2] * A[2]);
  CHECK(c.n[2] > 0.0, "the plane's normal points down");
  CHECK(lsdem_band_from_mesh(&m, 0.1, 0.25, LSDEM_BAND_TERRAIN, &b, &err) == LSDEM_OK, "%s",
        err.msg);
  CHECK(lsdem_band_check(&b, &err) == LSDEM_OK, "%s", err.msg);
  for (int a = 0; a < 2; a++) c.top[a] = b.origin[a] + (b.n[a] - 1) * b.h;
  for_each_sample(&b, tilt_check, NULL, &c);
  /* heights rounded to float: the vertices sit off the fitted plane by ~1e-7 */
  CHECK(c.worst <= 1e-6, "tilted: samples over the terrain differ from the plane distance by "
        "%g", c.worst);
  CHECK(c.worst_bound <= 1e-6, "tilted: a sample nearer than the plane by %g", c.worst_bound);
  CHECK(c.inner > 2000, "tilted: only %ld samples over the terrain", c.inner);
  printf("tilted terrain: %lld bricks, %ld samples (%ld over the terrain), max error %.2g\n",
         (long long)b.nbricks, c.checked, c.inner, c.worst);
  lsdem_band_free(&b);
  lsdem_mesh_free(&m);
}

/* ------------------------------------------------------------- closed cube ---- */

/* A cube of half-side 1 centred at (0.1, 0.2, 0.3): the exact box SDF at every stored
 * sample, and every background brick on its side (INSIDE when its centre is in the cube).
 * Turned inside out, the same mesh is a container: everything flips. */
typedef struct {
  lsdem_sdf box;
  double c[3], w, worst, flip;
  long inside_bricks, outside_bricks, wrong_side;
} cube_ctx;

static double cube_sdf(cube_ctx *c, const double p[3])
{
  double g[3];
  const double q[3] = {p[0] - c->c[0], p[1] - c->c[1], p[2] - c->c[2]};
  return c->flip * lsdem_sdf_eval(&c->box, q, g);
}

static void cube_check(const double p[3], float v, void *vc)
{
  cube_ctx *c = vc;
  c->worst = fmax(c->worst, fabs(v - clampd(cube_sdf(c, p), c->w)));
}

static void cube_background(const double p[3], float s, void *vc)
{
  cube_ctx *c = vc;
  const double e = cube_sdf(c, p);
  if ((e < 0) != (s < 0)) c->wrong_side++;
  if (s < 0) c->inside_bricks++;
  else c->outside_bricks++;
}

static lsdem_status cube_mesh(lsdem_mesh *m, const double c[3], int skip_face, int flip)
{
  tris s = {0};
  const double hh[3] = {1.0, 1.0, 1.0};
  add_box(&s, c, hh, skip_face);
  write_stl_binary("band_cube.stl", &s, 0);
  free(s.t);
  lsdem_error err;
  const lsdem_status st = lsdem_mesh_read("band_cube.stl", m, &err);
  for (int t = 0; flip && st == LSDEM_OK && t < m->ntris; t++) {
    const int x = m->tris[3 * t + 1];
    m->tris[3 * t + 1] = m->tris[3 * t + 2], m->tris[3 * t + 2] = x;
  }
  return st;
}

static void test_cube(void)
{
  for (int flip = 0; flip < 2; flip++) {
    cube_ctx c;
    memset(&c, 0, sizeof c);
    c.box.kind = LSDEM_SDF_BOX;
    c.box.a[0] = c.box.a[1] = c.box.a[2] = 1.0;
    c.c[0] = 0.1, c.c[1] = 0.2, c.c[2] = 0.3;
    c.w = 0.1, c.flip = flip ? -1.0 : 1.0;
    lsdem_mesh m;
    lsdem_band b;
    lsdem_error err;
    CHECK(cube_mesh(&m, c.c, -1, flip) == LSDEM_OK, "cube mesh");
    CHECK(m.ntris == 12, "%d tris", m.ntris);
    CHECK(lsdem_band_from_mesh(&m, 0.05, 0.1, LSDEM_BAND_MESH, &b, &err) == LSDEM_OK, "%s",
          err.msg);
    CHECK(lsdem_band_check(&b, &err) == LSDEM_OK, "%s", err.msg);
    for_each_sample(&b, cube_check, cube_background, &c);
    CHECK(c.worst <= 1e-6, "cube%s: samples differ from the box SDF by %g",
          flip ? " (container)" : "", c.worst);
    CHECK(c.wrong_side == 0, "cube: %ld background bricks on the wrong side", c.wrong_side);
    /* interior [-0.9, 0.9]^3 beyond the band: 36 cells, several whole bricks of 8 */
    CHECK((flip ? c.outside_bricks : c.inside_bricks) >= 8, "cube: %ld background bricks "
          "inside", flip ? c.outside_bricks : c.inside_bricks);
    /* a lookup at a vertex and at a face centre: 0 within float rounding */
    double g[3];
    const double corner[3] = {1.1, 1.2, 1.3}, face[3] = {0.1, 0.2, 1.3}, deep[3] = {0.1, 0.2, 0.3};
    CHECK_NEAR(lsdem_band_eval(&b, corner, g), 0.0, 1e-7);
    CHECK_NEAR(lsdem_band_eval(&b, face, g), 0.0, 1e-7);
    CHECK_NEAR(lsdem_band_eval(&b, deep, g), -c.flip * 0.1, 1e-7);
    /* the closest triangle from the brick lists is the brute-force closest, for points
     * nearer than the width to the surface */
    int agree = 0, near_points = 0;
    for (int k = 0; k < 2000; k++) {
      const double p[3] = {c.c[0] + 1.2 * srand1(), c.c[1] + 1.2 * srand1(), c.c[2] + 1.2 * srand1()};
      double gp[3];
      if (fabs(lsdem_band_eval(&b, p, gp)) > 0.09) continue;
      near_points++;
      double d2, best = HUGE_VAL;
      const int64_t t = lsdem_band_closest_triangle(&b, p, &d2);
      for (int u = 0; u < m.ntris; u++) {
        double q[3], d[3];
        int feat;
        lsdem_closest_on_triangle(p, m.verts + 3 * m.tris[3 * u], m.verts + 3 * m.tris[3 * u + 1],
                                  m.verts + 3 * m.tris[3 * u + 2], q, &feat);
        lsdem_sub3(p, q, d);
        best = fmin(best, lsdem_dot3(d, d));
      }
      agree += t >= 0 && d2 == best;
    }
    CHECK(near_points > 100 && agree == near_points, "closest triangle: %d of %d agree with "
          "brute force", agree, near_points);
    /* exact mode against the analytic box, near its edges and corners (convex for the
     * cube, concave for the container): trilinear rounds them by about h, exact is exact */
    lsdem_pseudonormals pn;
    CHECK(lsdem_pseudonormals_make(b.verts, b.nverts, b.tris, b.ntris, b.nbr, &pn, &err) ==
          LSDEM_OK, "%s", err.msg);
    lsdem_band exact = b;
    exact.exact = &pn;
    double worst_grid = 0.0, worst_exact = 0.0, worst_normal = 0.0;
    int edge_points = 0;
    for (int k = 0; k < 4000; k++) {
      /* near an edge: two coordinates within 0.1 of +-1 */
      double u[3] = {srand1(), srand1(), srand1()};
      const int a0 = k % 3, a1 = (k + 1) % 3;
      u[a0] = (u[a0] > 0 ? 1.0 : -1.0) + 0.08 * srand1();
      u[a1] = (u[a1] > 0 ? 1.0 : -1.0) + 0.08 * srand1();
      const double p[3] = {c.c[0] + u[0], c.c[1] + u[1], c.c[2] + u[2]};
      double ga[3], gg[3], ge[3];
      const double truth = c.flip * lsdem_sdf_eval(&c.box, u, ga);
      if (fabs(truth) > 0.09) continue;
      edge_points++;
      worst_grid = fmax(worst_grid, fabs(lsdem_band_eval(&b, p, gg) - truth));
      worst_exact = fmax(worst_exact, fabs(lsdem_band_eval(&exact, p, ge) - truth));
      if (fabs(truth) > 1e-3) /* the normal is the analytic gradient's (flipped for a container) */
        worst_normal = fmax(worst_normal, fabs(ge[0] - c.flip * ga[0]) + fabs(ge[1] - c.flip * ga[1]) +
                                              fabs(ge[2] - c.flip * ga[2]));
    }
    printf("cube%s near edges and corners (%d points): grid path error %.3g h, exact %.2g\n",
           flip ? " as a container" : "", edge_points, worst_grid / 0.05, worst_exact);
    CHECK(edge_points > 500, "%d points near the edges", edge_points);
    CHECK(worst_exact <= 1e-6, "exact mode: %.3g off the box's distance", worst_exact);
    /* the mesh holds the box to ~5e-8: its normals, 1e-3 away, to ~5e-5 */
    CHECK(worst_normal <= 1e-4, "exact mode: normals %.3g off the box's", worst_normal);
    CHECK(worst_grid > 10 * worst_exact, "the grid path rounds the edges (%.3g)", worst_grid);
    lsdem_pseudonormals_free(&pn);
    printf("cube%s: %lld bricks (%ld inside, %ld outside background), max error %.2g\n",
           flip ? " as a container" : "", (long long)b.nbricks, c.inside_bricks,
           c.outside_bricks, c.worst);
    lsdem_band_free(&b);
    lsdem_mesh_free(&m);
  }
}

/* -------------------------------------------------------------- bad input ---- */

static void expect_band_error(const lsdem_mesh *m, double h, double w, lsdem_band_source src,
                              lsdem_status want, const char *needle)
{
  lsdem_band b;
  lsdem_error err;
  err.msg[0] = '\0';
  const lsdem_status st = lsdem_band_from_mesh(m, h, w, src, &b, &err);
  CHECK(st == want, "h %g w %g: status %d, expected %d (%s)", h, w, st, want, err.msg);
  CHECK(strstr(err.msg, needle) != NULL, "h %g w %g: '%s' lacks '%s'", h, w, err.msg, needle);
  CHECK(b.index == NULL && b.phi == NULL && b.nbricks == 0, "a failed build left a band");
  if (st == LSDEM_OK) lsdem_band_free(&b);
}

static void test_bad_arguments(void)
{
  const double c[3] = {0, 0, 0};
  lsdem_mesh m, open;
  CHECK(cube_mesh(&m, c, -1, 0) == LSDEM_OK, "cube");
  expect_band_error(&m, 0.0, 0.1, LSDEM_BAND_MESH, LSDEM_ERR_ARG, "spacing h = 0 is not > 0");
  expect_band_error(&m, -0.1, 0.1, LSDEM_BAND_MESH, LSDEM_ERR_ARG, "is not > 0");
  expect_band_error(&m, NAN, 0.1, LSDEM_BAND_MESH, LSDEM_ERR_ARG, "is not > 0");
  expect_band_error(&m, 0.1, 0.05, LSDEM_BAND_MESH, LSDEM_ERR_ARG, "below the spacing");
  expect_band_error(&m, 0.1, 6.5, LSDEM_BAND_MESH, LSDEM_ERR_ARG, "above 64 h");
  expect_band_error(&m, 0.1, 0.2, (lsdem_band_source)7, LSDEM_ERR_ARG, "neither a mesh");
  expect_band_error(&m, 1e-10, 2e-10, LSDEM_BAND_MESH, LSDEM_ERR_NOMEM, "samples along axis 0");
  expect_band_error(&m, 1e-4, 2e-4, LSDEM_BAND_MESH, LSDEM_ERR_NOMEM, "more than 2^31 - 1 brick "
                    "slots");
  lsdem_mesh empty = {0, 0, NULL, NULL};
  expect_band_error(&empty, 0.1, 0.2, LSDEM_BAND_MESH, LSDEM_ERR_ARG, "empty mesh");
  m.verts[4] = NAN;
  expect_band_error(&m, 0.1, 0.2, LSDEM_BAND_MESH, LSDEM_ERR_ARG, "vertex 1 is not finite");
  lsdem_mesh_free(&m);
  CHECK(cube_mesh(&open, c, 2, 0) == LSDEM_OK, "open cube");
  expect_band_error(&open, 0.1, 0.2, LSDEM_BAND_MESH, LSDEM_ERR_ARG, "not closed (4 boundary");
  /* a closed cube with a zero-area triangle: one bottom triangle split at the midpoint of
   * an edge, the sliver (c, m, b) closing the split */
  spill_text("degen.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\n"
             "v 0 1 1\nv 1 0.5 0\nf 1 3 9\nf 1 9 2\nf 2 9 3\nf 1 4 3\nf 1 2 6\nf 1 6 5\n"
             "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\nf 5 6 7\nf 5 7 8\n");
  lsdem_mesh degen;
  lsdem_mesh_topology topo;
  lsdem_error err;
  CHECK(lsdem_mesh_read("degen.obj", &degen, &err) == LSDEM_OK, "%s", err.msg);
  lsdem_mesh_check_closed(&degen, &topo, NULL);
  CHECK(topo.degenerate_tris == 1 && topo.boundary_edges == 0 && topo.nonmanifold_edges == 0 &&
        topo.misoriented_edges == 0, "degen.obj: %d degenerate, %d open", topo.degenerate_tris,
        topo.boundary_edges);
  expect_band_error(&degen, 0.1, 0.2, LSDEM_BAND_MESH, LSDEM_ERR_ARG, "1 degenerate triangles");
  lsdem_mesh_free(&degen);
  /* the open cube is a fine terrain (an open surface): no error */
  lsdem_band b;
  CHECK(lsdem_band_from_mesh(&open, 0.1, 0.2, LSDEM_BAND_TERRAIN, &b, &err) == LSDEM_OK, "%s",
        err.msg);
  lsdem_band_free(&b);
  lsdem_mesh_free(&open);
  /* height maps a surface cannot come from */
  float z4[4] = {0, 0, 0, NAN}, z2[2] = {0, 0};
  const lsdem_heightmap holes = {2, 2, 0, 0, 1, z4}, thin = {2, 1, 0, 0, 1, z2},
                        nocell = {2, 2, 0, 0, 0, z4};
  lsdem_mesh hm;
  CHECK(lsdem_heightmap_mesh(&holes, &hm, &err) == LSDEM_ERR_ARG && strstr(err.msg, "no cell "
        "has four heights"), "%s", err.msg);
  CHECK(lsdem_heightmap_mesh(&thin, &hm, &err) == LSDEM_ERR_ARG && strstr(err.msg, "2 x 1 "
        "heights"), "%s", err.msg);
  CHECK(lsdem_heightmap_mesh(&nocell, &hm, &err) == LSDEM_ERR_ARG && strstr(err.msg, "cell "
        "size 0"), "%s", err.msg);
}

/* --------------------------------------------------------------- holes ---- */

/* A 4 x 4 terrain with one nodata height: the cells touching it are dropped (9 - 4 = 5
 * cells, 10 triangles, 12 of the 15 heights used), and the band over the hole is built
 * and checks out. */
static void test_terrain_hole(void)
{
  float z[16];
  for (int i = 0; i < 16; i++) z[i] = 0.5f;
  z[5] = NAN; /* (1, 1) */
  const lsdem_heightmap hm = {4, 4, 10.0, 20.0, 1.0, z};
  lsdem_mesh m;
  lsdem_band b;
  lsdem_error err;
  CHECK(lsdem_heightmap_mesh(&hm, &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(m.ntris == 10 && m.nverts == 12, "%d tris, %d verts", m.ntris, m.nverts);
  CHECK(lsdem_band_from_mesh(&m, 0.25, 0.5, LSDEM_BAND_TERRAIN, &b, &err) == LSDEM_OK, "%s",
        err.msg);
  CHECK(lsdem_band_check(&b, &err) == LSDEM_OK, "%s", err.msg);
  double g[3];
  const double above[3] = {12.5, 22.5, 0.75}, below[3] = {12.5, 22.5, 0.25};
  CHECK_NEAR(lsdem_band_eval(&b, above, g), 0.25, 1e-6);
  CHECK_NEAR(lsdem_band_eval(&b, below, g), -0.25, 1e-6);
  lsdem_band_free(&b);
  lsdem_mesh_free(&m);
}

/* ----------------------------------------------------- ESRI ASCII grids ---- */

static void expect_asc_error(const char *name, const char *text, const char *needle)
{
  spill_text(name, text);
  lsdem_heightmap hm;
  lsdem_error err;
  err.msg[0] = '\0';
  const lsdem_status st = lsdem_heightmap_read_asc(name, &hm, &err);
  CHECK(st == LSDEM_ERR_FORMAT, "%s: status %d (%s)", name, st, err.msg);
  CHECK(strstr(err.msg, name) && strstr(err.msg, needle), "%s: '%s' lacks '%s'", name, err.msg,
        needle);
  CHECK(hm.z == NULL && hm.nx == 0, "%s: a failed read left heights", name);
}

static void test_asc(void)
{
  spill_text("good.asc", "ncols 3\nNROWS 2\nxllcorner 100\nyllcorner 200\ncellsize 2\n"
                         "NODATA_value -9999\n1 2 3\n4 -9999 6.5\n");
  lsdem_heightmap hm;
  lsdem_error err;
  CHECK(lsdem_heightmap_read_asc("good.asc", &hm, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(hm.nx == 3 && hm.ny == 2 && hm.cell == 2.0, "%d x %d cell %g", hm.nx, hm.ny, hm.cell);
  CHECK(hm.x0 == 101.0 && hm.y0 == 201.0, "corner origin: first centre %g %g", hm.x0, hm.y0);
  /* file rows north to south: the last row is y = 0 */
  CHECK(hm.z[0] == 4.0f && isnan(hm.z[1]) && hm.z[2] == 6.5f && hm.z[3] == 1.0f &&
        hm.z[5] == 3.0f, "heights %g %g %g %g %g", hm.z[0], hm.z[1], hm.z[2], hm.z[3], hm.z[5]);
  lsdem_heightmap_free(&hm);
  /* centre origin, keys in another order, values over several lines, CRLF */
  spill_text("centre.asc", "cellsize 0.5\r\nxllcenter 1\r\nyllcenter -1\r\nncols 2\r\nnrows 2\r\n"
                           "1\r\n2 3\r\n4\r\n");
  CHECK(lsdem_heightmap_read_asc("centre.asc", &hm, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(hm.x0 == 1.0 && hm.y0 == -1.0 && hm.z[0] == 3.0f && hm.z[3] == 2.0f, "centre origin");
  lsdem_heightmap_free(&hm);

  const char *head = "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n";
  char text[512];
  expect_asc_error("bad_key.asc", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncelsize 1\n"
                   "1 2 3 4\n", "line 5: unknown header key 'celsize'");
  expect_asc_error("dxdy.asc", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ndx 1\ndy 2\n1 2 3 4\n",
                   "line 5: unknown header key 'dx': cells that are not square");
  expect_asc_error("no_cell.asc", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\n1 2 3 4\n",
                   "missing header key 'cellsize'");
  expect_asc_error("no_x.asc", "ncols 2\nnrows 2\nyllcorner 0\ncellsize 1\n1 2 3 4\n",
                   "missing header key 'xllcorner' or 'xllcenter'");
  expect_asc_error("both_x.asc", "ncols 2\nnrows 2\nxllcorner 0\nxllcenter 0\nyllcorner 0\n"
                   "cellsize 1\n1 2 3 4\n", "both 'xllcorner' and 'xllcenter'");
  expect_asc_error("twice.asc", "ncols 2\nnrows 2\nncols 3\nxllcorner 0\nyllcorner 0\n"
                   "cellsize 1\n1 2 3 4\n", "line 3: header key 'ncols' repeated");
  expect_asc_error("bad_ncols.asc", "ncols 2.5\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n"
                   "1 2 3 4\n", "line 1: 'ncols' 2.5 is not a positive integer");
  expect_asc_error("bad_cell.asc", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize -1\n"
                   "1 2 3 4\n", "line 5: 'cellsize' -1 is not > 0");
  expect_asc_error("no_value.asc", "ncols 2\nnrows 2\nxllcorner\nyllcorner 0\ncellsize 1\n"
                   "1 2 3 4\n", "line 3: header key 'xllcorner' needs a finite number");
  snprintf(text, sizeof text, "%s1 2\n3\n", head);
  expect_asc_error("few.asc", text, "line 7: the file ends after 3 of the ncols x nrows = 2 x 2 "
                   "= 4");
  snprintf(text, sizeof text, "%s1 2\n3 4\n5\n", head);
  expect_asc_error("many.asc", text, "line 8: more than the ncols x nrows = 2 x 2 = 4 values");
  snprintf(text, sizeof text, "%s1 2\n3 x4\n", head);
  expect_asc_error("word.asc", text, "line 7: 'x4' is not a number");
  snprintf(text, sizeof text, "%s1 2\nnan 4\n", head);
  expect_asc_error("nan.asc", text, "line 7: value 'nan' is not finite");
  expect_asc_error("nodata.asc", "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n"
                   "NODATA_value -1\n-1 -1\n", "every height is nodata");
  expect_asc_error("header_only.asc", head, "line 6: the file ends in the header");
}

/* ------------------------------------------------------ GeoTIFF and PNG ---- */

static void write_geotiff(const char *path, int with_scale)
{
  static const TIFFFieldInfo geo[] = {
      {33550, -1, -1, TIFF_DOUBLE, FIELD_CUSTOM, 1, 1, "ModelPixelScaleTag"},
      {33922, -1, -1, TIFF_DOUBLE, FIELD_CUSTOM, 1, 1, "ModelTiepointTag"},
      {42113, -1, -1, TIFF_ASCII, FIELD_CUSTOM, 1, 0, "GDALNoDataValue"}};
  TIFF *t = TIFFOpen(path, "w");
  TIFFMergeFieldInfo(t, geo, 3);
  TIFFSetField(t, TIFFTAG_IMAGEWIDTH, 3);
  TIFFSetField(t, TIFFTAG_IMAGELENGTH, 2);
  TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 32);
  TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_IEEEFP);
  TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 1);
  TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
  TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, 2);
  const double scale[3] = {5, 5, 0}, tie[6] = {0, 0, 0, 1000, 2000, 0};
  if (with_scale) {
    TIFFSetField(t, 33550, 3, scale);
    TIFFSetField(t, 33922, 6, tie);
    TIFFSetField(t, 42113, "-32768");
  }
  const float px[6] = {1, 2, 3, 4, -32768, 6}; /* row 0 (north) first */
  TIFFWriteEncodedStrip(t, 0, (void *)px, sizeof px);
  TIFFClose(t);
}

static void write_png16(const char *path)
{
  FILE *f = fopen(path, "wb");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, f);
  png_set_IHDR(png, info, 2, 2, 16, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  const unsigned char rows[2][4] = {{0x00, 0x01, 0x01, 0x00}, {0xff, 0xff, 0x12, 0x34}};
  png_write_row(png, rows[0]);
  png_write_row(png, rows[1]);
  png_write_end(png, NULL);
  png_destroy_write_struct(&png, &info);
  fclose(f);
}

static void test_tiff_png(void)
{
  lsdem_heightmap hm;
  lsdem_error err;
  write_geotiff("geo.tif", 1);
  CHECK(lsdem_heightmap_read("geo.tif", 0.0, 1.0, &hm, &err) == LSDEM_OK, "%s", err.msg);
  /* PixelIsArea: the north-west pixel's centre at (1000 + 2.5, 2000 - 2.5); the south-west
   * one 5 further south */
  CHECK(hm.nx == 3 && hm.ny == 2 && hm.cell == 5.0, "%d x %d cell %g", hm.nx, hm.ny, hm.cell);
  CHECK(hm.x0 == 1002.5 && hm.y0 == 1992.5, "origin %g %g", hm.x0, hm.y0);
  CHECK(hm.z[0] == 4.0f && isnan(hm.z[1]) && hm.z[3] == 1.0f && hm.z[5] == 3.0f, "heights");
  lsdem_heightmap_free(&hm);
  CHECK(lsdem_heightmap_read("geo.tif", 2.0, 1.0, &hm, &err) == LSDEM_ERR_ARG &&
        strstr(err.msg, "gives its pixel size"), "%s", err.msg);
  write_geotiff("plain.tif", 0);
  CHECK(lsdem_heightmap_read("plain.tif", 0.0, 1.0, &hm, &err) == LSDEM_ERR_FORMAT &&
        strstr(err.msg, "no ModelPixelScaleTag (33550)"), "%s", err.msg);
  CHECK(lsdem_heightmap_read("plain.tif", 2.0, 0.5, &hm, &err) == LSDEM_OK, "%s", err.msg);
  /* no GDAL_NODATA: -32768 is a height; zscale 0.5 */
  CHECK(hm.cell == 2.0 && hm.x0 == 0.0 && hm.z[0] == 2.0f && hm.z[1] == -16384.0f &&
        hm.z[5] == 1.5f, "plain tiff %g %g %g", hm.z[0], hm.z[1], hm.z[5]);
  lsdem_heightmap_free(&hm);
  write_png16("h16.png");
  CHECK(lsdem_heightmap_read("h16.png", 0.5, 0.01, &hm, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(hm.nx == 2 && hm.ny == 2 && hm.cell == 0.5, "png %d x %d", hm.nx, hm.ny);
  /* top row (north) is y = 1: 1 and 256; bottom row 65535 and 0x1234 */
  CHECK(hm.z[2] == 0.01f && hm.z[3] == 2.56f && hm.z[0] == (float)(65535 * 0.01) &&
        hm.z[1] == (float)(0x1234 * 0.01), "png heights %g %g %g %g", hm.z[0], hm.z[1], hm.z[2],
        hm.z[3]);
  lsdem_heightmap_free(&hm);
  CHECK(lsdem_heightmap_read("h16.png", 0.0, 1.0, &hm, &err) == LSDEM_ERR_ARG &&
        strstr(err.msg, "needs a cell size"), "%s", err.msg);
  unsigned char rgb[12] = {0};
  CHECK(lsdem_png_write("rgb.png", 2, 2, rgb, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_heightmap_read("rgb.png", 1.0, 1.0, &hm, &err) == LSDEM_ERR_FORMAT &&
        strstr(err.msg, "a colour image"), "%s", err.msg);
  CHECK(lsdem_heightmap_read("x.xyz", 0.0, 1.0, &hm, &err) == LSDEM_ERR_ARG &&
        strstr(err.msg, "unknown height-map format"), "%s", err.msg);
}

/* ------------------------------------------------------------ band files ---- */

static unsigned char *slurp(const char *path, size_t *n)
{
  FILE *f = fopen(path, "rb");
  fseek(f, 0, SEEK_END);
  *n = (size_t)ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char *b = malloc(*n);
  *n = fread(b, 1, *n, f);
  fclose(f);
  return b;
}

static void expect_open_error(const char *path, const char *needle)
{
  lsdem_band_file *f = NULL;
  lsdem_error err;
  CHECK(lsdem_band_open(path, &f, &err) == LSDEM_ERR_FORMAT && f == NULL, "%s opened", path);
  CHECK(strstr(err.msg, needle) != NULL, "%s: '%s' lacks '%s'", path, err.msg, needle);
}

static void test_band_file(void)
{
  const double c[3] = {0, 0, 0};
  lsdem_mesh m;
  lsdem_band b;
  lsdem_error err;
  CHECK(cube_mesh(&m, c, -1, 0) == LSDEM_OK, "cube");
  CHECK(lsdem_band_from_mesh(&m, 0.1, 0.2, LSDEM_BAND_MESH, &b, &err) == LSDEM_OK, "%s", err.msg);
  remove("cube.band");
  CHECK(lsdem_band_write("cube.band", &b, LSDEM_BAND_MESH, &err) == LSDEM_OK, "%s", err.msg);
  lsdem_band_file *f = NULL;
  CHECK(lsdem_band_open("cube.band", &f, &err) == LSDEM_OK, "%s", err.msg);
  if (f) {
    const lsdem_band *r = lsdem_band_file_band(f);
    const size_t slots = (size_t)b.nb[0] * b.nb[1] * b.nb[2];
    CHECK(lsdem_band_file_source(f) == LSDEM_BAND_MESH, "source");
    CHECK(memcmp(r->n, b.n, sizeof b.n) == 0 && memcmp(r->nb, b.nb, sizeof b.nb) == 0 &&
          memcmp(r->origin, b.origin, sizeof b.origin) == 0 && r->h == b.h &&
          r->width == b.width && r->nbricks == b.nbricks, "header fields differ");
    CHECK(memcmp(r->index, b.index, slots * 4) == 0, "index differs");
    CHECK(memcmp(r->phi, b.phi, (size_t)b.nbricks * 729 * 4) == 0, "samples differ");
    CHECK(r->ntris == 12 && r->nverts == b.nverts && b.ntris == 12, "surface: %lld triangles",
          (long long)r->ntris);
    if (r->ntris == 12) {
      CHECK(memcmp(r->verts, b.verts, (size_t)b.nverts * 24) == 0 &&
            memcmp(r->tris, b.tris, 12 * 12) == 0, "surface differs");
      CHECK(memcmp(r->brick_tri_start, b.brick_tri_start, ((size_t)b.nbricks + 1) * 8) == 0 &&
            memcmp(r->brick_tris, b.brick_tris, (size_t)b.brick_tri_start[b.nbricks] * 4) == 0,
            "brick lists differ");
      CHECK(memcmp(r->nbr, b.nbr, 12 * 12) == 0, "triangle neighbours differ");
    }
    lsdem_band_close(f);
  }
  /* the size: header, index, then each section at a multiple of 64 bytes */
  size_t n;
  unsigned char *bytes = slurp("cube.band", &n);
  size_t at = 128 + 4 * (size_t)b.nb[0] * b.nb[1] * b.nb[2];
  const size_t sections[6] = {(size_t)b.nbricks * 729 * 4, (size_t)b.nverts * 24, 12 * 12,
                              ((size_t)b.nbricks + 1) * 8, (size_t)b.brick_tri_start[b.nbricks] * 4,
                              12 * 12};
  for (int k = 0; k < 6; k++) at = (at + 63) / 64 * 64 + sections[k];
  CHECK(n == at, "file size %zu, expected %zu", n, at);
  CHECK(memcmp(bytes, "LSDEMBND", 8) == 0, "magic");
  bytes[n - 5] ^= 0x10; /* a sample */
  write_file_bytes("bad_payload.band", bytes, n);
  expect_open_error("bad_payload.band", "payload checksum mismatch");
  bytes[n - 5] ^= 0x10;
  bytes[60] ^= 0x01; /* the origin */
  write_file_bytes("bad_header.band", bytes, n);
  expect_open_error("bad_header.band", "header checksum mismatch");
  bytes[60] ^= 0x01;
  write_file_bytes("short.band", bytes, n - 4);
  expect_open_error("short.band", "truncated");
  free(bytes);
  /* a terrain file says so */
  CHECK(lsdem_band_write("terrain.band", &b, LSDEM_BAND_TERRAIN, &err) == LSDEM_OK, "%s",
        err.msg);
  CHECK(lsdem_band_open("terrain.band", &f, &err) == LSDEM_OK, "%s", err.msg);
  if (f) CHECK(lsdem_band_file_source(f) == LSDEM_BAND_TERRAIN, "terrain source");
  lsdem_band_close(f);
  /* a failed write leaves nothing: into a missing folder, over a folder */
  CHECK(lsdem_band_write("no/such/dir/x.band", &b, LSDEM_BAND_MESH, &err) == LSDEM_ERR_IO,
        "wrote into a missing folder");
  mkdir("a_folder.band", 0755);
  CHECK(lsdem_band_write("a_folder.band", &b, LSDEM_BAND_MESH, &err) == LSDEM_ERR_IO &&
        strstr(err.msg, "not a regular file"), "%s", err.msg);
  /* a band that fails lsdem_band_check is not written */
  float *phi = (float *)b.phi;
  phi[3] = (float)(2.0 * b.width);
  remove("bad.band");
  CHECK(lsdem_band_write("bad.band", &b, LSDEM_BAND_MESH, &err) == LSDEM_ERR_ARG &&
        strstr(err.msg, "outside [-width, width]") && !file_exists("bad.band"), "%s", err.msg);
  lsdem_band_free(&b);
  lsdem_mesh_free(&m);
}

/* ------------------------------------------------- a terrain kept as heights ---- */

/* A rough terrain (smooth relief, a one-cell spike and a one-cell slot: sharp features a
 * trilinear band rounds) kept as heights: at random points, within the band the value is
 * the exact signed distance to the nearest of all its triangles (brute force, pseudonormal
 * signs) and equals the brick band's exact mode; beyond, a lower bound >= width with the
 * right sign; the file round trip keeps the bits; nodata is refused. */
static void test_heights(void)
{
  enum { NX = 40, NY = 30 };
  float z[NX * NY];
  for (int j = 0; j < NY; j++)
    for (int i = 0; i < NX; i++)
      z[NX * j + i] = (float)(3.0 * sin(0.15 * i) * cos(0.1 * j) + 0.05 * srand1());
  z[NX * 12 + 20] += 2.0f; /* spike */
  z[NX * 20 + 8] -= 1.5f;  /* slot */
  const lsdem_heightmap hm = {NX, NY, -3.0, 2.0, 0.5, z};
  lsdem_mesh m;
  lsdem_band bricks, heights;
  lsdem_pseudonormals pn;
  lsdem_error err;
  CHECK(lsdem_heightmap_mesh(&hm, &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_band_from_mesh(&m, 0.5, 1.0, LSDEM_BAND_TERRAIN, &bricks, &err) == LSDEM_OK,
        "%s", err.msg);
  CHECK(lsdem_pseudonormals_make(bricks.verts, bricks.nverts, bricks.tris, bricks.ntris,
                                 bricks.nbr, &pn, &err) == LSDEM_OK, "%s", err.msg);
  bricks.exact = &pn;
  CHECK(lsdem_band_from_heights(&hm, 1.0, &heights, &err) == LSDEM_OK, "%s", err.msg);
  float *tiles = NULL;
  CHECK(lsdem_heights_tiles(&heights, &tiles, heights.nt, &err) == LSDEM_OK, "%s", err.msg);
  heights.tile_range = tiles;
  CHECK(lsdem_band_check(&heights, &err) == LSDEM_OK, "%s", err.msg);
  double worst = 0.0, worst_bricks = 0.0, worst_grad = 0.0, worst_bound = 0.0;
  long inside = 0, beyond = 0, wrong_side = 0;
  for (int k = 0; k < 20000; k++) {
    const double p[3] = {-3.0 + 19.5 * urand(), 2.0 + 14.5 * urand(), -5.0 + 12.0 * urand()};
    double best = HUGE_VAL, d_true = 0.0, g_true[3] = {0, 0, 0}, g[3], gb[3];
    for (int64_t t = 0; t < m.ntris; t++) {
      double gt[3];
      const double d = lsdem_signed_distance_to_triangle(m.verts, m.tris, &pn, p, t, gt);
      if (fabs(d) < best) best = fabs(d), d_true = d, memcpy(g_true, gt, sizeof gt);
    }
    const double v = lsdem_band_eval(&heights, p, g);
    if ((v > 0) != (d_true > 0) && best > 1e-9) wrong_side++;
    if (best < 0.999 * heights.width) {
      inside++;
      worst = fmax(worst, fabs(v - d_true));
      worst_bricks = fmax(worst_bricks, fabs(lsdem_band_eval(&bricks, p, gb) - v));
      if (best > 1e-6)
        for (int a = 0; a < 3; a++) worst_grad = fmax(worst_grad, fabs(g[a] - g_true[a]));
    } else if (best > 1.001 * heights.width) {
      beyond++;
      /* a lower bound, never nearer than width nor farther than the truth */
      worst_bound = fmax(worst_bound, fmax(heights.width - fabs(v), fabs(v) - best));
    }
  }
  CHECK(inside > 3000 && beyond > 3000, "%ld points in the band, %ld beyond", inside, beyond);
  CHECK(wrong_side == 0, "%ld points on the wrong side", wrong_side);
  CHECK(worst <= 1e-12, "heights vs the nearest of all triangles: %g", worst);
  CHECK(worst_bricks <= 1e-12, "heights vs the brick band's exact mode: %g", worst_bricks);
  CHECK(worst_grad <= 1e-9, "heights' direction vs the nearest triangle's: %g", worst_grad);
  CHECK(worst_bound <= 1e-12, "beyond the band: a bound off by %g", worst_bound);
  printf("heights: %ld points in the band (max error %.2g, bricks' exact mode %.2g), %ld "
         "beyond; %zu bytes against %zu for bricks\n", inside, worst, worst_bricks, beyond,
         lsdem_band_bytes(&heights), lsdem_band_bytes(&bricks));
  /* file round trip: the same bits at the same points */
  remove("heights.band");
  CHECK(lsdem_band_write("heights.band", &heights, LSDEM_BAND_HEIGHTS, &err) == LSDEM_OK, "%s",
        err.msg);
  CHECK(lsdem_band_write("heights2.band", &heights, LSDEM_BAND_TERRAIN, &err) == LSDEM_ERR_ARG,
        "heights written as bricks");
  lsdem_band_file *f = NULL;
  CHECK(lsdem_band_open("heights.band", &f, &err) == LSDEM_OK, "%s", err.msg);
  if (f) {
    const lsdem_band *r = lsdem_band_file_band(f);
    CHECK(lsdem_band_file_source(f) == LSDEM_BAND_HEIGHTS && r->heights && !r->index,
          "read back as heights");
    long differ = 0;
    for (int k = 0; k < 2000; k++) {
      const double p[3] = {-5.0 + 24.0 * urand(), 0.0 + 18.0 * urand(), -5.0 + 12.0 * urand()};
      double g1[3], g2[3];
      differ += lsdem_band_eval(r, p, g1) != lsdem_band_eval(&heights, p, g2) ||
                memcmp(g1, g2, sizeof g1) != 0;
    }
    CHECK(differ == 0, "%ld lookups differ after the round trip", differ);
    lsdem_band_close(f);
  }
  size_t n;
  unsigned char *bytes = slurp("heights.band", &n);
  bytes[n - 3] ^= 0x10; /* a height */
  write_file_bytes("bad_heights.band", bytes, n);
  expect_open_error("bad_heights.band", "payload checksum mismatch");
  free(bytes);
  /* nodata cannot be kept as heights */
  z[NX * 3 + 4] = NAN;
  lsdem_band holes;
  CHECK(lsdem_band_from_heights(&hm, 1.0, &holes, &err) == LSDEM_ERR_ARG &&
        strstr(err.msg, "nodata") && strstr(err.msg, "(4, 3)"), "%s", err.msg);
  free(tiles);
  lsdem_pseudonormals_free(&pn);
  lsdem_band_free(&heights);
  lsdem_band_free(&bricks);
  lsdem_mesh_free(&m);
}

/* ------------------------------------------------------- ridges and slots ---- */

/* A plate 0.15 thick (a ridge at h = 0.1: thinner than 2 h) under a block 0.33 thick (float
 * STL coordinates: widths to 1e-6)
 * with a 0.12 gap between them (a slot): exactly one of each, with their widths; at
 * h = 0.05 (2 h = 0.1) neither. */
static void test_thin_features(void)
{
  tris s = {0};
  const double c1[3] = {0.0, 0.0, 0.075}, h1[3] = {1.0, 1.0, 0.075};
  const double c2[3] = {0.0, 0.0, 0.435}, h2[3] = {1.0, 1.0, 0.165};
  add_box(&s, c1, h1, -1);
  add_box(&s, c2, h2, -1);
  write_stl_binary("band_thin.stl", &s, 0);
  free(s.t);
  lsdem_mesh m;
  lsdem_error err;
  CHECK(lsdem_mesh_read("band_thin.stl", &m, &err) == LSDEM_OK, "%s", err.msg);
  for (int fine = 0; fine < 2; fine++) {
    const double h = fine ? 0.05 : 0.1;
    lsdem_band b;
    lsdem_thin_feature *f = NULL;
    int n = -1;
    CHECK(lsdem_band_from_mesh(&m, h, 2.0 * h, LSDEM_BAND_MESH, &b, &err) == LSDEM_OK, "%s",
          err.msg);
    CHECK(lsdem_band_thin_features(&b, 2.0 * h, &f, &n, &err) == LSDEM_OK, "%s", err.msg);
    if (fine) {
      CHECK(n == 0, "h = 0.05: %d thin features, expected none", n);
    } else {
      CHECK(n == 2, "h = 0.1: %d thin features, expected a ridge and a slot", n);
    }
    if (!fine && n == 2) {
      CHECK(f[0].ridge && f[0].ntris == 4 && fabs(f[0].thinnest - 0.15) < 1e-6 &&
            fabs(f[0].at[2] - (f[0].at[2] > 0.1 ? 0.15 : 0.0)) < 1e-6,
            "ridge: %d triangles, %g across at z = %g", f[0].ntris, f[0].thinnest, f[0].at[2]);
      CHECK(!f[1].ridge && f[1].ntris == 4 && fabs(f[1].thinnest - 0.12) < 1e-6,
            "slot: %d triangles, %g across", f[1].ntris, f[1].thinnest);
    }
    free(f);
    lsdem_band_free(&b);
  }
  lsdem_mesh_free(&m);
}

/* ------------------------------------------------------- meshes with holes ---- */

/* Samples of a band against the sphere of radius 1 at the origin: stored samples farther
 * than `skip` from it on the wrong side, and background slots on the wrong side; points
 * of the sphere above z = zcut (a hole's chord plane, which a winding number spans instead
 * of the cap) are not counted. */
static int sphere_side_known(const double p[3], double skip, double zcut)
{
  const double r = sqrt(lsdem_dot3(p, p));
  return fabs(r - 1.0) > skip && !(p[2] > zcut - skip && r < 1.0 + skip);
}

static long sphere_sign_errors(const lsdem_band *b, double skip, double zcut)
{
  long wrong = 0;
  for (int bz = 0; bz < b->nb[2]; bz++)
    for (int by = 0; by < b->nb[1]; by++)
      for (int bx = 0; bx < b->nb[0]; bx++) {
        const int32_t k = b->index[bx + (int64_t)b->nb[0] * (by + (int64_t)b->nb[1] * bz)];
        if (k < 0) { /* background: its centre's side */
          double c[3];
          sample_at(b, bx, by, bz, 4, 4, 4, c);
          if (sphere_side_known(c, 0.0, zcut))
            wrong += (sqrt(lsdem_dot3(c, c)) > 1.0) != (k == LSDEM_BAND_OUTSIDE);
          continue;
        }
        for (int cc = 0; cc < 9; cc++)
          for (int bb = 0; bb < 9; bb++)
            for (int a = 0; a < 9; a++) {
              double p[3];
              sample_at(b, bx, by, bz, a, bb, cc, p);
              const double r = sqrt(lsdem_dot3(p, p));
              const float v = b->phi[729 * (size_t)k + a + 9 * (bb + 9 * cc)];
              if (sphere_side_known(p, skip, zcut)) wrong += (v > 0.0f) != (r > 1.0);
            }
      }
  return wrong;
}

/* An icosphere (1280 triangles, edges ~0.13) with one triangle removed: refused as a
 * closed mesh; as a mesh with holes every sample and background brick is on the sphere's
 * side (the winding number closes the hole); the closed icosphere gives the same bits by
 * either path; with a cap of radius 0.6 cut off the hole is too wide and is refused. */
static void test_open_mesh(void)
{
  tris s = {0};
  add_icosphere(&s, 1.0, 3);
  lsdem_mesh m;
  lsdem_band closed, open, hole;
  lsdem_error err;
  write_stl_binary("band_ico.stl", &s, 0);
  CHECK(lsdem_mesh_read("band_ico.stl", &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_band_from_mesh(&m, 0.05, 0.1, LSDEM_BAND_MESH, &closed, &err) == LSDEM_OK, "%s",
        err.msg);
  CHECK(lsdem_band_from_open_mesh(&m, 0.05, 0.1, &open, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(closed.nbricks == open.nbricks &&
        memcmp(closed.phi, open.phi, (size_t)closed.nbricks * 729 * sizeof(float)) == 0,
        "a closed mesh differs between the closed and the open path");
  CHECK(sphere_sign_errors(&closed, 0.01, 2.0) == 0, "closed icosphere: samples on the wrong side");
  lsdem_band_free(&open);
  lsdem_band_free(&closed);
  lsdem_mesh_free(&m);
  /* one triangle out (the first: on the face around a vertex at (.., 0.85, ..)) */
  tris one = s;
  one.t += 9, one.n -= 1;
  write_stl_binary("band_ico_hole.stl", &one, 0);
  CHECK(lsdem_mesh_read("band_ico_hole.stl", &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_band_from_mesh(&m, 0.05, 0.1, LSDEM_BAND_MESH, &hole, &err) == LSDEM_ERR_ARG &&
        strstr(err.msg, "3 boundary edges"), "a mesh with a hole as closed: %s", err.msg);
  CHECK(lsdem_band_from_open_mesh(&m, 0.05, 0.1, &hole, &err) == LSDEM_OK, "%s", err.msg);
  const long wrong = sphere_sign_errors(&hole, 0.01, 2.0);
  CHECK(wrong == 0, "icosphere with a hole: %ld samples or bricks on the wrong side", wrong);
  lsdem_band_free(&hole);
  lsdem_mesh_free(&m);
  /* a cap above z = 0.95 cut off (a hole 0.6 across), band 0.4 wide: the winding number
   * spans the hole by about its chord plane, so the samples over the hole within 0.05 of
   * the sphere, on which the rim's pseudonormals are wrong, are outside; 0.1 wide, the hole
   * is too wide and the fill meets itself through it */
  for (int wide = 0; wide < 2; wide++) {
    tris cut = {0};
    const double zcut = wide ? 0.8 : 0.95;
    for (int t = 0; t < s.n; t++) {
      const double zc = (s.t[9 * t + 2] + s.t[9 * t + 5] + s.t[9 * t + 8]) / 3.0;
      if (zc < zcut) add_tri(&cut, s.t + 9 * t, s.t + 9 * t + 3, s.t + 9 * t + 6);
    }
    write_stl_binary("band_ico_cut.stl", &cut, 0);
    free(cut.t);
    CHECK(lsdem_mesh_read("band_ico_cut.stl", &m, &err) == LSDEM_OK, "%s", err.msg);
    if (wide) {
      CHECK(lsdem_band_from_open_mesh(&m, 0.05, 0.1, &hole, &err) == LSDEM_ERR_ARG &&
            strstr(err.msg, "holes are too wide"), "a wide hole: %s", err.msg);
    } else {
      CHECK(lsdem_band_from_open_mesh(&m, 0.05, 0.4, &hole, &err) == LSDEM_OK, "%s", err.msg);
      const long off = sphere_sign_errors(&hole, 0.01, zcut);
      CHECK(off == 0, "icosphere without its cap: %ld samples or bricks on the wrong side", off);
      lsdem_band_free(&hole);
    }
    lsdem_mesh_free(&m);
  }
  free(s.t);
}

/* ---------------------------------------------- the band against its mesh ---- */

/* lsdem_band_misfit: a flat terrain's band is its plane (a linear function is interpolated
 * exactly: both distances ~float rounding). A turned cube's band rounds its edges and cuts
 * its corners, so both distances are positive, within bounds that hold for any band of
 * exact samples: a zero crossing on a grid edge has the true surface on that edge, at most
 * h away; a trilinear value at a surface point mixes samples at most sqrt 3 h away, each
 * no larger than that (1-Lipschitz). (Measured: 0.48 h and 0.27 h.) Crossings: more than
 * the faces' area over h^2. */
static void test_misfit(void)
{
  float z[100];
  for (int k = 0; k < 100; k++) z[k] = 1.25f;
  const lsdem_heightmap hm = {10, 10, 0.0, 0.0, 0.5, z};
  lsdem_mesh m;
  lsdem_band b;
  lsdem_band_distance d;
  lsdem_error err;
  CHECK(lsdem_heightmap_mesh(&hm, &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_band_from_mesh(&m, 0.1, 0.2, LSDEM_BAND_TERRAIN, &b, &err) == LSDEM_OK, "%s",
        err.msg);
  lsdem_band_misfit(&b, &m, &d);
  CHECK(d.hausdorff < 1e-6 && d.crossings > 2000, "flat terrain: Hausdorff %g over %lld "
        "crossings", d.hausdorff, (long long)d.crossings);
  lsdem_band_free(&b);
  lsdem_mesh_free(&m);
  /* the cube turned by 30 deg about z and 20 deg about x: its faces off the grid's planes
   * (unturned they lie on them and the band is exact) */
  const double c[3] = {0.0, 0.0, 0.0}, cz = cos(M_PI / 6), sz = sin(M_PI / 6);
  const double cx = cos(M_PI / 9), sx = sin(M_PI / 9);
  CHECK(cube_mesh(&m, c, -1, 0) == LSDEM_OK, "cube");
  for (int v = 0; v < m.nverts; v++) {
    double *p = m.verts + 3 * v;
    const double x = cz * p[0] - sz * p[1], y = sz * p[0] + cz * p[1];
    p[0] = x, p[1] = cx * y - sx * p[2], p[2] = sx * y + cx * p[2];
  }
  CHECK(lsdem_band_from_mesh(&m, 0.1, 0.2, LSDEM_BAND_MESH, &b, &err) == LSDEM_OK, "%s", err.msg);
  lsdem_band_misfit(&b, &m, &d);
  CHECK(d.mesh_to_zero > 1e-3 * 0.1 && d.mesh_to_zero <= sqrt(3.0) * 0.1 &&
        d.zero_to_mesh > 1e-3 * 0.1 && d.zero_to_mesh <= 0.1 &&
        d.hausdorff == fmax(d.mesh_to_zero, d.zero_to_mesh) &&
        d.crossings > 6 * 4 * 100, "cube: mesh to zero %g, zero to mesh %g over %lld crossings",
        d.mesh_to_zero, d.zero_to_mesh, (long long)d.crossings);
  printf("misfit: cube at h = 0.1: mesh to zero %.3g h, zero to mesh %.3g h (%lld crossings)\n",
         d.mesh_to_zero / 0.1, d.zero_to_mesh / 0.1, (long long)d.crossings);
  lsdem_band_free(&b);
  lsdem_mesh_free(&m);
}

int main(void)
{
  test_flat_terrain();
  test_tilted_terrain();
  test_cube();
  test_bad_arguments();
  test_terrain_hole();
  test_asc();
  test_tiff_png();
  test_band_file();
  test_heights();
  test_thin_features();
  test_open_mesh();
  test_misfit();
  return lsdem_test_summary();
}
