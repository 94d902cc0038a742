/* measure.c -- measurements of a granular specimen (report §3.3.1, §3.5): Love-Weber
 * average stress (eq 3.6), p and q (eqs 3.7-3.8), principal stresses and the mobilised
 * friction angle (eq 3.9), dilatancy angle (eq 3.10), inertial number (eq 3.5), the fabric
 * of grain long axes (§3.5.4) and grain rotation angles (§3.5.3).
 *
 * Sign convention (soil mechanics): stresses and strains are COMPRESSION POSITIVE. */
#include "lsdem_specimen.h"

#include <math.h>
#include <stdlib.h>

static double sym_contract(const double A[9], const double B[9])
{
  double s = 0.0;
  for (int k = 0; k < 9; k++) s += A[k] * B[k];
  return s;
}

/* Report eq 3.6 in its per-grain form: one contact's moment f (x) (x_c - x_grain). */
void lsdem_love_weber_add(double M[9], const double f[3], const double point[3],
                          const double centre[3])
{
  const double r[3] = {point[0] - centre[0], point[1] - centre[1], point[2] - centre[2]};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) M[3 * i + j] += f[i] * r[j];
}

/* sigma = -sym(M) / V: contact forces push grains apart, so a compressed assembly has
 * f . r < 0 and a positive (compressive) stress. */
void lsdem_love_weber_stress(const double M[9], double volume, double sigma[9])
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) sigma[3 * i + j] = -0.5 * (M[3 * i + j] + M[3 * j + i]) / volume;
}

/* Report eq 3.7: p = tr(sigma) / 3. */
double lsdem_stress_mean(const double sigma[9])
{
  return (sigma[0] + sigma[4] + sigma[8]) / 3.0;
}

/* Report eq 3.8: q = sqrt(3/2 s:s), s = sigma - p I. */
double lsdem_stress_deviatoric(const double sigma[9])
{
  const double p = lsdem_stress_mean(sigma);
  double s[9];
  for (int k = 0; k < 9; k++) s[k] = sigma[k] - (k % 4 == 0 ? p : 0.0);
  return sqrt(1.5 * sym_contract(s, s));
}

void lsdem_sym_to_voigt(const double T[9], double out[6])
{
  out[0] = T[0];
  out[1] = T[4];
  out[2] = T[8];
  out[3] = T[1];
  out[4] = T[2];
  out[5] = T[5];
}

void lsdem_stress_principal(const double sigma[9], double s[3])
{
  double w[3], V[9];
  lsdem_sym_eigen(sigma, w, V);
  s[0] = w[2];
  s[1] = w[1];
  s[2] = w[0];
}

/* Report eq 3.9: sin(phi) = (s1 - s3) / (s1 + s3). */
double lsdem_friction_angle(double s1, double s3)
{
  if (!(s1 + s3 > 0.0)) return 0.0;
  double r = (s1 - s3) / (s1 + s3);
  if (r > 1.0) r = 1.0;
  if (r < -1.0) r = -1.0;
  return asin(r);
}

/* Report eq 3.10 (Schanz & Vermeer 1996, triaxial compression), compression positive:
 * sin(psi) = -x / (2 - x), x = d eps_v / d eps_a; psi > 0 when the specimen dilates.
 * x >= 1 means the radius shrinks too (not triaxial-compression kinematics; the formula
 * would pass -1 and blow up at x = 2): -90 degrees, the value at x = 1. */
double lsdem_dilatancy_angle(double deps_v, double deps_a)
{
  if (deps_a == 0.0) return 0.0;
  const double x = deps_v / deps_a;
  if (x >= 1.0) return -asin(1.0);
  return asin(-x / (2.0 - x));
}

/* Report eq 3.5: I = strain_rate d / sqrt(pressure / density). */
double lsdem_inertial_number(double strain_rate, double d, double pressure, double density)
{
  if (!(pressure > 0.0) || !(density > 0.0)) return HUGE_VAL;
  return fabs(strain_rate) * d / sqrt(pressure / density);
}

/* The long axis: the principal axis of the smallest principal moment, in the world frame
 * (column k of R(q)). Its sign is arbitrary (fabric uses n (x) n). */
void lsdem_long_axis(const double q[4], const double inertia[3], double n[3])
{
  int k = 0;
  if (inertia[1] < inertia[k]) k = 1;
  if (inertia[2] < inertia[k]) k = 2;
  double e[3] = {0.0, 0.0, 0.0};
  e[k] = 1.0;
  lsdem_quat_rotate(q, e, n);
}

void lsdem_fabric_add(double F[9], const double n[3])
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) F[3 * i + j] += n[i] * n[j];
}

/* Deviatoric fabric of the second kind (Kanatani 1984): D = 15/2 (F/count - I/3), so the
 * orientation density is E(n) = (1 + D : n n) / (4 pi) to second order. */
void lsdem_fabric_deviator(const double F[9], double count, double D[9])
{
  for (int k = 0; k < 9; k++) {
    const double mean = count > 0.0 ? F[k] / count : 0.0;
    D[k] = count > 0.0 ? 7.5 * (mean - (k % 4 == 0 ? 1.0 / 3.0 : 0.0)) : 0.0;
  }
}

/* Anisotropy factor a = sqrt(3/2 D : D) (e.g. Zhao & Guo 2013, Wiebicke et al. 2020). */
double lsdem_fabric_anisotropy(const double D[9])
{
  return sqrt(1.5 * sym_contract(D, D));
}

/* Angle of the rotation q qref^-1 (world frame) in [0, pi]. */
double lsdem_rotation_angle(const double q[4], const double qref[4])
{
  double c[4], d[4];
  lsdem_quat_conjugate(qref, c);
  lsdem_quat_multiply(q, c, d);
  const double vlen = sqrt(d[1] * d[1] + d[2] * d[2] + d[3] * d[3]);
  return 2.0 * atan2(vlen, fabs(d[0]));
}

static int compare_doubles(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

double lsdem_median_diameter(int n, const double *volume)
{
  if (n <= 0) return 0.0;
  double *v = malloc(sizeof(double) * (size_t)n);
  if (!v) return NAN;
  double total = 0.0;
  for (int i = 0; i < n; i++) total += (v[i] = volume[i] > 0.0 ? volume[i] : 0.0);
  qsort(v, (size_t)n, sizeof(double), compare_doubles); /* by volume = by diameter */
  /* the sieve curve: grain i's diameter at the middle of its share of the volume; the last
   * grain's point is at 1 - v/(2 total) >= 0.5, so the curve crosses 0.5 when total > 0 */
  double below = 0.0, prev_f = -1.0, prev_d = 0.0, d50 = 0.0;
  for (int i = 0; i < n; i++) {
    if (v[i] == 0.0) continue;
    const double d = cbrt(6.0 * v[i] / 3.14159265358979323846);
    const double f = (below + 0.5 * v[i]) / total;
    below += v[i];
    if (f >= 0.5) {
      d50 = prev_f < 0.0 ? d : prev_d + (d - prev_d) * (0.5 - prev_f) / (f - prev_f);
      break;
    }
    prev_f = f;
    prev_d = d;
  }
  free(v);
  return d50;
}
