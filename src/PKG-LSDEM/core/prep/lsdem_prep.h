/* lsdem_prep.h -- preparation of grains (not linked into lmp): grids from SDFs, mass
 * properties, surface nodes, shape building and checks, shapes from voxels, meshes, star-shaped
 * and random grains, Kawamoto/Tan files, packing, and the shape-library writer; and the
 * narrow bands of walls (meshes, terrain) with their file writer. */
#ifndef LSDEM_PREP_H
#define LSDEM_PREP_H

#include "../lsdem_kernel.h"
#include "../io/lsdem_io.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------ making grids ---- */

/* Sample an SDF onto a new grid covering [lo, hi] (shape frame) with spacing h, plus
 * `margin` extra samples on each side. Allocates g->phi (free with lsdem_grid_free). */
lsdem_status lsdem_grid_sample(const lsdem_sdf *s, const double lo[3], const double hi[3],
                               double h, int margin, lsdem_grid *g, lsdem_error *err);
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


/* ------------------------------------------------------------ surface nodes ---- */
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


/* ---------------------------------------------------- shape library (writer) ---- */

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
  LSDEM_CHECK_COARSE_GRID = 1,    /* lsdem_grid_is_coarse: h > R/10, R equivalent radius */
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
  double volume_tol, inertia_tol; /* the tolerances the two node checks used */
  int warnings;          /* LSDEM_CHECK_* bits */
} lsdem_shape_report;

/* Run the checks on a finished shape (normals from its SDF at the nodes), with the default
 * tolerances LSDEM_CHECK_VOLUME_TOL and LSDEM_CHECK_INERTIA_TOL. Returns LSDEM_ERR_ARG for
 * a shape without nodes or volume; warnings are not errors. */
lsdem_status lsdem_shape_check(const lsdem_shape *s, lsdem_shape_report *r, lsdem_error *err);
/* The same with the node checks' tolerances given: a shape source whose discretisation
 * is known to give larger node errors on good shapes (voxel labels: lsdem-shape
 * from-labels) sets them from what it measured. */
lsdem_status lsdem_shape_check_tol(const lsdem_shape *s, double volume_tol, double inertia_tol,
                                   lsdem_shape_report *r, lsdem_error *err);
/* One line of text per warning (each ending in '\n') into buf; returns the length that
 * was needed (like snprintf). "" when there is no warning. */
size_t lsdem_shape_report_text(const lsdem_shape_report *r, char *buf, size_t size);


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


/* ------------------------------------- triangle meshes: checks (mesh_check.c) ---- */
/* (reading: lsdem_mesh_read, lsdem_io.h) */

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


/* ------------------------------------------- walls: narrow bands (band_build.c) ---- */

/* The narrow band (lsdem_band, lsdem_geom.h) of a wall made of triangle mesh m, spacing h,
 * half-width `width` (h <= width <= LSDEM_BAND_MAX_WIDTH_CELLS h). The box: m's bounding
 * box grown by width + h on every side. A brick is stored when some triangle's bounding
 * box grown by width touches it. Samples within width of the surface hold the exact
 * distance to the closest triangle (every triangle visits the samples within width of its
 * bounding box), the others +-width, clamped to [-width, width] as floats.
 * Signs (phi < 0 on the wall's solid side):
 *   LSDEM_BAND_MESH: a closed, consistently oriented mesh without zero-area triangles
 *     (else LSDEM_ERR_ARG with the counts of lsdem_mesh_check_closed); the solid is the
 *     side its faces point away from (its inside when they point outwards; its outside,
 *     a container, when they all point inwards). Near the surface by the angle-weighted
 *     pseudonormal of the closest feature, farther by flood fill (brick by brick; 1 byte
 *     per stored sample).
 *   LSDEM_BAND_TERRAIN: a height field (lsdem_heightmap_mesh): the solid is below it (z
 *     up). A sample over the surface is + above it, - below; beside the terrain's xy
 *     extent or over a hole, near the surface the pseudonormal sign of the closest feature,
 *     farther the side of the height at its (x, y) clamped to the extent (+ over a hole).
 *     A brick no triangle touches is background when its samples share their sign, else
 *     it is stored.
 * Time O(triangles (extent / h + 2 width / h + 1)^3 + stored bricks); memory while
 * building about 13 bytes per stored sample plus the result. Allocates b->index and
 * b->phi (lsdem_band_free); b->far is NULL. LSDEM_ERR_ARG for bad arguments (empty mesh,
 * h <= 0, width < h or > 64 h, a non-finite vertex), LSDEM_ERR_NOMEM when a count would
 * pass 2^31 - 1 (samples per axis, brick slots, stored bricks) or memory runs out. */
lsdem_status lsdem_band_from_mesh(const lsdem_mesh *m, double h, double width,
                                  lsdem_band_source src, lsdem_band *b, lsdem_error *err);
/* The band of a mesh with holes (boundary edges; otherwise as lsdem_band_from_mesh with
 * LSDEM_BAND_MESH: manifold, consistently oriented, no zero-area triangles): a reached
 * sample whose closest triangle lies on a hole's rim takes its side from the generalised
 * winding number (|w| > 1/2: enclosed), so a hole narrower than about 2 width is closed
 * as the winding number spans it; a wider hole, through which the sign fill meets itself
 * with both signs, is refused naming where (LSDEM_ERR_ARG). Extra cost: O(triangles) per
 * sample near a rim. */
lsdem_status lsdem_band_from_open_mesh(const lsdem_mesh *m, double h, double width,
                                       lsdem_band *b, lsdem_error *err);
/* A terrain band kept as its heights (lsdem_band.heights, the column form: 4 bytes per
 * column, exact distances at lookup): hm's heights copied, spacing hm's cell, half-width
 * width (h <= width <= LSDEM_BAND_MAX_WIDTH_CELLS h). LSDEM_ERR_ARG for fewer than 2 x 2
 * heights, bad sizes, or any nodata height (heights cannot hold holes: fill them, or make
 * bricks with lsdem_heightmap_mesh + lsdem_band_from_mesh). Allocates b->heights. */
lsdem_status lsdem_band_from_heights(const lsdem_heightmap *hm, double width, lsdem_band *b,
                                     lsdem_error *err);
/* Frees what lsdem_band_from_mesh or _from_heights allocated (not a mapped file's band). */
void lsdem_band_free(lsdem_band *b);
/* How far a band's zero level set is from the mesh m it was made from (band_check.c):
 * mesh_to_zero, the largest |phi| at m's vertices and triangle centroids; zero_to_mesh,
 * the largest distance from a zero crossing of a stored brick's grid edge (linear along the
 * edge, as the interpolation) to the closest kept triangle, over `crossings` of them (0
 * when the band keeps no triangles); hausdorff, the larger, the Hausdorff distance between
 * the two surfaces as sampled there (lengths). */
typedef struct {
  double mesh_to_zero, zero_to_mesh, hausdorff;
  int64_t crossings;
} lsdem_band_distance;
void lsdem_band_misfit(const lsdem_band *b, const lsdem_mesh *m, lsdem_band_distance *out);
/* Write a band file (format in doc/wall_band.rst, geom/bandfile_format.h; read by
 * lsdem_band_open) after lsdem_band_check; to a temporary file renamed onto path, so a
 * failure leaves no file and readers that map the old one keep it whole. */
lsdem_status lsdem_band_write(const char *path, const lsdem_band *b, lsdem_band_source src,
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

#ifdef __cplusplus
}
#endif
#endif /* LSDEM_PREP_H */
