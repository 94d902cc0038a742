/* test_local_strain.c -- per-grain local strain (local_strain.c): imposed affine maps on
 * random neighbour sets, rigid rotations, a non-affine set against an independent
 * least-squares solve, and singular neighbourhoods. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <math.h>

#define NB 14 /* neighbours of the random sets */

static const double PI = 3.14159265358979323846;

/* n random neighbour vectors of length 0.5..1.5 in random directions */
static void random_neighbours(int n, double *d0)
{
  for (int k = 0; k < n; k++) {
    double v[3], len;
    do {
      for (int i = 0; i < 3; i++) v[i] = srand1();
      len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    } while (len < 0.1 || len > 1.0);
    const double r = 0.5 + urand();
    for (int i = 0; i < 3; i++) d0[3 * k + i] = r * v[i] / len;
  }
}

static void apply(int n, const double F[9], const double *d0, double *d)
{
  for (int k = 0; k < n; k++)
    for (int i = 0; i < 3; i++)
      d[3 * k + i] = F[3 * i] * d0[3 * k] + F[3 * i + 1] * d0[3 * k + 1] +
                     F[3 * i + 2] * d0[3 * k + 2];
}

static double max_abs(const double A[9])
{
  double m = 0.0;
  for (int k = 0; k < 9; k++) m = fmax(m, fabs(A[k]));
  return m;
}

/* F = I + H: both strain kinds equal the tensors written out by hand, F is recovered,
 * the invariants match the values given, D2min vanishes */
static void check_affine(const char *name, const double H[9], double vol, double shear)
{
  double d0[3 * NB], d[3 * NB], F[9], eps[9], E[9];
  random_neighbours(NB, d0);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      F[3 * i + j] = (i == j) + H[3 * i + j];
      eps[3 * i + j] = 0.5 * (H[3 * i + j] + H[3 * j + i]);
      double hh = 0.0; /* (H^T H)_ij */
      for (int k = 0; k < 3; k++) hh += H[3 * k + i] * H[3 * k + j];
      E[3 * i + j] = eps[3 * i + j] + 0.5 * hh;
    }
  apply(NB, F, d0, d);
  lsdem_local_strain s, g;
  CHECK(lsdem_local_strain_fit(NB, d0, d, LSDEM_STRAIN_SMALL, &s) == LSDEM_OK, "%s", name);
  CHECK(lsdem_local_strain_fit(NB, d0, d, LSDEM_STRAIN_GREEN, &g) == LSDEM_OK, "%s", name);
  const double tol_e = 1e-10 * max_abs(eps), tol_E = 1e-10 * max_abs(E);
  for (int k = 0; k < 9; k++) {
    CHECK_NEAR(s.F[k], F[k], 1e-14);
    CHECK_NEAR(s.strain[k], eps[k], tol_e);
    CHECK_NEAR(g.strain[k], E[k], tol_E);
  }
  CHECK_NEAR(s.volumetric, vol, 1e-10 * fabs(vol) + 1e-15);
  CHECK_NEAR(s.shear, shear, 1e-10 * fabs(shear) + 1e-15);
  CHECK(s.d2min <= 1e-20 && g.d2min <= 1e-20, "%s: D2min %g %g", name, s.d2min, g.d2min);
}

static void test_affine_maps(void)
{
  const double e = 0.01;
  const double pure[9] = {e, 0, 0, 0, -e, 0, 0, 0, 0};
  const double simple[9] = {0, e, 0, 0, 0, 0, 0, 0, 0};
  const double dilation[9] = {e, 0, 0, 0, e, 0, 0, 0, e};
  /* pure shear: e' = H, sqrt(H:H / 2) = e; simple shear: eps_xy = e/2, sqrt(2 (e/2)^2 / 2) */
  check_affine("pure shear", pure, 0.0, e);
  check_affine("simple shear", simple, 0.0, 0.5 * e);
  check_affine("dilation", dilation, 3.0 * e, 0.0);
}

/* rotation by angle th about the unit axis a, as a matrix (Rodrigues) and a quaternion */
static void axis_rotation(const double a[3], double th, double R[9], double q[4])
{
  const double c = cos(th), s = sin(th);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) R[3 * i + j] = c * (i == j) + (1.0 - c) * a[i] * a[j];
  R[1] -= s * a[2], R[2] += s * a[1], R[3] += s * a[2];
  R[5] -= s * a[0], R[6] -= s * a[1], R[7] += s * a[0];
  q[0] = cos(0.5 * th);
  for (int i = 0; i < 3; i++) q[i + 1] = sin(0.5 * th) * a[i];
}

/* a rigid 30 degree turn: no Green-Lagrange strain, polar angle 30 degrees, the quaternion
 * of the turn; a grain turning with it has no relative rotation, one turning 10 degrees
 * further about the same axis has 10 */
static void test_rigid_rotation(void)
{
  const double a[3] = {2.0 / 7.0, 3.0 / 7.0, 6.0 / 7.0}, th = PI / 6.0;
  double R[9], q[4], d0[3 * NB], d[3 * NB];
  axis_rotation(a, th, R, q);
  random_neighbours(NB, d0);
  apply(NB, R, d0, d);
  lsdem_local_strain g;
  CHECK(lsdem_local_strain_fit(NB, d0, d, LSDEM_STRAIN_GREEN, &g) == LSDEM_OK, "rigid");
  CHECK(max_abs(g.strain) <= 1e-12, "Green strain of a rigid turn %g", max_abs(g.strain));
  CHECK_NEAR(g.angle, th, 1e-12);
  const double sign = g.rotation[0] < 0.0 ? -1.0 : 1.0;
  for (int k = 0; k < 4; k++) CHECK_NEAR(sign * g.rotation[k], q[k], 1e-12);
  CHECK(g.d2min <= 1e-20, "D2min %g", g.d2min);

  const double qref[4] = {0.5, 0.5, -0.5, 0.5};
  double Rx[9], qx[4], qnow[4], qmore[4];
  lsdem_quat_multiply(q, qref, qnow);
  CHECK_NEAR(lsdem_rotation_from_continuum(qnow, qref, g.rotation), 0.0, 1e-12);
  axis_rotation(a, PI / 18.0, Rx, qx);
  lsdem_quat_multiply(qx, qnow, qmore);
  CHECK_NEAR(lsdem_rotation_from_continuum(qmore, qref, g.rotation), PI / 18.0, 1e-12);

  lsdem_local_strain s;
  lsdem_local_strain_fit(NB, d0, d, LSDEM_STRAIN_SMALL, &s);
  CHECK_NEAR(s.angle, th, 1e-12);
  CHECK_NEAR(s.strain[0], R[0] - 1.0, 1e-14); /* small strain is not rotation-free */
}

/* F = R U with a stretch U: the polar decomposition returns R, Green-Lagrange (U^2 - I)/2 */
static void test_rotated_stretch(void)
{
  const double a[3] = {0.0, 0.6, 0.8}, th = PI / 6.0;
  const double U[9] = {1.02, 0.01, 0.0, 0.01, 0.99, -0.005, 0.0, -0.005, 1.0};
  double R[9], q[4], F[9], d0[3 * NB], d[3 * NB];
  axis_rotation(a, th, R, q);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      F[3 * i + j] = R[3 * i] * U[j] + R[3 * i + 1] * U[3 + j] + R[3 * i + 2] * U[6 + j];
  random_neighbours(NB, d0);
  apply(NB, F, d0, d);
  lsdem_local_strain g;
  CHECK(lsdem_local_strain_fit(NB, d0, d, LSDEM_STRAIN_GREEN, &g) == LSDEM_OK, "stretch");
  CHECK_NEAR(g.angle, th, 1e-12);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      const double uu = U[3 * i] * U[j] + U[3 * i + 1] * U[3 + j] + U[3 * i + 2] * U[6 + j];
      CHECK_NEAR(g.strain[3 * i + j], 0.5 * (uu - (i == j)), 1e-13);
    }
}

/* the least-squares F by the adjugate of Y (Cramer's rule), independent of the code's
 * eigen-decomposition; returns the sum of squared residuals */
static double residual_by_cramer(int n, const double *d0, const double *d)
{
  double X[9] = {0}, Y[9] = {0}, adj[9], F[9];
  for (int k = 0; k < n; k++)
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        X[3 * i + j] += d[3 * k + i] * d0[3 * k + j];
        Y[3 * i + j] += d0[3 * k + i] * d0[3 * k + j];
      }
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      const int r1 = (j + 1) % 3, r2 = (j + 2) % 3, c1 = (i + 1) % 3, c2 = (i + 2) % 3;
      adj[3 * i + j] = Y[3 * r1 + c1] * Y[3 * r2 + c2] - Y[3 * r1 + c2] * Y[3 * r2 + c1];
    }
  const double det = Y[0] * adj[0] + Y[1] * adj[3] + Y[2] * adj[6];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      F[3 * i + j] =
          (X[3 * i] * adj[j] + X[3 * i + 1] * adj[3 + j] + X[3 * i + 2] * adj[6 + j]) / det;
  double sum = 0.0;
  for (int k = 0; k < n; k++)
    for (int i = 0; i < 3; i++) {
      const double r = d[3 * k + i] - F[3 * i] * d0[3 * k] - F[3 * i + 1] * d0[3 * k + 1] -
                       F[3 * i + 2] * d0[3 * k + 2];
      sum += r * r;
    }
  return sum;
}

/* a non-affine set: D2min is the independent least-squares residual, and no other F does
 * better */
static void test_nonaffine(void)
{
  const double F[9] = {1.01, 0.003, 0.0, -0.002, 0.995, 0.004, 0.001, 0.0, 1.002};
  double d0[3 * NB], d[3 * NB];
  random_neighbours(NB, d0);
  apply(NB, F, d0, d);
  for (int k = 0; k < 3 * NB; k++) d[k] += 1e-3 * srand1();
  lsdem_local_strain s;
  CHECK(lsdem_local_strain_fit(NB, d0, d, LSDEM_STRAIN_SMALL, &s) == LSDEM_OK, "non-affine");
  const double expect = residual_by_cramer(NB, d0, d);
  CHECK(expect > 1e-7, "the perturbation is not affine: %g", expect);
  CHECK_REL(s.d2min, expect, 1e-9);
  for (int k = 0; k < 9; k++) {
    double dprobe[3 * NB], Fp[9];
    for (int m = 0; m < 9; m++) Fp[m] = s.F[m] + (m == k ? 1e-4 : 0.0);
    apply(NB, Fp, d0, dprobe);
    double sum = 0.0;
    for (int m = 0; m < 3 * NB; m++) sum += (d[m] - dprobe[m]) * (d[m] - dprobe[m]);
    CHECK(sum > s.d2min, "F + 1e-4 at %d fits better: %g < %g", k, sum, s.d2min);
  }
}

static void check_singular(const char *name, int n, const double *d0, const double *d)
{
  lsdem_local_strain s;
  CHECK(lsdem_local_strain_fit(n, d0, d, LSDEM_STRAIN_GREEN, &s) == LSDEM_ERR_NUMERIC, "%s", name);
  CHECK(isnan(s.F[0]) && isnan(s.strain[4]) && isnan(s.volumetric) && isnan(s.shear) &&
            isnan(s.d2min) && isnan(s.angle) && isnan(s.rotation[0]),
        "%s: outputs are NaN", name);
}

/* two neighbours, coplanar neighbours, a mirrored neighbourhood: flagged, NaN outputs */
static void test_singular(void)
{
  double d0[3 * NB], d[3 * NB];
  random_neighbours(NB, d0);
  check_singular("two neighbours", 2, d0, d0);
  for (int k = 0; k < NB; k++) d0[3 * k + 2] = 0.0;
  check_singular("coplanar", NB, d0, d0);
  random_neighbours(NB, d0);
  const double mirror[9] = {1, 0, 0, 0, 1, 0, 0, 0, -1};
  apply(NB, mirror, d0, d);
  check_singular("mirrored", NB, d0, d);
  lsdem_local_strain s;
  CHECK(lsdem_local_strain_fit(3, d0, d0, LSDEM_STRAIN_SMALL, &s) == LSDEM_OK,
        "three independent neighbours are enough");
}

int main(void)
{
  test_affine_maps();
  test_rigid_rotation();
  test_rotated_stretch();
  test_nonaffine();
  test_singular();
  return lsdem_test_summary();
}
