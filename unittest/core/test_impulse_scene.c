/* test_impulse_scene.c -- impulse mode end to end on grains and rigid walls (report
 * §4.3.4, §4.4.1, Figure 4.4): a step is kick (gravity), detection and ETM of the
 * collisions, the wall correction of resting contacts at the predicted pose (repeated up
 * to 10 times), damping, drift -- the core's detection, gluing, ETM, wall correction and
 * integrator together. Checked against closed forms: a ball dropped on a plane rebounds to
 * e^2 h0 and comes to rest on it; a block on an incline stays for tan(theta) < mu and
 * slides with a = g (sin theta - mu cos theta) otherwise. The wall correction alone: a
 * resting grain is stopped exactly, the deepest point of a tilted grain clears the wall at
 * the next predicted pose, moving platens and cylinder containers, and the fallback when
 * the overlaps' torque would sink the deepest point. */
#include "impulse_fixtures.h"

#include <stdio.h>

enum { SC_MAX_POINTS = 256, SC_MAX_CONTACTS = 512, SC_WALL_PASSES = 10 };

typedef struct {
  fx_state s;
  const lsdem_shape *shape;
} sc_grain;

typedef struct {
  lsdem_shape shape;
  lsdem_pose pose; /* pose.v: the wall's prescribed velocity */
} sc_wall;

typedef struct {
  sc_grain g[2];
  int ng;
  sc_wall w[1];
  int nw;
  double gravity[3], dt, mu, e, xi;
  lsdem_wall_params wall;
  lsdem_glue_params glue;
  lsdem_impulse_body body[3];
  int64_t etm_iterations, corrections, sliding;
} scene;

static lsdem_pose pose_of(const fx_state *s, const lsdem_impulse_body *b)
{
  lsdem_pose p;
  memcpy(p.x, s->x, sizeof p.x);
  lsdem_quat_to_matrix(s->q, p.R);
  memcpy(p.v, b->v, sizeof p.v);
  memcpy(p.omega, b->omega, sizeof p.omega);
  return p;
}

/* Contacts of grain i with wall j at the current poses, glued, appended to c. */
static int wall_contacts(scene *sc, int i, int j, lsdem_impulse_contact *c, int n)
{
  static lsdem_contact_point pts[SC_MAX_POINTS];
  lsdem_manifold m = lsdem_manifold_over(pts, SC_MAX_POINTS);
  const lsdem_pose pg = pose_of(&sc->g[i].s, &sc->body[i]);
  const lsdem_detect_params det = {1, 0.0};
  lsdem_detect(sc->g[i].shape, &pg, &sc->w[j].shape, &sc->w[j].pose, &det, 0, NULL, NULL,
               &m);
  int32_t group[SC_MAX_POINTS];
  return n + lsdem_impulse_glue(&m, i, sc->ng + j, sc->mu, sc->e, &sc->glue, c + n, group,
                                NULL);
}

/* Step 3 of Figure 4.4: detect every grain against every wall at the predicted poses and
 * correct resting contacts, until nothing is corrected or SC_WALL_PASSES passes. */
static void wall_passes(scene *sc)
{
  static lsdem_contact_point pts[SC_MAX_POINTS];
  const lsdem_detect_params det = {1, 0.0};
  for (int pass = 0; pass < SC_WALL_PASSES; pass++) {
    int corrected = 0;
    for (int i = 0; i < sc->ng; i++)
      for (int j = 0; j < sc->nw; j++) {
        lsdem_manifold m = lsdem_manifold_over(pts, SC_MAX_POINTS);
        const fx_state *s = &sc->g[i].s;
        lsdem_pose pg, pw = sc->w[j].pose;
        lsdem_impulse_predict_pose(s->x, s->q, sc->body[i].v, sc->body[i].omega, s->inertia,
                                   sc->dt, &pg);
        for (int d = 0; d < 3; d++) pw.x[d] += sc->dt * pw.v[d];
        lsdem_detect(sc->g[i].shape, &pg, &sc->w[j].shape, &pw, &det, 0, NULL, NULL, &m);
        lsdem_wall_result wr;
        lsdem_error err;
        CHECK(lsdem_wall_correct(&sc->body[i], &m, sc->dt, &sc->wall, &wr, &err) ==
                  LSDEM_OK,
              "%s", err.msg);
        if (wr.kind == LSDEM_WALL_RESTING) {
          corrected = 1;
          sc->corrections++;
          sc->sliding += wr.sliding;
        }
      }
    if (!corrected) break;
  }
}

/* The contacts ETM resolves, kept in place: the report's selection (stage 4,
 * lsdem_impulse_stage_select without split), here of wall contacts alone: those that
 * collide, approaching faster than the resting speed. Returns how many. */
static int select_collisions(const scene *sc, lsdem_impulse_contact *c, int n)
{
  static lsdem_impulse_step_contact all[SC_MAX_CONTACTS], coll[SC_MAX_CONTACTS];
  lsdem_impulse_step s;
  memset(&s, 0, sizeof s);
  s.wall = sc->wall;
  for (int k = 0; k < n; k++) {
    memset(&all[k], 0, sizeof all[k]);
    all[k].i = c[k].a;
    all[k].j = -1 - (c[k].b - sc->ng);
    all[k].c = c[k];
  }
  int ncoll = 0;
  lsdem_impulse_stage_select(sc->body, all, n, &s, 1, coll, &ncoll);
  for (int k = 0; k < ncoll; k++) c[k] = coll[k].c;
  return ncoll;
}

static void scene_step(scene *sc)
{
  const double zero[3] = {0, 0, 0};
  for (int i = 0; i < sc->ng; i++) { /* 1: bodies, gravity */
    fx_body_of(&sc->g[i].s, &sc->body[i]);
    const double f[3] = {sc->g[i].s.mass * sc->gravity[0], sc->g[i].s.mass * sc->gravity[1],
                         sc->g[i].s.mass * sc->gravity[2]};
    lsdem_impulse_kick(&sc->body[i], f, zero, sc->dt);
  }
  for (int j = 0; j < sc->nw; j++)
    fx_wall(&sc->body[sc->ng + j], -1 - j, sc->w[j].pose.x, sc->w[j].pose.v);
  lsdem_impulse_contact c[SC_MAX_CONTACTS]; /* 2: collisions */
  int n = 0;
  for (int i = 0; i < sc->ng; i++)
    for (int j = 0; j < sc->nw; j++) n = wall_contacts(sc, i, j, c, n);
  n = select_collisions(sc, c, n);
  if (n > 0) {
    lsdem_etm_result res;
    lsdem_error err;
    CHECK(fx_etm(sc->body, sc->ng + sc->nw, c, n, NULL, &res, &err) == LSDEM_OK, "%s",
          err.msg);
    sc->etm_iterations += res.iterations;
  }
  wall_passes(sc);                   /* 3 */
  for (int i = 0; i < sc->ng; i++) { /* 4 */
    lsdem_error err;
    CHECK(lsdem_impulse_damp(&sc->body[i], sc->xi, sc->dt, &err) == LSDEM_OK, "%s",
          err.msg);
    fx_state *s = &sc->g[i].s;
    fx_state_from(s, &sc->body[i]);
    lsdem_impulse_drift(s->x, s->q, s->omega, s->v, s->inertia, sc->dt);
  }
}

static void scene_init(scene *sc, double g, double theta, double dt, double mu, double e)
{
  memset(sc, 0, sizeof *sc);
  sc->gravity[0] = g * sin(theta);
  sc->gravity[2] = -g * cos(theta);
  sc->dt = dt;
  sc->mu = mu;
  sc->e = e;
  lsdem_wall_params_default(&sc->wall, g, dt, mu);
  lsdem_glue_params_default(&sc->glue);
  sc->nw = 1;
  sc->w[0].shape = fix_shape(fix_sdf(LSDEM_SDF_PLANE, 0, 0, 0), 0, NULL, HUGE_VAL);
  sc->w[0].pose = fix_pose(0, 0, 0);
}

/* ------------------------------------------------------------- ball drop ---- */

/* A sphere (radius 0.1) dropped from rest with its lowest point h0 = 1 above the plane
 * rebounds to e^2 h0 (Stronge: W_release = e^2 W_absorbed, eq 4.1). */
static void test_ball_drop(void)
{
  const double r = 0.1, h0 = 1.0, g = 9.81, dt = 2e-5;
  const double es[3] = {1.0, 0.65, 0.3};
  static const lsdem_shape ball = {.sdf = {.kind = LSDEM_SDF_SPHERE, .a = {0.1}},
                                   .radius = 0.1};
  for (int k = 0; k < 3; k++) {
    scene sc;
    scene_init(&sc, g, 0.0, dt, 0.0, es[k]);
    const double x[3] = {0, 0, r + h0}, z[3] = {0, 0, 0};
    sc.ng = 1;
    sc.g[0].s = fx_sphere(1, r, x, z);
    sc.g[0].shape = &ball;
    int bounced = 0;
    double apex = 0.0;
    for (int step = 0; step < 200000; step++) {
      const double vz = sc.g[0].s.v[2];
      scene_step(&sc);
      if (!bounced && vz < 0.0 && sc.g[0].s.v[2] > 0.0) bounced = 1;
      if (bounced && sc.g[0].s.v[2] <= 0.0) {
        apex = sc.g[0].s.x[2] - r;
        break;
      }
    }
    CHECK(bounced, "e %g: no bounce", es[k]);
    CHECK_REL(apex, es[k] * es[k] * h0, 0.01);
    printf("ball drop e %.2f: rebound %.5f, e^2 h0 %.5f, ratio %.4f, %lld ETM iterations\n",
           es[k], apex, es[k] * es[k] * h0, apex / (es[k] * es[k] * h0),
           (long long)sc.etm_iterations);
  }
}

/* With e = 0.3 the bounces die out and the ball ends resting on the plane: neither
 * sinking nor jittering (the wall correction holds it). */
static void test_ball_comes_to_rest(void)
{
  const double r = 0.1, g = 9.81, dt = 1e-3;
  static const lsdem_shape ball = {.sdf = {.kind = LSDEM_SDF_SPHERE, .a = {0.1}},
                                   .radius = 0.1};
  scene sc;
  scene_init(&sc, g, 0.0, dt, 0.0, 0.3);
  const double x[3] = {0, 0, r + 0.2}, z[3] = {0, 0, 0};
  sc.ng = 1;
  sc.g[0].s = fx_sphere(1, r, x, z);
  sc.g[0].shape = &ball;
  for (int step = 0; step < 2000; step++) scene_step(&sc);
  double zmin = HUGE_VAL, zmax = -HUGE_VAL;
  for (int step = 0; step < 500; step++) {
    scene_step(&sc);
    zmin = fmin(zmin, sc.g[0].s.x[2]);
    zmax = fmax(zmax, sc.g[0].s.x[2]);
  }
  CHECK(zmin > r - 2 * g * dt * dt && zmax < r + 2 * g * dt * dt, "ball at %g .. %g", zmin,
        zmax);
  CHECK(fabs(sc.g[0].s.v[2]) <= 1e-12, "still moving: %g", sc.g[0].s.v[2]);
  CHECK(sc.corrections >= 500, "only %lld wall corrections", (long long)sc.corrections);
  printf("ball at rest: centre %.9f .. %.9f (r %.1f), %lld corrections\n", zmin, zmax, r,
         (long long)sc.corrections);
}

/* ---------------------------------------------------------------- incline ---- */

/* A block 1 x 1 x 0.5 with nodes on a lattice of spacing 0.25 over its surface. */
enum { BLOCK_NODES = 66 };
static double block_nodes[3 * BLOCK_NODES];

static lsdem_shape block_shape(void)
{
  int n = 0;
  for (int i = 0; i <= 4; i++)
    for (int j = 0; j <= 4; j++)
      for (int k = 0; k <= 2; k++) {
        if (i % 4 && j % 4 && k % 2) continue; /* interior */
        block_nodes[3 * n] = -0.5 + 0.25 * i;
        block_nodes[3 * n + 1] = -0.5 + 0.25 * j;
        block_nodes[3 * n + 2] = -0.25 + 0.25 * k;
        n++;
      }
  CHECK(n == BLOCK_NODES, "%d nodes", n);
  return fix_shape(fix_sdf(LSDEM_SDF_BOX, 0.5, 0.5, 0.25), n, block_nodes, 0.75);
}

/* The block resting on the plane z = 0 under gravity tilted by theta about y (the
 * incline's frame), for T seconds: returns the velocity and displacement along the slope.
 */
static void run_incline(double theta, double mu, double T, double *vx, double *dx,
                        double *tilt, scene *sc)
{
  const double g = 9.81, dt = 1e-3, m = 0.5;
  const lsdem_shape shape = block_shape();
  scene_init(sc, g, theta, dt, mu, 0.5);
  const double x[3] = {0, 0, 0.25}, z[3] = {0, 0, 0};
  sc->ng = 1;
  sc->g[0].s = fx_grain(1, m, m * 1.25 / 12, m * 1.25 / 12, m * 2.0 / 12, x, z, z);
  sc->g[0].shape = &shape;
  const int n = (int)lround(T / dt);
  for (int step = 0; step < n; step++) scene_step(sc);
  *vx = sc->g[0].s.v[0];
  *dx = sc->g[0].s.x[0];
  *tilt = 2.0 *
          asin(sqrt(sc->g[0].s.q[1] * sc->g[0].s.q[1] + sc->g[0].s.q[2] * sc->g[0].s.q[2]));
  CHECK(fabs(sc->g[0].s.x[2] - 0.25) < 1e-3, "block left the plane: z %g", sc->g[0].s.x[2]);
}

/* tan(theta) < mu: static friction holds the block; tan(theta) > mu: it slides with
 * a = g (sin theta - mu cos theta). */
static void test_incline(void)
{
  const double g = 9.81, T = 0.5, theta = 30.0 * FIX_PI / 180.0;
  double vx, dx, tilt;
  scene sc;
  run_incline(theta, 0.8, T, &vx, &dx, &tilt, &sc);
  CHECK(fabs(dx) < 1e-4 && fabs(vx) < 1e-3, "stick (tan %.3f < mu 0.8): dx %g, vx %g",
        tan(theta), dx, vx);
  printf("incline 30 deg, mu 0.8: dx %.2e, vx %.2e, tilt %.2e rad, %lld corrections "
         "(%lld sliding)\n",
         dx, vx, tilt, (long long)sc.corrections, (long long)sc.sliding);
  const double mu = 0.3, a = g * (sin(theta) - mu * cos(theta));
  run_incline(theta, mu, T, &vx, &dx, &tilt, &sc);
  CHECK_REL(vx / T, a, 0.02);
  CHECK_REL(2.0 * dx / (T * T), a, 0.02);
  printf(
      "incline 30 deg, mu 0.3: a from v %.4f, from x %.4f, expected %.4f (errors %.2f %%, "
      "%.2f %%), tilt %.2e rad\n",
      vx / T, 2.0 * dx / (T * T), a, 100.0 * (vx / T / a - 1),
      100.0 * (2 * dx / (T * T) / a - 1), tilt);
}

/* ------------------------------------------------------ the correction alone ---- */

/* Correct grain b against wall B (pose pw, prescribed velocity pw.v) once. */
static lsdem_wall_result correct_once(const fx_state *s, lsdem_impulse_body *b,
                                      const lsdem_shape *A, const lsdem_shape *B,
                                      const lsdem_pose *pw, double dt, double rest,
                                      double mu, lsdem_manifold *m)
{
  const lsdem_wall_params p = {.rest_speed = rest, .depth_tol = 1e-9, .mu = mu};
  lsdem_pose pg, pwp = *pw;
  lsdem_impulse_predict_pose(s->x, s->q, b->v, b->omega, s->inertia, dt, &pg);
  for (int d = 0; d < 3; d++) pwp.x[d] += dt * pw->v[d];
  const lsdem_detect_params det = {1, 0.0};
  lsdem_detect(A, &pg, B, &pwp, &det, 0, NULL, NULL, m);
  lsdem_wall_result wr;
  lsdem_error err;
  CHECK(lsdem_wall_correct(b, m, dt, &p, &wr, &err) == LSDEM_OK, "%s", err.msg);
  return wr;
}

/* A sphere touching the plane and approaching at g dt is stopped exactly; fast approach
 * is a collision, fast leaving a separation: both left alone. */
static void test_correction_ball(void)
{
  static const lsdem_shape ball = {.sdf = {.kind = LSDEM_SDF_SPHERE, .a = {0.1}},
                                   .radius = 0.1};
  const lsdem_shape plane = fix_shape(fix_sdf(LSDEM_SDF_PLANE, 0, 0, 0), 0, NULL, HUGE_VAL);
  const lsdem_pose pw = fix_pose(0, 0, 0);
  const double dt = 1e-3, g = 9.81, x[3] = {0, 0, 0.1};
  lsdem_manifold *m = fix_manifold();
  const double speeds[3] = {-g * dt, -1.0, 0.5};
  const lsdem_wall_contact_kind want[3] = {LSDEM_WALL_RESTING, LSDEM_WALL_COLLIDING,
                                           LSDEM_WALL_CLEAR};
  for (int k = 0; k < 3; k++) {
    const double v[3] = {0.2, 0, speeds[k]};
    fx_state s = fx_sphere(1, 0.1, x, v);
    lsdem_impulse_body b;
    fx_body_of(&s, &b);
    const lsdem_wall_result wr =
        correct_once(&s, &b, &ball, &plane, &pw, dt, 2 * g * dt, 0, m);
    CHECK(wr.kind == want[k], "approach %g: kind %d", speeds[k], wr.kind);
    if (wr.kind == LSDEM_WALL_RESTING) {
      CHECK_NEAR(b.v[2], 0.0, 1e-14);
      CHECK_NEAR(wr.impulse[2], s.mass * g * dt, 1e-15);
      CHECK(b.v[0] == 0.2, "frictionless wall changed the tangential velocity");
      CHECK(correct_once(&s, &b, &ball, &plane, &pw, dt, 2 * g * dt, 0, m).kind ==
                LSDEM_WALL_CLEAR,
            "still penetrating after the correction");
    } else {
      CHECK(b.v[2] == speeds[k], "velocity changed");
    }
  }
  /* a sphere sunk 1e-4 into the plane, leaving slowly: resting, pushed out */
  const double xs[3] = {0, 0, 0.1 - 1e-4}, vs[3] = {0, 0, 0.001};
  fx_state s = fx_sphere(1, 0.1, xs, vs);
  lsdem_impulse_body b;
  fx_body_of(&s, &b);
  lsdem_wall_result wr = correct_once(&s, &b, &ball, &plane, &pw, dt, 2 * g * dt, 0, m);
  CHECK(wr.kind == LSDEM_WALL_RESTING, "kind %d", wr.kind);
  CHECK_NEAR(b.v[2], 1e-4 / dt, 1e-12);
  CHECK(lsdem_wall_classify(0.03, 0.02) == LSDEM_WALL_SEPARATING &&
            lsdem_wall_classify(-0.03, 0.02) == LSDEM_WALL_COLLIDING &&
            lsdem_wall_classify(-0.02, 0.02) == LSDEM_WALL_RESTING,
        "classification at the thresholds");
}

/* A tilted, spinning block sinking into the plane. Frictionless, one correction raises
 * its deepest node's normal velocity by exactly d/dt (that node is then clear at the next
 * predicted pose to first order); with friction (which couples in through the torque of
 * the tangential impulse) repeated corrections clear the block within a few passes. */
static void test_correction_tilted_block(void)
{
  const lsdem_shape block = block_shape(),
                    plane = fix_shape(fix_sdf(LSDEM_SDF_PLANE, 0, 0, 0), 0, NULL, HUGE_VAL);
  const lsdem_pose pw = fix_pose(0, 0, 0);
  const double dt = 1e-3, th = 0.1;
  const double x[3] = {0, 0, 0.25 * cos(th) + 0.5 * sin(th) + 0.002};
  const double v[3] = {0.05, 0, -3.0}, w[3] = {0.3, -0.4, 0.2};
  fx_state s = fx_grain(1, 0.5, 0.5 * 1.25 / 12, 0.5 * 1.25 / 12, 1.0 / 12, x, v, w);
  s.q[0] = cos(th / 2);
  s.q[2] = sin(th / 2); /* tilted about y */
  lsdem_manifold *m = fix_manifold();
  for (int fr = 0; fr <= 1; fr++) {
    const double mu = fr ? 0.5 : 0.0;
    lsdem_impulse_body b;
    fx_body_of(&s, &b);
    lsdem_wall_result wr = correct_once(&s, &b, &block, &plane, &pw, dt, 10.0, mu, m);
    CHECK(wr.kind == LSDEM_WALL_RESTING && m->n >= 1, "kind %d, %d points", wr.kind, m->n);
    const lsdem_contact_point deep = m->point[wr.deepest];
    double p[3], u[3]; /* the deepest node's velocity after, same arm from the centroid */
    for (int i = 0; i < 3; i++) p[i] = deep.point[i] - m->xa[i] + b.x[i];
    lsdem_impulse_point_velocity(&b, p, u);
    const double dun = lsdem_dot3(u, deep.normal) - wr.u_n;
    if (!fr) CHECK_REL(dun, wr.depth / dt, 1e-12);
    int passes = 1;
    double depth[10] = {wr.depth};
    while (passes < 10 && wr.kind == LSDEM_WALL_RESTING) {
      wr = correct_once(&s, &b, &block, &plane, &pw, dt, 10.0, mu, m);
      depth[passes++] = wr.depth;
    }
    CHECK(wr.kind == LSDEM_WALL_CLEAR, "mu %g: still %g deep after %d passes", mu, wr.depth,
          passes);
    printf("tilted block, mu %.1f: %d points, u_n %.3f raised by %.3f (d/dt %.3f), clear "
           "after %d passes, depths",
           mu, m->n, deep.vrel[2], dun, depth[0] / dt, passes);
    for (int k = 0; k < passes; k++) printf(" %.1e", depth[k]);
    printf("\n");
  }
}

/* A platen moving up at 0.5 under a resting grain: the grain is given the platen's
 * velocity; the inside of a cylinder container (an inverted cylinder) holds a grain
 * pressing outwards. */
static void test_correction_moving_and_cylinder(void)
{
  static const lsdem_shape ball = {.sdf = {.kind = LSDEM_SDF_SPHERE, .a = {0.1}},
                                   .radius = 0.1};
  const lsdem_shape plane = fix_shape(fix_sdf(LSDEM_SDF_PLANE, 0, 0, 0), 0, NULL, HUGE_VAL);
  const double dt = 1e-3, g = 9.81;
  lsdem_manifold *m = fix_manifold();
  lsdem_pose pw = fix_pose(0, 0, 0.2);
  pw.v[2] = 0.5;
  const double x[3] = {0, 0, 0.3}, v[3] = {0, 0, 0.5 - g * dt};
  fx_state s = fx_sphere(1, 0.1, x, v);
  lsdem_impulse_body b;
  fx_body_of(&s, &b);
  lsdem_wall_result wr = correct_once(&s, &b, &ball, &plane, &pw, dt, 2 * g * dt, 0, m);
  CHECK(wr.kind == LSDEM_WALL_RESTING, "kind %d", wr.kind);
  CHECK_NEAR(b.v[2], 0.5, 1e-12);

  lsdem_shape can = fix_shape(fix_sdf(LSDEM_SDF_CYLINDER, 1.0, 0.0, 0), 0, NULL, HUGE_VAL);
  can.sdf.inverted = 1;
  const lsdem_pose pc = fix_pose(0, 0, 0);
  const double xc[3] = {0.9, 0, 0}, vc[3] = {0.005, 0.3, 0};
  s = fx_sphere(2, 0.1, xc, vc);
  fx_body_of(&s, &b);
  wr = correct_once(&s, &b, &ball, &can, &pc, dt, 0.01, 0, m);
  CHECK(wr.kind == LSDEM_WALL_RESTING, "cylinder kind %d", wr.kind);
  CHECK_NEAR(wr.u_n, -0.005, 1e-4); /* a little more: the normal turns with the motion */
  /* cleared to first order: the wall's curvature under the tangential motion leaves
   * (0.3 dt)^2 / 2 = 4.5e-8 */
  wr = correct_once(&s, &b, &ball, &can, &pc, dt, 0.01, 0, m);
  CHECK(wr.kind == LSDEM_WALL_CLEAR || wr.depth < 1e-7, "outside the container by %g",
        wr.depth);
  CHECK_NEAR(b.v[1], 0.3, 1e-5); /* the normal turned by 3e-4 */
}

/* A rod (principal moments of a thin bar along x) whose deepest point is one end and
 * whose far end carries many shallow points: the overlaps' torque would push the deepest
 * end down (no positive lambda), so the deepest point alone is pushed out. */
static void test_correction_fallback(void)
{
  lsdem_contact_point pts[9];
  const double L = 1.0, m = 1.0, I = m * L * L / 3.0, dt = 1e-3;
  for (int k = 0; k < 9; k++) {
    memset(&pts[k], 0, sizeof pts[k]);
    pts[k].point[0] = k == 0 ? -L : L;
    pts[k].point[1] = k == 0 ? 0.0 : 0.01 * (k - 4);
    pts[k].normal[2] = 1.0;
    pts[k].area = 1.0;
    pts[k].depth = k == 0 ? 1e-4 : 0.5e-4;
  }
  lsdem_manifold man = lsdem_manifold_over(pts, 9);
  man.n = 9;
  const double x[3] = {0, 0, 0}, z[3] = {0, 0, 0};
  fx_state s = fx_grain(1, m, 1e-3, I, I, x, z, z);
  lsdem_impulse_body b;
  fx_body_of(&s, &b);
  const lsdem_wall_params p = {.rest_speed = 1.0, .depth_tol = 0.0, .mu = 0.0};
  lsdem_wall_result wr;
  CHECK(lsdem_wall_correct(&b, &man, dt, &p, &wr, NULL) == LSDEM_OK && wr.deepest == 0,
        "deepest %d", wr.deepest);
  /* impulse J along z at (-L, 0, 0): dv = J/m, omega_y = L J / I, deepest end rises by
   * J (1/m + L^2/I) = d/dt */
  const double J = 1e-4 / dt / (1.0 / m + L * L / I);
  CHECK_NEAR(wr.impulse[2], J, 1e-12);
  CHECK_NEAR(b.v[2], J / m, 1e-12);
  CHECK_NEAR(b.omega[1], L * J / I, 1e-12);
  CHECK_NEAR(b.v[2] + b.omega[1] * L, 1e-4 / dt, 1e-12);
}

int main(void)
{
  test_ball_drop();
  test_ball_comes_to_rest();
  test_incline();
  test_correction_ball();
  test_correction_tilted_block();
  test_correction_moving_and_cylinder();
  test_correction_fallback();
  return lsdem_test_summary();
}
