/* lsdem.h -- public API of the LSDEM core: level-set grains as plain C11.
 *
 * No LAMMPS and no MPI in here. Memory is owned by the caller unless a function says
 * it allocates (then a matching *_free exists). Errors come back as an lsdem_status
 * with a message in a caller-supplied lsdem_error (which may be NULL); the core never
 * calls exit() or abort().
 *
 * Conventions used throughout:
 *   - Quaternions are scalar-first (w, x, y, z), unit length, and rotate body (principal)
 *     frame vectors into the world frame: v_world = R(q) v_body.
 *   - Matrices are 3x3 row-major double[9].
 *   - A level set phi is a signed distance: negative inside the solid, positive outside,
 *     in the same length unit as positions. Gradients point outward.
 *   - A grain shape lives in its principal frame: centroid at the origin, inertia
 *     tensor diagonal. Inertia values are per unit density (volume-weighted), so
 *     mass = density * volume and I = density * inertia.
 */
#ifndef LSDEM_H
#define LSDEM_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- errors ---- */

typedef enum {
  LSDEM_OK = 0,
  LSDEM_ERR_ARG,     /* a bad argument (NULL, negative size, out of range) */
  LSDEM_ERR_IO,      /* a file could not be opened, read, written or mapped */
  LSDEM_ERR_FORMAT,  /* a file's content is malformed, truncated or corrupt */
  LSDEM_ERR_NOMEM,   /* an allocation failed or a size would overflow */
  LSDEM_ERR_NUMERIC  /* NaN/inf or a degenerate quantity (zero volume, ...) */
} lsdem_status;

typedef struct {
  char msg[512];
} lsdem_error;

/* Human-readable name of a status code ("format error", ...). */
const char *lsdem_status_name(lsdem_status s);

/* Record a printf-style message in err (if not NULL) and return s. */
lsdem_status lsdem_fail(lsdem_error *err, lsdem_status s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Read a whole file (at most max_bytes) into a new buffer, NUL-terminated (not counted in
 * *size); free(*data) when done. */
lsdem_status lsdem_read_file(const char *path, size_t max_bytes, unsigned char **data,
                             size_t *size, lsdem_error *err);

/* ------------------------------------------------- quaternions, rotations ---- */

void lsdem_quat_normalize(double q[4]);
void lsdem_quat_multiply(const double a[4], const double b[4], double out[4]); /* a*b */
void lsdem_quat_conjugate(const double q[4], double out[4]);
void lsdem_quat_to_matrix(const double q[4], double R[9]);          /* body -> world */
void lsdem_matrix_to_quat(const double R[9], double q[4]);          /* proper rotation */
void lsdem_quat_rotate(const double q[4], const double v[3], double out[3]);     /* R v */
void lsdem_quat_rotate_inv(const double q[4], const double v[3], double out[3]); /* R^T v */
/* q <- q * exp(omega_body * dt / 2): exact update for a body-frame angular velocity
 * held constant over dt (solution of the quaternion rate equation, report eq 2.28). */
void lsdem_quat_advance(double q[4], const double omega_body[3], double dt);
/* Rodrigues' formula (report eq 2.9): rotate v about the unit axis k by angle theta. */
void lsdem_rodrigues(const double v[3], const double k[3], double theta, double out[3]);
/* Rotate v by the rotation that takes unit vector n_old onto unit vector n_new
 * (the operator Z of report eq 2.8). Identity when n_old == n_new. */
void lsdem_rotate_between(const double v[3], const double n_old[3], const double n_new[3],
                          double out[3]);

/* Kawamoto/Tan rotation files store (q0 q1 q2 q3) = their code's quaternion, w last.
 * Their rotation matrix (report eq 2.26 with Evans' q1..q4 = file q0..q3) equals the
 * textbook body->world matrix of the scalar-first quaternion (q3, -q1, q0, -q2). */
void lsdem_quat_from_tan(const double qtan[4], double q[4]);
void lsdem_quat_to_tan(const double q[4], double qtan[4]);
/* Eq 2.26 exactly as printed, with Evans' (q1, q2, q3, q4) = qtan[0..3]. */
void lsdem_tan_matrix_eq226(const double qtan[4], double R[9]);

/* 3x3 helpers shared by the core and the styles. */
void lsdem_mat_vec(const double R[9], const double v[3], double out[3]);   /* R v */
void lsdem_matT_vec(const double R[9], const double v[3], double out[3]);  /* R^T v */
void lsdem_cross3(const double a[3], const double b[3], double out[3]); /* a x b; out may alias */
/* Symmetric 3x3 eigen-decomposition (Jacobi). Eigenvalues ascending in w; column k of V
 * (V[3*i+k]) is the unit eigenvector of w[k]; V is a proper rotation (det +1). */
void lsdem_sym_eigen(const double A[9], double w[3], double V[9]);

/* ----------------------------------------------------------- level sets ---- */

/* A signed-distance grid: n[0]*n[1]*n[2] float samples, x fastest, then y, then z.
 * Sample (i,j,k) sits at origin + h*(i,j,k) in the shape's own (principal) frame. */
typedef struct {
  int n[3];
  double h;          /* uniform spacing, length units */
  double origin[3];  /* position of sample (0,0,0) */
  const float *phi;
  double lip;        /* bound on |grad phi| where phi >= 0 (lsdem_grid_outer_lipschitz),
                        0 = unknown; set by lsdem_library_open, for the node lists */
  double lip_reach;  /* ... valid while lip * skin < lip_reach */
} lsdem_grid;

/* Trilinear interpolation of value and gradient (report Algorithm 1).
 * Returns phi at p and writes the normalised gradient to grad (unit length; +x if the
 * trilinear gradient vanishes).
 * Outside the grid box: returns phi(clamp(p)) + |p - clamp(p)| with grad = the unit
 * vector from clamp(p) towards p. Grids carry a positive margin, so such points are
 * never inside the solid. */
double lsdem_grid_eval(const lsdem_grid *g, const double p[3], double grad[3]);
/* lsdem_grid_eval of n points p[3m..3m+2] into phi[m], grad[3m..3m+2] (bit-identical
 * results), done back to back so that their cache misses overlap. */
void lsdem_grid_eval_many(const lsdem_grid *g, int n, const double *p, double *phi,
                          double *grad);
/* The 8 samples of one grid cell, kept by a caller between lookups (x fastest: 000,
 * 100, 010, 110, 001, 101, 011, 111; index = that of sample 000, -1 = none). */
typedef struct {
  int64_t index;
  float v[8];
} lsdem_grid_cell;
/* lsdem_grid_eval_many (bit-identical) whose samples come from cells[m] when it holds
 * the cell of p[m], and are otherwise read from the grid into cells[m]: a caller that
 * looks the same points up step after step keeps the samples near at hand. */
void lsdem_grid_eval_many_cached(const lsdem_grid *g, int n, const double *p, double *phi,
                                 double *grad, lsdem_grid_cell *cells);
/* Value only (same outside rule), for mass properties and checks. */
double lsdem_grid_value(const lsdem_grid *g, const double p[3]);
/* Raw trilinear gradient (not normalised) inside the grid; zero outside. For tests. */
void lsdem_grid_gradient_raw(const lsdem_grid *g, const double p[3], double grad[3]);
lsdem_status lsdem_grid_check(const lsdem_grid *g, lsdem_error *err); /* sizes, NaN */
/* A bound L on |grad phi| of the trilinear level set along any path on which
 * 0 <= phi <= L s, for every s with L s below the smallest sample on the grid's boundary
 * (0 if there is none: no bound). The gradient components of a cell are blends of its
 * edge differences, so max over cells with a corner >= 0 of
 * sqrt(sum over axes of (largest |edge difference| / h)^2) bounds it inside the box; the
 * outside rule (phi >= that smallest boundary sample) is never reached on such a path.
 * Returned as L, with the limit on L s in *reach_limit. */
double lsdem_grid_outer_lipschitz(const lsdem_grid *g, double *reach_limit);

/* ------------------------------------------------------- signed distances ---- */

typedef enum {
  LSDEM_SDF_GRID = 0,
  LSDEM_SDF_SPHERE,    /* a[0] = radius, centred at the origin */
  LSDEM_SDF_PLANE,     /* solid is z <= 0 (half-space), outward normal +z */
  LSDEM_SDF_CYLINDER,  /* a[0] = radius, a[1] = half-length along z (<=0: infinite) */
  LSDEM_SDF_BOX,       /* a[0..2] = half-extents */
  LSDEM_SDF_ELLIPSOID, /* a[0..2] = semi-axes along x, y, z (exact distance) */
  /* a[0..2] semi-axes, a[3] = e1 (north-south), a[4] = e2 (east-west) exponents, > 0:
   * the surface is F = (|x/a0|^(2/e2) + |y/a1|^(2/e2))^(e2/e1) + |z/a2|^(2/e1) = 1.
   * lsdem_sdf_eval gives the first-order distance (g - 1)/|grad g|, g = F^(e1/2) the
   * degree-1 gauge: exact zero set and normals, approximate magnitude away from the
   * surface (node seeding, checks). Its grid (lsdem_grid_sample) is a true SDF, built by
   * lsdem_grid_from_star. */
  LSDEM_SDF_SUPERELLIPSOID
} lsdem_sdf_kind;

/* Any shape behind one interface: phi(p) and its outward unit gradient, in the shape's
 * own frame. inverted != 0 swaps inside and outside (a cylindrical container, a box
 * of walls) by negating phi and grad. */
typedef struct {
  lsdem_sdf_kind kind;
  int inverted;
  double a[5];     /* shape parameters (per kind above); a[3], a[4] only for the
                      superellipsoid's exponents e1, e2 (libraries store a[0..2]) */
  lsdem_grid grid; /* used when kind == LSDEM_SDF_GRID */
} lsdem_sdf;

double lsdem_sdf_eval(const lsdem_sdf *s, const double p[3], double grad[3]);
/* lsdem_sdf_eval of n points p[3m..3m+2] into phi[m], grad[3m..3m+2], bit-identical, with
 * the kind dispatched once (grids: lsdem_grid_eval_many). */
void lsdem_sdf_eval_many(const lsdem_sdf *s, int n, const double *p, double *phi,
                         double *grad);
/* Radius of a sphere about the origin that contains the solid (HUGE_VAL if unbounded,
 * including every inverted SDF). For a grid it bounds the trilinear solid
 * {lsdem_grid_value < 0} (inside and outside the grid box); for a grid with positive
 * values on its border it over-estimates the solid's extent by at most 0.03 h (cells
 * refined by bisection). It scans all cells: compute it once per shape, not per contact. */
/* Lower-case name of a shape kind ("grid", "sphere", ...), for messages and listings. */
const char *lsdem_sdf_kind_name(lsdem_sdf_kind k);
double lsdem_sdf_bound_radius(const lsdem_sdf *s);

/* Sample an SDF onto a new grid covering [lo, hi] (shape frame) with spacing h, plus
 * `margin` extra samples on each side. Allocates g->phi (free with lsdem_grid_free). */
lsdem_status lsdem_grid_sample(const lsdem_sdf *s, const double lo[3], const double hi[3],
                               double h, int margin, lsdem_grid *g, lsdem_error *err);
void lsdem_grid_free(lsdem_grid *g); /* frees phi allocated by the core; phi = NULL */
/* Lay out a grid covering [lo, hi] with spacing h plus `margin` samples on each side
 * (the layout lsdem_grid_sample uses) and allocate its values, uninitialised; *values
 * is the writable view of g->phi. Free with lsdem_grid_free. */
lsdem_status lsdem_grid_alloc(const double lo[3], const double hi[3], double h, int margin,
                              lsdem_grid *g, float **values, lsdem_error *err);

/* -------------------------------------------------------- mass properties ---- */

typedef struct {
  double volume;
  double centroid[3];    /* in the grid's frame */
  double inertia[9];     /* about the centroid, grid frame, per unit density */
  double principal[3];   /* principal moments, ascending */
  double axes[9];        /* columns = principal axes in the grid frame (proper rotation) */
} lsdem_massprops;

/* Volume, centroid and inertia of {phi < 0}, integrating a smoothed Heaviside of
 * phi over each voxel with `sub` sub-samples per axis (1 = voxel centres). Voxels are
 * centred on the samples; sub-samples use a second-order Taylor model of phi about the
 * sample. Accuracy for a sphere at R/h = 10: volume 0.03% (sub 1), <0.01% (sub >= 2);
 * inertia +0.35% (sub 1), +0.11% (sub 2), +0.02% (sub 4). sub = 2 is a good default. */
lsdem_status lsdem_massprops_grid(const lsdem_grid *g, int sub, lsdem_massprops *mp,
                                  lsdem_error *err);

/* Re-express a grid shape in its principal frame (report §2.2.3): resample onto a new
 * grid whose axes are the principal axes and whose coordinates are relative to the
 * centroid, same spacing, keeping `margin` samples of positive phi around the solid.
 * Allocates out->phi. q_out receives the rotation principal -> original grid frame. */
lsdem_status lsdem_grid_to_principal(const lsdem_grid *in, const lsdem_massprops *mp, int margin,
                                     lsdem_grid *out, double q_out[4], lsdem_error *err);

/* ---------------------------------------------- star-shaped surfaces (surfsdf.c) ---- */

/* A solid that is star-shaped about the origin: its surface point in the unit direction u
 * is radius(u) * u, radius > 0 and finite. ctx is the shape's parameters. */
typedef double (*lsdem_radius_fn)(const double u[3], const void *ctx);

/* Radius function of an LSDEM_SDF_SUPERELLIPSOID (ctx: its const lsdem_sdf *):
 * 1 / g(u), g the degree-1 gauge of the superellipsoid (evaluated overflow-free). */
double lsdem_superellipsoid_radius(const double u[3], const void *sdf);

/* Volume, centroid and inertia (per unit density) of a star-shaped solid by quadrature
 * over directions: V = int r^3/3 dOmega, first moments int r^4/4 u dOmega, second moments
 * int r^5/5 u u^T dOmega (midpoint rule, n polar x 2n azimuthal cells; n = 256 gives
 * ~1e-5 relative for smooth shapes). Frame of the radius function. */
lsdem_status lsdem_star_massprops(lsdem_radius_fn radius, const void *ctx, int n,
                                  lsdem_massprops *mp, lsdem_error *err);
/* Bounding box of a star-shaped solid from a dense direction sampling, padded by 2% of
 * the largest radius (covers extremes between the sampled directions). */
lsdem_status lsdem_star_bounds(lsdem_radius_fn radius, const void *ctx, double lo[3],
                               double hi[3], lsdem_error *err);
/* Signed-distance grid of a star-shaped solid over [lo, hi] + margin (the layout of
 * lsdem_grid_sample). The surface is sampled on a latitude-longitude direction grid,
 * refined until neighbouring surface samples are at most h/3 apart; each sample carries
 * its outward normal (central differences of neighbouring samples) and stands for a disc
 * of radius rho = the largest neighbour distance. |phi| = distance to the nearest disc:
 * exact within 1.5 h of the surface (every sample visits its band), beyond by closest-point
 * propagation (8 octant sweeps over 7 upwind neighbours, twice). Against the exact
 * ellipsoid distance: 0.03 h within 2 h of the surface, 0.07 h anywhere (R/h = 10).
 * Sign from the star test |p| < radius(p/|p|) (far from the surface, from the nearest
 * disc's plane when p lies along its normal), so the inside is exact.
 * Allocates g->phi (lsdem_grid_free). */
lsdem_status lsdem_grid_from_star(lsdem_radius_fn radius, const void *ctx, const double lo[3],
                                  const double hi[3], double h, int margin, lsdem_grid *g,
                                  lsdem_error *err);

/* ------------------------------------------------------------ grain shapes ---- */

/* A grain template in its principal frame. Nodes are stored cluster by cluster:
 * cluster c owns nodes [cluster_start[c], cluster_start[c+1]) and a bounding sphere
 * (cluster_sphere[4c..4c+2] centre, [4c+3] radius), so a whole cluster can be skipped
 * with one distance test. */
typedef struct {
  lsdem_sdf sdf;
  int nnodes;
  const double *nodes;      /* 3*nnodes, principal frame */
  const double *node_area;  /* nnodes: surface area represented by each node */
  int nclusters;
  const int *cluster_start; /* nclusters+1 */
  const double *cluster_sphere; /* 4*nclusters */
  double radius;            /* bounding radius: max |node| and the solid's extent */
  double volume;            /* per unit density = mass at density 1 */
  double inertia[3];        /* principal moments per unit density */
} lsdem_shape;

/* Build node clusters of about `target` nodes each by spatial bisection. Reorders
 * nodes (and areas) in place; cluster_start must hold nnodes+1 ints and
 * cluster_sphere 4*nnodes doubles (worst case); returns the cluster count. */
int lsdem_nodes_cluster(int nnodes, double *nodes, double *area, int target,
                        int *cluster_start, double *cluster_sphere);
/* Cluster size used by the importers (lsdem_morph_to_shape, lsdem-shape). */
#define LSDEM_CLUSTER_TARGET 16

/* Seed about target_count evenly spread surface nodes on the zero level set of a
 * bounded SDF (grid or analytic), in the SDF's frame. Dense candidates (a jittered
 * lattice inside the bounding box, ~40 per requested node) are projected onto phi = 0 by
 * Newton steps p -= phi grad and kept when |phi| is tiny; farthest-point sampling then
 * picks the nodes, so spacing is even, independent of corners or grid artefacts.
 * area[k] = (surface area) * (fraction of candidates whose nearest node is k): a
 * Voronoi-like share that sums to the estimated total area. nodes holds 3*target_count
 * doubles, area target_count; *count receives the number written (== target_count
 * unless the surface yielded fewer candidates). Deterministic for a given seed. */
lsdem_status lsdem_nodes_seed(const lsdem_sdf *s, int target_count, uint64_t seed,
                              double *nodes, double *area, int *count, lsdem_error *err);

/* Surface area of the zero level set of a grid: integral of delta_eps(phi) |grad phi|
 * over the grid with a smoothed delta of half-width one spacing (voxel-centre rule). */
double lsdem_surface_area_grid(const lsdem_grid *g);

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

/* ---------------------------------------------------------------- integrator ---- */

/* Centred-difference translation with global damping xi (report eqs 2.18-2.19):
 * v <- [(1 - xi dt/2) v + dt f / m] / (1 + xi dt/2);  x <- x + dt v. */
void lsdem_step_translation(double x[3], double v[3], const double f[3], double mass,
                            double xi, double dt);

/* Predictor-corrector Euler equations in the principal frame (report eqs 2.21-2.25).
 * omega: body-frame angular velocity at n-1/2, updated to n+1/2.
 * dw_prev: the previous step's corrector increment (Delta omega^{n-1}), updated.
 * torque: body-frame torque at n. inertia: principal moments. */
void lsdem_step_rotation(double omega[3], double dw_prev[3], const double torque[3],
                         const double inertia[3], double xi, double dt);
/* Note on eq 2.25: the printed "1/2" is not applied; omega^{n+1/2} = omega^{n-1/2} +
 * Delta omega^n (the full corrector increment), so that a constant torque about a
 * principal axis gives omega = M t / I. Start a body with dw_prev = 0. */

/* One whole rigid-body step from world-frame force and torque at step n:
 *   x, v   world; x at n -> n+1, v at n-1/2 -> n+1/2 (eqs 2.18-2.19);
 *   q      body -> world orientation, n -> n+1 (lsdem_quat_advance with omega_body
 *          at n+1/2);
 *   omega_body, dw_prev   body-frame state for lsdem_step_rotation (n-1/2 -> n+1/2);
 *          the torque is taken to the body frame with q at n;
 *   omega_world (out)     R(q^{n+1}) omega_body^{n+1/2}, for the contact kernel.
 * A caller starting from a world angular velocity w sets omega_body = R(q)^T w and
 * dw_prev = 0. Per-grain state to keep (and migrate/restart): x, v, q, omega_body,
 * dw_prev. */
void lsdem_step_body(double x[3], double v[3], double q[4], double omega_body[3],
                     double dw_prev[3], const double force[3], const double torque[3],
                     double mass, const double inertia[3], double xi, double dt,
                     double omega_world[3]);

/* Kinetic energy of a rigid body: translational and rotational parts. */
double lsdem_kinetic_translational(double mass, const double v[3]);
double lsdem_kinetic_rotational(const double inertia[3], const double omega_body[3]);

/* Pivoting platen (report §3.2.1): a rigid plate that may rotate about a pivot point P
 * (the ram's ball joint) with the two rotational degrees of freedom perpendicular to the
 * unit ram axis a (no spin about a), scalar moment of inertia I about P, viscous
 * damping torque -c omega. All vectors world frame. */
/* Torque about point p of a force f whose torque about point o is t_o:
 * t_p = t_o + (o - p) x f. */
void lsdem_torque_about(const double t_o[3], const double o[3], const double f[3],
                        const double p[3], double t_p[3]);
/* One centred-difference step (eqs 2.18-2.19 with mass I and xi = c / I): the
 * torque about P at step n with its component along a removed drives omega (world,
 * n-1/2 -> n+1/2, kept perpendicular to a); q (plate body -> world) is advanced from n
 * to n+1 by omega over dt (eq 2.28). */
void lsdem_step_pivot(double q[4], double omega[3], const double torque_p[3],
                      const double axis[3], double inertia, double damping, double dt);
/* Pose of a plate whose frame is q, whose reference point sits at h along the plate's
 * body z axis from the pivot P (x = P + h R(q) e_z), with P moving at v_p and the plate
 * turning at omega about P: pose->v = v_p + omega x (x - P). */
void lsdem_pivot_pose(const double pivot[3], const double v_p[3], const double q[4],
                      const double omega[3], double h, lsdem_pose *pose);
/* Tilt of the plate: the angle (radians, [0, pi]) between unit vectors n and a, as
 * atan2(|n x a|, n . a) (accurate for small angles, unlike acos). */
double lsdem_tilt_angle(const double n[3], const double a[3]);

/* ---------------------------------------------------------- shape library ---- */

/* A read-only, memory-mapped library of shapes (format in doc/shape_library.rst).
 * All pointers in the shapes point into the mapping; ranks on one node share one copy
 * through the page cache. */
typedef struct lsdem_library lsdem_library;

lsdem_status lsdem_library_open(const char *path, lsdem_library **lib, lsdem_error *err);
void lsdem_library_close(lsdem_library *lib);
int lsdem_library_count(const lsdem_library *lib);
const lsdem_shape *lsdem_library_shape(const lsdem_library *lib, int index);
const char *lsdem_library_name(const lsdem_library *lib, int index); /* may be "" */

/* Limits of the format (checked by the writer and by open). */
#define LSDEM_LIBRARY_NAME_MAX 128            /* name bytes including the NUL */
#define LSDEM_LIBRARY_MAX_SHAPES 16777216     /* 2^24 shapes */
#define LSDEM_LIBRARY_MAX_NODES 67108864      /* 2^26 nodes per shape */
#define LSDEM_LIBRARY_MAX_SAMPLES 2147483647u /* grid samples per shape (int index) */

/* Open checks the header, the header/TOC checksum, every offset and length and the
 * cluster tables, but reads no grid. This checks shape `index` (-1: all shapes): its
 * section checksum, and that its nodes, areas, cluster spheres and grid are finite.
 * LSDEM_ERR_FORMAT on a checksum mismatch, LSDEM_ERR_NUMERIC on NaN/inf. */
lsdem_status lsdem_library_verify(const lsdem_library *lib, int index, lsdem_error *err);

/* Write shapes (grid SDF or analytic) to a library file. names may be NULL. */
lsdem_status lsdem_library_write(const char *path, const lsdem_shape *shapes,
                                 const char *const *names, int count, lsdem_error *err);

/* ---------------------------------------------- Kawamoto/Tan morphology files ---- */

/* One morph_<i>.dat file: 8 lines (see doc/morphology_format.rst). Voxel units, grid
 * spacing 1, cm_grid = centroid in grid-index coordinates. Allocates; free with
 * lsdem_morph_free. */
typedef struct {
  double mass;          /* line 1: volume in voxel^3 (density-1 mass) */
  double inertia[3];    /* line 2: principal moments, density 1 */
  double cm_grid[3];    /* line 3 */
  int nnodes;           /* line 4 */
  double *nodes;        /* line 5: 3*nnodes, relative to the centroid, principal frame */
  double radius;        /* line 6 */
  int n[3];             /* line 7 */
  float *phi;           /* line 8: n[0]*n[1]*n[2] values, x fastest */
} lsdem_morph;

/* Reader limits: larger files are rejected with LSDEM_ERR_FORMAT before allocating. */
#define LSDEM_MORPH_MAX_SAMPLES 134217728 /* 512^3 grid values */
#define LSDEM_MORPH_MAX_NODES 16777216    /* nodes on line 4 */
#define LSDEM_MORPH_MAX_ROWS 100000000    /* rows of a positions/rotations file */

/* Errors name the file and the line (1..8): LSDEM_ERR_FORMAT for a truncated file, a
 * token that is not a number, a wrong value count on a line (e.g. line 5 against the
 * node count of line 4), grid dims < 2 or above the cap; LSDEM_ERR_NUMERIC for NaN/inf,
 * mass or a principal moment <= 0. On error *m is left empty. */
lsdem_status lsdem_morph_read(const char *path, lsdem_morph *m, lsdem_error *err);
lsdem_status lsdem_morph_write(const char *path, const lsdem_morph *m, lsdem_error *err);
void lsdem_morph_free(lsdem_morph *m);
/* View a morphology as a shape: grid origin = -cm_grid, spacing 1. Nodes and areas are
 * copied into caller storage sized by the morph's node count; clusters likewise.
 * The shape borrows m->phi. */
lsdem_status lsdem_morph_to_shape(const lsdem_morph *m, double *nodes, double *area,
                                  int *cluster_start, double *cluster_sphere,
                                  lsdem_shape *s, lsdem_error *err);

/* positions_*.dat (x y z per line) and rotations_*.dat (q0 q1 q2 q3 per line, Tan's
 * order). Allocate *out (3*n or 4*n doubles, caller frees with free()). */
lsdem_status lsdem_read_positions(const char *path, double **out, int *n, lsdem_error *err);
lsdem_status lsdem_read_rotations(const char *path, double **out, int *n, lsdem_error *err);

/* ------------------------------------------------ building and checking shapes ---- */

/* A library shape together with the storage it owns (shapebuild.c). */
typedef struct {
  lsdem_shape shape;
  double *nodes, *area, *cluster_sphere;
  int *cluster_start;
  float *phi; /* grid values owned by this shape (NULL for an analytic SDF) */
} lsdem_built_shape;

/* Make a library shape from an SDF given in its principal frame (centroid at the origin,
 * axes along the principal axes): about `nnodes` surface nodes (lsdem_nodes_seed with
 * `seed`), clustered (LSDEM_CLUSTER_TARGET), bounding radius. For a grid SDF the volume
 * and principal moments come from lsdem_massprops_grid (sub 2) and the grid values
 * (allocated by the core) are taken over: they belong to *out from the call on, also on
 * failure. For an analytic SDF the caller sets out->shape.volume and .inertia.
 * nnodes <= 0 asks for a count from a spacing (grids only): ceil(area / spacing^2),
 * area = lsdem_surface_area_grid, with spacing = node_spacing if > 0, otherwise
 * LSDEM_AUTO_NODE_SPACING * d (d the equivalent-sphere diameter): just inside the d/10
 * the report uses at most (LSDEM_CHECK_SPARSE_NODES). */
#define LSDEM_AUTO_NODE_SPACING 0.09
lsdem_status lsdem_shape_build(const lsdem_sdf *sdf, int nnodes, double node_spacing,
                               uint64_t seed, lsdem_built_shape *out, lsdem_error *err);
void lsdem_built_shape_free(lsdem_built_shape *b);

/* Quality checks every shape source runs (issue 4): warnings are bits of `warnings`. */
enum {
  LSDEM_CHECK_COARSE_GRID = 1,    /* grid spacing h > R/10, R equivalent-sphere radius */
  LSDEM_CHECK_SPARSE_NODES = 2,   /* mean node spacing sqrt(area/N) > d/10, d = 2R */
  LSDEM_CHECK_OPEN_LEVEL_SET = 4, /* a negative sample on the grid border */
  LSDEM_CHECK_VOLUME = 8,         /* node (divergence-theorem) volume vs shape volume */
  LSDEM_CHECK_INERTIA = 16        /* node moments vs shape moments */
};
#define LSDEM_CHECK_VOLUME_TOL 0.03  /* relative, for LSDEM_CHECK_VOLUME */
#define LSDEM_CHECK_INERTIA_TOL 0.05 /* relative, largest of the three moments' errors */

typedef struct {
  double h;              /* grid spacing (0 for an analytic SDF) */
  double radius_eq;      /* (3 V / 4 pi)^(1/3) */
  double node_spacing;   /* sqrt(sum of node areas / nnodes) */
  double volume_nodes;   /* (1/3) sum_k a_k x_k . n_k (divergence theorem) */
  double inertia_nodes[3]; /* from (1/5) sum_k a_k x_i x_j (x_k . n_k), principal frame */
  double volume_error;   /* volume_nodes / volume - 1 */
  double inertia_error;  /* max_i |inertia_nodes[i] / inertia[i] - 1| */
  long border_negative;  /* negative grid samples on the grid's border faces */
  int warnings;          /* LSDEM_CHECK_* bits */
} lsdem_shape_report;

/* Run the checks on a finished shape (normals from its SDF at the nodes). Returns
 * LSDEM_ERR_ARG for a shape without nodes or volume; warnings are not errors. */
lsdem_status lsdem_shape_check(const lsdem_shape *s, lsdem_shape_report *r, lsdem_error *err);
/* One line of text per warning (each ending in '\n') into buf; returns the length that
 * was needed (like snprintf). "" when there is no warning. */
size_t lsdem_shape_report_text(const lsdem_shape_report *r, char *buf, size_t size);

/* ------------------------------------------------------------ label images ---- */

/* A labelled 3-D image: one label per voxel, x fastest, then y, then z. Label <= 0 is
 * background. Voxel (i,j,k) has its centre at voxel_size * (i,j,k) in scan coordinates. */
typedef struct {
  int n[3];
  int32_t *label; /* n[0]*n[1]*n[2], allocated by the reader */
} lsdem_label_image;

typedef enum { LSDEM_VOXEL_U8 = 0, LSDEM_VOXEL_U16, LSDEM_VOXEL_U32, LSDEM_VOXEL_I32 } lsdem_voxel_type;

#define LSDEM_IMAGE_MAX_VOXELS 1073741824L /* 1024^3 voxels */
#define LSDEM_IMAGE_MAX_PAGES 65536        /* TIFF pages (z slices) */

/* Raw binary labels, no header: exactly n[0]*n[1]*n[2] values of `type`. The file size
 * must match (a mismatch is reported with both sizes); u32 values above INT32_MAX are
 * rejected. */
lsdem_status lsdem_image_read_raw(const char *path, const int n[3], lsdem_voxel_type type,
                                  int big_endian, lsdem_label_image *img, lsdem_error *err);
/* Multi-page TIFF, one page per z slice (baseline: uncompressed, one sample per pixel,
 * 8/16/32-bit unsigned integer, strips, both byte orders). All pages must have the same
 * size. Compressed, tiled, multi-sample, float or signed pages are rejected naming the
 * tag; every offset is bounds-checked and IFD chains that loop or exceed
 * LSDEM_IMAGE_MAX_PAGES are rejected. */
lsdem_status lsdem_image_read_tiff(const char *path, lsdem_label_image *img, lsdem_error *err);
/* 1 if the file starts with a TIFF signature ("II*\0" or "MM\0*"), else 0. */
int lsdem_image_is_tiff(const char *path);
void lsdem_label_image_free(lsdem_label_image *img);

/* ------------------------------------------------------ grains from voxels ---- */

typedef struct {
  double voxel_size; /* s: length of a voxel edge */
  long min_voxels;   /* labels with fewer voxels are dropped (counted) */
  int smooth;        /* iterations of a [1 2 1]/4 filter on phi near the surface (0: none) */
  int margin;        /* positive samples kept around each grain (>= 1) */
} lsdem_voxel_options;

/* One label's grain: its level set in its principal frame and its pose in the scan. */
typedef struct {
  int32_t label;
  long nvoxels;
  lsdem_grid grid;    /* principal frame, spacing voxel_size; phi owned by the core */
  double position[3]; /* centroid in scan coordinates (voxel index * voxel_size) */
  double quat[4];     /* rotation principal -> scan frame */
} lsdem_voxel_grain;

#define LSDEM_VOXEL_MAX_LABEL 16777215 /* largest label value accepted */

/* The signed distance of one label in scan coordinates over its bounding box plus pad
 * voxels: exact squared Euclidean distance transforms (Felzenszwalb-Huttenlocher,
 * separable, O(n)) of the label and of its complement, phi = d_out - 1/2 outside and
 * 1/2 - d_in inside (the surface midway between label and non-label voxel centres),
 * scaled by the voxel size; other labels count as outside. Then `smooth` iterations of a
 * separable [1 2 1]/4 filter where |phi| < 3 voxels, renormalised by |grad phi| and
 * shifted by a constant to restore the unsmoothed volume (smoothing shrinks convex
 * parts). lo/hi: inclusive voxel bounding box of the label; the grid has `pad` samples
 * around it, origin voxel_size * (lo - pad). */
lsdem_status lsdem_voxel_label_sdf(const lsdem_label_image *img, int32_t label,
                                   const int lo[3], const int hi[3], int pad,
                                   const lsdem_voxel_options *o, lsdem_grid *g,
                                   lsdem_error *err);
/* Every label with >= min_voxels voxels as a grain (ascending label order): SDF above
 * (pad margin + 1), mass properties (sub 2), re-expressed in its principal frame
 * (lsdem_grid_to_principal) with its scan pose kept; the principal grid is shifted by a
 * constant to the scan grid's volume (trilinear resampling shrinks convex parts by
 * ~h^2 kappa / 8). Accuracy for a sphere 20 voxels across: volume and moments within
 * 0.1%, zero level within 0.32 voxel of the true surface (0.17 with smooth 2).
 * Allocates *grains (free with lsdem_voxel_grains_free); *dropped = labels below
 * min_voxels. */
lsdem_status lsdem_voxel_grains(const lsdem_label_image *img, const lsdem_voxel_options *o,
                                lsdem_voxel_grain **grains, int *count, int *dropped,
                                lsdem_error *err);
void lsdem_voxel_grains_free(lsdem_voxel_grain *grains, int count);

/* ------------------------------------------------------------ triangle meshes ---- */

/* A triangle mesh with shared vertices (STL vertices are welded on exact equality). */
typedef struct {
  int nverts, ntris;
  double *verts; /* 3*nverts */
  int *tris;     /* 3*ntris vertex indices, counter-clockwise seen from outside */
} lsdem_mesh;

#define LSDEM_MESH_MAX_TRIS 16777216 /* triangles per mesh */

/* STL (ASCII or binary, detected from the content: a binary file's size is
 * 84 + 50 * count) or Wavefront OBJ (v and f lines; polygons fan-triangulated,
 * negative indices relative). The format comes from the extension (.stl / .obj, any
 * case), otherwise from the content. Errors name the file and the line or triangle. */
lsdem_status lsdem_mesh_read(const char *path, lsdem_mesh *m, lsdem_error *err);
void lsdem_mesh_free(lsdem_mesh *m);

typedef struct {
  int boundary_edges;     /* edges used by one triangle */
  int nonmanifold_edges;  /* edges used by more than two */
  int misoriented_edges;  /* edges whose two triangles traverse them the same way */
  int degenerate_tris;    /* zero-area triangles or repeated vertices */
  double where[3];        /* midpoint of the first bad edge / triangle */
} lsdem_mesh_topology;

/* Closedness: every edge shared by exactly two triangles with opposite orientation.
 * LSDEM_ERR_FORMAT with a message giving the counts and an example location otherwise
 * (topo, if not NULL, is filled either way). */
lsdem_status lsdem_mesh_check_closed(const lsdem_mesh *m, lsdem_mesh_topology *topo,
                                     lsdem_error *err);
/* Self-intersection of non-adjacent triangles (no shared vertex), accelerated by a
 * uniform grid; LSDEM_ERR_FORMAT naming the first intersecting pair. *pair (if not
 * NULL) receives the two triangle indices, -1 -1 when none. */
lsdem_status lsdem_mesh_check_self_intersection(const lsdem_mesh *m, int pair[2],
                                                lsdem_error *err);
/* Signed distance to the mesh sampled on a grid covering its bounding box with spacing h
 * and `margin` extra samples, mesh frame. Within 2h of the mesh: exact distance to the
 * closest triangle (each triangle visits the samples near its bounding box), signed by
 * the angle-weighted pseudonormal of the closest feature (Baerentzen & Aanaes 2005;
 * needs a closed, consistently oriented mesh). Farther: the closest triangle propagated
 * from neighbouring samples (Bridson's sweeps; error well below h, e.g. 0.06 h at the
 * centre of a 5120-triangle sphere at R = 10h) and the sign of the band region the
 * sample's 6-connected region touches. O(samples + triangles * (size/h + 5)^3). */
lsdem_status lsdem_mesh_sdf_grid(const lsdem_mesh *m, double h, int margin, lsdem_grid *g,
                                 lsdem_error *err);
/* Signed volume of the closed mesh (sum of signed tetrahedra; > 0 when outward). */
double lsdem_mesh_volume(const lsdem_mesh *m);

/* ------------------------------------------- surface meshes and pictures ---- */

/* The zero level set of a bounded SDF as a closed, outward-oriented triangle mesh
 * (lsdem_mesh above) in the SDF's frame (marching tetrahedra on a lattice: surface.c).
 * Lattice spacing h; h <= 0 means the grid's own samples for a grid SDF, bound radius / 20
 * for an analytic one.
 * Vertices are shared between triangles (the mesh is watertight: every edge has two
 * triangles). Allocates m; free with lsdem_mesh_free. LSDEM_ERR_ARG for unbounded SDFs. */
lsdem_status lsdem_mesh_extract(const lsdem_sdf *s, double h, lsdem_mesh *m, lsdem_error *err);
double lsdem_mesh_area(const lsdem_mesh *m);
/* Legacy VTK polydata (ASCII) and PLY (ASCII). */
lsdem_status lsdem_mesh_write_vtk(const char *path, const lsdem_mesh *m, lsdem_error *err);
lsdem_status lsdem_mesh_write_ply(const char *path, const lsdem_mesh *m, lsdem_error *err);

/* One posed grain of a picture. */
typedef struct {
  int shape;    /* index into the shapes array */
  int64_t id;   /* grain id: picks the colour */
  double x[3];  /* centroid, world */
  double q[4];  /* body -> world, unit length */
} lsdem_render_grain;

/* Orthographic camera looking along `view`; `up` is the world direction shown upwards
 * (projected; must not be parallel to view). Image right = view x up. pixel > 0 fixes
 * the frame: world point `centre` at the image centre, pixel = world length per pixel;
 * pixel <= 0 fits the grains' bounding spheres with a 5% margin (centre ignored). */
typedef struct {
  int width, height;
  double view[3], up[3];
  double centre[3], pixel;
  int colour_by_shape; /* 0: colour by a hash of the grain id, 1: by shape index */
} lsdem_render_view;

/* Value of all three channels of pixels that see no grain; grain pixels never have it. */
#define LSDEM_RENDER_BACKGROUND 255

/* Ray-march the grains' level sets (render.c): per pixel, bounding spheres from a
 * screen-space bin grid, then sphere tracing in each grain's frame, Lambert + ambient
 * shading with the level-set normal. rgb receives width*height*3 bytes, row 0 at the top.
 * Shapes must be bounded (finite radius). Deterministic. */
lsdem_status lsdem_render(const lsdem_shape *const *shapes, int nshapes,
                          const lsdem_render_grain *grains, int ngrains,
                          const lsdem_render_view *view, unsigned char *rgb, lsdem_error *err);
/* An 8-bit RGB PNG (rows top first), compressed by the core's own deflate (fixed Huffman
 * codes, LZ77): no compression library needed. */
lsdem_status lsdem_png_write(const char *path, int width, int height, const unsigned char *rgb,
                             lsdem_error *err);

/* ------------------------------------------------- random grains (randgrain.c) ---- */

/* splitmix64 (Steele, Lea, Flood 2014): the generators' reproducible random stream. */
uint64_t lsdem_splitmix64(uint64_t *state);
double lsdem_uniform01(uint64_t *state); /* uniform in (0, 1] */
/* A uniformly distributed random rotation (Shoemake 1992) from the stream (packing.c). */
void lsdem_random_quat(uint64_t *state, double q[4]);

/* Real orthonormal spherical harmonics Y_lm(u) for l = 0..L, m = -l..l, at index
 * l*l + l + m (Condon-Shortley phase dropped; m > 0 ~ cos(m phi), m < 0 ~ sin(|m| phi)).
 * Sum_m Y_lm^2 = (2l+1)/(4 pi) (addition theorem). u is a unit vector. */
void lsdem_sph_harmonics(int L, const double u[3], const double *table, double *Y);
/* The recurrence factors for lsdem_sph_harmonics (table: (L+1)^2 doubles, or NULL to
 * compute them on the fly): saves the square roots when evaluating many directions. */
void lsdem_sph_harmonics_table(int L, double *table);

#define LSDEM_RANDGRAIN_LMAX 16      /* highest degree of the random radius */
#define LSDEM_RANDGRAIN_FORM_LMAX 7  /* degrees 2..7: form and angularity; 8..LMAX: roughness */

typedef struct {
  double size;       /* equivalent-sphere diameter (volume = pi size^3 / 6) */
  double elongation; /* Zingg I/L in (0, 1] (equivalent-ellipsoid axes, from inertia) */
  double flatness;   /* Zingg S/I in (0, 1] */
  double angularity; /* RMS of ln(r/R0) from degrees 2..FORM_LMAX (e.g. 0.1) */
  double roughness;  /* RMS of ln(r/R0) from degrees FORM_LMAX+1..LMAX (e.g. 0.02) */
  uint64_t seed;
} lsdem_randgrain_params;

/* A random sand-like grain, star-shaped about its generation centre (the origin of its
 * radius function): r(v) = rs(u) / |T^-1 v|, u = T^-1 v / |T^-1 v|, where
 * rs(u) = exp(sum_{l=2..LMAX} sum_m a_lm Y_lm(u)) (exp keeps r > 0: star-shaped always;
 * equal to 1 + sum to first order), a_lm ~ N(0, sigma_l^2) with per-degree variance
 * (2l+1) sigma_l^2 / (4 pi) proportional to l^-2 inside each band, normalised to the band's
 * RMS (angularity or roughness). T = k diag(1, EL, EL*FL) W, W = Mc^(-1/2) the inverse
 * square root of rs's central second-moment tensor: the affine map makes the grain's
 * central second moments proportional to diag(1, EL^2, (EL FL)^2), so elongation and
 * flatness of its inertia-equivalent ellipsoid are exactly the requested ones; k sets
 * the volume. Deterministic for a seed (splitmix64 + Box-Muller). */
typedef struct {
  double coef[(LSDEM_RANDGRAIN_LMAX + 1) * (LSDEM_RANDGRAIN_LMAX + 1)]; /* a_lm */
  double T[9], Tinv[9]; /* the affine map and its inverse (row-major) */
  double table[(LSDEM_RANDGRAIN_LMAX + 1) * (LSDEM_RANDGRAIN_LMAX + 1)]; /* harmonics' factors */
} lsdem_randgrain;

lsdem_status lsdem_randgrain_make(const lsdem_randgrain_params *p, lsdem_randgrain *g,
                                  lsdem_error *err);
/* Radius function of the grain (an lsdem_radius_fn; ctx: const lsdem_randgrain *). */
double lsdem_randgrain_radius(const double v[3], const void *grain);
/* The grain's signed-distance grid in its principal frame (lsdem_grid_from_star, then
 * lsdem_massprops_grid + lsdem_grid_to_principal), spacing h, margin samples. centre
 * (may be NULL) receives the generation centre in the principal frame: the point the
 * grain is star-shaped about. Allocates out->phi. */
lsdem_status lsdem_randgrain_grid(const lsdem_randgrain *g, double h, int margin,
                                  lsdem_grid *out, double centre[3], lsdem_error *err);

/* Shape statistics from volume, principal moments (ascending) and surface area:
 * inertia-equivalent ellipsoid semi-axes L >= I >= S (a_k^2 = 5 (I_j + I_l - I_k) / (2V)),
 * elongation I/L, flatness S/I, Wadell sphericity pi^(1/3) (6V)^(2/3) / area,
 * equivalent-sphere diameter (6V/pi)^(1/3). */
typedef struct {
  double d_eq, axes[3], elongation, flatness, sphericity;
} lsdem_shape_stats;
void lsdem_shape_stats_compute(double volume, const double inertia[3], double area,
                               lsdem_shape_stats *st);

/* ------------------------------------------------------- packing (packing.c) ---- */

typedef enum { LSDEM_CONTAINER_BOX = 0, LSDEM_CONTAINER_CYLINDER = 1 } lsdem_container_kind;

/* Box: [0, size[0]] x [0, size[1]] x [0, size[2]]. Cylinder: axis z through x = y = 0,
 * radius size[0], 0 <= z <= size[1]. */
typedef struct {
  lsdem_container_kind kind;
  double size[3];
} lsdem_container;

double lsdem_container_volume(const lsdem_container *c);

typedef struct {
  int count;            /* grains wanted */
  double gap;           /* clearance: every node pushed out by gap along its normal must
                           stay outside the other grains and the walls (so the distance
                           between grains is about gap, at least ~gap cos(normal angle)) */
  long max_tries;       /* placement attempts per grain before it is skipped */
  uint64_t seed;
  const double *weights; /* per shape, relative (NULL: uniform) */
} lsdem_pack_params;

typedef struct {
  int shape;     /* 0-based index into the shapes */
  double x[3];   /* centroid, world */
  double q[4];   /* orientation, principal -> world, scalar-first */
} lsdem_placed;

/* Random sequential addition (packing.c): the N shape choices are drawn first (weights),
 * then placed largest bounding radius first, each at uniform random positions inside the
 * container and uniform random orientations (Shoemake) until it fits or max_tries is
 * used up (then it is skipped). Fit test: a cell list of placed grains and bounding
 * spheres first, then the contact kernel (lsdem_contact_nodes) in both directions -- any
 * node of one (pushed out by gap) inside the other's level set is an overlap -- and
 * against the walls (planes; an inverted cylinder). out holds p->count entries;
 * *placed receives how many were placed (<= count), in placement order. RSA saturates
 * at low solid fractions (~0.2-0.3, less near walls): it makes a loose, overlap-free
 * sample to settle or compact in LAMMPS. */
lsdem_status lsdem_pack(const lsdem_shape *shapes, int nshapes, const lsdem_container *c,
                        const lsdem_pack_params *p, lsdem_placed *out, int *placed,
                        lsdem_error *err);
/* 1 if grains a and b (poses from placed entries) overlap by the kernel test with
 * clearance gap, else 0 (the generator's test, for re-checks). */
int lsdem_pack_overlap(const lsdem_shape *sa, const lsdem_placed *a, const lsdem_shape *sb,
                       const lsdem_placed *b, double gap);
/* 1 if a grain crosses the container walls (its nodes pushed out by gap), else 0. */
int lsdem_pack_outside(const lsdem_shape *s, const lsdem_placed *a, const lsdem_container *c,
                       double gap);
/* The container's bounding box (for a data file's box). */
void lsdem_container_bounds(const lsdem_container *c, double lo[3], double hi[3]);

/* ------------------------------------------- specimen measurements (measure.c) ---- */

/* Sign convention: stresses and strains are COMPRESSION POSITIVE (soil mechanics):
 * p > 0 under confinement, axial strain ln(L0/L) > 0 when the specimen shortens,
 * volumetric strain ln(V0/V) > 0 when it contracts. Tensors are 3x3 row-major double[9]. */

/* Love-Weber average stress (report eq 3.6), accumulated per grain: M += f (x) (x_c - x_g),
 * M_ij += f_i (x_c - x_g)_j, with f a contact force ON the grain (world), x_c the contact
 * point, x_g the grain's centroid (for a periodic image, the image nearest x_c). Sum every
 * contact of every grain of the set: a grain-grain contact enters once per grain (opposite
 * forces, the branch vector of each side), a wall, platen or membrane contact once. The
 * report writes x^c from the origin; for a grain in equilibrium (sum f = 0) both agree, and
 * this form is origin-independent also for boundary contacts and unbalanced grains. */
void lsdem_love_weber_add(double M[9], const double f[3], const double point[3],
                          const double centre[3]);
/* sigma = -sym(M) / volume (compression positive; volume = the specimen's, voids included). */
void lsdem_love_weber_stress(const double M[9], double volume, double sigma[9]);
double lsdem_stress_mean(const double sigma[9]);       /* p = tr(sigma) / 3 (eq 3.7) */
double lsdem_stress_deviatoric(const double sigma[9]); /* q = sqrt(3/2 s:s) (eq 3.8) */
/* Principal stresses, descending: s[0] = sigma_1 (major) >= s[1] >= s[2] = sigma_3. */
void lsdem_stress_principal(const double sigma[9], double s[3]);
/* A symmetric tensor's six components in LAMMPS order: xx yy zz xy xz yz. */
void lsdem_sym_to_voigt(const double T[9], double out[6]);
/* Mobilised friction angle (eq 3.9), radians: asin((s1 - s3) / (s1 + s3)); 0 if s1 + s3 <= 0. */
double lsdem_friction_angle(double s1, double s3);
/* Dilatancy angle (eq 3.10, Schanz & Vermeer 1996 for triaxial compression), radians,
 * from increments of volumetric and axial strain (compression positive):
 * sin(psi) = -x / (2 - x), x = deps_v / deps_a; psi > 0 for dilation. 0 if deps_a == 0;
 * -pi/2 for x >= 1 (the radius shrinks as well: outside the formula's range).
 * (The report prints (x/2)/(2 - x/2); we use the published Schanz-Vermeer form.) */
double lsdem_dilatancy_angle(double deps_v, double deps_a);
/* Inertial number (eq 3.5): |strain_rate| d / sqrt(pressure / density); d = mean equivalent
 * grain diameter. HUGE_VAL if pressure or density <= 0. Quasi-static when < 1e-3. */
double lsdem_inertial_number(double strain_rate, double d, double pressure, double density);

/* Long axis of a grain (report §3.5.4): the principal axis of its smallest principal moment,
 * in the world frame (q: body -> world). Sign arbitrary. */
void lsdem_long_axis(const double q[4], const double inertia[3], double n[3]);
/* Fabric of unit vectors: F += n (x) n (divide by the count for <n (x) n>). */
void lsdem_fabric_add(double F[9], const double n[3]);
/* Deviatoric fabric tensor of the second kind (Kanatani 1984): D = 15/2 (F/count - I/3);
 * the orientation density is then (1 + D : n n) / (4 pi) to second order. Zero if count <= 0. */
void lsdem_fabric_deviator(const double F[9], double count, double D[9]);
/* Anisotropy factor a = sqrt(3/2 D : D) (Zhao & Guo 2013; Wiebicke et al. 2020): 0 for an
 * isotropic set, 15/2 when every axis is parallel. */
double lsdem_fabric_anisotropy(const double D[9]);
/* Rotation angle in [0, pi] of q relative to a reference orientation qref (angle of
 * q qref^-1), for the rotated-grain shear-band indicator (report §3.5.3). */
double lsdem_rotation_angle(const double q[4], const double qref[4]);

/* ------------------------------------------- flexible membrane (membrane.c) ---- */

/* The triaxial test's membrane (report §2.3.5, §3.3.2): two layers of bonded spheres on
 * coaxial cylinders (axis parallel to z through centre[0..1]), each a triangular
 * ("hexagonal") lattice: rings of nper spheres, alternate rings offset by half a step.
 *  - Inner layer: spheres of radius rb whose centres lie on radius R = Rs + rb, so they
 *    touch a specimen of radius Rs. nper = round(pi / asin(rb / R)) (in-ring chord ~2 rb);
 *    nrings rings from z0 to z0 + H (end rings exactly at z0 and z0 + H; ring spacing
 *    H / (nrings - 1) ~ chord * sqrt(3)/2).
 *  - Outer layer: spheres of radius outer_factor * rb, one over each "up" hole of the
 *    inner lattice (triangle with two vertices on ring m, apex on ring m+1), i.e. nrings-1
 *    rings of nper at z = z_m + dz/3, on the radius where an outer sphere touches the
 *    nearest of the three inner spheres around its hole. The up-hole centroids form a
 *    translated copy of the lattice, so the outer layer is a hexagonal lattice too.
 *  - Bonds: the in-layer lattice edges (interior spheres have 6) and, between layers,
 *    each outer sphere to the three inner spheres around its hole, so the outer layer
 *    stays registered over the holes it covers (the membrane is frictionless: without
 *    these bonds the layers could slide apart and uncover the holes).
 *  - Bond kinds (same geometry for every bond of a kind, by symmetry; atom 1 -> atom 2):
 *    layer*3 + 0: in-ring, towards increasing angle; layer*3 + 1 / + 2: to the upper ring's
 *    neighbour at +half / -half a step; 6, 7, 8: outer sphere -> inner hole vertex at
 *    -half step, +half step (lower ring), apex (upper ring).
 *  - Triangles: each layer's lattice triangles, vertices ordered so S_T points outward.
 *  - Cap edges: the end rings of each layer as closed polygons, bottom ring traversed
 *    clockwise seen from +z (cap normal -z), top ring counter-clockwise (+z), so lateral
 *    triangles + caps bound a closed, outward-oriented surface. */
typedef struct {
  double specimen_radius; /* Rs */
  double height;          /* H: z distance between the inner layer's end rings */
  double centre[2];       /* axis position (x, y) */
  double z0;              /* z of the inner layer's bottom ring */
  double rb;              /* inner sphere radius */
  double outer_factor;    /* outer radius / rb (report: 1.1); <= 0: single layer */
} lsdem_membrane_params;

#define LSDEM_MEMBRANE_BOND_KINDS 9

typedef struct {
  int nper;             /* spheres per ring (both layers) */
  int nrings[2];        /* rings per layer (outer: nrings[0] - 1, or 0) */
  int nspheres, nbonds, ntris, ncap_edges;
  double ring_radius[2];/* centre radius of each layer's cylinder */
  double sphere_radius[2];
  double dz;            /* ring spacing (both layers) */
  double *x;            /* 3 * nspheres; inner spheres first, ring by ring */
  int *layer, *ring;    /* per sphere: 0 inner / 1 outer; ring index within its layer */
  int *bond;            /* 2 * nbonds sphere indices (atom 1, atom 2) */
  int *bond_kind;       /* nbonds */
  double kind_r0[LSDEM_MEMBRANE_BOND_KINDS];      /* rest length of each kind */
  double kind_rest[2 * LSDEM_MEMBRANE_BOND_KINDS];/* rest in-surface offset (hoop, axial) */
  int kind_used[LSDEM_MEMBRANE_BOND_KINDS];       /* number of bonds of each kind */
  int *tri, *tri_layer; /* 3 * ntris, ntris */
  int *cap_edge;        /* 2 * ncap_edges */
  int *cap_layer, *cap_end; /* per cap edge: layer; 0 bottom, 1 top */
} lsdem_membrane;

/* Generate the membrane. Allocates the arrays (free with lsdem_membrane_free).
 * LSDEM_ERR_ARG for non-positive sizes or rb too large (fewer than 6 spheres per ring or
 * fewer than 2 rings). */
lsdem_status lsdem_membrane_build(const lsdem_membrane_params *p, lsdem_membrane *m,
                                  lsdem_error *err);
void lsdem_membrane_free(lsdem_membrane *m);

/* Directional area of triangle (a, b, c): S = 0.5 (b - a) x (c - a) (report §2.3.5). */
void lsdem_triangle_area_vector(const double a[3], const double b[3], const double c[3],
                                double S[3]);
/* Confining-pressure force on EACH vertex of a triangle with directional area S:
 * p |S| / 3 along -S/|S| (inward for outward S), i.e. f = -p S / 3. */
void lsdem_pressure_vertex_force(const double S[3], double p, double f[3]);
/* Divergence-theorem volume term of one outward triangle (report eq 2.30, with the
 * centroid as the point of the face): (1/3) x_T . S_T = a . (b x c) / 6. Summed over a
 * closed outward surface it gives the enclosed volume, for any origin. */
double lsdem_triangle_volume_term(const double a[3], const double b[3], const double c[3]);
/* Planar-polygon cap closed through its vertex centroid g (a fan of triangles g, v_k,
 * v_k+1). Accumulate one directed edge (vi -> vj): sum_v += vi, sum_s += 0.5 vi x vj.
 * The fan's volume term is then (1/3) g . S_cap with g = sum_v / n and
 * S_cap = sum_s (the polygon's vector area); the sums can be reduced across ranks. */
void lsdem_cap_edge_accumulate(const double vi[3], const double vj[3], double sum_v[3],
                               double sum_s[3]);
double lsdem_cap_volume_term(const double sum_v[3], int n, const double sum_s[3]);
/* Enclosed volume of one layer's lateral triangles closed by its two end caps (serial
 * reference: the LAMMPS fix computes the same sums distributed). x: 3 * nspheres. */
double lsdem_membrane_volume(const lsdem_membrane *m, const double *x, int layer);
/* Specimen volume inside a membrane whose sphere centres enclose volume V with lateral
 * area A and height H, the lateral surface moved inward by the sphere radius rb (a
 * cylinder's parallel surface): V - rb A + pi rb^2 H. */
double lsdem_membrane_inset_volume(double V, double A, double H, double rb);

/* Membrane bond force (bond_style lsdem/membrane): with d = xj - xi, u = d/|d|, a local
 * cylindrical frame at the bond midpoint (r = horizontal unit vector away from the axis
 * through axis[0..1], t = z x r hoop, z):
 *   normal spring      -kn (|d| - r0) u                                on j
 *   tangential spring  -ks (e - (e.u) u),  e = (d.t - rest[0]) t + (d.z - rest[1]) z
 * The tangential spring resists the change of the bond's in-surface (hoop, axial) offset
 * from its rest value except along the bond, i.e. shear of the hexagonal pattern; it is
 * blind to radial motion (bulging) and to rigid rotation about / translation along the
 * axis, and needs no per-bond history. Writes the force on j (the force on i is -fj) and
 * returns the energy 0.5 kn (|d| - r0)^2 + 0.5 ks |e - (e.u)u|^2. */
double lsdem_membrane_bond_force(const double xi[3], const double xj[3], const double axis[2],
                                 double kn, double ks, double r0, const double rest[2],
                                 double fj[3]);

#ifdef __cplusplus
}
#endif
#endif /* LSDEM_H */
