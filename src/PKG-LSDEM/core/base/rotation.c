/* rotation.c -- quaternions, rotation matrices, Rodrigues' formula, the shear-history
 * rotation Z of report eq 2.8, the Kawamoto/Tan quaternion convention (eq 2.26) and a
 * symmetric 3x3 eigen-solver.
 *
 * Quaternions are scalar-first (w, x, y, z) and rotate body-frame vectors into the world
 * frame: v_world = R(q) v_body = q v_body q*. Matrices are row-major double[9]. */
#include "lsdem_base.h"

#include <math.h>

/* ------------------------------------------------------------- quaternions ---- */

void lsdem_quat_conjugate(const double q[4], double out[4])
{
  out[0] = q[0];
  out[1] = -q[1];
  out[2] = -q[2];
  out[3] = -q[3];
}

/* Textbook body -> world matrix of a unit quaternion. */
void lsdem_quat_to_matrix(const double q[4], double R[9])
{
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  R[0] = 1.0 - 2.0 * (y * y + z * z);
  R[1] = 2.0 * (x * y - w * z);
  R[2] = 2.0 * (x * z + w * y);
  R[3] = 2.0 * (x * y + w * z);
  R[4] = 1.0 - 2.0 * (x * x + z * z);
  R[5] = 2.0 * (y * z - w * x);
  R[6] = 2.0 * (x * z - w * y);
  R[7] = 2.0 * (y * z + w * x);
  R[8] = 1.0 - 2.0 * (x * x + y * y);
}

/* Shepperd's method: extract the largest of |w|,|x|,|y|,|z| from the diagonal first, so
 * the division is always by a quantity >= 1/2. Result has w >= 0 where possible. */
void lsdem_matrix_to_quat(const double R[9], double q[4])
{
  const double tr = R[0] + R[4] + R[8];
  if (tr >= R[0] && tr >= R[4] && tr >= R[8]) {
    const double s = 2.0 * sqrt(1.0 + tr); /* 4w */
    q[0] = 0.25 * s;
    q[1] = (R[7] - R[5]) / s;
    q[2] = (R[2] - R[6]) / s;
    q[3] = (R[3] - R[1]) / s;
  } else if (R[0] >= R[4] && R[0] >= R[8]) {
    const double s = 2.0 * sqrt(1.0 + R[0] - R[4] - R[8]); /* 4x */
    q[0] = (R[7] - R[5]) / s;
    q[1] = 0.25 * s;
    q[2] = (R[1] + R[3]) / s;
    q[3] = (R[2] + R[6]) / s;
  } else if (R[4] >= R[8]) {
    const double s = 2.0 * sqrt(1.0 + R[4] - R[0] - R[8]); /* 4y */
    q[0] = (R[2] - R[6]) / s;
    q[1] = (R[1] + R[3]) / s;
    q[2] = 0.25 * s;
    q[3] = (R[5] + R[7]) / s;
  } else {
    const double s = 2.0 * sqrt(1.0 + R[8] - R[0] - R[4]); /* 4z */
    q[0] = (R[3] - R[1]) / s;
    q[1] = (R[2] + R[6]) / s;
    q[2] = (R[5] + R[7]) / s;
    q[3] = 0.25 * s;
  }
  if (q[0] < 0.0)
    for (int i = 0; i < 4; i++) q[i] = -q[i];
  lsdem_quat_normalize(q);
}

/* R v without forming R: v + 2 u x (u x v + w v), u = (x, y, z). */
void lsdem_quat_rotate(const double q[4], const double v[3], double out[3])
{
  const double *u = q + 1;
  double t[3], c[3];
  lsdem_cross3(u, v, t);
  for (int i = 0; i < 3; i++) t[i] += q[0] * v[i];
  lsdem_cross3(u, t, c);
  for (int i = 0; i < 3; i++) out[i] = v[i] + 2.0 * c[i];
}

void lsdem_quat_rotate_inv(const double q[4], const double v[3], double out[3])
{
  double qc[4];
  lsdem_quat_conjugate(q, qc);
  lsdem_quat_rotate(qc, v, out);
}

void lsdem_quat_advance(double q[4], const double omega_body[3], double dt)
{
  double e[4], r[4];
  lsdem_quat_exp_half(omega_body, dt, e);
  lsdem_quat_multiply(q, e, r);
  for (int i = 0; i < 4; i++) q[i] = r[i];
  lsdem_quat_normalize(q); /* only removes round-off drift */
}

/* ------------------------------------------------------ vector rotations ---- */

/* Report eq 2.9 (the printed formula drops the leading v):
 * v_rot = v cos(theta) + (1 - cos(theta)) (k.v) k + sin(theta) k x v, k unit. */
void lsdem_rodrigues(const double v[3], const double k[3], double theta, double out[3])
{
  const double c = cos(theta), s = sin(theta);
  const double kv = lsdem_dot3(k, v);
  double kxv[3];
  lsdem_cross3(k, v, kxv);
  for (int i = 0; i < 3; i++) out[i] = v[i] * c + (1.0 - c) * kv * k[i] + s * kxv[i];
}

/* ---------------------------------------- Kawamoto/Tan quaternion convention ---- */

/* File (q0, q1, q2, q3) = Evans (q1, q2, q3, q4); eq 2.26 equals the textbook matrix of
 * (w, x, y, z) = (q3, -q1, q0, -q2) (verified entry by entry in test_rotation.c). */
void lsdem_quat_from_tan(const double qtan[4], double q[4])
{
  q[0] = qtan[3];
  q[1] = -qtan[1];
  q[2] = qtan[0];
  q[3] = -qtan[2];
}

void lsdem_quat_to_tan(const double q[4], double qtan[4])
{
  qtan[0] = q[2];
  qtan[1] = -q[1];
  qtan[2] = -q[3];
  qtan[3] = q[0];
}

/* Report eq 2.26 as printed, Evans' (q1, q2, q3, q4) = qtan[0..3]. */
void lsdem_tan_matrix_eq226(const double qtan[4], double R[9])
{
  const double q1 = qtan[0], q2 = qtan[1], q3 = qtan[2], q4 = qtan[3];
  R[0] = -q1 * q1 + q2 * q2 - q3 * q3 + q4 * q4;
  R[1] = -2.0 * (q1 * q2 - q3 * q4);
  R[2] = 2.0 * (q2 * q3 + q1 * q4);
  R[3] = -2.0 * (q1 * q2 + q3 * q4);
  R[4] = q1 * q1 - q2 * q2 - q3 * q3 + q4 * q4;
  R[5] = -2.0 * (q1 * q3 - q2 * q4);
  R[6] = 2.0 * (q2 * q3 - q1 * q4);
  R[7] = -2.0 * (q1 * q3 + q2 * q4);
  R[8] = -q1 * q1 - q2 * q2 + q3 * q3 + q4 * q4;
}

/* One Jacobi rotation in the (p, r) plane that zeroes A[p][r] (Golub & Van Loan 8.4),
 * accumulated into V's columns. */
static void jacobi_rotate(double A[9], double V[9], int p, int r)
{
  const double apr = A[3 * p + r];
  if (apr == 0.0) return;
  const double tau = (A[3 * r + r] - A[3 * p + p]) / (2.0 * apr);
  const double t = (tau >= 0.0 ? 1.0 : -1.0) / (fabs(tau) + sqrt(1.0 + tau * tau));
  const double c = 1.0 / sqrt(1.0 + t * t), s = t * c;
  for (int k = 0; k < 3; k++) { /* A <- A J (columns p, r) */
    const double akp = A[3 * k + p], akr = A[3 * k + r];
    A[3 * k + p] = c * akp - s * akr;
    A[3 * k + r] = s * akp + c * akr;
  }
  for (int k = 0; k < 3; k++) { /* A <- J^T A (rows p, r) */
    const double apk = A[3 * p + k], ark = A[3 * r + k];
    A[3 * p + k] = c * apk - s * ark;
    A[3 * r + k] = s * apk + c * ark;
  }
  A[3 * p + r] = A[3 * r + p] = 0.0;
  for (int k = 0; k < 3; k++) { /* V <- V J */
    const double vkp = V[3 * k + p], vkr = V[3 * k + r];
    V[3 * k + p] = c * vkp - s * vkr;
    V[3 * k + r] = s * vkp + c * vkr;
  }
}

static void swap_columns(double w[3], double V[9], int a, int b)
{
  double t = w[a];
  w[a] = w[b];
  w[b] = t;
  for (int k = 0; k < 3; k++) {
    t = V[3 * k + a];
    V[3 * k + a] = V[3 * k + b];
    V[3 * k + b] = t;
  }
}

/* Cyclic Jacobi: sweep the three off-diagonal pairs until they vanish relative to the
 * diagonal (quadratic convergence; a few sweeps), then sort ascending and make
 * det V = +1 by flipping the last column if needed. */
void lsdem_sym_eigen(const double A_in[9], double w[3], double V[9])
{
  double A[9];
  for (int i = 0; i < 9; i++) {
    A[i] = A_in[i];
    V[i] = (i % 4 == 0) ? 1.0 : 0.0;
  }
  A[1] = A[3] = 0.5 * (A_in[1] + A_in[3]); /* symmetrise */
  A[2] = A[6] = 0.5 * (A_in[2] + A_in[6]);
  A[5] = A[7] = 0.5 * (A_in[5] + A_in[7]);
  for (int sweep = 0; sweep < 50; sweep++) {
    const double off = A[1] * A[1] + A[2] * A[2] + A[5] * A[5];
    const double diag = A[0] * A[0] + A[4] * A[4] + A[8] * A[8];
    if (off <= 1e-36 * diag || off == 0.0) break;
    jacobi_rotate(A, V, 0, 1);
    jacobi_rotate(A, V, 0, 2);
    jacobi_rotate(A, V, 1, 2);
  }
  w[0] = A[0];
  w[1] = A[4];
  w[2] = A[8];
  if (w[0] > w[1]) swap_columns(w, V, 0, 1);
  if (w[1] > w[2]) swap_columns(w, V, 1, 2);
  if (w[0] > w[1]) swap_columns(w, V, 0, 1);
  const double det = V[0] * (V[4] * V[8] - V[5] * V[7]) - V[1] * (V[3] * V[8] - V[5] * V[6]) +
                     V[2] * (V[3] * V[7] - V[4] * V[6]);
  if (det < 0.0)
    for (int k = 0; k < 3; k++) V[3 * k + 2] = -V[3 * k + 2];
}
