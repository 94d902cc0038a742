/* test_mesh.c -- mesh readers (STL ASCII/binary, OBJ), closedness and self-intersection
 * checks, and the mesh signed-distance grid against analytic box and sphere SDFs. */
#include "lsdem.h"
#include "file_writers.h"
#include "lsdem_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------- test meshes ---- */

static void spill_text(const char *path, const char *text)
{
  FILE *fp = fopen(path, "w");
  fputs(text, fp);
  fclose(fp);
}

/* ------------------------------------------------------------------- tests ---- */

/* Grid SDF of a mesh vs an analytic SDF: at the samples (distance to the polyhedron
 * is exact) and at random points within 0.5 of the surface through trilinear
 * interpolation (grid error, O(h^2 kappa) plus the kinks at box edges). */
static void compare_sdf(const lsdem_mesh *m, const lsdem_sdf *exact, double h, double tol_sample,
                        double tol_interp, const char *what)
{
  lsdem_grid g;
  lsdem_error err;
  CHECK(lsdem_mesh_sdf_grid(m, h, 3, &g, &err) == LSDEM_OK, "%s: %s", what, err.msg);
  double worst = 0.0, worst_far = 0.0, grad[3];
  size_t q = 0;
  for (int k = 0; k < g.n[2]; k++)
    for (int j = 0; j < g.n[1]; j++)
      for (int i = 0; i < g.n[0]; i++, q++) {
        const double p[3] = {g.origin[0] + h * i, g.origin[1] + h * j, g.origin[2] + h * k};
        const double e = lsdem_sdf_eval(exact, p, grad), d = fabs(g.phi[q] - e);
        if (fabs(e) <= 2.0 * h) worst = fmax(worst, d); /* the exactly computed band */
        else worst_far = fmax(worst_far, d);           /* closest-triangle propagation */
      }
  CHECK(worst <= tol_sample, "%s: samples differ from the exact SDF by %g", what, worst);
  CHECK(worst_far <= 0.1 * h, "%s: far samples differ from the exact SDF by %g", what, worst_far);
  double worst_i = 0.0;
  unsigned s = 7;
  for (int t = 0; t < 2000; t++) {
    double p[3];
    for (int a = 0; a < 3; a++) {
      s = s * 1103515245u + 12345u;
      p[a] = g.origin[a] + ((s >> 8) & 0xffff) / 65536.0 * h * (g.n[a] - 1);
    }
    const double e = lsdem_sdf_eval(exact, p, grad);
    if (fabs(e) > 0.5) continue; /* the band around the surface: away from medial kinks */
    worst_i = fmax(worst_i, fabs(lsdem_grid_value(&g, p) - e));
  }
  CHECK(worst_i <= tol_interp, "%s: interpolated SDF differs by %g", what, worst_i);
  printf("%s: %d x %d x %d samples, max error %.2g at samples within 2h, %.2g beyond, %.2g "
         "interpolated (h = %g)\n", what, g.n[0], g.n[1], g.n[2], worst, worst_far, worst_i, h);
  lsdem_grid_free(&g);
}

static void test_cube(void)
{
  tris s = {0};
  const double c[3] = {0, 0, 0}, hh[3] = {1.0, 0.75, 0.5};
  add_box(&s, c, hh, -1);
  write_stl_ascii("cube_ascii.stl", &s);
  write_stl_binary("cube_binary.stl", &s, 0);
  const char *files[2] = {"cube_ascii.stl", "cube_binary.stl"};
  const lsdem_sdf box = {LSDEM_SDF_BOX, 0, {1.0, 0.75, 0.5}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL};
  for (int f = 0; f < 2; f++) {
    lsdem_mesh m;
    lsdem_error err;
    CHECK(lsdem_mesh_read(files[f], &m, &err) == LSDEM_OK, "%s: %s", files[f], err.msg);
    CHECK(m.ntris == 12 && m.nverts == 8, "%s: %d tris %d verts", files[f], m.ntris, m.nverts);
    CHECK(lsdem_mesh_check_closed(&m, NULL, &err) == LSDEM_OK, "%s: %s", files[f], err.msg);
    CHECK(lsdem_mesh_check_self_intersection(&m, NULL, &err) == LSDEM_OK, "%s", err.msg);
    CHECK_NEAR(lsdem_mesh_volume(&m), 8 * 0.75 * 0.5, 1e-12);
    /* the box SDF is exact at samples; trilinear interpolation errs near edges by <= h/2 */
    compare_sdf(&m, &box, 0.1, 1e-6, 0.05, files[f]);
    lsdem_mesh_free(&m);
  }
  free(s.t);
}

static void test_icosphere(void)
{
  tris s = {0};
  add_icosphere(&s, 1.0, 4); /* 5120 triangles */
  write_stl_binary("ico.stl", &s, 0);
  lsdem_mesh m;
  lsdem_error err;
  CHECK(lsdem_mesh_read("ico.stl", &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(m.ntris == 5120 && m.nverts == 2562, "%d tris %d verts", m.ntris, m.nverts);
  CHECK(lsdem_mesh_check_closed(&m, NULL, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_mesh_check_self_intersection(&m, NULL, &err) == LSDEM_OK, "%s", err.msg);
  /* chord sagitta of the level-4 icosphere: edges ~ 0.078, sagitta ~ e^2/(8R) < 1e-3;
   * the flat faces lie inside the sphere by at most ~2e-3 */
  const lsdem_sdf sphere = {LSDEM_SDF_SPHERE, 0, {1.0, 0, 0}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL};
  compare_sdf(&m, &sphere, 0.1, 3e-3, 0.01, "icosphere");
  lsdem_mesh_free(&m);
  free(s.t);
}

static void test_open_and_misoriented(void)
{
  tris s = {0};
  const double c[3] = {0, 0, 0}, hh[3] = {1, 1, 1};
  add_box(&s, c, hh, 3); /* no +y face: its 4 edges are boundary edges */
  write_stl_ascii("open.stl", &s);
  lsdem_mesh m;
  lsdem_mesh_topology topo;
  lsdem_error err;
  CHECK(lsdem_mesh_read("open.stl", &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_mesh_check_closed(&m, &topo, &err) == LSDEM_ERR_FORMAT &&
            strstr(err.msg, "not closed") && strstr(err.msg, "4 boundary edges"),
        "open mesh: %s", err.msg);
  CHECK(topo.boundary_edges == 4 && fabs(topo.where[1] - 1.0) < 1e-12, "boundary %d at y %g",
        topo.boundary_edges, topo.where[1]);
  lsdem_mesh_free(&m);
  /* one flipped triangle: its three edges run the same way as their neighbours' */
  free(s.t);
  s = (tris){0};
  add_box(&s, c, hh, -1);
  double tmp[3];
  memcpy(tmp, s.t + 3, 24), memcpy(s.t + 3, s.t + 6, 24), memcpy(s.t + 6, tmp, 24);
  write_stl_ascii("flipped.stl", &s);
  CHECK(lsdem_mesh_read("flipped.stl", &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_mesh_check_closed(&m, &topo, &err) == LSDEM_ERR_FORMAT &&
            topo.misoriented_edges == 3 && topo.boundary_edges == 0 &&
            strstr(err.msg, "inconsistent orientation"), "flipped: %s", err.msg);
  lsdem_mesh_free(&m);
  free(s.t);
}

static void test_self_intersection(void)
{
  tris s = {0};
  const double c1[3] = {0, 0, 0}, c2[3] = {1.2, 0.3, 0.2}, c3[3] = {3.5, 0, 0}, hh[3] = {1, 1, 1};
  add_box(&s, c1, hh, -1);
  add_box(&s, c3, hh, -1); /* disjoint: fine */
  write_stl_binary("two.stl", &s, 0);
  lsdem_mesh m;
  lsdem_error err;
  int pair[2];
  CHECK(lsdem_mesh_read("two.stl", &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_mesh_check_closed(&m, NULL, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_mesh_check_self_intersection(&m, pair, &err) == LSDEM_OK && pair[0] == -1,
        "disjoint boxes: %s", err.msg);
  lsdem_mesh_free(&m);
  add_box(&s, c2, hh, -1); /* overlaps the first: closed, but intersecting */
  write_stl_binary("three.stl", &s, 0);
  CHECK(lsdem_mesh_read("three.stl", &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_mesh_check_closed(&m, NULL, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_mesh_check_self_intersection(&m, pair, &err) == LSDEM_ERR_FORMAT &&
            strstr(err.msg, "intersects itself") && pair[0] < 12 && pair[1] >= 24,
        "overlapping boxes: pair %d %d: %s", pair[0], pair[1], err.msg);
  lsdem_mesh_free(&m);
  free(s.t);
}

static void test_obj(void)
{
  /* a 2 x 2 x 2 cube from quads, with texture/normal indices and negative references */
  spill_text("cube.obj", "# cube\no cube\nv -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                    "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\nvn 0 0 1\nvt 0 0\n"
                    "f 1/1/1 4/1/1 3/1/1 2/1/1\nf 5//1 6//1 7//1 8//1\nf 1 2 6 5\n"
                    "f 2 3 7 6\nf 3 4 8 7\nf -8 -4 -1 -5\n");
  lsdem_mesh m;
  lsdem_error err;
  CHECK(lsdem_mesh_read("cube.obj", &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(m.ntris == 12 && m.nverts == 8, "%d tris %d verts", m.ntris, m.nverts);
  CHECK(lsdem_mesh_check_closed(&m, NULL, &err) == LSDEM_OK, "%s", err.msg);
  CHECK_NEAR(lsdem_mesh_volume(&m), 8.0, 1e-12);
  lsdem_mesh_free(&m);
}

static void expect_read_error(const char *path, const char *what)
{
  lsdem_mesh m;
  lsdem_error err = {{0}};
  const lsdem_status st = lsdem_mesh_read(path, &m, &err);
  CHECK(st == LSDEM_ERR_FORMAT && strstr(err.msg, what) && m.tris == NULL,
        "%s: status %d '%s' (expected '%s')", path, st, err.msg, what);
}

static void test_bad_files(void)
{
  spill_text("bad1.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  expect_read_error("bad1.obj", "line 4");
  spill_text("bad2.obj", "v 0 0 0\nv 1 0 nan\n");
  expect_read_error("bad2.obj", "line 2");
  spill_text("bad3.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
  expect_read_error("bad3.obj", "at least 3");
  spill_text("bad4.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                    "vertex 0 1 0\nvertex 1 1 0\nendloop\nendfacet\nendsolid\n");
  expect_read_error("bad4.stl", "line 7");
  spill_text("bad5.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n");
  expect_read_error("bad5.stl", "ends inside a facet");
  tris s = {0};
  const double c[3] = {0, 0, 0}, hh[3] = {1, 1, 1};
  add_box(&s, c, hh, -1);
  write_stl_binary("bad6.stl", &s, 1); /* count says 13, file holds 12 */
  expect_read_error("bad6.stl", "does not match its triangle count");
  free(s.t);
  lsdem_mesh m;
  lsdem_error err;
  CHECK(lsdem_mesh_read("missing.stl", &m, &err) == LSDEM_ERR_IO, "missing file");
}

int main(void)
{
  test_cube();
  test_icosphere();
  test_open_and_misoriented();
  test_self_intersection();
  test_obj();
  test_bad_files();
  return lsdem_test_summary();
}
