/* The packing generator (packing.c). Every result is re-checked here independently of the
 * generator's cell list and probes: all pairs by the contact kernel in both directions,
 * every node inside the container by its coordinates, clearances by direct level-set
 * lookups; plus determinism, weights, and an overfull request. */
#include "contact_fixtures.h"
#include "lsdem_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

enum { NSHAPES = 2 };

static lsdem_built_shape built[NSHAPES];
static lsdem_shape shapes[NSHAPES];

/* A grid ellipsoid and a grid box (sampled exact SDFs), 150 nodes each. */
static void make_shapes(void)
{
  const lsdem_sdf kinds[NSHAPES] = {
      {LSDEM_SDF_ELLIPSOID, 0, {0.5, 0.35, 0.25}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL},
      {LSDEM_SDF_BOX, 0, {0.35, 0.3, 0.2}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL}};
  for (int k = 0; k < NSHAPES; k++) {
    const double lo[3] = {-kinds[k].a[0], -kinds[k].a[1], -kinds[k].a[2]};
    lsdem_sdf g;
    lsdem_error err;
    memset(&g, 0, sizeof g);
    g.kind = LSDEM_SDF_GRID;
    CHECK(lsdem_grid_sample(&kinds[k], lo, kinds[k].a, 0.04, 2, &g.grid, &err) == LSDEM_OK,
          "%s", err.msg);
    CHECK(lsdem_shape_build(&g, 150, 0.0, 1, &built[k], &err) == LSDEM_OK, "%s", err.msg);
    shapes[k] = built[k].shape;
  }
}

static void pose_of(const lsdem_placed *g, lsdem_pose *p)
{
  memset(p, 0, sizeof *p);
  memcpy(p->x, g->x, sizeof p->x);
  lsdem_quat_to_matrix(g->q, p->R);
}

/* Penetrating nodes of every pair, both directions, all pairs (no culling). */
static int pair_penetrations(const lsdem_placed *g, int n)
{
  const lsdem_contact_params prm = fix_params(1.0, 0.0, 0.0, 0.0);
  int total = 0;
  for (int i = 0; i < n; i++)
    for (int j = i + 1; j < n; j++) {
      lsdem_pose a, b;
      lsdem_contact_result res;
      int nout;
      pose_of(&g[i], &a);
      pose_of(&g[j], &b);
      total += fix_contact(&shapes[g[i].shape], &a, &shapes[g[j].shape], &b, &prm, 0,
                         NULL, 0, NULL, &nout, &res);
      total += fix_contact(&shapes[g[j].shape], &b, &shapes[g[i].shape], &a, &prm, 0,
                         NULL, 0, NULL, &nout, &res);
    }
  return total;
}

/* Smallest level-set value of any node of one grain in any other grain. */
static double min_clearance(const lsdem_placed *g, int n)
{
  double m = HUGE_VAL;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) {
      if (i == j) continue;
      const lsdem_shape *A = &shapes[g[i].shape], *B = &shapes[g[j].shape];
      double Ra[9], Rb[9];
      lsdem_quat_to_matrix(g[i].q, Ra);
      lsdem_quat_to_matrix(g[j].q, Rb);
      for (int k = 0; k < A->nnodes; k++) {
        double w[3], d[3], body[3], gr[3];
        lsdem_mat_vec(Ra, A->nodes + 3 * k, w);
        for (int a = 0; a < 3; a++) d[a] = w[a] + g[i].x[a] - g[j].x[a];
        lsdem_matT_vec(Rb, d, body);
        m = fmin(m, lsdem_sdf_eval(&B->sdf, body, gr));
      }
    }
  return m;
}

/* Nodes outside the container (by world coordinates). */
static int nodes_outside(const lsdem_placed *g, int n, const lsdem_container *c)
{
  int bad = 0;
  for (int i = 0; i < n; i++) {
    const lsdem_shape *A = &shapes[g[i].shape];
    double R[9];
    lsdem_quat_to_matrix(g[i].q, R);
    for (int k = 0; k < A->nnodes; k++) {
      double w[3];
      lsdem_mat_vec(R, A->nodes + 3 * k, w);
      for (int a = 0; a < 3; a++) w[a] += g[i].x[a];
      if (c->kind == LSDEM_CONTAINER_BOX)
        bad += w[0] < 0 || w[1] < 0 || w[2] < 0 || w[0] > c->size[0] || w[1] > c->size[1] ||
               w[2] > c->size[2];
      else
        bad += hypot(w[0], w[1]) > c->size[0] || w[2] < 0 || w[2] > c->size[1];
    }
  }
  return bad;
}

static void test_box(void)
{
  const lsdem_container c = {LSDEM_CONTAINER_BOX, {3.0, 3.0, 3.0}};
  const lsdem_pack_params p = {25, 0.0, 3000, 7, NULL};
  lsdem_placed g[25], g2[25];
  int n = 0, n2 = 0;
  lsdem_error err;
  CHECK(lsdem_pack(shapes, NSHAPES, &c, &p, g, &n, &err) == LSDEM_OK, "%s", err.msg);
  double vs = 0.0;
  int used[NSHAPES] = {0};
  for (int i = 0; i < n; i++) vs += shapes[g[i].shape].volume, used[g[i].shape]++;
  printf("box: %d of 25 placed (shapes %d/%d), solid fraction %.3f, void ratio %.3f\n", n,
         used[0], used[1], vs / 27.0, 27.0 / vs - 1.0);
  CHECK(n == 25, "placed %d of 25 at a solid fraction of ~0.16", n);
  printf("box: smallest node clearance between grains %.4f (touching ~ 0)\n", min_clearance(g, n));
  CHECK(used[0] > 10 && used[1] > 10, "uniform choice gave %d / %d", used[0], used[1]);
  CHECK(pair_penetrations(g, n) == 0, "%s", "overlapping pair");
  CHECK(nodes_outside(g, n, &c) == 0, "%s", "node outside the box");
  CHECK_NEAR(lsdem_container_volume(&c), 27.0, 1e-12);
  /* deterministic for a seed, different for another */
  CHECK(lsdem_pack(shapes, NSHAPES, &c, &p, g2, &n2, &err) == LSDEM_OK, "%s", err.msg);
  int same = n2 == n;
  for (int i = 0; same && i < n; i++)
    same = g[i].shape == g2[i].shape && memcmp(g[i].x, g2[i].x, sizeof g[i].x) == 0 &&
           memcmp(g[i].q, g2[i].q, sizeof g[i].q) == 0;
  CHECK(same, "%s", "same seed, other packing");
  lsdem_pack_params q = p;
  q.seed = 8;
  CHECK(lsdem_pack(shapes, NSHAPES, &c, &q, g2, &n2, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(memcmp(g[0].x, g2[0].x, sizeof g[0].x) != 0, "%s", "seeds 7 and 8 gave the same first grain");
  /* the public re-check agrees: the generator's own test sees no overlap either */
  int any = 0;
  for (int i = 0; i < n; i++)
    for (int j = i + 1; j < n; j++)
      any |= lsdem_pack_overlap(&shapes[g[i].shape], &g[i], &shapes[g[j].shape], &g[j], 0.0);
  CHECK(!any, "%s", "lsdem_pack_overlap reports an overlap");
}

/* Negative control for the re-checks: two grains at the same place overlap, a grain
 * across a wall is outside. */
static void test_detects_overlap(void)
{
  const lsdem_container c = {LSDEM_CONTAINER_BOX, {3.0, 3.0, 3.0}};
  lsdem_placed a = {0, {1.5, 1.5, 1.5}, {1, 0, 0, 0}}, b = {1, {1.6, 1.5, 1.5}, {0, 1, 0, 0}};
  CHECK(lsdem_pack_overlap(&shapes[0], &a, &shapes[1], &b, 0.0), "%s", "overlap missed");
  CHECK(pair_penetrations((lsdem_placed[]){a, b}, 2) > 0, "%s", "kernel re-check misses it");
  b.x[0] = 2.5; /* ellipsoid x-extent 0.5 + box extent <= 0.55 < 1.0 apart: clear */
  CHECK(!lsdem_pack_overlap(&shapes[0], &a, &shapes[1], &b, 0.0), "%s", "false overlap");
  a.x[0] = 0.3;
  CHECK(lsdem_pack_outside(&shapes[0], &a, &c, 0.0), "%s", "grain across the wall x = 0");
  a.x[0] = 1.5;
  CHECK(!lsdem_pack_outside(&shapes[0], &a, &c, 0.0), "%s", "centred grain outside");
}

static void test_cylinder_gap_weights(void)
{
  const lsdem_container c = {LSDEM_CONTAINER_CYLINDER, {1.5, 3.0, 0.0}};
  const double w[NSHAPES] = {0.0, 1.0};
  const double gap = 0.05;
  const lsdem_pack_params p = {15, gap, 3000, 3, w};
  lsdem_placed g[15];
  int n = 0;
  lsdem_error err;
  CHECK(lsdem_pack(shapes, NSHAPES, &c, &p, g, &n, &err) == LSDEM_OK, "%s", err.msg);
  int wrong = 0;
  for (int i = 0; i < n; i++) wrong += g[i].shape != 1;
  const double clear = min_clearance(g, n);
  printf("cylinder: %d of 15 placed, smallest node clearance %.4f (gap %.2f)\n", n, clear, gap);
  CHECK(n == 15, "placed %d of 15", n);
  CHECK(wrong == 0, "%d grains of weight-0 shape", wrong);
  CHECK(nodes_outside(g, n, &c) == 0, "%s", "node outside the cylinder");
  /* the gap is enforced along node normals: at least ~gap cos(angle between normals) */
  CHECK(clear > 0.3 * gap, "clearance %g below 0.3 gap", clear);
  CHECK_REL(lsdem_container_volume(&c), PI * 1.5 * 1.5 * 3.0, 1e-12);
}

/* More grains than fit: the count placed is reported, and what was placed is valid. */
static void test_overfull(void)
{
  const lsdem_container c = {LSDEM_CONTAINER_BOX, {2.0, 2.0, 2.0}};
  enum { N = 200 };
  static lsdem_placed g[N];
  const lsdem_pack_params p = {N, 0.0, 200, 11, NULL};
  int n = -1;
  lsdem_error err;
  CHECK(lsdem_pack(shapes, NSHAPES, &c, &p, g, &n, &err) == LSDEM_OK, "%s", err.msg);
  double vs = 0.0;
  for (int i = 0; i < n; i++) vs += shapes[g[i].shape].volume;
  printf("overfull: %d of %d placed, solid fraction %.3f\n", n, N, vs / 8.0);
  CHECK(n >= 8 && n < N, "placed %d", n);
  CHECK(vs < 8.0, "%s", "solids exceed the container");
  CHECK(pair_penetrations(g, n) == 0, "%s", "overlap in the overfull packing");
  CHECK(nodes_outside(g, n, &c) == 0, "%s", "node outside");
  const lsdem_pack_params bad = {5, -1.0, 10, 1, NULL};
  CHECK(lsdem_pack(shapes, NSHAPES, &c, &bad, g, &n, &err) == LSDEM_ERR_ARG, "%s", "gap < 0");
}

int main(void)
{
  make_shapes();
  test_box();
  test_detects_overlap();
  test_cylinder_gap_weights();
  test_overfull();
  for (int k = 0; k < NSHAPES; k++) lsdem_built_shape_free(&built[k]);
  return lsdem_test_summary();
}
