/* test_contact.c -- the node-to-surface contact kernel and the sphere fast paths
 * against analytic expectations computed here from the geometry (sphere and box
 * distances written out independently), conservation identities and symmetry. */
#include "contact_fixtures.h"
#include "lsdem.h"
#include "lsdem_test.h"

#include <math.h>
#include <string.h>

#define NR 10
#define NP 12
#define NNODES (2 + NR * NP)

static double nodes_unit[3 * NNODES]; /* ring nodes on the unit sphere */

static void world_node(const lsdem_pose *pa, const double *node, double p[3])
{
  for (int i = 0; i < 3; i++)
    p[i] = pa->x[i] + pa->R[3 * i] * node[0] + pa->R[3 * i + 1] * node[1] +
           pa->R[3 * i + 2] * node[2];
}

/* Total angular momentum change about the origin of one pair result:
 * xA x F + torque_a + xB x (-F) + torque_b (zero by action-reaction). */
static double angular_imbalance(const lsdem_pose *pa, const lsdem_pose *pb,
                                const lsdem_contact_result *r)
{
  double a[3], b[3], s[3];
  fix_cross(pa->x, r->force, a);
  fix_cross(pb->x, r->force, b);
  for (int i = 0; i < 3; i++) s[i] = a[i] + r->torque_a[i] - b[i] + r->torque_b[i];
  return fix_norm(s);
}

/* Two unit spheres overlapping by delta along x; A's node 0 is on the axis. */
static void test_single_axis_node(void)
{
  const double delta = 1e-3, kn = 1000.0;
  lsdem_shape A = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, 1, 0, 0), NNODES, nodes_unit, 1.0);
  lsdem_shape B = A;
  lsdem_pose pa = fix_pose(0, 0, 0), pb = fix_pose(2.0 - delta, 0, 0);
  lsdem_contact_params prm = fix_params(kn, 0, 0, 1e-3);
  lsdem_contact_result r;
  const int np = fix_contact(&A, &pa, &B, &pb, &prm, 1, NULL, 0, NULL, NULL, &r);
  CHECK(np == 1 && r.npen == 1, "penetrating nodes %d (only the axis node expected)", np);
  CHECK(r.ntested == 1, "ntested %d", r.ntested);
  CHECK_REL(r.force[0], -kn * delta, 1e-9); /* pushes A away from B (-x) */
  CHECK_NEAR(r.force[1], 0.0, 1e-15);
  CHECK_NEAR(r.force[2], 0.0, 1e-15);
  CHECK_REL(r.max_depth, delta, 1e-9);
  CHECK_NEAR(fix_norm(r.torque_a), 0.0, 1e-15);
  CHECK_NEAR(r.point[0], 1.0, 1e-12);
  /* reaction on B acts at (1,0,0), on B's axis too: no torque */
  CHECK_NEAR(fix_norm(r.torque_b), 0.0, 1e-15);
}

/* Large overlap: F = sum over A's nodes inside B of kn (1 - |p - xB|) (p - xB)/|p - xB|,
 * computed here directly; with the ring-symmetric nodes the torque on A vanishes. */
static void expected_sphere_sum(const lsdem_pose *pa, const lsdem_pose *pb, double kn,
                                int stride, double F[3], double Ta[3], int *npen)
{
  memset(F, 0, 3 * sizeof(double));
  memset(Ta, 0, 3 * sizeof(double));
  *npen = 0;
  for (int k = 0; k < NNODES; k += stride) {
    double p[3], d[3], ra[3], t[3], f[3];
    world_node(pa, &nodes_unit[3 * k], p);
    for (int i = 0; i < 3; i++) d[i] = p[i] - pb->x[i];
    const double dist = fix_norm(d);
    if (dist >= 1.0) continue;
    (*npen)++;
    for (int i = 0; i < 3; i++) {
      f[i] = stride * kn * (1.0 - dist) * d[i] / dist;
      ra[i] = p[i] - pa->x[i];
      F[i] += f[i];
    }
    fix_cross(ra, f, t);
    for (int i = 0; i < 3; i++) Ta[i] += t[i];
  }
}

static void test_sphere_overlap_sum(void)
{
  const double kn = 1000.0;
  lsdem_shape A = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, 1, 0, 0), NNODES, nodes_unit, 1.0);
  lsdem_shape B = A;
  lsdem_contact_params prm = fix_params(kn, 0, 0, 1e-3);
  lsdem_contact_result r;
  double F[3], Ta[3];
  int npen;

  /* symmetric: A unrotated, B on A's x axis */
  lsdem_pose pa = fix_pose(0.1, -0.2, 0.3), pb = fix_pose(1.9, -0.2, 0.3);
  fix_axis_angle((double[]){1, 0, 0}, 0.3, pb.R); /* a sphere: B's rotation is irrelevant */
  fix_contact(&A, &pa, &B, &pb, &prm, 1, NULL, 0, NULL, NULL, &r);
  expected_sphere_sum(&pa, &pb, kn, 1, F, Ta, &npen);
  CHECK(r.npen == npen && npen > 1, "npen %d, expected %d", r.npen, npen);
  CHECK(F[0] < 0, "expected force pushes A to -x");
  for (int i = 0; i < 3; i++) CHECK_NEAR(r.force[i], F[i], 1e-10 * fabs(F[0]));
  CHECK_NEAR(fix_norm(r.torque_a), 0.0, 1e-12 * fabs(F[0]));
  CHECK_REL(r.max_depth, 0.2, 1e-12);

  /* general: both rotated, B off axis */
  double k[3] = {1, 2, -2};
  for (int i = 0; i < 3; i++) k[i] /= 3.0;
  fix_axis_angle(k, 0.9, pa.R);
  pb = fix_pose(1.5, 0.6, -0.4);
  fix_axis_angle((double[]){0, 0.6, 0.8}, -1.3, pb.R);
  fix_contact(&A, &pa, &B, &pb, &prm, 1, NULL, 0, NULL, NULL, &r);
  expected_sphere_sum(&pa, &pb, kn, 1, F, Ta, &npen);
  CHECK(r.npen == npen && npen > 3, "npen %d, expected %d", r.npen, npen);
  for (int i = 0; i < 3; i++) {
    CHECK_NEAR(r.force[i], F[i], 1e-10 * fix_norm(F));
    CHECK_NEAR(r.torque_a[i], Ta[i], 1e-10 * fix_norm(F));
  }
  CHECK_NEAR(angular_imbalance(&pa, &pb, &r), 0.0, 1e-12 * fix_norm(F));

  /* node_stride 2: every second node, twice the force per node */
  prm.detect.node_stride = 2;
  fix_contact(&A, &pa, &B, &pb, &prm, 1, NULL, 0, NULL, NULL, &r);
  expected_sphere_sum(&pa, &pb, kn, 2, F, Ta, &npen);
  CHECK(r.npen == npen, "stride 2: npen %d, expected %d", r.npen, npen);
  for (int i = 0; i < 3; i++) CHECK_NEAR(r.force[i], F[i], 1e-10 * fix_norm(F));
}

/* A rotated box B (half-extents a): inside it, phi = -min_i (a_i - |q_i|) and the
 * normal is sign(q_i) e_i of the nearest face, taken to the world with RB. */
static void expected_box_sum(const lsdem_pose *pa, const lsdem_pose *pb, const double a[3],
                             double kn, double F[3], int *npen)
{
  memset(F, 0, 3 * sizeof(double));
  *npen = 0;
  for (int k = 0; k < NNODES; k++) {
    double p[3], d[3], q[3];
    world_node(pa, &nodes_unit[3 * k], p);
    for (int i = 0; i < 3; i++) d[i] = p[i] - pb->x[i];
    for (int i = 0; i < 3; i++)
      q[i] = pb->R[i] * d[0] + pb->R[3 + i] * d[1] + pb->R[6 + i] * d[2];
    int face = -1;
    double depth = HUGE_VAL;
    for (int i = 0; i < 3; i++) {
      const double gap = a[i] - fabs(q[i]);
      if (gap <= 0) face = -2;
      if (face != -2 && gap < depth) {
        depth = gap;
        face = i;
      }
    }
    if (face < 0) continue;
    (*npen)++;
    const double s = q[face] > 0 ? 1.0 : -1.0;
    for (int i = 0; i < 3; i++) F[i] += kn * depth * s * pb->R[3 * i + face];
  }
}

static void box_pair(lsdem_shape *A, lsdem_shape *B, lsdem_pose *pa, lsdem_pose *pb,
                     const double a[3])
{
  *A = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, 1, 0, 0), NNODES, nodes_unit, 1.0);
  *B = fix_shape(fix_sdf(LSDEM_SDF_BOX, a[0], a[1], a[2]), 0, NULL, fix_norm(a));
  *pb = fix_pose(0.3, -0.2, 0.5);
  double k[3] = {1, 2, 3}, j[3] = {-2, 1, 0.5};
  for (int i = 0; i < 3; i++) {
    k[i] /= sqrt(14.0);
    j[i] /= sqrt(5.25);
  }
  fix_axis_angle(k, 0.7, pb->R);
  *pa = fix_pose(0, 0, 0);
  fix_axis_angle(j, 1.1, pa->R);
  const double off[3] = {a[0] + 0.6, 0.2, 0.1}; /* A overlaps B's +x face by 0.4 */
  for (int i = 0; i < 3; i++)
    pa->x[i] = pb->x[i] + pb->R[3 * i] * off[0] + pb->R[3 * i + 1] * off[1] +
               pb->R[3 * i + 2] * off[2];
}

static void test_box_transform(void)
{
  const double a[3] = {2.0, 1.5, 1.0}, kn = 50.0;
  lsdem_shape A, B;
  lsdem_pose pa, pb;
  box_pair(&A, &B, &pa, &pb, a);
  lsdem_contact_params prm = fix_params(kn, 0, 0, 1e-3);
  lsdem_contact_result r;
  double F[3];
  int npen;
  fix_contact(&A, &pa, &B, &pb, &prm, 1, NULL, 0, NULL, NULL, &r);
  expected_box_sum(&pa, &pb, a, kn, F, &npen);
  CHECK(r.npen == npen && npen > 3, "box: npen %d, expected %d", r.npen, npen);
  for (int i = 0; i < 3; i++) CHECK_NEAR(r.force[i], F[i], 1e-10 * fix_norm(F));
  /* the force is along B's +x face normal, RB e_x */
  double nx[3] = {pb.R[0], pb.R[3], pb.R[6]};
  double c[3];
  fix_cross(r.force, nx, c);
  CHECK_NEAR(fix_norm(c), 0.0, 1e-10 * fix_norm(r.force));
}

/* Action-reaction with friction, damping and moving, spinning grains: the pair's
 * angular momentum change about the origin is zero; also at a later step with
 * history. */
static void test_momentum_balance(void)
{
  const double a[3] = {2.0, 1.5, 1.0};
  lsdem_shape A, B;
  lsdem_pose pa, pb;
  box_pair(&A, &B, &pa, &pb, a);
  const double va[3] = {0.3, -0.7, 0.2}, vb[3] = {-0.1, 0.4, 0.5};
  const double wa[3] = {1.1, 0.2, -0.6}, wb[3] = {-0.3, 0.9, 0.4};
  memcpy(pa.v, va, sizeof va);
  memcpy(pb.v, vb, sizeof vb);
  memcpy(pa.omega, wa, sizeof wa);
  memcpy(pb.omega, wb, sizeof wb);
  lsdem_contact_params prm = fix_params(50.0, 40.0, 0.4, 1e-2);
  prm.law.cn = 2.0;
  prm.law.ct = 1.0;
  lsdem_shear_hist h1[NNODES], h2[NNODES];
  int n1 = 0, n2 = 0;
  lsdem_contact_result r;
  fix_contact(&A, &pa, &B, &pb, &prm, 7, NULL, 0, h1, &n1, &r);
  CHECK(n1 == r.npen && n1 > 3, "history entries %d, npen %d", n1, r.npen);
  for (int e = 1; e < n1; e++) CHECK(h1[e].node > h1[e - 1].node, "history not sorted");
  const double scale = fix_norm(r.force) * 3.0;
  CHECK_NEAR(angular_imbalance(&pa, &pb, &r), 0.0, 1e-13 * scale);
  pa.x[0] += 0.01; /* a small move: most contacts persist, their shear rotates */
  pa.x[1] -= 0.005;
  fix_contact(&A, &pa, &B, &pb, &prm, 8, h1, n1, h2, &n2, &r);
  CHECK(n2 > 0, "history entries at step 8: %d", n2);
  CHECK_NEAR(angular_imbalance(&pa, &pb, &r), 0.0, 1e-13 * scale);
  /* every applied tangential force respects the cap */
  for (int e = 0; e < n2; e++) {
    const double *s = h2[e].shear, *n = h2[e].normal;
    const double sn = s[0] * n[0] + s[1] * n[1] + s[2] * n[2];
    CHECK_NEAR(sn, 0.0, 1e-12 * (1 + fix_norm(s)));
  }
}

/* Two identical point-symmetric spheres: A's nodes on B give the mirror image of B's
 * nodes on A, so each direction's force is minus the other's, and the two-way average
 * is equal and opposite and balances angular momentum. */
static void test_two_way(void)
{
  lsdem_shape A = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, 1, 0, 0), NNODES, nodes_unit, 1.0);
  lsdem_shape B = A;
  lsdem_pose pa = fix_pose(0, 0, 0), pb = fix_pose(1.8, 0.3, -0.2);
  fix_axis_angle((double[]){0, 0.6, 0.8}, 0.4, pa.R);
  memcpy(pb.R, pa.R, sizeof pa.R);
  lsdem_contact_params prm = fix_params(100.0, 0, 0, 1e-3);
  lsdem_contact_result ab, ba;
  fix_contact(&A, &pa, &B, &pb, &prm, 1, NULL, 0, NULL, NULL, &ab);
  fix_contact(&B, &pb, &A, &pa, &prm, 1, NULL, 0, NULL, NULL, &ba);
  const double fs = fix_norm(ab.force);
  CHECK(ab.npen > 1 && ab.npen == ba.npen, "npen %d vs %d", ab.npen, ba.npen);
  for (int i = 0; i < 3; i++) {
    CHECK_NEAR(ab.force[i], -ba.force[i], 1e-12 * fs);
    CHECK_NEAR(ab.torque_a[i], ba.torque_a[i], 1e-12 * fs);
  }
  lsdem_contact_result avg;
  memset(&avg, 0, sizeof avg);
  double fb[3];
  for (int i = 0; i < 3; i++) {
    avg.force[i] = 0.5 * (ab.force[i] - ba.force[i]);
    avg.torque_a[i] = 0.5 * (ab.torque_a[i] + ba.torque_b[i]);
    avg.torque_b[i] = 0.5 * (ab.torque_b[i] + ba.torque_a[i]);
    fb[i] = 0.5 * (ba.force[i] - ab.force[i]);
    CHECK(fb[i] == -avg.force[i], "two-way forces not exactly opposite");
  }
  CHECK_NEAR(angular_imbalance(&pa, &pb, &avg), 0.0, 1e-12 * fs);
}

/* ---- tangential history: one node (A's node 0) in contact ---- */

typedef struct {
  lsdem_shape A, B;
  lsdem_pose pa, pb;
  lsdem_contact_params prm;
  double delta;
} one_node;

static one_node one_node_setup(void)
{
  one_node s;
  s.delta = 1e-3;
  s.A = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, 1, 0, 0), NNODES, nodes_unit, 1.0);
  s.B = s.A;
  s.pa = fix_pose(0, 0, 0);
  s.pb = fix_pose(2.0 - s.delta, 0, 0);
  s.prm = fix_params(1000.0, 800.0, 0.5, 1e-3);
  return s;
}

static void test_history_slide_and_cap(void)
{
  one_node s = one_node_setup();
  const double vt = 0.1;
  s.pa.v[1] = vt; /* A slides along +y over B */
  const double inc = s.prm.law.ks * vt * s.prm.dt;         /* 0.08 per step */
  const double cap = s.prm.law.mu * s.prm.law.kn * s.delta;    /* 0.5 */
  lsdem_shear_hist h[2][NNODES];
  int n = 0, cur = 0, capped_steps = 0;
  lsdem_contact_result r;
  for (int step = 1; step <= 10; step++) {
    int n_out;
    fix_contact(&s.A, &s.pa, &s.B, &s.pb, &s.prm, step, h[cur], n, h[1 - cur], &n_out,
                        &r);
    cur = 1 - cur;
    n = n_out;
    CHECK(n == 1 && h[cur][0].node == 0 && h[cur][0].stamp == lsdem_shear_stamp(step),
          "history at step %d", step);
    const double expect = fmin(step * inc, cap);
    if (step * inc > cap) capped_steps++;
    CHECK_REL(r.force[1], -expect, 1e-9);
    CHECK_NEAR(r.force[2], 0.0, 1e-15);
    CHECK_REL(r.force[0], -s.prm.law.kn * s.delta, 1e-9);
    CHECK_REL(h[cur][0].shear[1], -expect, 1e-9);
  }
  CHECK(capped_steps == 4, "capped steps %d", capped_steps);
  /* exactly at the cap (relative round-off only) */
  CHECK_NEAR(fabs(r.force[1]), s.prm.law.mu * fabs(r.force[0]), 1e-14);

  /* a second call at the same step reuses the entry: no second increment */
  lsdem_shear_hist again[NNODES];
  int n_again;
  lsdem_contact_result r2;
  s.prm.law.mu = 10.0; /* cap out of the way: an advance would show */
  fix_contact(&s.A, &s.pa, &s.B, &s.pb, &s.prm, 10, h[cur], n, again, &n_again, &r2);
  CHECK(n_again == 1, "entries %d", n_again);
  CHECK(r2.force[1] == r.force[1], "same-step call changed the shear: %g vs %g", r2.force[1],
        r.force[1]);
  CHECK(again[0].shear[1] == h[cur][0].shear[1], "same-step shear advanced");
  /* the next step advances it again, now uncapped */
  fix_contact(&s.A, &s.pa, &s.B, &s.pb, &s.prm, 11, again, 1, h[1 - cur], &n, &r2);
  CHECK_REL(r2.force[1], -cap - inc, 1e-9);
}

/* Shear from eq 2.6's angular terms: A spinning about z at wa, B at wb. At the
 * contact node p = (1,0,0): wa x (p - xA) = (0, wa, 0), wb x (p - xB) = (0, -wb(1-d), 0). */
static void test_relative_velocity(void)
{
  one_node s = one_node_setup();
  s.pa.v[1] = 0.02;
  s.pb.v[1] = -0.03;
  s.pa.omega[2] = 0.5;
  s.pb.omega[2] = 0.25;
  s.pb.v[0] = 0.7; /* normal relative velocity: no shear from it */
  s.prm.law.mu = 100.0; /* keep the cap out of the way */
  lsdem_shear_hist h[NNODES];
  int n;
  lsdem_contact_result r;
  fix_contact(&s.A, &s.pa, &s.B, &s.pb, &s.prm, 1, NULL, 0, h, &n, &r);
  const double vrel = 0.02 + 0.5 - (-0.03) + 0.25 * (1.0 - s.delta);
  CHECK_REL(h[0].shear[1], -s.prm.law.ks * s.prm.dt * vrel, 1e-12);
  CHECK_NEAR(h[0].shear[0], 0.0, 1e-15);
  CHECK_NEAR(h[0].shear[2], 0.0, 1e-15);
}

/* Rotating the whole pair by Q about z (perpendicular to the normal) rotates the
 * stored shear with the normal: the next step's shear is Q s (no sliding). */
static void test_history_rotation(void)
{
  one_node s = one_node_setup();
  s.pa.v[1] = 0.1;
  s.pa.v[2] = -0.05;
  lsdem_shear_hist h1[NNODES], h2[NNODES], h3[NNODES];
  int n1, n2, n3;
  lsdem_contact_result r;
  fix_contact(&s.A, &s.pa, &s.B, &s.pb, &s.prm, 1, NULL, 0, h1, &n1, &r);
  fix_contact(&s.A, &s.pa, &s.B, &s.pb, &s.prm, 2, h1, n1, h2, &n2, &r);
  const double *s_old = h2[0].shear;
  CHECK(fix_norm(s_old) > 0 && fix_norm(s_old) < s.prm.law.mu * s.prm.law.kn * s.delta,
        "shear %g must be below the cap for this test", fix_norm(s_old));

  double Q[9];
  fix_axis_angle((double[]){0, 0, 1}, 0.5, Q);
  lsdem_pose qa = s.pa, qb = s.pb;
  memset(qa.v, 0, sizeof qa.v);
  for (int i = 0; i < 3; i++) {
    qa.x[i] = Q[3 * i] * s.pa.x[0] + Q[3 * i + 1] * s.pa.x[1] + Q[3 * i + 2] * s.pa.x[2];
    qb.x[i] = Q[3 * i] * s.pb.x[0] + Q[3 * i + 1] * s.pb.x[1] + Q[3 * i + 2] * s.pb.x[2];
  }
  memcpy(qa.R, Q, sizeof Q);
  memcpy(qb.R, Q, sizeof Q);
  fix_contact(&s.A, &qa, &s.B, &qb, &s.prm, 3, h2, n2, h3, &n3, &r);
  CHECK(n3 == 1, "entries %d", n3);
  for (int i = 0; i < 3; i++) {
    const double qs = Q[3 * i] * s_old[0] + Q[3 * i + 1] * s_old[1] + Q[3 * i + 2] * s_old[2];
    CHECK_NEAR(h3[0].shear[i], qs, 1e-12);
    const double qn = -Q[3 * i]; /* Q (-e_x) */
    CHECK_NEAR(h3[0].normal[i], qn, 1e-12);
    CHECK_NEAR(r.force[i], s.prm.law.kn * s.delta * qn + qs, 1e-9);
  }
}

static void test_no_history_without_friction(void)
{
  one_node s = one_node_setup();
  s.prm.law.mu = 0.0;
  s.pa.v[1] = 1.0;
  lsdem_shear_hist h[NNODES];
  int n = -1;
  lsdem_contact_result r;
  fix_contact(&s.A, &s.pa, &s.B, &s.pb, &s.prm, 1, NULL, 0, h, &n, &r);
  CHECK(r.npen == 1 && n == 0, "npen %d, history entries %d", r.npen, n);
  CHECK(r.force[1] == 0.0, "tangential force %g without friction", r.force[1]);
}

static void test_stride_single_node(void)
{
  one_node s = one_node_setup();
  s.prm.law.mu = 0.0;
  lsdem_contact_result r1, r3;
  fix_contact(&s.A, &s.pa, &s.B, &s.pb, &s.prm, 1, NULL, 0, NULL, NULL, &r1);
  s.prm.detect.node_stride = 3;
  fix_contact(&s.A, &s.pa, &s.B, &s.pb, &s.prm, 1, NULL, 0, NULL, NULL, &r3);
  CHECK(r3.npen == 1, "npen %d", r3.npen);
  CHECK_REL(r3.force[0], 3.0 * r1.force[0], 1e-15);
}

static void test_traction_and_damping(void)
{
  one_node s = one_node_setup();
  s.prm.law.mu = 0.0;
  double area[NNODES];
  for (int k = 0; k < NNODES; k++) area[k] = 0.05 + 0.001 * k;
  s.A.node_area = area;
  s.prm.law.normal = LSDEM_NORMAL_TRACTION;
  lsdem_contact_result r;
  fix_contact(&s.A, &s.pa, &s.B, &s.pb, &s.prm, 1, NULL, 0, NULL, NULL, &r);
  CHECK_REL(r.force[0], -s.prm.law.kn * s.delta * 0.05, 1e-9);

  /* normal damping: A approaching B at u adds cn u to the repulsion */
  s.prm.law.normal = LSDEM_NORMAL_PER_NODE;
  s.prm.law.cn = 3.0;
  s.pa.v[0] = 0.2;
  fix_contact(&s.A, &s.pa, &s.B, &s.pb, &s.prm, 1, NULL, 0, NULL, NULL, &r);
  CHECK_REL(r.force[0], -(s.prm.law.kn * s.delta + 3.0 * 0.2), 1e-9);
  /* separating fast: the damped normal force is clamped at zero, never attractive */
  s.pa.v[0] = -10.0;
  fix_contact(&s.A, &s.pa, &s.B, &s.pb, &s.prm, 1, NULL, 0, NULL, NULL, &r);
  CHECK(r.force[0] == 0.0 && r.npen == 1, "force %g, npen %d", r.force[0], r.npen);
}

/* Cheap rejection: no lookups beyond the bounding spheres; clusters are used (a
 * cluster whose sphere is placed away hides its nodes) and change nothing when
 * their spheres are honest. */
static void test_rejection_and_clusters(void)
{
  lsdem_shape A = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, 1, 0, 0), NNODES, nodes_unit, 1.0);
  lsdem_shape B = A;
  lsdem_pose pa = fix_pose(0, 0, 0), pb = fix_pose(2.0001, 0, 0);
  lsdem_contact_params prm = fix_params(100.0, 0, 0, 1e-3);
  lsdem_contact_result r;
  fix_contact(&A, &pa, &B, &pb, &prm, 1, NULL, 0, NULL, NULL, &r);
  CHECK(r.ntested == 0 && r.npen == 0 && r.force[0] == 0.0, "far pair: ntested %d",
        r.ntested);
  pb.x[0] = 1.999; /* bounding spheres overlap; only nodes inside B's sphere looked up */
  fix_contact(&A, &pa, &B, &pb, &prm, 1, NULL, 0, NULL, NULL, &r);
  CHECK(r.ntested == 1, "near pair: ntested %d", r.ntested);

  static double nodes_c[3 * NNODES], scratch[3 * NNODES], sphere[4 * NNODES];
  static int start[NNODES + 1];
  memcpy(nodes_c, nodes_unit, sizeof nodes_c);
  lsdem_shape C = A;
  C.nodes = nodes_c;
  C.cluster_start = start;
  C.cluster_sphere = sphere;
  C.nclusters = fix_octant_clusters(NNODES, nodes_c, scratch, start, sphere);
  CHECK(C.nclusters == 8, "clusters %d", C.nclusters);

  const double a[3] = {2.0, 1.5, 1.0};
  lsdem_shape Aunused, Bbox;
  lsdem_pose qa, qb;
  box_pair(&Aunused, &Bbox, &qa, &qb, a);
  lsdem_contact_result ru, rc;
  A.nodes = nodes_c; /* same order, no clusters */
  fix_contact(&A, &qa, &Bbox, &qb, &prm, 1, NULL, 0, NULL, NULL, &ru);
  fix_contact(&C, &qa, &Bbox, &qb, &prm, 1, NULL, 0, NULL, NULL, &rc);
  CHECK(ru.npen == rc.npen && ru.ntested == rc.ntested, "clustered npen %d/%d", rc.npen,
        ru.npen);
  for (int i = 0; i < 3; i++) CHECK(ru.force[i] == rc.force[i], "clustered force differs");

  /* with a node stride the same nodes are tested, clusters or not */
  prm.detect.node_stride = 3;
  fix_contact(&A, &qa, &Bbox, &qb, &prm, 1, NULL, 0, NULL, NULL, &ru);
  fix_contact(&C, &qa, &Bbox, &qb, &prm, 1, NULL, 0, NULL, NULL, &rc);
  CHECK(ru.npen == rc.npen && ru.npen > 0, "stride 3: clustered npen %d/%d", rc.npen, ru.npen);
  for (int i = 0; i < 3; i++) CHECK(ru.force[i] == rc.force[i], "stride 3: force differs");
  prm.detect.node_stride = 1;

  /* move every cluster sphere far away: all nodes are skipped */
  for (int c = 0; c < C.nclusters; c++) sphere[4 * c] += 100.0;
  fix_contact(&C, &qa, &Bbox, &qb, &prm, 1, NULL, 0, NULL, NULL, &rc);
  CHECK(rc.ntested == 0 && rc.npen == 0, "displaced clusters: ntested %d", rc.ntested);
}

/* A container (inverted sphere of radius 3, unbounded solid outside): A's node 0 pokes
 * delta through the wall; the force pushes A back towards the centre. */
static void test_inverted_container(void)
{
  const double delta = 1e-3, kn = 500.0;
  lsdem_shape A = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, 1, 0, 0), NNODES, nodes_unit, 1.0);
  lsdem_sdf wall = fix_sdf(LSDEM_SDF_SPHERE, 3.0, 0, 0);
  wall.inverted = 1;
  lsdem_shape W = fix_shape(wall, 0, NULL, HUGE_VAL);
  lsdem_pose pa = fix_pose(2.0 + delta, 0, 0), pw = fix_pose(0, 0, 0);
  lsdem_contact_params prm = fix_params(kn, 0, 0, 1e-3);
  lsdem_contact_result r;
  fix_contact(&A, &pa, &W, &pw, &prm, 1, NULL, 0, NULL, NULL, &r);
  CHECK(r.npen == 1 && r.ntested == NNODES, "container: npen %d, ntested %d", r.npen,
        r.ntested);
  CHECK_REL(r.force[0], -kn * delta, 1e-9);
  CHECK_NEAR(r.force[1], 0.0, 1e-15);
}

/* Sphere fast paths: one lookup; analytic depth and normal; agree with each other. The
 * sphere-shape path is taken against a sphere written as an ellipsoid of equal semi-axes
 * (an exact distance that is not the sphere kind), the closed form against the sphere. */
static void test_sphere_paths(void)
{
  lsdem_contact_params prm = fix_params(200.0, 150.0, 0.3, 1e-3);
  const double ra = 0.5, rb = 2.0;
  lsdem_shape A = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, ra, 0, 0), 0, NULL, ra);
  lsdem_shape B = fix_shape(fix_sdf(LSDEM_SDF_ELLIPSOID, rb, rb, rb), 0, NULL, rb);
  lsdem_shape Bs = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, rb, 0, 0), 0, NULL, rb);
  lsdem_pose pa = fix_pose(1.2, 1.6, 0.9), pb = fix_pose(0.1, 0.2, 0.3);
  fix_axis_angle((double[]){0, 0, 1}, 0.8, pb.R);
  pa.v[2] = 0.4;
  pb.omega[0] = 0.3;
  double d[3];
  for (int i = 0; i < 3; i++) d[i] = pa.x[i] - pb.x[i];
  const double dist = fix_norm(d), depth = ra + rb - dist;
  CHECK(depth > 0, "setup overlap %g", depth);

  lsdem_shear_hist h1[1], h2[1];
  int n1, n2;
  lsdem_contact_result r1, r2;
  const int c1 = fix_contact_grain(&A, &pa, &B, &pb, &prm, 1, h1, &n1, &r1);
  const int c2 = fix_contact_grain(&A, &pa, &Bs, &pb, &prm, 1, h2, &n2, &r2);
  CHECK(c1 == 1 && c2 == 1 && r1.ntested == 1 && n1 == 1 && n2 == 1, "contact %d %d", c1, c2);
  /* normal part: kn * depth along (xA - xB)/|xA - xB| */
  double fn1 = 0;
  for (int i = 0; i < 3; i++) fn1 += r1.force[i] * d[i] / dist;
  CHECK_REL(fn1, prm.law.kn * depth, 1e-12);
  CHECK_REL(r1.max_depth, depth, 1e-12);
  for (int i = 0; i < 3; i++) {
    CHECK_NEAR(r1.force[i], r2.force[i], 1e-12 * prm.law.kn * depth);
    CHECK_NEAR(r1.torque_b[i], r2.torque_b[i], 1e-12 * prm.law.kn * depth);
    /* contact point: middle of the overlap on the line of centres */
    CHECK_NEAR(r1.point[i], pa.x[i] - (ra - 0.5 * depth) * d[i] / dist, 1e-12);
  }
  CHECK(h1[0].node == 0 && fix_norm(h1[0].shear) > 0, "sphere history");
  CHECK_NEAR(angular_imbalance(&pa, &pb, &r1), 0.0, 1e-12 * prm.law.kn);
  /* the sphere's torque is the tangential force's only: |torque_a| = (ra - d/2)|ft| */
  double ft[3];
  for (int i = 0; i < 3; i++) ft[i] = r1.force[i] - fn1 * d[i] / dist;
  CHECK_REL(fix_norm(r1.torque_a), (ra - 0.5 * depth) * fix_norm(ft), 1e-9);

  /* deep inside a grain: depth = r - phi with phi < 0 still pushes out */
  pa = fix_pose(0.1, 0.2, 1.3); /* 1.0 from B's centre: phi = -1 */
  fix_contact_grain(&A, &pa, &B, &pb, &prm, 1, h1, &n1, &r1);
  CHECK_REL(r1.force[2], prm.law.kn * (ra + 1.0), 1e-12);

  /* a wall: plane z <= 0, sphere of radius ra at height ra - 0.01, traction law: the
   * sphere's tributary area is its cross-section */
  lsdem_shape W = fix_shape(fix_sdf(LSDEM_SDF_PLANE, 0, 0, 0), 0, NULL, HUGE_VAL);
  lsdem_pose pw = fix_pose(0, 0, 0);
  pa = fix_pose(3.0, -4.0, ra - 0.01);
  prm.law.normal = LSDEM_NORMAL_TRACTION;
  fix_contact_grain(&A, &pa, &W, &pw, &prm, 1, h1, &n1, &r1);
  CHECK_REL(r1.force[2], prm.law.kn * 0.01 * (FIX_PI * ra * ra), 1e-9);
  CHECK_NEAR(fix_norm(r1.torque_a), 0.0, 1e-15);

  /* out of reach: nothing tested */
  pa = fix_pose(0.1, 0.2, 0.3 + ra + rb + 1e-9);
  CHECK(fix_contact_grain(&A, &pa, &B, &pb, &prm, 1, h1, &n1, &r1) == 0 &&
            r1.ntested == 0 && n1 == 0,
        "far sphere tested");
  CHECK(fix_contact_grain(&A, &pa, &Bs, &pb, &prm, 1, h2, &n2, &r2) == 0,
        "far sphere pair in contact");
}

int main(void)
{
  CHECK(fix_ring_nodes(1.0, NR, NP, nodes_unit) == NNODES, "node count");
  test_single_axis_node();
  test_sphere_overlap_sum();
  test_box_transform();
  test_momentum_balance();
  test_two_way();
  test_history_slide_and_cap();
  test_relative_velocity();
  test_history_rotation();
  test_no_history_without_friction();
  test_stride_single_node();
  test_traction_and_damping();
  test_rejection_and_clusters();
  test_inverted_container();
  test_sphere_paths();
  return lsdem_test_summary();
}
