/* test_impulse_contact.c -- impulse-mode building blocks: the body record's world inverse
 * inertia, the collision matrix K (eq 4.13) checked by the work-energy identity of rigid
 * bodies, the Coulomb-limited increment (eqs 4.14-4.20), the gluing rule, validation,
 * the ETM's priority queue against brute force, and contact islands. */
#include "impulse/queue.h"
#include "impulse_fixtures.h"

/* I^-1 of the record times I = R I0 R^T (formed here) is the identity. */
static void test_world_inverse_inertia(void)
{
  for (int trial = 0; trial < 20; trial++) {
    const double x[3] = {srand1(), srand1(), srand1()}, z[3] = {0, 0, 0};
    fx_state s = fx_grain(trial, 2.0 + urand(), 0.5 + urand(), 1.0 + urand(), 2.0 + urand(),
                          x, z, z);
    fx_random_quat(s.q);
    lsdem_impulse_body b;
    fx_body_of(&s, &b);
    double I[9];
    fx_world_inertia(&s, I);
    double worst = 0.0;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        double sum = 0.0;
        for (int k = 0; k < 3; k++) sum += b.inv_inertia[3 * i + k] * I[3 * k + j];
        worst = fmax(worst, fabs(sum - (i == j)));
      }
    CHECK(worst < 1e-12, "trial %d: |I^-1 I - 1| = %g", trial, worst);
    CHECK_REL(b.inv_mass, 1.0 / s.mass, 1e-15);
  }
}

/* Two random bodies, a point between them. */
static void random_pair(fx_state s[2], lsdem_impulse_body b[2], double p[3])
{
  for (int k = 0; k < 2; k++) {
    const double x[3] = {2.0 * k - 1.0 + 0.3 * srand1(), 0.3 * srand1(), 0.3 * srand1()};
    const double v[3] = {srand1(), srand1(), srand1()},
                 w[3] = {srand1(), srand1(), srand1()};
    s[k] = fx_grain(10 + k, 1.0 + 3.0 * urand(), 0.2 + urand(), 0.4 + urand(),
                    0.6 + urand(), x, v, w);
    fx_random_quat(s[k].q);
    fx_body_of(&s[k], &b[k]);
  }
  for (int i = 0; i < 3; i++) p[i] = 0.4 * srand1();
}

/* For rigid bodies, an impulse P at p (on a, -P on b) changes the kinetic energy by
 * P . u + 1/2 P . K P exactly (u the relative velocity at p): eq 4.21 with K's definition.
 * The energies come from I = R I0 R^T, not from the core's inverse. K is symmetric
 * positive definite. */
static void test_collision_matrix_energy(void)
{
  for (int trial = 0; trial < 50; trial++) {
    fx_state s[2];
    lsdem_impulse_body b[2];
    double p[3], K[9], ua[3], ub[3], u[3], KP[3];
    random_pair(s, b, p);
    lsdem_impulse_collision_matrix(&b[0], &b[1], p, K);
    const double P[3] = {srand1(), srand1(), srand1()}, mP[3] = {-P[0], -P[1], -P[2]};
    lsdem_impulse_point_velocity(&b[0], p, ua);
    lsdem_impulse_point_velocity(&b[1], p, ub);
    lsdem_sub3(ua, ub, u);
    const double e0 = fx_kinetic(&s[0], &b[0]) + fx_kinetic(&s[1], &b[1]);
    lsdem_impulse_apply(&b[0], p, P);
    lsdem_impulse_apply(&b[1], p, mP);
    const double e1 = fx_kinetic(&s[0], &b[0]) + fx_kinetic(&s[1], &b[1]);
    lsdem_mat_vec(K, P, KP);
    CHECK_NEAR(e1 - e0, lsdem_dot3(P, u) + 0.5 * lsdem_dot3(P, KP), 1e-12 * (1.0 + e0));
    /* and the relative velocity changed by K P (eq 4.12) */
    double ua1[3], ub1[3];
    lsdem_impulse_point_velocity(&b[0], p, ua1);
    lsdem_impulse_point_velocity(&b[1], p, ub1);
    for (int i = 0; i < 3; i++) CHECK_NEAR(ua1[i] - ub1[i] - u[i], KP[i], 1e-12);
    double w[3], V[9];
    lsdem_sym_eigen(K, w, V);
    CHECK(K[1] == K[3] && K[2] == K[6] && K[5] == K[7], "K not symmetric");
    CHECK(w[0] > 0.0, "K not positive definite: %g", w[0]);
  }
  /* a wall against a sphere hit on its line of centres: K = 1/m (no rotation) */
  const double x[3] = {0, 0, 1}, z[3] = {0, 0, 0}, p[3] = {0, 0, 0.5};
  fx_state sp = fx_sphere(1, 0.5, x, z);
  lsdem_impulse_body b[2];
  fx_body_of(&sp, &b[0]);
  fx_wall(&b[1], -1, z, z);
  double K[9];
  lsdem_impulse_collision_matrix(&b[0], &b[1], p, K);
  CHECK_REL(K[8], 1.0 / sp.mass, 1e-15);
  CHECK_REL(K[0], 1.0 / sp.mass + 0.25 / (0.4 * sp.mass * 0.25), 1e-14);
}

/* K and the relative velocity at the contact of a random pair. */
static void pair_matrix(double K[9], double u[3])
{
  fx_state s[2];
  lsdem_impulse_body b[2];
  double p[3], ua[3], ub[3];
  random_pair(s, b, p);
  lsdem_impulse_collision_matrix(&b[0], &b[1], p, K);
  lsdem_impulse_point_velocity(&b[0], p, ua);
  lsdem_impulse_point_velocity(&b[1], p, ub);
  lsdem_sub3(ua, ub, u);
}

/* Frictionless: P along n. Friction acts against w, the slip a frictionless increment
 * would leave (u_t + (K n)_t du/knn, formed here); large mu: stuck, the fraction s of w
 * removed (zero tangential restitution for s = 1); small mu: |P_t| = mu P_n. Always
 * n . K P = du_n (eq 4.15). */
static void test_coulomb_increment(void)
{
  int sticks = 0;
  for (int trial = 0; trial < 30; trial++) {
    double K[9], u[3], P[3], KP[3], Kn[3], w[3], Pt[3], x[3];
    pair_matrix(K, u);
    const double n[3] = {0.0, 0.6, 0.8}, du = 0.3 + urand();
    lsdem_mat_vec(K, n, Kn);
    const double un = lsdem_dot3(u, n), knn = lsdem_dot3(n, Kn);
    for (int i = 0; i < 3; i++) w[i] = u[i] - un * n[i] + (Kn[i] - knn * n[i]) * du / knn;
    const double wl = sqrt(lsdem_dot3(w, w));

    CHECK(lsdem_coulomb_impulse(K, n, u, du, 0.0, 1.0, P) == 1, "frictionless slides");
    lsdem_mat_vec(K, P, KP);
    CHECK_NEAR(lsdem_dot3(n, KP), du, 1e-12);
    CHECK_NEAR(sqrt(lsdem_dot3(P, P)), lsdem_dot3(P, n), 1e-12);

    const double shares[2] = {1.0, 0.5};
    for (int k = 0; k < 2; k++) {
      const int stuck = lsdem_coulomb_impulse(K, n, u, du, 1e6, shares[k], P) == 0;
      lsdem_mat_vec(K, P, KP);
      CHECK_NEAR(lsdem_dot3(n, KP), du, 1e-12);
      const double pn = lsdem_dot3(P, n);
      for (int i = 0; i < 3; i++) Pt[i] = P[i] - pn * n[i];
      fix_cross(Pt, w, x);
      CHECK(sqrt(lsdem_dot3(x, x)) <= 1e-12 * wl * (1 + sqrt(lsdem_dot3(Pt, Pt))),
            "friction not along the slip");
      CHECK(lsdem_dot3(Pt, w) <= 0.0, "friction does not oppose the slip");
      if (stuck) { /* what is left of the slip along w: (1 - s) |w| */
        sticks++;
        double after[3];
        for (int i = 0; i < 3; i++) after[i] = u[i] + KP[i];
        CHECK_NEAR(lsdem_dot3(after, w) / wl, (1.0 - shares[k]) * wl, 1e-12);
      }
    }

    const double mu = 0.01;
    const int slides = lsdem_coulomb_impulse(K, n, u, du, mu, 1.0, P);
    lsdem_mat_vec(K, P, KP);
    CHECK_NEAR(lsdem_dot3(n, KP), du, 1e-12);
    const double pn2 = lsdem_dot3(P, n);
    for (int i = 0; i < 3; i++) Pt[i] = P[i] - pn2 * n[i];
    CHECK(pn2 > 0.0 && slides, "normal impulse %g, sliding %d", pn2, slides);
    CHECK_REL(sqrt(lsdem_dot3(Pt, Pt)), mu * pn2, 1e-12);
    CHECK(lsdem_dot3(Pt, w) < 0.0, "friction does not oppose the slip");
  }
  CHECK(sticks > 40, "only %d of 60 random contacts stick at huge mu", sticks);
}

/* A manifold over caller storage with the given points (normal +z unless set). */
static lsdem_manifold manifold_of(lsdem_contact_point *pts, int n)
{
  lsdem_manifold m = lsdem_manifold_over(pts, n);
  m.n = n;
  return m;
}

static void set_point(lsdem_contact_point *p, double x, double y, double z, double area,
                      double depth)
{
  memset(p, 0, sizeof *p);
  p->point[0] = x;
  p->point[1] = y;
  p->point[2] = z;
  p->normal[2] = 1.0;
  p->area = area;
  p->depth = depth;
}

/* A row of 5 points spaced 1 with distance 1.5: the seeds 0, 2, 4 take {0,1}, {2,3},
 * {4}; points are area-weighted, depths the largest; normals 20 degrees apart do not
 * glue at 15 degrees; distance 0 keeps every point. */
static void test_glue_rule(void)
{
  lsdem_contact_point pts[6];
  const double area[5] = {1, 3, 2, 2, 1}, depth[5] = {0.1, 0.3, 0.2, 0.05, 0.4};
  for (int k = 0; k < 5; k++) set_point(&pts[k], k, 0, 0, area[k], depth[k]);
  lsdem_manifold m = manifold_of(pts, 5);
  lsdem_glue_params g;
  lsdem_glue_params_default(&g);
  CHECK_NEAR(g.max_angle, 15.0 * FIX_PI / 180.0, 1e-15);
  g.distance = 1.5;
  lsdem_impulse_contact out[6];
  int32_t group[6];
  lsdem_error err;
  int n = lsdem_impulse_glue(&m, 3, 7, 0.4, 0.6, &g, out, group, &err);
  CHECK(n == 3, "%d contacts", n);
  const int32_t want[5] = {0, 0, 1, 1, 2};
  for (int k = 0; k < 5; k++)
    CHECK(group[k] == want[k], "point %d in group %d", k, group[k]);
  CHECK_NEAR(out[0].point[0], 3.0 / 4.0, 1e-15);         /* (0*1 + 1*3) / 4 */
  CHECK_NEAR(out[1].point[0], (4.0 + 6.0) / 4.0, 1e-15); /* (2*2 + 3*2) / 4 */
  CHECK_NEAR(out[2].point[0], 4.0, 0.0);
  CHECK(out[0].depth == 0.3 && out[1].depth == 0.2 && out[2].depth == 0.4, "depths");
  CHECK(out[1].a == 3 && out[1].b == 7 && out[1].mu == 0.4 && out[1].restitution == 0.6,
        "pair data");
  CHECK(out[0].normal[2] == 1.0, "normal %g", out[0].normal[2]);

  /* tilt point 1's normal by 20 degrees: it no longer joins point 0, and seeds its own
   * group which takes point 2 (1 apart, normals 20 degrees apart: no) -> 0 | 1 | 2,3 | 4 */
  pts[1].normal[0] = sin(20.0 * FIX_PI / 180.0);
  pts[1].normal[2] = cos(20.0 * FIX_PI / 180.0);
  n = lsdem_impulse_glue(&m, 0, 1, 0, 1, &g, out, group, &err);
  CHECK(n == 4, "%d contacts with a tilted normal", n);
  /* tilted by 10 degrees it glues, and the mean normal is the normalised weighted sum */
  const double th = 10.0 * FIX_PI / 180.0;
  pts[1].normal[0] = sin(th);
  pts[1].normal[2] = cos(th);
  n = lsdem_impulse_glue(&m, 0, 1, 0, 1, &g, out, group, &err);
  CHECK(n == 3, "%d contacts with a 10 degree normal", n);
  const double sx = 3.0 * sin(th), sz = 1.0 + 3.0 * cos(th), len = sqrt(sx * sx + sz * sz);
  CHECK_NEAR(out[0].normal[0], sx / len, 1e-15);
  CHECK_NEAR(out[0].normal[2], sz / len, 1e-15);

  g.distance = 0.0;
  n = lsdem_impulse_glue(&m, 0, 1, 0, 1, &g, out, group, &err);
  CHECK(n == 5, "no gluing: %d contacts", n);
  for (int k = 0; k < 5; k++)
    CHECK(memcmp(out[k].point, pts[k].point, sizeof out[k].point) == 0 && group[k] == k,
          "point %d kept as is", k);
  CHECK_NEAR(out[1].normal[0], pts[1].normal[0], 1e-16);

  g.max_angle = 0.5 * FIX_PI;
  CHECK(lsdem_impulse_glue(&m, 0, 1, 0, 1, &g, out, group, &err) == -1,
        "angle pi/2 refused");
  g.max_angle = 0.1;
  CHECK(lsdem_impulse_glue(&m, 0, 1, 0, 1, &g, out, NULL, &err) == -1, "no group storage");
}

/* A real manifold: a box's bottom face (5 x 5 nodes, spacing 0.25) sunk into a plane.
 * Distance 0.3 glues each node with its 4 neighbours' worth of seeds; distance 2 (the
 * whole face) gives one contact at the face's centre with normal +z. */
static void test_glue_box_on_plane(void)
{
  double nodes[3 * 25];
  for (int i = 0; i < 5; i++)
    for (int j = 0; j < 5; j++) {
      double *p = &nodes[3 * (5 * i + j)];
      p[0] = -0.5 + 0.25 * i;
      p[1] = -0.5 + 0.25 * j;
      p[2] = -0.25;
    }
  const lsdem_shape box = fix_shape(fix_sdf(LSDEM_SDF_BOX, 0.5, 0.5, 0.25), 25, nodes, 0.8);
  lsdem_shape plane = fix_shape(fix_sdf(LSDEM_SDF_PLANE, 0, 0, 0), 0, NULL, HUGE_VAL);
  const lsdem_pose pa = fix_pose(0.3, -0.2, 0.24), pb = fix_pose(0, 0, 0);
  lsdem_detect_params det = {1, 0.0};
  lsdem_manifold *m = fix_manifold();
  CHECK(lsdem_detect(&box, &pa, &plane, &pb, &det, 0, NULL, NULL, m) == 25, "%d points",
        m->n);
  lsdem_glue_params g;
  lsdem_glue_params_default(&g);
  lsdem_impulse_contact out[25];
  int32_t group[25];
  g.distance = 2.0;
  CHECK(lsdem_impulse_glue(m, 0, 1, 0.5, 0.5, &g, out, group, NULL) == 1, "one contact");
  CHECK_NEAR(out[0].point[0], 0.3, 1e-14);
  CHECK_NEAR(out[0].point[1], -0.2, 1e-14);
  CHECK_NEAR(out[0].normal[2], 1.0, 1e-15);
  CHECK_NEAR(out[0].depth, 0.01, 1e-14);
  g.distance = 0.3; /* seeds in node order take their free neighbours at 0.25 */
  const int n = lsdem_impulse_glue(m, 0, 1, 0.5, 0.5, &g, out, group, NULL);
  CHECK(n > 1 && n < 25, "%d contacts at distance 0.3", n);
  for (int k = 0; k < 25; k++) {
    double d[3];
    lsdem_sub3(m->point[k].point, out[group[k]].point, d);
    CHECK(lsdem_dot3(d, d) <= 0.6 * 0.6, "point %d beyond 2 distance of its contact", k);
  }
}

/* Non-finite or inconsistent islands are refused, naming the culprit. */
static void test_validation(void)
{
  const double x[3] = {0, 0, 1}, z[3] = {0, 0, 0}, p[3] = {0, 0, 0.5};
  fx_state s = fx_sphere(5, 0.5, x, z);
  lsdem_impulse_body b[3];
  fx_body_of(&s, &b[0]);
  fx_wall(&b[1], -1, z, z);
  fx_wall(&b[2], -2, z, z);
  lsdem_impulse_contact c = fx_contact(0, 1, p, 0, 0, 1, 0.3, 0.5);
  lsdem_error err;
  CHECK(lsdem_impulse_validate(b, 3, &c, 1, &err) == LSDEM_OK, "%s", err.msg);
  c.b = 3;
  CHECK(lsdem_impulse_validate(b, 3, &c, 1, &err) == LSDEM_ERR_ARG, "index out of range");
  c.b = 0;
  CHECK(lsdem_impulse_validate(b, 3, &c, 1, &err) == LSDEM_ERR_ARG, "a == b");
  c.a = 1;
  c.b = 2;
  CHECK(lsdem_impulse_validate(b, 3, &c, 1, &err) == LSDEM_ERR_ARG, "two walls");
  c = fx_contact(0, 1, p, 0, 0, 1, 0.3, 0.5);
  c.normal[2] = 1.1;
  CHECK(lsdem_impulse_validate(b, 3, &c, 1, &err) == LSDEM_ERR_NUMERIC, "normal not unit");
  c = fx_contact(0, 1, p, 0, 0, 1, 0.3, 1.5);
  CHECK(lsdem_impulse_validate(b, 3, &c, 1, &err) == LSDEM_ERR_NUMERIC, "e > 1");
  c = fx_contact(0, 1, p, 0, 0, 1, 0.3, 0.5);
  b[0].v[1] = NAN;
  CHECK(lsdem_impulse_validate(b, 3, &c, 1, &err) == LSDEM_ERR_NUMERIC, "NaN velocity");
  CHECK(strstr(err.msg, "id 5") != NULL, "message names the body: %s", err.msg);
  const double I[3] = {1, 1, 1}, q[4] = {1, 0, 0, 0};
  CHECK(lsdem_impulse_body_grain(&b[0], 1, -1.0, I, q, x, z, z, &err) == LSDEM_ERR_NUMERIC,
        "negative mass");
  const double Ibad[3] = {1, 0, 1}, vnan[3] = {0, INFINITY, 0};
  CHECK(lsdem_impulse_body_grain(&b[0], 1, 1.0, Ibad, q, x, z, z, &err) ==
            LSDEM_ERR_NUMERIC,
        "zero moment");
  CHECK(lsdem_impulse_body_grain(&b[0], 1, 1.0, I, q, x, vnan, z, &err) ==
            LSDEM_ERR_NUMERIC,
        "infinite velocity");
  CHECK(lsdem_impulse_body_wall(&b[1], 1, x, vnan, z, &err) == LSDEM_ERR_NUMERIC,
        "infinite wall velocity");
}

/* The indexed heap against brute force: top = least (key, index), collect = every
 * key <= limit (each once), invariants after each operation. */
static void test_queue(void)
{
  enum { N = 40 };
  int32_t heap[N], pos[N], out[N], stack[N];
  double key[N], ref[N];
  int in[N] = {0};
  lsdem_etm_queue q;
  lsdem_etm_queue_init(&q, N, heap, pos, key);
  int bad = 0;
  for (int op = 0; op < 3000; op++) {
    const int32_t c = (int32_t)(urand() * N) % N;
    if (urand() < 0.3) {
      lsdem_etm_queue_remove(&q, c);
      in[c] = 0;
    } else {
      ref[c] = floor(10.0 * srand1()) / 2.0; /* many ties */
      lsdem_etm_queue_set(&q, c, ref[c]);
      in[c] = 1;
    }
    bad += !lsdem_etm_queue_valid(&q, N);
    int32_t best = -1;
    for (int32_t k = 0; k < N; k++)
      if (in[k] && (best < 0 || ref[k] < ref[best])) best = k;
    if (best >= 0) bad += q.heap[0] != best;
    const double limit = 1.0 * srand1();
    const int32_t n = lsdem_etm_queue_collect(&q, limit, out, stack);
    int seen[N] = {0}, m = 0;
    for (int32_t g = 0; g < n; g++) bad += seen[out[g]]++ != 0; /* no repeats */
    for (int32_t k = 0; k < N; k++)
      if (in[k] && ref[k] <= limit) bad += !seen[k], m++;
    bad += m != n;
  }
  CHECK(bad == 0, "%d mismatches against brute force", bad);
}

/* Islands: labels are the smallest id, walls (negative indices) join nothing, the result
 * does not depend on the order of the pairs. */
static void test_islands(void)
{
  enum { N = 9 };
  const int64_t id[N] = {40, 12, 7, 33, 90, 5, 61, 18, 2};
  /* components {0,1,3}, {2,4,5,6}, {7}, {8}; two wall pairs */
  const int32_t pairs[] = {0, 1, 2, 4, 3, 1, -1, 7, 5, 6, 4, 6, 8, -1};
  const int np = (int)(sizeof pairs / sizeof pairs[0]) / 2;
  int32_t parent[N], size[N];
  int64_t label[N];
  CHECK(lsdem_islands_build(N, id, np, pairs, parent, size, label) == 4, "island count");
  const int64_t want[N] = {12, 12, 5, 12, 5, 5, 5, 18, 2};
  for (int i = 0; i < N; i++)
    CHECK(label[i] == want[i], "body %d label %lld", i, (long long)label[i]);
  lsdem_error err;
  CHECK(lsdem_islands_validate(N, parent, label, &err) == LSDEM_OK, "%s", err.msg);
  int32_t rev[sizeof pairs / sizeof pairs[0]];
  for (int k = 0; k < np; k++) {
    rev[2 * k] = pairs[2 * (np - 1 - k) + 1];
    rev[2 * k + 1] = pairs[2 * (np - 1 - k)];
  }
  int64_t label2[N];
  lsdem_islands_build(N, id, np, rev, parent, size, label2);
  CHECK(memcmp(label, label2, sizeof label) == 0, "labels depend on the pair order");
  parent[3] = 99;
  CHECK(lsdem_islands_validate(N, parent, label, &err) == LSDEM_ERR_ARG, "broken parent");
}

/* The cross-rank merge on a chain 0-1-2-3-4-5 (ids 50, 40, 30, 20, 10, 60) split over two
 * "ranks": rank A owns 0..2 and sees 3 as a ghost, rank B owns 3..5 and sees 2 as a
 * ghost. Exchanging labels (owner -> ghost, ghost -> owner) until nothing changes gives
 * every body the chain's smallest id, 10. */
static void test_islands_merge(void)
{
  const int64_t idA[4] = {50, 40, 30, 20}, idB[4] = {20, 10, 60, 30};
  /* A's local bodies: 0,1,2 owned, 3 = ghost of B's 0; B's: 0,1,2 owned, 3 = ghost of A's 2
   */
  const int32_t pA[] = {0, 1, 1, 2, 2, 3}, pB[] = {3, 0, 0, 1, 1, 2};
  int32_t parA[4], sizA[4], parB[4], sizB[4];
  int64_t labA[4], labB[4];
  lsdem_islands_build(4, idA, 3, pA, parA, sizA, labA);
  lsdem_islands_build(4, idB, 3, pB, parB, sizB, labB);
  CHECK(labA[0] == 20 && labB[2] == 10, "local labels %lld %lld", (long long)labA[0],
        (long long)labB[2]);
  int sweeps = 0, changed = 1;
  while (changed && sweeps < 10) {
    /* forward: A's ghost 3 gets B's owned 0; B's ghost 3 gets A's owned 2; reverse: each
     * owner gets its ghost's label on the other rank */
    const int32_t bodyA[2] = {3, 2}, bodyB[2] = {3, 0};
    const int64_t nlA[2] = {labB[0], labB[3]}, nlB[2] = {labA[2], labA[3]};
    changed = lsdem_islands_merge(4, parA, labA, 2, bodyA, nlA);
    changed |= lsdem_islands_merge(4, parB, labB, 2, bodyB, nlB);
    sweeps++;
  }
  CHECK(!changed, "no fixed point after %d sweeps", sweeps);
  for (int i = 0; i < 4; i++)
    CHECK(labA[i] == 10 && labB[i] == 10, "body %d labels %lld %lld", i, (long long)labA[i],
          (long long)labB[i]);
  lsdem_error err;
  CHECK(lsdem_islands_validate(4, parA, labA, &err) == LSDEM_OK, "%s", err.msg);
}

int main(void)
{
  test_world_inverse_inertia();
  test_collision_matrix_energy();
  test_coulomb_increment();
  test_glue_rule();
  test_glue_box_on_plane();
  test_validation();
  test_queue();
  test_islands();
  test_islands_merge();
  return lsdem_test_summary();
}
