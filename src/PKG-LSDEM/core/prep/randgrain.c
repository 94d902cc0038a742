/* randgrain.c -- random sand-like grains: a star-shaped radius from random spherical
 * harmonics with a prescribed spectrum, an affine map to the requested Zingg ratios and
 * size, and shape statistics (see lsdem.h for the model). */
#include "lsdem_prep.h"

#include <math.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

#define NCOEF ((LSDEM_RANDGRAIN_LMAX + 1) * (LSDEM_RANDGRAIN_LMAX + 1))

/* --------------------------------------------------------- spherical harmonics ---- */

/* Normalised associated Legendre functions Q_lm = N_lm P_lm(cos theta) by the standard
 * recurrences: Q_mm = sqrt((2m+1)/(2m)) sin(theta) Q_{m-1,m-1}, Q_{m+1,m} =
 * sqrt(2m+3) cos(theta) Q_mm, Q_lm = a_lm (cos(theta) Q_{l-1,m} - Q_{l-2,m} / a_{l-1,m})
 * with a_lm = sqrt((4l^2-1)/(l^2-m^2)) (the usual b_lm is 1/a_{l-1,m}; a_{m,m} is taken as
 * infinite, so the first step has no Q_{l-2} term); the real harmonics are Q_l0 and
 * sqrt(2) Q_lm (cos m phi, sin m phi). */
static double recurrence_factor(int l, int m)
{
  return l == m ? sqrt((2.0 * m + 1.0) / (2.0 * m)) /* m > 0 */
                : sqrt((4.0 * l * l - 1.0) / ((double)(l * l - m * m)));
}

void lsdem_sph_harmonics_table(int L, double *table)
{
  for (int l = 1; l <= L; l++)
    for (int m = 0; m <= l; m++) table[l * l + l + m] = recurrence_factor(l, m);
}

void lsdem_sph_harmonics(int L, const double u[3], const double *table, double *Y)
{
  const double x = u[2], s = sqrt(u[0] * u[0] + u[1] * u[1]);
  const double cp = s > 0.0 ? u[0] / s : 1.0, sp = s > 0.0 ? u[1] / s : 0.0;
  double qmm = sqrt(1.0 / (4.0 * PI)), cm = 1.0, sm = 0.0; /* cos(m phi), sin(m phi) */
  for (int m = 0; m <= L; m++) {
    if (m > 0) {
      qmm *= (table ? table[m * m + 2 * m] : recurrence_factor(m, m)) * s;
      const double c = cm * cp - sm * sp;
      sm = sm * cp + cm * sp;
      cm = c;
    }
    const double cw = sqrt(2.0) * cm, sw = sqrt(2.0) * sm;
    double q2 = 0.0, q1 = qmm, inv_prev = 0.0; /* Q_{l-2,m}, Q_{l-1,m}, 1/a_{l-1,m} */
    for (int l = m; l <= L; l++) {
      double q = qmm;
      if (l > m) {
        const double a = table ? table[l * l + l + m] : recurrence_factor(l, m);
        q = a * (x * q1 - q2 * inv_prev);
        inv_prev = 1.0 / a;
        q2 = q1, q1 = q;
      }
      if (m == 0)
        Y[l * l + l] = q;
      else {
        Y[l * l + l + m] = q * cw;
        Y[l * l + l - m] = q * sw;
      }
    }
  }
}

/* ------------------------------------------------------------- random numbers ---- */

uint64_t lsdem_splitmix64(uint64_t *state)
{
  uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

/* Never 0, so the logarithm in normal01 is finite. */
double lsdem_uniform01(uint64_t *state)
{
  return ((double)(lsdem_splitmix64(state) >> 11) + 1.0) * (1.0 / 9007199254740992.0);
}

/* Box-Muller: one standard normal per call (the second value is not kept). */
static double normal01(uint64_t *state)
{
  const double u1 = lsdem_uniform01(state), u2 = lsdem_uniform01(state);
  return sqrt(-2.0 * log(u1)) * cos(2.0 * PI * u2);
}

/* ------------------------------------------------------------------- the grain ---- */

/* sigma_l^2 for the band [l0, l1] with RMS `rms`: per-degree variance
 * P_l = (2l+1) sigma_l^2 / (4 pi) proportional to l^-2, sum P_l = rms^2. */
static double band_sigma2(int l, int l0, int l1, double rms)
{
  double sum = 0.0;
  for (int k = l0; k <= l1; k++) sum += 1.0 / ((double)k * k);
  const double P = rms * rms / ((double)l * l) / sum;
  return P * 4.0 * PI / (2.0 * l + 1.0);
}

double lsdem_randgrain_radius(const double v[3], const void *grain)
{
  const lsdem_randgrain *g = grain;
  double w[3], Y[NCOEF];
  lsdem_mat_vec(g->Tinv, v, w);
  const double nw = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  const double u[3] = {w[0] / nw, w[1] / nw, w[2] / nw};
  lsdem_sph_harmonics(LSDEM_RANDGRAIN_LMAX, u, g->table, Y);
  double S = 0.0;
  for (int i = 4; i < NCOEF; i++) S += g->coef[i] * Y[i]; /* l >= 2 */
  return exp(S) / nw;
}

static double det3(const double A[9])
{
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
         A[2] * (A[3] * A[7] - A[4] * A[6]);
}

static void inverse3(const double A[9], double B[9])
{
  const double d = det3(A);
  B[0] = (A[4] * A[8] - A[5] * A[7]) / d;
  B[1] = (A[2] * A[7] - A[1] * A[8]) / d;
  B[2] = (A[1] * A[5] - A[2] * A[4]) / d;
  B[3] = (A[5] * A[6] - A[3] * A[8]) / d;
  B[4] = (A[0] * A[8] - A[2] * A[6]) / d;
  B[5] = (A[2] * A[3] - A[0] * A[5]) / d;
  B[6] = (A[3] * A[7] - A[4] * A[6]) / d;
  B[7] = (A[1] * A[6] - A[0] * A[7]) / d;
  B[8] = (A[0] * A[4] - A[1] * A[3]) / d;
}

/* W = Mc^(-1/2) from the inertia I of the unstretched body: I = tr(Mc) 1 - Mc, so
 * Mc = tr(I)/2 1 - I; W = V diag(lambda^-1/2) V^T. */
static int inverse_sqrt_moments(const double inertia[9], double W[9])
{
  const double half_tr = 0.5 * (inertia[0] + inertia[4] + inertia[8]);
  double Mc[9], lam[3], V[9];
  for (int k = 0; k < 9; k++) Mc[k] = (k % 4 == 0 ? half_tr : 0.0) - inertia[k];
  lsdem_sym_eigen(Mc, lam, V);
  if (!(lam[0] > 0.0)) return 0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double s = 0.0;
      for (int k = 0; k < 3; k++) s += V[3 * i + k] * V[3 * j + k] / sqrt(lam[k]);
      W[3 * i + j] = s;
    }
  return 1;
}

lsdem_status lsdem_randgrain_make(const lsdem_randgrain_params *p, lsdem_randgrain *g,
                                  lsdem_error *err)
{
  if (!p || !g) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  if (!(p->size > 0.0) || !isfinite(p->size))
    return lsdem_fail(err, LSDEM_ERR_ARG, "size %g: must be positive", p->size);
  if (!(p->elongation > 0.0 && p->elongation <= 1.0) || !(p->flatness > 0.0 && p->flatness <= 1.0))
    return lsdem_fail(err, LSDEM_ERR_ARG, "elongation %g and flatness %g must be in (0, 1]",
                      p->elongation, p->flatness);
  if (!(p->angularity >= 0.0 && p->angularity <= 1.0) ||
      !(p->roughness >= 0.0 && p->roughness <= 1.0))
    return lsdem_fail(err, LSDEM_ERR_ARG, "angularity %g and roughness %g must be in [0, 1]",
                      p->angularity, p->roughness);
  memset(g, 0, sizeof *g);
  lsdem_sph_harmonics_table(LSDEM_RANDGRAIN_LMAX, g->table);
  uint64_t rng = p->seed;
  for (int l = 2; l <= LSDEM_RANDGRAIN_LMAX; l++) {
    const int form = l <= LSDEM_RANDGRAIN_FORM_LMAX;
    const double sigma = sqrt(form ? band_sigma2(l, 2, LSDEM_RANDGRAIN_FORM_LMAX, p->angularity)
                                   : band_sigma2(l, LSDEM_RANDGRAIN_FORM_LMAX + 1,
                                                 LSDEM_RANDGRAIN_LMAX, p->roughness));
    for (int m = -l; m <= l; m++) g->coef[l * l + l + m] = sigma * normal01(&rng);
  }
  /* moments of the unstretched body rs(u) (T = identity) */
  for (int k = 0; k < 9; k++) g->T[k] = g->Tinv[k] = k % 4 == 0 ? 1.0 : 0.0;
  lsdem_massprops mp;
  lsdem_status st = lsdem_star_massprops(lsdem_randgrain_radius, g, 128, &mp, err);
  if (st != LSDEM_OK) return st;
  double W[9];
  if (!inverse_sqrt_moments(mp.inertia, W))
    return lsdem_fail(err, LSDEM_ERR_NUMERIC, "degenerate second moments of the random body");
  const double D[3] = {1.0, p->elongation, p->elongation * p->flatness};
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[3 * i + j] = D[i] * W[3 * i + j];
  const double vol = fabs(det3(T)) * mp.volume, want = PI * p->size * p->size * p->size / 6.0;
  const double k = cbrt(want / vol);
  for (int i = 0; i < 9; i++) g->T[i] = k * T[i];
  inverse3(g->T, g->Tinv);
  return LSDEM_OK;
}

lsdem_status lsdem_randgrain_grid(const lsdem_randgrain *g, double h, int margin,
                                  lsdem_grid *out, double centre[3], lsdem_error *err)
{
  if (!g || !out) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  double lo[3], hi[3], q[4];
  lsdem_grid raw;
  lsdem_massprops mp;
  lsdem_status st = lsdem_star_bounds(lsdem_randgrain_radius, g, lo, hi, err);
  if (st != LSDEM_OK) return st;
  st = lsdem_grid_from_star(lsdem_randgrain_radius, g, lo, hi, h, margin, &raw, err);
  if (st != LSDEM_OK) return st;
  st = lsdem_massprops_grid(&raw, 2, &mp, err);
  if (st == LSDEM_OK) st = lsdem_grid_to_principal(&raw, &mp, margin, out, q, err);
  if (st == LSDEM_OK && centre) {
    const double minus_c[3] = {-mp.centroid[0], -mp.centroid[1], -mp.centroid[2]};
    lsdem_quat_rotate_inv(q, minus_c, centre); /* principal = R^T (generation - centroid) */
  }
  lsdem_grid_free(&raw);
  return st;
}

void lsdem_shape_stats_compute(double volume, const double inertia[3], double area,
                               lsdem_shape_stats *st)
{
  double ax[3];
  for (int k = 0; k < 3; k++) {
    const double a2 = 5.0 * (inertia[(k + 1) % 3] + inertia[(k + 2) % 3] - inertia[k]) /
                      (2.0 * volume);
    ax[k] = sqrt(fmax(a2, 0.0));
  }
  /* sort descending: L >= I >= S */
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2 - i; j++)
      if (ax[j] < ax[j + 1]) {
        const double t = ax[j];
        ax[j] = ax[j + 1];
        ax[j + 1] = t;
      }
  memcpy(st->axes, ax, sizeof ax);
  st->d_eq = cbrt(6.0 * volume / PI);
  st->elongation = ax[1] / ax[0];
  st->flatness = ax[2] / ax[1];
  st->sphericity = area > 0.0 ? cbrt(PI) * pow(6.0 * volume, 2.0 / 3.0) / area : 0.0;
}
