/* lsdem_contact.h -- contact of level-set grains (kernel). */
#ifndef LSDEM_CONTACT_H
#define LSDEM_CONTACT_H

#include "../geom/lsdem_geom.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ contact ---- */

/* Rigid-body state of one grain in the world frame, as the contact kernel needs it. */
typedef struct {
  double x[3];      /* centroid */
  double R[9];      /* body -> world rotation */
  double v[3];      /* centroid velocity */
  double omega[3];  /* angular velocity, world frame */
} lsdem_pose;

/* Per-node tangential history (report eq 2.8): the shear force carried by node `node`
 * of the master against one partner, the contact normal it was last rotated to, and the
 * step it was last advanced. World frame. */
typedef struct {
  int32_t node;
  int32_t pad_;
  int64_t stamp;
  double shear[3];
  double normal[3];
} lsdem_node_hist;

typedef enum { LSDEM_NORMAL_PER_NODE = 0, LSDEM_NORMAL_TRACTION = 1 } lsdem_normal_law;

typedef struct {
  double kn;        /* per-node normal stiffness (force/length), or traction stiffness
                       (stress/length) when law == LSDEM_NORMAL_TRACTION */
  double ks;        /* tangential stiffness, same convention as kn */
  double mu;        /* Coulomb friction coefficient (eq 2.10); 0 = no history at all */
  double cn;        /* normal viscous damping per node (force/velocity), 0 = none */
  double ct;        /* tangential viscous damping per node, 0 = none */
  double dt;        /* time step, for the shear increment (eq 2.7) */
  int node_stride;  /* test every N-th node, forces scaled by N (report §3.4.1); 1 = all */
  lsdem_normal_law law;
  double node_skin; /* > 0: keep a node list per pair in its history (see below), built
                       with this skin (length); 0 = screen every node at every call */
} lsdem_contact_params;

/* What one master-on-slave test produced. Forces and torques are world-frame and act
 * on the master A; the slave B receives -force and torque_b. */
typedef struct {
  double force[3];     /* sum of node forces on A (eq 2.14) */
  double torque_a[3];  /* about A's centroid (eq 2.16) */
  double torque_b[3];  /* about B's centroid, of the reaction on B */
  double point[3];     /* mean contact point weighted by normal force (world) */
  double max_depth;    /* deepest penetration (>= 0) */
  int npen;            /* penetrating nodes */
  int ntested;         /* nodes that reached the trilinear lookup */
} lsdem_contact_result;

/* Node-to-surface contact of master A's nodes against slave B's level set
 * (report Algorithm 2, eqs 2.2-2.16). Cheap rejection first: clusters and nodes outside
 * B's bounding sphere are skipped before any trilinear lookup.
 *
 * History: hist_in (n_in entries, sorted by node) is this pair's history from the
 * previous step; every penetrating node's updated entry is written to hist_out (sorted,
 * capacity >= lsdem_contact_history_capacity(A)), count in *n_out. An entry whose stamp
 * == step is reused as is (already advanced this step: a second force call at the same
 * step must not advance the shear twice). With mu == 0 and node_skin == 0 no history is
 * read or written (pass NULL, 0, NULL).
 *
 * Node list (node_skin = s > 0; a Verlet list of nodes): the history also carries, in
 * entries with negative node ids, the pose of B relative to A (two entries placed first)
 * and the nodes of A that may touch B found at that pose (one entry per node, between
 * those two and the shear entries, holding the node's coordinates). While no node has
 * moved by s relative to B since then (bound |M - M0| rA + |t - t0| on the change of
 * q = M x + t), only those nodes are looked up; otherwise every node is screened again and
 * the list rebuilt. A node is left out when it is farther than rB + s from B's centre or,
 * when B's level set has a known gradient bound L (exact distances: 1; grids:
 * lsdem_grid_outer_lipschitz), when phi_B >= L s there: it cannot reach phi < 0 before the
 * list is rebuilt. Against a grid each listed node's entry also keeps its cell (the 8
 * samples), and a lookup in the same cell reads those instead of the grid
 * (lsdem_grid_eval_many_cached). The contacts found are therefore the same, bit for bit,
 * as without a list; only lookups of nodes that cannot touch, and grid reads, are saved
 * (res->ntested counts the lookups made). A list is trusted up to the least distance any
 * node it left out had to move to touch B (at least its skin: the distance to the widened
 * sphere, phi / L, a left-out cluster's clearance), whatever the skin is now; one built
 * with another stride is rebuilt. The skin adapts per pair: a list outlived within 8 steps
 * is followed by one wide enough to last 8 steps at the pair's rate of motion (at most
 * 4 s, and within B's gradient bound), and a wide list (validity radius above 2 s) is
 * rebuilt after 32 steps. Returns the number of penetrating nodes. */
int lsdem_contact_nodes(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                        const lsdem_pose *pb, const lsdem_contact_params *prm, int64_t step,
                        const lsdem_node_hist *hist_in, int n_in, lsdem_node_hist *hist_out,
                        int *n_out, lsdem_contact_result *res);
/* Details shared by all contact functions (lsdem_contact_nodes and the sphere paths):
 *   - The normal n is B's outward unit normal (world), pointing towards A. A contact's
 *     force on A is f = fn n + ft with fn = kn d (per node) or kn d area_k (traction),
 *     minus cn (v_rel . n) when cn > 0, clamped at >= 0 (never attractive); v_rel is
 *     the velocity of A's material point relative to B's at the contact (eq 2.6).
 *   - Shear (mu > 0): spring s = Z s_old - ks v_t dt (eqs 2.7-2.8; s_old = 0 for a new
 *     contact, Z = lsdem_rotate_between from the stored to the current normal),
 *     ft = s - ct v_t, |ft| capped at mu fn (eq 2.10) with s reset to ft + ct v_t.
 *     The history entry stores s, n and stamp = step.
 *   - node_stride N: only nodes k with k % N == 0 are tested (in the stored, clustered
 *     order); kn, ks, cn, ct are multiplied by N for them.
 *   - A shape with nclusters == 0 is one cluster without a cluster-sphere test.
 *     B->radius must bound B's solid (HUGE_VAL for walls and inverted shapes).
 *   - res->point is weighted by the normal-force magnitudes (zero when npen == 0).
 *   - hist_in and hist_out must not overlap. hist_out == NULL with mu > 0 evaluates the
 *     shear from hist_in without keeping it (a one-off evaluation). */

/* Sphere fast path (report §2.3.5): a sphere A (centre pa->x, radius) against any
 * shape B, with ONE level-set lookup of the sphere centre in B's frame: depth
 * d = radius - phi_B(centre), normal = B's gradient there. Works for a membrane ball or
 * a grain whose sdf kind is SPHERE, and stays correct when the sphere centre is inside
 * B. The contact point is the middle of the overlap, xA - (radius - d/2) n, so the
 * normal force exerts no torque on the sphere. `area` is the sphere's tributary area
 * (used only by the traction law). node_stride is ignored. History uses node index 0
 * (capacity of hist_out >= 1). ntested is 1 when the bounding spheres overlap.
 * Returns 1 if in contact, else 0. */
int lsdem_contact_sphere_shape(double radius, double area, const lsdem_pose *pa,
                               const lsdem_shape *B, const lsdem_pose *pb,
                               const lsdem_contact_params *prm, int64_t step,
                               const lsdem_node_hist *hist_in, int n_in,
                               lsdem_node_hist *hist_out, int *n_out,
                               lsdem_contact_result *res);
/* Analytic sphere-sphere contact: d = ra + rb - |xA - xB|, n = (xA - xB)/|xA - xB|;
 * otherwise the same conventions as lsdem_contact_sphere_shape (A = sphere ra). */
int lsdem_contact_sphere_sphere(double ra, double area, const lsdem_pose *pa, double rb,
                                const lsdem_pose *pb, const lsdem_contact_params *prm,
                                int64_t step, const lsdem_node_hist *hist_in, int n_in,
                                lsdem_node_hist *hist_out, int *n_out,
                                lsdem_contact_result *res);

/* Contact of grain A (its nodes, or one lookup when A is a sphere kind) against shape B,
 * the path chosen from the kinds: sphere-sphere, sphere-shape (area
 * lsdem_sphere_contact_area) or nodes. Same conventions and returns;
 * hist_out needs lsdem_contact_history_capacity(A) entries. */
int lsdem_contact_grain(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                        const lsdem_pose *pb, const lsdem_contact_params *prm, int64_t step,
                        const lsdem_node_hist *hist_in, int n_in, lsdem_node_hist *hist_out,
                        int *n_out, lsdem_contact_result *res);
/* 1 for a sphere, else nnodes plus the node list's entries */
int lsdem_contact_history_capacity(const lsdem_shape *A);
/* The sphere path's tributary area under the traction law: the cross-section pi r^2. */
double lsdem_sphere_contact_area(double radius);

#ifdef __cplusplus
}
#endif
#endif /* LSDEM_CONTACT_H */
