/* test_measure.c -- specimen measurements (measure.c) against hand-computable cases. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <math.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* Two grains pressed together by equal and opposite forces F along their branch vector l:
 * sigma = F l (x) l / (|l| V), whatever the contact point. */
static void test_two_grains(void)
{
  const double xa[3] = {0.1, -0.2, 0.3}, xb[3] = {1.1, 0.8, 0.3};
  const double l[3] = {xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]};
  const double len = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
  const double F = 2.5, V = 7.0;
  const double fa[3] = {-F * l[0] / len, -F * l[1] / len, -F * l[2] / len}; /* pushed from B */
  const double fb[3] = {-fa[0], -fa[1], -fa[2]};
  const double xc[3] = {0.4, 0.1, 0.35}; /* off the branch line: must not matter */
  double M[9] = {0}, sigma[9];
  lsdem_love_weber_add(M, fa, xc, xa);
  lsdem_love_weber_add(M, fb, xc, xb);
  lsdem_love_weber_stress(M, V, sigma);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      CHECK_NEAR(sigma[3 * i + j], F * l[i] * l[j] / (len * V), 1e-14);
  CHECK(sigma[0] > 0.0, "compression is positive: sxx = %g", sigma[0]);
  /* the branch is along (1,1,0)/sqrt2: principal stresses F len / V, 0, 0 */
  double s[3];
  lsdem_stress_principal(sigma, s);
  CHECK_NEAR(s[0], F * len / V, 1e-12);
  CHECK_NEAR(s[1], 0.0, 1e-12);
  CHECK_NEAR(s[2], 0.0, 1e-12);
}

/* One grain of height 2r between two platens in a cell of cross-section A: the platen
 * force over the area, F / A, is the axial stress (boundary contacts enter once). */
static void test_platen_contacts(void)
{
  const double xg[3] = {3.0, 4.0, 5.0}, r = 0.8, F = 12.0, A = 2.0;
  const double top[3] = {3.1, 4.2, 5.0 + r}, bottom[3] = {3.1, 4.2, 5.0 - r}; /* one line */
  const double ftop[3] = {0.0, 0.0, -F}, fbottom[3] = {0.0, 0.0, F};
  double M[9] = {0}, sigma[9];
  lsdem_love_weber_add(M, ftop, top, xg);
  lsdem_love_weber_add(M, fbottom, bottom, xg);
  lsdem_love_weber_stress(M, A * 2.0 * r, sigma);
  CHECK_NEAR(sigma[8], F / A, 1e-12);
  for (int k = 0; k < 8; k++) CHECK_NEAR(sigma[k], 0.0, 1e-12);
}

/* R d R^T for a diagonal tensor d (row-major 3x3), R the rotation of 0.6 rad about (1,2,2)/3 */
static void rotated(const double d[9], double out[9])
{
  double R[9];
  const double q[4] = {cos(0.3), sin(0.3) / 3.0, 2.0 * sin(0.3) / 3.0, 2.0 * sin(0.3) / 3.0};
  lsdem_quat_to_matrix(q, R);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      out[3 * i + j] = 0.0;
      for (int k = 0; k < 3; k++) out[3 * i + j] += R[3 * i + k] * d[4 * k] * R[3 * j + k];
    }
}

static void test_invariants(void)
{
  /* hydrostatic: q = 0, friction angle 0 */
  const double hyd[9] = {3, 0, 0, 0, 3, 0, 0, 0, 3};
  double s[3];
  CHECK_NEAR(lsdem_stress_mean(hyd), 3.0, 1e-15);
  CHECK_NEAR(lsdem_stress_deviatoric(hyd), 0.0, 1e-15);
  lsdem_stress_principal(hyd, s);
  CHECK_NEAR(lsdem_friction_angle(s[0], s[2]), 0.0, 1e-15);

  /* triaxial compression sigma_1 = 3 (axial z), sigma_3 = 1: p = 5/3, q = 2, sin phi = 1/2 */
  const double tri[9] = {1, 0, 0, 0, 1, 0, 0, 0, 3};
  CHECK_NEAR(lsdem_stress_mean(tri), 5.0 / 3.0, 1e-15);
  CHECK_NEAR(lsdem_stress_deviatoric(tri), 2.0, 1e-14);
  /* the same state in a rotated frame */
  double rot[9];
  rotated(tri, rot);
  lsdem_stress_principal(rot, s);
  CHECK_NEAR(s[0], 3.0, 1e-12);
  CHECK_NEAR(s[1], 1.0, 1e-12);
  CHECK_NEAR(s[2], 1.0, 1e-12);
  CHECK_NEAR(lsdem_stress_deviatoric(rot), 2.0, 1e-12);
  CHECK_NEAR(lsdem_friction_angle(s[0], s[2]), PI / 6.0, 1e-12);
  /* sigma_1 / sigma_3 = 6 gives 45.58 deg (the report: "6 times the confining pressure") */
  CHECK_NEAR(lsdem_friction_angle(6.0, 1.0) * 180.0 / PI, 45.584, 1e-3);
  /* 45 deg exactly where sigma_1 / sigma_3 = (1 + sin 45)/(1 - sin 45) = 3 + 2 sqrt 2 = 5.83,
   * also from the principal stresses of that state in the rotated frame (issue 35's check) */
  const double r45 = 3.0 + 2.0 * sqrt(2.0);
  const double s45[9] = {1, 0, 0, 0, 1, 0, 0, 0, r45};
  rotated(s45, rot);
  lsdem_stress_principal(rot, s);
  CHECK_NEAR(lsdem_friction_angle(s[0], s[2]), PI / 4.0, 1e-12);
  CHECK_NEAR(lsdem_friction_angle(r45, 1.0), PI / 4.0, 1e-15);
  /* the ratio rounded to 5.83: 45.005 deg */
  CHECK_NEAR(lsdem_friction_angle(5.83, 1.0) * 180.0 / PI, 45.0055, 1e-4);
  CHECK_NEAR(lsdem_friction_angle(1.0, -1.0), 0.0, 0.0); /* tension: undefined, 0 */
}

static void test_dilatancy_inertial(void)
{
  /* isochoric shearing: psi = 0; eps_v = -eps_a (dilation): sin psi = 1/3;
   * no lateral strain (eps_v = eps_a, pure compaction): sin psi = -1 */
  CHECK_NEAR(lsdem_dilatancy_angle(0.0, 0.01), 0.0, 1e-15);
  CHECK_NEAR(sin(lsdem_dilatancy_angle(-0.01, 0.01)), 1.0 / 3.0, 1e-14);
  CHECK_NEAR(lsdem_dilatancy_angle(0.02, 0.02), -PI / 2.0, 1e-12);
  /* stronger contraction (the radius shrinks too) stays at -90, never flips sign */
  CHECK_NEAR(lsdem_dilatancy_angle(0.05, 0.01), -PI / 2.0, 1e-12);
  CHECK_NEAR(lsdem_dilatancy_angle(0.02, 0.01), -PI / 2.0, 1e-12);
  /* strong dilation tends to +90: x = -100 gives sin psi = 100/102 */
  CHECK_NEAR(sin(lsdem_dilatancy_angle(-1.0, 0.01)), 100.0 / 102.0, 1e-12);
  /* report eq 3.5 with its numbers: 1%/s, d = 0.5 mm, 100 kPa, 2650 kg/m^3 */
  CHECK_REL(lsdem_inertial_number(0.01, 5e-4, 1e5, 2650.0), 0.01 * 5e-4 / sqrt(1e5 / 2650.0),
            1e-14);
  CHECK_NEAR(lsdem_inertial_number(0.01, 5e-4, 1e5, 2650.0), 8.14e-7, 1e-9);
}

static void test_fabric(void)
{
  double F[9] = {0}, D[9];
  /* isotropic: the six faces' normals of a cube */
  const double axes[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int k = 0; k < 6; k++) lsdem_fabric_add(F, axes[k]);
  lsdem_fabric_deviator(F, 6.0, D);
  for (int k = 0; k < 9; k++) CHECK_NEAR(D[k], 0.0, 1e-15);
  CHECK_NEAR(lsdem_fabric_anisotropy(D), 0.0, 1e-15);

  /* grains whose smallest moment is about body x, all turned so body x points along z:
   * F/N = diag(0, 0, 1), D = 15/2 diag(-1/3, -1/3, 2/3), a = sqrt(3/2 * 75/2) = 15/2 */
  memset(F, 0, sizeof F);
  const double inertia[3] = {1.0, 4.0, 5.0};
  const double s = sqrt(0.5);
  const double qs[3][4] = {{s, 0.0, -s, 0.0},   /* x -> z (about y by -90 deg) */
                           {0.5, 0.5, -0.5, 0.5},
                           {0.5, -0.5, -0.5, -0.5}};
  for (int g = 0; g < 3; g++) {
    double n[3];
    lsdem_long_axis(qs[g], inertia, n);
    CHECK_NEAR(fabs(n[2]), 1.0, 1e-14);
    lsdem_fabric_add(F, n);
  }
  lsdem_fabric_deviator(F, 3.0, D);
  CHECK_NEAR(D[0], -2.5, 1e-13);
  CHECK_NEAR(D[4], -2.5, 1e-13);
  CHECK_NEAR(D[8], 5.0, 1e-13);
  CHECK_NEAR(lsdem_fabric_anisotropy(D), 7.5, 1e-13);

  /* the long axis follows the smallest moment wherever it is */
  const double ident[4] = {1, 0, 0, 0}, iz[3] = {5.0, 5.0, 1.0};
  double n[3];
  lsdem_long_axis(ident, iz, n);
  CHECK(n[0] == 0.0 && n[1] == 0.0 && n[2] == 1.0, "long axis %g %g %g", n[0], n[1], n[2]);
}

static void test_rotation_angle(void)
{
  const double qref[4] = {0.5, 0.5, 0.5, 0.5};
  const double th = 0.7, k[3] = {0.0, 0.6, 0.8};
  const double dq[4] = {cos(th / 2), sin(th / 2) * k[0], sin(th / 2) * k[1], sin(th / 2) * k[2]};
  double q[4], qneg[4];
  lsdem_quat_multiply(dq, qref, q);
  CHECK_NEAR(lsdem_rotation_angle(q, qref), th, 1e-13);
  CHECK_NEAR(lsdem_rotation_angle(qref, qref), 0.0, 1e-15);
  for (int d = 0; d < 4; d++) qneg[d] = -q[d]; /* same rotation */
  CHECK_NEAR(lsdem_rotation_angle(qneg, qref), th, 1e-13);
}

int main(void)
{
  test_two_grains();
  test_platen_contacts();
  test_invariants();
  test_dilatancy_inertial();
  test_fabric();
  test_rotation_angle();
  return lsdem_test_summary();
}
