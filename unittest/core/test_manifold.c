/* test_manifold.c -- the contact manifold as a public type, on its own:
 *   - detection of a node sphere against analytic shapes with a known overlap (a plane
 *     and an exact sphere): every point, normal, depth, node id and relative
 *     velocity against closed forms written here, points in increasing node order, and
 *     exactly the nodes the closed form puts inside;
 *   - the analytic sphere-sphere path: one point in the middle of the overlap;
 *   - the penalty law fed a hand-made manifold gives the forces of eqs 2.2-2.16 computed
 *     here term by term (normal spring and damping with the clamp, shear spring, Coulomb
 *     cap, traction and stride weights, torques on both grains), and reuses a history
 *     entry already advanced at this step;
 *   - master and slave (lsdem_contact_roles);
 *   - a pair's state through exchange/restart records and back. */
#include "contact_fixtures.h"
#include "lsdem_test.h"

#include <math.h>
#include <string.h>

#define NR 12
#define NP 16
#define NNODES (2 + NR * NP)

static double unit_nodes[3 * NNODES];

/* p = x + R node */
static void world_point(const lsdem_pose *pa, const double *node, double p[3])
{
  for (int i = 0; i < 3; i++)
    p[i] = pa->x[i] + pa->R[3 * i] * node[0] + pa->R[3 * i + 1] * node[1] +
           pa->R[3 * i + 2] * node[2];
}

/* eq 2.6 written out: vA + wA x (p - xA) - vB - wB x (p - xB) */
static void relative_velocity(const lsdem_pose *pa, const lsdem_pose *pb, const double p[3],
                              double v[3])
{
  double ra[3], rb[3], wa[3], wb[3];
  for (int i = 0; i < 3; i++) {
    ra[i] = p[i] - pa->x[i];
    rb[i] = p[i] - pb->x[i];
  }
  fix_cross(pa->omega, ra, wa);
  fix_cross(pb->omega, rb, wb);
  for (int i = 0; i < 3; i++) v[i] = pa->v[i] + wa[i] - pb->v[i] - wb[i];
}

/* The closed-form signed distance and outward normal of B at p (world), per kind. */
typedef double (*closed_form)(const double p[3], double n[3]);

static double plane_z0(const double p[3], double n[3])
{
  n[0] = n[1] = 0.0;
  n[2] = 1.0;
  return p[2];
}

static double ball_at_origin(const double p[3], double n[3]) /* radius 1.5 */
{
  const double r = fix_norm(p);
  for (int i = 0; i < 3; i++) n[i] = p[i] / r;
  return r - 1.5;
}

/* Detection of A (node sphere of radius 1 at pa) against B at the world origin (pose
 * pb = identity) checked point by point against the closed form. */
static void check_against(const char *what, const lsdem_shape *B, const lsdem_pose *pb,
                          const lsdem_pose *pa, closed_form phi)
{
  lsdem_shape A = fix_shape(fix_sdf(LSDEM_SDF_ELLIPSOID, 1, 1, 1), NNODES, unit_nodes, 1.0);
  const lsdem_detect_params every = {1, 0.0};
  lsdem_manifold *m = fix_manifold();
  lsdem_detect(&A, pa, B, pb, &every, 1, NULL, NULL, m);
  int expected = 0, k = 0, ok = 1, order = 1;
  for (int node = 0; node < NNODES; node++) {
    double p[3], n[3];
    world_point(pa, &unit_nodes[3 * node], p);
    const double d = phi(p, n);
    if (!(d < 0.0)) continue;
    expected++;
    if (k >= m->n) continue;
    const lsdem_contact_point *c = &m->point[k++];
    double v[3];
    relative_velocity(pa, pb, p, v);
    ok &= c->node == node;
    for (int i = 0; i < 3; i++)
      ok &= fabs(c->point[i] - p[i]) < 1e-12 && fabs(c->normal[i] - n[i]) < 1e-12 &&
            fabs(c->vrel[i] - v[i]) < 1e-12;
    ok &= fabs(c->depth + d) < 1e-12 && c->area == 1.0;
  }
  for (int j = 1; j < m->n; j++) order &= m->point[j].node > m->point[j - 1].node;
  CHECK(m->n == expected && expected >= 3, "%s: %d points, %d nodes inside", what, m->n,
        expected);
  CHECK(ok && order, "%s: a point differs from the closed form", what);
  CHECK(m->stride == 1 && m->ntested >= m->n, "%s: stride %d, %d tested", what, m->stride,
        m->ntested);
  for (int i = 0; i < 3; i++) {
    CHECK_NEAR(m->xa[i], pa->x[i], 0.0);
    CHECK_NEAR(m->dab[i], pa->x[i] - pb->x[i], 0.0);
  }
}

static void test_detection_closed_forms(void)
{
  lsdem_pose pa = fix_pose(0.3, -0.2, 0.82);
  fix_rotation_about(0.3, 1.0, 0.2, 0.9, pa.R);
  pa.v[0] = 0.5;
  pa.v[2] = -0.2;
  pa.omega[1] = 1.5;
  pa.omega[2] = -0.7;
  lsdem_pose pb = fix_pose(0, 0, 0);
  pb.omega[0] = 0.4; /* B turns too: the relative velocity takes wB x (p - xB) */
  pb.v[1] = 0.1;
  const lsdem_shape plane = fix_shape(fix_sdf(LSDEM_SDF_PLANE, 0, 0, 0), 0, NULL, HUGE_VAL);
  check_against("plane", &plane, &pb, &pa, plane_z0);
  const lsdem_shape ball = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, 1.5, 0, 0), 0, NULL, 1.5);
  lsdem_pose near = pa;
  near.x[2] = 2.3; /* overlap 0.2 along z */
  check_against("ball", &ball, &pb, &near, ball_at_origin);
}

/* Two analytic spheres: one point at xA - (ra - d/2) n, n = (xA - xB)/|xA - xB|. */
static void test_sphere_sphere_point(void)
{
  const double ra = 0.7, rb = 1.1;
  lsdem_shape A = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, ra, 0, 0), 0, NULL, ra);
  lsdem_shape B = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, rb, 0, 0), 0, NULL, rb);
  lsdem_pose pa = fix_pose(1.0, 0.9, 0.6), pb = fix_pose(0.1, 0.2, 0.3);
  pa.omega[2] = 2.0;
  const lsdem_detect_params every = {1, 0.0};
  lsdem_manifold *m = fix_manifold();
  CHECK(lsdem_detect(&A, &pa, &B, &pb, &every, 1, NULL, NULL, m) == 1, "sphere pair: %d", m->n);
  double d[3];
  for (int i = 0; i < 3; i++) d[i] = pa.x[i] - pb.x[i];
  const double dist = fix_norm(d), depth = ra + rb - dist;
  const lsdem_contact_point *c = &m->point[0];
  double v[3];
  relative_velocity(&pa, &pb, c->point, v);
  CHECK_REL(c->depth, depth, 1e-14);
  CHECK_REL(c->area, FIX_PI * ra * ra, 1e-14);
  for (int i = 0; i < 3; i++) {
    CHECK_NEAR(c->normal[i], d[i] / dist, 1e-15);
    CHECK_NEAR(c->point[i], pa.x[i] - (ra - 0.5 * depth) * d[i] / dist, 1e-14);
    CHECK_NEAR(c->vrel[i], v[i], 1e-14);
  }
}

/* ------------------------------------------------------------- the law ---- */

typedef struct {
  double f[3], ta[3], tb[3];
} expected_sums;

/* eqs 2.2-2.16 term by term for one point (no carried shear): weight w = stride
 * (per node) or stride * area (traction); fn = kn w d - cn stride vn, clamped; shear
 * s = -ks w dt vt; ft = s - ct stride vt capped at mu fn. */
static void expected_point(const lsdem_contact_point *c, const lsdem_penalty_law *law,
                           double stride, double dt, const double xa[3], const double dab[3],
                           expected_sums *e)
{
  const double w = law->normal == LSDEM_NORMAL_TRACTION ? stride * c->area : stride;
  const double vn = c->vrel[0] * c->normal[0] + c->vrel[1] * c->normal[1] +
                    c->vrel[2] * c->normal[2];
  double fn = law->kn * w * c->depth - law->cn * stride * vn;
  if (fn < 0.0) fn = 0.0;
  double vt[3], ft[3], f[3], ra[3], rb[3], t[3];
  for (int i = 0; i < 3; i++) vt[i] = c->vrel[i] - vn * c->normal[i];
  for (int i = 0; i < 3; i++) ft[i] = -law->ks * w * dt * vt[i] - law->ct * stride * vt[i];
  const double mag = fix_norm(ft);
  if (mag > law->mu * fn)
    for (int i = 0; i < 3; i++) ft[i] *= law->mu * fn / mag;
  for (int i = 0; i < 3; i++) {
    f[i] = fn * c->normal[i] + ft[i];
    ra[i] = c->point[i] - xa[i];
    rb[i] = ra[i] + dab[i];
    e->f[i] += f[i];
  }
  fix_cross(ra, f, t);
  for (int i = 0; i < 3; i++) e->ta[i] += t[i];
  fix_cross(rb, f, t);
  for (int i = 0; i < 3; i++) e->tb[i] -= t[i]; /* the reaction -f on B */
}

static lsdem_contact_point hand_point(int node, double px, double py, double pz, double nx,
                                      double ny, double nz, double depth, double area,
                                      double vx, double vy, double vz)
{
  lsdem_contact_point c;
  memset(&c, 0, sizeof c);
  const double len = sqrt(nx * nx + ny * ny + nz * nz);
  c.node = node;
  c.point[0] = px, c.point[1] = py, c.point[2] = pz;
  c.normal[0] = nx / len, c.normal[1] = ny / len, c.normal[2] = nz / len;
  c.depth = depth;
  c.area = area;
  c.vrel[0] = vx, c.vrel[1] = vy, c.vrel[2] = vz;
  return c;
}

static void test_law_on_hand_made_manifold(void)
{
  lsdem_contact_point pts[4];
  pts[0] = hand_point(3, 0.1, 0.2, -0.9, 0.1, 0.0, 1.0, 0.02, 0.3, 0.4, -0.1, -0.5);
  pts[1] = hand_point(7, -0.4, 0.3, -0.8, -0.2, 0.1, 1.0, 0.01, 0.2, 0.0, 0.3, 0.2);
  pts[2] = hand_point(11, 0.5, -0.5, -0.7, 0.3, -0.2, 1.0, 0.005, 0.5, 2.0, 0.0, -0.05);
  pts[3] = hand_point(12, 0.0, 0.0, -1.0, 0.0, 0.0, 1.0, 1e-4, 0.1, 0.0, 0.0, -40.0);
  for (int law_kind = 0; law_kind < 2; law_kind++)
    for (int stride = 1; stride <= 2; stride++) {
      lsdem_manifold m = lsdem_manifold_over(pts, 4);
      m.n = 4;
      m.stride = stride;
      const double xa[3] = {0.05, -0.02, 0.1}, dab[3] = {0.2, -0.1, 1.9};
      memcpy(m.xa, xa, sizeof xa);
      memcpy(m.dab, dab, sizeof dab);
      m.ntested = 9;
      lsdem_penalty_law law = {1000.0, 800.0, 0.4, 3.0, 0.5, LSDEM_NORMAL_PER_NODE};
      if (law_kind) law.normal = LSDEM_NORMAL_TRACTION;
      const double dt = 1e-3;
      expected_sums e;
      memset(&e, 0, sizeof e);
      for (int k = 0; k < 4; k++) expected_point(&pts[k], &law, stride, dt, xa, dab, &e);
      lsdem_shear_hist out[4];
      int nout = 0;
      lsdem_contact_result r;
      lsdem_penalty_apply(&m, &law, dt, 5, NULL, 0, out, &nout, &r);
      const double scale = fix_norm(e.f);
      for (int i = 0; i < 3; i++) {
        CHECK_NEAR(r.force[i], e.f[i], 1e-12 * scale);
        CHECK_NEAR(r.torque_a[i], e.ta[i], 1e-12 * scale);
        CHECK_NEAR(r.torque_b[i], e.tb[i], 1e-12 * scale);
      }
      CHECK(r.npen == 4 && r.ntested == 9 && nout == 4 && out[2].node == 11 &&
                out[2].stamp == 5,
            "law %d stride %d: %d points, %d tested, %d history", law_kind, stride, r.npen,
            r.ntested, nout);
      CHECK_NEAR(r.max_depth, 0.02, 0.0);
      /* an entry already advanced at this step is reused as is */
      lsdem_shear_hist again[4];
      int nagain = 0;
      lsdem_contact_result r2;
      lsdem_penalty_apply(&m, &law, dt, 5, out, nout, again, &nagain, &r2);
      CHECK(memcmp(r2.force, r.force, sizeof r.force) == 0 && nagain == nout &&
                memcmp(again, out, sizeof *out * (size_t)nout) == 0,
            "second call at the same step changed the shear");
    }
  /* the damping clamp: a point closing slowly but separating fast carries no pull */
  lsdem_contact_point sep = hand_point(0, 0, 0, -1, 0, 0, 1, 1e-4, 1.0, 0, 0, 50.0);
  lsdem_manifold m1 = lsdem_manifold_over(&sep, 1);
  m1.n = 1;
  lsdem_penalty_law damped = {1000.0, 0.0, 0.0, 3.0, 0.0, LSDEM_NORMAL_PER_NODE};
  lsdem_contact_result r;
  lsdem_penalty_apply(&m1, &damped, 1e-3, 1, NULL, 0, NULL, NULL, &r);
  CHECK(r.force[0] == 0.0 && r.force[1] == 0.0 && r.force[2] == 0.0,
        "separating point pulls: %g", r.force[2]);
}

/* ------------------------------------------------------------- roles ---- */

static void test_roles(void)
{
  static double node[3] = {1, 0, 0};
  const lsdem_shape grain = fix_shape(fix_sdf(LSDEM_SDF_BOX, 1, 1, 1), 1, node, 1.8);
  const lsdem_shape ball = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, 1, 0, 0), 0, NULL, 1.0);
  const double kg = lsdem_contact_node_scale(&grain), kb = lsdem_contact_node_scale(&ball);
  CHECK(lsdem_contact_roles(&grain, kg, 3, &grain, kg, 5, LSDEM_ROLES_ONEWAY) == 1.0 &&
            lsdem_contact_roles(&grain, kg, 5, &grain, kg, 3, LSDEM_ROLES_ONEWAY) == 0.0,
        "oneway: the lower id tests");
  CHECK(lsdem_contact_roles(&grain, 1.0, 9, &grain, 2.0, 1, LSDEM_ROLES_ONEWAY) == 1.0 &&
            lsdem_contact_roles(&grain, 2.0, 1, &grain, 1.0, 9, LSDEM_ROLES_ONEWAY) == 0.0 &&
            lsdem_contact_roles(&grain, 2.0, 1, &grain, 1.0, 9, LSDEM_ROLES_ONEWAY_ID) == 1.0,
        "oneway: the finer nodes test whatever the ids (oneway_id: the lower id)");
  CHECK(lsdem_contact_roles(&grain, kg, 5, &grain, kg, 3, LSDEM_ROLES_TWOWAY) == 0.5 &&
            lsdem_contact_roles(&grain, kg, 3, &grain, kg, 5, LSDEM_ROLES_TWOWAY) == 0.5,
        "twoway: both, halved");
  CHECK(lsdem_contact_roles(&ball, kb, 9, &grain, kg, 1, LSDEM_ROLES_TWOWAY) == 1.0 &&
            lsdem_contact_roles(&grain, kg, 1, &ball, kb, 9, LSDEM_ROLES_TWOWAY) == 0.0,
        "a sphere against a grain: the sphere tests");
  CHECK(lsdem_contact_roles(&ball, kb, 2, &ball, kb, 4, LSDEM_ROLES_TWOWAY) == 1.0 &&
            lsdem_contact_roles(&ball, kb, 4, &ball, kb, 2, LSDEM_ROLES_TWOWAY) == 0.0,
        "two spheres: the lower id");
  CHECK(lsdem_contact_roles(&grain, kg, 4, &grain, kg, 4, LSDEM_ROLES_TWOWAY) == 0.0, "self image");
}

/* ------------------------------------------------------------- records ---- */

static void test_state_records(void)
{
  /* three entries with their nodes and samples (the second without a kept cell), in 8
   * words each */
  enum { W = LSDEM_NODELIST_MAX_WORDS, WORDS = 3 * W };
  lsdem_nodelist_entry words[WORDS], back_words[WORDS], *entries = words;
  lsdem_nodelist_head head, back_head;
  lsdem_shear_hist shear[2], back_shear[8];
  lsdem_pair_state st, back;
  memset(&st, 0, sizeof st);
  memset(&head, 0, sizeof head);
  memset(words, 0, sizeof words);
  st.list.valid = 1;
  st.list.head = &head;
  for (int i = 0; i < 9; i++) st.list.head->M[i] = 0.1f * i - 0.3f;
  for (int i = 0; i < 3; i++) st.list.head->t[i] = 1.0f + i;
  st.list.head->built = 123456789012LL;
  st.list.head->radius = 0.0625f;
  st.list.head->stride = 2;
  st.list.head->count = 3;
  st.list.head->words = WORDS;
  st.list.head->cells = 1;
  st.list.entry = entries;
  CHECK(lsdem_nodelist_entry_words(&head) == W && lsdem_nodelist_at(&head, entries, 2) ==
                                                      &entries[2 * W],
        "entry size");
  for (int k = 0; k < 3; k++) {
    lsdem_nodelist_entry *e = lsdem_nodelist_at(&head, entries, k);
    e->node = 10 * k + 1;
    e->cell = k == 1 ? -1 : 1000 + k;
    for (int i = 0; i < 3; i++) lsdem_nodelist_x(e)[i] = k + 0.25 * i;
    for (int j = 0; j < 8; j++) lsdem_nodelist_samples(e)[j] = (float)(0.5 * j - k);
  }
  memset(shear, 0, sizeof shear);
  for (int k = 0; k < 2; k++) {
    shear[k].node = 4 + 7 * k;
    shear[k].stamp = 99 + k;
    for (int i = 0; i < 3; i++) {
      shear[k].shear[i] = 0.01 * (i + 1) * (k + 1);
      shear[k].normal[i] = i == 2 ? 1.0 : 0.0;
    }
  }
  st.shear = shear;
  st.nshear = 2;
  lsdem_state_record rec[8];
  const int n = lsdem_pair_state_encode(&st, rec);
  CHECK(n == lsdem_pair_state_records(&st) && n == 7, "%d records", n);
  CHECK(rec[0].id == -2 && rec[1].id == -1 && rec[2].id == -(1 << 29) + 1 && rec[5].id == 4,
        "record ids %d %d %d %d", rec[0].id, rec[1].id, rec[2].id, rec[5].id);
  CHECK(rec[3].b[1] == 1.25 && rec[3].aux == -1 && rec[4].aux == 1002,
        "node records: the nodes' coordinates and cells");
  memset(&back, 0, sizeof back);
  memset(back_words, 0xff, sizeof back_words);
  back.list.head = &back_head;
  back.list.entry = back_words;
  back.shear = back_shear;
  lsdem_pair_state_decode(rec, n, 40, &back);
  CHECK(back.list.valid && memcmp(&back_head, &head, sizeof head) == 0 &&
            memcmp(back_words, words, sizeof words) == 0,
        "the list came back changed");
  CHECK(back.nshear == 2 && memcmp(back_shear, shear, sizeof shear) == 0,
        "the shear came back changed (%d)", back.nshear);
  /* a shape with fewer nodes: the list's node records name no node of it */
  lsdem_pair_state_decode(rec, n, 1, &back);
  CHECK(!back.list.valid && back.nshear == 2, "list for another shape taken");
  /* shear only (no list) */
  st.list.valid = 0;
  const int ns = lsdem_pair_state_encode(&st, rec);
  lsdem_pair_state_decode(rec, ns, 40, &back);
  CHECK(ns == 2 && !back.list.valid && back.nshear == 2, "shear only: %d records", ns);
}

int main(void)
{
  CHECK(fix_ring_nodes(1.0, NR, NP, unit_nodes) == NNODES, "node count");
  test_detection_closed_forms();
  test_sphere_sphere_point();
  test_law_on_hand_made_manifold();
  test_roles();
  test_state_records();
  return lsdem_test_summary();
}
