/* test_membrane.c -- the triaxial membrane (core/membrane.c): lattice geometry against its
 * construction rules, watertightness of lateral triangles + caps, areas and enclosed
 * volume against closed forms (prismatoid formula and pi R^2 H), pressure forces (closed
 * surface: zero net force; scaling with p and area), the bond force against
 * hand-worked configurations, and the membrane bond as a net bond plus its tangential
 * spring. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <stdlib.h>
#include <string.h>

static double dist(const double *a, const double *b)
{
  double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

static double hdist(const double *a, const double c[2])
{
  return hypot(a[0] - c[0], a[1] - c[1]);
}

static const lsdem_membrane_params P = {10.0, 20.0, {1.0, -2.0}, 3.0, 1.0, 1.1};

static void test_geometry(const lsdem_membrane *m)
{
  double R = P.specimen_radius + P.rb;
  int N = m->nper;
  CHECK(N == (int) lround(M_PI / asin(P.rb / R)), "nper %d", N);
  CHECK(m->nspheres == N * (m->nrings[0] + m->nrings[1]), "sphere count");
  CHECK(m->nrings[1] == m->nrings[0] - 1, "outer rings %d", m->nrings[1]);
  double zmin = 1e300, zmax = -1e300;
  for (int i = 0; i < m->nspheres; i++) {
    if (m->layer[i] != 0) continue;
    CHECK_NEAR(hdist(m->x + 3 * i, P.centre), R, 1e-12);
    zmin = fmin(zmin, m->x[3 * i + 2]);
    zmax = fmax(zmax, m->x[3 * i + 2]);
  }
  CHECK_NEAR(zmin, P.z0, 1e-12);
  CHECK_NEAR(zmax, P.z0 + P.height, 1e-12);
  /* hex spacing: in-ring chord within a rounding of N of 2 rb; ring spacing near
   * chord * sqrt(3)/2 (the height is met exactly by adjusting it) */
  double chord = 2.0 * R * sin(M_PI / N);
  CHECK(fabs(chord - 2.0 * P.rb) < 2.0 * P.rb * (M_PI / N), "chord %g vs 2 rb", chord);
  CHECK(fabs(m->dz / (chord * sqrt(3.0) / 2.0) - 1.0) < 0.5 / (m->nrings[0] - 1) + 1e-12,
        "ring spacing %g vs %g", m->dz, chord * sqrt(3.0) / 2.0);
  /* outer spheres: on their cylinder, outside the inner layer, touching the nearest inner
   * sphere of their hole */
  double contact = P.rb * (1.0 + P.outer_factor);
  int *nin = calloc((size_t) m->nspheres, sizeof(int)), *nint = calloc((size_t) m->nspheres, sizeof(int));
  double *nearest = malloc((size_t) m->nspheres * sizeof(double));
  for (int i = 0; i < m->nspheres; i++) nearest[i] = 1e300;
  CHECK(m->ring_radius[1] > R + P.rb, "outer radius %g", m->ring_radius[1]);
  for (int b = 0; b < m->nbonds; b++) {
    int i = m->bond[2 * b], j = m->bond[2 * b + 1], k = m->bond_kind[b];
    double len = dist(m->x + 3 * i, m->x + 3 * j);
    CHECK_NEAR(len, m->kind_r0[k], 1e-9);
    if (k < 6) {
      CHECK(m->layer[i] == m->layer[j] && m->layer[i] == k / 3, "bond %d layers", b);
      /* between 2 rb (0.85) and the layer's in-ring chord (1.15): the outer lattice has the
       * inner one's ring spacing and sphere count on a larger radius */
      double a = chord * m->ring_radius[m->layer[i]] / R;
      CHECK(len > 0.85 * 2 * P.rb && len < 1.15 * a, "in-layer bond %d length %g vs %g", b, len, a);
      nin[i]++;
      nin[j]++;
    } else {
      CHECK(m->layer[i] == 1 && m->layer[j] == 0, "inter-layer bond %d", b);
      CHECK(len >= contact - 1e-9, "outer sphere overlaps inner: %g < %g", len, contact);
      nearest[i] = fmin(nearest[i], len);
      nint[i]++;
    }
  }
  for (int i = 0; i < m->nspheres; i++) {
    int end = m->ring[i] == 0 || m->ring[i] == m->nrings[m->layer[i]] - 1;
    CHECK(nin[i] == (end ? 4 : 6), "sphere %d (layer %d ring %d) has %d neighbours", i,
          m->layer[i], m->ring[i], nin[i]);
    if (m->layer[i] == 1) {
      CHECK(nint[i] == 3, "outer sphere %d has %d inner bonds", i, nint[i]);
      CHECK_NEAR(nearest[i], contact, 1e-9);
    }
  }
  free(nin);
  free(nint);
  free(nearest);
}

/* Every directed edge of the lateral triangles + caps of a layer appears once and its
 * reverse once: closed and consistently oriented. */
static void test_watertight(const lsdem_membrane *m, int layer)
{
  int n = m->nspheres;
  int *count = calloc((size_t) n * (size_t) n, sizeof(int));
  for (int t = 0; t < m->ntris; t++) {
    if (m->tri_layer[t] != layer) continue;
    for (int e = 0; e < 3; e++) count[m->tri[3 * t + e] * n + m->tri[3 * t + (e + 1) % 3]]++;
  }
  /* caps as fans: only their rim edges matter for closure with the lateral surface */
  for (int e = 0; e < m->ncap_edges; e++)
    if (m->cap_layer[e] == layer) count[m->cap_edge[2 * e] * n + m->cap_edge[2 * e + 1]]++;
  int bad = 0, edges = 0;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) {
      if (count[i * n + j] > 1 || (count[i * n + j] == 1 && count[j * n + i] != 1)) bad++;
      edges += count[i * n + j];
    }
  CHECK(bad == 0, "layer %d: %d edges not closed/oriented", layer, bad);
  CHECK(edges > 0, "layer %d has edges", layer);
  free(count);
}

static void test_area_volume(const lsdem_membrane *m)
{
  int N = m->nper;
  for (int layer = 0; layer < 2; layer++) {
    double R = m->ring_radius[layer], H = m->dz * (m->nrings[layer] - 1), step = 2 * M_PI / N;
    /* closed forms for the lattice: every triangle has base 2R sin(step/2) and height
     * sqrt(dz^2 + (R (1 - cos(step/2)))^2); the solid between two rings is a prismatoid,
     * V = dz/6 (A + 4 Amid + A), A = N/2 R^2 sin(step) the ring polygon, Amid the
     * 2N-gon of lateral edge midpoints (radius R cos(step/4), angle step/2 apart) */
    double tri_area = R * sin(step / 2) * sqrt(m->dz * m->dz + pow(R * (1 - cos(step / 2)), 2));
    double A = 0.5 * N * R * R * sin(step);
    double Amid = N * R * R * pow(cos(step / 4), 2) * sin(step / 2);
    double V = (m->nrings[layer] - 1) * m->dz / 6.0 * (2 * A + 4 * Amid);
    double area = 0.0;
    int ntri = 0;
    for (int t = 0; t < m->ntris; t++) {
      if (m->tri_layer[t] != layer) continue;
      const double *a = m->x + 3 * m->tri[3 * t], *b = m->x + 3 * m->tri[3 * t + 1],
                   *c = m->x + 3 * m->tri[3 * t + 2];
      double S[3];
      lsdem_triangle_area_vector(a, b, c, S);
      double g[3] = {(a[0] + b[0] + c[0]) / 3 - P.centre[0], (a[1] + b[1] + c[1]) / 3 - P.centre[1], 0};
      CHECK(S[0] * g[0] + S[1] * g[1] > 0, "triangle %d points inward", t);
      double sa = sqrt(S[0] * S[0] + S[1] * S[1] + S[2] * S[2]);
      CHECK_REL(sa, tri_area, 1e-9);
      area += sa;
      ntri++;
    }
    CHECK(ntri == 2 * N * (m->nrings[layer] - 1), "layer %d: %d triangles", layer, ntri);
    /* tiling: total ~ 2 pi R H within the inscribed-polygon error (step^2/24 relative) */
    CHECK_REL(area, 2 * M_PI * R * H, step * step / 24 * 1.5);
    double vol = lsdem_membrane_volume(m, m->x, layer);
    CHECK_REL(vol, V, 1e-10);
    /* and pi R^2 H within the discretisation error: polygon area N/2 R^2 sin(2pi/N)
     * < pi R^2 < Amid-ish; V lies between A H and Amid H */
    CHECK(vol > A * H * (1 - 1e-12) && vol < Amid * H * (1 + 1e-12), "volume %g vs [%g, %g]",
          vol, A * H, Amid * H);
    CHECK_REL(vol, M_PI * R * R * H, step * step / 6);
  }
}

/* Volume does not depend on the origin; a layer translated by (7, -3, 11) keeps it. */
static void test_volume_translation(const lsdem_membrane *m)
{
  double *y = malloc(3 * (size_t) m->nspheres * sizeof(double));
  double shift[3] = {7.0, -3.0, 11.0};
  for (int i = 0; i < 3 * m->nspheres; i++) y[i] = m->x[i] + shift[i % 3];
  CHECK_REL(lsdem_membrane_volume(m, y, 0), lsdem_membrane_volume(m, m->x, 0), 1e-12);
  /* a uniform scale by s about any point scales the volume by s^3 */
  for (int i = 0; i < 3 * m->nspheres; i++) y[i] = 1.5 * m->x[i];
  CHECK_REL(lsdem_membrane_volume(m, y, 1), 3.375 * lsdem_membrane_volume(m, m->x, 1), 1e-12);
  free(y);
}

/* Uniform pressure on the closed surface (lateral triangles + cap polygons) gives zero net
 * force; forces scale with p and with area. */
static void test_pressure(const lsdem_membrane *m)
{
  double p = 3.7, net[3] = {0, 0, 0}, lateral = 0.0;
  for (int t = 0; t < m->ntris; t++) {
    if (m->tri_layer[t] != 0) continue;
    const double *a = m->x + 3 * m->tri[3 * t], *b = m->x + 3 * m->tri[3 * t + 1],
                 *c = m->x + 3 * m->tri[3 * t + 2];
    double S[3], f[3], f2[3];
    lsdem_triangle_area_vector(a, b, c, S);
    lsdem_pressure_vertex_force(S, p, f);
    lsdem_pressure_vertex_force(S, 2 * p, f2);
    double sa = sqrt(S[0] * S[0] + S[1] * S[1] + S[2] * S[2]);
    CHECK_REL(sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]), p * sa / 3, 1e-14);
    CHECK_REL(f2[0], 2 * f[0], 1e-15);
    for (int k = 0; k < 3; k++) net[k] += 3 * f[k];
    lateral += 3 * sqrt(f[0] * f[0] + f[1] * f[1]);
  }
  double R = m->ring_radius[0];
  CHECK_REL(lateral, p * 2 * M_PI * R * m->dz * (m->nrings[0] - 1), 0.02);
  /* the lateral surface alone: zero net force (its boundary, the two end rings, are
   * congruent polygons: opposite cap areas) */
  CHECK(fabs(net[0]) + fabs(net[1]) + fabs(net[2]) < 1e-11 * lateral, "lateral net %g %g %g",
        net[0], net[1], net[2]);
  for (int end = 0; end < 2; end++) {
    double sv[3] = {0, 0, 0}, ss[3] = {0, 0, 0}, f[3];
    for (int e = 0; e < m->ncap_edges; e++)
      if (m->cap_layer[e] == 0 && m->cap_end[e] == end)
        lsdem_cap_edge_accumulate(m->x + 3 * m->cap_edge[2 * e],
                                  m->x + 3 * m->cap_edge[2 * e + 1], sv, ss);
    double A = 0.5 * m->nper * R * R * sin(2 * M_PI / m->nper);
    CHECK_REL(ss[2], end == 0 ? -A : A, 1e-12);
    lsdem_pressure_vertex_force(ss, p, f); /* a third of the cap force */
    for (int k = 0; k < 3; k++) net[k] += 3 * f[k];
  }
  CHECK(fabs(net[0]) + fabs(net[1]) + fabs(net[2]) < 1e-11 * lateral, "closed net %g %g %g",
        net[0], net[1], net[2]);
  /* area scaling: a triangle scaled by 2 carries 4 times the force */
  double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, b2[3] = {2, 0, 0}, c2[3] = {0, 2, 0};
  double S[3], S2[3], f[3], f2[3];
  lsdem_triangle_area_vector(a, b, c, S);
  lsdem_triangle_area_vector(a, b2, c2, S2);
  CHECK_NEAR(S[2], 0.5, 1e-15);
  lsdem_pressure_vertex_force(S, p, f);
  lsdem_pressure_vertex_force(S2, p, f2);
  CHECK_NEAR(f[2], -p * 0.5 / 3, 1e-15);
  CHECK_NEAR(f2[2], 4 * f[2], 1e-15);
}

static void test_bond_force(const lsdem_membrane *m)
{
  /* every generated bond is at rest */
  double worst = 0.0;
  for (int b = 0; b < m->nbonds; b++) {
    int k = m->bond_kind[b];
    double f[3];
    double e = lsdem_membrane_bond_force(m->x + 3 * m->bond[2 * b], m->x + 3 * m->bond[2 * b + 1],
                                         P.centre, 10.0, 7.0, m->kind_r0[k], m->kind_rest + 2 * k, f);
    worst = fmax(worst, fabs(f[0]) + fabs(f[1]) + fabs(f[2]) + fabs(e));
  }
  CHECK(worst < 1e-10, "force at rest %g", worst);
  /* rigid rotation about the axis by 0.3 rad and translation along z: still at rest */
  double cs = cos(0.3), sn = sin(0.3);
  worst = 0.0;
  for (int b = 0; b < m->nbonds; b++) {
    int k = m->bond_kind[b];
    double y[2][3], f[3];
    for (int s = 0; s < 2; s++) {
      const double *x = m->x + 3 * m->bond[2 * b + s];
      double dx = x[0] - P.centre[0], dy = x[1] - P.centre[1];
      y[s][0] = P.centre[0] + cs * dx - sn * dy;
      y[s][1] = P.centre[1] + sn * dx + cs * dy;
      y[s][2] = x[2] + 5.0;
    }
    lsdem_membrane_bond_force(y[0], y[1], P.centre, 10.0, 7.0, m->kind_r0[k], m->kind_rest + 2 * k, f);
    worst = fmax(worst, fabs(f[0]) + fabs(f[1]) + fabs(f[2]));
  }
  CHECK(worst < 1e-10, "force after rigid rotation %g", worst);

  /* an axial bond at (10, 0): rest length 1, rest offset (0, 1) */
  double axis[2] = {0, 0}, rest[2] = {0, 1}, xi[3] = {10, 0, 0}, f[3];
  double kn = 5.0, ks = 2.0, eps = 1e-4;
  /* stretch along the bond: normal spring only */
  double xs[3] = {10, 0, 1 + eps};
  double e = lsdem_membrane_bond_force(xi, xs, axis, kn, ks, 1.0, rest, f);
  CHECK_NEAR(f[2], -kn * eps, 1e-15);
  CHECK_NEAR(f[0] + f[1], 0.0, 1e-15);
  CHECK_NEAR(e, 0.5 * kn * eps * eps, 1e-18);
  /* hoop shear: tangential spring -ks eps along the hoop direction (+y here), to O(eps^2) */
  double xh[3] = {10, eps, 1};
  lsdem_membrane_bond_force(xi, xh, axis, kn, ks, 1.0, rest, f);
  CHECK_NEAR(f[1], -ks * eps, 10 * (kn + ks) * eps * eps);
  CHECK_NEAR(f[0], 0.0, 10 * (kn + ks) * eps * eps);
  /* radial (bulging) displacement: neither spring to first order */
  double xr[3] = {10 + eps, 0, 1};
  lsdem_membrane_bond_force(xi, xr, axis, kn, ks, 1.0, rest, f);
  CHECK(fabs(f[0]) + fabs(f[1]) + fabs(f[2]) < 10 * (kn + ks) * eps * eps, "bulge force %g %g %g",
        f[0], f[1], f[2]);
  /* a finite bulge tilt of 0.2 rad at constant length: only second-order tangential force
   * ks * L (1 - cos t) sin t (the axial offset shrinks by L(1 - cos t)) */
  double tl = 0.2, xt[3] = {10 + sin(tl), 0, cos(tl)};
  lsdem_membrane_bond_force(xi, xt, axis, kn, ks, 1.0, rest, f);
  double mag = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  CHECK_NEAR(mag, ks * (1 - cos(tl)) * sin(tl), 1e-12);
}

/* The membrane is a net: a membrane bond with its tangential stiffness 0 gives the net
 * bond's force and energy (lsdem_net_bond_force, undamped) bit for bit, on every generated
 * bond moved off its rest geometry; with ks > 0 the difference is the tangential spring
 * alone, perpendicular to the bond. */
static void test_membrane_is_net(const lsdem_membrane *m)
{
  const double kn = 10.0, ks = 7.0, v0[3] = {0.3, -1.1, 0.7}, v1[3] = {-2.0, 0.4, 0.9};
  int same = 0, perpendicular = 0;
  unsigned seed = 12345u;
  for (int b = 0; b < m->nbonds; b++) {
    const int k = m->bond_kind[b];
    double y[2][3], fm[3], fn[3], ft[3], stretch;
    for (int s = 0; s < 2; s++)
      for (int c = 0; c < 3; c++) {
        seed = seed * 1103515245u + 12345u;
        y[s][c] = m->x[3 * m->bond[2 * b + s] + c] + 0.2 * ((seed >> 8) / 16777216.0 - 0.5);
      }
    const double rest[2] = {m->kind_rest[2 * k], m->kind_rest[2 * k + 1]};
    const double em = lsdem_membrane_bond_force(y[0], y[1], P.centre, kn, 0.0, m->kind_r0[k],
                                                rest, fm);
    const double en = lsdem_net_bond_force(y[0], y[1], v0, v1, kn, m->kind_r0[k], 0.0, fn,
                                           &stretch);
    same += em == en && fm[0] == fn[0] && fm[1] == fn[1] && fm[2] == fn[2];
    lsdem_membrane_bond_force(y[0], y[1], P.centre, kn, ks, m->kind_r0[k], rest, ft);
    double u[3], dt[3] = {ft[0] - fn[0], ft[1] - fn[1], ft[2] - fn[2]};
    lsdem_bond_axis(y[0], y[1], u);
    perpendicular += fabs(dt[0] * u[0] + dt[1] * u[1] + dt[2] * u[2]) <= 1e-12 * ks;
  }
  CHECK(same == m->nbonds, "membrane bonds with ks = 0 equal to net bonds: %d of %d", same,
        m->nbonds);
  CHECK(perpendicular == m->nbonds, "tangential springs perpendicular to their bonds: %d of %d",
        perpendicular, m->nbonds);
}

static void test_bad_input(void)
{
  lsdem_membrane m;
  lsdem_error err;
  lsdem_membrane_params q = P;
  q.rb = 11.0;
  CHECK(lsdem_membrane_build(&q, &m, &err) == LSDEM_ERR_ARG && strstr(err.msg, "too large"),
        "rb > Rs: %s", err.msg);
  q = P;
  q.height = -1;
  CHECK(lsdem_membrane_build(&q, &m, &err) == LSDEM_ERR_ARG, "negative height");
  /* single layer */
  q = P;
  q.outer_factor = 0;
  CHECK(lsdem_membrane_build(&q, &m, &err) == LSDEM_OK, "single layer: %s", err.msg);
  CHECK(m.nrings[1] == 0 && m.nspheres == m.nper * m.nrings[0], "single layer counts");
  CHECK(m.nbonds == m.nper * m.nrings[0] + 2 * m.nper * (m.nrings[0] - 1), "single layer bonds");
  lsdem_membrane_free(&m);
}

/* The inset volume of a circular cylinder of radius R + rb is the cylinder of radius R. */
static void test_inset_volume(void)
{
  const double R = 7.0, rb = 0.8, H = 3.5, Rc = R + rb;
  const double V = M_PI * Rc * Rc * H, A = 2.0 * M_PI * Rc * H;
  CHECK_REL(lsdem_membrane_inset_volume(V, A, H, rb), M_PI * R * R * H, 1e-14);
}

int main(void)
{
  lsdem_membrane m;
  lsdem_error err;
  CHECK(lsdem_membrane_build(&P, &m, &err) == LSDEM_OK, "build: %s", err.msg);
  test_geometry(&m);
  test_watertight(&m, 0);
  test_watertight(&m, 1);
  test_area_volume(&m);
  test_volume_translation(&m);
  test_pressure(&m);
  test_bond_force(&m);
  test_membrane_is_net(&m);
  test_inset_volume();
  lsdem_membrane_free(&m);
  test_bad_input();
  return lsdem_test_summary();
}
