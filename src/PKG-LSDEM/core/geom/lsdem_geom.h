/* lsdem_geom.h -- geometry of the LSDEM kernel: level-set grids (Algorithm 1), analytic
 * signed distances, grain shapes, the shape library (read side) and the zero level set as
 * a triangle mesh (for output). */
#ifndef LSDEM_GEOM_H
#define LSDEM_GEOM_H

#include "../base/lsdem_base.h"

#ifdef __cplusplus
extern "C" {
#endif

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
 * never inside the solid. This outside value is an UPPER bound of the distance to the
 * solid (triangle inequality), exact only along the box's face normals, and its
 * gradient is not the surface normal: a sphere whose centre lies outside the box is
 * detected from its surface instead (contact/detect.c). */
double lsdem_grid_eval(const lsdem_grid *g, const double p[3], double grad[3]);
/* Whether p lies in the grid's box (where lsdem_grid_eval interpolates). */
int lsdem_grid_box_contains(const lsdem_grid *g, const double p[3]);
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
/* A level-set grain behaves like a DEM sphere with a grid spacing finer than R/10, R the
 * radius of the sphere of the grain's volume (Duriez & Bonelli 2021): the limit R/10 for
 * a volume, and whether spacing h exceeds it by more than a relative 1e-5 (so a spacing
 * of R/10 up to round-off is not coarse, and a coarse one differs from R/10 within the 6
 * significant digits that messages print). */
double lsdem_grid_spacing_limit(double volume);
int lsdem_grid_is_coarse(double h, double volume);
/* Whether a sample of g (n[0] n[1] n[2] values of phi) is negative: a grid without one
 * holds no solid, so no grain. */
int lsdem_grid_has_solid(const lsdem_grid *g);


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
  LSDEM_SDF_SUPERELLIPSOID,
  LSDEM_SDF_BAND       /* a narrow-band level set (lsdem_band below): walls, not grains */
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
  const struct lsdem_band *band; /* used when kind == LSDEM_SDF_BAND (not owned) */
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
/* A bound L such that phi(p) <= L dist(p, solid) wherever phi(p) >= 0 (also inverted):
 * what bounding-ball screening and node lists rely on (a ball of radius r about c is
 * clear of the solid when phi(c) > L r). 1 for exact signed distances,
 * LSDEM_BAND_LIPSCHITZ for narrow bands (|grad phi| <= sqrt 3 within the stored bricks,
 * background values below the distance to them), 0 for none: grids have none everywhere
 * (trilinear interpolation of samples that may be smoothed or approximate;
 * lsdem_grid_outer_lipschitz bounds it where phi >= 0), nor has the superellipsoid's
 * first-order distance. */
double lsdem_sdf_lipschitz(const lsdem_sdf *s);
void lsdem_grid_free(lsdem_grid *g); /* frees phi allocated by the core; phi = NULL */

/* ------------------------------------------------------ star-shaped solids ---- */

/* A solid that is star-shaped about the origin: its surface point in the unit direction u
 * is radius(u) * u, radius > 0 and finite. ctx is the shape's parameters. */
typedef double (*lsdem_radius_fn)(const double u[3], const void *ctx);

/* Radius function of an LSDEM_SDF_SUPERELLIPSOID (ctx: its const lsdem_sdf *):
 * 1 / g(u), g the degree-1 gauge of the superellipsoid (evaluated overflow-free). */
double lsdem_superellipsoid_radius(const double u[3], const void *sdf);

/* ------------------------------------------------- triangle pseudonormals ---- */

/* Angle-weighted pseudonormals of a triangle surface (Baerentzen & Aanaes, IEEE TVCG 11(3),
 * 2005): the sign of the distance to the closest feature of a closed, consistently oriented
 * surface, exact when the triangle is the closest one. Triangles are vertex index triples
 * (counter-clockwise seen from outside); nbr[3t + e] is the triangle across edge e of t
 * (corner e to corner e + 1), -1 when there is none (an open edge). */
typedef struct {
  double *face;      /* 3 per triangle: unit face normal (0 for a degenerate triangle) */
  double *vertex;    /* 3 per vertex: sum of the incident faces' normals times their angle */
  double *sphere;    /* 4 per triangle: a bounding sphere (centroid, radius), for pruning */
  const int *nbr;    /* 3 per triangle (not owned) */
} lsdem_pseudonormals;
lsdem_status lsdem_pseudonormals_make(const double *verts, int64_t nverts, const int *tris,
                                      int64_t ntris, const int *nbr, lsdem_pseudonormals *pn,
                                      lsdem_error *err);
void lsdem_pseudonormals_free(lsdem_pseudonormals *pn);
/* Signed distance from p to triangle t: to its closest point q (lsdem_closest_on_triangle),
 * signed by the pseudonormal of q's feature (face, edge: the two faces' sum, vertex); when
 * grad is not NULL, the unit vector sign (p - q) / |p - q| (the face normal when p is on
 * the surface). */
double lsdem_signed_distance_to_triangle(const double *verts, const int *tris,
                                         const lsdem_pseudonormals *pn, const double p[3],
                                         int64_t t, double grad[3]);

/* ------------------------------------------------- narrow-band level sets ---- */

/* A signed-distance grid stored only near its zero level set, for walls of any shape
 * (meshes, terrain; report §4.6.3, eqs 4.48-4.49: a dense terrain grid needed 10 GB).
 * The virtual dense grid (n samples per axis at spacing h from origin, x fastest, as
 * lsdem_grid) is cut into bricks of LSDEM_BAND_BRICK^3 cells. A brick that may hold a
 * sample nearer than `width` to the surface is stored: its (LSDEM_BAND_BRICK + 1)^3
 * samples, x fastest (neighbouring stored bricks repeat their shared faces, so the 8
 * samples of any cell lie in one brick). Any other brick is background: every sample
 * +width (the grains' side) or -width (the wall's solid side). Stored samples are exact
 * signed distances clamped to [-width, width] (float). Memory grows with the surface's
 * area, not the box's volume.
 *
 * Lookup (lsdem_band_eval): one index read for the cell's brick, then the same trilinear
 * cell interpolation as lsdem_grid (Algorithm 1). Outside the box [origin, origin +
 * (n-1) h] the value and gradient at the nearest point of the box (the band continues
 * as its boundary values: a terrain beyond its edge as its edge columns).
 * Lipschitz bound: the samples are a 1-Lipschitz function's (a clamped distance), so
 * each trilinear partial derivative is at most 1 and |grad phi| <= sqrt 3 everywhere,
 * the outside rule included (LSDEM_BAND_LIPSCHITZ, with room for float rounding of
 * samples up to LSDEM_BAND_MAX_WIDTH_CELLS spacings). A node that reads -width has gone
 * through the band (tunnelling, lsdem_band_tunnelled). Frame: the wall's own. */
#define LSDEM_BAND_BRICK_LOG2 3
#define LSDEM_BAND_BRICK 8                 /* cells per brick edge: 1 << LOG2 */
#define LSDEM_BAND_BRICK_SIDE 9            /* samples per brick edge */
#define LSDEM_BAND_BRICK_SAMPLES 729       /* samples per stored brick: 9^3 */
#define LSDEM_BAND_LIPSCHITZ 1.7321        /* > sqrt 3 = 1.7320508 */
#define LSDEM_BAND_MAX_WIDTH_CELLS 64.0    /* width / h at most (the bound's rounding room) */
enum { LSDEM_BAND_OUTSIDE = -1, LSDEM_BAND_INSIDE = -2 }; /* background bricks' index */

typedef struct lsdem_band {
  int n[3];             /* samples of the virtual dense grid per axis (>= 2) */
  double h;             /* spacing, length units */
  double origin[3];     /* position of sample (0,0,0), wall frame */
  int nb[3];            /* bricks per axis: (n[a] - 2) / LSDEM_BAND_BRICK + 1 */
  int64_t nbricks;      /* stored bricks */
  double width;         /* half-width of the band: |phi| <= width, background +-width */
  const int32_t *index; /* nb[0] nb[1] nb[2] entries, x fastest: stored brick number, or
                           LSDEM_BAND_OUTSIDE / LSDEM_BAND_INSIDE */
  const float *phi;     /* nbricks * LSDEM_BAND_BRICK_SAMPLES */
  const uint16_t *far;  /* per brick slot, the coarse level: a background slot's Chebyshev
                           distance in bricks to the nearest stored brick (1: adjacent;
                           capped at 65535), from lsdem_band_far; NULL: background values
                           are +-width */
  /* The surface it was made from (ntris = 0: not kept): triangles in the wall frame, and
   * per stored brick the triangles whose bounding box grown by `width` touches it (so a
   * point of the brick nearer than width to the surface finds its closest triangle there):
   * brick k's are brick_tris[brick_tri_start[k] .. brick_tri_start[k+1]). For per-triangle
   * force maps (lsdem_band_closest_triangle) and output. */
  int64_t nverts, ntris;
  const double *verts;            /* 3 nverts */
  const int32_t *tris;            /* 3 ntris vertex indices, counter-clockwise from outside */
  const int64_t *brick_tri_start; /* nbricks + 1 */
  const int32_t *brick_tris;
  const int32_t *nbr;             /* 3 ntris: the triangle across each edge (-1: open) */
  /* Exact mode (set by the user of a band, e.g. fix wall/lsdem exact yes): pseudonormals
   * made from the surface; inside the band, values and normals come from the closest
   * triangle instead of trilinear interpolation. NULL: trilinear everywhere. */
  const lsdem_pseudonormals *exact;
  /* A terrain kept as its heights (the column form; source LSDEM_BAND_HEIGHTS): n[0] x n[1]
   * heights, x fastest, column (i,j) at (origin[0] + h i, origin[1] + h j); n[2] = 1, no
   * bricks, no index, no kept surface; lookups give the exact signed distance to its
   * triangles (lsdem_heights_eval). NULL: bricks. */
  const float *heights;
  const float *tile_range; /* per tile of LSDEM_HEIGHTS_TILE^2 cells, x fastest: its lowest
                              and highest height (lsdem_heights_tiles, made at open) */
  int nt[2];               /* tiles per axis */
} lsdem_band;

/* phi at p (wall frame) and the unit gradient (normalised trilinear; +x where it
 * vanishes, e.g. in a background brick); with b->exact, where the trilinear value is
 * within the band (|phi| < width), the exact signed distance to the closest triangle of
 * p's brick and its direction (lsdem_signed_distance_to_triangle): sharp edges and
 * corners as they are, not rounded or filled by about h. A background slot k bricks from the band reads
 * +-max(width, (k - 1) LSDEM_BAND_BRICK h): no farther than the stored bricks, which hold
 * the surface, so a grain far from the wall is rejected by one lookup at its centre. */
double lsdem_band_eval(const lsdem_band *b, const double p[3], double grad[3]);
void lsdem_band_eval_many(const lsdem_band *b, int n, const double *p, double *phi,
                          double *grad);
/* A band kept as heights: within width of the surface the exact signed distance to its
 * nearest triangle (lsdem_heightmap_mesh's: cell (i,j) split along (i,j)-(i+1,j+1)) and its
 * direction (the triangle's upward normal on the surface); beyond, +-a lower bound >= width
 * from the height ranges of p's tile and its neighbours (at most LSDEM_HEIGHTS_TILE h), so
 * a far grain is rejected by one lookup at its centre. Outside: above the surface. Beyond
 * the columns' xy extent, the value at the nearest column (as bricks: the outside rule).
 * lsdem_band_eval calls it for such bands. */
#define LSDEM_HEIGHTS_TILE 16
double lsdem_heights_eval(const lsdem_band *b, const double p[3], double grad[3]);
/* The tiles' height ranges of a band kept as heights. Allocates *range (free()). */
lsdem_status lsdem_heights_tiles(const lsdem_band *b, float **range, int nt[2],
                                 lsdem_error *err);
/* Sizes (at least 2 x 2 columns, n[2] = 1, no bricks nor surface) and finite heights. */
lsdem_status lsdem_heights_check(const lsdem_band *b, lsdem_error *err);
/* The triangle nearest to p (wall frame) among those listed for p's brick, and its
 * squared distance in *d2: exact when p is nearer than width to the surface; -1 when p's
 * brick is background or the band keeps no surface. */
int64_t lsdem_band_closest_triangle(const lsdem_band *b, const double p[3], double *d2);
/* A band's sharp convex features as points (band_points.c), for testing a wall against a
 * grain's level set the other way round (fix wall/lsdem twoway): a flat grain face on a
 * knife edge or a box corner holds no node inside the wall. An edge of the kept surface
 * is sharp when it is convex (the neighbour's far vertex lies on the solid side of the
 * triangle's plane) and its triangles' normals differ by LSDEM_BAND_SHARP_DEG or more;
 * its points are its two vertices (each once) and samples at most `spacing` apart along
 * it. Points are numbered brick by brick in brick order (stored bricks are numbered in
 * slot order, x fastest), so a visit of slots in increasing order meets them in
 * increasing number. Wall frame. */
#define LSDEM_BAND_SHARP_DEG 30.0
typedef struct {
  int64_t n;            /* points */
  double *x;            /* 3 n */
  int64_t *brick_start; /* nbricks + 1: brick k's points are [brick_start[k], [k + 1]) */
  int64_t nedges;       /* sharp edges */
} lsdem_band_points;
/* The points of b's sharp edges (b keeps its surface and its triangles' neighbours).
 * LSDEM_ERR_ARG for a band without surface (heights, or ntris = 0), a point whose brick
 * is not stored (a band narrower than a cell's diagonal), spacing <= 0; LSDEM_ERR_NOMEM.
 * Allocates p->x and p->brick_start (lsdem_band_points_free). */
lsdem_status lsdem_band_points_make(const lsdem_band *b, double spacing, lsdem_band_points *p,
                                    lsdem_error *err);
void lsdem_band_points_free(lsdem_band_points *p);
/* The slots (brick coordinates, inclusive) that a ball of radius r about c (wall frame)
 * reaches, clamped to the box. */
void lsdem_band_slot_range(const lsdem_band *b, const double c[3], double r, int lo[3],
                           int hi[3]);
/* A bound on the points any ball of radius r holds: the most points in the slots such a
 * ball can reach, over the stored bricks that hold points (setup only). */
int64_t lsdem_band_points_within(const lsdem_band *b, const lsdem_band_points *p, double r);
/* Whether a penetration depth (-phi of a node) means the node read the solid-side
 * background: it went through the band. */
int lsdem_band_tunnelled(const lsdem_band *b, double depth);
/* The coarse level of b (lsdem_band.far): Chebyshev distance transform of the stored
 * bricks over the brick slots (exact, two raster passes). Allocates *far (free()). */
lsdem_status lsdem_band_far(const lsdem_band *b, uint16_t **far, lsdem_error *err);
/* Sizes, finiteness, index entries in range, samples within [-width, width]; the surface's
 * vertices finite, triangles naming vertices, brick lists increasing and naming
 * triangles. */
lsdem_status lsdem_band_check(const lsdem_band *b, lsdem_error *err);
/* Bytes of the index, the coarse level, the stored bricks and the surface. */
size_t lsdem_band_bytes(const lsdem_band *b);

/* A ridge or slot of a wall narrower than a limit (lsdem_band_thin_features). */
typedef struct {
  int ridge;       /* 1: solid thinner than the limit; 0: a slot, a gap narrower than it */
  int ntris;       /* its triangles: those joined by edges whose width across is below it */
  double thinnest; /* the least width across, along a triangle's normal from its centroid */
  double at[3];    /* the centroid of that triangle */
  int32_t tri;     /* that triangle */
} lsdem_thin_feature;
/* The ridges and slots of a band's kept surface narrower than limit (e.g. 2 h, below which
 * trilinear interpolation cannot hold them): from each triangle's centroid a ray along its
 * inward and one along its outward normal; one that meets another triangle within limit
 * marks the triangle (width across = that distance); marked triangles joined by edges or
 * facing each other across make one feature. Ridges first, each kind in order of its first triangle. Allocates *out
 * (free()); LSDEM_ERR_ARG when the band keeps no surface. */
lsdem_status lsdem_band_thin_features(const lsdem_band *b, double limit,
                                      lsdem_thin_feature **out, int *nout, lsdem_error *err);
/* A band file (format in doc/wall_band.rst; written by lsdem-shape wall/terrain through
 * lsdem_band_write, lsdem_prep.h): memory-mapped read-only, so ranks on one machine share
 * one copy through the page cache. Open checks the header, the checksums, the sizes and
 * lsdem_band_check. */
typedef struct lsdem_band_file lsdem_band_file;
/* What a band file holds: a closed mesh's bricks, a terrain's bricks, or a terrain's
 * heights (lsdem_band.heights). */
typedef enum {
  LSDEM_BAND_MESH = 0,
  LSDEM_BAND_TERRAIN = 1,
  LSDEM_BAND_HEIGHTS = 2
} lsdem_band_source;
lsdem_status lsdem_band_open(const char *path, lsdem_band_file **file, lsdem_error *err);
void lsdem_band_close(lsdem_band_file *file);
const lsdem_band *lsdem_band_file_band(const lsdem_band_file *file);
lsdem_band_source lsdem_band_file_source(const lsdem_band_file *file);

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
 * section checksum, then lsdem_shape_validate. LSDEM_ERR_FORMAT on a checksum mismatch,
 * LSDEM_ERR_NUMERIC from lsdem_shape_validate. */
lsdem_status lsdem_library_verify(const lsdem_library *lib, int index, lsdem_error *err);

/* What a grain needs of a shape's arrays beyond its counts and scalars (the library
 * reader checks those at open, the writer before writing): nodes, node areas, cluster
 * spheres and grid values finite; a grid shape has a solid (a negative value) and its
 * centroid, the frame's origin, inside the grid box; every node area > 0; every node
 * within the bounding radius (relative slack 1e-9). A shape failing these lets grains
 * pass through each other. LSDEM_ERR_NUMERIC with a message naming shape `index` and
 * `name` (may be NULL) and the first failure. */
lsdem_status lsdem_shape_validate(const lsdem_shape *s, int index, const char *name,
                                  lsdem_error *err);

/* ------------------------------------------------------------ triangle meshes ---- */

/* A triangle mesh with shared vertices (STL vertices are welded on exact equality). */
typedef struct {
  int nverts, ntris;
  double *verts; /* 3*nverts */
  int *tris;     /* 3*ntris vertex indices, counter-clockwise seen from outside */
} lsdem_mesh;

#define LSDEM_MESH_MAX_TRIS 16777216 /* triangles per mesh */
void lsdem_mesh_free(lsdem_mesh *m);

/* ---------------------------------------------------- zero level set as a mesh ---- */

/* The zero level set of a bounded SDF as a closed, outward-oriented triangle mesh
 * (lsdem_mesh above) in the SDF's frame (marching tetrahedra on a lattice: surface.c).
 * Lattice spacing h; h <= 0 means the grid's own samples for a grid SDF, bound radius / 20
 * for an analytic one.
 * Vertices are shared between triangles (the mesh is watertight: every edge has two
 * triangles). Allocates m; free with lsdem_mesh_free. LSDEM_ERR_ARG for unbounded SDFs. */
lsdem_status lsdem_mesh_extract(const lsdem_sdf *s, double h, lsdem_mesh *m, lsdem_error *err);
double lsdem_mesh_area(const lsdem_mesh *m);

#ifdef __cplusplus
}
#endif
#endif /* LSDEM_GEOM_H */
