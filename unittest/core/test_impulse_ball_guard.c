/* test_impulse_ball_guard.c -- the ball guard of impulse mode (ball.c; report §4.4.2,
 * Figure 4.4): net balls against grains at the predicted poses, against closed forms
 * computed here from the masses and the geometry:
 *   - two spheres overlapping by d at rest: the impulse d m M / ((m + M) dt) (the reduced
 *     mass closing d in one step), equal and opposite (momentum kept to round-off), the
 *     overlap at the new predicted poses gone, whichever body is the master;
 *   - a grain approaching a ball fast (a collision, which the wall guard leaves to ETM)
 *     that the advance would carry into it: caught, it bounces as a collision of
 *     restitution e does (the relative approach -V becomes e V);
 *   - a box lying on three balls (parallel normals): a stiff box is lifted in one pass by
 *     exactly d/dt, the balls fixed (bodies of infinite mass) or free (the relative speed
 *     d/dt per pair, the momentum kept), where the sum of three unsplit pair corrections
 *     would lift it 3 d/dt; with its own moments repeated passes converge to d/dt, no spin;
 *   - bodies at or beyond nown (ghosts) are not changed; clear pairs are not counted;
 *   - an overlap deeper than a step makes (a ball placed into a grain) is lifted out no
 *     faster than the wall guard's push-out limit, max(r, sqrt(r d / dt)). */
#include "impulse_fixtures.h"

static lsdem_shape sphere_shape(double r)
{
  return fix_shape(fix_sdf(LSDEM_SDF_SPHERE, r, 0, 0), 0, NULL, r);
}

/* body k and its grain record at x with velocity v: mass m, moments I (inv_mass 0: a body
 * of prescribed velocity) */
static void make_body(lsdem_impulse_body *b, lsdem_impulse_grain *g, int64_t id, double m,
                      double I, const double x[3], const double v[3], const lsdem_shape *shape)
{
  memset(g, 0, sizeof *g);
  g->q[0] = 1.0;
  g->inertia[0] = g->inertia[1] = g->inertia[2] = I;
  g->mass = m;
  g->radius = shape->radius;
  g->shape = shape;
  g->groups = 1;
  const double z[3] = {0, 0, 0};
  lsdem_error err;
  if (m > 0.0)
    CHECK(lsdem_impulse_body_grain(b, id, m, g->inertia, g->q, x, v, z, &err) == LSDEM_OK,
          "%s", err.msg);
  else
    CHECK(lsdem_impulse_body_wall(b, id, x, v, z, &err) == LSDEM_OK, "%s", err.msg);
}

static const double DT = 1e-3, E = 0.5; /* time step, restitution */
/* rest_speed, depth_tol, mu: the overlaps below stay under the push-out limit (rest_speed
 * dt), so that the lift is d/dt; the last test takes a deep one */
static const lsdem_wall_params PRM = {1.0, 1e-9, 0.0};

static lsdem_ball_guard_pair guard_pair(int32_t a, int32_t b)
{
  lsdem_ball_guard_pair q;
  memset(&q, 0, sizeof q);
  q.a = a;
  q.b = b;
  return q;
}

/* one pass of the guard over pairs (detect, then correct bodies below nown); returns the
 * pairs corrected, the counts in count (nbodies) */
static int guard_pass(lsdem_impulse_body *body, const lsdem_impulse_grain *grain, int nbodies,
                      lsdem_ball_guard_pair *pairs, int n, int nown, int32_t *count)
{
  lsdem_contact_point pts[8];
  lsdem_detect_params det = {1, 0.0};
  memset(count, 0, sizeof(int32_t) * (size_t)nbodies);
  lsdem_impulse_ball_guard_detect(body, grain, pairs, n, &det, &PRM, E, DT, 0, pts, 8, count);
  /* the energy audit: the impulses' booked work is the kinetic energy change of the bodies
   * they moved (those below nown), to round-off */
  double before = 0.0, after = 0.0, work = 0.0;
  for (int i = 0; i < nown; i++)
    before += lsdem_impulse_kinetic_energy(grain[i].mass, grain[i].inertia, grain[i].q,
                                           body[i].v, body[i].omega);
  const int corrected = lsdem_impulse_ball_guard_correct(body, pairs, n, count, nown, &work);
  for (int i = 0; i < nown; i++)
    after += lsdem_impulse_kinetic_energy(grain[i].mass, grain[i].inertia, grain[i].q,
                                          body[i].v, body[i].omega);
  CHECK(fabs((after - before) - work) <= 1e-12 * fmax(fmax(before, after), fabs(work)),
        "ball guard: booked %.17g, dKE %.17g", work, after - before);
  CHECK(corrected == 0 || work != 0.0 || after == before, "a correction booked no work");
  return corrected;
}

/* the overlap of two spheres at their predicted centres x + v dt */
static double predicted_overlap(const lsdem_impulse_body *a, double ra,
                                const lsdem_impulse_body *b, double rb)
{
  double d[3];
  for (int i = 0; i < 3; i++) d[i] = (a->x[i] + DT * a->v[i]) - (b->x[i] + DT * b->v[i]);
  return ra + rb - sqrt(lsdem_dot3(d, d));
}

/* A ball (r 0.05, m 0.01) and a spherical grain (R 0.3, M 2) at rest, overlapping by d
 * along a tilted line; ids chosen so that either body is the sphere-sphere master. */
static void test_two_spheres(int64_t id_ball, int64_t id_grain)
{
  const double r = 0.05, R = 0.3, m = 0.01, M = 2.0, d = 2e-4;
  lsdem_shape sb = sphere_shape(r), sg = sphere_shape(R);
  const double n[3] = {0.6, 0.0, 0.8}; /* from the grain towards the ball */
  const double xg[3] = {0.1, -0.2, 0.4}, z[3] = {0, 0, 0};
  double xb[3];
  for (int i = 0; i < 3; i++) xb[i] = xg[i] + (r + R - d) * n[i];
  lsdem_impulse_body body[2];
  lsdem_impulse_grain grain[2];
  make_body(&body[0], &grain[0], id_ball, m, 0.4 * m * r * r, xb, z, &sb);
  make_body(&body[1], &grain[1], id_grain, M, 0.4 * M * R * R, xg, z, &sg);
  lsdem_ball_guard_pair pair = guard_pair(0, 1);
  int32_t count[2];
  CHECK(guard_pass(body, grain, 2, &pair, 1, 2, count) == 1, "ids %lld %lld: not corrected",
        (long long)id_ball, (long long)id_grain);
  CHECK(count[0] == 1 && count[1] == 1, "counts %d %d", count[0], count[1]);
  CHECK_REL(pair.depth, d, 1e-9);
  const double lambda = d * m * M / ((m + M) * DT); /* reduced mass times d / dt */
  double p[3] = {0, 0, 0};
  for (int i = 0; i < 3; i++) {
    CHECK_NEAR(body[0].v[i], lambda * n[i] / m, 1e-9 * lambda / m);
    CHECK_NEAR(body[1].v[i], -lambda * n[i] / M, 1e-9 * lambda / m);
    p[i] = m * body[0].v[i] + M * body[1].v[i];
  }
  CHECK(sqrt(lsdem_dot3(p, p)) < 1e-14 * lambda, "momentum %g of the impulse %g",
        sqrt(lsdem_dot3(p, p)), lambda);
  CHECK(sqrt(lsdem_dot3(body[0].omega, body[0].omega)) < 1e-12 &&
            sqrt(lsdem_dot3(body[1].omega, body[1].omega)) < 1e-12,
        "a central push turned a sphere");
  CHECK(fabs(predicted_overlap(&body[0], r, &body[1], R)) < 1e-12,
        "overlap at the new predicted poses %g", predicted_overlap(&body[0], r, &body[1], R));
  CHECK(guard_pass(body, grain, 2, &pair, 1, 2, count) == 0 && count[0] == 0,
        "the closed pair corrected again");
}

/* A grain approaching a resting ball at 50 rest speeds, 0.2 of its speed's step away: the
 * advance would carry it 0.8 v dt into the ball. The wall guard calls that a collision and
 * leaves it; the ball guard gives it the bounce of restitution e. A ball outside nown (a ghost) keeps
 * its velocity, and the pair is not counted (its owner counts it). */
static void test_fast_approach(void)
{
  const double r = 0.05, R = 0.3, m = 0.01, M = 2.0, V = 50 * PRM.rest_speed;
  lsdem_shape sb = sphere_shape(r), sg = sphere_shape(R);
  const double gap = 0.2 * V * DT;
  const double xb[3] = {0, 0, 0}, xg[3] = {0, 0, r + R + gap}, zero[3] = {0, 0, 0};
  const double vg[3] = {0, 0, -V};
  lsdem_impulse_body body[2];
  lsdem_impulse_grain grain[2];
  make_body(&body[0], &grain[0], 1, m, 0.4 * m * r * r, xb, zero, &sb);
  make_body(&body[1], &grain[1], 2, M, 0.4 * M * R * R, xg, vg, &sg);
  lsdem_ball_guard_pair pair = guard_pair(0, 1);
  int32_t count[2];
  CHECK(guard_pass(body, grain, 2, &pair, 1, 2, count) == 1, "fast approach not caught");
  CHECK_REL(pair.depth, 0.8 * V * DT, 1e-9);
  /* a collision: the approach -V becomes e V (more than the 0.8 V that closes the gap) */
  const double lambda = (1.0 + E) * V * m * M / (m + M);
  CHECK_REL(body[0].v[2], -lambda / m, 1e-9);
  CHECK_REL(body[1].v[2], -V + lambda / M, 1e-9);
  CHECK_REL(body[1].v[2] - body[0].v[2], E * V, 1e-9);
  /* the pair counted by the owner of a: listed with the grain as a (both owned), once;
   * with nothing owned (nown = 0), not counted and nothing changed */
  make_body(&body[0], &grain[0], 1, m, 0.4 * m * r * r, xb, zero, &sb);
  make_body(&body[1], &grain[1], 2, M, 0.4 * M * R * R, xg, vg, &sg);
  pair.a = 1; /* the grain as a: owned */
  pair.b = 0;
  const int counted = guard_pass(body, grain, 2, &pair, 1, 2, count);
  CHECK(counted == 1, "owned a: %d counted", counted);
  make_body(&body[0], &grain[0], 1, m, 0.4 * m * r * r, xb, zero, &sb);
  make_body(&body[1], &grain[1], 2, M, 0.4 * M * R * R, xg, vg, &sg);
  pair.a = 0;
  pair.b = 1;
  CHECK(guard_pass(body, grain, 2, &pair, 1, 0, count) == 0, "a ghost's pair counted");
  CHECK(body[0].v[2] == 0.0 && body[1].v[2] == -V, "a body beyond nown changed");
}

/* A box (half-extents 0.4 0.2 0.1, mass M) at rest on three balls under its bottom face at
 * x = -0.3, 0, 0.3, each overlapping it by d: the normals are parallel (the face's), so the
 * exact correction lifts the box by d/dt relative to the balls.
 * Stiff box (moments 1e12: the arms add no turn): one pass is exact. Balls fixed (bodies of
 * infinite mass): the box's v_z = d/dt (without the mass split it would be 3 d/dt); balls
 * free (mass m): each pair's relative speed rises by d/dt, momentum kept.
 * The box's own moments: the outer pairs' responses include a turn, so a pass lifts less
 * than d/dt and passes repeated converge to it, without spin, until no pair is deeper than
 * depth_tol at the predicted poses. */
static void test_box_on_three_balls(int free_balls, int stiff)
{
  const double h[3] = {0.4, 0.2, 0.1}, r = 0.05, d = 3e-4, M = 1.5, m = 0.02;
  lsdem_shape sbox = fix_shape(fix_sdf(LSDEM_SDF_BOX, h[0], h[1], h[2]), 0, NULL,
                               sqrt(lsdem_dot3(h, h)));
  lsdem_shape sb = sphere_shape(r);
  const double zero[3] = {0, 0, 0}, xbox[3] = {0.05, 0.0, 1.0};
  lsdem_impulse_body body[4];
  lsdem_impulse_grain grain[4];
  const double Ibox = stiff ? 1e12 : M / 3.0 * (h[0] * h[0] + h[2] * h[2]);
  make_body(&body[0], &grain[0], 10, M, Ibox, xbox, zero, &sbox);
  lsdem_ball_guard_pair pairs[3];
  for (int k = 0; k < 3; k++) {
    const double xb[3] = {xbox[0] - 0.3 + 0.3 * k, 0.0, xbox[2] - h[2] - r + d};
    make_body(&body[1 + k], &grain[1 + k], 1 + k, free_balls ? m : 0.0, 0.4 * m * r * r, xb,
              zero, &sb);
    pairs[k] = guard_pair(1 + k, 0);
  }
  int32_t count[4];
  CHECK(guard_pass(body, grain, 4, pairs, 3, 4, count) == 3, "not every pair corrected");
  CHECK(count[0] == 3, "the box's count %d", count[0]);
  int passes = 1;
  if (!stiff) {
    const double lift = body[0].v[2] - body[2].v[2]; /* the middle pair's */
    CHECK(lift > 0.3 * d / DT && lift < d / DT, "first pass: lift %g of %g", lift, d / DT);
    while (passes < 100 && guard_pass(body, grain, 4, pairs, 3, 4, count) > 0) passes++;
    CHECK(passes < 100, "no convergence in 100 passes");
  }
  const double spin = sqrt(lsdem_dot3(body[0].omega, body[0].omega));
  CHECK(spin < 1e-9 * d / DT, "a symmetric lift turned the box: %g", spin);
  /* stiff: exact; else no pair deeper than depth_tol at the predicted poses, none lifted
   * clear by more than 1 % of d */
  double pz = M * body[0].v[2];
  for (int k = 0; k < 3; k++) {
    const double lift = body[0].v[2] - body[1 + k].v[2];
    if (stiff) CHECK_REL(lift, d / DT, 1e-9);
    else
      CHECK(lift >= (d - PRM.depth_tol) / DT && lift <= 1.01 * d / DT, "pair %d: lift %.9g of %g",
            k, lift, d / DT);
    pz += m * body[1 + k].v[2] * free_balls;
  }
  if (free_balls) CHECK(fabs(pz) < 1e-14 * M * d / DT, "momentum %g", pz);
  if (stiff && free_balls) /* lambda = d / (dt (1/m + 3/M)) per pair */
    CHECK_REL(body[0].v[2], 3.0 * d / (DT * (1.0 / m + 3.0 / M)) / M, 1e-9);
  printf("box on three %s balls, %s: %d pass(es), v_z %.9g (d/dt %g)\n",
         free_balls ? "free" : "fixed", stiff ? "stiff" : "its own moments", passes,
         body[0].v[2], d / DT);
}

/* A resting ball of fixed grain overlapping it by 40 rest-speed steps: the pair's relative
 * speed rises by the push-out limit max(r, sqrt(r d / dt)), not d/dt. */
static void test_deep_overlap_limited(void)
{
  const double r = 0.05, R = 0.3, m = 0.01, d = 40 * PRM.rest_speed * DT;
  lsdem_shape sb = sphere_shape(r), sg = sphere_shape(R);
  const double xg[3] = {0, 0, 0}, xb[3] = {0, 0, r + R - d}, zero[3] = {0, 0, 0};
  lsdem_impulse_body body[2];
  lsdem_impulse_grain grain[2];
  make_body(&body[0], &grain[0], 1, m, 0.4 * m * r * r, xb, zero, &sb);
  make_body(&body[1], &grain[1], 2, 0.0, 0.0, xg, zero, &sg);
  lsdem_ball_guard_pair pair = guard_pair(0, 1);
  int32_t count[2];
  CHECK(guard_pass(body, grain, 2, &pair, 1, 2, count) == 1, "deep overlap not corrected");
  const double rs = PRM.rest_speed;
  CHECK_REL(body[0].v[2], fmax(rs, sqrt(rs * d / DT)), 1e-9);
  CHECK(body[1].v[2] == 0.0, "the fixed grain moved");
}

int main(void)
{
  test_two_spheres(1, 2);
  test_two_spheres(2, 1);
  test_fast_approach();
  for (int stiff = 0; stiff < 2; stiff++) {
    test_box_on_three_balls(0, stiff);
    test_box_on_three_balls(1, stiff);
  }
  test_deep_overlap_limited();
  return lsdem_test_summary();
}
