/* test_band_points.c -- a band wall's sharp points (geom/band_points.c) and their test
 * against a grain's level set (lsdem_detect_band_points, contact/detect.c), against
 * closed-form expectations: a box's 12 edges sampled at the spacing (and none for the same
 * box as a container, whose edges are concave from its solid), every point on an edge and
 * in its brick's range; a cube grain pressed by d onto the box's top edge holds exactly the
 * edge's points under its face, each d deep with the face's normal, in any wall pose; the
 * penalty law on them gives n kn d; the capacity bound covers every ball. */
#include "lsdem.h"
#include "contact_fixtures.h"
#include "file_writers.h"
#include "lsdem_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double SPACING = 0.125; /* 2 / 0.125 = 16 pieces per edge, exactly */

/* the band of the box [-half, half]^3 (flip: its faces inwards, a container) */
static void box_band(double half, int flip, lsdem_band *b)
{
  tris s = {0};
  const double c[3] = {0, 0, 0}, hh[3] = {half, half, half};
  add_box(&s, c, hh, -1);
  write_stl_binary("points_box.stl", &s, 0);
  free(s.t);
  lsdem_mesh m;
  lsdem_error err;
  CHECK(lsdem_mesh_read("points_box.stl", &m, &err) == LSDEM_OK, "%s", err.msg);
  for (int t = 0; flip && t < m.ntris; t++) {
    const int x = m.tris[3 * t + 1];
    m.tris[3 * t + 1] = m.tris[3 * t + 2], m.tris[3 * t + 2] = x;
  }
  CHECK(lsdem_band_from_mesh(&m, SPACING, 2 * SPACING, LSDEM_BAND_MESH, b, &err) == LSDEM_OK,
        "%s", err.msg);
  lsdem_mesh_free(&m);
}

static void test_box_points(void)
{
  lsdem_band b;
  lsdem_band_points p;
  lsdem_error err;
  const double half = 3.0; /* 6 / 0.125 = 48 pieces per edge */
  box_band(half, 0, &b);
  CHECK(lsdem_band_points_make(&b, SPACING, &p, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(p.nedges == 12, "sharp edges %lld, expected the box's 12", (long long)p.nedges);
  CHECK(p.n == 8 + 12 * 47, "points %lld, expected 8 corners + 12 x 47", (long long)p.n);
  int off_edge = 0, off_brick = 0;
  for (int64_t k = 0; k < b.nbricks; k++)
    for (int64_t i = p.brick_start[k]; i < p.brick_start[k + 1]; i++) {
      const double *x = &p.x[3 * i];
      int at_face = 0;
      for (int a = 0; a < 3; a++) at_face += fabs(fabs(x[a]) - half) < 1e-12;
      off_edge += at_face < 2;
      int lo[3], hi[3];
      lsdem_band_slot_range(&b, x, 0.0, lo, hi);
      off_brick += b.index[lo[0] + (int64_t)b.nb[0] * (lo[1] + (int64_t)b.nb[1] * lo[2])] != k;
    }
  CHECK(p.brick_start[b.nbricks] == p.n, "brick ranges end at %lld, not %lld",
        (long long)p.brick_start[b.nbricks], (long long)p.n);
  CHECK(off_edge == 0, "%d points off the box's edges", off_edge);
  CHECK(off_brick == 0, "%d points listed under another brick", off_brick);

  /* the bound on a ball's points: brute force around random centres near the surface */
  const double r = 0.6;
  const int64_t bound = lsdem_band_points_within(&b, &p, r);
  int64_t most = 0;
  for (int trial = 0; trial < 2000; trial++) {
    const double c[3] = {3.3 * srand1(), 3.3 * srand1(), 3.3 * srand1()};
    int64_t in = 0;
    for (int64_t i = 0; i < p.n; i++) {
      const double d[3] = {p.x[3 * i] - c[0], p.x[3 * i + 1] - c[1], p.x[3 * i + 2] - c[2]};
      in += lsdem_dot3(d, d) <= r * r;
    }
    most = in > most ? in : most;
  }
  CHECK(most > 0 && bound >= most, "bound %lld below the %lld points of a ball",
        (long long)bound, (long long)most);
  CHECK(bound < p.n, "bound %lld is no bound (all %lld points)", (long long)bound,
        (long long)p.n);
  lsdem_band_points_free(&p);
  lsdem_band_free(&b);

  box_band(1.0, 1, &b); /* the container: its edges are concave seen from its solid */
  CHECK(lsdem_band_points_make(&b, SPACING, &p, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(p.n == 0 && p.nedges == 0, "a container has %lld sharp points", (long long)p.n);
  lsdem_band_points_free(&p);
  lsdem_band_free(&b);
}

/* wall pose: turned by `angle` about z, moved by t; the grain's pose the same transform of
 * its wall-frame pose (centre c, unrotated) */
static void place(double angle, const double t[3], const double c[3], lsdem_pose *wall,
                  lsdem_pose *grain)
{
  *wall = fix_pose(t[0], t[1], t[2]);
  fix_rotation_about(0, 0, 1, angle, wall->R);
  *grain = fix_pose(0, 0, 0);
  memcpy(grain->R, wall->R, sizeof grain->R);
  lsdem_affine3(wall->R, wall->x, c, grain->x);
}

static void test_cube_on_edge(void)
{
  lsdem_band b;
  lsdem_band_points p;
  lsdem_error err;
  box_band(1.0, 0, &b);
  CHECK(lsdem_band_points_make(&b, SPACING, &p, &err) == LSDEM_OK, "%s", err.msg);
  /* a cube of half-side 0.5 over the top edge x = z = 1 (along y), its face d below the
   * edge: the edge's points with |y - 0.03| < 0.5 are inside, y = -1 + k/8 for k = 5..12 */
  const double d = 1e-3, centre[3] = {1.0, 0.03, 1.5 - d};
  lsdem_shape cube = fix_shape(fix_sdf(LSDEM_SDF_BOX, 0.5, 0.5, 0.5), 0, NULL, sqrt(0.75));
  const double moves[3][4] = {{0, 0, 0, 0}, {0.3, -0.2, 0.1, M_PI / 2}, {5, 2, -7, 0.7}};
  for (int mv = 0; mv < 3; mv++) {
    lsdem_pose wall, grain;
    place(moves[mv][3], moves[mv], centre, &wall, &grain);
    lsdem_manifold *m = fix_manifold();
    const int n = lsdem_detect_band_points(&b, &p, &wall, &cube, &grain, m);
    CHECK(n == 8, "pose %d: %d points inside the cube, expected 8", mv, n);
    double down[3], ysum = 0.0;
    int off_sample = 0;
    const double z[3] = {0, 0, -1};
    lsdem_mat_vec(wall.R, z, down);
    for (int k = 0; k < n; k++) {
      const lsdem_contact_point *c = &m->point[k];
      CHECK_NEAR(c->depth, d, 1e-12);
      CHECK(k == 0 || c->node > m->point[k - 1].node, "pose %d: points not in increasing "
            "number", mv);
      double local[3], rel[3];
      lsdem_sub3(c->point, wall.x, rel);
      lsdem_matT_vec(wall.R, rel, local);
      CHECK_NEAR(local[0], 1.0, 1e-12);
      CHECK_NEAR(local[2], 1.0, 1e-12);
      const double kk = (local[1] + 1.0) / SPACING; /* its sample number along the edge */
      off_sample += fabs(kk - round(kk)) > 1e-9 || kk < 4.5 || kk > 12.5;
      ysum += local[1];
      for (int a = 0; a < 3; a++) CHECK_NEAR(c->normal[a], down[a], 1e-12);
    }
    CHECK(off_sample == 0, "pose %d: %d points are not the edge's samples 5..12", mv,
          off_sample);
    CHECK_NEAR(ysum, 8 * -1.0 + (5 + 6 + 7 + 8 + 9 + 10 + 11 + 12) * SPACING, 1e-12);
    /* the law: each point kn d along the normal on the wall (master), the reaction up */
    lsdem_contact_result res;
    const lsdem_penalty_law law = fix_params(100.0, 0.0, 0.0, 1e-3).law;
    lsdem_penalty_apply(m, &law, 1e-3, 0, NULL, 0, NULL, NULL, &res);
    for (int a = 0; a < 3; a++) CHECK_NEAR(res.force[a], 8 * 100.0 * d * down[a], 1e-12);
  }
  /* a cube clear of the box: nothing looked up where no brick is stored */
  lsdem_pose wall, grain;
  const double far[3] = {0, 0, 3.0}, none[3] = {0, 0, 0};
  place(0.0, none, far, &wall, &grain);
  lsdem_manifold *m = fix_manifold();
  CHECK(lsdem_detect_band_points(&b, &p, &wall, &cube, &grain, m) == 0 && m->ntested == 0,
        "a far cube: %d points, %d lookups", m->n, m->ntested);
  lsdem_band_points_free(&p);
  lsdem_band_free(&b);
}

int main(void)
{
  test_box_points();
  test_cube_on_edge();
  return lsdem_test_summary();
}
