/* test_impulse_step.c -- the stages of an impulse step over the solver's arrays (step.c),
 * against closed forms computed here: a free grain under gravity kicked and drifted (the
 * symplectic Euler sums), global damping ((1 - xi dt)^n of v and omega, the energy it
 * takes, the positions it leaves), the thresholds' documented rules, the classify and
 * selection rules on contacts of chosen speeds, the wall guard on a sphere in a plane (the
 * lift d/dt of a shallow overlap, the push-out limit max(r, sqrt(r d0 / dt)) of a deep one,
 * no second push of a grain that leaves, the group bits, the skip of a grain seen clear)
 * and the CFL ratio. */
#include "impulse_fixtures.h"

/* Grain k of the tests: body and grain record, at rest at x. shape: its shape. */
static void make_grain(lsdem_impulse_body *b, lsdem_impulse_grain *g, int64_t id, double mass,
                       const double inertia[3], const double x[3], const lsdem_shape *shape)
{
  memset(g, 0, sizeof *g);
  g->q[0] = 1.0;
  memcpy(g->inertia, inertia, sizeof g->inertia);
  g->mass = mass;
  g->radius = shape->radius;
  g->shape = shape;
  g->groups = 1;
  const double z[3] = {0, 0, 0};
  lsdem_error err;
  CHECK(lsdem_impulse_body_grain(b, id, mass, inertia, g->q, x, z, z, &err) == LSDEM_OK, "%s",
        err.msg);
}

static lsdem_shape sphere_shape(double r)
{
  return fix_shape(fix_sdf(LSDEM_SDF_SPHERE, r, 0, 0), 0, NULL, r);
}

/* Kick and drift of a free grain under gravity for n steps: v_n = -g n dt and
 * z_n = z0 - g dt^2 n (n + 1) / 2 (symplectic Euler's sums); a grain that is not moving
 * keeps its state; the kick returns g, the largest acceleration. */
static void test_kick_drift_gravity(void)
{
  const double g = 9.81, dt = 1e-3, m = 2.0, I[3] = {0.1, 0.2, 0.3};
  const double x0[3] = {0.5, -0.25, 2.0}, x1[3] = {3, 0, 0};
  lsdem_shape box = fix_shape(fix_sdf(LSDEM_SDF_BOX, 0.1, 0.2, 0.3), 0, NULL, 0.4);
  lsdem_impulse_body body[2];
  lsdem_impulse_grain grain[2];
  make_grain(&body[0], &grain[0], 1, m, I, x0, &box);
  make_grain(&body[1], &grain[1], 2, m, I, x1, &box);
  const char moving[2] = {1, 0};
  for (int k = 0; k < 2; k++) grain[k].force[2] = -g * m;
  const int n = 300;
  double amax = 0.0, damped = 0.0;
  lsdem_error err;
  for (int s = 0; s < n; s++) {
    amax = lsdem_impulse_stage_kick(body, grain, moving, 2, dt, NULL);
    CHECK(lsdem_impulse_stage_damp_drift(body, grain, moving, 2, 0.0, dt, &damped, NULL, &err) ==
              LSDEM_OK,
          "%s", err.msg);
  }
  CHECK_REL(amax, g, 1e-15);
  CHECK_REL(body[0].v[2], -g * n * dt, 1e-12);
  CHECK_REL(body[0].x[2], x0[2] - g * dt * dt * n * (n + 1) / 2.0, 1e-12);
  CHECK(body[0].x[0] == x0[0] && body[0].x[1] == x0[1], "sideways drift");
  CHECK(grain[0].q[0] == 1.0 && grain[0].q[1] == 0.0, "a grain without spin turned");
  CHECK(damped == 0.0, "undamped step took energy %g", damped);
  CHECK(body[1].x[2] == 0.0 && body[1].v[2] == 0.0, "a grain that is not moving moved");
  /* the kinetic energy sum: the moving grain's only, 1/2 m v^2 */
  CHECK_REL(lsdem_impulse_stage_kinetic_energy(body, grain, moving, 2),
            0.5 * m * (g * n * dt) * (g * n * dt), 1e-12);
}

/* Global damping (eqs 4.44-4.46) over n steps without forces: v_n = v0 (1 - xi dt)^n,
 * omega likewise; the energy taken is KE0 (1 - (1 - xi dt)^(2n)); the position is
 * x0 + dt v0 sum_{k=1..n} (1 - xi dt)^k. As dt -> 0 at fixed t the decay tends to
 * exp(-xi t). A sphere's omega ends 0 (it never turns). xi dt > 1 is refused. */
static void test_damp_drift_decay(void)
{
  const double xi = 2.0, dt = 1e-3, m = 1.5, Iiso = 0.2, I[3] = {Iiso, Iiso, Iiso};
  const double x0[3] = {0, 0, 0}, v0[3] = {0.3, -0.4, 1.2}, w0[3] = {0.0, 0.0, 2.0};
  lsdem_shape ell = fix_shape(fix_sdf(LSDEM_SDF_ELLIPSOID, 0.1, 0.1, 0.1), 0, NULL, 0.1);
  lsdem_shape ball = sphere_shape(0.1);
  lsdem_impulse_body body[2];
  lsdem_impulse_grain grain[2];
  make_grain(&body[0], &grain[0], 1, m, I, x0, &ell);
  make_grain(&body[1], &grain[1], 2, m, I, x0, &ball);
  for (int k = 0; k < 2; k++) {
    memcpy(body[k].v, v0, sizeof v0);
    memcpy(body[k].omega, w0, sizeof w0);
  }
  const char moving[2] = {1, 1};
  const int n = 500;
  double damped = 0.0;
  lsdem_error err;
  for (int s = 0; s < n; s++)
    CHECK(lsdem_impulse_stage_damp_drift(body, grain, moving, 1, xi, dt, &damped, NULL, &err) ==
              LSDEM_OK,
          "%s", err.msg);
  const double h = 1.0 - xi * dt, hn = pow(h, n);
  for (int d = 0; d < 3; d++) {
    CHECK_REL(body[0].v[d], v0[d] * hn, 1e-12);
    CHECK_REL(body[0].x[d], dt * v0[d] * h * (1.0 - hn) / (1.0 - h), 1e-11);
  }
  CHECK_REL(body[0].omega[2], w0[2] * hn, 1e-12);
  const double ke0 = 0.5 * m * lsdem_dot3(v0, v0) + 0.5 * Iiso * lsdem_dot3(w0, w0);
  CHECK_REL(damped, ke0 * (1.0 - hn * hn), 1e-12);
  CHECK(fabs(hn - exp(-xi * n * dt)) < 2.0 * xi * xi * n * dt * dt,
        "decay %g far from exp(-xi t) %g", hn, exp(-xi * n * dt));
  /* the sphere: translation damped and drifted, omega 0 after the drift */
  CHECK(lsdem_impulse_stage_damp_drift(body + 1, grain + 1, moving, 1, xi, dt, &damped, NULL,
                                        &err) ==
            LSDEM_OK,
        "%s", err.msg);
  CHECK(body[1].omega[0] == 0.0 && body[1].omega[1] == 0.0 && body[1].omega[2] == 0.0,
        "a sphere kept its spin");
  CHECK_REL(body[1].x[2], dt * v0[2] * h, 1e-15);
  CHECK(lsdem_impulse_stage_damp_drift(body, grain, moving, 1, 2.0 / dt, dt, &damped, NULL, &err) ==
            LSDEM_ERR_ARG,
        "xi dt = 2 accepted");
}

/* The thresholds from the resting speed r: the documented rules. */
static void test_thresholds(void)
{
  const double r = 0.04, dt = 2e-3;
  lsdem_etm_params etm;
  lsdem_etm_params_default(&etm);
  etm.velocity_tol = 1e-3;
  lsdem_resting_params rest;
  lsdem_resting_params_default(&rest);
  rest.max_sweeps = 7;
  lsdem_impulse_step s;
  memset(&s, 0, sizeof s);
  s.dt = dt;
  s.split = 1;
  s.residual = 0.3;
  lsdem_impulse_step_thresholds(&s, r, &etm, &rest);
  CHECK_REL(s.wall.rest_speed, r, 1e-15);
  CHECK_REL(s.wall.depth_tol, 2.0 * r * dt, 1e-15);
  CHECK_REL(s.island.rest.slop, r * dt, 1e-15);
  CHECK(s.island.rest.max_sweeps == 7 && s.island.rest.dt == dt &&
            s.island.rest.ref_speed == r && s.island.rest.max_push == r,
        "resting solve's settings");
  CHECK_REL(s.approach_floor, 1e-3 * r, 1e-15);
  CHECK_REL(s.island.approach_floor, 1e-3 * r, 1e-15);
  CHECK_REL(s.island.etm.min_approach, 0.3 * r, 1e-15);
  CHECK(s.island.collide_speed == r, "collide speed");
  s.split = 0;
  lsdem_impulse_step_thresholds(&s, r, &etm, &rest);
  /* lsdem_wall_params_default's rule with r = 2 |g| dt: 1 % of |g| dt^2 */
  lsdem_wall_params def;
  lsdem_wall_params_default(&def, r / (2.0 * dt), dt, 0.0);
  CHECK_REL(s.wall.depth_tol, def.depth_tol, 1e-14);
  CHECK(s.island.approach_floor == 0.0 && s.island.etm.min_approach == etm.min_approach,
        "the report's method: ETM on any approach");
  CHECK_REL(lsdem_impulse_auto_rest_speed(2.0, 9.81, dt), 2.0 * 9.81 * dt, 1e-15);
}

/* Three grains on a line along x and a wall below: contacts of chosen normal speeds. */
enum { NB = 4, NC = 4 };
static void contact_scene(lsdem_impulse_body *b, lsdem_impulse_step_contact *c)
{
  const double z[3] = {0, 0, 0};
  for (int k = 0; k < 3; k++) {
    const double x[3] = {(double)k, 0, 0};
    fx_state s = fx_sphere(k + 1, 0.5, x, z);
    fx_body_of(&s, &b[k]);
  }
  fx_wall(&b[3], -1, z, z);
  b[0].v[0] = 1.0;   /* 0 -> 1 approach at 1 */
  b[2].v[0] = 0.01;  /* 1 <- 2: separate at 0.01 */
  b[1].v[2] = -0.03; /* 1 into the wall slowly */
  b[2].v[2] = -0.5;  /* 2 into the wall fast */
  memset(c, 0, NC * sizeof *c);
  const int a[NC] = {1, 2, 1, 2}, bb[NC] = {0, 1, 3, 3}, j[NC] = {0, 1, -1, -1};
  const double n[NC][3] = {{1, 0, 0}, {1, 0, 0}, {0, 0, 1}, {0, 0, 1}};
  for (int k = 0; k < NC; k++) {
    c[k].i = a[k];
    c[k].j = j[k];
    c[k].c.a = a[k];
    c[k].c.b = bb[k];
    memcpy(c[k].c.normal, n[k], sizeof n[k]);
    c[k].c.point[0] = a[k] - 0.5 * n[k][0];
    c[k].c.point[2] = -0.5 * n[k][2];
    c[k].c.restitution = 0.5;
  }
}

/* classify: resting when not approaching faster than the resting speed; select: the
 * report's method keeps the grain pairs (approaching or not, flagged) and the colliding
 * wall contact, with wall_etm also the slow approaching one (e = 0); split flags every
 * contact, resting ones only in the first pass. */
static void test_classify_select(void)
{
  lsdem_impulse_body b[NB];
  lsdem_impulse_step_contact c[NC], coll[NC];
  contact_scene(b, c);
  const double r = 0.1;
  lsdem_impulse_stage_classify(b, c, NC, r);
  CHECK(!c[0].resting && c[1].resting && c[2].resting && !c[3].resting,
        "classify: %d %d %d %d", c[0].resting, c[1].resting, c[2].resting, c[3].resting);
  b[1].v[2] = -r; /* exactly the resting speed: resting; a little faster: colliding */
  lsdem_impulse_stage_classify(b, c, NC, r);
  CHECK(c[2].resting, "u_n = -r is resting");
  b[1].v[2] = -r * (1.0 + 1e-12);
  lsdem_impulse_stage_classify(b, c, NC, r);
  CHECK(!c[2].resting, "u_n < -r is colliding");
  b[1].v[2] = -0.03;
  lsdem_impulse_stage_classify(b, c, NC, r);

  lsdem_impulse_step s;
  memset(&s, 0, sizeof s);
  s.wall.rest_speed = r;
  s.approach_floor = 1e-4;
  int ncoll = -1;
  int nap = lsdem_impulse_stage_select(b, c, NC, &s, 1, coll, &ncoll);
  CHECK(ncoll == 3 && coll[0].c.b == 0 && coll[1].c.b == 1 && coll[2].j == -1 &&
            coll[2].c.a == 2,
        "report's method kept %d", ncoll);
  CHECK(coll[0].approaching && !coll[1].approaching && coll[2].approaching && nap == 2,
        "flags %d %d %d, %d approaching", coll[0].approaching, coll[1].approaching,
        coll[2].approaching, nap);
  CHECK(coll[2].c.restitution == 0.5, "a collision keeps its restitution");
  s.wall_etm = 1;
  nap = lsdem_impulse_stage_select(b, c, NC, &s, 1, coll, &ncoll);
  CHECK(ncoll == 4 && coll[2].c.a == 1 && coll[2].c.restitution == 0.0 &&
            coll[3].c.restitution == 0.5 && nap == 3,
        "wall_etm: kept %d, e %g, %d approaching", ncoll, coll[2].c.restitution, nap);

  s.split = 1;
  ncoll = -1;
  nap = lsdem_impulse_stage_select(b, c, NC, &s, 1, NULL, &ncoll);
  CHECK(ncoll == -1, "split wrote ncoll");
  CHECK(c[0].approaching && c[1].approaching && c[2].approaching && c[3].approaching &&
            nap == 2,
        "split, first pass: %d %d %d %d, %d", c[0].approaching, c[1].approaching,
        c[2].approaching, c[3].approaching, nap);
  nap = lsdem_impulse_stage_select(b, c, NC, &s, 0, NULL, &ncoll);
  CHECK(c[0].approaching && !c[1].approaching && c[2].approaching && c[3].approaching,
        "split, later pass: %d %d %d %d", c[0].approaching, c[1].approaching,
        c[2].approaching, c[3].approaching);
}

/* The report's method's selection on a grain falling onto a wall and a second grain
 * falling onto it: a wall contact is a collision (kept for ETM) only when it approaches
 * faster than the resting speed, a slower one is the wall guard's; the grain pair is kept
 * and is a collision (flagged approaching) only when it approaches. */
static void test_select_collisions(void)
{
  const double z[3] = {0, 0, 0}, xa[3] = {0, 0, 1}, xb[3] = {0, 0, 2.2};
  const double va[3] = {0, 0, -0.05}, vb[3] = {0, 0, -0.06};
  fx_state sa = fx_sphere(1, 0.5, xa, va), sb = fx_sphere(2, 0.5, xb, vb);
  lsdem_impulse_body b[3];
  fx_body_of(&sa, &b[0]);
  fx_body_of(&sb, &b[1]);
  fx_wall(&b[2], -1, z, z);
  const double p0[3] = {0, 0, 0.5}, p1[3] = {0, 0, 1.6};
  lsdem_impulse_step_contact c[2], coll[2];
  memset(c, 0, sizeof c);
  c[0].i = 0;
  c[0].j = -1;
  c[0].c = fx_contact(0, 2, p0, 0, 0, 1, 0, 1); /* u_n = -0.05 */
  c[1].i = 1;
  c[1].j = 0;
  c[1].c = fx_contact(1, 0, p1, 0, 0, 1, 0, 1); /* u_n = -0.01 */
  lsdem_impulse_step s;
  memset(&s, 0, sizeof s);
  int ncoll = -1;
  s.wall.rest_speed = 0.1;
  lsdem_impulse_stage_select(b, c, 2, &s, 1, coll, &ncoll);
  CHECK(ncoll == 1 && coll[0].c.a == 1, "slow wall contact left to the wall correction");
  s.wall.rest_speed = 0.01;
  lsdem_impulse_stage_select(b, c, 2, &s, 1, coll, &ncoll);
  CHECK(ncoll == 2, "fast wall contact kept");
  b[1].v[2] = 0.0; /* the grain pair separates: u_n = +0.05 */
  const int nap = lsdem_impulse_stage_select(b, c, 2, &s, 1, coll, &ncoll);
  CHECK(nap == 1 && coll[0].c.a == 0 && coll[0].approaching && !coll[1].approaching,
        "separating grains no collision");
}

/* The wall guard on a sphere of radius R at rest with its centre h above the plane z = 0
 * (overlap d0 = R - h; at rest the predicted pose is the pose): the deepest point rises
 * by d0/dt when that is below the push-out limit, else to the limit max(r, sqrt(r d0/dt))
 * (lsdem_wall_limit_push_out with a = r / (2 dt)); the impulse is m times the lift. A
 * grain approaching faster than r is a collision, ETM's: the guard leaves it alone. */
/* The guard's wall: the plane z = 0 (in plane), acting on group 1, with parameters prm. */
static void plane_wall(lsdem_boundary *plane, lsdem_impulse_guard_wall *w,
                       lsdem_wall_params prm)
{
  const double p0[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
  lsdem_error err;
  CHECK(lsdem_boundary_plane(plane, p0, nz, &err) == LSDEM_OK, "%s", err.msg);
  memset(w, 0, sizeof *w);
  w->boundary = plane;
  w->groups = 1;
  lsdem_boundary_pose_at(plane, 0.0, &w->pose);
  w->detect.node_stride = 1;
  w->prm = prm;
}

static void guard_once(double d0, double v0z, double *vz, double *impulse, int *corrected)
{
  const double R = 0.1, dt = 1e-3, m = 1.0, I[3] = {0.004, 0.004, 0.004};
  lsdem_shape ball = sphere_shape(R);
  const double x[3] = {0.2, 0.1, R - d0};
  lsdem_impulse_body body[2];
  lsdem_impulse_grain grain[2];
  make_grain(&body[0], &grain[0], 1, m, I, x, &ball);
  make_grain(&body[1], &grain[1], 2, m, I, x, &ball);
  body[0].v[2] = v0z;
  grain[1].groups = 2; /* not in the wall's group */
  const char moving[2] = {1, 1};
  lsdem_boundary plane;
  lsdem_impulse_guard_wall w;
  plane_wall(&plane, &w, (lsdem_wall_params){0.02, 1e-8, 0.5});
  lsdem_error err;
  lsdem_contact_point pts[4];
  lsdem_wall_guard_seen seen[2];
  memset(seen, 0, sizeof seen);
#define GUARD() \
  lsdem_impulse_stage_wall_guard(body, grain, moving, 2, &w, 0, dt, pts, 4, seen, &err)
  *corrected = GUARD();
  *vz = body[0].v[2];
  *impulse = seen[0].impulse[2];
  CHECK(seen[0].corrected == (*corrected == 1) && !seen[1].corrected && body[1].v[2] == 0.0,
        "the grain outside the wall's group was taken");
  CHECK(fabs(body[0].v[0]) < 1e-15 && fabs(body[0].v[1]) < 1e-15, "sideways push");
  /* again: the grain now clears the wall at its predicted pose (shallow) or leaves faster
   * than r (deep): no second push */
  const double before = body[0].v[2];
  CHECK(GUARD() == 0, "a corrected grain pushed again");
  CHECK(body[0].v[2] == before && seen[0].clear, "a corrected grain changed or not seen clear");
  /* seen clear at these velocities: not checked again, even against a wall moved into it */
  w.pose.x[2] += 0.5 * R;
  CHECK(GUARD() == 0, "a grain seen clear was checked again");
#undef GUARD
}

static void test_wall_guard(void)
{
  const double r = 0.02, dt = 1e-3;
  double vz, J;
  int n;
  const double shallow = 1e-5; /* d0/dt = 0.01 < limit max(r, sqrt(r d0/dt)) = r */
  guard_once(shallow, 0.0, &vz, &J, &n);
  CHECK(n == 1, "shallow overlap: %d corrected", n);
  CHECK_REL(vz, shallow / dt, 1e-9);
  CHECK_REL(J, vz, 1e-12); /* m = 1 */
  const double deep = 0.01; /* d0/dt = 10 > limit sqrt(r d0/dt) = 0.447 */
  guard_once(deep, 0.0, &vz, &J, &n);
  CHECK(n == 1, "deep overlap: %d corrected", n);
  CHECK_REL(vz, fmax(r, sqrt(r * deep / dt)), 1e-9);
  CHECK_REL(J, vz, 1e-12);
  guard_once(shallow, -2.5 * r, &vz, &J, &n);
  CHECK(n == 0 && vz == -2.5 * r, "a collision corrected: %d, v_z %g", n, vz);
}

/* The guard's cheap rejection: a grain with near[k] == 0 is skipped while dt |v| < far_gap
 * (the caller vouches that it cannot reach the wall then), tested once it moves faster. */
static void test_wall_guard_far(void)
{
  const double R = 0.1, dt = 1e-3, I[3] = {0.004, 0.004, 0.004}, d0 = 1e-5;
  lsdem_shape ball = sphere_shape(R);
  const double x[3] = {0.0, 0.0, R - d0}; /* overlapping the plane z = 0 */
  lsdem_impulse_body body[1];
  lsdem_impulse_grain grain[1];
  make_grain(&body[0], &grain[0], 1, 1.0, I, x, &ball);
  body[0].v[0] = 1.0; /* dt |v| = 1e-3 */
  const char moving[1] = {1};
  const unsigned char near[1] = {0};
  lsdem_boundary plane;
  lsdem_impulse_guard_wall w;
  plane_wall(&plane, &w, (lsdem_wall_params){0.02, 1e-8, 0.5});
  lsdem_error err;
  w.near = near;
  w.far_gap = 2e-3;
  lsdem_contact_point pts[4];
  lsdem_wall_guard_seen seen[1];
  memset(seen, 0, sizeof seen);
  CHECK(lsdem_impulse_stage_wall_guard(body, grain, moving, 1, &w, 0, dt, pts, 4, seen, &err) ==
            0 && body[0].v[2] == 0.0 && !seen[0].clear,
        "a grain marked far and slow was tested");
  w.far_gap = 5e-4; /* dt |v| beyond the gap: tested, and corrected */
  CHECK(lsdem_impulse_stage_wall_guard(body, grain, moving, 1, &w, 0, dt, pts, 4, seen, &err) ==
            1 && body[0].v[2] > 0.0,
        "a grain faster than the gap was not tested");
}

/* The CFL ratio: |v| dt / radius of the worst moving grain; NaN counts as the worst. */
static void test_cfl(void)
{
  lsdem_shape ball = sphere_shape(0.1), big = sphere_shape(1.0);
  const double I[3] = {1, 1, 1}, x[3] = {0, 0, 0}, dt = 0.01;
  lsdem_impulse_body body[3];
  lsdem_impulse_grain grain[3];
  make_grain(&body[0], &grain[0], 1, 1.0, I, x, &ball);
  make_grain(&body[1], &grain[1], 2, 1.0, I, x, &big);
  make_grain(&body[2], &grain[2], 3, 1.0, I, x, &ball);
  body[0].v[0] = 3.0;
  body[0].v[1] = 4.0; /* 5 dt / 0.1 = 0.5 */
  body[1].v[2] = 20.0; /* 0.2 */
  body[2].v[2] = 100.0; /* not moving */
  char moving[3] = {1, 1, 0};
  int worst = -2;
  CHECK_REL(lsdem_impulse_stage_cfl(body, grain, moving, 3, dt, &worst), 0.5, 1e-15);
  CHECK(worst == 0, "worst %d", worst);
  body[1].v[0] = NAN;
  CHECK(lsdem_impulse_stage_cfl(body, grain, moving, 3, dt, &worst) == HUGE_VAL && worst == 1,
        "NaN not the worst");
  moving[0] = moving[1] = 0;
  CHECK(lsdem_impulse_stage_cfl(body, grain, moving, 3, dt, &worst) == 0.0 && worst == -1,
        "no moving grain");
}

/* The energy audit's bookings of the stages (lsdem_impulse_audit), each against the
 * kinetic energy measured here before and after it (lsdem_impulse_kinetic_energy, at the
 * grain's orientation then), to 1e-12 of the energy: the kick of a tumbling ellipsoid under
 * a force and a torque; the free rotation of a spin about no principal axis (the drift's
 * truncation error, well above round-off); damping from its scale factor; the wall guard
 * on an ellipsoid sinking, tilted and sliding, into a plane with friction (normal and
 * friction impulses). Then the residual's rule. */
static fix_grain ellipsoid_grain;

static double grain_energy(const lsdem_impulse_body *b, const lsdem_impulse_grain *g)
{
  return lsdem_impulse_kinetic_energy(g->mass, g->inertia, g->q, b->v, b->omega);
}

static void test_audit_bookings(void)
{
  const double a[3] = {0.2, 0.12, 0.08}, m = 1.3, I[3] = {0.0078, 0.0121, 0.0156};
  const lsdem_sdf ell = fix_sdf(LSDEM_SDF_ELLIPSOID, a[0], a[1], a[2]);
  fix_make_grain(&ellipsoid_grain, a, &ell);
  const double x0[3] = {0, 0, 1};
  lsdem_impulse_body b;
  lsdem_impulse_grain g;
  make_grain(&b, &g, 1, m, I, x0, &ellipsoid_grain.plain);
  const char moving[1] = {1};
  lsdem_error err;
  double rel;
  /* kick */
  const double q0[4] = {0.8, 0.2, -0.4, 0.4}, v0[3] = {0.3, -0.2, 0.5}, w0[3] = {4, -2, 3};
  const double f[3] = {0.5, 1.0, -12.0}, tau[3] = {0.2, -0.3, 0.1}, dt = 2e-3;
  memcpy(g.q, q0, sizeof q0);
  lsdem_quat_normalize(g.q);
  CHECK(lsdem_impulse_body_grain(&b, 1, m, I, g.q, x0, v0, w0, &err) == LSDEM_OK, "%s", err.msg);
  memcpy(g.force, f, sizeof f);
  memcpy(g.torque, tau, sizeof tau);
  double e0 = grain_energy(&b, &g), work = 0.0;
  lsdem_impulse_stage_kick(&b, &g, moving, 1, dt, &work);
  rel = fabs(grain_energy(&b, &g) - e0 - work) / e0;
  CHECK(rel <= 1e-12 && fabs(work) > 1e-4 * e0, "kick: booked %.17g, dKE %.17g", work,
        grain_energy(&b, &g) - e0);
  /* damping and drift: a fast spin about no principal axis */
  const double spin[3] = {20, -35, 50};
  memcpy(b.omega, spin, sizeof spin);
  e0 = grain_energy(&b, &g);
  double damped = 0.0, turn = 0.0;
  CHECK(lsdem_impulse_stage_damp_drift(&b, &g, moving, 1, 0.5, dt, &damped, &turn, &err) ==
            LSDEM_OK, "%s", err.msg);
  const double e1 = grain_energy(&b, &g); /* at the turned orientation */
  rel = fabs(e1 - e0 + damped - turn) / e0;
  CHECK(rel <= 1e-12, "damp and drift: dKE %.17g, booked -%.17g + %.17g", e1 - e0, damped,
        turn);
  CHECK_REL(damped, e0 * (1.0 - (1.0 - 0.5 * dt) * (1.0 - 0.5 * dt)), 1e-12);
  CHECK(fabs(turn) > 1e-9 * e0, "the free rotation's energy change %.3g is round-off", turn);
  /* the wall guard: the ellipsoid tilted, 1e-4 into the plane z = 0, sliding */
  lsdem_boundary plane;
  lsdem_impulse_guard_wall w;
  plane_wall(&plane, &w, (lsdem_wall_params){0.05, 1e-8, 0.5});
  const double qt[4] = {0.9961946980917455, 0.08715574274765817, 0, 0}; /* 10 deg about x */
  memcpy(g.q, qt, sizeof qt);
  double R[9], lowest = HUGE_VAL;
  lsdem_quat_to_matrix(g.q, R);
  for (int k = 0; k < FIX_GRAIN_NODES; k++) {
    const double *n = ellipsoid_grain.nodes + 3 * k;
    lowest = fmin(lowest, R[6] * n[0] + R[7] * n[1] + R[8] * n[2]);
  }
  const double x1[3] = {0, 0, -lowest - 1e-4}, v1[3] = {0.4, 0.1, -0.01}, w1[3] = {0.5, 1, -2};
  CHECK(lsdem_impulse_body_grain(&b, 1, m, I, g.q, x1, v1, w1, &err) == LSDEM_OK, "%s", err.msg);
  lsdem_contact_point pts[FIX_GRAIN_NODES];
  lsdem_wall_guard_seen seen;
  memset(&seen, 0, sizeof seen);
  e0 = grain_energy(&b, &g);
  const int n = lsdem_impulse_stage_wall_guard(&b, &g, moving, 1, &w, 0, dt, pts,
                                               FIX_GRAIN_NODES, &seen, &err);
  rel = fabs(grain_energy(&b, &g) - e0 - seen.work) / e0;
  printf("audit bookings: drift %.3g of the energy; wall guard %.3g, residual %.3g\n",
         turn / e0, seen.work / e0, rel);
  CHECK(n == 1 && seen.corrected, "the wall guard did not correct (%d)", n);
  CHECK(rel <= 1e-12 && fabs(seen.work) > 1e-3 * e0, "wall guard: booked %.17g, dKE %.17g",
        seen.work, grain_energy(&b, &g) - e0);
  /* the residual: relative to the largest of the energies and the terms' magnitudes */
  lsdem_impulse_audit au;
  memset(&au, 0, sizeof au);
  au.kick = 0.75;
  au.etm = -0.25;
  CHECK(lsdem_impulse_audit_residual(1.0, 1.5, &au) == 0.0, "an exact audit");
  au.damping = -0.125;
  CHECK_REL(lsdem_impulse_audit_residual(1.0, 1.5, &au), 0.125 / 1.5, 1e-15);
  CHECK_REL(lsdem_impulse_audit_residual(0.0, 0.0, &au), 0.375 / 1.125, 1e-15);
  memset(&au, 0, sizeof au);
  CHECK(lsdem_impulse_audit_residual(0.0, 0.0, &au) == 0.0, "all zero");
}

/* The guard reads a grain's node list against the wall (lsdem_impulse_guard_wall.lists)
 * where it holds at the predicted pose: an ellipsoid grain with 400 nodes, its lowest node
 * 1e-3 into a plane and sinking, corrected the same, bit for bit, with the list made by
 * detection at its pose as without; the list is really consulted (an empty list that
 * claims to hold, radius 1, leaves the grain uncorrected) and not trusted past its radius
 * (an empty list of radius 1e-6, less than the step's motion 4e-6: the plain result). */
static void test_wall_guard_lists(void)
{
  const double a[3] = {0.1, 0.08, 0.06}, dt = 1e-3, I[3] = {0.004, 0.003, 0.002};
  static fix_grain g;
  const lsdem_sdf ell = fix_sdf(LSDEM_SDF_ELLIPSOID, a[0], a[1], a[2]);
  fix_make_grain(&g, a, &ell);
  double low = HUGE_VAL;
  for (int k = 0; k < FIX_GRAIN_NODES; k++) low = fmin(low, g.nodes[3 * k + 2]);
  const double x[3] = {0.0, 0.0, -low - 1e-3};
  lsdem_boundary plane;
  lsdem_impulse_guard_wall w;
  plane_wall(&plane, &w, (lsdem_wall_params){0.02, 1e-8, 0.5});
  w.detect.node_skin = 0.01;
  static lsdem_nodelist_entry entry[FIX_GRAIN_NODES * LSDEM_NODELIST_MAX_WORDS];
  static lsdem_contact_point pts[FIX_GRAIN_NODES];
  lsdem_nodelist_head head;
  lsdem_nodelist list = {0, &head, entry};
  double v[4][3];
  int n[4];
  for (int run = 0; run < 4; run++) {
    lsdem_impulse_body body;
    lsdem_impulse_grain grain;
    make_grain(&body, &grain, 1, 1.0, I, x, &g.clustered);
    body.v[2] = -0.2 * w.prm.rest_speed; /* sinking slowly: a resting contact */
    lsdem_pose pose;
    lsdem_impulse_predict_pose(body.x, grain.q, body.v, body.omega, I, dt, &pose);
    lsdem_manifold m = lsdem_manifold_over(pts, FIX_GRAIN_NODES);
    lsdem_detect(&g.clustered, &pose, &plane.shape, &w.pose, &w.detect, 0, NULL, &list, &m);
    CHECK(list.valid && head.count > 0 && head.count < FIX_GRAIN_NODES / 2,
          "a list of %d nodes", head.count);
    if (run >= 2) { /* an empty list that claims to hold, built at the current pose */
      head.count = 0;
      head.radius = run == 2 ? 1.0 : 1e-6;
      head.t[2] -= dt * body.v[2];
    }
    w.lists = run == 0 ? NULL : &list;
    const char moving[1] = {1};
    lsdem_wall_guard_seen seen[1];
    memset(seen, 0, sizeof seen);
    lsdem_error err;
    n[run] = lsdem_impulse_stage_wall_guard(&body, &grain, moving, 1, &w, 0, dt, pts,
                                            FIX_GRAIN_NODES, seen, &err);
    memcpy(v[run], body.v, sizeof v[run]);
  }
  CHECK(n[0] == 1 && v[0][2] > 0.0, "no correction without a list (%d, %g)", n[0], v[0][2]);
  CHECK(n[1] == 1 && memcmp(v[1], v[0], sizeof v[0]) == 0, "the list changed the correction");
  CHECK(n[2] == 0 && v[2][2] < 0.0, "an empty list was not consulted (%d)", n[2]);
  CHECK(n[3] == 1 && memcmp(v[3], v[0], sizeof v[0]) == 0,
        "an empty list trusted past its radius (%d)", n[3]);
}

int main(void)
{
  test_kick_drift_gravity();
  test_damp_drift_decay();
  test_thresholds();
  test_classify_select();
  test_select_collisions();
  test_wall_guard();
  test_wall_guard_far();
  test_wall_guard_lists();
  test_cfl();
  test_audit_bookings();
  return lsdem_test_summary();
}
