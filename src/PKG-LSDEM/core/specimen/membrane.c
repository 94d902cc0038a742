/* membrane.c -- the triaxial test's flexible membrane (report §2.3.5, §3.3.2): lattice
 * generation, confining-pressure forces, enclosed volume (eq 2.30) and the bond force.
 * Conventions in lsdem.h ("flexible membrane"). Lengths in the caller's units; the axis is
 * parallel to z. */
#include "lsdem_specimen.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------- geometry ---- */

/* Angular offset of a ring, in steps: the inner layer's odd rings are shifted by half a
 * step; the outer ring j sits over the up holes of inner rings (j, j+1), whose centroids
 * share the angles of inner ring j+1. */
static double ring_shift(int layer, int ring)
{
  int parity = layer == 0 ? ring % 2 : (ring + 1) % 2;
  return 0.5 * parity;
}

/* Index of the sphere of ring `ring` nearest to angle `steps` (in units of the step). */
static int index_at(int nper, int layer, int ring, double steps)
{
  long k = lround(steps - ring_shift(layer, ring));
  return (int) (((k % nper) + nper) % nper);
}

static int sphere_index(const lsdem_membrane *m, int layer, int ring, int k)
{
  return (layer == 0 ? 0 : m->nrings[0] * m->nper) + ring * m->nper + k;
}

/* Radius of the outer cylinder: an outer sphere over an up hole touches the nearest of
 * the hole's three inner spheres (apex: same angle, 2dz/3 above; base: +-half a step,
 * dz/3 below), i.e. the largest radius of the three touching conditions. */
static double outer_ring_radius(double R, double dz, double half_step, double contact)
{
  double ra = R + sqrt(fmax(0.0, contact * contact - (2.0 * dz / 3.0) * (2.0 * dz / 3.0)));
  double c = R * cos(half_step);
  double disc = c * c - R * R - (dz / 3.0) * (dz / 3.0) + contact * contact;
  double rbase = c + sqrt(fmax(0.0, disc));
  return fmax(ra, rbase);
}

static void place_spheres(lsdem_membrane *m, const lsdem_membrane_params *p)
{
  double step = 2.0 * M_PI / m->nper;
  int n = 0;
  for (int layer = 0; layer < 2; layer++) {
    double zoff = layer == 0 ? 0.0 : m->dz / 3.0;
    for (int ring = 0; ring < m->nrings[layer]; ring++)
      for (int k = 0; k < m->nper; k++, n++) {
        double theta = (k + ring_shift(layer, ring)) * step;
        m->x[3 * n + 0] = p->centre[0] + m->ring_radius[layer] * cos(theta);
        m->x[3 * n + 1] = p->centre[1] + m->ring_radius[layer] * sin(theta);
        m->x[3 * n + 2] = p->z0 + ring * m->dz + zoff;
        m->layer[n] = layer;
        m->ring[n] = ring;
      }
  }
}

static void add_bond(lsdem_membrane *m, int i, int j, int kind)
{
  m->bond[2 * m->nbonds] = i;
  m->bond[2 * m->nbonds + 1] = j;
  m->bond_kind[m->nbonds++] = kind;
}

static void add_tri(lsdem_membrane *m, int a, int b, int c, int layer)
{
  m->tri[3 * m->ntris] = a;
  m->tri[3 * m->ntris + 1] = b;
  m->tri[3 * m->ntris + 2] = c;
  m->tri_layer[m->ntris++] = layer;
}

/* In-layer lattice: ring edges, edges to the upper ring, and the up/down triangles
 * (vertex order gives an outward S_T: see lsdem.h). */
static void connect_layer(lsdem_membrane *m, int layer)
{
  int N = m->nper;
  for (int ring = 0; ring < m->nrings[layer]; ring++)
    for (int k = 0; k < N; k++) {
      int a = sphere_index(m, layer, ring, k);
      int b = sphere_index(m, layer, ring, (k + 1) % N);
      add_bond(m, a, b, 3 * layer);
      if (ring + 1 == m->nrings[layer]) continue;
      double s = k + ring_shift(layer, ring);
      int up_r = sphere_index(m, layer, ring + 1, index_at(N, layer, ring + 1, s + 0.5));
      int up_l = sphere_index(m, layer, ring + 1, index_at(N, layer, ring + 1, s - 0.5));
      add_bond(m, a, up_r, 3 * layer + 1);
      add_bond(m, a, up_l, 3 * layer + 2);
      add_tri(m, a, b, up_r, layer);        /* up: base on this ring, apex above */
      int next_r = sphere_index(m, layer, ring + 1,
                                index_at(N, layer, ring + 1, s + 1.5));
      add_tri(m, up_r, b, next_r, layer);   /* down: apex b below, base above */
    }
}

/* Each outer sphere to the three inner spheres around the up hole it covers. */
static void connect_layers(lsdem_membrane *m)
{
  int N = m->nper;
  for (int j = 0; j < m->nrings[1]; j++)
    for (int k = 0; k < N; k++) {
      int o = sphere_index(m, 1, j, k);
      double s = k + ring_shift(1, j);
      add_bond(m, o, sphere_index(m, 0, j, index_at(N, 0, j, s - 0.5)), 6);
      add_bond(m, o, sphere_index(m, 0, j, index_at(N, 0, j, s + 0.5)), 7);
      add_bond(m, o, sphere_index(m, 0, j + 1, index_at(N, 0, j + 1, s)), 8);
    }
}

/* End rings as cap polygons: bottom traversed towards decreasing angle, top increasing. */
static void add_caps(lsdem_membrane *m)
{
  int N = m->nper;
  for (int layer = 0; layer < 2; layer++) {
    if (m->nrings[layer] == 0) continue;
    for (int end = 0; end < 2; end++) {
      int ring = end == 0 ? 0 : m->nrings[layer] - 1;
      for (int k = 0; k < N; k++) {
        int a = sphere_index(m, layer, ring, k);
        int b = sphere_index(m, layer, ring, (k + 1) % N);
        int e = m->ncap_edges++;
        m->cap_edge[2 * e] = end == 0 ? b : a;
        m->cap_edge[2 * e + 1] = end == 0 ? a : b;
        m->cap_layer[e] = layer;
        m->cap_end[e] = end;
      }
    }
  }
}

/* Hoop unit vector t = z x r at the midpoint of (xi, xj), r the horizontal direction away
 * from the axis; zero on the axis. */
static void midpoint_hoop(const double xi[3], const double xj[3], const double axis[2],
                          double t[3])
{
  double mx = 0.5 * (xi[0] + xj[0]) - axis[0], my = 0.5 * (xi[1] + xj[1]) - axis[1];
  double rr = sqrt(mx * mx + my * my);
  t[0] = rr > 0.0 ? -my / rr : 0.0;
  t[1] = rr > 0.0 ? mx / rr : 0.0;
  t[2] = 0.0;
}

/* Rest length and in-surface offset (d.t, d.z) of every bond kind, from the generated
 * geometry (the first bond of a kind; all bonds of a kind are congruent). */
static void bond_kind_rest(lsdem_membrane *m, const lsdem_membrane_params *p)
{
  for (int b = 0; b < m->nbonds; b++) {
    int kind = m->bond_kind[b];
    if (m->kind_used[kind]++) continue;
    const double *xi = m->x + 3 * m->bond[2 * b], *xj = m->x + 3 * m->bond[2 * b + 1];
    double d[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]}, t[3];
    midpoint_hoop(xi, xj, p->centre, t);
    m->kind_r0[kind] = sqrt(lsdem_dot3(d, d));
    m->kind_rest[2 * kind] = lsdem_dot3(d, t);
    m->kind_rest[2 * kind + 1] = d[2];
  }
}

static lsdem_status check_params(const lsdem_membrane_params *p, lsdem_error *err)
{
  if (!(p->specimen_radius > 0 && p->height > 0 && p->rb > 0))
    return lsdem_fail(err, LSDEM_ERR_ARG,
                      "membrane: specimen radius (%g), height (%g) and sphere radius (%g) "
                      "must be positive", p->specimen_radius, p->height, p->rb);
  if (!(isfinite(p->centre[0]) && isfinite(p->centre[1]) && isfinite(p->z0) &&
        isfinite(p->outer_factor)))
    return lsdem_fail(err, LSDEM_ERR_ARG, "membrane: centre, z0 and outer factor must be finite");
  double R = p->specimen_radius + p->rb;
  if (p->rb / R > sin(M_PI / 6.0))
    return lsdem_fail(err, LSDEM_ERR_ARG,
                      "membrane: sphere radius %g too large for specimen radius %g (fewer "
                      "than 6 spheres per ring; need rb <= Rs)", p->rb, p->specimen_radius);
  return LSDEM_OK;
}

static lsdem_status allocate(lsdem_membrane *m, lsdem_error *err)
{
  size_t n = (size_t) m->nspheres, N = (size_t) m->nper;
  size_t nb = N * (3 * (size_t) m->nrings[0] + 3 * (size_t) m->nrings[1] + 3 * (size_t) m->nrings[1]);
  size_t nt = 2 * N * (size_t) (m->nrings[0] - 1 + (m->nrings[1] ? m->nrings[1] - 1 : 0));
  size_t nc = 2 * N * (m->nrings[1] ? 2 : 1);
  m->x = malloc(3 * n * sizeof(double));
  m->layer = malloc(n * sizeof(int));
  m->ring = malloc(n * sizeof(int));
  m->bond = malloc(2 * nb * sizeof(int));
  m->bond_kind = malloc(nb * sizeof(int));
  m->tri = malloc(3 * nt * sizeof(int));
  m->tri_layer = malloc(nt * sizeof(int));
  m->cap_edge = malloc(2 * nc * sizeof(int));
  m->cap_layer = malloc(nc * sizeof(int));
  m->cap_end = malloc(nc * sizeof(int));
  if (!m->x || !m->layer || !m->ring || !m->bond || !m->bond_kind || !m->tri || !m->tri_layer ||
      !m->cap_edge || !m->cap_layer || !m->cap_end) {
    lsdem_membrane_free(m);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "membrane: out of memory for %zu spheres", n);
  }
  return LSDEM_OK;
}

lsdem_status lsdem_membrane_build(const lsdem_membrane_params *p, lsdem_membrane *m,
                                  lsdem_error *err)
{
  memset(m, 0, sizeof(*m));
  lsdem_status st = check_params(p, err);
  if (st != LSDEM_OK) return st;
  double R = p->specimen_radius + p->rb;
  m->nper = (int) lround(M_PI / asin(p->rb / R));
  if (m->nper < 6) m->nper = 6;
  double chord = 2.0 * R * sin(M_PI / m->nper);
  long nr = lround(p->height / (chord * sqrt(3.0) / 2.0)) + 1;
  if (nr < 2) nr = 2;
  if (nr > 1000000)
    return lsdem_fail(err, LSDEM_ERR_ARG, "membrane: height %g / sphere radius %g gives too "
                      "many rings (%ld)", p->height, p->rb, nr);
  m->nrings[0] = (int) nr;
  m->nrings[1] = p->outer_factor > 0 ? m->nrings[0] - 1 : 0;
  m->dz = p->height / (m->nrings[0] - 1);
  m->sphere_radius[0] = p->rb;
  m->sphere_radius[1] = p->outer_factor > 0 ? p->outer_factor * p->rb : 0.0;
  m->ring_radius[0] = R;
  m->ring_radius[1] = p->outer_factor > 0
                          ? outer_ring_radius(R, m->dz, M_PI / m->nper,
                                              m->sphere_radius[0] + m->sphere_radius[1])
                          : 0.0;
  m->nspheres = m->nper * (m->nrings[0] + m->nrings[1]);
  st = allocate(m, err);
  if (st != LSDEM_OK) return st;
  place_spheres(m, p);
  for (int layer = 0; layer < 2; layer++)
    if (m->nrings[layer]) connect_layer(m, layer);
  if (m->nrings[1]) connect_layers(m);
  add_caps(m);
  bond_kind_rest(m, p);
  return LSDEM_OK;
}

void lsdem_membrane_free(lsdem_membrane *m)
{
  free(m->x);
  free(m->layer);
  free(m->ring);
  free(m->bond);
  free(m->bond_kind);
  free(m->tri);
  free(m->tri_layer);
  free(m->cap_edge);
  free(m->cap_layer);
  free(m->cap_end);
  m->x = NULL;
  m->layer = m->ring = m->bond = m->bond_kind = m->tri = m->tri_layer = NULL;
  m->cap_edge = m->cap_layer = m->cap_end = NULL;
}

/* ------------------------------------------------- pressure and volume ---- */

void lsdem_triangle_area_vector(const double a[3], const double b[3], const double c[3],
                                double S[3])
{
  double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  lsdem_cross3(ab, ac, S);
  for (int k = 0; k < 3; k++) S[k] *= 0.5;
}

/* report §2.3.5: p times a third of the triangle's area, along the inward normal */
void lsdem_pressure_vertex_force(const double S[3], double p, double f[3])
{
  for (int k = 0; k < 3; k++) f[k] = -p * S[k] / 3.0;
}

/* report eq 2.30: V = sum_T (1/3) x_T . S_T */
double lsdem_triangle_volume_term(const double a[3], const double b[3], const double c[3])
{
  double S[3], g[3];
  lsdem_triangle_area_vector(a, b, c, S);
  for (int k = 0; k < 3; k++) g[k] = (a[k] + b[k] + c[k]) / 3.0;
  return lsdem_dot3(g, S) / 3.0;
}

void lsdem_cap_edge_accumulate(const double vi[3], const double vj[3], double sum_v[3],
                               double sum_s[3])
{
  double c[3];
  lsdem_cross3(vi, vj, c);
  for (int k = 0; k < 3; k++) {
    sum_v[k] += vi[k];
    sum_s[k] += 0.5 * c[k];
  }
}

/* The fan (g, v_k, v_k+1) has sum_k (1/6) g . (v_k x v_k+1) = (1/3) g . S_cap */
double lsdem_cap_volume_term(const double sum_v[3], int n, const double sum_s[3])
{
  if (n <= 0) return 0.0;
  double g[3] = {sum_v[0] / n, sum_v[1] / n, sum_v[2] / n};
  return lsdem_dot3(g, sum_s) / 3.0;
}

double lsdem_membrane_volume(const lsdem_membrane *m, const double *x, int layer)
{
  double v = 0.0;
  for (int t = 0; t < m->ntris; t++)
    if (m->tri_layer[t] == layer)
      v += lsdem_triangle_volume_term(x + 3 * m->tri[3 * t], x + 3 * m->tri[3 * t + 1],
                                      x + 3 * m->tri[3 * t + 2]);
  for (int end = 0; end < 2; end++) {
    double sv[3] = {0, 0, 0}, ss[3] = {0, 0, 0};
    int n = 0;
    for (int e = 0; e < m->ncap_edges; e++)
      if (m->cap_layer[e] == layer && m->cap_end[e] == end) {
        lsdem_cap_edge_accumulate(x + 3 * m->cap_edge[2 * e], x + 3 * m->cap_edge[2 * e + 1],
                                  sv, ss);
        n++;
      }
    v += lsdem_cap_volume_term(sv, n, ss);
  }
  return v;
}

/* --------------------------------------------------------------- bonds ---- */

/* the membrane's tangential spring (report §2.3.5, Ksbb): the in-surface offset e of the
 * bond from its rest value in the cylinder frame at the midpoint, less its part along u */
static void in_surface_offset(const double xi[3], const double xj[3], const double axis[2],
                              const double rest[2], const double u[3], double delta[3])
{
  const double d[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
  double t[3];
  midpoint_hoop(xi, xj, axis, t);
  double et = lsdem_dot3(d, t) - rest[0], ez = d[2] - rest[1];
  double e[3] = {et * t[0], et * t[1], et * t[2] + ez};
  double eu = lsdem_dot3(e, u);
  for (int k = 0; k < 3; k++) delta[k] = e[k] - eu * u[k];
}

double lsdem_membrane_bond_force(const double xi[3], const double xj[3], const double axis[2],
                                 double kn, double ks, double r0, const double rest[2],
                                 double fj[3])
{
  double u[3], delta[3];
  const double len = lsdem_bond_axis(xi, xj, u);
  fj[0] = fj[1] = fj[2] = 0.0;
  if (len <= 0.0) return 0.0;
  const double energy = lsdem_bond_axial_force(u, len - r0, kn, 0.0, fj);
  in_surface_offset(xi, xj, axis, rest, u, delta);
  for (int k = 0; k < 3; k++) fj[k] -= ks * delta[k];
  return energy + 0.5 * ks * lsdem_dot3(delta, delta);
}

double lsdem_membrane_inset_volume(double V, double A, double H, double rb)
{
  return V - rb * A + M_PI * rb * rb * H;
}
