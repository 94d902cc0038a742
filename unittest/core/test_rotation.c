/* test_rotation.c -- quaternions, matrices, Rodrigues, rotate_between, eq 2.26 mapping,
 * symmetric eigen-solver. Expectations are independent: closed-form rotations, matrix
 * algebra identities, and eq 2.26 typed in from the report. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <math.h>
#include <stdint.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static void random_quat(double q[4])
{
  for (int i = 0; i < 4; i++) q[i] = srand1();
  lsdem_quat_normalize(q);
}
static void random_unit(double v[3])
{
  double n;
  do {
    for (int i = 0; i < 3; i++) v[i] = srand1();
    n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  } while (n < 0.1 || n > 1.0);
  for (int i = 0; i < 3; i++) v[i] /= n;
}
static double dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static double dist3(const double a[3], const double b[3])
{
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
              (a[2] - b[2]) * (a[2] - b[2]));
}
static double max_abs_diff9(const double A[9], const double B[9])
{
  double m = 0.0;
  for (int i = 0; i < 9; i++) m = fmax(m, fabs(A[i] - B[i]));
  return m;
}
static double det3(const double M[9])
{
  return M[0] * (M[4] * M[8] - M[5] * M[7]) - M[1] * (M[3] * M[8] - M[5] * M[6]) +
         M[2] * (M[3] * M[7] - M[4] * M[6]);
}

/* Rotation about z by angle t, built by hand. */
static void rot_z(double t, double R[9])
{
  const double c = cos(t), s = sin(t);
  const double M[9] = {c, -s, 0, s, c, 0, 0, 0, 1};
  for (int i = 0; i < 9; i++) R[i] = M[i];
}

static void test_basic_quaternion(void)
{
  /* q for 90 degrees about z maps x to y */
  const double q[4] = {cos(M_PI / 4), 0, 0, sin(M_PI / 4)};
  const double ex[3] = {1, 0, 0};
  double out[3], R[9], Rz[9];
  lsdem_quat_rotate(q, ex, out);
  CHECK_NEAR(out[0], 0.0, 1e-15);
  CHECK_NEAR(out[1], 1.0, 1e-15);
  CHECK_NEAR(out[2], 0.0, 1e-15);
  lsdem_quat_to_matrix(q, R);
  rot_z(M_PI / 2, Rz);
  CHECK(max_abs_diff9(R, Rz) < 1e-15, "matrix of 90deg about z");
  /* multiplication composes: (a*b) rotates like R(a) R(b); conjugate inverts */
  for (int t = 0; t < 200; t++) {
    double a[4], b[4], ab[4], v[3], w1[3], w2[3], tmp[3], ac[4], back[3];
    random_quat(a);
    random_quat(b);
    for (int i = 0; i < 3; i++) v[i] = 3.0 * srand1();
    lsdem_quat_multiply(a, b, ab);
    lsdem_quat_rotate(ab, v, w1);
    lsdem_quat_rotate(b, v, tmp);
    lsdem_quat_rotate(a, tmp, w2);
    CHECK(dist3(w1, w2) < 1e-13, "composition");
    lsdem_quat_conjugate(a, ac);
    lsdem_quat_rotate(ac, w2, tmp);
    lsdem_quat_rotate_inv(a, w2, back);
    CHECK(dist3(tmp, back) < 1e-13, "rotate_inv == rotate by conjugate");
    lsdem_quat_rotate(a, back, tmp);
    CHECK(dist3(tmp, w2) < 1e-13, "rotate_inv inverts rotate");
  }
  double z[4] = {0, 0, 0, 0};
  lsdem_quat_normalize(z);
  CHECK(z[0] == 1.0 && z[1] == 0.0, "zero quaternion normalises to identity");
}

static void test_rotate_vs_matrix(void)
{
  double worst = 0.0, worst_orth = 0.0, worst_rt = 0.0;
  for (int t = 0; t < 1000; t++) {
    double q[4], R[9], v[3], a[3], b[3], c[3], q2[4], R2[9];
    random_quat(q);
    for (int i = 0; i < 3; i++) v[i] = 5.0 * srand1();
    lsdem_quat_to_matrix(q, R);
    lsdem_quat_rotate(q, v, a);
    lsdem_mat_vec(R, v, b);
    worst = fmax(worst, dist3(a, b));
    lsdem_quat_rotate_inv(q, v, a);
    lsdem_matT_vec(R, v, c);
    worst = fmax(worst, dist3(a, c));
    /* R R^T = I and det = +1 */
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        double s = 0;
        for (int k = 0; k < 3; k++) s += R[3 * i + k] * R[3 * j + k];
        worst_orth = fmax(worst_orth, fabs(s - (i == j)));
      }
    worst_orth = fmax(worst_orth, fabs(det3(R) - 1.0));
    /* matrix -> quaternion -> matrix round trip; quaternion equal up to sign */
    lsdem_matrix_to_quat(R, q2);
    lsdem_quat_to_matrix(q2, R2);
    worst_rt = fmax(worst_rt, max_abs_diff9(R, R2));
    const double sgn = (q[0] * q2[0] + q[1] * q2[1] + q[2] * q2[2] + q[3] * q2[3]) < 0 ? -1 : 1;
    for (int i = 0; i < 4; i++) worst_rt = fmax(worst_rt, fabs(q[i] - sgn * q2[i]));
  }
  CHECK(worst < 1e-13, "quat_rotate vs matrix: %g", worst);
  CHECK(worst_orth < 1e-14, "orthonormality: %g", worst_orth);
  CHECK(worst_rt < 1e-14, "matrix_to_quat round trip: %g", worst_rt);
  /* half-turns exercise the non-trace branches of Shepperd's method */
  const double half_turns[3][4] = {{0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0.6, 0, 0.8}};
  for (int t = 0; t < 3; t++) {
    double R[9], q2[4], R2[9];
    lsdem_quat_to_matrix(half_turns[t], R);
    lsdem_matrix_to_quat(R, q2);
    lsdem_quat_to_matrix(q2, R2);
    CHECK(max_abs_diff9(R, R2) < 1e-15, "half-turn round trip %d", t);
  }
}

static void test_advance(void)
{
  /* constant body omega about a fixed axis k: closed form q(t) = q0 * (cos(wt/2), sin(wt/2) k) */
  for (int t = 0; t < 50; t++) {
    double q0[4], k[3], q[4];
    random_quat(q0);
    random_unit(k);
    const double w = 0.5 + 10.0 * urand(), dt = 1e-3 * (1 + urand());
    const int steps = 1000;
    double omega[3] = {w * k[0], w * k[1], w * k[2]};
    for (int i = 0; i < 4; i++) q[i] = q0[i];
    for (int s = 0; s < steps; s++) lsdem_quat_advance(q, omega, dt);
    const double ang = w * dt * steps;
    const double e[4] = {cos(ang / 2), sin(ang / 2) * k[0], sin(ang / 2) * k[1],
                         sin(ang / 2) * k[2]};
    double exact[4];
    lsdem_quat_multiply(q0, e, exact);
    double err = 0;
    for (int i = 0; i < 4; i++) err = fmax(err, fabs(q[i] - exact[i]));
    CHECK(err < 1e-12, "advance vs closed form: %g", err);
  }
  /* body-frame semantics: the body axis k stays fixed in the world under spin about k */
  double q[4] = {1, 0, 0, 0}, k[3] = {0, 0, 1}, xb[3] = {1, 0, 0}, xw[3], kw[3];
  const double omega[3] = {0, 0, M_PI};
  lsdem_quat_advance(q, omega, 0.5); /* a quarter turn about z */
  lsdem_quat_rotate(q, xb, xw);
  lsdem_quat_rotate(q, k, kw);
  CHECK_NEAR(xw[1], 1.0, 1e-15);
  CHECK_NEAR(kw[2], 1.0, 1e-15);
  /* tiny omega (Taylor branch) agrees with the first-order rate equation dq = q (0,w) dt/2 */
  double qa[4], qb[4], wq[4];
  random_quat(qa);
  const double om[3] = {1e-6, -2e-6, 3e-6};
  for (int i = 0; i < 4; i++) qb[i] = qa[i];
  lsdem_quat_advance(qa, om, 1.0);
  const double pure[4] = {0, om[0] / 2, om[1] / 2, om[2] / 2};
  lsdem_quat_multiply(qb, pure, wq);
  for (int i = 0; i < 4; i++) CHECK_NEAR(qa[i], qb[i] + wq[i], 1e-11);
}

static void test_rodrigues(void)
{
  for (int t = 0; t < 500; t++) {
    double v[3], k[3], out[3], q[4], ref[3];
    for (int i = 0; i < 3; i++) v[i] = 4.0 * srand1();
    random_unit(k);
    const double th = M_PI * srand1();
    lsdem_rodrigues(v, k, th, out);
    CHECK_NEAR(sqrt(dot(out, out)), sqrt(dot(v, v)), 1e-13); /* keeps length */
    CHECK_NEAR(dot(out, k), dot(v, k), 1e-13);               /* keeps the axial part */
    /* angle between the components perpendicular to k equals |theta| */
    double vp[3], op[3];
    for (int i = 0; i < 3; i++) {
      vp[i] = v[i] - dot(v, k) * k[i];
      op[i] = out[i] - dot(out, k) * k[i];
    }
    const double c = dot(vp, op) / dot(vp, vp);
    if (dot(vp, vp) > 1e-3) CHECK_NEAR(c, cos(th), 1e-12);
    /* the same rotation as a quaternion (cos(th/2), sin(th/2) k) */
    q[0] = cos(th / 2);
    for (int i = 0; i < 3; i++) q[i + 1] = sin(th / 2) * k[i];
    lsdem_quat_rotate(q, v, ref);
    CHECK(dist3(out, ref) < 1e-13, "rodrigues vs quaternion");
  }
}

static void test_rotate_between(void)
{
  double worst_map = 0, worst_perp = 0, worst_len = 0;
  for (int t = 0; t < 1000; t++) {
    double a[3], b[3], out[3], v[3], perp[3];
    random_unit(a);
    random_unit(b);
    lsdem_rotate_between(a, a, b, out);
    worst_map = fmax(worst_map, dist3(out, b));
    /* a x b is orthogonal to both and must be unchanged */
    perp[0] = a[1] * b[2] - a[2] * b[1];
    perp[1] = a[2] * b[0] - a[0] * b[2];
    perp[2] = a[0] * b[1] - a[1] * b[0];
    lsdem_rotate_between(perp, a, b, out);
    worst_perp = fmax(worst_perp, dist3(out, perp));
    for (int i = 0; i < 3; i++) v[i] = 3.0 * srand1();
    lsdem_rotate_between(v, a, b, out);
    worst_len = fmax(worst_len, fabs(sqrt(dot(out, out)) - sqrt(dot(v, v))));
    /* the rotation angle is the angle between a and b: (v.a) is carried to (out.b) */
    CHECK_NEAR(dot(out, b), dot(v, a), 1e-12);
  }
  CHECK(worst_map < 1e-13, "rotate_between maps n_old to n_new: %g", worst_map);
  CHECK(worst_perp < 1e-13, "vectors orthogonal to both unchanged: %g", worst_perp);
  CHECK(worst_len < 1e-13, "length kept: %g", worst_len);
  /* equal normals: identity */
  double a[3], v[3] = {0.3, -0.7, 2.0}, out[3];
  random_unit(a);
  lsdem_rotate_between(v, a, a, out);
  CHECK(dist3(out, v) < 1e-15, "identity for equal normals");
  /* exactly and nearly opposite normals: still a rotation mapping a to b */
  const double eps[4] = {0.0, 1e-12, 1e-9, 1e-7};
  for (int t = 0; t < 4; t++) {
    double b[3], w[3], u[3];
    random_unit(a);
    random_unit(u);
    for (int i = 0; i < 3; i++) b[i] = -a[i] + eps[t] * u[i];
    const double nb = sqrt(dot(b, b));
    for (int i = 0; i < 3; i++) b[i] /= nb;
    lsdem_rotate_between(a, a, b, w);
    CHECK(dist3(w, b) < 1e-12, "opposite normals (eps %g): |R a - b| = %g", eps[t],
          dist3(w, b));
    lsdem_rotate_between(v, a, b, out);
    CHECK_NEAR(sqrt(dot(out, out)), sqrt(dot(v, v)), 1e-12);
    CHECK_NEAR(dot(out, b), dot(v, a), 1e-12);
  }
}

static void test_tan_mapping(void)
{
  /* Eq 2.26 as printed vs the textbook matrix of the mapped quaternion. */
  double worst = 0, worst_back = 0;
  for (int t = 0; t < 2000; t++) {
    double qt[4], q[4], R1[9], R2[9], back[4];
    random_quat(qt);
    lsdem_tan_matrix_eq226(qt, R1);
    lsdem_quat_from_tan(qt, q);
    lsdem_quat_to_matrix(q, R2);
    worst = fmax(worst, max_abs_diff9(R1, R2));
    lsdem_quat_to_tan(q, back);
    for (int i = 0; i < 4; i++) worst_back = fmax(worst_back, fabs(back[i] - qt[i]));
  }
  CHECK(worst < 1e-14, "eq 2.26 == R(quat_from_tan(q)): %g", worst);
  CHECK(worst_back == 0.0, "quat_to_tan inverts quat_from_tan: %g", worst_back);
  /* eq 2.27 with Euler angles (z, x', z'): theta = phi = psi = 0 is the identity, and
   * a pure first rotation by angle a about z (theta = psi = 0) */
  const double a = 0.7;
  const double qt[4] = {0, 0, sin(a / 2), cos(a / 2)}; /* Evans q3 = cos(th/2) sin(phi/2) */
  double R[9], Rz[9], q[4], R2[9];
  lsdem_tan_matrix_eq226(qt, R);
  rot_z(a, Rz);
  /* either R or its transpose: record which; eq 2.26 is a proper rotation either way */
  double RzT[9] = {Rz[0], Rz[3], Rz[6], Rz[1], Rz[4], Rz[7], Rz[2], Rz[5], Rz[8]};
  CHECK(max_abs_diff9(R, Rz) < 1e-15 || max_abs_diff9(R, RzT) < 1e-15, "eq 2.27 z rotation");
  lsdem_quat_from_tan(qt, q);
  lsdem_quat_to_matrix(q, R2);
  CHECK(max_abs_diff9(R, R2) < 1e-15, "mapping on the z rotation");
}

static void test_sym_eigen(void)
{
  for (int t = 0; t < 300; t++) {
    double q[4], Q[9], w0[3], A[9], w[3], V[9];
    random_quat(q);
    lsdem_quat_to_matrix(q, Q);
    for (int i = 0; i < 3; i++) w0[i] = 10.0 * srand1();
    if (t % 3 == 0) w0[1] = w0[0]; /* a repeated eigenvalue */
    if (t % 7 == 0) w0[0] = w0[1] = w0[2] = 2.5; /* multiple of identity */
    for (int i = 0; i < 3; i++) /* A = Q diag(w0) Q^T */
      for (int j = 0; j < 3; j++) {
        double s = 0;
        for (int k = 0; k < 3; k++) s += Q[3 * i + k] * w0[k] * Q[3 * j + k];
        A[3 * i + j] = s;
      }
    lsdem_sym_eigen(A, w, V);
    /* sort the expected values */
    double e[3] = {w0[0], w0[1], w0[2]};
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2 - i; j++)
        if (e[j] > e[j + 1]) {
          const double tmp = e[j];
          e[j] = e[j + 1];
          e[j + 1] = tmp;
        }
    for (int k = 0; k < 3; k++) CHECK_NEAR(w[k], e[k], 1e-12);
    CHECK(w[0] <= w[1] && w[1] <= w[2], "ascending");
    CHECK_NEAR(det3(V), 1.0, 1e-13);
    /* A v_k = w_k v_k for every column */
    double res = 0;
    for (int k = 0; k < 3; k++) {
      const double v[3] = {V[k], V[3 + k], V[6 + k]};
      double Av[3];
      lsdem_mat_vec(A, v, Av);
      for (int i = 0; i < 3; i++) res = fmax(res, fabs(Av[i] - w[k] * v[i]));
    }
    CHECK(res < 1e-12, "eigen residual %g", res);
  }
  /* diagonal input: eigenvectors are coordinate axes */
  const double D[9] = {3, 0, 0, 0, 1, 0, 0, 0, 2};
  double w[3], V[9];
  lsdem_sym_eigen(D, w, V);
  CHECK(w[0] == 1 && w[1] == 2 && w[2] == 3, "diagonal eigenvalues %g %g %g", w[0], w[1], w[2]);
  CHECK_NEAR(fabs(V[3 * 1 + 0]), 1.0, 0.0);
  CHECK_NEAR(fabs(V[3 * 2 + 1]), 1.0, 0.0);
  CHECK_NEAR(fabs(V[3 * 0 + 2]), 1.0, 0.0);
}

int main(void)
{
  test_basic_quaternion();
  test_rotate_vs_matrix();
  test_advance();
  test_rodrigues();
  test_rotate_between();
  test_tan_mapping();
  test_sym_eigen();
  return lsdem_test_summary();
}
