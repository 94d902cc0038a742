/* sdf.c -- signed distance functions behind one interface: sampled grids and analytic
 * shapes (sphere, half-space, cylinder, box, ellipsoid, superellipsoid). phi < 0 inside,
 * gradients point outward and have unit length. All in the shape's own frame. */
#include "lsdem_geom.h"

#include <float.h>
#include <math.h>

static double norm3(const double v[3])
{
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

static void set3(double g[3], double x, double y, double z)
{
  g[0] = x;
  g[1] = y;
  g[2] = z;
}

static double sign_of(double x)
{
  return x < 0.0 ? -1.0 : 1.0;
}

/* |p| - r; at the centre the gradient is arbitrary and we give +x. */
static double sphere_sdf(double r, const double p[3], double g[3])
{
  const double d = norm3(p);
  if (d > 0.0)
    set3(g, p[0] / d, p[1] / d, p[2] / d);
  else
    set3(g, 1.0, 0.0, 0.0);
  return d - r;
}

/* Solid z <= 0. */
static double plane_sdf(const double p[3], double g[3])
{
  set3(g, 0.0, 0.0, 1.0);
  return p[2];
}

/* Cylinder about z: radius r, half-length hl (infinite when hl <= 0). With
 * d = (rho - r, |z| - hl): phi = min(max(d), 0) + |max(d, 0)| (exact). */
static double cylinder_sdf(double r, double hl, const double p[3], double g[3])
{
  const double rho = sqrt(p[0] * p[0] + p[1] * p[1]);
  const double ex = rho > 0.0 ? p[0] / rho : 1.0, ey = rho > 0.0 ? p[1] / rho : 0.0;
  const double dr = rho - r;
  if (!(hl > 0.0)) {
    set3(g, ex, ey, 0.0);
    return dr;
  }
  const double dz = fabs(p[2]) - hl, sz = sign_of(p[2]);
  if (dr > 0.0 && dz > 0.0) { /* nearest point on the rim */
    const double d = sqrt(dr * dr + dz * dz);
    set3(g, ex * dr / d, ey * dr / d, sz * dz / d);
    return d;
  }
  if (dr >= dz) { /* nearest feature is the side */
    set3(g, ex, ey, 0.0);
    return dr;
  }
  set3(g, 0.0, 0.0, sz); /* nearest feature is a cap */
  return dz;
}

/* Box with half-extents a. q = |p| - a: phi = |max(q, 0)| + min(max_i q_i, 0) (exact). */
static double box_sdf(const double a[3], const double p[3], double g[3])
{
  double q[3], o[3];
  int imax = 0;
  for (int i = 0; i < 3; i++) {
    q[i] = fabs(p[i]) - a[i];
    o[i] = q[i] > 0.0 ? q[i] : 0.0;
    if (q[i] > q[imax]) imax = i;
  }
  const double out = norm3(o);
  if (out > 0.0) {
    set3(g, sign_of(p[0]) * o[0] / out, sign_of(p[1]) * o[1] / out,
         sign_of(p[2]) * o[2] / out);
    return out;
  }
  set3(g, 0.0, 0.0, 0.0);
  g[imax] = sign_of(p[imax]);
  return q[imax];
}

/* ------------------------------------------------------------- ellipsoid ---- */

/* Root of F(s) = sum_i (r_i z_i / (s + r_i))^2 - 1 on its bracket [s0, s1] (F(s0) >= 0 >=
 * F(s1)). F is convex and decreasing there, so after at most one step from the right
 * Newton approaches the root monotonically from the left; each step is kept inside the
 * shrinking bracket (else bisected) and the loop runs to machine precision. Starting at
 * s = 0 (the value on the surface) makes points near the surface, the common case in
 * contact, converge in a few steps. */
static double ellipsoid_root(int dim, const double r[3], const double z[3], double s0,
                             double s1)
{
  double s = fmin(fmax(0.0, s0), s1);
  for (int it = 0; it < 200; it++) {
    double f = -1.0, df = 0.0;
    for (int i = 0; i < dim; i++) {
      const double inv = 1.0 / (s + r[i]);
      const double t = r[i] * z[i] * inv;
      f += t * t;
      df -= 2.0 * t * t * inv;
    }
    if (f > 0.0)
      s0 = s;
    else if (f < 0.0)
      s1 = s;
    else
      return s;
    double next = df < 0.0 ? s - f / df : 0.5 * (s0 + s1);
    if (!(next >= s0 && next <= s1)) next = 0.5 * (s0 + s1);
    if (fabs(next - s) <= 2.0 * DBL_EPSILON * fmax(1.0, fabs(s)) || s1 - s0 <= 0.0) return next;
    s = next;
  }
  return s;
}

/* Closest point x on the ellipsoid surface sum (x_i/e_i)^2 = 1 to y, for semi-axes
 * e sorted descending and y >= 0 componentwise, in `dim` <= 3 dimensions (Eberly,
 * "Distance from a point to an ellipse, an ellipsoid, or a hyperellipsoid"). The
 * Lagrange condition is x_i = e_i^2 y_i / (t + e_i^2); with s = t / e_min^2 and
 * r_i = (e_i / e_min)^2 this is x_i = r_i y_i / (s + r_i) and s solves F(s) = 0.
 * Zero coordinates reduce the dimension. */
static void ellipsoid_closest(int dim, const double e[3], const double y[3], double x[3])
{
  const int last = dim - 1;
  if (dim == 1) {
    x[0] = e[0];
    return;
  }
  if (y[last] > 0.0) {
    for (int i = 0; i < last; i++) {
      if (y[i] > 0.0) continue;
      /* y_i = 0 with y_last > 0 forces x_i = 0: drop axis i */
      double es[3] = {0}, ys[3] = {0}, xs[3];
      for (int m = 0, k = 0; m < dim; m++)
        if (m != i) {
          es[k] = e[m];
          ys[k++] = y[m];
        }
      ellipsoid_closest(dim - 1, es, ys, xs);
      for (int m = 0, k = 0; m < dim; m++) x[m] = (m == i) ? 0.0 : xs[k++];
      return;
    }
    double z[3] = {0}, r[3] = {0}, g = -1.0, rz2 = 0.0;
    for (int i = 0; i < dim; i++) {
      z[i] = y[i] / e[i];
      r[i] = (e[i] / e[last]) * (e[i] / e[last]);
      g += z[i] * z[i];
      rz2 += r[i] * z[i] * r[i] * z[i];
    }
    if (g == 0.0) {
      for (int i = 0; i < dim; i++) x[i] = y[i];
      return;
    }
    const double s0 = z[last] - 1.0, s1 = g < 0.0 ? 0.0 : sqrt(rz2) - 1.0;
    const double s = ellipsoid_root(dim, r, z, s0, s1);
    for (int i = 0; i < dim; i++) x[i] = r[i] * y[i] / (s + r[i]);
    return;
  }
  /* y_last = 0: the closest point may leave the plane (inside, near the short axis) */
  double xde[3], discr = 1.0;
  int off_plane = 1;
  for (int i = 0; i < last && off_plane; i++) {
    const double numer = e[i] * y[i], denom = e[i] * e[i] - e[last] * e[last];
    if (numer < denom) {
      xde[i] = numer / denom;
      discr -= xde[i] * xde[i];
    } else {
      off_plane = 0;
    }
  }
  if (off_plane && discr > 0.0) {
    for (int i = 0; i < last; i++) x[i] = e[i] * xde[i];
    x[last] = e[last] * sqrt(discr);
    return;
  }
  x[last] = 0.0;
  ellipsoid_closest(dim - 1, e, y, x);
}

/* Exact signed distance to the ellipsoid with semi-axes a. Sorts the axes, reflects p
 * into the first octant, finds the closest point, and takes the gradient as the
 * surface normal there (parallel to p - x, and defined on the surface itself). */
static double ellipsoid_sdf(const double a[3], const double p[3], double g[3])
{
  int idx[3] = {0, 1, 2};
  for (int i = 0; i < 2; i++) /* sort axis indices by semi-axis, descending */
    for (int j = 0; j < 2 - i; j++)
      if (a[idx[j]] < a[idx[j + 1]]) {
        const int t = idx[j];
        idx[j] = idx[j + 1];
        idx[j + 1] = t;
      }
  double e[3], y[3], x[3];
  for (int i = 0; i < 3; i++) {
    e[i] = a[idx[i]];
    y[i] = fabs(p[idx[i]]);
  }
  ellipsoid_closest(3, e, y, x);
  double d2 = 0.0, inside = -1.0, n[3];
  for (int i = 0; i < 3; i++) {
    d2 += (x[i] - y[i]) * (x[i] - y[i]);
    inside += (y[i] / e[i]) * (y[i] / e[i]);
    n[i] = x[i] / (e[i] * e[i]);
  }
  const double nn = norm3(n);
  for (int i = 0; i < 3; i++) g[idx[i]] = sign_of(p[idx[i]]) * n[i] / nn;
  const double d = sqrt(d2);
  return inside < 0.0 ? -d : d;
}

/* -------------------------------------------------------- superellipsoid ---- */

/* Gauge g(p) = F(p)^(e1/2) of the superellipsoid, F = (X^(2/e2) + Y^(2/e2))^(e2/e1) +
 * Z^(2/e1) with X = |x/a0|, Y = |y/a1|, Z = |z/a2|: g is homogeneous of degree 1, the
 * surface is g = 1. Evaluated at p/m, m = max(X, Y, Z), so no power overflows; the
 * gradient (degree 0) is the same there. dg/dx = F^(e1/2-1) A^(e2/e1-1) X^(2/e2-1) sx/a0,
 * dg/dz = F^(e1/2-1) Z^(2/e1-1) sz/a2, A = X^(2/e2) + Y^(2/e2). grad may be NULL. */
static double superellipsoid_gauge(const double a[3], const double e[2], const double p[3],
                                   double grad[3])
{
  double X = fabs(p[0] / a[0]), Y = fabs(p[1] / a[1]), Z = fabs(p[2] / a[2]);
  const double m = fmax(X, fmax(Y, Z));
  if (grad) set3(grad, 0.0, 0.0, 0.0);
  if (m == 0.0) return 0.0;
  X /= m, Y /= m, Z /= m;
  const double e1 = e[0], e2 = e[1];
  const double A = pow(X, 2.0 / e2) + pow(Y, 2.0 / e2);
  const double F = pow(A, e2 / e1) + pow(Z, 2.0 / e1);
  if (grad) {
    const double Fp = pow(F, 0.5 * e1 - 1.0);
    if (A > 0.0) {
      const double Ap = pow(A, e2 / e1 - 1.0);
      grad[0] = X > 0.0 ? Fp * Ap * pow(X, 2.0 / e2 - 1.0) * sign_of(p[0]) / a[0] : 0.0;
      grad[1] = Y > 0.0 ? Fp * Ap * pow(Y, 2.0 / e2 - 1.0) * sign_of(p[1]) / a[1] : 0.0;
    }
    grad[2] = Z > 0.0 ? Fp * pow(Z, 2.0 / e1 - 1.0) * sign_of(p[2]) / a[2] : 0.0;
  }
  return m * pow(F, 0.5 * e1);
}

/* First-order distance (g - 1) / |grad g| (see lsdem.h): zero exactly on the surface,
 * gradient along the surface normal. At the centre: -min semi-axis, gradient +x. */
static double superellipsoid_sdf(const double a[3], const double e[2], const double p[3],
                                 double g[3])
{
  const double v = superellipsoid_gauge(a, e, p, g);
  const double n = norm3(g);
  if (!(n > 0.0)) {
    set3(g, 1.0, 0.0, 0.0);
    return v == 0.0 ? -fmin(a[0], fmin(a[1], a[2])) : v - 1.0;
  }
  set3(g, g[0] / n, g[1] / n, g[2] / n);
  return (v - 1.0) / n;
}

double lsdem_superellipsoid_radius(const double u[3], const void *sdf)
{
  const lsdem_sdf *s = sdf;
  return 1.0 / superellipsoid_gauge(s->a, s->a + 3, u, NULL);
}

/* ------------------------------------------------------------- interface ---- */

double lsdem_sdf_eval(const lsdem_sdf *s, const double p[3], double grad[3])
{
  double phi;
  switch (s->kind) {
  case LSDEM_SDF_GRID: phi = lsdem_grid_eval(&s->grid, p, grad); break;
  case LSDEM_SDF_SPHERE: phi = sphere_sdf(s->a[0], p, grad); break;
  case LSDEM_SDF_PLANE: phi = plane_sdf(p, grad); break;
  case LSDEM_SDF_CYLINDER: phi = cylinder_sdf(s->a[0], s->a[1], p, grad); break;
  case LSDEM_SDF_BOX: phi = box_sdf(s->a, p, grad); break;
  case LSDEM_SDF_ELLIPSOID: phi = ellipsoid_sdf(s->a, p, grad); break;
  case LSDEM_SDF_SUPERELLIPSOID: phi = superellipsoid_sdf(s->a, s->a + 3, p, grad); break;
  case LSDEM_SDF_BAND: phi = lsdem_band_eval(s->band, p, grad); break;
  default: set3(grad, 1.0, 0.0, 0.0); return HUGE_VAL;
  }
  if (s->inverted) {
    set3(grad, -grad[0], -grad[1], -grad[2]);
    return -phi;
  }
  return phi;
}

/* The kind's function is chosen once for the batch (walls test many nodes per call). */
void lsdem_sdf_eval_many(const lsdem_sdf *s, int n, const double *p, double *phi,
                         double *grad)
{
  switch (s->kind) {
  case LSDEM_SDF_GRID: lsdem_grid_eval_many(&s->grid, n, p, phi, grad); break;
  case LSDEM_SDF_BAND: lsdem_band_eval_many(s->band, n, p, phi, grad); break;
  case LSDEM_SDF_PLANE:
    for (int m = 0; m < n; m++) phi[m] = plane_sdf(&p[3 * m], &grad[3 * m]);
    break;
  case LSDEM_SDF_CYLINDER:
    for (int m = 0; m < n; m++)
      phi[m] = cylinder_sdf(s->a[0], s->a[1], &p[3 * m], &grad[3 * m]);
    break;
  default: /* the rest one by one, inversion included */
    for (int m = 0; m < n; m++) phi[m] = lsdem_sdf_eval(s, &p[3 * m], &grad[3 * m]);
    return;
  }
  if (s->inverted)
    for (int m = 0; m < n; m++) {
      phi[m] = -phi[m];
      set3(&grad[3 * m], -grad[3 * m], -grad[3 * m + 1], -grad[3 * m + 2]);
    }
}

/* ------------------------------------------------------ grid bound radius ---- */

/* The bound of a grid is that of the solid the lookups see, {phi_trilinear < 0}: a
 * trilinear function on a box is linear along each axis, so its extremes over the box
 * are at the box's 8 corners. A box whose corner values are all >= 0 holds no solid; a
 * box whose corner values are all < 0 is solid throughout. Cells with mixed corners are
 * bisected (sub-box corner values are exact trilinear evaluations of the parent's
 * corners) down to h / 2^BOUND_DEPTH, and the farthest corner of each box that may hold
 * solid bounds it: over-estimate <= sqrt(3) h / 2^BOUND_DEPTH (0.03 h). Boxes whose
 * farthest corner cannot raise the current bound are pruned, so only the cells near the
 * extreme points are refined. BOUND_EPS h counts a corner as solid when it is barely
 * positive, so that round-off in a lookup never finds solid beyond the bound. */
enum { BOUND_DEPTH = 6 };
static const double BOUND_EPS = 1e-9;

typedef struct {
  double r2;  /* squared bound so far */
  double eps; /* corner values below eps count as solid */
} bound_search;

/* Squared distance from the origin to the farthest corner of the box lo + [0, size]^3. */
static double farthest_corner2(const double lo[3], double size)
{
  double r2 = 0.0;
  for (int a = 0; a < 3; a++) {
    const double m = fmax(fabs(lo[a]), fabs(lo[a] + size));
    r2 += m * m;
  }
  return r2;
}

/* Trilinear interpolation of corner values v (index x + 2y + 4z) at fractions f. */
static double lerp_corners(const double v[8], const double f[3])
{
  double e[4];
  for (int c = 0; c < 4; c++) e[c] = v[2 * c] + f[0] * (v[2 * c + 1] - v[2 * c]);
  const double f0 = e[0] + f[1] * (e[1] - e[0]), f1 = e[2] + f[1] * (e[3] - e[2]);
  return f0 + f[2] * (f1 - f0);
}

/* Raise b->r2 to cover the solid of the box lo + [0, size]^3 with corner values v. */
static void bound_box(bound_search *b, const double lo[3], double size, const double v[8],
                      int depth)
{
  int solid = 0, all_solid = 1;
  for (int c = 0; c < 8; c++) {
    solid |= v[c] < b->eps;
    all_solid &= v[c] < -b->eps;
  }
  if (!solid) return;
  const double r2 = farthest_corner2(lo, size);
  if (r2 <= b->r2) return;
  if (all_solid || depth == 0) {
    b->r2 = r2;
    return;
  }
  double w[27]; /* values at the 3x3x3 lattice of half-steps, index i + 3j + 9k */
  for (int m = 0; m < 27; m++) {
    const double f[3] = {0.5 * (m % 3), 0.5 * (m / 3 % 3), 0.5 * (m / 9)};
    w[m] = lerp_corners(v, f);
  }
  const double half = 0.5 * size;
  for (int child = 0; child < 8; child++) {
    const int ci = child & 1, cj = child >> 1 & 1, ck = child >> 2;
    const double clo[3] = {lo[0] + half * ci, lo[1] + half * cj, lo[2] + half * ck};
    double cv[8];
    for (int c = 0; c < 8; c++)
      cv[c] = w[(ci + (c & 1)) + 3 * (cj + (c >> 1 & 1)) + 9 * (ck + (c >> 2))];
    bound_box(b, clo, half, cv, depth - 1);
  }
}

/* Outside the grid box a lookup returns phi(clamp(p)) + |p - clamp(p)| (levelset.c),
 * negative only within -phi(clamp(p)) of a negative value on the box's surface. The
 * surface's trilinear minimum is its smallest face sample (bilinear on each face cell),
 * so the solid there reaches at most that far beyond the solid inside the box. */
static double grid_outside_reach(const lsdem_grid *g)
{
  double lowest = 0.0;
  for (int k = 0; k < g->n[2]; k++)
    for (int j = 0; j < g->n[1]; j++)
      for (int i = 0; i < g->n[0]; i++) {
        const int face = i == 0 || j == 0 || k == 0 || i == g->n[0] - 1 ||
                         j == g->n[1] - 1 || k == g->n[2] - 1;
        const float v = g->phi[i + (size_t)g->n[0] * (j + (size_t)g->n[1] * k)];
        if (face && v < lowest) lowest = v;
      }
  return -lowest;
}

/* Corner values of cell (i, j, k), index x + 2y + 4z. */
static void cell_corners(const lsdem_grid *g, int i, int j, int k, double v[8])
{
  const size_t sy = (size_t)g->n[0], sz = sy * (size_t)g->n[1];
  const float *c = g->phi + (size_t)i + sy * (size_t)j + sz * (size_t)k;
  for (int m = 0; m < 8; m++) v[m] = c[(m & 1) + sy * (m >> 1 & 1) + sz * (m >> 2)];
}

/* Bound of the trilinear solid: first the largest |sample| among negative samples (points
 * of the solid, so a lower bound that prunes most cells at once), then every cell with a
 * corner that may be solid. */
static double grid_bound_radius(const lsdem_grid *g)
{
  bound_search b = {0.0, BOUND_EPS * g->h};
  for (int k = 0; k < g->n[2]; k++)
    for (int j = 0; j < g->n[1]; j++)
      for (int i = 0; i < g->n[0]; i++) {
        const double p[3] = {g->origin[0] + g->h * i, g->origin[1] + g->h * j,
                             g->origin[2] + g->h * k};
        if (g->phi[i + (size_t)g->n[0] * (j + (size_t)g->n[1] * k)] < -b.eps)
          b.r2 = fmax(b.r2, p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      }
  for (int k = 0; k + 1 < g->n[2]; k++)
    for (int j = 0; j + 1 < g->n[1]; j++)
      for (int i = 0; i + 1 < g->n[0]; i++) {
        double v[8];
        cell_corners(g, i, j, k, v);
        const double lo[3] = {g->origin[0] + g->h * i, g->origin[1] + g->h * j,
                              g->origin[2] + g->h * k};
        bound_box(&b, lo, g->h, v, BOUND_DEPTH);
      }
  return sqrt(b.r2) + grid_outside_reach(g);
}

double lsdem_sdf_bound_radius(const lsdem_sdf *s)
{
  if (s->inverted) return HUGE_VAL;
  switch (s->kind) {
  case LSDEM_SDF_GRID: return grid_bound_radius(&s->grid);
  case LSDEM_SDF_SPHERE: return s->a[0];
  case LSDEM_SDF_PLANE: return HUGE_VAL;
  case LSDEM_SDF_CYLINDER:
    return s->a[1] > 0.0 ? sqrt(s->a[0] * s->a[0] + s->a[1] * s->a[1]) : HUGE_VAL;
  case LSDEM_SDF_BOX: return norm3(s->a);
  case LSDEM_SDF_ELLIPSOID: return fmax(s->a[0], fmax(s->a[1], s->a[2]));
  case LSDEM_SDF_SUPERELLIPSOID: return norm3(s->a); /* inside the box of its semi-axes */
  case LSDEM_SDF_BAND: return HUGE_VAL; /* walls; beyond its box a band continues */
  }
  return HUGE_VAL;
}

double lsdem_sdf_lipschitz(const lsdem_sdf *s)
{
  switch (s->kind) {
  case LSDEM_SDF_SPHERE:
  case LSDEM_SDF_PLANE:
  case LSDEM_SDF_CYLINDER:
  case LSDEM_SDF_BOX:
  case LSDEM_SDF_ELLIPSOID: return 1.0;
  case LSDEM_SDF_BAND: return LSDEM_BAND_LIPSCHITZ;
  default: return 0.0;
  }
}

const char *lsdem_sdf_kind_name(lsdem_sdf_kind k)
{
  switch (k) {
  case LSDEM_SDF_GRID: return "grid";
  case LSDEM_SDF_SPHERE: return "sphere";
  case LSDEM_SDF_PLANE: return "plane";
  case LSDEM_SDF_CYLINDER: return "cylinder";
  case LSDEM_SDF_BOX: return "box";
  case LSDEM_SDF_ELLIPSOID: return "ellipsoid";
  case LSDEM_SDF_SUPERELLIPSOID: return "superellipsoid";
  case LSDEM_SDF_BAND: return "band";
  }
  return "unknown";
}
