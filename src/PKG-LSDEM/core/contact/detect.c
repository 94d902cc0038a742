/* detect.c -- node-to-surface detection of level-set grains (report Algorithm 2, the
 * geometry of eqs 2.1-2.6) and the analytic sphere paths (report §2.3.5), producing a
 * contact manifold (lsdem_contact.h). No forces here: see penalty.c.
 *
 * Frames: node coordinates are in A's principal frame, cb (B's centre) too; q, g (a node
 * and B's level-set gradient) in B's principal frame; the manifold is world frame. */
#include "nodelist.h"
#include "point.h"

#include <math.h>
#include <string.h>

/* An empty manifold for the pair (no points yet). */
static void manifold_begin(lsdem_manifold *m, const pair_motion *pm, int stride)
{
  m->n = 0;
  m->ntested = 0;
  m->stride = stride;
  for (int i = 0; i < 3; i++) {
    m->xa[i] = pm->xa[i];
    m->dab[i] = pm->dab[i];
  }
}

/* Appends a point at p (world) with B's outward normal n, depth d > 0 and area. */
static inline __attribute__((always_inline)) void add_point(lsdem_manifold *restrict m,
                                                            const pair_motion *restrict pm,
                                                            int node, const double p[3],
                                                            const double n[3], double d,
                                                            double area)
{
  point_set(&m->point[m->n++], pm, node, p, n, d, area);
}

static int no_contact(lsdem_manifold *m, lsdem_nodelist *list_out)
{
  m->n = 0;
  m->ntested = 0;
  if (list_out) list_out->valid = 0;
  return 0;
}

/* ------------------------------------------------------------ node batches ---- */

/* Nodes looked up together, at most. */
enum { NODE_BATCH = 64 };

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
  int slotted;                 /* a list in use with slack: */
  int slot[NODE_BATCH];        /* each node's entry in the output list (-1: none kept) */
  unsigned char slack[NODE_BATCH]; /* and its slack */
  int cached;                  /* B is a grid whose cells come from the pair's list */
  lsdem_grid_cell cell[NODE_BATCH];
} node_batch;

/* What one detection shares between its batches. */
typedef struct {
  const lsdem_shape *A, *B;
  const lsdem_pose *pb;
  double M[9], t[3]; /* A's frame -> B's frame: q = M x + t */
  pair_motion motion;
  node_list list;
  lsdem_manifold *m;
} detection;

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

/* Looks the batch up, then adds its penetrating nodes to the manifold; empties the batch.
 * While a list is built, the nodes that may come to touch join it; the listed nodes (and
 * their cells, when B is a grid) are kept in the output list. */
static void detect_batch(detection *restrict dt, node_batch *b)
{
  node_list *L = &dt->list;
  const lsdem_shape *A = dt->A;
  b->cached = L->cached;
  lookup_batch(&dt->B->sdf, dt->M, dt->t, b);
  dt->m->ntested += b->n;
  for (int i = 0; i < b->n; i++) {
    if (L->use && b->slotted) {
      if (b->slot[i] >= 0)
        nodelist_write(L, &L->out->entry[b->slot[i]], b->node[i], &b->x[3 * i], &b->cell[i],
                       b->slack[i]);
    } else if (L->use) {
      if (L->out)
        nodelist_write(L, nodelist_next(L), b->node[i], &b->x[3 * i], &b->cell[i], 0);
    } else if (L->building && b->phi[i] < L->reach) {
      const unsigned slack = nodelist_slack(L, b->phi[i]);
      L->nslack += slack > 0;
      nodelist_write(L, nodelist_next(L), b->node[i], &b->x[3 * i], &b->cell[i], slack);
    } else if (L->building) {
      nodelist_margin(L, b->phi[i] / L->lip); /* phi >= L s: L > 0 here */
    }
  }
  int at[NODE_BATCH], npen = 0; /* the penetrating ones, gathered without a branch per node */
  for (int i = 0; i < b->n; i++) {
    at[npen] = i;
    npen += b->phi[i] < 0.0;
  }
  const lsdem_pose *pb = dt->pb;
  for (int m = 0; m < npen; m++) {
    const int i = at[m], k = b->node[i];
    double p[3], n[3];
    lsdem_affine3(pb->R, pb->x, &b->q[3 * i], p); /* world position of the node */
    lsdem_mat_vec(pb->R, &b->grad[3 * i], n);     /* world normal, outward from B */
    add_point(dt->m, &dt->motion, k, p, n, -b->phi[i], A->node_area ? A->node_area[k] : 1.0);
  }
  b->n = 0;
}

/* detect_batch for screened nodes: their coordinates from A, their cells from the input
 * list's entries where kept. */
static void screened_batch(detection *restrict dt, node_batch *b)
{
  for (int i = 0; i < b->n; i++) {
    memcpy(&b->x[3 * i], &dt->A->nodes[3 * b->node[i]], 3 * sizeof(double));
    if (dt->list.cached) nodelist_cell_of(&dt->list, b->node[i], &b->cell[i]);
  }
  detect_batch(dt, b);
}

/* p clamped into the box, a millionth of a spacing inside its faces (where lookups
 * interpolate, with the gradient of the cell) */
static void clamp_to_box(const lsdem_grid *gr, const double p[3], double q[3])
{
  const double inset = 1e-6 * gr->h;
  for (int a = 0; a < 3; a++) {
    const double lo = gr->origin[a] + inset, hi = gr->origin[a] + gr->h * (gr->n[a] - 1) - inset;
    q[a] = lsdem_min(lsdem_max(p[a], lo), hi);
  }
}

/* A master with fewer clusters is not screened by a grid grain's level set: a cluster's
 * lookup then saves too few of its nodes' (measured: the reference scene's 250-node
 * ellipsoids, 16 clusters, 5 % slower over its first 200 steps; 120-node grains, 8
 * clusters, no change; flowing 750-node grains, 64 clusters, 15 % faster; 2,500 nodes,
 * 256 clusters, 35-40 %: bench/README.md; 32 clusters from 272 nodes). */
enum { LEVEL_SET_SCREEN_MIN_CLUSTERS = 32 };

/* The bound L on |grad phi_B| that ball screening of A (ball_clearance) may use, 0 for
 * none: an unbounded B's (a wall: lsdem_sdf_lipschitz); a grid grain's when it is not
 * inverted and its box's boundary samples are all positive (lip_reach > 0: its solid lies
 * inside the box), lsdem_grid_outer_lipschitz's bound, which holds inside the box wherever
 * phi >= 0, for an A of at least LEVEL_SET_SCREEN_MIN_CLUSTERS clusters. Other bounded
 * shapes are screened by their bounding sphere only. */
static double screening_lipschitz(const lsdem_shape *A, const lsdem_shape *B)
{
  const lsdem_sdf *s = &B->sdf;
  if (!isfinite(B->radius)) return lsdem_sdf_lipschitz(s);
  const int grid = s->kind == LSDEM_SDF_GRID && !s->inverted &&
                   A->nclusters >= LEVEL_SET_SCREEN_MIN_CLUSTERS;
  return grid && s->grid.lip > 0.0 && s->grid.lip_reach > 0.0 ? s->grid.lip : 0.0;
}

/* A lower bound on the distance from q (B's frame) to a grid's solid, which lies inside
 * the box: the box distance, |q - c| for c = q clamped into the box (a millionth of a
 * spacing inside its faces: less at most 2e-6 h), and phi(c) / L - |q - c| (c's distance
 * is at least phi(c) / L: the segment from c to the nearest solid point stays in the box,
 * where |grad phi| <= L while phi >= 0); the larger of the two. box_gap_of and
 * grid_gap_of split it so that a point far from the box costs no lookup. */
static double box_gap_of(const lsdem_grid *gr, const double q[3], double c[3])
{
  double d[3];
  clamp_to_box(gr, q, c);
  lsdem_sub3(q, c, d);
  return sqrt(lsdem_dot3(d, d));
}

static double grid_gap_of(const lsdem_grid *gr, double lip, const double c[3], double out)
{
  return lsdem_max(out - 2e-6 * gr->h, lsdem_grid_value(gr, c) / lip - out);
}

/* For B with |grad phi| <= L (screening_lipschitz): no point of the ball of radius r
 * about centre (A's frame, mapped to B's by q = M x + t) is inside B when phi_B(q) / L > r
 * (a grid: its distance bound above > r). This is how a wall (unbounded: no bounding
 * sphere) skips a grain, or a cluster, and a grain a cluster of another's nodes, with one
 * evaluation instead of one per node. ball_margin: the relative margin that covers
 * round-off in phi at the nodes; ball_clearance: the bound less r and that margin, a
 * distance the ball must move to touch. */
static double ball_margin(const double q[3], double r)
{
  return 1e-12 * (fabs(q[0]) + fabs(q[1]) + fabs(q[2]) + r);
}

static double ball_clearance(const lsdem_sdf *sdfB, double lip, const double M[9],
                             const double t[3], const double centre[3], double r)
{
  double q[3], g[3], c[3];
  lsdem_affine3(M, t, centre, q);
  const double dist = sdfB->kind == LSDEM_SDF_GRID
                          ? grid_gap_of(&sdfB->grid, lip, c, box_gap_of(&sdfB->grid, q, c))
                          : lsdem_sdf_eval(sdfB, q, g) / lip;
  return dist - r - ball_margin(q, r);
}

/* Clusters screened at a time: their level-set lookups done back to back. */
enum { CLUSTER_BATCH = 32 };

/* Which of A's clusters [c0, c1) (at most CLUSTER_BATCH) may touch B: kept in keep[] in
 * increasing order, their count returned. A cluster is left out when its sphere is clear
 * of B's bounding sphere widened by `widen` (cb: B's centre in A's frame) or, for B with a
 * gradient bound lip > 0, of B's solid by more than `clear` (a grid: first by its box,
 * which needs no lookup, then by its level set, the lookups of the batch together). A
 * cluster left out of a list being built gives the list a margin: how far it is from
 * touching. */
static int screen_clusters(detection *dt, int c0, int c1, double widen, double lip,
                           double clear, const double cb[3], int keep[CLUSTER_BATCH])
{
  const lsdem_shape *A = dt->A, *B = dt->B;
  node_list *L = &dt->list;
  const int grid = B->sdf.kind == LSDEM_SDF_GRID;
  int n = 0;
  double q[CLUSTER_BATCH][3], c[CLUSTER_BATCH][3], out[CLUSTER_BATCH];
  for (int cl = c0; cl < c1; cl++) {
    const double *sph = &A->cluster_sphere[4 * cl];
    const double d[3] = {sph[0] - cb[0], sph[1] - cb[1], sph[2] - cb[2]};
    const double reach = B->radius + widen + sph[3];
    if (lsdem_dot3(d, d) > reach * reach) {
      if (L->building) nodelist_margin(L, sqrt(lsdem_dot3(d, d)) - B->radius - sph[3]);
      continue;
    }
    if (lip > 0.0) {
      lsdem_affine3(dt->M, dt->t, sph, q[n]);
      if (grid) {
        out[n] = box_gap_of(&B->sdf.grid, q[n], c[n]);
        const double gap = out[n] - 2e-6 * B->sdf.grid.h - sph[3] - ball_margin(q[n], sph[3]);
        if (gap > clear) {
          if (L->building) nodelist_margin(L, gap);
          continue;
        }
      }
    }
    keep[n++] = cl;
  }
  if (!(lip > 0.0)) return n;
  double dist[CLUSTER_BATCH], g[3];
  for (int i = 0; i < n; i++)
    dist[i] = grid ? grid_gap_of(&B->sdf.grid, lip, c[i], out[i])
                   : lsdem_sdf_eval(&B->sdf, q[i], g) / lip;
  int kept = 0;
  for (int i = 0; i < n; i++) {
    const double r = A->cluster_sphere[4 * keep[i] + 3];
    const double gap = dist[i] - r - ball_margin(q[i], r);
    if (gap > clear) {
      if (L->building) nodelist_margin(L, gap);
      continue;
    }
    keep[kept++] = keep[i];
  }
  return kept;
}

/* Nodes [start, end) of A (every stride-th) screened against B's bounding sphere, the kept
 * ones looked up in batches. */
static void screen_range(detection *restrict dt, int start, int end, int stride,
                         const double cb[3], double rb2, node_batch *batch, double *nearest)
{
  int k = (start + stride - 1) / stride * stride;
  while (k < end) {
    const int left = (end - k + stride - 1) / stride, room = NODE_BATCH - batch->n;
    const int count = left < room ? left : room;
    screen_nodes(dt->A->nodes, k, count, stride, cb, rb2, batch, nearest);
    k += count * stride;
    if (batch->n == NODE_BATCH) screened_batch(dt, batch);
  }
}

/* Every node of A screened: clusters, then nodes against B's bounding sphere (both
 * widened by the skin while a list is built), the kept ones looked up in batches. The
 * kept nodes of successive clusters share a batch (more lookups to overlap); the batch is
 * looked up when full and at the end, so nodes stay in increasing order. */
static void detect_screened_nodes(detection *restrict dt, const double cb[3], double lip,
                                  node_batch *batch, int stride)
{
  const lsdem_shape *A = dt->A;
  const node_list *L = &dt->list;
  const double widen = L->building ? L->skin : 0.0, rb = dt->B->radius + widen, rb2 = rb * rb;
  /* a node left out of a list being built has phi >= L s: its ball's gap beyond s */
  const double clear = L->building && isfinite(L->reach) ? L->skin : 0.0;
  double nearest = HUGE_VAL; /* squared distance from cb of the nearest node left out */
  if (isfinite(dt->B->radius) && lip > 0.0) { /* a grid grain B: A's bounding sphere first */
    const double origin[3] = {0.0, 0.0, 0.0};
    const double gap = ball_clearance(&dt->B->sdf, lip, dt->M, dt->t, origin, A->radius);
    if (gap > clear) {
      if (L->building) nodelist_margin(&dt->list, gap);
      return;
    }
  }
  if (A->nclusters > 0 && A->cluster_start && A->cluster_sphere) {
    for (int c0 = 0; c0 < A->nclusters; c0 += CLUSTER_BATCH) {
      const int c1 = c0 + CLUSTER_BATCH < A->nclusters ? c0 + CLUSTER_BATCH : A->nclusters;
      int keep[CLUSTER_BATCH];
      const int n = screen_clusters(dt, c0, c1, widen, lip, clear, cb, keep);
      for (int i = 0; i < n; i++)
        screen_range(dt, A->cluster_start[keep[i]], A->cluster_start[keep[i] + 1], stride, cb,
                     rb2, batch, &nearest);
    }
  } else {
    screen_range(dt, 0, A->nnodes, stride, cb, rb2, batch, &nearest);
  }
  screened_batch(dt, batch);
  if (L->building && nearest < HUGE_VAL)
    nodelist_margin(&dt->list, sqrt(nearest) - dt->B->radius);
}

/* Only the nodes of the pair's list, in increasing order, looked up in batches: their
 * coordinates and cells from the list's entries; with `skipping` (the list keeps slack), a
 * node whose slack is not used up is not looked up, its entry carried over. An entry that
 * names no node of A (a damaged restart file) is dropped. Inlined twice, so that a list
 * without slack (most in a dense packing: their nodes touch) pays no test per entry. */
static inline __attribute__((always_inline)) void
listed_nodes(detection *restrict dt, node_batch *batch, const int skipping)
{
  const node_list *L = &dt->list;
  const int words = lsdem_nodelist_entry_words(L->head_in);
  const lsdem_nodelist_entry *h = L->node_in;
  for (int e = 0; e < L->nnode_in; e++, h += words) {
    if ((int)h->node >= dt->A->nnodes) continue;
    lsdem_nodelist_entry *out = skipping && L->out ? nodelist_next(L) : NULL;
    if (skipping && nodelist_skips(L, h)) {
      if (out) memcpy(out, h, 8 * (size_t)words);
      continue;
    }
    const int i = batch->n++;
    if (skipping) { /* its place in the output list, taken now: entries stay in order */
      batch->slot[i] = out ? (int)(out - L->out->entry) : -1;
      batch->slack[i] = (unsigned char)h->slack;
    }
    batch->node[i] = h->node;
    memcpy(&batch->x[3 * i], lsdem_nodelist_x(h), 3 * sizeof(double));
    if (L->cached) nodelist_entry_cell(h, &batch->cell[i]);
    if (batch->n == NODE_BATCH) detect_batch(dt, batch);
  }
  detect_batch(dt, batch);
}

static void detect_listed_nodes(detection *restrict dt, node_batch *batch)
{
  batch->slotted = dt->list.slack_unit > 0.0;
  if (batch->slotted)
    listed_nodes(dt, batch, 1);
  else
    listed_nodes(dt, batch, 0);
}

int lsdem_detect_nodes(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                        const lsdem_pose *pb, const lsdem_detect_params *det, int64_t step,
                        const lsdem_nodelist *list_in, lsdem_nodelist *list_out,
                        lsdem_manifold *m)
{
  /* eq 2.1: bounding spheres of the pair */
  double dx[3];
  for (int i = 0; i < 3; i++) dx[i] = pb->x[i] - pa->x[i];
  const double rb = B->radius, rab = A->radius + rb;
  if (lsdem_dot3(dx, dx) > rab * rab) return no_contact(m, list_out);

  /* cb: B's centre in A's frame (for screening). A's frame -> B's frame:
   * q = M node + t with M = RB^T RA, t = RB^T (xA - xB). */
  detection dt;
  double cb[3], mdx[3] = {-dx[0], -dx[1], -dx[2]};
  lsdem_matT_vec(pa->R, dx, cb);
  lsdem_matT_mul(pb->R, pa->R, dt.M);
  lsdem_matT_vec(pb->R, mdx, dt.t);

  /* B with a gradient bound: a wall, which has no bounding sphere to screen with, rejects
   * A's bounding sphere (about A's centroid, the origin of A's frame) here, then A's
   * clusters by its level set; a grid grain does both only when A's nodes are screened (a
   * list built, or none kept: a list in use costs less than the lookup); lip = 0: no such
   * screening */
  const double lip = screening_lipschitz(A, B);
  const double origin[3] = {0.0, 0.0, 0.0};
  if (!isfinite(rb) && lip > 0.0 &&
      ball_clearance(&B->sdf, lip, dt.M, dt.t, origin, A->radius) > 0.0)
    return no_contact(m, list_out);

  const int stride = det->node_stride > 1 ? det->node_stride : 1;
  dt.A = A;
  dt.B = B;
  dt.pb = pb;
  dt.m = m;
  pair_motion_of(pa, pb, &dt.motion);
  manifold_begin(m, &dt.motion, stride);
  nodelist_begin(&dt.list, A, &B->sdf, det, step, list_in, list_out, dt.M, dt.t);

  node_batch batch;
  batch.n = batch.slotted = 0;
  if (dt.list.use)
    detect_listed_nodes(&dt, &batch);
  else
    detect_screened_nodes(&dt, cb, lip, &batch, stride);
  nodelist_finish(&dt.list);
  return m->n;
}

/* ------------------------------------------------ a wall's sharp points ---- */

/* The points of one stored brick (wall frame) within B's bounding sphere (cb: B's centre,
 * wall frame) looked up in B's level set, the penetrating ones added. */
static void detect_brick_points(const lsdem_band_points *pts, int32_t brick,
                                const double cb[3], double rb2, const double M[9],
                                const double t[3], const lsdem_shape *B,
                                const lsdem_pose *pa, const lsdem_pose *pb,
                                const pair_motion *pm, lsdem_manifold *m)
{
  for (int64_t k = pts->brick_start[brick]; k < pts->brick_start[brick + 1]; k++) {
    const double *x = &pts->x[3 * k];
    const double d0 = x[0] - cb[0], d1 = x[1] - cb[1], d2 = x[2] - cb[2];
    if (d0 * d0 + d1 * d1 + d2 * d2 > rb2 || m->n == m->cap) continue;
    double q[3], g[3], p[3], n[3];
    lsdem_affine3(M, t, x, q);
    const double phi = lsdem_sdf_eval(&B->sdf, q, g);
    m->ntested++;
    if (!(phi < 0.0)) continue;
    lsdem_affine3(pa->R, pa->x, x, p); /* the point in the world */
    lsdem_mat_vec(pb->R, g, n);        /* B's outward normal: from B towards the wall */
    add_point(m, pm, (int)k, p, n, -phi, 1.0);
  }
}

int lsdem_detect_band_points(const lsdem_band *band, const lsdem_band_points *pts,
                             const lsdem_pose *pa, const lsdem_shape *B,
                             const lsdem_pose *pb, lsdem_manifold *m)
{
  /* cb: B's centre in the wall's frame; the wall's frame -> B's: q = M x + t with
   * M = RB^T RA, t = RB^T (xA - xB) */
  double dx[3], cb[3], mdx[3], M[9], t[3];
  pair_motion pm;
  lsdem_sub3(pb->x, pa->x, dx);
  for (int a = 0; a < 3; a++) mdx[a] = -dx[a];
  lsdem_matT_vec(pa->R, dx, cb);
  lsdem_matT_mul(pb->R, pa->R, M);
  lsdem_matT_vec(pb->R, mdx, t);
  pair_motion_of(pa, pb, &pm);
  manifold_begin(m, &pm, 1);
  int lo[3], hi[3];
  lsdem_band_slot_range(band, cb, B->radius, lo, hi);
  const double rb2 = B->radius * B->radius;
  /* slots in increasing order: bricks, and so points, in increasing number */
  for (int z = lo[2]; z <= hi[2]; z++)
    for (int y = lo[1]; y <= hi[1]; y++)
      for (int x = lo[0]; x <= hi[0]; x++) {
        const int64_t slot = x + (int64_t)band->nb[0] * (y + (int64_t)band->nb[1] * z);
        const int32_t brick = band->index[slot];
        if (brick >= 0) detect_brick_points(pts, brick, cb, rb2, M, t, B, pa, pb, &pm, m);
      }
  return m->n;
}

/* ----------------------------------------------------------- sphere paths ---- */

/* One sphere contact (sphere A against B) given B's outward normal n and the depth d, at
 * the middle of the overlap (sphere_contact_point). */
static int sphere_point(double radius, const double n[3], double d, const lsdem_pose *pa,
                        const pair_motion *pm, lsdem_manifold *m)
{
  double p[3];
  sphere_contact_point(radius, pa->x, n, d, p);
  add_point(m, pm, 0, p, n, d, lsdem_sphere_contact_area(radius));
  return 1;
}

/* The distance from a point c outside B's grid box (B's frame) to B's solid, where the
 * grid's outside rule gives only an upper bound, phi(q) + |c - q| at q = clamp(c), and a
 * direction that is not the normal (lsdem_grid_eval). The distance is the least value of
 * f(q) = |c - q| + phi_B(q) over the box (triangle inequality: equal where q lies on the
 * segment from c to its closest surface point, phi being a distance inside the box),
 * reached on the box's boundary. It is found by projected descent from clamp(c),
 * q <- clamp(q - a grad f), grad f = (q - c)/|q - c| + grad phi_B(q): a step is kept only
 * when f decreases, and halved otherwise; on a face squarely below c the first point is
 * already the minimum. Returns the distance, the normal in n (from the minimising q
 * towards c: the line to c's closest surface point, which the grid's interpolated
 * gradient at q follows only to about h over the distance from an edge) and the lookups
 * made in *lookups. */
enum { OUTSIDE_LOOKUPS = 32 };

/* f(q) and its gradient (unprojected) */
static double outside_f(const lsdem_sdf *sdf, const double c[3], const double q[3],
                        double g[3], double grad_f[3])
{
  double d[3];
  lsdem_sub3(q, c, d);
  const double len = sqrt(lsdem_dot3(d, d)), phi = lsdem_sdf_eval(sdf, q, g);
  for (int a = 0; a < 3; a++) grad_f[a] = (len > 0.0 ? d[a] / len : 0.0) + g[a];
  return len + phi;
}

static double outside_distance(const lsdem_sdf *sdf, const double c[3], double n[3],
                               int *lookups)
{
  const lsdem_grid *gr = &sdf->grid;
  double q[3], gf[3], g[3];
  clamp_to_box(gr, c, q);
  double d0[3];
  lsdem_sub3(q, c, d0);
  double best = outside_f(sdf, c, q, g, gf), step = sqrt(lsdem_dot3(d0, d0));
  *lookups = 1;
  while (*lookups < OUTSIDE_LOOKUPS && step > 1e-6 * gr->h) {
    double p[3], t[3], tf[3], moved = 0.0;
    for (int a = 0; a < 3; a++) p[a] = q[a] - step * gf[a];
    clamp_to_box(gr, p, t);
    for (int a = 0; a < 3; a++) moved += (t[a] - q[a]) * (t[a] - q[a]);
    if (moved < 1e-24 * gr->h * gr->h) break; /* the projected gradient vanishes */
    const double f = outside_f(sdf, c, t, g, tf);
    ++*lookups;
    if (f < best) {
      best = f;
      memcpy(q, t, sizeof q);
      memcpy(gf, tf, sizeof gf);
    } else {
      step *= 0.5;
    }
  }
  lsdem_sub3(c, q, n);
  const double len = sqrt(lsdem_dot3(n, n));
  for (int a = 0; a < 3; a++) n[a] /= len; /* c lies outside the box: len > 0 */
  return best;
}

static int is_sphere(const lsdem_shape *s) { return s->sdf.kind == LSDEM_SDF_SPHERE; }

/* B not a sphere: ONE level-set lookup of the sphere centre in B's frame (report §2.3.5):
 * depth d = radius - phi_B(centre), normal = B's gradient there; for a centre outside B's
 * grid, its distance found by descent over the grid's box (outside_distance); none for a
 * centre at or beyond a band's width. */
int lsdem_sphere_overlap_shape(double radius, const lsdem_pose *pa, const lsdem_shape *B,
                               const lsdem_pose *pb, double n[3], double *d, int *lookups)
{
  double dx[3];
  for (int i = 0; i < 3; i++) dx[i] = pa->x[i] - pb->x[i];
  const double reach = radius + B->radius;
  *lookups = 0;
  if (lsdem_dot3(dx, dx) > reach * reach) return 0;

  double q[3], g[3];
  *lookups = 1;
  lsdem_matT_vec(pb->R, dx, q);
  if (B->sdf.kind == LSDEM_SDF_GRID && !B->sdf.inverted &&
      !lsdem_grid_box_contains(&B->sdf.grid, q))
    *d = radius - outside_distance(&B->sdf, q, g, lookups);
  else
    *d = lsdem_sphere_depth(&B->sdf, lsdem_sdf_eval(&B->sdf, q, g), radius);
  if (!(*d > 0.0)) return 0;
  lsdem_mat_vec(pb->R, g, n);
  return 1;
}

/* Sphere A against any B (lsdem_sphere_overlap) as a manifold of one point. */
static int detect_sphere(double radius, const lsdem_pose *pa, const lsdem_shape *B,
                         const lsdem_pose *pb, lsdem_manifold *m)
{
  double n[3], d;
  int lookups;
  const int touch = lsdem_sphere_overlap(radius, pa, B, pb, n, &d, &lookups);
  if (lookups == 0) return no_contact(m, NULL);
  pair_motion pm;
  pair_motion_of(pa, pb, &pm);
  manifold_begin(m, &pm, 1);
  m->ntested = lookups;
  return touch ? sphere_point(radius, n, d, pa, &pm, m) : 0;
}

/* ----------------------------------------------------------------- dispatch ---- */

lsdem_manifold lsdem_manifold_over(lsdem_contact_point *storage, int cap)
{
  lsdem_manifold m;
  memset(&m, 0, sizeof m);
  m.point = storage;
  m.cap = cap;
  m.stride = 1;
  return m;
}

int lsdem_detect(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                 const lsdem_pose *pb, const lsdem_detect_params *det, int64_t step,
                 const lsdem_nodelist *list_in, lsdem_nodelist *list_out, lsdem_manifold *m)
{
  if (!is_sphere(A))
    return lsdem_detect_nodes(A, pa, B, pb, det, step, list_in, list_out, m);
  if (list_out) list_out->valid = 0;
  return detect_sphere(A->sdf.a[0], pa, B, pb, m);
}
