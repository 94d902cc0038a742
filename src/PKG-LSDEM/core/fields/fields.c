/* fields.c -- continuum fields from grains and contacts: moments of a local-linear
 * Gaussian fit deposited on the grid, smoothed by FFT, solved per node (lsdem_fields.h). */
#include "lsdem_fields.h"

#include "../base/lsdem_vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* the deposited channels, per node */
enum {
  CH_MASS = 0,     /* m */
  CH_Y = 1,        /* m y (3) */
  CH_YY = 4,       /* m y y^T: xx xy xz yy yz zz (6) */
  CH_U = 10,       /* m u (3) */
  CH_UY = 13,      /* m u y^T, row-major (9) */
  CH_VOLUME = 22,  /* V */
  CH_STRESS = 23,  /* -sym(f (x) b): xx xy xz yy yz zz (6) */
  NCHAN = 29
};
/* (row, column) of the six stored components of a symmetric tensor */
static const int SYM_I[6] = {0, 0, 0, 1, 1, 2}, SYM_J[6] = {0, 1, 2, 1, 2, 2};

static void fields_bounds(int n, const lsdem_field_grain *grains, int nb,
                          const lsdem_field_branch *branches, double lo[3], double hi[3])
{
  for (int k = 0; k < 3; k++) lo[k] = hi[k] = grains[0].x[k];
  for (int i = 0; i < n + 2 * nb; i++) {
    const double *x = i < n ? grains[i].x
                            : (i - n) % 2 ? branches[(i - n) / 2].point
                                          : branches[(i - n) / 2].centre;
    for (int k = 0; k < 3; k++) {
      if (x[k] < lo[k]) lo[k] = x[k];
      if (x[k] > hi[k]) hi[k] = x[k];
    }
  }
}

/* the grid's centre: moments are taken about it to keep y small against the grid */
static void grid_centre(const lsdem_field_grid *g, double c[3])
{
  for (int k = 0; k < 3; k++) c[k] = g->origin[k] + 0.5 * g->h * (g->n[k] - 1);
}

static void deposit_grain(const lsdem_field_grid *g, const double c[3],
                          const lsdem_field_grain *gr, double *channels)
{
  double v[CH_STRESS] = {0.0}, y[3];
  lsdem_sub3(gr->x, c, y);
  const double m = gr->mass;
  v[CH_MASS] = m;
  for (int i = 0; i < 3; i++) {
    v[CH_Y + i] = m * y[i];
    v[CH_U + i] = m * gr->u[i];
    for (int j = 0; j < 3; j++) v[CH_UY + 3 * i + j] = m * gr->u[i] * y[j];
  }
  for (int s = 0; s < 6; s++) v[CH_YY + s] = m * y[SYM_I[s]] * y[SYM_J[s]];
  v[CH_VOLUME] = gr->volume;
  lsdem_field_deposit(g, gr->x, CH_STRESS, v, channels);
}

/* Goldhirsch's line integral along b = point - centre, by the midpoint rule on pieces no
 * longer than h: each piece carries 1/pieces of -sym(f (x) b) */
static void deposit_branch(const lsdem_field_grid *g, const lsdem_field_branch *br,
                           double *channels)
{
  double b[3], v[6];
  lsdem_sub3(br->point, br->centre, b);
  const int pieces = (int)ceil(sqrt(lsdem_dot3(b, b)) / g->h) + (lsdem_dot3(b, b) == 0.0);
  for (int s = 0; s < 6; s++) {
    const int i = SYM_I[s], j = SYM_J[s];
    v[s] = -0.5 * (br->force[i] * b[j] + br->force[j] * b[i]) / pieces;
  }
  const size_t nodes = lsdem_field_grid_nodes(g);
  for (int p = 0; p < pieces; p++) {
    const double t = (p + 0.5) / pieces;
    const double x[3] = {br->centre[0] + t * b[0], br->centre[1] + t * b[1],
                         br->centre[2] + t * b[2]};
    lsdem_field_deposit(g, x, 6, v, channels + CH_STRESS * nodes);
  }
}

/* M^-1 of a general 3x3 matrix by cofactors; 0 when det M <= 0 (the fit turned the
 * neighbourhood inside out) */
static int invert_proper(const double M[9], double inv[9])
{
  double c[9];
  lsdem_cross3(M + 3, M + 6, c);
  lsdem_cross3(M + 6, M, c + 3);
  lsdem_cross3(M, M + 3, c + 6);
  const double det = lsdem_dot3(M, c);
  if (!(det > 0.0)) return 0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) inv[3 * i + j] = c[3 * j + i] / det; /* adj = cof^T */
  return 1;
}

/* C^-1 through its eigen-decomposition; 0 when its smallest eigenvalue is below min_var */
static int invert_covariance(const double C[9], double min_var, double inv[9])
{
  double w[3], V[9];
  lsdem_sym_eigen(C, w, V);
  if (!(w[0] >= min_var)) return 0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double s = 0.0;
      for (int k = 0; k < 3; k++) s += V[3 * i + k] * V[3 * j + k] / w[k];
      inv[3 * i + j] = s;
    }
  return 1;
}

/* F at a node from its smoothed moments: the weighted fit u = a + L (x - xbar),
 * L = cov(u, y) cov(y, y)^-1, F = (I - L)^-1; 0 if the node is not regular */
static int node_gradient(const double *mom, double min_var, double F[9])
{
  const double s0 = mom[CH_MASS];
  double ybar[3], ubar[3], C[9], Cinv[9], Cuy[9], L[9], Finv[9];
  for (int i = 0; i < 3; i++) {
    ybar[i] = mom[CH_Y + i] / s0;
    ubar[i] = mom[CH_U + i] / s0;
  }
  for (int s = 0; s < 6; s++) {
    const int i = SYM_I[s], j = SYM_J[s];
    C[3 * i + j] = C[3 * j + i] = mom[CH_YY + s] / s0 - ybar[i] * ybar[j];
  }
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) Cuy[3 * i + j] = mom[CH_UY + 3 * i + j] / s0 - ubar[i] * ybar[j];
  if (!invert_covariance(C, min_var, Cinv)) return 0;
  lsdem_mat_mul(Cuy, Cinv, L);
  for (int k = 0; k < 9; k++) Finv[k] = (k % 4 == 0 ? 1.0 : 0.0) - L[k];
  return invert_proper(Finv, F);
}

/* rotation vector (angle times axis) of a unit quaternion, the angle in [0, pi] */
static void rotation_vector(const double q[4], double r[3])
{
  const double s = q[0] < 0.0 ? -1.0 : 1.0; /* q and -q: the same rotation */
  const double vn = sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  const double angle = 2.0 * atan2(vn, s * q[0]);
  for (int k = 0; k < 3; k++) r[k] = vn > 0.0 ? s * q[1 + k] * angle / vn : 0.0;
}

static void set_nan(double *a, int count)
{
  for (int k = 0; k < count; k++) a[k] = NAN;
}

static void clear_kinematics(lsdem_fields *f, size_t node)
{
  set_nan(f->grad + 9 * node, 9);
  set_nan(f->strain_small + 9 * node, 9);
  set_nan(f->strain_green + 9 * node, 9);
  set_nan(f->rotation + 3 * node, 3);
  f->volumetric[node] = f->shear[node] = NAN;
}

static void solve_kinematics(lsdem_fields *f, size_t node, const double *mom, double min_var,
                             double min_mass)
{
  double F[9];
  lsdem_local_strain small, green;
  f->regular[node] = mom[CH_MASS] >= min_mass && node_gradient(mom, min_var, F) &&
                     lsdem_strain_measures(F, LSDEM_STRAIN_SMALL, &small) == LSDEM_OK &&
                     lsdem_strain_measures(F, LSDEM_STRAIN_GREEN, &green) == LSDEM_OK;
  if (!f->regular[node]) {
    clear_kinematics(f, node);
    return;
  }
  for (int k = 0; k < 9; k++) {
    f->grad[9 * node + k] = F[k] - (k % 4 == 0 ? 1.0 : 0.0);
    f->strain_small[9 * node + k] = small.strain[k];
    f->strain_green[9 * node + k] = green.strain[k];
  }
  rotation_vector(green.rotation, f->rotation + 3 * node);
  f->volumetric[node] = green.volumetric;
  f->shear[node] = green.shear;
}

static int fields_alloc(lsdem_fields *f, size_t nodes)
{
  f->density = malloc(nodes * sizeof(double));
  f->solid_fraction = malloc(nodes * sizeof(double));
  f->grad = malloc(9 * nodes * sizeof(double));
  f->strain_small = malloc(9 * nodes * sizeof(double));
  f->strain_green = malloc(9 * nodes * sizeof(double));
  f->rotation = malloc(3 * nodes * sizeof(double));
  f->volumetric = malloc(nodes * sizeof(double));
  f->shear = malloc(nodes * sizeof(double));
  f->stress = malloc(9 * nodes * sizeof(double));
  f->regular = malloc(nodes);
  f->inside = malloc(nodes);
  return f->density && f->solid_fraction && f->grad && f->strain_small && f->strain_green &&
         f->rotation && f->volumetric && f->shear && f->stress && f->regular && f->inside;
}

void lsdem_fields_free(lsdem_fields *f)
{
  free(f->density);
  free(f->solid_fraction);
  free(f->grad);
  free(f->strain_small);
  free(f->strain_green);
  free(f->rotation);
  free(f->volumetric);
  free(f->shear);
  free(f->stress);
  free(f->regular);
  free(f->inside);
  memset(f, 0, sizeof *f);
}

/* every node's fields from the smoothed channels */
static void solve_nodes(lsdem_fields *f, const double *channels, const lsdem_field_params *p)
{
  const size_t nodes = lsdem_field_grid_nodes(&f->grid);
  const double per_volume = 1.0 / (f->grid.h * f->grid.h * f->grid.h);
  double max_mass = 0.0;
  for (size_t k = 0; k < nodes; k++)
    if (channels[k] > max_mass) max_mass = channels[k];
  for (size_t node = 0; node < nodes; node++) {
    double mom[NCHAN];
    for (int c = 0; c < NCHAN; c++) mom[c] = channels[(size_t)c * nodes + node];
    f->density[node] = per_volume * mom[CH_MASS];
    f->solid_fraction[node] = per_volume * mom[CH_VOLUME];
    for (int s = 0; s < 6; s++) {
      const int i = SYM_I[s], j = SYM_J[s];
      f->stress[9 * node + 3 * i + j] = f->stress[9 * node + 3 * j + i] =
          per_volume * mom[CH_STRESS + s];
    }
    solve_kinematics(f, node, mom, p->min_variance * p->width * p->width, p->min_weight * max_mass);
    f->inside[node] = 1;
  }
}

lsdem_status lsdem_fields_compute(const lsdem_field_params *p, int n,
                                  const lsdem_field_grain *grains, int nb,
                                  const lsdem_field_branch *branches, lsdem_fields *out,
                                  lsdem_error *err)
{
  memset(out, 0, sizeof *out);
  if (n < 1 || nb < 0 || !(p->min_variance >= 0.0) || !(p->min_weight >= 0.0))
    return lsdem_fail(err, LSDEM_ERR_ARG, "fields: %d grains, %d branches, min_variance %g, "
                      "min_weight %g", n, nb, p->min_variance, p->min_weight);
  double lo[3], hi[3], c[3];
  fields_bounds(n, grains, nb, branches, lo, hi);
  lsdem_status s = lsdem_field_grid_cover(lo, hi, p->h, p->width, &out->grid, err);
  if (s != LSDEM_OK) return s;
  const size_t nodes = lsdem_field_grid_nodes(&out->grid);
  double *channels = calloc(NCHAN * nodes, sizeof(double));
  if (!channels || !fields_alloc(out, nodes)) {
    free(channels);
    lsdem_fields_free(out);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "fields: no memory for %zu nodes", nodes);
  }
  grid_centre(&out->grid, c);
  for (int i = 0; i < n; i++) deposit_grain(&out->grid, c, grains + i, channels);
  for (int i = 0; i < nb; i++) deposit_branch(&out->grid, branches + i, channels);
  s = lsdem_field_smooth_fft(&out->grid, p->width, NCHAN, channels, err);
  if (s == LSDEM_OK) solve_nodes(out, channels, p);
  else lsdem_fields_free(out);
  free(channels);
  return s;
}

void lsdem_fields_mask_cylinder(lsdem_fields *f, const double centre[2], double radius,
                                double zlo, double zhi)
{
  const lsdem_field_grid *g = &f->grid;
  size_t node = 0;
  for (int i2 = 0; i2 < g->n[2]; i2++)
    for (int i1 = 0; i1 < g->n[1]; i1++)
      for (int i0 = 0; i0 < g->n[0]; i0++, node++) {
        const double x = g->origin[0] + g->h * i0 - centre[0];
        const double y = g->origin[1] + g->h * i1 - centre[1];
        const double z = g->origin[2] + g->h * i2;
        if (x * x + y * y <= radius * radius && z >= zlo && z <= zhi) continue;
        f->inside[node] = 0;
        f->regular[node] = 0;
        f->density[node] = f->solid_fraction[node] = NAN;
        clear_kinematics(f, node);
        set_nan(f->stress + 9 * node, 9);
      }
}
