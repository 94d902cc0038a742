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
} lsdem_grid;

/* Trilinear interpolation of value and gradient (report Algorithm 1).
 * Returns phi at p and writes the normalised gradient to grad (unit length; +x if the
 * trilinear gradient vanishes).
 * Outside the grid box: returns phi(clamp(p)) + |p - clamp(p)| with grad = the unit
 * vector from clamp(p) towards p. Grids carry a positive margin, so such points are
 * never inside the solid. */
double lsdem_grid_eval(const lsdem_grid *g, const double p[3], double grad[3]);
/* Value only (same outside rule), for mass properties and checks. */
double lsdem_grid_value(const lsdem_grid *g, const double p[3]);
/* Raw trilinear gradient (not normalised) inside the grid; zero outside. For tests. */
void lsdem_grid_gradient_raw(const lsdem_grid *g, const double p[3], double grad[3]);
lsdem_status lsdem_grid_check(const lsdem_grid *g, lsdem_error *err); /* sizes, NaN */

/* ------------------------------------------------------- signed distances ---- */

typedef enum {
  LSDEM_SDF_GRID = 0,
  LSDEM_SDF_SPHERE,    /* a[0] = radius, centred at the origin */
  LSDEM_SDF_PLANE,     /* solid is z <= 0 (half-space), outward normal +z */
  LSDEM_SDF_CYLINDER,  /* a[0] = radius, a[1] = half-length along z (<=0: infinite) */
  LSDEM_SDF_BOX,       /* a[0..2] = half-extents */
  LSDEM_SDF_ELLIPSOID  /* a[0..2] = semi-axes along x, y, z (exact distance) */
} lsdem_sdf_kind;

/* Any shape behind one interface: phi(p) and its outward unit gradient, in the shape's
 * own frame. inverted != 0 swaps inside and outside (a cylindrical container, a box
 * of walls) by negating phi and grad. */
typedef struct {
  lsdem_sdf_kind kind;
  int inverted;
  double a[3];
  lsdem_grid grid; /* used when kind == LSDEM_SDF_GRID */
} lsdem_sdf;

double lsdem_sdf_eval(const lsdem_sdf *s, const double p[3], double grad[3]);
/* Radius of a sphere about the origin that contains the solid (HUGE_VAL if unbounded). */
double lsdem_sdf_bound_radius(const lsdem_sdf *s);

/* Sample an SDF onto a new grid covering [lo, hi] (shape frame) with spacing h, plus
 * `margin` extra samples on each side. Allocates g->phi (free with lsdem_grid_free). */
lsdem_status lsdem_grid_sample(const lsdem_sdf *s, const double lo[3], const double hi[3],
                               double h, int margin, lsdem_grid *g, lsdem_error *err);
void lsdem_grid_free(lsdem_grid *g); /* frees phi allocated by the core; phi = NULL */

/* -------------------------------------------------------- mass properties ---- */

typedef struct {
  double volume;
  double centroid[3];    /* in the grid's frame */
  double inertia[9];     /* about the centroid, grid frame, per unit density */
  double principal[3];   /* principal moments, ascending */
  double axes[9];        /* columns = principal axes in the grid frame (proper rotation) */
} lsdem_massprops;

/* Volume, centroid and inertia of {phi < 0}, integrating a smoothed Heaviside of
 * phi over each voxel with `sub` sub-samples per axis (1 = voxel centres). */
lsdem_status lsdem_massprops_grid(const lsdem_grid *g, int sub, lsdem_massprops *mp,
                                  lsdem_error *err);

/* Re-express a grid shape in its principal frame (report §2.2.3): resample onto a new
 * grid whose axes are the principal axes and whose coordinates are relative to the
 * centroid, same spacing, keeping `margin` samples of positive phi around the solid.
 * Allocates out->phi. q_out receives the rotation principal -> original grid frame. */
lsdem_status lsdem_grid_to_principal(const lsdem_grid *in, const lsdem_massprops *mp, int margin,
                                     lsdem_grid *out, double q_out[4], lsdem_error *err);

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
} lsdem_contact_params;

/* What one master-on-slave test produced. Forces and torques are world-frame and act
 * on the master A; the slave B receives -force and torque_b. */
typedef struct {
  double force[3];     /* sum of node forces on A (eq 2.14) */
  double torque_a[3];  /* about A's centroid (eq 2.16) */
  double torque_b[3];  /* about B's centroid, of the reaction on B */
  double point[3];     /* force-weighted mean contact point (world) */
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
 * capacity >= A->nnodes), count in *n_out. An entry whose stamp == step is reused as is
 * (already advanced this step: a second force call at the same step must not advance the
 * shear twice). With mu == 0 no history is read or written (pass NULL, 0, NULL).
 * Returns the number of penetrating nodes. */
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
 *   - hist_in and hist_out must not overlap. */

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

#ifdef __cplusplus
}
#endif
#endif /* LSDEM_H */
