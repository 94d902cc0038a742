/* test_sphere_pair.c -- the sphere kernel lsdem_contact_sphere (report §2.3.5 with the
 * penalty law, eqs 2.2-2.16):
 *   - against closed forms worked out by hand below: overlap, normal, contact point,
 *     normal force with damping, the tangential spring's first and second step, the
 *     Coulomb cap and its reset spring, the spring turned with the normal (eq 2.8), and
 *     the torques on both spheres;
 *   - against the general path (lsdem_detect, then lsdem_penalty_apply on its manifold)
 *     on random pairs (the partner a sphere, an ellipsoid, a plane wall or a grid), laws
 *     and histories: the same bits. */
#include "contact_fixtures.h"
#include "lsdem_test.h"

#include <string.h>

/* A at (1.4, 0, 0), radius 1, moving (-0.2, 0.3, 0) and spinning 0.5 about z; B at the
 * origin, radius 0.5, spinning -1 about z. Overlap d = 1.5 - 1.4 = 0.1 along n = x; the
 * point p = xA - (1 - 0.05) n = (0.45, 0, 0); arms rA = (-0.95, 0, 0), rB = (0.45, 0, 0).
 * A's material point moves vA + wA x rA = (-0.2, -0.175, 0), B's wB x rB = (0, -0.45, 0):
 * vrel = (-0.2, 0.275, 0), vn = -0.2, vt = (0, 0.275, 0). */
static const double RA = 1.0, RB = 0.5;

static void poses(lsdem_pose *pa, lsdem_pose *pb)
{
  *pa = fix_pose(1.4, 0.0, 0.0);
  *pb = fix_pose(0.0, 0.0, 0.0);
  pa->v[0] = -0.2;
  pa->v[1] = 0.3;
  pa->omega[2] = 0.5;
  pb->omega[2] = -1.0;
}

static lsdem_penalty_law law_of(double mu)
{
  lsdem_penalty_law law = {1000.0, 800.0, mu, 5.0, 2.0, LSDEM_NORMAL_PER_NODE};
  return law;
}

static void check_vec(const double *v, double x, double y, double z, double tol, const char *what)
{
  CHECK(fabs(v[0] - x) <= tol && fabs(v[1] - y) <= tol && fabs(v[2] - z) <= tol,
        "%s = (%.17g %.17g %.17g), expected (%.17g %.17g %.17g)", what, v[0], v[1], v[2], x,
        y, z);
}

static void test_closed_form(void)
{
  const double dt = 1e-3, tol = 1e-12;
  const lsdem_shape B = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, RB, 0, 0), 0, NULL, RB);
  lsdem_pose pa, pb;
  poses(&pa, &pb);
  lsdem_penalty_law law = law_of(0.4);
  lsdem_shear_hist h1, h2;
  lsdem_contact_result r;
  int n = -1;

  /* step 1, a new contact: fn = kn d - cn vn = 100 + 1 (eq 2.2); s = -ks dt vt =
   * (0, -0.22, 0) (eqs 2.7-2.8); ft = s - ct vt = (0, -0.77, 0), below mu fn = 40.4 */
  CHECK(lsdem_contact_sphere(RA, &pa, &B, &pb, &law, dt, 1, NULL, 0, &h1, &n, &r) == 1,
        "in contact");
  CHECK(r.npen == 1 && r.ntested == 1 && n == 1, "npen %d ntested %d n %d", r.npen, r.ntested,
        n);
  CHECK_NEAR(r.max_depth, 0.1, tol);
  check_vec(r.point, 0.45, 0.0, 0.0, tol, "point");
  check_vec(r.force, 101.0, -0.77, 0.0, tol, "force");
  /* eq 2.16: rA x f = (0, 0, 0.95 * 0.77); on B, rB x (-f) = (0, 0, 0.45 * 0.77) */
  check_vec(r.torque_a, 0.0, 0.0, 0.7315, tol, "torque_a");
  check_vec(r.torque_b, 0.0, 0.0, 0.3465, tol, "torque_b");
  check_vec(h1.shear, 0.0, -0.22, 0.0, tol, "spring");
  check_vec(h1.normal, 1.0, 0.0, 0.0, tol, "spring normal");
  CHECK(h1.node == 0 && h1.stamp == 1, "entry node %d stamp %lld", h1.node,
        (long long)h1.stamp);

  /* the same step again (a second force call): the entry is taken as is */
  lsdem_contact_sphere(RA, &pa, &B, &pb, &law, dt, 1, &h1, 1, &h2, &n, &r);
  check_vec(h2.shear, 0.0, -0.22, 0.0, tol, "spring, same step");

  /* step 2, same geometry: s = (0, -0.44, 0), ft = (0, -0.99, 0) */
  lsdem_contact_sphere(RA, &pa, &B, &pb, &law, dt, 2, &h1, 1, &h2, &n, &r);
  check_vec(h2.shear, 0.0, -0.44, 0.0, tol, "spring, step 2");
  check_vec(r.force, 101.0, -0.99, 0.0, tol, "force, step 2");

  /* the cap (eq 2.10): mu = 0.005 gives mu fn = 0.505 < 0.77: ft = (0, -0.505, 0) and the
   * spring is reset to ft + ct vt = (0, 0.045, 0) */
  law = law_of(0.005);
  lsdem_contact_sphere(RA, &pa, &B, &pb, &law, dt, 1, NULL, 0, &h2, &n, &r);
  check_vec(r.force, 101.0, -0.505, 0.0, tol, "capped force");
  check_vec(h2.shear, 0.0, 0.045, 0.0, tol, "reset spring");

  /* the spring turned with the normal (eq 2.8): at rest, A moved to (0, 1.4, 0), the
   * normal turned from x to y by a quarter turn about z, so h1's (0, -0.22, 0) becomes
   * (0.22, 0, 0); fn = kn d = 100 along y */
  law = law_of(0.4);
  pa = fix_pose(0.0, 1.4, 0.0);
  pb = fix_pose(0.0, 0.0, 0.0);
  lsdem_contact_sphere(RA, &pa, &B, &pb, &law, dt, 2, &h1, 1, &h2, &n, &r);
  check_vec(h2.shear, 0.22, 0.0, 0.0, tol, "turned spring");
  check_vec(h2.normal, 0.0, 1.0, 0.0, tol, "new normal");
  check_vec(r.force, 0.22, 100.0, 0.0, tol, "force with the turned spring");

  /* apart: no contact, nothing kept, the result all zero */
  pa = fix_pose(1.5, 0.0, 0.0);
  CHECK(lsdem_contact_sphere(RA, &pa, &B, &pb, &law, dt, 3, &h1, 1, &h2, &n, &r) == 0 &&
            n == 0 && r.npen == 0 && r.ntested == 0 && r.force[0] == 0.0,
        "touching spheres (d = 0) are apart");
}

/* The general path on the same pair: detection's sphere path, then the law. */
static void general(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                    const lsdem_pose *pb, const lsdem_penalty_law *law, double dt, int64_t step,
                    const lsdem_shear_hist *in, int n_in, lsdem_shear_hist *out, int *n_out,
                    lsdem_contact_result *res)
{
  const lsdem_detect_params det = {1, 0.0};
  lsdem_contact_point pt;
  lsdem_manifold m = lsdem_manifold_over(&pt, 1);
  lsdem_detect(A, pa, B, pb, &det, step, NULL, NULL, &m);
  lsdem_penalty_apply(&m, law, dt, step, in, n_in, out, n_out, res);
}

static double srange(double lo, double hi) { return lo + (hi - lo) * urand(); }

/* Partners of a sphere: another sphere (closed form), an ellipsoid (exact distance), a
 * plane wall, and an ellipsoid sampled on a grid (a centre outside its box takes the
 * descent over the box). */
enum { PARTNER_KINDS = 4 };
static const char *const KIND_NAME[PARTNER_KINDS] = {"sphere", "ellipsoid", "plane", "grid"};

static void test_same_as_general_path(void)
{
  const double ell[3] = {1.2, 0.9, 0.6};
  lsdem_sdf grid;
  lsdem_error err;
  CHECK(fix_ellipsoid_grid(ell, &grid, &err) == LSDEM_OK, "grid: %s", err.msg);
  int contacts[PARTNER_KINDS] = {0}, same = 0, descents = 0;
  const int trials = 8000;
  for (int t = 0; t < trials; t++) {
    const int kind = t % PARTNER_KINDS;
    const double ra = srange(0.3, 1.5), rb = srange(0.5, 2.0);
    lsdem_shape A = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, ra, 0, 0), 0, NULL, ra);
    lsdem_shape B;
    double reach; /* centre distances that may touch, from B's centre */
    if (kind == 0) {
      B = fix_shape(fix_sdf(LSDEM_SDF_SPHERE, rb, 0, 0), 0, NULL, rb);
      reach = ra + rb;
    } else if (kind == 1) {
      B = fix_shape(fix_sdf(LSDEM_SDF_ELLIPSOID, ell[0], ell[1], ell[2]), 0, NULL, ell[0]);
      reach = ra + ell[0];
    } else if (kind == 2) {
      B = fix_shape(fix_sdf(LSDEM_SDF_PLANE, 0, 0, 0), 0, NULL, HUGE_VAL);
      reach = 1.2 * ra;
    } else {
      B = fix_shape(grid, 0, NULL, 6.0); /* a loose bound: centres outside the grid's box */
      reach = ra + (t % 8 == 3 ? 6.0 : ell[0]);
    }
    lsdem_pose pb = fix_pose(srand1(), srand1(), srand1()), pa = pb;
    fix_rotation_about(srand1(), srand1(), srand1(), 3 * srand1(), pb.R);
    double dir[3] = {srand1(), srand1(), srand1()};
    const double len = fix_norm(dir), dist = reach * srange(0.3, 1.05);
    for (int i = 0; i < 3; i++) {
      pa.x[i] = pb.x[i] + dist * dir[i] / len;
      pa.v[i] = srand1();
      pb.v[i] = srand1();
      pa.omega[i] = 3 * srand1();
      pb.omega[i] = 3 * srand1();
    }
    lsdem_penalty_law law = {srange(1, 1e3), srange(0, 1e3), t % 5 ? srange(0, 1) : 0.0,
                             t % 3 ? srange(0, 50) : 0.0, t % 7 ? srange(0, 20) : 0.0,
                             t % 2 ? LSDEM_NORMAL_PER_NODE : LSDEM_NORMAL_TRACTION};
    /* the pair's entry of the last step (or of this step, or none) */
    lsdem_shear_hist in;
    memset(&in, 0, sizeof in);
    for (int i = 0; i < 3; i++) {
      in.shear[i] = srand1();
      in.normal[i] = srand1();
    }
    const double nl = fix_norm(in.normal);
    for (int i = 0; i < 3; i++) in.normal[i] /= nl;
    const int64_t step = 10;
    in.stamp = t % 9 ? step - 1 : step;
    const int n_in = t % 6 ? 1 : 0;
    lsdem_shear_hist out_fast, out_general;
    memset(&out_fast, 0x5a, sizeof out_fast);
    memset(&out_general, 0x5a, sizeof out_general);
    int n_fast = -1, n_general = -1;
    lsdem_contact_result fast, gen;
    const int c = lsdem_contact_sphere(ra, &pa, &B, &pb, &law, 1e-3, step, &in, n_in, &out_fast,
                                       &n_fast, &fast);
    general(&A, &pa, &B, &pb, &law, 1e-3, step, &in, n_in, &out_general, &n_general, &gen);
    contacts[kind] += c;
    descents += fast.ntested > 1;
    const int kept = n_fast == n_general &&
                     (n_fast == 0 || memcmp(&out_fast, &out_general, sizeof out_fast) == 0);
    /* out of contact only the counts are the law's (the general path's torque_b is then
     * -0 - dab x 0, of either sign) */
    const int equal = c ? memcmp(&fast, &gen, sizeof fast) == 0
                        : gen.npen == 0 && fast.npen == 0 && fast.ntested == gen.ntested;
    same += kept && equal;
    if (!(kept && equal))
      CHECK(0, "trial %d (%s): the kernel differs from the general path (contact %d, n %d %d, "
               "ntested %d %d, force %.17g %.17g)", t, KIND_NAME[kind], c, n_fast, n_general,
            fast.ntested, gen.ntested, fast.force[0], gen.force[0]);
  }
  for (int k = 0; k < PARTNER_KINDS; k++)
    CHECK(contacts[k] > trials / PARTNER_KINDS / 20 && contacts[k] < trials / PARTNER_KINDS,
          "%s: %d contacts of %d", KIND_NAME[k], contacts[k], trials / PARTNER_KINDS);
  CHECK(descents > 0, "no centre outside the grid's box");
  CHECK(same == trials, "%d of %d the same", same, trials);
}

int main(void)
{
  test_closed_form();
  test_same_as_general_path();
  return lsdem_test_summary();
}
