/* voxel.c -- grains from a labelled 3-D image (CT scan after watershed segmentation).
 *
 * Each label becomes a signed-distance grid from exact Euclidean distance transforms of
 * the label and of its complement (Felzenszwalb & Huttenlocher 2012, "Distance transforms
 * of sampled functions": the squared EDT is a lower envelope of parabolas, separable over
 * the three axes, O(n)). The surface is taken midway between label and non-label voxel
 * centres: phi = d_out - 1/2 voxel outside, 1/2 voxel - d_in inside, so a flat face sits
 * exactly on the voxel faces. Scan frame: voxel (i,j,k) is centred at s*(i,j,k). */
#include "lsdem_prep.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double EDT_FAR = 1e20; /* "no feature": larger than any squared distance */

/* One line of the squared EDT (F&H Algorithm 1): d[q] = min_p (q - p)^2 + f[p], the lower
 * envelope of the parabolas rooted at the features (f < EDT_FAR; others are skipped, so
 * a line without features stays at EDT_FAR). v (n ints) and z (n+1 doubles) are scratch:
 * v holds the envelope's parabola roots, z the boundaries between them. */
static void edt_line(const double *f, int n, double *d, int *v, double *z)
{
  int k = -1;
  for (int q = 0; q < n; q++) {
    if (f[q] >= EDT_FAR) continue;
    double s = -HUGE_VAL;
    while (k >= 0) {
      const int p = v[k];
      s = ((f[q] + (double)q * q) - (f[p] + (double)p * p)) / (2.0 * (q - p));
      if (s > z[k]) break;
      k--;
    }
    if (k < 0) s = -HUGE_VAL;
    k++;
    v[k] = q;
    z[k] = s;
    z[k + 1] = HUGE_VAL;
  }
  if (k < 0) {
    for (int q = 0; q < n; q++) d[q] = EDT_FAR;
    return;
  }
  k = 0;
  for (int q = 0; q < n; q++) {
    while (z[k + 1] < q) k++;
    const double dq = q - v[k];
    d[q] = dq * dq + f[v[k]];
  }
}

/* In-place separable squared EDT of a box volume (x fastest): on input 0 at features and
 * EDT_FAR elsewhere; on output the squared distance (voxel units) to the nearest feature. */
static lsdem_status edt_3d(double *vol, const int n[3], lsdem_error *err)
{
  const int nmax = n[0] > n[1] ? (n[0] > n[2] ? n[0] : n[2]) : (n[1] > n[2] ? n[1] : n[2]);
  double *f = malloc(sizeof(double) * (size_t)nmax), *d = malloc(sizeof(double) * (size_t)nmax);
  double *z = malloc(sizeof(double) * ((size_t)nmax + 1));
  int *v = malloc(sizeof(int) * (size_t)nmax);
  if (!f || !d || !z || !v) {
    free(f), free(d), free(z), free(v);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate distance-transform lines");
  }
  const size_t stride[3] = {1, (size_t)n[0], (size_t)n[0] * n[1]};
  for (int a = 0; a < 3; a++) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (int jc = 0; jc < n[c]; jc++)
      for (int jb = 0; jb < n[b]; jb++) {
        double *line = vol + stride[b] * jb + stride[c] * jc;
        for (int i = 0; i < n[a]; i++) f[i] = line[stride[a] * i];
        edt_line(f, n[a], d, v, z);
        for (int i = 0; i < n[a]; i++) line[stride[a] * i] = fmin(d[i], EDT_FAR);
      }
  }
  free(f), free(d), free(z), free(v);
  return LSDEM_OK;
}

/* One pass of the [1 2 1]/4 filter along axis a (clamped at the box ends). */
static void filter_axis(const float *in, float *out, const int n[3], int a)
{
  const size_t stride[3] = {1, (size_t)n[0], (size_t)n[0] * n[1]};
  size_t m = 0;
  for (int k = 0; k < n[2]; k++)
    for (int j = 0; j < n[1]; j++)
      for (int i = 0; i < n[0]; i++, m++) {
        const int c = a == 0 ? i : a == 1 ? j : k;
        const float lo = c > 0 ? in[m - stride[a]] : in[m];
        const float hi = c < n[a] - 1 ? in[m + stride[a]] : in[m];
        out[m] = 0.25f * lo + 0.5f * in[m] + 0.25f * hi;
      }
}

/* Light smoothing of the staircase: `iters` separable [1 2 1]/4 passes, kept where
 * |phi| < 2 voxels and blended back to the unfiltered distance by 3 voxels; then
 * phi / |grad phi| (central differences) in the band restores a unit gradient there. */
static lsdem_status smooth_phi(float *phi, const int n[3], double h, int iters, lsdem_error *err)
{
  const size_t total = (size_t)n[0] * n[1] * n[2];
  float *a = malloc(total * sizeof(float)), *b = malloc(total * sizeof(float));
  if (!a || !b) {
    free(a), free(b);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate the smoothing buffers");
  }
  memcpy(a, phi, total * sizeof(float));
  for (int it = 0; it < iters; it++) {
    filter_axis(a, b, n, 0);
    filter_axis(b, a, n, 1);
    filter_axis(a, b, n, 2);
    memcpy(a, b, total * sizeof(float));
  }
  for (size_t m = 0; m < total; m++) {
    const double w = fmin(fmax(3.0 - fabs(phi[m]) / h, 0.0), 1.0); /* 1 inside 2h, 0 past 3h */
    b[m] = (float)(w * a[m] + (1.0 - w) * phi[m]);
  }
  const size_t stride[3] = {1, (size_t)n[0], (size_t)n[0] * n[1]};
  size_t m = 0;
  for (int k = 0; k < n[2]; k++)
    for (int j = 0; j < n[1]; j++)
      for (int i = 0; i < n[0]; i++, m++) {
        phi[m] = b[m];
        if (fabs(b[m]) >= 2.0 * h) continue;
        const int c[3] = {i, j, k};
        double g2 = 0.0;
        for (int ax = 0; ax < 3; ax++) {
          const int up = c[ax] < n[ax] - 1, dn = c[ax] > 0;
          const double fp = up ? b[m + stride[ax]] : b[m], fm = dn ? b[m - stride[ax]] : b[m];
          const double d = (fp - fm) / ((up + dn) * h);
          g2 += d * d;
        }
        const double g = fmin(fmax(sqrt(g2), 0.5), 2.0);
        phi[m] = (float)(b[m] / g);
      }
  free(a), free(b);
  return LSDEM_OK;
}

/* Shift phi by a constant so that the solid's volume becomes `target`: one Newton step
 * per pass on V(phi - c), dV/dc = surface area (lsdem_surface_area_grid). Undoes the
 * uniform shrinking of convex parts by smoothing and by trilinear resampling (both
 * O(h^2 kappa)); a constant shift keeps |grad phi|. */
static lsdem_status match_volume(lsdem_grid *g, float *phi, double target, lsdem_error *err)
{
  const size_t total = (size_t)g->n[0] * g->n[1] * g->n[2];
  for (int pass = 0; pass < 2; pass++) {
    lsdem_massprops mp;
    const lsdem_status st = lsdem_massprops_grid(g, 2, &mp, err);
    if (st != LSDEM_OK) return st;
    const double area = lsdem_surface_area_grid(g);
    if (!(area > 0.0)) return LSDEM_OK;
    const double c = (mp.volume - target) / area;
    for (size_t m = 0; m < total; m++) phi[m] = (float)(phi[m] + c);
  }
  return LSDEM_OK;
}

/* Squared EDTs of the label (d_out^2 for the others) and of the rest (d_in^2 inside),
 * combined to phi with the half-voxel offset, in voxel units scaled by h. */
static lsdem_status label_distance(const lsdem_label_image *img, int32_t label, const int lo[3],
                                   const int n[3], float *phi, double h, lsdem_error *err)
{
  const size_t total = (size_t)n[0] * n[1] * n[2];
  double *dout = malloc(total * sizeof(double)), *din = malloc(total * sizeof(double));
  unsigned char *in = malloc(total);
  lsdem_status st = LSDEM_OK;
  if (!dout || !din || !in) st = lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate a %d x %d x "
                                            "%d distance box", n[0], n[1], n[2]);
  size_t m = 0;
  for (int k = 0; st == LSDEM_OK && k < n[2]; k++)
    for (int j = 0; j < n[1]; j++)
      for (int i = 0; i < n[0]; i++, m++) {
        const int c[3] = {lo[0] + i, lo[1] + j, lo[2] + k};
        const int inside_image = c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < img->n[0] &&
                                 c[1] < img->n[1] && c[2] < img->n[2];
        in[m] = inside_image &&
                img->label[((size_t)c[2] * img->n[1] + c[1]) * img->n[0] + c[0]] == label;
        dout[m] = in[m] ? 0.0 : EDT_FAR;
        din[m] = in[m] ? EDT_FAR : 0.0;
      }
  if (st == LSDEM_OK) st = edt_3d(dout, n, err);
  if (st == LSDEM_OK) st = edt_3d(din, n, err);
  for (m = 0; st == LSDEM_OK && m < total; m++)
    phi[m] = (float)(h * (in[m] ? 0.5 - sqrt(din[m]) : sqrt(dout[m]) - 0.5));
  free(dout), free(din), free(in);
  return st;
}

lsdem_status lsdem_voxel_label_sdf(const lsdem_label_image *img, int32_t label,
                                   const int lo[3], const int hi[3], int pad,
                                   const lsdem_voxel_options *o, lsdem_grid *g,
                                   lsdem_error *err)
{
  if (!img || !img->label || !lo || !hi || !o || !g)
    return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  if (!(o->voxel_size > 0.0) || !isfinite(o->voxel_size))
    return lsdem_fail(err, LSDEM_ERR_ARG, "voxel size %g: must be positive", o->voxel_size);
  if (pad < 1 || pad > 1000 || o->smooth < 0)
    return lsdem_fail(err, LSDEM_ERR_ARG, "pad %d / smoothing %d out of range", pad, o->smooth);
  const double h = o->voxel_size;
  double blo[3], bhi[3];
  int n[3], start[3];
  for (int a = 0; a < 3; a++) {
    if (lo[a] > hi[a])
      return lsdem_fail(err, LSDEM_ERR_ARG, "empty bounding box on axis %d", a);
    start[a] = lo[a] - pad;
    blo[a] = h * lo[a];
    bhi[a] = h * hi[a];
  }
  float *phi;
  lsdem_status st = lsdem_grid_alloc(blo, bhi, h, pad, g, &phi, err);
  if (st != LSDEM_OK) return st;
  memcpy(n, g->n, sizeof n);
  for (int a = 0; a < 3; a++) g->origin[a] = h * start[a]; /* exactly on voxel centres */
  st = label_distance(img, label, start, n, phi, h, err);
  if (st == LSDEM_OK && o->smooth > 0) {
    lsdem_massprops before;
    st = lsdem_massprops_grid(g, 2, &before, err);
    if (st == LSDEM_OK) st = smooth_phi(phi, n, h, o->smooth, err);
    if (st == LSDEM_OK) st = match_volume(g, phi, before.volume, err);
  }
  if (st != LSDEM_OK) lsdem_grid_free(g);
  return st;
}

void lsdem_voxel_grains_free(lsdem_voxel_grain *grains, int count)
{
  for (int i = 0; grains && i < count; i++) lsdem_grid_free(&grains[i].grid);
  free(grains);
}

/* Per label: voxel count and inclusive bounding box. */
typedef struct {
  long count;
  int lo[3], hi[3];
} label_box;

static lsdem_status scan_labels(const lsdem_label_image *img, label_box **boxes, int32_t *maxlab,
                                lsdem_error *err)
{
  const size_t total = (size_t)img->n[0] * img->n[1] * img->n[2];
  int32_t mx = 0;
  for (size_t m = 0; m < total; m++) mx = img->label[m] > mx ? img->label[m] : mx;
  if (mx > LSDEM_VOXEL_MAX_LABEL)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "label %ld is above the largest accepted label %d: "
                      "relabel the image consecutively", (long)mx, LSDEM_VOXEL_MAX_LABEL);
  label_box *b = calloc((size_t)mx + 1, sizeof *b);
  if (!b) return lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate %ld label boxes", (long)mx + 1);
  size_t m = 0;
  for (int k = 0; k < img->n[2]; k++)
    for (int j = 0; j < img->n[1]; j++)
      for (int i = 0; i < img->n[0]; i++, m++) {
        const int32_t l = img->label[m];
        if (l <= 0) continue;
        label_box *x = &b[l];
        const int c[3] = {i, j, k};
        for (int a = 0; a < 3; a++) {
          if (!x->count || c[a] < x->lo[a]) x->lo[a] = c[a];
          if (!x->count || c[a] > x->hi[a]) x->hi[a] = c[a];
        }
        x->count++;
      }
  *boxes = b;
  *maxlab = mx;
  return LSDEM_OK;
}

/* One label's grain: scan-frame SDF, mass properties, principal frame, pose. */
static lsdem_status make_grain(const lsdem_label_image *img, int32_t label, const label_box *b,
                               const lsdem_voxel_options *o, lsdem_voxel_grain *gr,
                               lsdem_error *err)
{
  lsdem_grid scan;
  lsdem_status st = lsdem_voxel_label_sdf(img, label, b->lo, b->hi, o->margin + 1, o, &scan, err);
  if (st != LSDEM_OK) return st;
  lsdem_massprops mp;
  st = lsdem_massprops_grid(&scan, 2, &mp, err);
  if (st == LSDEM_OK) st = lsdem_grid_to_principal(&scan, &mp, o->margin, &gr->grid, gr->quat, err);
  if (st == LSDEM_OK) st = match_volume(&gr->grid, (float *)gr->grid.phi, mp.volume, err);
  lsdem_grid_free(&scan);
  if (st != LSDEM_OK) {
    lsdem_grid_free(&gr->grid);
    char msg[sizeof err->msg] = "";
    if (err) memcpy(msg, err->msg, sizeof msg);
    return lsdem_fail(err, st, "label %ld: %s", (long)label, msg);
  }
  gr->label = label;
  gr->nvoxels = b->count;
  memcpy(gr->position, mp.centroid, sizeof gr->position);
  return LSDEM_OK;
}

lsdem_status lsdem_voxel_grains(const lsdem_label_image *img, const lsdem_voxel_options *o,
                                lsdem_voxel_grain **grains, int *count, int *dropped,
                                lsdem_error *err)
{
  if (!img || !img->label || !o || !grains || !count || !dropped)
    return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  *grains = NULL, *count = 0, *dropped = 0;
  if (o->margin < 1) return lsdem_fail(err, LSDEM_ERR_ARG, "margin %d: must be >= 1", o->margin);
  label_box *boxes = NULL;
  int32_t mx;
  lsdem_status st = scan_labels(img, &boxes, &mx, err);
  if (st != LSDEM_OK) return st;
  int keep = 0;
  for (int32_t l = 1; l <= mx; l++) {
    if (!boxes[l].count) continue;
    if (boxes[l].count < o->min_voxels) (*dropped)++;
    else keep++;
  }
  lsdem_voxel_grain *out = calloc(keep > 0 ? (size_t)keep : 1, sizeof *out);
  if (!out) st = lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate %d grains", keep);
  int made = 0;
  for (int32_t l = 1; st == LSDEM_OK && l <= mx; l++) {
    if (!boxes[l].count || boxes[l].count < o->min_voxels) continue;
    st = make_grain(img, l, &boxes[l], o, &out[made], err);
    if (st == LSDEM_OK) made++;
  }
  free(boxes);
  if (st != LSDEM_OK) {
    lsdem_voxel_grains_free(out, made);
    *dropped = 0;
    return st;
  }
  *grains = out;
  *count = made;
  return LSDEM_OK;
}
