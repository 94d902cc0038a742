/* test_collision.c -- two level-set grains (grid-sampled ellipsoids with surface nodes)
 * in a head-on, frictionless, undamped collision, integrated with the core's rigid-body
 * step: kinetic energy is recovered after separation (elastic contact) and linear
 * momentum is conserved to round-off (action equals reaction). */
#include "contact_fixtures.h"
#include "lsdem.h"
#include "lsdem_test.h"

#include <math.h>
#include <string.h>

#define NN 250

typedef struct {
  lsdem_shape shape;
  lsdem_grid grid;
  double nodes[3 * NN];
  double mass, inertia[3];
  lsdem_pose pose;
  double q[4], omega_body[3], dw_prev[3];
} grain;

/* An ellipsoid sampled at spacing 1 with a 3-sample margin, Fibonacci nodes on its
 * surface, analytic mass properties at density 1 (V = 4/3 pi abc, I_x = V (b^2+c^2)/5). */
static int grain_init(grain *g, const double a[3], double x, double vx, const double q[4])
{
  lsdem_sdf exact = fix_sdf(LSDEM_SDF_ELLIPSOID, a[0], a[1], a[2]);
  const double lo[3] = {-a[0], -a[1], -a[2]};
  lsdem_error err;
  if (lsdem_grid_sample(&exact, lo, a, 1.0, 3, &g->grid, &err) != LSDEM_OK) {
    CHECK(0, "grid sampling failed: %s", err.msg);
    return 0;
  }
  lsdem_sdf sdf = fix_sdf(LSDEM_SDF_GRID, 0, 0, 0);
  sdf.grid = g->grid;
  fix_fibonacci_ellipsoid(NN, a, g->nodes);
  g->shape = fix_shape(sdf, NN, g->nodes, lsdem_sdf_bound_radius(&sdf));
  const double V = 4.0 / 3.0 * FIX_PI * a[0] * a[1] * a[2];
  g->mass = V;
  g->inertia[0] = V * (a[1] * a[1] + a[2] * a[2]) / 5;
  g->inertia[1] = V * (a[0] * a[0] + a[2] * a[2]) / 5;
  g->inertia[2] = V * (a[0] * a[0] + a[1] * a[1]) / 5;
  g->pose = fix_pose(x, 0, 0);
  g->pose.v[0] = vx;
  memcpy(g->q, q, 4 * sizeof(double));
  lsdem_quat_to_matrix(g->q, g->pose.R);
  memset(g->omega_body, 0, sizeof g->omega_body);
  memset(g->dw_prev, 0, sizeof g->dw_prev);
  return 1;
}

static double kinetic(const grain *g)
{
  return lsdem_kinetic_translational(g->mass, g->pose.v) +
         lsdem_kinetic_rotational(g->inertia, g->omega_body);
}

/* Angular momentum about the origin: m x cross v + R I omega_body. */
static void angular_momentum(const grain *g, double L[3])
{
  const double Iw[3] = {g->inertia[0] * g->omega_body[0], g->inertia[1] * g->omega_body[1],
                        g->inertia[2] * g->omega_body[2]};
  double xv[3], spin[3];
  fix_cross(g->pose.x, g->pose.v, xv);
  lsdem_quat_rotate(g->q, Iw, spin);
  for (int i = 0; i < 3; i++) L[i] = g->mass * xv[i] + spin[i];
}

static void grain_step(grain *g, const double f[3], const double t[3], double dt)
{
  lsdem_step_body(g->pose.x, g->pose.v, g->q, g->omega_body, g->dw_prev, f, t, g->mass,
                  g->inertia, 0.0, dt, g->pose.omega);
  lsdem_quat_to_matrix(g->q, g->pose.R);
}

/* Forces on A and B (and torques) for one step; two_way averages both directions. */
static int pair_forces(grain *A, grain *B, const lsdem_contact_params *prm, int two_way,
                       double fa[3], double ta[3], double fb[3], double tb[3])
{
  lsdem_contact_result ab, ba;
  fix_contact(&A->shape, &A->pose, &B->shape, &B->pose, prm, 0, NULL, 0, NULL, NULL,
                      &ab);
  if (!two_way) {
    for (int i = 0; i < 3; i++) {
      fa[i] = ab.force[i];
      ta[i] = ab.torque_a[i];
      fb[i] = -ab.force[i];
      tb[i] = ab.torque_b[i];
    }
    return ab.npen;
  }
  fix_contact(&B->shape, &B->pose, &A->shape, &A->pose, prm, 0, NULL, 0, NULL, NULL,
                      &ba);
  for (int i = 0; i < 3; i++) {
    fa[i] = 0.5 * (ab.force[i] - ba.force[i]);
    fb[i] = -fa[i];
    ta[i] = 0.5 * (ab.torque_a[i] + ba.torque_b[i]);
    tb[i] = 0.5 * (ab.torque_b[i] + ba.torque_a[i]);
  }
  return ab.npen + ba.npen;
}

static void collide(int two_way)
{
  const double a1[3] = {10, 8, 7}, a2[3] = {9, 9, 6};
  const double c = cos(0.35), s = sin(0.35);
  const double q1[4] = {1, 0, 0, 0}, q2[4] = {c, s, 0, 0}; /* B turned about the x axis */
  grain A, B;
  if (!grain_init(&A, a1, -10.6, 0.02, q1) || !grain_init(&B, a2, 9.6, -0.015, q2)) return;

  /* the contact lasts ~100 time units (pi sqrt(m_eff / k_eff)) */
  const lsdem_contact_params prm = fix_params(1.0, 0.0, 0.0, 0.2);

  const double e0 = kinetic(&A) + kinetic(&B);
  const double p0 = A.mass * A.pose.v[0] + B.mass * B.pose.v[0];
  const double pscale = A.mass * fabs(A.pose.v[0]) + B.mass * fabs(B.pose.v[0]);
  int touched = 0, separated = 0, steps = 0, max_pen = 0;
  double max_dp = 0;
  while (steps < 20000 && separated < 50) {
    double fa[3], ta[3], fb[3], tb[3];
    const int npen = pair_forces(&A, &B, &prm, two_way, fa, ta, fb, tb);
    if (npen > max_pen) max_pen = npen;
    if (npen > 0) touched = 1;
    if (touched && npen == 0) separated++;
    grain_step(&A, fa, ta, prm.dt);
    grain_step(&B, fb, tb, prm.dt);
    for (int i = 0; i < 3; i++) {
      const double p = A.mass * A.pose.v[i] + B.mass * B.pose.v[i] - (i == 0 ? p0 : 0.0);
      if (fabs(p) > max_dp) max_dp = fabs(p);
    }
    steps++;
  }
  CHECK(touched && separated >= 50, "%s: no complete collision in %d steps",
        two_way ? "two-way" : "one-way", steps);
  CHECK(max_pen >= 3, "only %d penetrating nodes at most: too gentle a test", max_pen);
  const double e1 = kinetic(&A) + kinetic(&B);
  CHECK(fabs(e1 - e0) <= 0.01 * e0, "%s: kinetic energy %.6g after, %.6g before",
        two_way ? "two-way" : "one-way", e1, e0);
  CHECK(max_dp <= 1e-12 * pscale, "%s: momentum drift %.3g (scale %.3g)",
        two_way ? "two-way" : "one-way", max_dp, pscale);
  /* angular momentum: zero before (motion along the line of centres); after, only the
   * integrator's error (the contact torques balance the moment of the forces) */
  double La[3], Lb[3], L[3];
  angular_momentum(&A, La);
  angular_momentum(&B, Lb);
  for (int i = 0; i < 3; i++) L[i] = La[i] + Lb[i];
  CHECK(fix_norm(L) <= 1e-6 * pscale * a1[0], "%s: angular momentum %.3g after, 0 before",
        two_way ? "two-way" : "one-way", fix_norm(L));
  /* it was a collision: the grains now move apart */
  CHECK(A.pose.v[0] < B.pose.v[0], "velocities after: %g, %g", A.pose.v[0], B.pose.v[0]);
  lsdem_grid_free(&A.grid);
  lsdem_grid_free(&B.grid);
}

int main(void)
{
  collide(1);
  collide(0);
  return lsdem_test_summary();
}
