/* local_strain.c -- per-grain local strain: the best-fit affine deformation of a grain's
 * neighbourhood between a reference configuration and now (Falk & Langer 1998, PRE 57,
 * 7192), for the shear-band indicators of report §3.5.3. */
#include "lsdem_specimen.h"

#include "../base/lsdem_vec3.h"

#include <math.h>

/* Y is treated as singular when its smallest eigenvalue is below this fraction of its
 * largest: the neighbours then (nearly) lie in a plane or on a line, and F's component
 * normal to it is undetermined (round-off would amplify by 1 / LOCAL_STRAIN_RCOND). */
#define LOCAL_STRAIN_RCOND 1e-10

/* S = V diag(f) V^T, V's columns the eigenvectors */
static void eigen_compose(const double V[9], const double f[3], double S[9])
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      S[3 * i + j] = V[3 * i] * f[0] * V[3 * j] + V[3 * i + 1] * f[1] * V[3 * j + 1] +
                     V[3 * i + 2] * f[2] * V[3 * j + 2];
}

/* det F as the triple product of its rows */
static double determinant(const double F[9])
{
  double c[3];
  lsdem_cross3(F + 3, F + 6, c);
  return lsdem_dot3(F, c);
}

/* Y^-1 from the sum of d0 d0^T; 0 when Y is singular (fewer than 3 independent d0) */
static int inverse_moment(int n, const double *d0, double Yinv[9])
{
  double Y[9] = {0.0}, w[3], V[9];
  for (int k = 0; k < n; k++)
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) Y[3 * i + j] += d0[3 * k + i] * d0[3 * k + j];
  lsdem_sym_eigen(Y, w, V);
  if (!(w[0] > LOCAL_STRAIN_RCOND * w[2])) return 0;
  const double inv[3] = {1.0 / w[0], 1.0 / w[1], 1.0 / w[2]};
  eigen_compose(V, inv, Yinv);
  return 1;
}

/* F = X Y^-1, X = sum d d0^T */
static void best_fit_gradient(int n, const double *d0, const double *d, const double Yinv[9],
                              double F[9])
{
  double X[9] = {0.0};
  for (int k = 0; k < n; k++)
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) X[3 * i + j] += d[3 * k + i] * d0[3 * k + j];
  lsdem_mat_mul(X, Yinv, F);
}

/* sum_k |d_k - F d0_k|^2, each residual formed before it is squared (exact-affine sets give
 * round-off squared, ~1e-32 |d|^2, not the cancellation of an expanded quadratic form) */
static double nonaffine_residual(int n, const double *d0, const double *d, const double F[9])
{
  double sum = 0.0;
  for (int k = 0; k < n; k++) {
    double r[3];
    lsdem_mat_vec(F, d0 + 3 * k, r);
    lsdem_sub3(d + 3 * k, r, r);
    sum += lsdem_dot3(r, r);
  }
  return sum;
}

/* R of the polar decomposition F = R U, U = sqrt(F^T F) (det F > 0) */
static void polar_rotation(const double F[9], const double C[9], double R[9])
{
  double c[3], Q[9], Uinv[9];
  lsdem_sym_eigen(C, c, Q);
  const double f[3] = {1.0 / sqrt(c[0]), 1.0 / sqrt(c[1]), 1.0 / sqrt(c[2])};
  eigen_compose(Q, f, Uinv);
  lsdem_mat_mul(F, Uinv, R);
}

/* von Mises shear invariant sqrt(e':e' / 2), e' = e - tr(e) I / 3 */
static double shear_invariant(const double e[9], double trace)
{
  double s = 0.0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      const double dev = e[3 * i + j] - (i == j ? trace / 3.0 : 0.0);
      s += dev * dev;
    }
  return sqrt(0.5 * s);
}

static void fill_nan(lsdem_local_strain *out)
{
  double *fields[] = {out->F, out->strain, out->rotation};
  const int len[] = {9, 9, 4};
  for (int f = 0; f < 3; f++)
    for (int k = 0; k < len[f]; k++) fields[f][k] = NAN;
  out->volumetric = out->shear = out->d2min = out->angle = NAN;
}

lsdem_status lsdem_strain_measures(const double F[9], lsdem_strain_kind kind,
                                   lsdem_local_strain *out)
{
  double C[9], R[9];
  if (!(determinant(F) > 0.0)) {
    fill_nan(out);
    return LSDEM_ERR_NUMERIC;
  }
  if (out->F != F)
    for (int k = 0; k < 9; k++) out->F[k] = F[k];
  lsdem_matT_mul(F, F, C);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      const double delta = i == j ? 1.0 : 0.0;
      out->strain[3 * i + j] = kind == LSDEM_STRAIN_GREEN
                                   ? 0.5 * (C[3 * i + j] - delta)
                                   : 0.5 * (F[3 * i + j] + F[3 * j + i]) - delta;
    }
  out->volumetric = out->strain[0] + out->strain[4] + out->strain[8];
  out->shear = shear_invariant(out->strain, out->volumetric);
  polar_rotation(F, C, R);
  lsdem_matrix_to_quat(R, out->rotation);
  const double identity[4] = {1.0, 0.0, 0.0, 0.0};
  out->angle = lsdem_rotation_angle(out->rotation, identity);
  return LSDEM_OK;
}

lsdem_status lsdem_local_strain_fit(int n, const double *d0, const double *d,
                                    lsdem_strain_kind kind, lsdem_local_strain *out)
{
  double Yinv[9];
  if (n < 3 || !inverse_moment(n, d0, Yinv)) {
    fill_nan(out);
    return LSDEM_ERR_NUMERIC;
  }
  best_fit_gradient(n, d0, d, Yinv, out->F);
  const lsdem_status s = lsdem_strain_measures(out->F, kind, out);
  if (s == LSDEM_OK) out->d2min = nonaffine_residual(n, d0, d, out->F);
  return s;
}

double lsdem_rotation_from_continuum(const double q[4], const double qref[4],
                                     const double qcont[4])
{
  double c[4], dq[4];
  lsdem_quat_conjugate(qref, c);
  lsdem_quat_multiply(q, c, dq);
  return lsdem_rotation_angle(dq, qcont);
}
