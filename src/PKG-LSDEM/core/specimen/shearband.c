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

/* RANSAC: of `samples` planes through 3 sampled candidates, the one with most candidates
 * within threshold (the first on ties); its count, 0 when every sample was degenerate */
static int ransac_plane(int m, const int *cand, const double *x, int samples, double threshold,
                        uint64_t *rng, unsigned char *mask, double centre[3], double normal[3])
{
  int best = 0;
  for (int s = 0; s < samples; s++) {
    const double *a = x + 3 * cand[lcg_index(rng, m)];
    const double *b = x + 3 * cand[lcg_index(rng, m)];
    const double *c = x + 3 * cand[lcg_index(rng, m)];
    double n[3];
    if (!plane_through(a, b, c, n)) continue;
    const int count = select_inliers(m, cand, x, a, n, threshold, mask);
    if (count > best) {
      best = count;
      memcpy(centre, a, sizeof(double) * 3);
      memcpy(normal, n, sizeof(double) * 3);
    }
  }
  return best;
}

/* the masked candidates' centroid and the eigen-decomposition of their scatter matrix
 * about it, count times their covariance (eigenvalues ascending in w, unit eigenvectors in
 * V's columns, lsdem_sym_eigen); returns the count */
static int principal_axes(int m, const int *cand, const double *x, const unsigned char *mask,
                           double centre[3], double w[3], double V[9])
{
  double C[9] = {0.0};
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
  return count;
}

/* least squares: the masked candidates' centroid and the smallest-eigenvalue eigenvector of
 * their covariance */
static void pca_plane(int m, const int *cand, const double *x, const unsigned char *mask,
                      double centre[3], double normal[3])
{
  double w[3], V[9];
  principal_axes(m, cand, x, mask, centre, w, V);
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

/* one plane fitted to the m candidates: RANSAC within threshold, then refitted to the
 * candidates within slab (>= threshold) until that set is stable; mask marks them, the
 * plane's ninliers counts them and its thickness is theirs; 0 when none was found */
static int fit_one_plane(int m, const int *cand, const double *x, int samples, double threshold,
                         double slab, uint64_t *rng, unsigned char *mask, unsigned char *trial,
                         lsdem_shearband_plane *pl)
{
  if (m < 3 || ransac_plane(m, cand, x, samples, threshold, rng, trial, pl->centre,
                            pl->normal) < 3)
    return 0;
  select_inliers(m, cand, x, pl->centre, pl->normal, slab, mask);
  pl->ninliers = refine_plane(m, cand, x, slab, mask, trial, pl->centre, pl->normal);
  orient_up(pl->normal);
  plane_angles(pl);
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
  while (*nplanes < p->planes && fit_one_plane(m, cand, x, p->samples, p->threshold,
                                               p->threshold, &rng, mask, trial,
                                               &plane[*nplanes])) {
    plane[*nplanes].inlier_fraction = (double) plane[*nplanes].ninliers / nflagged;
    m = drop_inliers(m, cand, mask);
    (*nplanes)++;
  }
  classify_points(n, x, *nplanes, plane, band);
  free(cand);
  free(mask);
  free(trial);
  return LSDEM_OK;
}

/* sqrt(12 w / count) of a scatter matrix's eigenvalues w (ascending) into sizes, largest
 * first: the sides of a uniformly filled box of that covariance */
static void sizes_of(const double w[3], int count, double sizes[3])
{
  for (int r = 0; r < 3; r++) sizes[r] = sqrt(12.0 * fmax(w[2 - r], 0.0) / count);
}

/* the principal sizes, centroid and upward normal (smallest axis) of the masked candidates */
static void masked_sizes(int m, const int *cand, const double *x, const unsigned char *mask,
                         double centre[3], double sizes[3], double normal[3])
{
  double w[3], V[9];
  const int count = principal_axes(m, cand, x, mask, centre, w, V);
  sizes_of(w, count, sizes);
  for (int r = 0; r < 3; r++) normal[r] = V[3 * r];
  orient_up(normal);
}

lsdem_status lsdem_point_sizes(int n, const double *x, lsdem_shearband_plane *plane,
                               double sizes[3])
{
  if (n < 2 || !x || !plane || !sizes) return LSDEM_ERR_ARG;
  int *all = malloc(sizeof(int) * (size_t) n);
  unsigned char *mask = malloc((size_t) n);
  if (!all || !mask) {
    free(all);
    free(mask);
    return LSDEM_ERR_NOMEM;
  }
  for (int i = 0; i < n; i++) {
    all[i] = i;
    mask[i] = 1;
  }
  memset(plane, 0, sizeof *plane);
  masked_sizes(n, all, x, mask, plane->centre, sizes, plane->normal);
  plane_angles(plane);
  plane->thickness = sizes[2];
  plane->ninliers = n;
  plane->inlier_fraction = 1.0;
  free(all);
  free(mask);
  return LSDEM_OK;
}

/* the sheet of the plane just fitted (pl, its slab's points in mask): its points within tol
 * (marked in inl) measured; 1 when they form a sheet (long and broad enough) */
static int measure_sheet(int m, const int *cand, const double *x, const lsdem_sheet_params *p,
                         unsigned char *inl, lsdem_sheet *sh)
{
  sh->plane.ninliers = select_inliers(m, cand, x, sh->plane.centre, sh->plane.normal, p->tol,
                                      inl);
  sh->length = sh->breadth = 0.0;
  if (sh->plane.ninliers >= 2) {
    double c[3], sizes[3], n[3];
    masked_sizes(m, cand, x, inl, c, sizes, n);
    sh->length = sizes[0];
    sh->breadth = sizes[1];
  }
  return sh->length >= p->min_length && sh->breadth >= p->aspect * sh->plane.thickness;
}

lsdem_status lsdem_sheets_fit(int n, const double *x, const lsdem_sheet_params *p, int cap,
                              lsdem_sheet *sheet, int *nsheets, int *label)
{
  if (n < 0 || (n > 0 && (!x || !label)) || !p || cap < 0 || (cap > 0 && !sheet) ||
      !nsheets || !(p->tol > 0.0) || !(p->slab >= p->tol) || !(p->min_length >= 0.0) ||
      !(p->aspect >= 0.0) || p->samples <= 0)
    return LSDEM_ERR_ARG;
  *nsheets = 0;
  for (int i = 0; i < n; i++) label[i] = -1;
  const size_t size = n > 0 ? (size_t) n : 1;
  int *cand = malloc(sizeof(int) * size);
  unsigned char *mask = malloc(size), *trial = malloc(size), *inl = malloc(size);
  if (!cand || !mask || !trial || !inl) {
    free(cand);
    free(mask);
    free(trial);
    free(inl);
    return LSDEM_ERR_NOMEM;
  }
  for (int i = 0; i < n; i++) cand[i] = i;
  uint64_t rng = p->seed;
  int m = n;
  while (*nsheets < cap) {
    lsdem_sheet *sh = &sheet[*nsheets];
    if (!fit_one_plane(m, cand, x, p->samples, p->tol, p->slab, &rng, mask, trial, &sh->plane))
      break;
    if (!measure_sheet(m, cand, x, p, inl, sh)) break;
    sh->plane.inlier_fraction = (double) sh->plane.ninliers / n;
    for (int j = 0; j < m; j++)
      if (inl[j]) label[cand[j]] = *nsheets;
    (*nsheets)++;
    m = drop_inliers(m, cand, mask); /* the slab set aside */
  }
  free(cand);
  free(mask);
  free(trial);
  free(inl);
  return LSDEM_OK;
}

/* the order of the sheets by their point counts, largest first (ties: index order) */
static void order_by_size(int ns, const lsdem_sheet *sheet, int *order)
{
  for (int k = 0; k < ns; k++) {
    int j = k;
    while (j > 0 && sheet[order[j - 1]].plane.ninliers < sheet[k].plane.ninliers) {
      order[j] = order[j - 1];
      j--;
    }
    order[j] = k;
  }
}

lsdem_status lsdem_sheets_join(int n, const double *x, const int *label, int ns,
                               const lsdem_sheet *sheet, double angle, double dist,
                               double min_length, int *group, lsdem_sheet *band, int *nbands)
{
  if (n < 0 || ns < 0 || (n > 0 && (!x || !label)) || (ns > 0 && (!sheet || !group || !band)) ||
      !nbands || !(angle >= 0.0) || !(dist >= 0.0) || !(min_length >= 0.0))
    return LSDEM_ERR_ARG;
  *nbands = 0;
  const size_t size = n > 0 ? (size_t) n : 1, ssize = ns > 0 ? (size_t) ns : 1;
  int *order = malloc(sizeof(int) * ssize), *lead = malloc(sizeof(int) * ssize);
  int *all = malloc(sizeof(int) * size);
  unsigned char *mask = malloc(size);
  if (!order || !lead || !all || !mask) {
    free(order);
    free(lead);
    free(all);
    free(mask);
    return LSDEM_ERR_NOMEM;
  }
  /* groups: each sheet, largest first, joins the first group whose lead is parallel to it
   * within angle and whose plane passes within dist of its centre */
  const double cosmin = cos(angle / DEG);
  int ngroups = 0;
  order_by_size(ns, sheet, order);
  for (int k = 0; k < ns; k++) {
    const lsdem_shearband_plane *sp = &sheet[order[k]].plane;
    int g = 0;
    for (; g < ngroups; g++) {
      const lsdem_shearband_plane *lp = &sheet[lead[g]].plane;
      if (fabs(lsdem_dot3(sp->normal, lp->normal)) >= cosmin &&
          fabs(signed_distance(sp->centre, lp->centre, lp->normal)) <= dist)
        break;
    }
    if (g == ngroups) lead[ngroups++] = order[k];
    group[order[k]] = g;
  }
  /* each group measured as one: its sheets' points refitted, thickness their point-weighted
   * mean; a band when at least min_length long (groups renumbered as bands, -1: none) */
  for (int i = 0; i < n; i++) all[i] = i;
  int *band_of = lead; /* reused: group -> band */
  for (int g = 0; g < ngroups; g++) {
    int count = 0;
    double tsum = 0.0;
    for (int i = 0; i < n; i++) {
      mask[i] = label[i] >= 0 && label[i] < ns && group[label[i]] == g;
      count += mask[i];
    }
    for (int k = 0; k < ns; k++)
      if (group[k] == g) tsum += sheet[k].plane.ninliers * sheet[k].plane.thickness;
    band_of[g] = -1;
    if (count < 2) continue;
    lsdem_sheet b;
    memset(&b, 0, sizeof b);
    double sizes[3];
    masked_sizes(n, all, x, mask, b.plane.centre, sizes, b.plane.normal);
    if (sizes[0] < min_length) continue;
    b.length = sizes[0];
    b.breadth = sizes[1];
    b.plane.ninliers = count;
    b.plane.inlier_fraction = (double) count / n;
    b.plane.thickness = tsum / count;
    plane_angles(&b.plane);
    band_of[g] = *nbands;
    band[(*nbands)++] = b;
  }
  for (int k = 0; k < ns; k++) group[k] = band_of[group[k]];
  free(order);
  free(lead);
  free(all);
  free(mask);
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
