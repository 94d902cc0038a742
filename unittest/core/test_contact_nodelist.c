/* test_contact_nodelist.c -- node lists (lsdem_contact_params.node_skin) change the work,
 * never the result:
 *   - a grain sliding, rolling and jumping over a grid grain and over a plane wall, with
 *     friction history and without, every node and every second node: at every step the
 *     force, both torques, the contact point, the depth, the penetrating nodes and the
 *     shear history are bit-identical to the same run without lists, while most steps
 *     reuse the list (far fewer lookups) and the jumps rebuild it;
 *   - an inverted grid (a grain in a cavity) gives the same results with lists;
 *   - a list is trusted as far as the nodes it leaves out are from touching: lists built
 *     at random poses near a plane and a round grid, used after random moves towards B;
 *   - a list is not trusted under another stride, nor beyond its own validity radius
 *     when the skin changes;
 *   - a listed node whose slack is not used up is not looked up: a resting pair skips most
 *     lookups, with the same results (and every path above with them; a slack twice too
 *     large fails them); a grain hovering within the skin looks up none after the build,
 *     and finds the contact when lowered;
 *   - a pair that rattles gets a wider list (rebuilt far less often), and the base skin's
 *     list back once it rests; never wider than B's gradient bound covers;
 *   - against a grid the list keeps its nodes' cells: lookups in the same cell read them;
 *   - a history in an earlier version's list layout is not read as a list; a damaged node
 *     entry in a list is skipped (never used as a node index);
 *   - a grid grain B screens A's bounding sphere and clusters by its level set (and box)
 *     without dropping a contact: at random poses and after random moves within a list,
 *     the same nodes and force as A's plain nodes against B without a gradient bound
 *     (every node in B's bounding sphere looked up), with far fewer lookups;
 *   - lsdem_grid_outer_lipschitz bounds |phi(p) - phi(p')| / |p - p'| on random nearby
 *     pairs where phi >= 0, stays close to 1 for a sampled exact distance, and its reach
 *     limit is the smallest boundary sample. */
#include "contact_fixtures.h"
#include "lsdem_test.h"

#include <stdlib.h>

enum { STEPS = 400, CAP = 2 * FIX_GRAIN_NODES + 8 };
/* a node index past every node of A */
#define LSDEM_TEST_BAD_NODE 1000000

/* A pair's state (node list and shear history) with its storage. */
typedef struct {
  lsdem_nodelist_head head;
  lsdem_nodelist_entry entry[CAP * LSDEM_NODELIST_MAX_WORDS];
  lsdem_shear_hist shear[CAP];
  lsdem_pair_state st;
} pair_buf;

static void pair_buf_clear(pair_buf *b)
{
  memset(&b->st, 0, sizeof b->st);
  b->st.list.head = &b->head;
  b->st.list.entry = b->entry;
  b->st.shear = b->shear;
}

/* One step of the pair from state in (NULL: none) to out (NULL: not kept). */
static void step_pair(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                      const lsdem_pose *pb, const lsdem_contact_params *prm, int64_t step,
                      const pair_buf *in, pair_buf *out, lsdem_contact_result *res)
{
  lsdem_contact_penalty(A, pa, B, pb, prm, step, in ? &in->st : NULL, out ? &out->st : NULL,
                        fix_manifold(), res);
}

/* Whether b's list was built at step s. */
static int built_at(const pair_buf *b, int64_t s)
{
  return b->st.list.valid && b->head.built == s;
}

/* One run: its own state, swapped between steps. */
typedef struct {
  pair_buf buf[2];
  int cur;
} run_state;

static void run_clear(run_state *r)
{
  pair_buf_clear(&r->buf[0]);
  pair_buf_clear(&r->buf[1]);
  r->cur = 0;
}

static void step_run(run_state *r, const lsdem_shape *A, const lsdem_pose *pa,
                     const lsdem_shape *B, const lsdem_pose *pb,
                     const lsdem_contact_params *prm, int64_t step, lsdem_contact_result *res)
{
  step_pair(A, pa, B, pb, prm, step, &r->buf[r->cur], &r->buf[1 - r->cur], res);
  r->cur = 1 - r->cur;
}

/* The shear entries of a run's current state. */
static const lsdem_shear_hist *shear_entries(const run_state *r, int *n)
{
  *n = r->buf[r->cur].st.nshear;
  return r->buf[r->cur].shear;
}

/* A's pose at step s. SLIDE: a slow slide and roll across B's surface, approaching at
 * height z0 + 0.3 - 0.002 s, with a jump (the list must be rebuilt) every 97 steps.
 * APPROACH: straight down along z at 0.004 per step from z0 + 0.5, so that nodes just
 * outside the list's reach are the first to come into contact. REST: in contact at rest,
 * trembling (a settled pair). */
enum { SLIDE, APPROACH, REST };

static void path_pose(int path, int s, double z0, lsdem_pose *pa)
{
  if (path == REST) { /* APPROACH's pose at step 100, in contact, trembling by 0.002 */
    *pa = fix_pose(0.3, -0.2, z0 + 0.1 + 0.002 * sin(0.3 * s));
    fix_rotation_about(1.0, 0.3, 0.2, 0.4 + 0.0005 * cos(0.2 * s), pa->R);
    return;
  }
  if (path == APPROACH) {
    *pa = fix_pose(0.3, -0.2, z0 + 0.5 - 0.004 * s);
    fix_rotation_about(1.0, 0.3, 0.2, 0.4, pa->R);
    pa->v[2] = -0.004;
    return;
  }
  const double jump = (double)(s / 97);
  *pa = fix_pose(-2.0 + 0.006 * s + 0.7 * jump, sin(0.003 * s) - 0.5 * jump,
                 z0 + 0.3 - 0.002 * s);
  fix_rotation_about(1.0, 0.3 + 0.1 * jump, 0.2, 0.0005 * s + 0.3 * jump, pa->R);
  pa->v[0] = 0.006;
  pa->v[2] = -0.002;
  pa->omega[1] = 0.0005;
}

/* expect: FEWER: the list leaves nodes out (B has a gradient bound), so lookups must drop;
 * SKIPS: besides, most listed nodes are clear of B and keep slack (a resting pair), so
 * most of their lookups are skipped */
enum { FEWER = 1, SKIPS = 2 };

static void compare_runs(const char *what, int path, const lsdem_shape *A,
                         const lsdem_shape *B, const lsdem_pose *pb, double z0, double mu,
                         int stride, double skin, int expect)
{
  const int fewer = expect & FEWER;
  lsdem_contact_params prm = fix_params(50.0, 40.0, mu, 0.5);
  prm.detect.node_stride = stride;
  lsdem_contact_params listed = prm;
  listed.detect.node_skin = skin;
  static run_state plain, fast;
  run_clear(&plain);
  run_clear(&fast);
  long tested_plain = 0, tested_fast = 0;
  int contact_steps = 0, reused = 0, rebuilt = 0, same = 1, same_hist = 1;
  long skipped = 0, held = 0; /* listed nodes not looked up at steps their list held; all */
  for (int s = 0; s < STEPS; s++) {
    lsdem_pose pa;
    path_pose(path, s, z0, &pa);
    lsdem_contact_result rp, rf;
    const pair_buf *before = &fast.buf[fast.cur];
    const int listed_before = before->st.list.valid ? before->head.count : 0;
    step_run(&plain, A, &pa, B, pb, &prm, s, &rp);
    step_run(&fast, A, &pa, B, pb, &listed, s, &rf);
    same &= memcmp(rp.force, rf.force, sizeof rp.force) == 0 &&
            memcmp(rp.torque_a, rf.torque_a, sizeof rp.torque_a) == 0 &&
            memcmp(rp.torque_b, rf.torque_b, sizeof rp.torque_b) == 0 &&
            memcmp(rp.point, rf.point, sizeof rp.point) == 0 && rp.npen == rf.npen &&
            rp.max_depth == rf.max_depth;
    int np, nf;
    const lsdem_shear_hist *hp = shear_entries(&plain, &np), *hf = shear_entries(&fast, &nf);
    same_hist &= np == nf && memcmp(hp, hf, sizeof *hp * (size_t)np) == 0;
    contact_steps += rp.npen > 0;
    tested_plain += rp.ntested;
    tested_fast += rf.ntested;
    if (rp.npen > 0) reused += rf.ntested < rp.ntested / 2;
    rebuilt += built_at(&fast.buf[fast.cur], s);
    if (!built_at(&fast.buf[fast.cur], s) && fast.buf[fast.cur].st.list.valid) {
      skipped += listed_before - rf.ntested;
      held += listed_before;
    }
  }
  CHECK(same, "%s: a result differs with node lists", what);
  /* a settled pair's listed nodes mostly keep clear of B: most lookups skipped */
  CHECK(!(expect & SKIPS) || 2 * skipped > held, "%s: %ld of %ld listed lookups skipped",
        what, skipped, held);
  CHECK(same_hist, "%s: the shear history differs with node lists", what);
  CHECK(contact_steps > STEPS / 2, "%s: only %d steps in contact", what, contact_steps);
  if (!fewer) return;
  CHECK(reused > STEPS / 2 && (rebuilt >= 3 || path == REST), "%s: list reused at %d steps, rebuilt at %d",
        what, reused, rebuilt);
  /* (0.50 for the grid here: without a list B's level set screens A's clusters too) */
  CHECK(5 * tested_fast < 3 * tested_plain, "%s: %ld lookups with lists, %ld without", what,
        tested_fast, tested_plain);
}

/* A rattling pair gets a wider list, a settled one the base skin back: A shakes by 0.4
 * (more than the skin 0.3) at every step for 200 steps, then rests. Results stay those
 * of the plain run; the shaking rebuilds the list only now and then (with the base skin
 * alone it would be rebuilt at every step); at rest the list ends up as the base skin's:
 * as many lookups per step as a fresh list built there. */
static void rattle_pose(int s, lsdem_pose *pa)
{
  const double shake = s < 200 && s % 2 ? 0.4 : 0.0;
  *pa = fix_pose(0.3 + shake, -0.2, 11.7);
  fix_rotation_about(1.0, 0.3, 0.2, 0.4, pa->R);
}

static void test_rattle_widens(const lsdem_shape *A, const lsdem_shape *B, const lsdem_pose *pb)
{
  lsdem_contact_params prm = fix_params(50.0, 40.0, 0.5, 0.5), listed = prm;
  listed.detect.node_skin = 0.3;
  static run_state plain, fast, fresh;
  run_clear(&plain);
  run_clear(&fast);
  run_clear(&fresh);
  int same = 1, rebuilt_shaking = 0;
  lsdem_contact_result rp, rf, r0;
  for (int s = 0; s < STEPS; s++) {
    lsdem_pose pa;
    rattle_pose(s, &pa);
    step_run(&plain, A, &pa, B, pb, &prm, s, &rp);
    step_run(&fast, A, &pa, B, pb, &listed, s, &rf);
    same &= memcmp(rp.force, rf.force, sizeof rp.force) == 0 && rp.npen == rf.npen;
    if (s > 0 && s < 200)
      rebuilt_shaking += built_at(&fast.buf[fast.cur], s);
  }
  lsdem_pose rest;
  rattle_pose(STEPS, &rest);
  step_run(&fresh, A, &rest, B, pb, &listed, 0, &r0);
  step_run(&fresh, A, &rest, B, pb, &listed, 1, &r0);
  CHECK(same && rp.npen > 5, "rattle: results differ with node lists (%d nodes)", rp.npen);
  CHECK(rebuilt_shaking < 30, "rattle: list rebuilt at %d of 199 shaking steps",
        rebuilt_shaking);
  const int rest_entries = fast.buf[fast.cur].head.count,
            fresh_entries = fresh.buf[fresh.cur].head.count;
  CHECK(rest_entries == fresh_entries && rf.ntested < rp.ntested,
        "rattle: %d entries at rest, %d in a fresh list; %d lookups, %d without",
        rest_entries, fresh_entries, rf.ntested, rp.ntested);
}

/* A grain hovering just clear of the plane (REST's pose lifted by `lift`), trembling: its
 * list holds nodes within the skin, none touching. After the build no node is looked up
 * (each listed node's slack covers the trembling), and the results stay those without lists
 * (no contact); a slack that ignored the motion would miss the contact of the next check:
 * the same list lowered onto the plane by 0.25 (more than the skin's 31sts) finds it. */
static void test_hover_skips(const lsdem_shape *A, const lsdem_shape *plane,
                             const lsdem_pose *pw)
{
  lsdem_contact_params prm = fix_params(50.0, 40.0, 0.5, 0.5), listed = prm;
  listed.detect.node_skin = 0.8;
  static run_state plain, fast;
  run_clear(&plain);
  run_clear(&fast);
  const double lift = 0.72;
  int later_lookups = 0, touching = 0, entries = 0;
  lsdem_contact_result rp, rf;
  for (int s = 0; s < 40; s++) {
    lsdem_pose pa;
    path_pose(REST, s, lift, &pa);
    step_run(&plain, A, &pa, plane, pw, &prm, s, &rp);
    step_run(&fast, A, &pa, plane, pw, &listed, s, &rf);
    touching += rp.npen + rf.npen;
    if (s > 0) later_lookups += rf.ntested;
    entries = fast.buf[fast.cur].head.count;
  }
  CHECK(touching == 0 && entries > 0 && later_lookups == 0,
        "hover: %d touching nodes, %d listed, %d lookups after the build", touching, entries,
        later_lookups);
  /* a plane keeps no cells: each entry a word and its node's 3 */
  CHECK(fast.buf[fast.cur].head.words == 4 * entries, "hover: %d words for %d entries",
        fast.buf[fast.cur].head.words, entries);
  lsdem_pose low;
  path_pose(REST, 0, lift - 0.25, &low);
  step_run(&plain, A, &low, plane, pw, &prm, 40, &rp);
  step_run(&fast, A, &low, plane, pw, &listed, 40, &rf);
  CHECK(rp.npen > 0 && rf.npen == rp.npen &&
            memcmp(rp.force, rf.force, sizeof rp.force) == 0,
        "hover, lowered: %d nodes touch, %d found with the list", rp.npen, rf.npen);
}

/* The widening stops where B's gradient bound stops: against a grid whose bound holds only
 * up to 0.5 L (so for the skin 0.3, not for 4 x 0.3), the shaking pair keeps lists that
 * leave nodes out (a list past the bound would list every node it looks up). */
static void test_rattle_bound_limits(const lsdem_shape *A, const lsdem_shape *B,
                                     const lsdem_pose *pb)
{
  lsdem_shape tight = *B;
  tight.sdf.grid.lip_reach = 0.5 * tight.sdf.grid.lip;
  lsdem_contact_params prm = fix_params(50.0, 40.0, 0.5, 0.5), listed = prm;
  listed.detect.node_skin = 0.3;
  static run_state plain, fast;
  run_clear(&plain);
  run_clear(&fast);
  int same = 1;
  lsdem_contact_result rp, rf;
  for (int s = 0; s < 200; s++) {
    lsdem_pose pa;
    rattle_pose(s, &pa);
    step_run(&plain, A, &pa, &tight, pb, &prm, s, &rp);
    step_run(&fast, A, &pa, &tight, pb, &listed, s, &rf);
    same &= memcmp(rp.force, rf.force, sizeof rp.force) == 0 && rp.npen == rf.npen;
  }
  const int listed_nodes = fast.buf[fast.cur].head.count;
  CHECK(same && rp.npen > 5, "rattle, tight bound: results differ (%d nodes)", rp.npen);
  CHECK(listed_nodes > 0 && listed_nodes < rf.ntested,
        "rattle, tight bound: %d nodes listed of %d looked up", listed_nodes, rf.ntested);
}

/* A list holds only as far as it was proven: built with skin 0.1, it must not be trusted
 * after a move of 0.4 under skin 0.5 (new contacts appear); built with stride 2 (every
 * second node), not for stride 1 under the same skin. Against a plain evaluation (mu = 0,
 * no list). */
static void test_list_settings(const lsdem_shape *A, const lsdem_shape *wall,
                               const lsdem_pose *pw)
{
  static pair_buf h0, h1;
  pair_buf_clear(&h0);
  pair_buf_clear(&h1);
  lsdem_contact_params prm = fix_params(50.0, 0.0, 0.0, 0.5), first = prm, second = prm;
  first.detect.node_skin = 0.1;
  second.detect.node_skin = 0.5;
  lsdem_pose pa, moved;
  path_pose(APPROACH, 0, 0.0, &pa);
  moved = pa;
  moved.x[2] -= 0.4;
  lsdem_contact_result r0, r1, ref;
  step_pair(A, &pa, wall, pw, &first, 0, NULL, &h0, &r0);
  step_pair(A, &moved, wall, pw, &second, 1, &h0, &h1, &r1);
  step_pair(A, &moved, wall, pw, &prm, 1, NULL, NULL, &ref);
  CHECK(r1.npen == ref.npen && r1.npen > r0.npen + 3 &&
            memcmp(r1.force, ref.force, sizeof ref.force) == 0,
        "skin changed: %d penetrating nodes, %d without list (%d before the move)", r1.npen,
        ref.npen, r0.npen);
  first.detect.node_stride = 2;
  first.detect.node_skin = second.detect.node_skin;
  step_pair(A, &pa, wall, pw, &first, 0, NULL, &h0, &r0);
  step_pair(A, &pa, wall, pw, &second, 1, &h0, &h1, &r1);
  step_pair(A, &pa, wall, pw, &prm, 1, NULL, NULL, &ref);
  CHECK(r1.npen == ref.npen && r1.npen > r0.npen &&
            memcmp(r1.force, ref.force, sizeof ref.force) == 0,
        "stride changed: %d penetrating nodes, %d without list (%d at stride 2)", r1.npen,
        ref.npen, r0.npen);
}

/* The list keeps the cells of its nodes: at the same pose, a lookup in the same cell reads
 * the kept samples, not the grid. Seen by changing the grid under the list: the listed
 * run still gives the answer of the grid the cells came from. */
static void test_kept_cells(const lsdem_shape *A, const lsdem_shape *B, const lsdem_pose *pb)
{
  static pair_buf h0, h1;
  pair_buf_clear(&h0);
  pair_buf_clear(&h1);
  const lsdem_grid *g = &B->sdf.grid;
  const size_t ns = (size_t)g->n[0] * g->n[1] * g->n[2];
  float *shifted = malloc(ns * sizeof *shifted);
  for (size_t m = 0; m < ns; m++) shifted[m] = g->phi[m] + 0.05f;
  lsdem_shape B2 = *B;
  B2.sdf.grid.phi = shifted;
  lsdem_contact_params prm = fix_params(50.0, 0.0, 0.0, 0.5), listed = prm;
  listed.detect.node_skin = 0.3;
  lsdem_pose pa;
  path_pose(APPROACH, 100, 11.6, &pa);
  lsdem_contact_result r0, r1, on_b, on_b2;
  step_pair(A, &pa, B, pb, &listed, 0, NULL, &h0, &r0);
  step_pair(A, &pa, &B2, pb, &listed, 1, &h0, &h1, &r1);
  step_pair(A, &pa, B, pb, &prm, 1, NULL, NULL, &on_b);
  step_pair(A, &pa, &B2, pb, &prm, 1, NULL, NULL, &on_b2);
  CHECK(on_b.npen > 5 && on_b2.npen != on_b.npen, "%d / %d penetrating nodes", on_b.npen,
        on_b2.npen);
  CHECK(r1.npen == on_b.npen && memcmp(r1.force, on_b.force, sizeof r1.force) == 0,
        "listed run: %d nodes, force %g; from the cells' grid %d, %g", r1.npen, r1.force[2],
        on_b.npen, on_b.force[2]);
  free(shifted);
}

/* A list whose middle node entry is damaged (an id that is no node of A, as a corrupted
 * restart file could hold) is used without that entry: one lookup fewer, and no node
 * index out of A's range is ever read (the ASan build of this test would report it). */
static void test_damaged_entry(const lsdem_shape *A, const lsdem_shape *B, const lsdem_pose *pb)
{
  static pair_buf h0, h1;
  pair_buf_clear(&h0);
  pair_buf_clear(&h1);
  lsdem_contact_params listed = fix_params(50.0, 0.0, 0.0, 0.5);
  listed.detect.node_skin = 0.3;
  lsdem_pose pa;
  path_pose(APPROACH, 100, 11.6, &pa);
  lsdem_contact_result r0, r1;
  step_pair(A, &pa, B, pb, &listed, 0, NULL, &h0, &r0);
  const int nn = h0.head.count;
  CHECK(nn > 4 && r0.ntested >= nn, "%d listed of %d looked up", nn, r0.ntested);
  lsdem_nodelist_at(&h0.head, h0.entry, nn / 2)->node = LSDEM_TEST_BAD_NODE;
  h0.head.slack_unit = 0.0; /* as a list read from state records: no lookup skipped */
  step_pair(A, &pa, B, pb, &listed, 1, &h0, &h1, &r1);
  CHECK(r1.ntested == nn - 1, "damaged list: %d lookups, want %d", r1.ntested, nn - 1);
}

/* Lists are trusted only as far as the nodes they leave out are from touching: lists
 * built at random poses (grain near B, small and wide skins) and then used after random
 * moves towards B, of up to four skins, give the plain answer every time, while many of
 * the moves do reuse the list (seen as fewer lookups where B's bounding sphere is loose;
 * for a round B both look up about the same nodes). */
static void test_random_moves(const lsdem_shape *A, const lsdem_shape *B,
                              const lsdem_pose *pb, double lift, int loose, const char *what)
{
  static pair_buf h0;
  pair_buf_clear(&h0);
  int trusted = 0, same = 1, touching = 0;
  for (int t = 0; t < 300; t++) {
    const double skin = t % 2 ? 0.4 : 2.0;
    lsdem_contact_params prm = fix_params(50.0, 0.0, 0.0, 0.5), listed = prm;
    listed.detect.node_skin = skin;
    lsdem_pose pa = fix_pose(3.0 * srand1(), 3.0 * srand1(), lift + 2.5 * srand1());
    fix_rotation_about(srand1(), srand1(), srand1(), FIX_PI * urand(), pa.R);
    lsdem_contact_result r0;
    step_pair(A, &pa, B, pb, &listed, 0, NULL, &h0, &r0);
    for (int m = 0; m < 8; m++) {
      lsdem_pose moved = pa;
      const double u = 4.0 * skin * urand();
      const double dir[3] = {0.3 * srand1(), 0.3 * srand1(), -1.0};
      for (int i = 0; i < 3; i++) moved.x[i] += u * dir[i] / sqrt(1.18);
      double turn[9], R[9];
      fix_rotation_about(srand1(), srand1(), srand1(), 0.02 * urand(), turn);
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
          R[3 * i + j] = turn[3 * i] * pa.R[j] + turn[3 * i + 1] * pa.R[3 + j] +
                         turn[3 * i + 2] * pa.R[6 + j];
      memcpy(moved.R, R, sizeof R);
      lsdem_contact_result r1, ref;
      step_pair(A, &moved, B, pb, &listed, 1, &h0, NULL, &r1);
      step_pair(A, &moved, B, pb, &prm, 1, NULL, NULL, &ref);
      same &= r1.npen == ref.npen && memcmp(r1.force, ref.force, sizeof r1.force) == 0;
      trusted += r1.ntested < ref.ntested;
      touching += ref.npen > 0;
    }
  }
  CHECK(same, "%s: a moved grain's list missed a contact", what);
  CHECK((trusted > 500 || !loose) && touching > 1000, "%s: %d moves reused the list, %d touch",
        what, trusted, touching);
}

/* A's clusters (and bounding sphere) screened by grid B's level set against the plain
 * detection: A without clusters against B without a gradient bound, which looks up every
 * node in B's bounding sphere. At random poses about `lift` above B (some clusters' centres
 * outside B's grid box, some pairs not touching at all), with a list built and after random
 * moves that the list is trusted over: the same penetrating nodes and force bit for bit,
 * and at least a fifth fewer lookups (0.74 and 0.66 of them at lifts 13 and 15 when
 * written; 0.27 in a 2,500-node sand heap, where the grains' bounding spheres are looser). */
static void test_level_set_screening(const double a[3], const lsdem_shape *B,
                                     const lsdem_pose *pb, double lift)
{
  enum { N = 2000 }; /* clusters small against the grain, as in a library's grains */
  static double nodes[3 * N], area[N], sphere[4 * N];
  static int start[N + 1];
  fix_fibonacci_ellipsoid(N, a, nodes);
  for (int k = 0; k < N; k++) area[k] = 1.0;
  const int nc = lsdem_nodes_cluster(N, nodes, area, LSDEM_CLUSTER_TARGET, start, sphere);
  fix_grain grain, *g = &grain;
  g->plain = fix_shape(B->sdf, N, nodes, fmax(a[0], fmax(a[1], a[2])));
  g->clustered = g->plain;
  g->clustered.nclusters = nc;
  g->clustered.cluster_start = start;
  g->clustered.cluster_sphere = sphere;
  lsdem_shape unscreened = *B;
  unscreened.sdf.grid.lip = 0.0;
  static pair_buf h0;
  pair_buf_clear(&h0);
  long screened_lookups = 0, plain_lookups = 0;
  int same = 1, touching = 0, apart = 0;
  for (int t = 0; t < 400; t++) {
    lsdem_contact_params prm = fix_params(50.0, 0.0, 0.0, 0.5), listed = prm;
    listed.detect.node_skin = t % 2 ? 0.4 : 1.5;
    lsdem_pose pa = fix_pose(4.0 * srand1(), 4.0 * srand1(), lift + 3.0 * srand1());
    fix_rotation_about(srand1(), srand1(), srand1(), FIX_PI * urand(), pa.R);
    for (int m = 0; m < 4; m++) {
      lsdem_contact_result r, ref;
      if (m == 0)
        step_pair(&g->clustered, &pa, B, pb, &listed, 0, NULL, &h0, &r);
      else
        step_pair(&g->clustered, &pa, B, pb, &listed, m, &h0, NULL, &r);
      step_pair(&g->plain, &pa, &unscreened, pb, &prm, 0, NULL, NULL, &ref);
      same &= r.npen == ref.npen && memcmp(r.force, ref.force, sizeof r.force) == 0 &&
              memcmp(r.torque_a, ref.torque_a, sizeof r.torque_a) == 0;
      touching += ref.npen > 0;
      apart += ref.npen == 0;
      if (m == 0) { /* the work without a list: screened against plain */
        lsdem_contact_result rs;
        step_pair(&g->clustered, &pa, B, pb, &prm, 0, NULL, NULL, &rs);
        same &= rs.npen == ref.npen && memcmp(rs.force, ref.force, sizeof rs.force) == 0;
        screened_lookups += rs.ntested;
        plain_lookups += ref.ntested;
      }
      pa.x[2] -= 0.3 * listed.detect.node_skin * urand(); /* within the list's skin */
    }
  }
  CHECK(same, "level-set screening changed a result");
  CHECK(touching > 400 && apart > 100, "%d poses touching, %d apart", touching, apart);
  CHECK(5 * screened_lookups < 4 * plain_lookups, "%ld lookups screened, %ld plain",
        screened_lookups, plain_lookups);
}

static void test_outer_lipschitz(const lsdem_sdf *g)
{
  double limit = 0.0;
  const double L = lsdem_grid_outer_lipschitz(&g->grid, &limit);
  CHECK(L >= 1.0 && L < 1.2, "L = %g for a sampled exact distance", L);
  double lo = HUGE_VAL;
  const int *n = g->grid.n;
  for (int k = 0; k < n[2]; k++)
    for (int j = 0; j < n[1]; j++)
      for (int i = 0; i < n[0]; i++)
        if (!i || !j || !k || i == n[0] - 1 || j == n[1] - 1 || k == n[2] - 1)
          lo = fmin(lo, g->grid.phi[i + n[0] * (j + n[1] * k)]);
  CHECK(limit == lo && limit > 2.5, "reach limit %g, smallest boundary sample %g", limit, lo);
  int pairs = 0, ok = 1;
  double worst = 0.0;
  for (int t = 0; t < 20000; t++) {
    double p[3], q[3], gp[3], gq[3];
    for (int i = 0; i < 3; i++) {
      p[i] = 11.0 * srand1();
      q[i] = p[i] + 0.3 * srand1();
    }
    const double a = lsdem_grid_eval(&g->grid, p, gp), b = lsdem_grid_eval(&g->grid, q, gq);
    if (!(a >= 0.0 && b >= 0.0 && a <= limit && b <= limit)) continue;
    const double d = sqrt(pow(p[0] - q[0], 2) + pow(p[1] - q[1], 2) + pow(p[2] - q[2], 2));
    const double ratio = fabs(a - b) / d;
    worst = fmax(worst, ratio);
    ok &= ratio <= L * (1.0 + 1e-9);
    pairs++;
  }
  CHECK(ok && pairs > 1000, "%d pairs, largest slope %g against L = %g", pairs, worst, L);
}

/* A history in the layout of earlier versions (restart files written by them: masks
 * with ids -3.., the pose at -2 and -1, cells at ids -2^30 + k whose samples are stored
 * otherwise), as records, is not taken for a list: the answer is the plain one and a new
 * list is built at this step. The old entries are filled so that, read as a list, they
 * would hold. */
static void test_old_layout(const lsdem_shape *A, const lsdem_shape *B, const lsdem_pose *pb)
{
  static lsdem_state_record old[CAP];
  static pair_buf in, out;
  pair_buf_clear(&in);
  pair_buf_clear(&out);
  memset(old, 0, sizeof old);
  lsdem_contact_params prm = fix_params(50.0, 40.0, 0.5, 0.5), listed = prm;
  listed.detect.node_skin = 0.3;
  lsdem_pose pa;
  path_pose(APPROACH, 100, 11.6, &pa);
  double M[9], t[3], dx[3], mdx[3];
  for (int i = 0; i < 3; i++) {
    dx[i] = pb->x[i] - pa.x[i];
    mdx[i] = -dx[i];
  }
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      M[3 * i + j] = pb->R[i] * pa.R[j] + pb->R[3 + i] * pa.R[3 + j] + pb->R[6 + i] * pa.R[6 + j];
  lsdem_matT_vec(pb->R, mdx, t);
  int n = 0;
  old[n++] = (lsdem_state_record){.id = -3, .stamp = 99}; /* mask: node 0 alone */
  old[n].id = -2; /* pose M[0..5]; stamp: the validity radius (huge) */
  const double radius = 1e9;
  memcpy(&old[n].stamp, &radius, sizeof radius);
  old[n + 1].id = -1; /* M[6..8], t; stamp: the stride */
  old[n + 1].stamp = 1;
  for (int i = 0; i < 3; i++) {
    old[n].a[i] = M[i];
    old[n].b[i] = M[3 + i];
    old[n + 1].a[i] = M[6 + i];
    old[n + 1].b[i] = t[i];
  }
  n += 2;
  old[0].a[0] = 1.0;
  for (int k = 0; k < 4; k++) old[n++] = (lsdem_state_record){.id = -(1 << 30) + k, .aux = 7};
  lsdem_pair_state_decode(old, n, A->nnodes, &in.st);
  lsdem_contact_result plain, res;
  step_pair(A, &pa, B, pb, &prm, 100, NULL, NULL, &plain);
  step_pair(A, &pa, B, pb, &listed, 100, &in, &out, &res);
  CHECK(plain.npen > 5 && res.npen == plain.npen &&
            memcmp(res.force, plain.force, sizeof res.force) == 0,
        "old layout: %d nodes, force %g; plain %d, %g", res.npen, res.force[2], plain.npen,
        plain.force[2]);
  CHECK(!in.st.list.valid && built_at(&out, 100), "old layout: no new list (%d)",
        out.st.list.valid);
}

int main(void)
{
  const double a[3] = {10.0, 8.0, 6.0};
  lsdem_sdf gsdf;
  lsdem_error err;
  CHECK(fix_ellipsoid_grid(a, &gsdf, &err) == LSDEM_OK, "%s", err.msg);
  gsdf.grid.lip = lsdem_grid_outer_lipschitz(&gsdf.grid, &gsdf.grid.lip_reach);
  static fix_grain ga;
  fix_make_grain(&ga, a, &gsdf);
  const lsdem_shape B = fix_shape(gsdf, 0, NULL, lsdem_sdf_bound_radius(&gsdf));
  const lsdem_shape plane = fix_shape(fix_sdf(LSDEM_SDF_PLANE, 0, 0, 0), 0, NULL, HUGE_VAL);
  lsdem_pose pb = fix_pose(0.0, 0.0, 0.0), pw = fix_pose(0.0, 0.0, -5.6);
  fix_rotation_about(0.2, 1.0, 0.1, 0.7, pb.R);

  test_outer_lipschitz(&gsdf);
  test_list_settings(&ga.clustered, &plane, &pw);
  test_kept_cells(&ga.clustered, &B, &pb);
  test_old_layout(&ga.clustered, &B, &pb);
  test_damaged_entry(&ga.clustered, &B, &pb);
  test_rattle_widens(&ga.clustered, &B, &pb);
  test_hover_skips(&ga.clustered, &plane, &pw);
  test_rattle_bound_limits(&ga.clustered, &B, &pb);
  compare_runs("grid, friction", SLIDE, &ga.clustered, &B, &pb, 11.6, 0.5, 1, 0.3, 1);
  compare_runs("grid, no friction", SLIDE, &ga.clustered, &B, &pb, 11.6, 0.0, 1, 0.3, 1);
  compare_runs("grid, stride 2", SLIDE, &ga.plain, &B, &pb, 11.6, 0.5, 2, 0.3, 1);
  compare_runs("plane, friction", SLIDE, &ga.clustered, &plane, &pw, 0.0, 0.5, 1, 0.3, 1);
  compare_runs("grid, approach", APPROACH, &ga.clustered, &B, &pb, 11.6, 0.5, 1, 0.3, 1);
  /* resting on the grid, most listed nodes touch (this grain's contact is its flat side):
   * no slack kept; on the plane with a wide skin, most are clear of it */
  compare_runs("grid, resting", REST, &ga.clustered, &B, &pb, 11.6, 0.5, 1, 0.3, FEWER);
  compare_runs("plane, resting", REST, &ga.clustered, &plane, &pw, 0.0, 0.5, 1, 0.8,
               FEWER | SKIPS);
  compare_runs("plane, approach", APPROACH, &ga.clustered, &plane, &pw, 0.0, 0.5, 1, 0.3, 1);
  /* a wide skin: the clusters left out by their clearance from the plane bound the list */
  compare_runs("plane, approach, wide skin", APPROACH, &ga.clustered, &plane, &pw, 0.0, 0.5,
               1, 1.5, 0);
  /* a round B, whose bounding sphere is tight: the nodes left out by it bound the list */
  lsdem_sdf ball = fix_sdf(LSDEM_SDF_SPHERE, 8.0, 0, 0);
  lsdem_sdf bgrid = fix_sdf(LSDEM_SDF_GRID, 0, 0, 0);
  const double blo[3] = {-8, -8, -8}, bhi[3] = {8, 8, 8};
  CHECK(lsdem_grid_sample(&ball, blo, bhi, 1.0, 3, &bgrid.grid, &err) == LSDEM_OK, "%s",
        err.msg);
  bgrid.grid.lip = lsdem_grid_outer_lipschitz(&bgrid.grid, &bgrid.grid.lip_reach);
  const lsdem_shape round = fix_shape(bgrid, 0, NULL, lsdem_sdf_bound_radius(&bgrid));
  compare_runs("round grid, approach", APPROACH, &ga.plain, &round, &pb, 14.2, 0.5, 1, 0.3, 0);
  /* a small grain in a round cavity: an inverted grid whose samples inside the ball are
   * three times steeper than outside, same results with lists. (The grid's gradient bound
   * is for its own phi >= 0, so list_reach does not use it for an inverted grid; here the
   * cells across the surface already carry the steep slope, so this case would also pass
   * with it: no test here tells the two apart.) */
  static fix_grain small;
  const double sa[3] = {2.0, 1.6, 1.2};
  fix_make_grain(&small, sa, &bgrid);
  const size_t ns = (size_t)bgrid.grid.n[0] * bgrid.grid.n[1] * bgrid.grid.n[2];
  float *steep = malloc(ns * sizeof *steep);
  for (size_t m = 0; m < ns; m++)
    steep[m] = bgrid.grid.phi[m] < 0.0f ? 3.0f * bgrid.grid.phi[m] : bgrid.grid.phi[m];
  lsdem_shape cavity = round;
  cavity.sdf.grid.phi = steep;
  cavity.sdf.grid.lip = lsdem_grid_outer_lipschitz(&cavity.sdf.grid, &cavity.sdf.grid.lip_reach);
  cavity.sdf.inverted = 1;
  cavity.radius = lsdem_sdf_bound_radius(&cavity.sdf);
  const lsdem_pose centre = fix_pose(0.0, 0.0, 0.0);
  compare_runs("cavity, approach", APPROACH, &small.clustered, &cavity, &centre, -6.7, 0.5, 1,
               0.3, 0);
  free(steep);
  test_random_moves(&ga.clustered, &plane, &pw, 1.0, 1, "plane");
  test_random_moves(&ga.clustered, &B, &pb, 13.0, 1, "ellipsoid grid");
  test_random_moves(&ga.clustered, &round, &pb, 15.0, 0, "round grid");
  test_level_set_screening(a, &B, &pb, 13.0);
  test_level_set_screening(a, &B, &pb, 15.0);
  compare_runs("round grid, approach, clusters", APPROACH, &ga.clustered, &round, &pb, 14.2,
               0.5, 1, 0.3, 0);
  /* without a gradient bound every looked-up node is listed: still the same results */
  lsdem_shape unbounded = B;
  unbounded.sdf.grid.lip = 0.0;
  compare_runs("grid without bound", SLIDE, &ga.clustered, &unbounded, &pb, 11.6, 0.5, 1, 0.3,
               0);
  lsdem_grid_free(&gsdf.grid);
  lsdem_grid_free(&bgrid.grid);
  return lsdem_test_summary();
}
