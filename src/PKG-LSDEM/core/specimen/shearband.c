/* shearband.c -- shear-band measurement (report §3.5.3): points flagged by an indicator above
 * mean + k sd, up to two planes fitted to them robustly (RANSAC, then a least-squares
 * refit), each plane's dip, azimuth, inlier fraction and thickness; the Coulomb, Roscoe and
 * Arthur inclinations. Conventions in lsdem_specimen.h. */
#include "lsdem_specimen.h"

#include "../base/lsdem_vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SHEARBAND_REFITS 20 /* least-squares refits at most (usually 2-3 suffice) */

static const double DEG = 180.0 / 3.14159265358979323846;

/* the flagged points (value > mean + k sd over the finite values), ascending, into idx;
 * their count */
static int flag_points(int n, const double *value, double k, int *idx)
{
  double sum = 0.0, ss = 0.0;
  int nfinite = 0, m = 0;
  for (int i = 0; i < n; i++)
    if (isfinite(value[i])) {
      sum += value[i];
      nfinite++;
    }
  if (nfinite == 0) return 0;
  const double mean = sum / nfinite;
  for (int i = 0; i < n; i++)
    if (isfinite(value[i])) ss += (value[i] - mean) * (value[i] - mean);
  const double cut = mean + k * sqrt(ss / nfinite);
  for (int i = 0; i < n; i++)
    if (isfinite(value[i]) && value[i] > cut) idx[m++] = i;
  return m;
}

/* a sample index in [0, m) from a 64-bit LCG (Knuth's MMIX constants), high bits */
static int lcg_index(uint64_t *state, int m)
{
  *state = *state * 6364136223846793005ull + 1442695040888963407ull;
  return (int) ((*state >> 33) % (uint64_t) m);
}

/* unit normal of the plane through a, b, c; 0 when they are (nearly) on one line */
static int plane_through(const double *a, const double *b, const double *c, double normal[3])
{
  double ab[3], ac[3];
  lsdem_sub3(b, a, ab);
  lsdem_sub3(c, a, ac);
  lsdem_cross3(ab, ac, normal);
  const double nn = lsdem_dot3(normal, normal);
  if (!(nn > 1e-24 * lsdem_dot3(ab, ab) * lsdem_dot3(ac, ac))) return 0;
  for (int r = 0; r < 3; r++) normal[r] /= sqrt(nn);
  return 1;
}

static double signed_distance(const double *x, const double centre[3], const double normal[3])
{
  double d[3];
  lsdem_sub3(x, centre, d);
  return lsdem_dot3(d, normal);
}

/* mask[j] = 1 for the candidates within threshold of the plane; their count */
static int select_inliers(int m, const int *cand, const double *x, const double centre[3],
                          const double normal[3], double threshold, unsigned char *mask)
{
  int count = 0;
  for (int j = 0; j < m; j++) {
    mask[j] = fabs(signed_distance(x + 3 * cand[j], centre, normal)) <= threshold;
    count += mask[j];
  }
  return count;
}

/* RANSAC: the plane through 3 sampled candidates with most candidates within threshold;
 * 0 when every sample was degenerate */
static int ransac_plane(int m, const int *cand, const double *x, const lsdem_shearband_params *p,
                        uint64_t *rng, unsigned char *mask, double centre[3], double normal[3])
{
  int best = 0;
  for (int s = 0; s < p->samples; s++) {
    const double *a = x + 3 * cand[lcg_index(rng, m)];
    const double *b = x + 3 * cand[lcg_index(rng, m)];
    const double *c = x + 3 * cand[lcg_index(rng, m)];
    double n[3];
    if (!plane_through(a, b, c, n)) continue;
    const int count = select_inliers(m, cand, x, a, n, p->threshold, mask);
    if (count > best) {
      best = count;
      memcpy(centre, a, sizeof(double) * 3);
      memcpy(normal, n, sizeof(double) * 3);
    }
  }
  return best;
}

/* least squares: the masked candidates' centroid and the smallest-eigenvalue eigenvector of
 * their covariance */
static void pca_plane(int m, const int *cand, const double *x, const unsigned char *mask,
                      double centre[3], double normal[3])
{
  double C[9] = {0.0}, w[3], V[9];
  int count = 0;
  centre[0] = centre[1] = centre[2] = 0.0;
  for (int j = 0; j < m; j++)
    if (mask[j]) {
      for (int r = 0; r < 3; r++) centre[r] += x[3 * cand[j] + r];
      count++;
    }
  for (int r = 0; r < 3; r++) centre[r] /= count;
  for (int j = 0; j < m; j++)
    if (mask[j]) {
      double d[3];
      lsdem_sub3(x + 3 * cand[j], centre, d);
      for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) C[3 * r + c] += d[r] * d[c];
    }
  lsdem_sym_eigen(C, w, V);
  for (int r = 0; r < 3; r++) normal[r] = V[3 * r];
}

/* the RANSAC inliers (mask) refitted by least squares and re-selected until stable; the
 * plane is always the fit of the final mask; the inlier count */
static int refine_plane(int m, const int *cand, const double *x, double threshold,
                        unsigned char *mask, unsigned char *trial, double centre[3],
                        double normal[3])
{
  int count = 0;
  for (int j = 0; j < m; j++) count += mask[j];
  pca_plane(m, cand, x, mask, centre, normal);
  for (int it = 0; it < SHEARBAND_REFITS; it++) {
    const int now = select_inliers(m, cand, x, centre, normal, threshold, trial);
    if (now < 3 || memcmp(trial, mask, (size_t) m) == 0) break;
    memcpy(mask, trial, (size_t) m);
    count = now;
    pca_plane(m, cand, x, mask, centre, normal);
  }
  return count;
}

/* the normal up (n_z > 0; horizontal: first nonzero of n_x, n_y positive) */
static void orient_up(double n[3])
{
  const int flip = n[2] != 0.0 ? n[2] < 0.0 : (n[0] != 0.0 ? n[0] < 0.0 : n[1] < 0.0);
  if (flip)
    for (int r = 0; r < 3; r++) n[r] = -n[r];
}

/* sqrt(12) x the rms signed distance of the masked candidates (the plane passes through
 * their centroid, so the mean distance is zero) */
static double slab_thickness(int m, const int *cand, const double *x, const unsigned char *mask,
                             int count, const double centre[3], const double normal[3])
{
  double ss = 0.0;
  for (int j = 0; j < m; j++)
    if (mask[j]) {
      const double d = signed_distance(x + 3 * cand[j], centre, normal);
      ss += d * d;
    }
  return sqrt(12.0 * ss / count);
}

static void plane_angles(lsdem_shearband_plane *pl)
{
  const double *n = pl->normal;
  pl->dip = DEG * acos(fmin(1.0, n[2]));
  const double az = (n[0] == 0.0 && n[1] == 0.0) ? 0.0 : DEG * atan2(n[1], n[0]);
  pl->azimuth = az < 0.0 ? az + 360.0 : az;
}

/* one plane fitted to the m candidates; mask marks its inliers; 0 when none was found */
static int fit_one_plane(int m, const int *cand, const double *x, const lsdem_shearband_params *p,
                         int nflagged, uint64_t *rng, unsigned char *mask, unsigned char *trial,
                         lsdem_shearband_plane *pl)
{
  if (m < 3 || ransac_plane(m, cand, x, p, rng, trial, pl->centre, pl->normal) < 3) return 0;
  select_inliers(m, cand, x, pl->centre, pl->normal, p->threshold, mask);
  pl->ninliers = refine_plane(m, cand, x, p->threshold, mask, trial, pl->centre, pl->normal);
  orient_up(pl->normal);
  plane_angles(pl);
  pl->inlier_fraction = (double) pl->ninliers / nflagged;
  pl->thickness = slab_thickness(m, cand, x, mask, pl->ninliers, pl->centre, pl->normal);
  return 1;
}

/* the candidates not masked, in order, to the front of cand; their count */
static int drop_inliers(int m, int *cand, const unsigned char *mask)
{
  int left = 0;
  for (int j = 0; j < m; j++)
    if (!mask[j]) cand[left++] = cand[j];
  return left;
}

/* band[i]: the first plane within half its thickness of point i, else 0 */
static void classify_points(int n, const double *x, int nplanes,
                            const lsdem_shearband_plane *plane, int *band)
{
  for (int i = 0; i < n; i++) {
    band[i] = 0;
    for (int q = nplanes - 1; q >= 0; q--)
      if (fabs(signed_distance(x + 3 * i, plane[q].centre, plane[q].normal)) <=
          0.5 * plane[q].thickness)
        band[i] = q + 1;
  }
}

lsdem_status lsdem_shearband_fit(int n, const double *x, const double *value,
                                 const lsdem_shearband_params *p, lsdem_shearband_plane plane[2],
                                 int *nplanes, int *band)
{
  if (n < 0 || (n > 0 && (!x || !value || !band)) || !p || !plane || !nplanes ||
      !(p->planes == 1 || p->planes == 2) || !(p->threshold > 0.0) || !isfinite(p->k) ||
      p->samples <= 0)
    return LSDEM_ERR_ARG;
  *nplanes = 0;
  const size_t cap = n > 0 ? (size_t) n : 1;
  int *cand = malloc(sizeof(int) * cap);
  unsigned char *mask = malloc(cap), *trial = malloc(cap);
  if (!cand || !mask || !trial) {
    free(cand);
    free(mask);
    free(trial);
    return LSDEM_ERR_NOMEM;
  }
  const int nflagged = flag_points(n, value, p->k, cand);
  uint64_t rng = p->seed;
  int m = nflagged;
  while (*nplanes < p->planes &&
         fit_one_plane(m, cand, x, p, nflagged, &rng, mask, trial, &plane[*nplanes])) {
    m = drop_inliers(m, cand, mask);
    (*nplanes)++;
  }
  classify_points(n, x, *nplanes, plane, band);
  free(cand);
  free(mask);
  free(trial);
  return LSDEM_OK;
}

void lsdem_shearband_theory(double phi, double psi, double angle[3])
{
  angle[0] = 45.0 + 0.5 * phi;
  angle[1] = 45.0 + 0.5 * psi;
  angle[2] = 45.0 + 0.25 * (phi + psi);
}

static int compare_values(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* where the profile (bin means m over bins [0, nb), centres at (k - centre) bin, empty
 * bins cnt 0) first falls below half, walking from bin `peak` in direction `step`:
 * interpolated between the last bin above and the first below; NaN when it never does */
static double half_crossing(const double *m, const int *cnt, int nb, int peak, int step,
                            double half, int centre, double bin)
{
  int last = peak;
  for (int k = peak + step; k >= 0 && k < nb; k += step) {
    if (cnt[k] == 0) continue;
    if (m[k] < half) {
      const double t = (m[last] - half) / (m[last] - m[k]);
      return bin * ((double)(last - centre) + t * (double)(k - last));
    }
    last = k;
  }
  return NAN;
}

lsdem_status lsdem_shearband_profile(int n, const double *x, const double *value,
                                     const lsdem_shearband_plane *plane, double bin,
                                     double reach, double kernel, double *fwhm,
                                     double *corrected)
{
  if (n < 0 || !plane || !fwhm || !corrected || !(bin > 0.0) || !(reach > 0.0) ||
      !(kernel >= 0.0) || (n > 0 && (!x || !value)))
    return LSDEM_ERR_ARG;
  *fwhm = *corrected = NAN;
  double *vals = malloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
  double *s = malloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
  if (!vals || !s) {
    free(vals);
    free(s);
    return LSDEM_ERR_NOMEM;
  }
  int nf = 0;
  double smax = 0.0;
  for (int i = 0; i < n; i++) {
    if (!isfinite(value[i])) continue;
    double d[3];
    lsdem_sub3(&x[3 * i], plane->centre, d);
    s[nf] = lsdem_dot3(d, plane->normal);
    vals[nf++] = value[i];
    smax = fmax(smax, fabs(s[nf - 1]));
  }
  /* bins k = 0..nb-1 centred at (k - centre) bin: one on the plane */
  const int centre = (int)ceil(smax / bin - 0.5), nb = 2 * centre + 1;
  double *m = calloc((size_t)nb, sizeof(double));
  int *cnt = calloc((size_t)nb, sizeof(int));
  if (!m || !cnt) {
    free(vals);
    free(s);
    free(m);
    free(cnt);
    return LSDEM_ERR_NOMEM;
  }
  for (int i = 0; i < nf; i++) {
    int k = centre + (int)floor(s[i] / bin + 0.5);
    k = k < 0 ? 0 : (k >= nb ? nb - 1 : k);
    m[k] += vals[i];
    cnt[k]++;
  }
  for (int k = 0; k < nb; k++)
    if (cnt[k]) m[k] /= cnt[k];
  qsort(vals, (size_t)nf, sizeof(double), compare_values);
  const double median =
      nf == 0 ? NAN : (nf % 2 ? vals[nf / 2] : 0.5 * (vals[nf / 2 - 1] + vals[nf / 2]));
  int peak = -1;
  for (int k = 0; k < nb; k++)
    if (cnt[k] && fabs((double)(k - centre)) * bin <= reach && (peak < 0 || m[k] > m[peak]))
      peak = k;
  if (peak >= 0 && m[peak] > median) {
    const double half = median + 0.5 * (m[peak] - median);
    const double lo = half_crossing(m, cnt, nb, peak, -1, half, centre, bin);
    const double hi = half_crossing(m, cnt, nb, peak, +1, half, centre, bin);
    *fwhm = hi - lo;  /* NaN when either side is */
    if (isfinite(*fwhm))
      *corrected = *fwhm > kernel ? sqrt(*fwhm * *fwhm - kernel * kernel) : 0.0;
  }
  free(vals);
  free(s);
  free(m);
  free(cnt);
  return LSDEM_OK;
}
