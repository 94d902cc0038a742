/* lsdem_contact.h -- contact of level-set grains (kernel, core/contact).
 *
 * Two stages with a public type between them (report §2.2, Algorithm 2):
 *
 *   detection  (detect.c, nodelist.c)  which nodes of master A lie inside slave B, and
 *              the geometry there: a CONTACT MANIFOLD, one point per penetrating node
 *              (point, normal, depth, node, relative velocity). Knows nothing of forces.
 *   a solver   that consumes manifolds: the penalty law (penalty.c, eqs 2.2-2.16) turns
 *              one into forces, torques and per-node shear history; the impulse solver
 *              of report chapter 4 turns those of an island into impulses.
 *
 * A pair carries two kinds of state from step to step, each its own record type, both
 * owned by the master A (the caller keeps them; fix LSDEM_HISTORY in LAMMPS):
 *   - a node list (lsdem_nodelist): which of A's nodes may touch B, detection's cache;
 *   - shear history (lsdem_shear_hist): the penalty law's tangential springs, per node.
 * Who is master of a pair is decided by lsdem_contact_roles (roles.c).
 *
 * Frames and signs: everything here is world frame except node coordinates (A's
 * principal frame). The normal n is B's outward unit normal at the contact, so it points
 * from B towards A; a force computed for a contact acts on A (repulsive: +|f_n| n) and B
 * receives -f. Torques are about each grain's centroid. */
#ifndef LSDEM_CONTACT_H
#define LSDEM_CONTACT_H

#include "../geom/lsdem_geom.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Rigid-body state of one grain in the world frame, as the contact kernel needs it. */
typedef struct {
  double x[3];      /* centroid */
  double R[9];      /* body -> world rotation */
  double v[3];      /* centroid velocity */
  double omega[3];  /* angular velocity, world frame */
} lsdem_pose;

/* ---------------------------------------------------------------- parameters ---- */

/* What detection tests (not what force follows). */
typedef struct {
  int node_stride;  /* test every N-th node (report §3.4.1), the law's stiffnesses and
                       dampings then weighted by N; 1 = all */
  double node_skin; /* > 0: keep a node list per pair (lsdem_nodelist), built with this
                       skin (length); 0 = screen every node at every call */
} lsdem_detect_params;

typedef enum { LSDEM_NORMAL_PER_NODE = 0, LSDEM_NORMAL_TRACTION = 1 } lsdem_normal_law;

/* The penalty law (report eqs 2.2-2.16). */
typedef struct {
  double kn;        /* per-node normal stiffness (force/length), or traction stiffness
                       (stress/length) when normal == LSDEM_NORMAL_TRACTION */
  double ks;        /* tangential stiffness, same convention as kn */
  double mu;        /* Coulomb friction coefficient (eq 2.10); 0 = no shear history */
  double cn;        /* normal viscous damping per node (force/velocity), 0 = none */
  double ct;        /* tangential viscous damping per node, 0 = none */
  lsdem_normal_law normal;
} lsdem_penalty_law;

/* A pair's whole contact setting: law, detection and the time step (eq 2.7's dt). */
typedef struct {
  lsdem_penalty_law law;
  lsdem_detect_params detect;
  double dt;
} lsdem_contact_params;

/* ------------------------------------------------------------------ manifold ---- */

/* One contact point: a node of master A inside slave B. World frame. */
typedef struct {
  int32_t node;      /* A's node index (0 for a sphere) */
  double point[3];   /* the node's position (a sphere: the middle of the overlap) */
  double normal[3];  /* B's outward unit normal there: from B towards A */
  double depth;      /* penetration -phi_B > 0 */
  double area;       /* the node's tributary area (traction law; 1 when A has none; a
                        sphere: its cross-section, lsdem_sphere_contact_area) */
  double vrel[3];    /* velocity of A's material point at `point` relative to B's
                        (eq 2.6: vA + wA x (p - xA) - vB - wB x (p - xB)) */
} lsdem_contact_point;

/* The contact manifold of one master-on-slave test: its points in increasing node order,
 * with what a solver needs of the pair. Storage is the caller's: point[] holds cap
 * entries, at least lsdem_manifold_capacity(A). */
typedef struct {
  int n, cap;
  lsdem_contact_point *point;
  int stride;      /* the node stride the points were found with (weights them) */
  double xa[3];    /* A's centroid: the arm of point p about A is p - xa */
  double dab[3];   /* xA - xB: the arm about B is (p - xa) + dab */
  int ntested;     /* nodes that reached a level-set lookup (the work done) */
} lsdem_manifold;

/* Points a manifold can need for master A: 1 for a sphere, else A's node count. */
static inline int lsdem_manifold_capacity(const lsdem_shape *A)
{
  return A->sdf.kind == LSDEM_SDF_SPHERE ? 1 : A->nnodes;
}
/* An empty manifold over caller storage of cap points. */
lsdem_manifold lsdem_manifold_over(lsdem_contact_point *storage, int cap);

/* ------------------------------------------------------------------ node lists ---- */

/* A pair's node list: a Verlet list of A's nodes that may touch B (nodelist.c). It is
 * built when every node is screened, with the nodes that could reach B within a skin s,
 * and used while no node has moved by its validity radius relative to B (bound
 * |M - M0| rA + |t - t0| on the change of q = M x + t); then only its nodes are looked
 * up. A node is left out when it is farther than rB + s from B's centre or, when B's
 * level set has a known gradient bound L (exact distances: 1; grids:
 * lsdem_grid_outer_lipschitz), when phi_B >= L s there: it cannot reach phi < 0 before
 * the list is rebuilt. Against a grid each entry also keeps the 8 samples of the cell its
 * node was last looked up in, and a lookup in the same cell reads those instead of the
 * grid (lsdem_grid_eval_many_cached). The contacts found are the same, bit for bit, as
 * without a list; only lookups of nodes that cannot touch, and grid reads, are saved.
 * The skin adapts per pair: a list outlived within 8 steps is followed by one wide
 * enough to last 8 steps at the pair's rate of motion (at most 4 s, and within B's
 * gradient bound), and a wide list (validity radius above 2 s) is rebuilt after 32
 * steps. A list built with another stride is rebuilt. A node listed at phi > 0 keeps
 * its slack min(phi, the bound's limit) / L (rounded down to 31sts of the build's skin):
 * it cannot touch while the motion bound since the build is below that, and its lookups
 * are skipped till then (settled pairs: most of them), its entry carried over.
 *
 * Layout (8-byte words, one stream per pair): the head, then the entries in increasing
 * node order, each a word (node, slack, cell index) followed by the node's coordinates in
 * A's frame (3 words: a step that uses the list reads none of A's node memory) and, when
 * the list keeps cells (B a grid), the cell's samples (4 words): lsdem_nodelist_entry_words.
 * (Entries with slack kept as their first word alone until looked up were measured: a
 * quarter less history on a 750-node specimen, 7 % slower on the reference scene, where
 * their first lookup reads the grid: bench/README.md.) */
typedef struct {
  float M[9], t[3];  /* pose of B relative to A when built: node x -> M x + t (B's frame),
                        rounded to float (the motion bound allows for the rounding) */
  int64_t built;     /* step it was built at */
  float radius;      /* validity radius: the least distance any left-out node had to move
                        to touch B (at least the skin), rounded down */
  float slack_unit;  /* the unit of its entries' slack: the build's skin / 31, rounded down
                        (0: none, B has no gradient bound or the list came from state
                        records: its entries' slack is ignored) */
  int32_t stride;    /* node stride it was built with */
  int32_t count;     /* node entries */
  int32_t words;     /* the entries' size in 8-byte words */
  int32_t cells;     /* 1: the entries carry their cells' samples (B a grid) */
} lsdem_nodelist_head;

typedef struct {
  uint32_t node : 27; /* A's node index (< LSDEM_LIBRARY_MAX_NODES = 2^26), or
                         LSDEM_NODELIST_NO_NODE (a damaged state record's) */
  uint32_t slack : 5; /* the node cannot touch B before the motion bound since the build
                         reaches slack x head.slack_unit (its lookup is skipped till then;
                         0: looked up) */
  int32_t cell;  /* grid index of the kept cell's sample 000, -1: none kept (always, in a
                    list without cells) */
} lsdem_nodelist_entry; /* one word; the node and the samples follow it */

#define LSDEM_NODELIST_NO_NODE ((1u << 27) - 1u)
#define LSDEM_NODELIST_X_WORDS 3      /* double x[3], the node in A's frame */
#define LSDEM_NODELIST_SAMPLE_WORDS 4 /* float v[8], lsdem_grid_cell order */
#define LSDEM_NODELIST_MAX_WORDS (1 + LSDEM_NODELIST_X_WORDS + LSDEM_NODELIST_SAMPLE_WORDS)

/* Words each entry of a list with head h takes. */
static inline int lsdem_nodelist_entry_words(const lsdem_nodelist_head *h)
{
  return 1 + LSDEM_NODELIST_X_WORDS + (h->cells ? LSDEM_NODELIST_SAMPLE_WORDS : 0);
}

/* The node an entry carries (A's frame). */
static inline double *lsdem_nodelist_x(const lsdem_nodelist_entry *e)
{
  return (double *)(e + 1);
}

/* The cell samples an entry carries in a list of cells. */
static inline float *lsdem_nodelist_samples(const lsdem_nodelist_entry *e)
{
  return (float *)(e + 1 + LSDEM_NODELIST_X_WORDS);
}

/* Entry k of the list with head h whose entries begin at e. */
static inline lsdem_nodelist_entry *lsdem_nodelist_at(const lsdem_nodelist_head *h,
                                                      lsdem_nodelist_entry *e, int k)
{
  return e + (size_t)k * lsdem_nodelist_entry_words(h);
}

/* A node list as detection reads and writes it, in the caller's storage: valid = 0 means
 * none. As output, head points to room for the head and entry to room for
 * lsdem_nodelist_capacity(A) words of entries; detection sets valid. */
typedef struct {
  int valid;
  lsdem_nodelist_head *head;
  lsdem_nodelist_entry *entry;
} lsdem_nodelist;

/* Words of entries a node list of master A can need: one entry with its samples per node
 * of A (0 for a sphere). */
static inline int lsdem_nodelist_capacity(const lsdem_shape *A)
{
  return A->sdf.kind == LSDEM_SDF_SPHERE ? 0 : A->nnodes * LSDEM_NODELIST_MAX_WORDS;
}

/* ----------------------------------------------------------------- detection ---- */

/* Node-to-surface detection of master A's nodes in slave B's level set (report
 * Algorithm 2, the geometry of eqs 2.2-2.6), chosen by the kinds: A a sphere (one lookup
 * of its centre in B, or sphere-sphere in closed form, report §2.3.5) or A's nodes.
 * Cheap rejection first: bounding spheres (eq 2.1), then A's node clusters and nodes
 * outside B's bounding sphere (or, B an unbounded exact distance such as a wall, clear
 * of B's level set) are skipped before any trilinear lookup; looked-up nodes go in
 * batches (their cache misses overlap).
 * list_in (NULL or not valid: none) is the pair's node list of the last step; list_out
 * (NULL: none kept) receives this step's (copied, rebuilt or none when det->node_skin is
 * 0). m receives the points (m->n = 0: no contact). Returns m->n.
 * Spheres: the point is the middle of the overlap, xA - (radius - d/2) n, so a normal
 * force there exerts no torque on the sphere; a sphere's centre inside B is handled
 * (depth = radius - phi_B(centre)). B->radius must bound B's solid (HUGE_VAL for walls
 * and inverted shapes). node_stride N tests only nodes k with k % N == 0 (in the stored,
 * clustered order). A shape with nclusters == 0 is one cluster without a sphere test. */
int lsdem_detect(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                 const lsdem_pose *pb, const lsdem_detect_params *det, int64_t step,
                 const lsdem_nodelist *list_in, lsdem_nodelist *list_out,
                 lsdem_manifold *m);

/* The node path of lsdem_detect, whatever A's kind (an analytic sphere with nodes, in
 * tests). */
int lsdem_detect_nodes(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                       const lsdem_pose *pb, const lsdem_detect_params *det, int64_t step,
                       const lsdem_nodelist *list_in, lsdem_nodelist *list_out,
                       lsdem_manifold *m);

/* The other way round for a band wall A (fix wall/lsdem twoway): A's sharp points (pts,
 * lsdem_band_points of band; A at pa is the master) inside grain B's level set (B at pb,
 * B->radius bounding it). Only the stored bricks that B's bounding sphere reaches are
 * visited and only their points within it are looked up, one lookup each in B's frame.
 * The manifold's points are the wall's points in increasing number (node = point
 * number), normal B's outward normal (from the grain towards the wall), depth -phi_B,
 * area 1, stride 1, relative velocity the wall's point's against B's. m->cap bounds the
 * points kept (lsdem_band_points_within B's radius suffices). Returns m->n. */
int lsdem_detect_band_points(const lsdem_band *band, const lsdem_band_points *pts,
                             const lsdem_pose *pa, const lsdem_shape *B,
                             const lsdem_pose *pb, lsdem_manifold *m);

/* The depth d = radius - phi by which a sphere of that radius whose centre is at phi in
 * level set s overlaps it (report §2.3.5), or 0 when it does not: also when s is a band and
 * phi is at or beyond its width, where phi is a bound, not a distance (fix wall/lsdem
 * requires bands wider than the spheres). The one rule of lsdem_sphere_overlap and of a
 * wall that found phi itself (fix wall/lsdem). */
static inline double lsdem_sphere_depth(const lsdem_sdf *s, double phi, double radius)
{
  if (s->kind == LSDEM_SDF_BAND && phi >= s->band->width) return 0.0;
  const double d = radius - phi;
  return d > 0.0 ? d : 0.0;
}

/* The sphere path's tributary area under the traction law: the cross-section pi r^2
 * (inline: the sphere kernel takes it for every contact). */
static inline double lsdem_sphere_contact_area(double radius)
{
  return 3.14159265358979323846 * radius * radius; /* M_PI */
}

/* The stiffest contact shape s can form, in node springs: the most nodes one flat contact
 * (a wall, a flat face of a partner) presses at once. Over the six principal axes and
 * LSDEM_FLAT_CONTACT_DIRECTIONS directions u of a Fibonacci sphere, the nodes within
 * LSDEM_FLAT_CONTACT_DEPTH x the bounding radius of the shape's extreme along u
 * (u . node >= max u . node - depth): the largest count (normal law per node) or summed
 * node area (traction). The contact's normal stiffness is up to kn times this: a node
 * stride presses every stride-th node with stride times the spring, the same. An analytic
 * sphere (one contact point): 1, or its contact area. Principal frame, no allocation. */
#define LSDEM_FLAT_CONTACT_DIRECTIONS 120
#define LSDEM_FLAT_CONTACT_DEPTH 0.02
double lsdem_flat_contact_nodes(const lsdem_shape *s, lsdem_normal_law normal);

/* ---------------------------------------------------------------- penalty law ---- */

/* Per-node tangential history (report eq 2.8): the shear force carried by node `node`
 * of the master against one partner, the contact normal it was last rotated to, and the
 * step it was last advanced (its low 32 bits: lsdem_shear_stamp; an entry is kept from
 * one step to the next only). World frame. 56 bytes. */
typedef struct {
  int32_t node;
  uint32_t stamp;
  double shear[3];
  double normal[3];
} lsdem_shear_hist;

/* The stamp of step `step`. */
static inline uint32_t lsdem_shear_stamp(int64_t step)
{
  return (uint32_t)(uint64_t)step;
}

/* What the penalty law made of one manifold. Forces and torques are world-frame and act
 * on the master A; the slave B receives -force and torque_b. */
typedef struct {
  double force[3];     /* sum of node forces on A (eq 2.14) */
  double torque_a[3];  /* about A's centroid (eq 2.16) */
  double torque_b[3];  /* about B's centroid, of the reaction on B */
  double point[3];     /* mean contact point weighted by normal force (one point: it; 0
                          without contact) */
  double max_depth;    /* deepest penetration (>= 0) */
  int npen;            /* penetrating nodes (the manifold's points) */
  int ntested;         /* nodes looked up (the manifold's ntested) */
} lsdem_contact_result;

/* A contact's terms as the styles add them to the grains' f and torque (and a wall's
 * totals): scale times force, torque_a and torque_b, each rounded to its quantum
 * (lsdem_quantize3_scaled), so that every order of summation, on any rank count, gives
 * the same sums. scale 1 leaves them unscaled, exactly. */
typedef struct {
  double force[3], torque_a[3], torque_b[3];
} lsdem_contact_terms;
static inline void lsdem_contact_terms_of(const lsdem_contact_result *r, double scale,
                                          lsdem_quantum force_q, lsdem_quantum torque_q,
                                          lsdem_contact_terms *t)
{
  lsdem_quantize3_scaled(scale, r->force, force_q, t->force);
  lsdem_quantize3_scaled(scale, r->torque_a, torque_q, t->torque_a);
  lsdem_quantize3_scaled(scale, r->torque_b, torque_q, t->torque_b);
}

/* The penalty law on a manifold (report eqs 2.2-2.16), per point k with weight
 * w = stride (per node) or stride * area (traction):
 *   normal   fn = kn w d - cn stride (vrel . n), clamped at >= 0 (never attractive);
 *   shear    (mu > 0) spring s = Z s_old - ks w vt dt (eqs 2.7-2.8; s_old = 0 for a new
 *            contact, Z = lsdem_rotate_between from the stored to the current normal),
 *            ft = s - ct stride vt, |ft| capped at mu fn (eq 2.10) with s reset to
 *            ft + ct stride vt;
 *   sums     force and torques in node order (eqs 2.14-2.16).
 * hist_in (n_in entries, sorted by node) is this pair's shear history of the previous
 * step; every point's updated entry is written to hist_out (capacity m->n, sorted; count
 * in *n_out). An entry whose stamp == step is reused as is (already advanced this step:
 * a second force call at the same step must not advance the shear twice). mu == 0: no
 * history read or written (NULL, 0, NULL). hist_out == NULL with mu > 0 evaluates the
 * shear from hist_in without keeping it. hist_in and hist_out must not overlap.
 * Returns m->n. */
int lsdem_penalty_apply(const lsdem_manifold *m, const lsdem_penalty_law *law, double dt,
                        int64_t step, const lsdem_shear_hist *hist_in, int n_in,
                        lsdem_shear_hist *hist_out, int *n_out, lsdem_contact_result *res);

/* ------------------------------------------------- one pair, end to end ---- */

/* The state a pair keeps between steps (owned by the master): node list and shear
 * history, each may be absent. As output, list.entry needs lsdem_nodelist_capacity(A)
 * words and shear lsdem_manifold_capacity(A). */
typedef struct {
  lsdem_nodelist list;
  lsdem_shear_hist *shear;
  int nshear;
} lsdem_pair_state;

/* Detection then the penalty law, with the pair's state of the last step (in, NULL:
 * none) and of this one (out, NULL: none kept); m is scratch storage for the manifold
 * (capacity lsdem_manifold_capacity(A)). Returns the penetrating nodes. */
int lsdem_contact_penalty(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                          const lsdem_pose *pb, const lsdem_contact_params *prm,
                          int64_t step, const lsdem_pair_state *in, lsdem_pair_state *out,
                          lsdem_manifold *m, lsdem_contact_result *res);

/* An analytic sphere A (radius ra) against B end to end, with one contact point: B a
 * sphere in closed form (overlap d = ra + rb - |xA - xB|, normal n along the centre line
 * from B to A), any other B by one lookup of A's centre in B's level set (report §2.3.5);
 * the point in the middle of the overlap, p = xA - (ra - d/2) n, and the penalty law there
 * (eqs 2.2-2.16, weight 1, or the cross-section pi ra^2 under the traction law). The same
 * result, bit for bit, as lsdem_detect then lsdem_penalty_apply give for the sphere,
 * without a manifold or a node list. The pair's shear history is at most one entry (node
 * 0): hist_in (n_in entries, as lsdem_penalty_apply reads them) and hist_out (room for
 * one, NULL: not kept; *n_out 0 or 1). Returns 1 in contact, else 0 (res all zero but
 * its lookups, ntested). */
int lsdem_contact_sphere(double ra, const lsdem_pose *pa, const lsdem_shape *B,
                         const lsdem_pose *pb, const lsdem_penalty_law *law, double dt,
                         int64_t step, const lsdem_shear_hist *hist_in, int n_in,
                         lsdem_shear_hist *hist_out, int *n_out, lsdem_contact_result *res);
/* Its second half, for a caller that found the overlap itself (fix wall/lsdem: the
 * centre's distance phi to the wall, d = ra - phi > 0, n the wall's normal there): the
 * point and the law from B's outward normal n and depth d > 0, B at pose pb; the same
 * bits as lsdem_contact_sphere when n and d are its overlap's. Returns 1. */
int lsdem_contact_sphere_overlapping(double ra, const lsdem_pose *pa, const lsdem_pose *pb,
                                     const double n[3], double d,
                                     const lsdem_penalty_law *law, double dt, int64_t step,
                                     const lsdem_shear_hist *hist_in, int n_in,
                                     lsdem_shear_hist *hist_out, int *n_out,
                                     lsdem_contact_result *res);

/* ------------------------------------------------------------- master and slave ---- */

typedef enum {
  LSDEM_ROLES_ONEWAY = 0,    /* one direction: the grain with the finer nodes relative to
                                its partner's size tests (lsdem_contact_node_scale; ties:
                                the lower id) */
  LSDEM_ROLES_TWOWAY = 1,    /* both directions, each weighted 1/2 (action = reaction) */
  LSDEM_ROLES_ONEWAY_ID = 2  /* one direction, the report's rule: the lower id tests */
} lsdem_roles_rule;

/* The scale that picks the master of a one-way pair: node spacing times bounding radius,
 * the spacing estimated as V^(1/3) / sqrt(nnodes) (no node memory read). Grain a's nodes
 * resolve b when a's spacing is small against b's size: s_a / R_b < s_b / R_a, i.e. the
 * grain of the smaller s R tests. (A small grain on a large one of lower id would
 * otherwise sink: the large grain's nodes can be farther apart than the small one is
 * wide.) */
double lsdem_contact_node_scale(const lsdem_shape *s);

/* Weight of the test of grain a's nodes against grain b's level set (0: a does not test
 * b), for two grains with distinct ids (same ids: a periodic image of itself, 0):
 *   - a sphere against a grain with nodes: the sphere tests (1 lookup), the grain not;
 *   - two analytic spheres: the lower id (closed form, symmetric);
 *   - two grains with nodes: one direction by the finer nodes (ONEWAY) or the lower id
 *     (ONEWAY_ID), or both, each 1/2 (TWOWAY).
 * scale_a, scale_b: the grains' lsdem_contact_node_scale, computed once per shape by the
 * caller (the rule runs for every neighbour pair at every reneighbouring). */
double lsdem_contact_roles(const lsdem_shape *a, double scale_a, int64_t id_a,
                           const lsdem_shape *b, double scale_b, int64_t id_b,
                           lsdem_roles_rule rule);

/* ------------------------------------------- history in exchange and restart records ---- */

/* A pair's state as it travels between ranks and sits in restart files: a sequence of
 * fixed-size records (8 words each, one partner tag beside them in the caller's buffer),
 * the layout of every earlier version so that their restart files still load:
 *   list head  two records: id -2 {aux stride, stamp built, a M[0..2], b M[3..5]} and
 *              id -1 {aux count, stamp = the bits of radius, a M[6..8], b t};
 *   list node  one per entry: id -(1 << 29) + node {aux cell (-1: no samples), stamp and
 *              a = the samples v[0..7] as 32 bits each, b x (the node in A's frame)};
 *   shear      one per entry: id = node >= 0 {aux 0, stamp, a shear, b normal}. */
typedef struct {
  int32_t id, aux;
  int64_t stamp;
  double a[3], b[3];
} lsdem_state_record;

/* Records st needs: 2 + list count (if valid) + nshear. */
int lsdem_pair_state_records(const lsdem_pair_state *st);
/* st as records (lsdem_pair_state_records of them); returns the count. */
int lsdem_pair_state_encode(const lsdem_pair_state *st, lsdem_state_record *rec);
/* Records back into st, whose list.head points to room for a head, list.entry to room for
 * n entries with samples (n LSDEM_NODELIST_MAX_WORDS words) and shear to n shear entries.
 * A decoded list has no slack; its entries carry the records' nodes and cells. A list is
 * taken when a head is followed by its node entries (ids of nodes < nnodes); records
 * of an older layout (shear entries ahead of the list's nodes, masks with ids -3..) leave
 * no list, their shear entries kept. Shear entries are kept in increasing node order
 * (others dropped). */
void lsdem_pair_state_decode(const lsdem_state_record *rec, int n, int nnodes,
                             lsdem_pair_state *st);

#ifdef __cplusplus
}
#endif
#endif /* LSDEM_CONTACT_H */
