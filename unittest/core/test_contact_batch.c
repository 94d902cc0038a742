/* test_contact_batch.c -- the fast paths of the node kernel against a plain second path:
 *   - lsdem_grid_eval_many gives bit-identical values and gradients to lsdem_grid_eval, and
 *     lsdem_sdf_eval_many to lsdem_sdf_eval for every SDF kind, inverted or not;
 *   - lsdem_contact_nodes against a grid (batches of kept nodes, flushed when full) and
 *     against walls (grain and cluster rejection by the wall's distance function) gives
 *     the force of a brute-force sum over every node: f = sum over nodes with phi < 0 of
 *     kn (-phi) n, phi and n looked up node by node in B's frame (mu = 0, no damping);
 *   - clusters change nothing but the number of lookups. */
#include "contact_fixtures.h"
#include "lsdem_test.h"

#include <stdint.h>



static void random_rotation(double R[9])
{
  fix_rotation_about(srand1(), srand1(), srand1(), FIX_PI * urand(), R);
}

/* Brute force: force on A from every node of A with phi_B < 0 (per-node law, mu = 0). */
static int brute_force(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                       const lsdem_pose *pb, double kn, double f[3])
{
  int npen = 0;
  f[0] = f[1] = f[2] = 0.0;
  for (int k = 0; k < A->nnodes; k++) {
    double w[3], rel[3], q[3], g[3], n[3];
    lsdem_mat_vec(pa->R, &A->nodes[3 * k], w);
    for (int i = 0; i < 3; i++) rel[i] = w[i] + pa->x[i] - pb->x[i];
    lsdem_matT_vec(pb->R, rel, q);
    const double phi = lsdem_sdf_eval(&B->sdf, q, g);
    if (!(phi < 0.0)) continue;
    lsdem_mat_vec(pb->R, g, n);
    for (int i = 0; i < 3; i++) f[i] += kn * (-phi) * n[i];
    npen++;
  }
  return npen;
}

static void test_eval_many(const lsdem_grid *grid)
{
  enum { M = 200 };
  double p[3 * M], phi[M], grad[3 * M];
  for (int m = 0; m < 3 * M; m++) p[m] = 14.0 * srand1(); /* inside and outside the box */
  lsdem_grid_eval_many(grid, M, p, phi, grad);
  int same = 1;
  for (int m = 0; m < M; m++) {
    double g[3];
    const double v = lsdem_grid_eval(grid, &p[3 * m], g);
    same &= memcmp(&v, &phi[m], sizeof v) == 0 && memcmp(g, &grad[3 * m], sizeof g) == 0;
  }
  CHECK(same, "%s", "eval_many differs from eval");
}

static void test_sdf_eval_many(const lsdem_sdf *grid)
{
  enum { M = 100 };
  lsdem_sdf kinds[8] = {*grid,
                        fix_sdf(LSDEM_SDF_SPHERE, 5.0, 0, 0),
                        fix_sdf(LSDEM_SDF_PLANE, 0, 0, 0),
                        fix_sdf(LSDEM_SDF_CYLINDER, 6.0, 4.0, 0),
                        fix_sdf(LSDEM_SDF_CYLINDER, 6.0, 0.0, 0),
                        fix_sdf(LSDEM_SDF_BOX, 3.0, 4.0, 5.0),
                        fix_sdf(LSDEM_SDF_ELLIPSOID, 7.0, 5.0, 3.0),
                        fix_sdf(LSDEM_SDF_SUPERELLIPSOID, 7.0, 5.0, 3.0)};
  kinds[7].a[3] = 0.5;
  kinds[7].a[4] = 1.5;
  double p[3 * M], phi[M], grad[3 * M];
  for (int m = 0; m < 3 * M; m++) p[m] = 12.0 * srand1();
  for (int k = 0; k < 8; k++)
    for (int inv = 0; inv < 2; inv++) {
      lsdem_sdf s = kinds[k];
      s.inverted = inv;
      lsdem_sdf_eval_many(&s, M, p, phi, grad);
      int same = 1;
      for (int m = 0; m < M; m++) {
        double g[3];
        const double v = lsdem_sdf_eval(&s, &p[3 * m], g);
        same &= memcmp(&v, &phi[m], sizeof v) == 0 && memcmp(g, &grad[3 * m], sizeof g) == 0;
      }
      CHECK(same, "sdf_eval_many differs from sdf_eval: kind %s, inverted %d",
            lsdem_sdf_kind_name(s.kind), inv);
    }
}

/* Grid B, overlapping deeply so that more than one batch of nodes is looked up. */
static void test_grid_pairs(fix_grain *ga, const lsdem_shape *B)
{
  const double kn = 10.0;
  lsdem_contact_params prm = fix_params(kn, 0.0, 0.0, 1e-3);
  int batches = 0;
  for (int t = 0; t < 40; t++) {
    lsdem_pose pa = fix_pose(0, 0, 0), pb = fix_pose(srand1() * 8, srand1() * 8, srand1() * 8);
    random_rotation(pa.R);
    random_rotation(pb.R);
    lsdem_contact_result rc, rp;
    fix_contact(&ga->clustered, &pa, B, &pb, &prm, 1, NULL, 0, NULL, NULL, &rc);
    fix_contact(&ga->plain, &pa, B, &pb, &prm, 1, NULL, 0, NULL, NULL, &rp);
    double f[3];
    const int npen = brute_force(&ga->plain, &pa, B, &pb, kn, f);
    CHECK(rc.npen == npen && rp.npen == npen, "grid pair %d: npen %d %d vs %d", t, rc.npen,
          rp.npen, npen);
    for (int i = 0; i < 3; i++) {
      CHECK(rc.force[i] == rp.force[i], "grid pair %d: clusters change the force", t);
      CHECK_NEAR(rc.force[i], f[i], 1e-12 * (1.0 + fabs(f[i])));
    }
    batches += rp.ntested > 64;
  }
  CHECK(batches > 5, "only %d pairs needed more than one batch", batches);
}

/* Walls (unbounded, radius HUGE_VAL): a plane and an inverted infinite cylinder. */
static void test_walls(fix_grain *ga)
{
  const double kn = 7.0;
  lsdem_contact_params prm = fix_params(kn, 0.0, 0.0, 1e-3);
  lsdem_sdf plane = fix_sdf(LSDEM_SDF_PLANE, 0, 0, 0);
  lsdem_sdf tube = fix_sdf(LSDEM_SDF_CYLINDER, 30.0, 0.0, 0);
  tube.inverted = 1;
  const lsdem_shape walls[2] = {fix_shape(plane, 0, NULL, HUGE_VAL),
                                fix_shape(tube, 0, NULL, HUGE_VAL)};
  int fewer = 0, far = 0;
  for (int w = 0; w < 2; w++)
    for (int t = 0; t < 60; t++) {
      lsdem_pose pw = fix_pose(srand1(), srand1(), srand1());
      random_rotation(pw.R);
      /* grain centre at distance s from the wall surface along its normal (plane: +z of
       * the wall frame; tube: towards the axis), s in [-3, 14] */
      const double s = -3.0 + 17.0 * urand();
      double local[3] = {0.0, 0.0, s};
      if (w == 1) {
        const double ang = 2.0 * FIX_PI * urand();
        local[0] = (30.0 - s) * cos(ang);
        local[1] = (30.0 - s) * sin(ang);
        local[2] = 5.0 * srand1();
      }
      double off[3];
      lsdem_mat_vec(pw.R, local, off);
      lsdem_pose pa = fix_pose(pw.x[0] + off[0], pw.x[1] + off[1], pw.x[2] + off[2]);
      random_rotation(pa.R);
      lsdem_contact_result rc, rp;
      fix_contact(&ga->clustered, &pa, &walls[w], &pw, &prm, 1, NULL, 0, NULL, NULL,
                          &rc);
      fix_contact(&ga->plain, &pa, &walls[w], &pw, &prm, 1, NULL, 0, NULL, NULL, &rp);
      double f[3];
      const int npen = brute_force(&ga->plain, &pa, &walls[w], &pw, kn, f);
      CHECK(rc.npen == npen && rp.npen == npen, "wall %d case %d: npen %d %d vs %d", w, t,
            rc.npen, rp.npen, npen);
      for (int i = 0; i < 3; i++) {
        CHECK(rc.force[i] == rp.force[i], "wall %d case %d: clusters change the force", w, t);
        CHECK_NEAR(rc.force[i], f[i], 1e-12 * (1.0 + fabs(f[i])));
      }
      fewer += npen > 0 && rc.ntested < FIX_GRAIN_NODES / 2;
      if (s > 10.5) { /* beyond the bounding radius: no lookup at all */
        far++;
        CHECK(rc.ntested == 0 && rp.ntested == 0, "far grain: ntested %d %d", rc.ntested,
              rp.ntested);
      }
    }
  CHECK(fewer > 10 && far > 5, "cases: %d in contact with few lookups, %d far", fewer, far);
}

int main(void)
{
  const double a[3] = {10.0, 8.0, 6.0};
  lsdem_sdf gsdf;
  lsdem_error err;
  CHECK(fix_ellipsoid_grid(a, &gsdf, &err) == LSDEM_OK, "%s", err.msg);
  static fix_grain ga;
  fix_make_grain(&ga, a, &gsdf);
  lsdem_shape B = fix_shape(gsdf, 0, NULL, lsdem_sdf_bound_radius(&gsdf));

  test_eval_many(&gsdf.grid);
  test_sdf_eval_many(&gsdf);
  test_grid_pairs(&ga, &B);
  test_walls(&ga);
  lsdem_grid_free(&gsdf.grid);
  return lsdem_test_summary();
}
