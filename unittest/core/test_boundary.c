/* Walls (core/boundary): planes and cylindrical containers against closed forms written
 * here from the geometry (distance and normal of points, the bounding-sphere test, the
 * crossing test and its cheap rejection, the pose of a moving wall at time t, the pivoting
 * platen), and bad input refused with the parameter named. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <math.h>
#include <string.h>

static double dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* the plane through x0 with normal m (not unit): d = (p - x0) . m / |m|, normal m / |m|,
 * for random points and normals; the wall frame is proper and orthonormal with body z
 * the unit normal */
static void test_plane(void)
{
  for (int trial = 0; trial < 50; trial++) {
    const double x0[3] = {srand1(), srand1(), srand1()};
    const double m[3] = {3 * srand1(), 3 * srand1(), 3 * srand1()};
    lsdem_boundary b;
    CHECK(lsdem_boundary_plane(&b, x0, m, NULL) == LSDEM_OK, "plane");
    const double len = sqrt(dot(m, m));
    const double u[3] = {m[0] / len, m[1] / len, m[2] / len};
    const double *R = b.pose.R;
    for (int r = 0; r < 3; r++) CHECK_NEAR(R[3 * r + 2], u[r], 1e-15);
    double det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) +
                 R[2] * (R[3] * R[7] - R[4] * R[6]);
    CHECK_NEAR(det, 1.0, 1e-14);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        const double cij = R[i] * R[j] + R[3 + i] * R[3 + j] + R[6 + i] * R[6 + j];
        CHECK_NEAR(cij, i == j ? 1.0 : 0.0, 1e-15);
      }
    const double p[3] = {4 * srand1(), 4 * srand1(), 4 * srand1()};
    const double rel[3] = {p[0] - x0[0], p[1] - x0[1], p[2] - x0[2]};
    double n[3];
    CHECK_NEAR(lsdem_boundary_distance(&b, &b.pose, p, n), dot(rel, m) / len, 1e-14);
    for (int k = 0; k < 3; k++) CHECK_NEAR(n[k], u[k], 1e-15);
  }
  /* an axis-aligned floor: distance is the height, normal +z, behind is negative */
  lsdem_boundary f;
  const double o[3] = {0.0, 0.0, -1.0}, up[3] = {0.0, 0.0, 2.0};
  CHECK(lsdem_boundary_plane(&f, o, up, NULL) == LSDEM_OK, "floor");
  const double above[3] = {5.0, -3.0, 0.5}, below[3] = {0.0, 0.0, -1.25};
  CHECK(lsdem_boundary_distance(&f, &f.pose, above, NULL) == 1.5, "height above the floor");
  CHECK(lsdem_boundary_distance(&f, &f.pose, below, NULL) == -0.25, "depth behind the floor");
}

/* a container about y through (x, z) = (1, -2) with radius 3: d = 3 - rho,
 * rho = |(px - 1, pz + 2)|, normal towards the axis, (1 - px, 0, -2 - pz) / rho */
static void test_cylinder(void)
{
  lsdem_boundary b;
  const double c[2] = {1.0, -2.0};
  CHECK(lsdem_boundary_cylinder(&b, 1, c, 3.0, NULL) == LSDEM_OK, "cylinder");
  for (int trial = 0; trial < 50; trial++) {
    const double p[3] = {1.0 + 5 * srand1(), 10 * srand1(), -2.0 + 5 * srand1()};
    const double rho = hypot(p[0] - 1.0, p[2] + 2.0);
    double n[3];
    CHECK_NEAR(lsdem_boundary_distance(&b, &b.pose, p, n), 3.0 - rho, 1e-14);
    CHECK_NEAR(n[0], (1.0 - p[0]) / rho, 1e-14);
    CHECK_NEAR(n[1], 0.0, 1e-15);
    CHECK_NEAR(n[2], (-2.0 - p[2]) / rho, 1e-14);
  }
  /* the wall frame: body z along world y, proper */
  const double *R = b.pose.R;
  CHECK(R[3 * 1 + 2] == 1.0 && R[3 * 2 + 0] == 1.0 && R[3 * 0 + 1] == 1.0,
        "frame body x,y,z -> world z,x,y");
  /* each axis: the point half-way to the wall along the other two coordinates */
  for (int axis = 0; axis < 3; axis++) {
    const double cc[2] = {0.5, -0.5};
    CHECK(lsdem_boundary_cylinder(&b, axis, cc, 2.0, NULL) == LSDEM_OK, "axis %d", axis);
    const int o0 = axis == 0 ? 1 : 0, o1 = axis == 2 ? 1 : 2;
    double p[3];
    p[axis] = 7.0;
    p[o0] = 0.5 + 1.0;
    p[o1] = -0.5;
    double n[3];
    CHECK_NEAR(lsdem_boundary_distance(&b, &b.pose, p, n), 1.0, 1e-15);
    CHECK_NEAR(n[o0], -1.0, 1e-15);
  }
}

/* may touch: a sphere of radius r about c reaches the solid iff phi(c) < r */
static void test_may_touch(void)
{
  lsdem_boundary f;
  const double o[3] = {0.0, 0.0, 0.0}, up[3] = {0.0, 0.0, 1.0};
  lsdem_boundary_plane(&f, o, up, NULL);
  const double c[3] = {0.3, 0.4, 0.5};
  CHECK(lsdem_boundary_may_touch(&f, &f.pose, c, 0.5000001), "sphere reaching the floor");
  CHECK(!lsdem_boundary_may_touch(&f, &f.pose, c, 0.5), "sphere just touching: no overlap");
  CHECK(!lsdem_boundary_may_touch(&f, &f.pose, c, 0.4999), "sphere above the floor");
  const double under[3] = {0.0, 0.0, -3.0};
  CHECK(lsdem_boundary_may_touch(&f, &f.pose, under, 0.0), "a centre behind the floor");
  /* container of radius 2 about z: a sphere of radius 0.5 at rho = 1.4 stays clear, at
   * rho = 1.6 reaches the wall */
  lsdem_boundary can;
  const double cz[2] = {0.0, 0.0};
  lsdem_boundary_cylinder(&can, 2, cz, 2.0, NULL);
  const double in[3] = {1.4 / sqrt(2.0), 1.4 / sqrt(2.0), 9.0};
  const double out[3] = {0.0, -1.6, -9.0};
  CHECK(!lsdem_boundary_may_touch(&can, &can.pose, in, 0.5), "clear of the container");
  CHECK(lsdem_boundary_may_touch(&can, &can.pose, out, 0.5), "reaches the container");
}

/* crossing: d < 0, or d + vn dt < 0 with vn the normal velocity relative to the wall */
static void test_crossing(void)
{
  lsdem_boundary f;
  const double o[3] = {0.0, 0.0, 1.0}, up[3] = {0.0, 0.0, 1.0};
  lsdem_boundary_plane(&f, o, up, NULL);
  const double c[3] = {0.0, 0.0, 1.2}, dt = 0.1;
  double d, vn;
  const double slow[3] = {5.0, 0.0, -1.0}, fast[3] = {0.0, 0.0, -3.0}, away[3] = {0, 0, 1};
  CHECK(!lsdem_boundary_crossing(&f, &f.pose, c, slow, dt, &d, &vn), "0.2 - 0.1 stays");
  CHECK_NEAR(d, 0.2, 1e-15);
  CHECK_NEAR(vn, -1.0, 0.0);
  CHECK(lsdem_boundary_crossing(&f, &f.pose, c, fast, dt, &d, &vn), "0.2 - 0.3 crosses");
  CHECK_NEAR(vn, -3.0, 0.0);
  const double behind[3] = {0.0, 0.0, 0.9};
  CHECK(lsdem_boundary_crossing(&f, &f.pose, behind, away, dt, &d, NULL), "behind the wall");
  CHECK_NEAR(d, -0.1, 1e-15);
  /* the wall comes up at 2.5: relative vn = -1 - 2.5, 0.2 - 0.35 < 0 */
  f.pose.v[2] = 2.5;
  CHECK(lsdem_boundary_crossing(&f, &f.pose, c, slow, dt, &d, &vn), "wall catching up");
  CHECK_NEAR(vn, -3.5, 1e-15);
  /* a wall turning at omega = (0, w, 0) about its point moves at omega x (c - x) there:
   * c - x = (1, 0, 0.2) -> (0.2 w, 0, -w); with w = 3 and the grain at rest vn = +3 */
  f.pose.v[2] = 0.0;
  f.pose.omega[1] = 3.0;
  const double c2[3] = {1.0, 0.0, 1.2}, rest[3] = {0.0, 0.0, 0.0};
  CHECK(!lsdem_boundary_crossing(&f, &f.pose, c2, rest, dt, &d, &vn), "turning away");
  CHECK_NEAR(vn, 3.0, 1e-15);
  f.pose.omega[1] = -3.0;
  CHECK(lsdem_boundary_crossing(&f, &f.pose, c2, rest, dt, &d, &vn), "turning into it");
  const double nan3[3] = {NAN, 0.0, 0.0};
  CHECK(lsdem_boundary_crossing(&f, &f.pose, c2, nan3, dt, &d, &vn), "NaN counts as crossed");
  /* container: moving outwards towards the wall */
  lsdem_boundary can;
  const double cz[2] = {0.0, 0.0};
  lsdem_boundary_cylinder(&can, 2, cz, 1.0, NULL);
  const double p[3] = {0.0, 0.9, 0.0}, vout[3] = {0.0, 2.0, 0.0};
  CHECK(lsdem_boundary_crossing(&can, &can.pose, p, vout, dt, &d, &vn), "out of the can");
  CHECK_NEAR(d, 0.1, 1e-15);
  CHECK_NEAR(vn, -2.0, 1e-15);
}

/* the cheap rejection of the crossing test never clears a grain that crosses: random
 * centres and velocities against a moving, turning plane and a container, over many
 * steps' worth of motion; it clears most of those far from the wall; NaN is never clear */
static void test_clear_of_crossing(void)
{
  lsdem_boundary walls[2];
  const double o[3] = {0.1, -0.2, 0.3}, m[3] = {0.3, -0.5, 1.0}, cz[2] = {0.0, 0.0};
  lsdem_boundary_plane(&walls[0], o, m, NULL);
  lsdem_boundary_cylinder(&walls[1], 2, cz, 2.0, NULL);
  int cleared = 0, far = 0;
  for (int k = 0; k < 2; k++) {
    lsdem_boundary *b = &walls[k];
    for (int trial = 0; trial < 4000; trial++) {
      for (int d = 0; d < 3; d++) {
        b->pose.v[d] = trial % 3 == 0 ? 0.0 : srand1();
        b->pose.omega[d] = trial % 5 == 0 ? 0.0 : 0.5 * srand1();
      }
      const double c[3] = {1.9 * srand1(), 1.9 * srand1(), 1.9 * srand1()};
      const double v[3] = {10 * srand1(), 10 * srand1(), 10 * srand1()}, dt = 0.05;
      const double phi = lsdem_boundary_distance(b, &b->pose, c, NULL);
      const int clear = lsdem_boundary_clear_of_crossing(b, &b->pose, c, phi, v, dt);
      if (clear)
        CHECK(!lsdem_boundary_crossing(b, &b->pose, c, v, dt, NULL, NULL),
              "wall %d trial %d: cleared but crosses (phi %g)", k, trial, phi);
      if (phi > 2.0 * dt * (sqrt(dot(v, v)) + 5.0)) {
        far++;
        cleared += clear;
      }
    }
  }
  CHECK(far > 100 && cleared == far, "every centre far from the wall cleared: %d of %d",
        cleared, far);
  const double c[3] = {0.0, 0.0, 5.0}, v[3] = {0.0, 0.0, 0.0};
  CHECK(!lsdem_boundary_clear_of_crossing(&walls[0], &walls[0].pose, c, NAN, v, 0.1),
        "NaN is never clear");
}

/* a wall at constant velocity v: after n advances of dt its point is x0 + n dt v; the pose
 * at s is that moved by s v (the distance of a fixed point drops by s v.n), s = 0 the pose
 * as stored, and moving back one step returns the previous pose */
static void test_moving_pose(void)
{
  lsdem_boundary b;
  const double x0[3] = {0.5, -1.0, 2.0}, m[3] = {1.0, 2.0, -2.0}, dt = 1e-3;
  lsdem_boundary_plane(&b, x0, m, NULL);
  const double v[3] = {0.3, -0.2, 0.1};
  memcpy(b.pose.v, v, sizeof v);
  const int nstep = 250;
  lsdem_pose before;
  for (int n = 0; n < nstep; n++) {
    before = b.pose;
    lsdem_boundary_advance(&b, dt);
  }
  for (int k = 0; k < 3; k++) CHECK_NEAR(b.pose.x[k], x0[k] + nstep * dt * v[k], 1e-12);
  lsdem_pose now, back, later;
  lsdem_boundary_pose_at(&b, 0.0, &now);
  CHECK(memcmp(&now, &b.pose, sizeof now) == 0, "pose at s = 0 is the stored pose");
  lsdem_boundary_pose_at(&b, -dt, &back);
  for (int k = 0; k < 3; k++) CHECK_NEAR(back.x[k], before.x[k], 1e-15);
  const double s = 0.7, p[3] = {1.0, 1.0, 1.0};
  lsdem_boundary_pose_at(&b, s, &later);
  const double vn = dot(v, m) / 3.0; /* |m| = 3 */
  CHECK_NEAR(lsdem_boundary_distance(&b, &later, p, NULL),
             lsdem_boundary_distance(&b, &b.pose, p, NULL) - s * vn, 1e-14);
  for (int k = 0; k < 9; k++) CHECK(later.R[k] == b.pose.R[k], "no turn");
}

/* the platen: level at rest P = x - h n; a load f at arm a from the wall's point x gives
 * the torque about P (x - P + a) x f; under a constant torque T perpendicular to the ram
 * axis its tilt after N steps is dt^2 (T/I) N(N+1)/2 (centred difference from rest), its
 * point stays h from P along the tilted normal, and the pose at s = 0 is the kernel's
 * (lsdem_pivot_pose) */
static void test_platen(void)
{
  lsdem_boundary b;
  const double x0[3] = {0.0, 0.0, 1.0}, down[3] = {0.0, 0.0, -1.0};
  const double h = 0.5, I = 2.0, dt = 1e-3;
  lsdem_boundary_plane(&b, x0, down, NULL);
  CHECK(lsdem_boundary_pivot(&b, h, I, 0.0, NULL) == LSDEM_OK, "pivot");
  CHECK(b.pivots == 1, "pivots");
  CHECK_NEAR(b.platen.x[2], 1.5, 0.0);
  CHECK_NEAR(b.platen.axis[2], -1.0, 0.0);
  /* a unit upward force at x + (2, 0, 0): torque about P = (2, 0, -0.5) x (0, 0, 1) */
  const double f[3] = {0.0, 0.0, 1.0}, tx[3] = {0.0, -2.0, 0.0};
  lsdem_boundary_platen_load(&b, f, tx);
  CHECK_NEAR(b.platen.torque[0], 0.0, 1e-15);
  CHECK_NEAR(b.platen.torque[1], -2.0, 1e-15);
  CHECK_NEAR(b.platen.torque[2], 0.0, 1e-15);
  const int nstep = 400;
  for (int n = 0; n < nstep; n++) lsdem_boundary_advance(&b, dt);
  const double theta = dt * dt * (-2.0 / I) * 0.5 * nstep * (nstep + 1.0);
  /* rotation by theta about y takes (0, 0, -1) to (-sin theta, 0, -cos theta) */
  double n[3];
  const double far[3] = {0.0, 0.0, 10.0};
  lsdem_boundary_distance(&b, &b.pose, far, n);
  CHECK_REL(n[0], -sin(theta), 1e-9);
  CHECK_NEAR(n[1], 0.0, 1e-15);
  CHECK_REL(n[2], -cos(theta), 1e-12);
  CHECK_REL(b.pose.omega[1], nstep * dt * (-2.0 / I), 1e-12);
  for (int k = 0; k < 3; k++) CHECK_NEAR(b.pose.x[k], b.platen.x[k] + h * n[k], 1e-15);
  lsdem_pose kernel, at0;
  lsdem_pivot_pose(b.platen.x, b.pose.v, b.platen.q, b.platen.omega, h, &kernel);
  lsdem_boundary_pose_at(&b, 0.0, &at0);
  CHECK(memcmp(&kernel, &at0, sizeof at0) == 0, "platen pose at s = 0 is the kernel's");
  /* the point moves with the tilt: v = omega x (x - P) */
  CHECK_NEAR(at0.v[0], b.pose.omega[1] * h * n[2], 1e-15);
  /* a moving ram carries P: after N steps at v, P = P0 + N dt v */
  b.pose.v[2] = -0.2;
  const double pz = b.platen.x[2];
  for (int k = 0; k < 10; k++) lsdem_boundary_advance(&b, dt);
  CHECK_NEAR(b.platen.x[2], pz - 10 * dt * 0.2, 1e-14);
}

static void test_bad_input(void)
{
  lsdem_boundary b;
  lsdem_error err;
  const double x[3] = {0.0, 0.0, 0.0}, zero[3] = {0.0, 0.0, 0.0};
  const double inf[3] = {0.0, INFINITY, 1.0}, nan3[3] = {1.0, NAN, 1.0};
  CHECK(lsdem_boundary_plane(&b, x, zero, &err) == LSDEM_ERR_ARG, "zero normal");
  CHECK(strstr(err.msg, "normal") != NULL, "%s", err.msg);
  CHECK(lsdem_boundary_plane(&b, x, inf, &err) == LSDEM_ERR_ARG, "infinite normal");
  CHECK(lsdem_boundary_plane(&b, x, nan3, &err) == LSDEM_ERR_ARG, "NaN normal");
  /* a normal whose squares overflow is still a direction */
  const double huge[3] = {1e308, 1e308, 0.0};
  CHECK(lsdem_boundary_plane(&b, x, huge, &err) == LSDEM_OK, "huge normal");
  CHECK_NEAR(b.pose.R[2], sqrt(0.5), 1e-15);
  CHECK_NEAR(b.pose.R[5], sqrt(0.5), 1e-15);
  const double c[2] = {0.0, 0.0};
  CHECK(lsdem_boundary_cylinder(&b, 2, c, 0.0, &err) == LSDEM_ERR_ARG, "radius 0");
  CHECK(strstr(err.msg, "radius") != NULL, "%s", err.msg);
  CHECK(lsdem_boundary_cylinder(&b, 3, c, 1.0, &err) == LSDEM_ERR_ARG, "axis 3");
  CHECK(lsdem_boundary_cylinder(&b, 2, c, 1.0, &err) == LSDEM_OK, "a good cylinder");
  CHECK(lsdem_boundary_pivot(&b, 0.5, 1.0, 0.0, &err) == LSDEM_ERR_ARG, "pivot on a cylinder");
  CHECK(strstr(err.msg, "plane") != NULL && strstr(err.msg, "cylinder") != NULL, "%s",
        err.msg);
  const double up[3] = {0.0, 0.0, 1.0};
  lsdem_boundary_plane(&b, x, up, NULL);
  CHECK(lsdem_boundary_pivot(&b, -0.1, 1.0, 0.0, &err) == LSDEM_ERR_ARG, "h < 0");
  CHECK(strstr(err.msg, "pivot h") != NULL, "%s", err.msg);
  CHECK(lsdem_boundary_pivot(&b, 0.1, 0.0, 0.0, &err) == LSDEM_ERR_ARG, "I = 0");
  CHECK(strstr(err.msg, "pivot I") != NULL, "%s", err.msg);
  CHECK(lsdem_boundary_pivot(&b, 0.1, 1.0, -1.0, &err) == LSDEM_ERR_ARG, "c < 0");
  CHECK(strstr(err.msg, "pivot c") != NULL, "%s", err.msg);
  CHECK(b.pivots == 0, "a refused pivot leaves the plane as it was");
}

int main(void)
{
  test_plane();
  test_cylinder();
  test_may_touch();
  test_crossing();
  test_clear_of_crossing();
  test_moving_pose();
  test_platen();
  test_bad_input();
  return lsdem_test_summary();
}
