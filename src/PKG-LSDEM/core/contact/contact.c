/* contact.c -- node-to-surface contact of level-set grains (report Algorithm 2,
 * eqs 2.2-2.16) and the analytic sphere fast paths (report §2.3.5).
 *
 * Frames and signs: vectors are world-frame except node coordinates (A's principal
 * frame), cb (B's centre in A's frame) and q, g (a node and B's level-set gradient in
 * B's principal frame). The contact normal n is B's outward unit normal at the
 * contact, so it points from B towards A; the force f computed for a contact acts on
 * the master A (a repulsive normal force is +|f_n| n) and the slave B receives -f.
 * Torques are taken about each grain's centroid.
 *
 * The per-contact physics (normal spring and damping, the shear spring with its
 * history, the Coulomb cap, the accumulation into a result) lives in apply_contacts() and
 * the functions it calls, shared by the node loop and by the sphere paths. */
#include "lsdem_contact.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* --------------------------------------------------------- small vector ops ---- */

/* ------------------------------------------------------------ pair context ---- */

/* The pair's motion as the contact forces need it (world frame), with ra = p - xA the arm
 * of a contact point p from A's centroid: the velocity of A's material point at p relative
 * to B's is v0 + dw x ra (report eq 2.6: vA + wA x ra - vB - wB x (ra + dab) with
 * dab = xA - xB, so v0 = vA - vB - wB x dab and dw = wA - wB), and the reaction's torque
 * about B's centroid, (ra + dab) x (-f), sums to -(sum of ra x f) - dab x (sum of f). */
typedef struct {
  double xa[3], dab[3], v0[3], dw[3];
} pair_motion;

/* What one pair evaluation shares between its contacts. Motions, parameters and the
 * running sums are held by value, so the contact code reads and accumulates in memory
 * that nothing else aliases (passed as restrict); pair_end() publishes the result. */
typedef struct {
  pair_motion m;
  lsdem_contact_params prm;
  int64_t step;
  const lsdem_node_hist *hist_in; /* sorted by node; walked forward once (merge) */
  int n_in, cursor;
  lsdem_node_hist *hist_out;
  int n_out;
  double weight; /* sum of normal-force magnitudes, for the mean contact point */
  lsdem_contact_result sum;
} pair_ctx;

/* All zero (assigned rather than memset: a call per pair, kept cheap). */
static const lsdem_contact_result no_result;

static void pair_begin(pair_ctx *c, const lsdem_pose *pa, const lsdem_pose *pb,
                       const lsdem_contact_params *prm, int64_t step,
                       const lsdem_node_hist *hist_in, int n_in, lsdem_node_hist *hist_out)
{
  c->sum = no_result;
  pair_motion *m = &c->m;
  double wb_dab[3];
  for (int i = 0; i < 3; i++) {
    m->xa[i] = pa->x[i];
    m->dab[i] = pa->x[i] - pb->x[i];
    m->dw[i] = pa->omega[i] - pb->omega[i];
  }
  lsdem_cross3(pb->omega, m->dab, wb_dab);
  for (int i = 0; i < 3; i++) m->v0[i] = pa->v[i] - pb->v[i] - wb_dab[i];
  c->prm = *prm;
  c->step = step;
  c->hist_in = hist_in;
  c->n_in = hist_in ? n_in : 0;
  c->cursor = 0;
  c->hist_out = hist_out;
  c->n_out = 0;
  c->weight = 0.0;
}

static int pair_end(const pair_ctx *c, int *n_out, lsdem_contact_result *res)
{
  *res = c->sum;
  double dab_f[3]; /* the reaction's torque about B's centroid (see pair_motion) */
  lsdem_cross3(c->m.dab, res->force, dab_f);
  for (int i = 0; i < 3; i++) res->torque_b[i] = -res->torque_a[i] - dab_f[i];
  if (c->weight > 0.0)
    for (int i = 0; i < 3; i++) res->point[i] /= c->weight;
  if (n_out) *n_out = c->n_out;
  return res->npen;
}

/* An empty result: no contact, no history. */
static int no_contact(int *n_out, lsdem_contact_result *res)
{
  *res = no_result;
  if (n_out) *n_out = 0;
  return 0;
}

/* History entry of `node` in hist_in, or NULL. Nodes are visited in increasing order,
 * so the cursor only moves forward: O(1) amortised per call. */
static const lsdem_node_hist *find_history(pair_ctx *restrict c, int node)
{
  while (c->cursor < c->n_in && c->hist_in[c->cursor].node < node) c->cursor++;
  if (c->cursor < c->n_in && c->hist_in[c->cursor].node == node)
    return &c->hist_in[c->cursor];
  return NULL;
}

/* Nodes looked up together, and contacts computed together, at most. */
enum { NODE_BATCH = 64 };

/* The contacts of one batch of penetrating nodes, as apply_contacts() takes them: node k,
 * world point p, B's outward unit normal n, depth d > 0, and kscale (multiplies kn and
 * ks: the node stride, times the node area under the traction law). */
typedef struct {
  int n;
  int node[NODE_BATCH];
  double p[3 * NODE_BATCH], nrm[3 * NODE_BATCH];
  double depth[NODE_BATCH], kscale[NODE_BATCH];
} contact_set;

/* Normal force (eq 2.2, with damping) of each contact, and the quantities the shear and
 * the torques need: the arm ra = p - xA, the relative tangential velocity vt (eq 2.6,
 * see pair_motion), fn n in f. */
static void normal_forces(const pair_ctx *restrict c, const contact_set *restrict cs,
                          double cscale, double *restrict fn_out, double *restrict ra,
                          double *restrict vt, double *restrict f)
{
  const lsdem_contact_params *prm = &c->prm;
  for (int m = 0; m < cs->n; m++) {
    const double *p = &cs->p[3 * m], *n = &cs->nrm[3 * m];
    double *r = &ra[3 * m];
    double fn = prm->kn * cs->kscale[m] * cs->depth[m]; /* eq 2.2: repulsive, +n on A */
    double vrel[3] = {0.0, 0.0, 0.0}, vn = 0.0;
    for (int i = 0; i < 3; i++) r[i] = p[i] - c->m.xa[i];
    if (prm->cn > 0.0 || prm->mu > 0.0) { /* eq 2.6 (see pair_motion) */
      lsdem_cross3(c->m.dw, r, vrel);
      for (int i = 0; i < 3; i++) vrel[i] += c->m.v0[i];
      vn = lsdem_dot3(vrel, n);
    }
    if (prm->cn > 0.0) {
      fn -= prm->cn * cscale * vn;
      if (fn < 0.0) fn = 0.0; /* a penalty contact pushes, never pulls */
    }
    fn_out[m] = fn;
    for (int i = 0; i < 3; i++) {
      f[3 * m + i] = fn * n[i];
      vt[3 * m + i] = vrel[i] - vn * n[i];
    }
  }
}

/* Shear springs carried over (report eq 2.8): Z s_old, the stored spring rotated from
 * its normal to the current one; 0 for a new contact. An entry stamped with this step
 * was already advanced: it is taken as is and *fresh is 0 for it. */
static void carried_shear(pair_ctx *restrict c, const contact_set *restrict cs,
                          double *restrict s, int *restrict fresh)
{
  for (int m = 0; m < cs->n; m++) {
    const lsdem_node_hist *h = find_history(c, cs->node[m]);
    double *sm = &s[3 * m];
    fresh[m] = !(h && h->stamp == c->step);
    if (!h) {
      sm[0] = sm[1] = sm[2] = 0.0;
    } else if (!fresh[m]) {
      for (int i = 0; i < 3; i++) sm[i] = h->shear[i];
    } else {
      lsdem_rotate_between(h->shear, h->normal, &cs->nrm[3 * m], sm); /* eq 2.8: Z */
    }
  }
}

/* Tangential forces (report eqs 2.7, 2.8, 2.10) added to f, and their history entries:
 * shear spring s = Z s_old - ks dt v_t (kept as is for an entry already advanced this
 * step); applied force ft = s - ct v_t, capped at mu fn, with the spring reset so that
 * spring + damping equals the capped force. */
static void tangential_forces(pair_ctx *restrict c, const contact_set *restrict cs,
                              double cscale, const double *restrict fn,
                              const double *restrict vt, double *restrict s,
                              const int *restrict fresh, double *restrict f)
{
  const lsdem_contact_params *prm = &c->prm;
  const double ct = prm->ct * cscale;
  for (int m = 0; m < cs->n; m++) {
    const double *v = &vt[3 * m];
    double *sm = &s[3 * m], ft[3];
    if (fresh[m]) {
      const double ks = prm->ks * cs->kscale[m];
      for (int i = 0; i < 3; i++) sm[i] = sm[i] - ks * prm->dt * v[i]; /* eqs 2.7-2.8 */
    }
    for (int i = 0; i < 3; i++) ft[i] = sm[i] - ct * v[i];
    const double cap = prm->mu * fn[m]; /* eq 2.10 */
    const double ft2 = lsdem_dot3(ft, ft);
    if (ft2 > cap * cap) {
      const double scale = cap / sqrt(ft2);
      for (int i = 0; i < 3; i++) {
        ft[i] *= scale;
        sm[i] = ft[i] + ct * v[i];
      }
    }
    for (int i = 0; i < 3; i++) f[3 * m + i] += ft[i];
    if (!c->hist_out) continue;
    lsdem_node_hist *out = &c->hist_out[c->n_out++];
    out->node = cs->node[m];
    out->pad_ = 0;
    out->stamp = c->step;
    for (int i = 0; i < 3; i++) {
      out->shear[i] = sm[i];
      out->normal[i] = cs->nrm[3 * m + i];
    }
  }
}

/* The contacts of cs (cscale multiplies cn and ct: the node stride), accumulated into the
 * pair sums in node order. Done a step at a time over all of them, each step a short loop
 * whose iterations are independent, so that the contacts' long chains of dependent
 * arithmetic (a division in Z, the cap's square root) overlap. */
static void apply_contacts(pair_ctx *restrict c, const contact_set *restrict cs,
                           double cscale)
{
  double fn[NODE_BATCH], ra[3 * NODE_BATCH], vt[3 * NODE_BATCH], f[3 * NODE_BATCH];
  normal_forces(c, cs, cscale, fn, ra, vt, f);
  if (c->prm.mu > 0.0) {
    double s[3 * NODE_BATCH];
    int fresh[NODE_BATCH];
    carried_shear(c, cs, s, fresh);
    tangential_forces(c, cs, cscale, fn, vt, s, fresh, f);
  }
  /* eqs 2.14-2.16: force and torque on A; B's reaction torque follows in pair_end */
  lsdem_contact_result *sum = &c->sum;
  for (int m = 0; m < cs->n; m++) {
    const double *fm = &f[3 * m], *p = &cs->p[3 * m];
    double ta[3];
    lsdem_cross3(&ra[3 * m], fm, ta);
    for (int i = 0; i < 3; i++) {
      sum->force[i] += fm[i];
      sum->torque_a[i] += ta[i];
      sum->point[i] += fn[m] * p[i];
    }
    c->weight += fn[m];
    const double d = cs->depth[m];
    sum->max_depth = d > sum->max_depth ? d : sum->max_depth; /* a max, not a branch */
  }
  sum->npen += cs->n;
}

/* ------------------------------------------------------------ node contact ---- */

/* Nodes are screened in A's own frame, where B's centre sits at cb = RA^T (xB - xA):
 * |p - xB| = |node - cb|, so rejecting a node costs 8 flops and no transform. The
 * screening pass is branch-free (no mispredicted branch per rejected node): it keeps
 * the indices of nodes inside B's bounding sphere, a batch at a time, and only those
 * are mapped to B's frame and looked up, all lookups of a batch together (their cache
 * misses overlap: lsdem_grid_eval_many). */
typedef struct {
  int n;
  int node[NODE_BATCH];
  double x[3 * NODE_BATCH];    /* kept nodes in A's frame */
  double q[3 * NODE_BATCH];    /* and in B's frame */
  double phi[NODE_BATCH];      /* B's level set there */
  double grad[3 * NODE_BATCH]; /* and its outward unit gradient (B's frame) */
  int cached;                  /* B is a grid whose cells come from the pair's list */
  lsdem_grid_cell cell[NODE_BATCH];
} node_batch;

/* Screen `count` (<= NODE_BATCH - b->n) nodes first, first + stride, ...: appended to
 * the batch when |node - cb|^2 <= rb2; *nearest_out is lowered to the smallest
 * |node - cb|^2 of the nodes left out. */
static void screen_nodes(const double *nodes, int first, int count, int stride,
                         const double cb[3], double rb2, node_batch *b, double *nearest_out)
{
  int n = b->n;
  double nearest = *nearest_out;
  for (int i = 0; i < count; i++) {
    const int k = first + i * stride;
    const double *x = &nodes[3 * k];
    const double d0 = x[0] - cb[0], d1 = x[1] - cb[1], d2 = x[2] - cb[2];
    const double r2 = d0 * d0 + d1 * d1 + d2 * d2;
    const int in = r2 <= rb2;
    b->node[n] = k;
    n += in;
    nearest = !in && r2 < nearest ? r2 : nearest;
  }
  b->n = n;
  *nearest_out = nearest;
}

/* Level-set lookups of a screened batch (Algorithm 1 for a grid) at q = M node + t (B's
 * frame), the SDF kind dispatched once per batch. */
static void lookup_batch(const lsdem_sdf *sdfB, const double M[9], const double t[3],
                         node_batch *b)
{
  for (int i = 0; i < b->n; i++) lsdem_affine3(M, t, &b->x[3 * i], &b->q[3 * i]);
  if (b->cached)
    lsdem_grid_eval_many_cached(&sdfB->grid, b->n, b->q, b->phi, b->grad, b->cell);
  else
    lsdem_sdf_eval_many(sdfB, b->n, b->q, b->phi, b->grad);
}

/* Whether B's level set is an exact signed distance, so |phi(p) - phi(q)| <= |p - q|
 * (also inverted). Grids are not (trilinear interpolation of samples that may be
 * smoothed or approximate), nor is the superellipsoid's first-order distance. */
static int sdf_is_distance(const lsdem_sdf *s)
{
  switch (s->kind) {
  case LSDEM_SDF_SPHERE:
  case LSDEM_SDF_PLANE:
  case LSDEM_SDF_CYLINDER:
  case LSDEM_SDF_BOX:
  case LSDEM_SDF_ELLIPSOID: return 1;
  default: return 0;
  }
}

/* ------------------------------------------------------------- node lists ---- */

/* A pair's node list travels in its history: two entries first,
 *   LIST_POSE_M: M[0..5] of the pose the list was built at (shear, normal); stamp: the
 *     step it was built at; pad_: the node stride;
 *   LIST_POSE_T: M[6..8] and t (shear, normal); stamp: the bits of its validity radius,
 *     the least distance any left-out node had to move to touch B (at least the skin);
 *     pad_: the number of node entries;
 * then one entry per listed node k in increasing k, id LIST_NODE + k: the node in A's
 * frame (normal; copied from A, so that a step that uses the list reads none of A's node
 * memory) and, when B is a grid, the 8 samples of the cell the node was last looked up
 * in (stamp and shear hold the 8 floats, pad_ the cell's index, -1: none), so that a
 * lookup in the same cell reads no grid memory; and after them the shear entries
 * (ids >= 0). A step that uses the list knows how many node entries it writes, so its
 * whole history goes out in order, where it is kept (no entry moved). A list built with
 * another stride is not used; its node entries still give cells. (Histories of the
 * earlier layout, shear entries ahead of the node entries, are not taken for a list:
 * rebuilt, shear kept.) */
enum { LIST_POSE_M = -2, LIST_POSE_T = -1, LIST_HEAD = 2, LIST_NODE = -(1 << 29) };

/* The list state of one call. */
typedef struct {
  double skin;  /* s; 0: no list */
  double reach; /* L s: a looked-up node with phi >= reach is left out (HUGE_VAL: none) */
  double lip;   /* L (reach / skin) when finite */
  double margin; /* while built: the least distance a left-out node must move to touch */
  double cap;   /* the margin may not exceed this (grids: the gradient bound's limit) */
  int use;      /* hist_in's list holds: look up its nodes only */
  int cached;   /* B is a grid: listed nodes' cells are kept */
  const lsdem_node_hist *node_in; /* hist_in's node entries (increasing node), count */
  int nnode_in, node_cursor;
  lsdem_node_hist *head;     /* hist_out's list entries, or NULL */
  lsdem_node_hist *pose_out; /* == head while a new list is built, else NULL */
  lsdem_node_hist *node_out; /* hist_out's node entries (after the head) */
  int nnode_out;
  int shear_at; /* hist_out's shear entries are written from here: after the listed nodes
                   when their count is known, else after the largest node set (moved
                   down to follow the node entries at the end) */
} node_list;

/* Where in a node entry a kept cell's 8 floats sit: the 32 bytes of stamp and shear. */
#define CELL_AT offsetof(lsdem_node_hist, stamp)
_Static_assert(offsetof(lsdem_node_hist, shear) == CELL_AT + 8 &&
                   sizeof(((lsdem_grid_cell *)0)->v) == 32,
               "a node entry holds a cell's samples in stamp and shear");

static int is_node_entry(int32_t id, int nnodes)
{
  return id >= LIST_NODE && id < LIST_NODE + nnodes;
}

/* Entry of listed node k at x (A's frame) with its cell c (NULL or index -1: none). */
static void node_to_entry(int k, const double x[3], const lsdem_grid_cell *c,
                          lsdem_node_hist *e)
{
  const int kept = c && c->index >= 0 && c->index <= INT32_MAX;
  e->node = LIST_NODE + k;
  e->pad_ = kept ? (int32_t)c->index : -1;
  if (kept)
    memcpy((char *)e + CELL_AT, c->v, sizeof c->v);
  else
    memset((char *)e + CELL_AT, 0, sizeof c->v);
  memcpy(e->normal, x, sizeof e->normal);
}

static void entry_to_cell(const lsdem_node_hist *e, lsdem_grid_cell *c)
{
  c->index = e->pad_;
  if (e->pad_ >= 0) memcpy(c->v, (const char *)e + CELL_AT, sizeof c->v);
}

/* The kept cell of node k (nodes asked in increasing order), or none. */
static void kept_cell_of(node_list *L, int k, lsdem_grid_cell *c)
{
  while (L->node_cursor < L->nnode_in && L->node_in[L->node_cursor].node < LIST_NODE + k)
    L->node_cursor++;
  if (L->node_cursor < L->nnode_in && L->node_in[L->node_cursor].node == LIST_NODE + k)
    entry_to_cell(&L->node_in[L->node_cursor], c);
  else
    c->index = -1;
}

static void keep_node(node_list *L, int k, const double x[3], const lsdem_grid_cell *c)
{
  node_to_entry(k, x, L->cached ? c : NULL, L->node_out + L->nnode_out);
  L->nnode_out++;
}

/* The node-list reach L s for skin s: a node looked up with phi >= L s cannot reach
 * phi < 0 by moving less than s, L bounding |grad phi| where 0 <= phi <= L s (exact
 * distances: 1; grids that are not inverted: lsdem_grid_outer_lipschitz, within its
 * limit). HUGE_VAL when there is no such bound: every looked-up node is listed. */
static double list_reach(const lsdem_sdf *s, double skin)
{
  if (sdf_is_distance(s)) return skin;
  /* the grid's bound holds where its own phi >= 0, not where an inverted one is */
  const lsdem_grid *g = &s->grid;
  if (s->kind == LSDEM_SDF_GRID && !s->inverted && g->lip > 0.0 && g->lip * skin < g->lip_reach)
    return g->lip * skin;
  return HUGE_VAL;
}

static int64_t double_bits(double x)
{
  int64_t bits;
  memcpy(&bits, &x, sizeof bits);
  return bits;
}

static double bits_double(int64_t bits)
{
  double x;
  memcpy(&x, &bits, sizeof x);
  return x;
}

static int list_head_ok(const lsdem_node_hist *h, int n)
{
  return n >= LIST_HEAD && h[0].node == LIST_POSE_M && h[1].node == LIST_POSE_T;
}

/* How far any node of A (radius ra) may have moved relative to B since the list of h
 * (its head checked) was built at M0, t0: |M - M0| ra + |t - t0|, the rotation part
 * exact for rotations as |M - M0|_F / sqrt(2). */
static double list_motion(const lsdem_node_hist *h, const double M[9], const double t[3],
                          double ra)
{
  const double M0[9] = {h[0].shear[0],  h[0].shear[1],  h[0].shear[2],
                        h[0].normal[0], h[0].normal[1], h[0].normal[2],
                        h[1].shear[0],  h[1].shear[1],  h[1].shear[2]};
  double dm = 0.0, dt = 0.0;
  for (int i = 0; i < 9; i++) dm += (M[i] - M0[i]) * (M[i] - M0[i]);
  for (int i = 0; i < 3; i++) dt += (t[i] - h[1].normal[i]) * (t[i] - h[1].normal[i]);
  return (sqrt(0.5 * dm) + 1e-12) * ra + sqrt(dt);
}

/* Skin of a list built now against B, for the base skin s: a list that lasted fewer than
 * LIST_LIFETIME steps (the pair rattles) is followed by one wide enough to last that long
 * at the pair's rate of motion since, within [s, LIST_SKIN_GROWTH s], unless B's gradient
 * bound covers s but not the wider skin (every looked-up node would then be listed);
 * otherwise s, which costs the fewest lookups per step. */
enum { LIST_LIFETIME = 8, LIST_SKIN_GROWTH = 4 };

static double adapted_skin(double skin, const lsdem_sdf *sdfB, const lsdem_node_hist *h,
                           double motion, int64_t step)
{
  const int64_t age = step - h[0].stamp;
  if (age <= 0 || age >= LIST_LIFETIME) return skin;
  const double want = LIST_LIFETIME * motion / (double)age;
  const double wide = want < skin                      ? skin
                      : want > LIST_SKIN_GROWTH * skin ? LIST_SKIN_GROWTH * skin
                                                       : want;
  const int bound_lost = !isfinite(list_reach(sdfB, wide)) && isfinite(list_reach(sdfB, skin));
  return bound_lost ? skin : wide;
}

/* Whether the list of h holds: built with this stride, no node moved by its validity
 * radius, and not a wide list (radius above LIST_SKIN_GROWTH / 2 times the base skin)
 * older than 4 LIST_LIFETIME steps: a pair that has settled gets the base skin back. */
static int list_holds(const lsdem_node_hist *h, double motion, double skin, int64_t step,
                      int stride)
{
  const double radius = bits_double(h[1].stamp);
  const int wide = radius > 0.5 * LIST_SKIN_GROWTH * skin;
  if (wide && step - h[0].stamp > 4 * LIST_LIFETIME) return 0;
  return h[0].pad_ == stride && motion < radius * (1.0 - 1e-9);
}

/* Decides whether hist_in's list is used; when it is not and hist_out is given, starts a
 * new one there (pose M, t). Either way hist_out's head is reserved: the caller's shear
 * entries follow it. */
static void list_begin(node_list *L, const lsdem_shape *A, const lsdem_sdf *sdfB,
                       const lsdem_contact_params *prm, int64_t step,
                       const lsdem_node_hist *hist_in, int n_in, lsdem_node_hist *hist_out,
                       const double M[9], const double t[3])
{
  L->skin = prm->node_skin > 0.0 ? prm->node_skin : 0.0;
  L->use = L->cached = 0;
  L->node_in = NULL;
  L->nnode_in = L->node_cursor = L->nnode_out = 0;
  L->head = L->pose_out = L->node_out = NULL;
  L->shear_at = 0;
  if (L->skin == 0.0) return;
  L->margin = HUGE_VAL;
  L->cached = sdfB->kind == LSDEM_SDF_GRID && !sdfB->inverted;
  const int stride = prm->node_stride > 1 ? prm->node_stride : 1;
  if (hist_in && list_head_ok(hist_in, n_in)) {
    const int nn = hist_in[1].pad_;
    /* the first node entry tells this layout from the earlier one (a shear entry there);
     * the others are checked as they are read (reading the last one now would wait for
     * memory the sequential reads bring in later) */
    const lsdem_node_hist *nodes = hist_in + LIST_HEAD;
    if (nn > 0 && nn <= n_in - LIST_HEAD && is_node_entry(nodes[0].node, A->nnodes)) {
      L->node_in = nodes;
      L->nnode_in = nn;
    }
    const double motion = list_motion(hist_in, M, t, A->radius);
    L->use = list_holds(hist_in, motion, L->skin, step, stride);
    if (!L->use) L->skin = adapted_skin(L->skin, sdfB, hist_in, motion, step);
  }
  L->reach = list_reach(sdfB, L->skin);
  L->lip = isfinite(L->reach) ? L->reach / L->skin : 0.0;
  L->cap = sdfB->kind == LSDEM_SDF_GRID && L->lip > 0.0 ? sdfB->grid.lip_reach / L->lip
                                                         : HUGE_VAL;
  if (!hist_out) return;
  L->head = hist_out;
  L->node_out = hist_out + LIST_HEAD;
  L->shear_at = LIST_HEAD + (L->use ? L->nnode_in : A->nnodes);
  if (L->use) {
    memcpy(hist_out, hist_in, sizeof *hist_out * LIST_HEAD);
    return;
  }
  lsdem_node_hist *pm = &hist_out[0], *pt = &hist_out[1];
  pm->node = LIST_POSE_M;
  pt->node = LIST_POSE_T;
  for (int i = 0; i < 3; i++) {
    pm->shear[i] = M[i];
    pm->normal[i] = M[3 + i];
    pt->shear[i] = M[6 + i];
    pt->normal[i] = t[i];
  }
  pm->stamp = step;
  pm->pad_ = stride; /* pt->stamp: the validity radius, when the list is finished */
  L->pose_out = hist_out;
}

/* A left-out node (or cluster) that must move by d to touch B: the list holds until d. */
static void list_margin(node_list *L, double d)
{
  L->margin = d < L->margin ? d : L->margin;
}

/* Finishes hist_out's list (its validity radius when built, its node entries moved to
 * follow the n_out entries written so far); returns the new count. */
static int list_finish(node_list *L, int n_out)
{
  if (!L->head) return n_out;
  if (L->pose_out) {
    const double radius = L->margin < L->cap ? L->margin : L->cap;
    L->pose_out[1].stamp = double_bits(radius > L->skin ? radius : L->skin);
  }
  L->head[1].pad_ = L->nnode_out;
  const int nodes_end = LIST_HEAD + L->nnode_out, nshear = n_out - L->shear_at;
  if (nodes_end != L->shear_at)
    memmove(L->head + nodes_end, L->head + L->shear_at, sizeof *L->head * (size_t)nshear);
  return nodes_end + nshear;
}

/* Looks the batch up, then the contacts of its penetrating nodes; empties the batch.
 * While a list is built (L->pose_out), the nodes that may come to touch join it; the
 * listed nodes (and their cells, when B is a grid) are kept in hist_out's list. */
static void contact_batch(pair_ctx *restrict c, const lsdem_shape *A, const lsdem_shape *B,
                          const lsdem_pose *pb, const double M[9], const double t[3],
                          node_batch *b, double kstride, node_list *L)
{
  b->cached = L->cached;
  lookup_batch(&B->sdf, M, t, b);
  const int traction = c->prm.law == LSDEM_NORMAL_TRACTION && A->node_area;
  c->sum.ntested += b->n;
  for (int i = 0; i < b->n; i++) {
    const int listed = L->use || (L->pose_out && b->phi[i] < L->reach);
    if (!listed) {
      if (L->pose_out) list_margin(L, b->phi[i] / L->lip); /* phi >= L s: L > 0 here */
      continue;
    }
    if (L->node_out) keep_node(L, b->node[i], &b->x[3 * i], &b->cell[i]);
  }
  contact_set cs;
  int at[NODE_BATCH]; /* the penetrating ones, gathered without a branch per node */
  cs.n = 0;
  for (int i = 0; i < b->n; i++) {
    at[cs.n] = i;
    cs.n += b->phi[i] < 0.0;
  }
  for (int m = 0; m < cs.n; m++) {
    const int i = at[m], k = b->node[i];
    cs.node[m] = k;
    lsdem_affine3(pb->R, pb->x, &b->q[3 * i], &cs.p[3 * m]); /* world position of the node */
    lsdem_mat_vec(pb->R, &b->grad[3 * i], &cs.nrm[3 * m]); /* world normal, outward from B */
    cs.depth[m] = -b->phi[i];
    cs.kscale[m] = traction ? kstride * A->node_area[k] : kstride;
  }
  apply_contacts(c, &cs, kstride);
  b->n = 0;
}

/* contact_batch for screened nodes: their coordinates from A, their cells from the
 * list's node entries where kept. */
static void screened_batch(pair_ctx *restrict c, const lsdem_shape *A, const lsdem_shape *B,
                           const lsdem_pose *pb, const double M[9], const double t[3],
                           node_batch *b, double kstride, node_list *L)
{
  for (int i = 0; i < b->n; i++) {
    memcpy(&b->x[3 * i], &A->nodes[3 * b->node[i]], 3 * sizeof(double));
    if (L->cached) kept_cell_of(L, b->node[i], &b->cell[i]);
  }
  contact_batch(c, A, B, pb, M, t, b, kstride, L);
}

/* For a distance B: no point of the ball of radius r about centre (A's frame, mapped to
 * B's by q = M x + t) is inside B when phi_B(q) > r (1-Lipschitz). This is how a wall
 * (unbounded: no bounding sphere) skips a grain, or a cluster, with one evaluation
 * instead of one per node. The relative margin covers round-off in phi at the nodes. */
static double ball_clearance(const lsdem_sdf *sdfB, const double M[9], const double t[3],
                             const double centre[3], double r)
{
  double q[3], g[3];
  lsdem_affine3(M, t, centre, q);
  const double scale = fabs(q[0]) + fabs(q[1]) + fabs(q[2]) + r;
  return lsdem_sdf_eval(sdfB, q, g) - r - 1e-12 * scale;
}

static int ball_clear_of(const lsdem_sdf *sdfB, const double M[9], const double t[3],
                         const double centre[3], double r)
{
  return ball_clearance(sdfB, M, t, centre, r) > 0.0;
}

/* Node range [start, end) of cluster cl of A when it may touch B (or of all of A when
 * A has no clusters); returns 0 when the cluster's sphere is clear of B's bounding
 * sphere widened by `widen` (cb: B's centre in A's frame) or, for a distance B, of B's
 * solid by more than `clear`. A cluster left out of a list being built gives the list a
 * margin: how far it is from touching. */
static int cluster_range(const lsdem_shape *A, int cl, const lsdem_shape *B, double widen,
                         int distance, double clear, const double cb[3], const double M[9],
                         const double t[3], node_list *L, int *start, int *end)
{
  *start = 0;
  *end = A->nnodes;
  if (!(A->nclusters > 0 && A->cluster_start && A->cluster_sphere)) return 1;
  const double *sph = &A->cluster_sphere[4 * cl];
  const double d[3] = {sph[0] - cb[0], sph[1] - cb[1], sph[2] - cb[2]};
  const double reach = B->radius + widen + sph[3];
  if (lsdem_dot3(d, d) > reach * reach) {
    if (L->pose_out) list_margin(L, sqrt(lsdem_dot3(d, d)) - B->radius - sph[3]);
    return 0;
  }
  if (distance) {
    const double gap = ball_clearance(&B->sdf, M, t, sph, sph[3]);
    if (gap > clear) {
      if (L->pose_out) list_margin(L, gap);
      return 0;
    }
  }
  *start = A->cluster_start[cl];
  *end = A->cluster_start[cl + 1];
  return 1;
}

/* Every node of A screened: clusters, then nodes against B's bounding sphere (both
 * widened by the skin while a list is built), the kept ones looked up in batches. The
 * kept nodes of successive clusters share a batch (more lookups to overlap); the batch is
 * looked up when full and at the end, so nodes stay in increasing order. */
static void contacts_of_screened_nodes(pair_ctx *restrict c, const lsdem_shape *A,
                                       const lsdem_shape *B, const lsdem_pose *pb,
                                       const double cb[3], const double M[9],
                                       const double t[3], int distance, node_list *L,
                                       node_batch *batch, int stride)
{
  const double widen = L->pose_out ? L->skin : 0.0, rb = B->radius + widen, rb2 = rb * rb;
  const double clear = L->pose_out && isfinite(L->reach) ? L->reach : 0.0;
  const int nclusters = A->nclusters > 0 && A->cluster_start && A->cluster_sphere
                            ? A->nclusters : 1;
  double nearest = HUGE_VAL; /* squared distance from cb of the nearest node left out */
  for (int cl = 0; cl < nclusters; cl++) {
    int start, end;
    if (!cluster_range(A, cl, B, widen, distance, clear, cb, M, t, L, &start, &end)) continue;
    int k = (start + stride - 1) / stride * stride;
    while (k < end) {
      const int left = (end - k + stride - 1) / stride, room = NODE_BATCH - batch->n;
      const int count = left < room ? left : room;
      screen_nodes(A->nodes, k, count, stride, cb, rb2, batch, &nearest);
      k += count * stride;
      if (batch->n == NODE_BATCH) screened_batch(c, A, B, pb, M, t, batch, (double)stride, L);
    }
  }
  screened_batch(c, A, B, pb, M, t, batch, (double)stride, L);
  if (L->pose_out && nearest < HUGE_VAL) list_margin(L, sqrt(nearest) - B->radius);
}

/* Only the nodes of the pair's list, in increasing order, looked up in batches: their
 * coordinates and cells from the list's node entries. */
static void contacts_of_listed_nodes(pair_ctx *restrict c, const lsdem_shape *A,
                                     const lsdem_shape *B, const lsdem_pose *pb,
                                     const double M[9], const double t[3], node_list *L,
                                     node_batch *batch, int stride)
{
  for (int e = 0; e < L->nnode_in; e++) {
    const lsdem_node_hist *h = &L->node_in[e];
    if (!is_node_entry(h->node, A->nnodes)) continue; /* a damaged history: not a node */
    const int i = batch->n++;
    batch->node[i] = h->node - LIST_NODE;
    memcpy(&batch->x[3 * i], h->normal, 3 * sizeof(double));
    if (L->cached) entry_to_cell(h, &batch->cell[i]);
    if (batch->n == NODE_BATCH) contact_batch(c, A, B, pb, M, t, batch, (double)stride, L);
  }
  contact_batch(c, A, B, pb, M, t, batch, (double)stride, L);
}

int lsdem_contact_nodes(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                        const lsdem_pose *pb, const lsdem_contact_params *prm, int64_t step,
                        const lsdem_node_hist *hist_in, int n_in, lsdem_node_hist *hist_out,
                        int *n_out, lsdem_contact_result *res)
{
  /* eq 2.1: bounding spheres of the pair */
  double dx[3];
  for (int i = 0; i < 3; i++) dx[i] = pb->x[i] - pa->x[i];
  const double rb = B->radius, rab = A->radius + rb;
  if (lsdem_dot3(dx, dx) > rab * rab) return no_contact(n_out, res);

  /* cb: B's centre in A's frame (for screening). A's frame -> B's frame:
   * q = M node + t with M = RB^T RA, t = RB^T (xA - xB). */
  double cb[3], M[9], t[3], mdx[3] = {-dx[0], -dx[1], -dx[2]};
  lsdem_matT_vec(pa->R, dx, cb);
  lsdem_matT_mul(pb->R, pa->R, M);
  lsdem_matT_vec(pb->R, mdx, t);

  /* an unbounded distance B (a wall) has no bounding sphere to screen with: reject A's
   * bounding sphere (about A's centroid, the origin of A's frame) and then A's clusters
   * by B's level set instead */
  const int distance = !isfinite(rb) && sdf_is_distance(&B->sdf);
  const double origin[3] = {0.0, 0.0, 0.0};
  if (distance && ball_clear_of(&B->sdf, M, t, origin, A->radius))
    return no_contact(n_out, res);

  pair_ctx c;
  pair_begin(&c, pa, pb, prm, step, hist_in, n_in, hist_out);
  node_list list;
  list_begin(&list, A, &B->sdf, prm, step, hist_in, n_in, hist_out, M, t);
  if (list.head) c.n_out = list.shear_at;
  if (list.node_in) { /* the shear entries follow the node entries */
    c.hist_in = list.node_in + list.nnode_in;
    c.n_in = n_in - (int)(c.hist_in - hist_in);
  }

  node_batch batch;
  batch.n = 0;
  const int stride = prm->node_stride > 1 ? prm->node_stride : 1;
  if (list.use)
    contacts_of_listed_nodes(&c, A, B, pb, M, t, &list, &batch, stride);
  else
    contacts_of_screened_nodes(&c, A, B, pb, cb, M, t, distance, &list, &batch, stride);
  c.n_out = list_finish(&list, c.n_out);
  return pair_end(&c, n_out, res);
}

/* ----------------------------------------------------------- sphere paths ---- */

/* One sphere contact (sphere A against B) given B's outward normal n and the depth d:
 * the contact point is the middle of the overlap along the normal,
 * p = xA - (radius - d/2) n. */
static int sphere_contact(double radius, double area, const double n[3], double d,
                          const lsdem_pose *pa, const lsdem_pose *pb,
                          const lsdem_contact_params *prm, int64_t step,
                          const lsdem_node_hist *hist_in, int n_in, lsdem_node_hist *hist_out,
                          int *n_out, lsdem_contact_result *res)
{
  pair_ctx c;
  pair_begin(&c, pa, pb, prm, step, hist_in, n_in, hist_out);
  c.sum.ntested = 1;
  contact_set cs;
  cs.n = 1;
  cs.node[0] = 0;
  for (int i = 0; i < 3; i++) {
    cs.p[i] = pa->x[i] - (radius - 0.5 * d) * n[i];
    cs.nrm[i] = n[i];
  }
  cs.depth[0] = d;
  cs.kscale[0] = prm->law == LSDEM_NORMAL_TRACTION ? area : 1.0;
  apply_contacts(&c, &cs, 1.0);
  return pair_end(&c, n_out, res);
}

int lsdem_contact_sphere_shape(double radius, double area, const lsdem_pose *pa,
                               const lsdem_shape *B, const lsdem_pose *pb,
                               const lsdem_contact_params *prm, int64_t step,
                               const lsdem_node_hist *hist_in, int n_in,
                               lsdem_node_hist *hist_out, int *n_out,
                               lsdem_contact_result *res)
{
  double dx[3];
  for (int i = 0; i < 3; i++) dx[i] = pa->x[i] - pb->x[i];
  const double reach = radius + B->radius;
  if (lsdem_dot3(dx, dx) > reach * reach) return no_contact(n_out, res);

  /* report §2.3.5: one level-set lookup of the sphere centre in B's frame */
  double q[3], g[3], n[3];
  lsdem_matT_vec(pb->R, dx, q);
  const double d = radius - lsdem_sdf_eval(&B->sdf, q, g);
  if (!(d > 0.0)) {
    no_contact(n_out, res);
    res->ntested = 1;
    return 0;
  }
  lsdem_mat_vec(pb->R, g, n);
  return sphere_contact(radius, area, n, d, pa, pb, prm, step, hist_in, n_in, hist_out,
                        n_out, res);
}

int lsdem_contact_sphere_sphere(double ra, double area, const lsdem_pose *pa, double rb,
                                const lsdem_pose *pb, const lsdem_contact_params *prm,
                                int64_t step, const lsdem_node_hist *hist_in, int n_in,
                                lsdem_node_hist *hist_out, int *n_out,
                                lsdem_contact_result *res)
{
  double dx[3];
  for (int i = 0; i < 3; i++) dx[i] = pa->x[i] - pb->x[i];
  const double reach = ra + rb, dist2 = lsdem_dot3(dx, dx);
  if (!(dist2 < reach * reach)) return no_contact(n_out, res);

  const double dist = sqrt(dist2);
  double n[3] = {1.0, 0.0, 0.0}; /* coincident centres: any direction will do */
  if (dist > 0.0)
    for (int i = 0; i < 3; i++) n[i] = dx[i] / dist;
  return sphere_contact(ra, area, n, reach - dist, pa, pb, prm, step, hist_in, n_in,
                        hist_out, n_out, res);
}

/* ----------------------------------------------------------------- dispatch ---- */

static int is_sphere(const lsdem_shape *s) { return s->sdf.kind == LSDEM_SDF_SPHERE; }

int lsdem_contact_history_capacity(const lsdem_shape *A)
{
  /* shear entries, the list's head and an entry per listed node */
  return is_sphere(A) ? 1 : 2 * A->nnodes + LIST_HEAD;
}

double lsdem_sphere_contact_area(double radius) { return M_PI * radius * radius; }

int lsdem_contact_grain(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                        const lsdem_pose *pb, const lsdem_contact_params *prm, int64_t step,
                        const lsdem_node_hist *hist_in, int n_in, lsdem_node_hist *hist_out,
                        int *n_out, lsdem_contact_result *res)
{
  if (!is_sphere(A))
    return lsdem_contact_nodes(A, pa, B, pb, prm, step, hist_in, n_in, hist_out, n_out, res);
  const double ra = A->sdf.a[0], area = lsdem_sphere_contact_area(ra);
  if (is_sphere(B))
    return lsdem_contact_sphere_sphere(ra, area, pa, B->sdf.a[0], pb, prm, step, hist_in,
                                       n_in, hist_out, n_out, res);
  return lsdem_contact_sphere_shape(ra, area, pa, B, pb, prm, step, hist_in, n_in, hist_out,
                                    n_out, res);
}
