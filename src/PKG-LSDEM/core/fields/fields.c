/* fields.c -- continuum fields from grains and contacts: moments of a local-linear
 * Gaussian fit deposited on the grid, smoothed by FFT, solved per node (lsdem_fields.h). */
#include "lsdem_fields.h"

#include "../base/lsdem_vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* the channels, per node: deposited about the deposit node (y = d = x - x_g), smoothed
 * about the target node (y = x - x_n) */
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

/* the bounds of the grains' and branches' points in lattice coordinates (skew) */
static void fields_bounds(const double skew[3], int n, const lsdem_field_grain *grains, int nb,
                          const lsdem_field_branch *branches, double lo[3], double hi[3])
{
  lsdem_field_to_lattice(skew, grains[0].x, lo);
  for (int k = 0; k < 3; k++) hi[k] = lo[k];
  for (int i = 0; i < n + 2 * nb; i++) {
    double x[3];
    lsdem_field_to_lattice(skew,
                           i < n           ? grains[i].x
                           : (i - n) % 2 ? branches[(i - n) / 2].point
                                         : branches[(i - n) / 2].centre,
                           x);
    for (int k = 0; k < 3; k++) {
      if (x[k] < lo[k]) lo[k] = x[k];
      if (x[k] > hi[k]) hi[k] = x[k];
    }
  }
}

/* L_box = sum over periodic axes k of jump_k d_k^T, d_k the dual of the period vectors
 * (row k of T^-1 over the length l_k: d_k . a_j = delta_kj; e_k / l_k for an orthogonal
 * box): L_box a_k = jump_k, and u - L_box x is periodic */
static void box_gradient(const lsdem_field_box *box, double L[9])
{
  double skew[3];
  lsdem_field_box_skew(box, skew);
  for (int k = 0; k < 9; k++) L[k] = 0.0;
  for (int k = 0; k < 3; k++) {
    if (!box->periodic[k]) continue;
    double d[3];
    lsdem_field_inverse_row(skew, k, d);
    const double l = box->hi[k] - box->lo[k];
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) L[3 * i + j] += box->jump[k][i] * d[j] / l;
  }
}

/* a grain's moments about each node of its cell (d = x - x_g exact, the node's image next
 * to x), with u' = u - L_box x */
static void deposit_grain(const lsdem_field_grid *g, const double Lbox[9],
                          const lsdem_field_grain *gr, double *channels)
{
  size_t node[8];
  double w[8], d[8][3], u[3], Lx[3];
  lsdem_field_cell(g, gr->x, node, w, d);
  lsdem_mat_vec(Lbox, gr->x, Lx);
  lsdem_sub3(gr->u, Lx, u);
  const double m = gr->mass;
  const size_t nodes = lsdem_field_grid_nodes(g);
  for (int c = 0; c < 8; c++) {
    double v[CH_STRESS];
    const double *y = d[c];
    v[CH_MASS] = m;
    for (int i = 0; i < 3; i++) {
      v[CH_Y + i] = m * y[i];
      v[CH_U + i] = m * u[i];
      for (int j = 0; j < 3; j++) v[CH_UY + 3 * i + j] = m * u[i] * y[j];
    }
    for (int s = 0; s < 6; s++) v[CH_YY + s] = m * y[SYM_I[s]] * y[SYM_J[s]];
    v[CH_VOLUME] = gr->volume;
    for (int ch = 0; ch < CH_STRESS; ch++) channels[(size_t)ch * nodes + node[c]] += w[c] * v[ch];
  }
}

/* Goldhirsch's line integral along b = point - centre (minimum image on a periodic axis),
 * by the midpoint rule on pieces no longer than the finest spacing: each piece carries
 * 1/pieces of -sym(f (x) b) */
static void deposit_branch(const lsdem_field_grid *g, const lsdem_field_box *box,
                           const lsdem_field_branch *br, double *channels)
{
  double b[3], bxi[3], v[6];
  lsdem_sub3(br->point, br->centre, bxi);
  lsdem_field_to_lattice(g->skew, bxi, b); /* b in lattice coordinates first */
  for (int k = 0; k < 3; k++)
    if (box->periodic[k]) {
      const double period = box->hi[k] - box->lo[k];
      b[k] -= period * round(b[k] / period);
    }
  memcpy(bxi, b, sizeof bxi);
  lsdem_field_from_lattice(g->skew, bxi, b);
  const double h = fmin(g->h[0], fmin(g->h[1], g->h[2]));
  const int pieces = (int)ceil(sqrt(lsdem_dot3(b, b)) / h) + (lsdem_dot3(b, b) == 0.0);
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

/* The smoothing as moment kernels (lsdem_field_smooth_terms): with r = x_g - x_n, the
 * moments about the target node are sum G (m, m (d + r), m (d + r)(d + r)^T, m u,
 * m u (d + r)^T) -- the binomial expansion of each in d and r */
static int smoothing_terms(lsdem_field_term *t)
{
  int n = 0;
#define TERM(o, i, k) (t[n].out = (o), t[n].in = (i), t[n].kernel = (k), n++)
  for (int c = 0; c < NCHAN; c++) TERM(c, c, 0);
  for (int i = 0; i < 3; i++) TERM(CH_Y + i, CH_MASS, 1 + i);
  for (int s = 0; s < 6; s++) {
    const int i = SYM_I[s], j = SYM_J[s];
    TERM(CH_YY + s, CH_Y + j, 1 + i);
    TERM(CH_YY + s, CH_Y + i, 1 + j);
    TERM(CH_YY + s, CH_MASS, 4 + s);
  }
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) TERM(CH_UY + 3 * i + j, CH_U + i, 1 + j);
#undef TERM
  return n;
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

/* F at a node from its smoothed moments: the weighted fit u' = a + L' (x - xbar),
 * L' = cov(u', y) cov(y, y)^-1, L = L' + L_box, F = (I - L)^-1; 0 if the node is not
 * regular */
static int node_gradient(const double *mom, const double Lbox[9], double min_var, double F[9])
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
  for (int k = 0; k < 9; k++) Finv[k] = (k % 4 == 0 ? 1.0 : 0.0) - (L[k] + Lbox[k]);
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

static void solve_kinematics(lsdem_fields *f, size_t node, const double *mom,
                             const double Lbox[9], double min_var, double min_mass)
{
  double F[9];
  lsdem_local_strain small, green;
  f->regular[node] = mom[CH_MASS] >= min_mass && node_gradient(mom, Lbox, min_var, F) &&
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
  const double per_volume = 1.0 / (f->grid.h[0] * f->grid.h[1] * f->grid.h[2]);
  double Lbox[9];
  box_gradient(&p->box, Lbox);
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
    solve_kinematics(f, node, mom, Lbox, p->min_variance * p->width * p->width,
                     p->min_weight * max_mass);
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
  double lo[3], hi[3], Lbox[9];
  double skew[3];
  lsdem_field_box_skew(&p->box, skew);
  fields_bounds(skew, n, grains, nb, branches, lo, hi);
  lsdem_status s = lsdem_field_grid_cover_box(&p->box, lo, hi, p->h, p->width, &out->grid, err);
  if (s != LSDEM_OK) return s;
  const size_t nodes = lsdem_field_grid_nodes(&out->grid);
  double *channels = calloc(NCHAN * nodes, sizeof(double));
  if (!channels || !fields_alloc(out, nodes)) {
    free(channels);
    lsdem_fields_free(out);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "fields: no memory for %zu nodes", nodes);
  }
  box_gradient(&p->box, Lbox);
  for (int i = 0; i < n; i++) deposit_grain(&out->grid, Lbox, grains + i, channels);
  for (int i = 0; i < nb; i++) deposit_branch(&out->grid, &p->box, branches + i, channels);
  lsdem_field_term terms[64];
  const int nterms = smoothing_terms(terms);
  s = lsdem_field_smooth_terms(&out->grid, p->width, NCHAN, channels, NCHAN, channels, nterms,
                               terms, err);
  if (s == LSDEM_OK) solve_nodes(out, channels, p);
  else lsdem_fields_free(out);
  free(channels);
  return s;
}

/* a node outside the material: every field NaN */
static void mask_node(lsdem_fields *f, size_t node)
{
  f->inside[node] = 0;
  f->regular[node] = 0;
  f->density[node] = f->solid_fraction[node] = NAN;
  clear_kinematics(f, node);
  set_nan(f->stress + 9 * node, 9);
}

void lsdem_fields_mask_cylinder(lsdem_fields *f, const double centre[2], double radius,
                                double zlo, double zhi)
{
  const lsdem_field_grid *g = &f->grid;
  size_t node = 0;
  for (int i2 = 0; i2 < g->n[2]; i2++)
    for (int i1 = 0; i1 < g->n[1]; i1++)
      for (int i0 = 0; i0 < g->n[0]; i0++, node++) {
        const int i[3] = {i0, i1, i2};
        double p[3];
        lsdem_field_node_position(g, i, p);
        const double x = p[0] - centre[0], y = p[1] - centre[1], z = p[2];
        if (x * x + y * y <= radius * radius && z >= zlo && z <= zhi) continue;
        mask_node(f, node);
      }
}

lsdem_status lsdem_fields_mask_surface(lsdem_fields *f, int nv, const double *v, int nt,
                                       const int *tri, lsdem_error *err)
{
  const size_t nodes = lsdem_field_grid_nodes(&f->grid);
  unsigned char *in = malloc(nodes);
  if (!in) return lsdem_fail(err, LSDEM_ERR_NOMEM, "mask: no memory for %zu nodes", nodes);
  const lsdem_status s = lsdem_field_inside_surface(&f->grid, nv, v, nt, tri, in, err);
  for (size_t node = 0; s == LSDEM_OK && node < nodes; node++)
    if (!in[node]) mask_node(f, node);
  free(in);
  return s;
}
