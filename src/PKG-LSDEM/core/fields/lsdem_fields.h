/* lsdem_fields.h -- continuum fields of a granular assembly on a regular grid (library
 * lsdem_fields: the kernel plus FFTW3; linked by lmp and the tests, never by the tools).
 * Report §3.5.3-3.5.5 (strain localisation); doc/fix_field_lsdem.rst has the method.
 *
 *   grid.c    the grid: cover a box with padding, trilinear deposit, the Gaussian kernel
 *   smooth.c  convolution with the kernel: FFTW (r2c/c2r) and direct summation
 *   fields.c  the moments of a local-linear Gaussian fit and the per-voxel solve:
 *             density, solid fraction, displacement gradient, strains, rotation, contact
 *             stress (Goldhirsch)
 *   vti.c     VTK XML ImageData (.vti) writer
 *
 * Every field is EULERIAN: a voxel at x describes the grains now near x (kernel weights
 * from current centres). Strains are TENSION POSITIVE (as lsdem_local_strain), the contact
 * stress COMPRESSION POSITIVE (as lsdem_love_weber_stress). */
#ifndef LSDEM_FIELDS_H
#define LSDEM_FIELDS_H

#include "../lsdem_kernel.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------- grid (grid.c) ---- */

/* Nodes i = (i0, i1, i2), 0 <= ik < n[k], at x = T (origin + h i) (origin and h per axis,
 * in LATTICE coordinates xi = T^-1 x); stored with i0 fastest: index i0 + n0 (i1 + n1 i2).
 * T is the box's shape, unit upper triangular: T = [[1, skew[0], skew[1]], [0, 1, skew[2]],
 * [0, 0, 1]] with skew = (xy / ly, xz / lz, yz / lz) of a LAMMPS triclinic box (tilt factors
 * over lengths), zeros for an orthogonal box (then xi = x). Node rows along i0 run along x;
 * a voxel's volume is h0 h1 h2 (det T = 1). A periodic axis holds exactly one period: node
 * n[k] is node 0 again, one period vector further. */
typedef struct {
  int n[3];
  double origin[3];
  double h[3];
  int periodic[3];
  double skew[3];
} lsdem_field_grid;

/* The box the grains live in, as LAMMPS keeps it: bounds lo, hi and tilt factors (xy, xz,
 * yz; zeros: orthogonal), so that its period vectors are a = (hi0 - lo0, 0, 0),
 * b = (xy, hi1 - lo1, 0), c = (xz, yz, hi2 - lo2). On an axis with periodic[k], the grains
 * repeat by that period vector, and jump[k] is the displacement an image one period further
 * has over the grain (the period vector now minus the one at the reference: 0 for a box that
 * kept its shape; a homogeneous deformation of the box makes affine displacements periodic
 * only with it). Zeros: an open, orthogonal box. */
typedef struct {
  int periodic[3];
  double lo[3], hi[3];
  double tilt[3];
  double jump[3][3];
} lsdem_field_box;

/* The Gaussian kernel exp(-r^2 / (2 w^2)) is cut at LSDEM_FIELD_KERNEL_CUT w. */
#define LSDEM_FIELD_KERNEL_CUT 3.0

size_t lsdem_field_grid_nodes(const lsdem_field_grid *g);
/* The kernel's reach in nodes along axis k of grid g: the largest |i_k| of a node offset i
 * within LSDEM_FIELD_KERNEL_CUT w of a node, ceil(cut w |row k of T^-1| / h_k)
 * (ceil(cut w / h_k) on an orthogonal grid). */
int lsdem_field_grid_reach(const lsdem_field_grid *g, double width, int k);
/* x's lattice coordinates xi = T^-1 x (lsdem_field_grid) for skew s, and back: x = T xi.
 * Zero skew: xi = x, bit for bit. */
void lsdem_field_to_lattice(const double skew[3], const double x[3], double xi[3]);
void lsdem_field_from_lattice(const double skew[3], const double xi[3], double x[3]);
/* Row k of T^-1 for skew s (lsdem_field_grid): a node offset of length r has |xi_k| <=
 * r |row|, and row / l_k is the dual of period vector k (row . a_j = l_k delta_kj). */
void lsdem_field_inverse_row(const double skew[3], int k, double row[3]);
/* The skew of box (lsdem_field_grid): tilt factors over the box's lengths. */
void lsdem_field_box_skew(const lsdem_field_box *box, double skew[3]);
/* A box's period vectors (rows) last seen and now, and the reference's (rows, ref): when
 * `now` is another basis of last's lattice (a flip: LAMMPS's fix deform resets a tilt
 * beyond half a length by subtracting a period vector), the integer change of basis
 * M = round(now last^-1) is applied to ref as well, so that ref_k stays the reference image
 * of period vector k (what lsdem_field_box's jump_k = now_k - ref_k needs). last and now
 * must differ by little more than a flip (a step's deformation). Returns 1 when it acted,
 * 0 when M = I. */
int lsdem_field_box_rebase(const double last[3][3], const double now[3][3], double ref[3][3]);
/* Node i's position x = T (origin + h i). */
void lsdem_field_node_position(const lsdem_field_grid *g, const int i[3], double x[3]);
/* The grid over the box [lo, hi] (bounds of every point that will be deposited) with
 * spacing h, padded by reach + 1 nodes of zeros on each side, each axis then lengthened to
 * a size FFTW transforms fast (factors 2, 3, 5, 7; the extra nodes are more zero padding at
 * the high end). A circular convolution on it equals the linear one on every node: nothing
 * deposited comes within reach of a node across the periodic seam.
 * LSDEM_ERR_ARG for h, width <= 0 or an empty box; LSDEM_ERR_NOMEM beyond 2^31 nodes. */
lsdem_status lsdem_field_grid_cover(const double lo[3], const double hi[3], double h,
                                    double width, lsdem_field_grid *g, lsdem_error *err);
/* As lsdem_field_grid_cover on the open axes of box (box NULL: all open), with box's skew
 * (lo and hi then bound the points' lattice coordinates); a periodic axis spans exactly its
 * period, unpadded: n = the smallest fast size >= length / h nodes of lattice spacing
 * length / n (<= h), the FFT's circular convolution being the periodic one there.
 * LSDEM_ERR_ARG also when the kernel's reach is not below half the period (2 reach + 2 >
 * n: a grain would meet a node as two of its images). */
lsdem_status lsdem_field_grid_cover_box(const lsdem_field_box *box, const double lo[3],
                                        const double hi[3], double h, double width,
                                        lsdem_field_grid *g, lsdem_error *err);
/* The trilinear cell of x (world frame; the cell found from x's lattice coordinates): its 8
 * nodes (wrapped on periodic axes), their weights (>= 0, sum 1) and, if offset is not NULL,
 * x minus each node's position (world frame; the node's image next to x). x must lie inside
 * the grid's padded interior on the open axes; on a periodic axis anywhere. */
void lsdem_field_cell(const lsdem_field_grid *g, const double x[3], size_t node[8],
                      double weight[8], double offset[8][3]);
/* Adds value[c] times the trilinear weights of x to channel c (channels: nchan arrays of
 * lsdem_field_grid_nodes(g) doubles, one after the other). The weights are >= 0 and sum to
 * 1, so a deposit keeps every total. x as for lsdem_field_cell. */
void lsdem_field_deposit(const lsdem_field_grid *g, const double x[3], int nchan,
                         const double *value, double *channels);
/* The discrete kernel on the grid, periodic offsets (node i holds G at the offset
 * T (h j), j_k = i_k or i_k - n_k, whichever is nearer 0), normalised to sum 1: smoothing
 * keeps totals. */
void lsdem_field_kernel(const lsdem_field_grid *g, double width, double *kernel);
/* The moment kernel K(which) of lsdem_field_smooth_terms (K0: lsdem_field_kernel), the
 * same normalisation. */
void lsdem_field_kernel_moment(const lsdem_field_grid *g, double width, int which,
                               double *kernel);

/* ---------------------------------------------------------- smooth (smooth.c) ---- */

/* Every channel convolved with the normalised kernel, in place. The FFT's cost is the
 * grid's, whatever the kernel width; the direct sum (for tests and the benchmark) scatters
 * each occupied node over the (2 reach + 1)^3 nodes within reach, as a sum over grains
 * would. Both give the linear convolution of deposits made by lsdem_field_deposit on a grid
 * from lsdem_field_grid_cover (the direct sum needs them there: it writes within reach of
 * each), the periodic one on a periodic axis. FFTW plans with FFTW_ESTIMATE on
 * fftw_malloc'd buffers: the same bits on every call with the same grid. LSDEM_ERR_NOMEM. */
lsdem_status lsdem_field_smooth_fft(const lsdem_field_grid *g, double width, int nchan,
                                    double *channels, lsdem_error *err);
lsdem_status lsdem_field_smooth_direct(const lsdem_field_grid *g, double width, int nchan,
                                       double *channels, lsdem_error *err);
/* Moment kernels: K0 = G (the normalised kernel), K(1 + i) = G r_i, K(4 + s) = G r_i r_j
 * (s: xx xy xz yy yz zz), r = source node - target node (minimum image on periodic axes).
 * A term adds K(kernel) * channel in to channel out. */
enum { LSDEM_FIELD_KERNELS = 10 };
typedef struct {
  int out, in, kernel;
} lsdem_field_term;
/* out[t.out] = sum over the terms t of K(t.kernel) * in[t.in], by FFT (one forward transform
 * per input channel, one inverse per output channel); in and out may be the same array.
 * LSDEM_ERR_NOMEM. */
lsdem_status lsdem_field_smooth_terms(const lsdem_field_grid *g, double width, int nin,
                                      const double *in, int nout, double *out, int nterms,
                                      const lsdem_field_term *terms, lsdem_error *err);

/* ---------------------------------------------------------- fields (fields.c) ---- */

/* A grain now: mass, solid volume, centre x, displacement u since the reference. On a
 * periodic axis x may be any image, u being that image's displacement (the unwrapped centre
 * for the unwrapped displacement); the core wraps it. */
typedef struct {
  double mass, volume, x[3], u[3];
} lsdem_field_grain;
/* One side of a contact: the force ON a grain at the contact point, and that grain's
 * centre (the image nearest the point). A grain-grain contact gives two branches, a wall
 * contact one; the moment f (x) (point - centre) is lsdem_love_weber_add's. */
typedef struct {
  double force[3], point[3], centre[3];
} lsdem_field_branch;

typedef struct {
  double width;      /* Gaussian standard deviation w (length) */
  double h;          /* grid spacing (length) */
  double min_variance; /* a node is regular when the smallest eigenvalue of its weighted
                          position covariance is >= min_variance w^2 (the grains around it
                          spread in every direction) ... */
  double min_weight;   /* ... and its kernel mass is >= min_weight times the largest.
                          Below these the fit is ill-posed, and the FFT's round-off (relative
                          to each channel's largest value) would show */
  lsdem_field_box box; /* periodic axes (zeros: an open box) */
} lsdem_field_params;
/* defaults: on random packings an affine field comes out exact to ~1e-12 relative, a
 * rigid rotation strain-free to ~1e-13, at every regular node (unittest/core/test_fields.c) */
#define LSDEM_FIELD_MIN_VARIANCE 0.1
#define LSDEM_FIELD_MIN_WEIGHT 0.03

/* Per-node fields, each an array over the grid's nodes (tensors row-major, 9 per node).
 * Kinematic fields (grad .. shear) are NaN where the node is not regular. */
typedef struct {
  lsdem_field_grid grid;
  double *density;       /* mass per volume */
  double *solid_fraction;
  double *grad;          /* displacement gradient H = F - I (9) */
  double *strain_small;  /* (F + F^T) / 2 - I (9) */
  double *strain_green;  /* (F^T F - I) / 2 (9) */
  double *rotation;      /* rotation vector of R in F = R U: angle (radians) times axis (3) */
  double *volumetric;    /* tr E (Green) */
  double *shear;         /* von Mises shear of E: sqrt(E':E' / 2) */
  double *stress;        /* contact stress, compression positive (9, symmetric) */
  unsigned char *regular;
  unsigned char *inside; /* 1 unless masked (lsdem_fields_mask_cylinder) */
} lsdem_fields;

/* The fields of n grains and nb contact branches (in their given order: the result's bits
 * depend on it). Each grain deposits, on each node g of its trilinear cell, its moments
 * m, m d, m d d^T, m u, m u d^T about that node (d = x - x_g) and V; the smoothing moves
 * them to the target node n with the moment kernels (d + x_g - x_n, the binomial
 * expansion), so every node's moments are about itself, with the grain's image nearest it
 * on a periodic axis. Each branch deposits -sym(f (x) b) spread uniformly along
 * b = point - centre (minimum image on a periodic axis; Goldhirsch 2010: ceil(|b| / h)
 * equal pieces, each at its midpoint). A node's moments are those of a Gaussian-weighted
 * least-squares fit u(x) = a + L (x - xbar) over the grains, F = (I - L)^-1; an affine
 * displacement is recovered exactly. In a periodic box the fit is made of u - L_box x,
 * periodic for an affine field consistent with the box (L_box = sum_k jump_k e_k^T /
 * period_k), and L_box added back. Integrals over the grid: sum density dV = total mass,
 * sum stress dV = -sum sym(f (x) b) (the Love-Weber sum). Allocates out
 * (lsdem_fields_free). LSDEM_ERR_ARG (bad params, n < 1), LSDEM_ERR_NOMEM. */
lsdem_status lsdem_fields_compute(const lsdem_field_params *p, int n,
                                  const lsdem_field_grain *grains, int nb,
                                  const lsdem_field_branch *branches, lsdem_fields *out,
                                  lsdem_error *err);
void lsdem_fields_free(lsdem_fields *f);
/* Nodes outside the cylinder |(x, y) - centre| <= radius, zlo <= z <= zhi (axis z): inside
 * = 0 and every field NaN (a membrane's outline: nothing outside is granular material). */
void lsdem_fields_mask_cylinder(lsdem_fields *f, const double centre[2], double radius,
                                double zlo, double zhi);
/* inside[node] = 1 for the grid nodes inside the closed surface of nt triangles (vertex
 * indices into the nv points v, 3 doubles each); each loop of boundary edges (edges of one
 * triangle only: an open membrane's end rings) is closed by a fan to the loop's centroid.
 * Point in closed surface by ray parity: a ray along +x from each node row, the crossings
 * found in the (y, z) projection with an exact, shared tie rule (an edge's orientation
 * computed once in a fixed vertex order, ties broken by the perturbation (y + e, z + e^2)),
 * so a ray through an edge or vertex counts one crossing, or two at a fold; nodes on the
 * surface fall either side. Cost: triangles times the rows under each, plus the nodes.
 * LSDEM_ERR_ARG for a vertex index out of range, LSDEM_ERR_NOMEM. */
lsdem_status lsdem_field_inside_surface(const lsdem_field_grid *g, int nv, const double *v,
                                        int nt, const int *tri, unsigned char *inside,
                                        lsdem_error *err);
/* The nodes outside that surface masked as by lsdem_fields_mask_cylinder. */
lsdem_status lsdem_fields_mask_surface(lsdem_fields *f, int nv, const double *v, int nt,
                                       const int *tri, lsdem_error *err);

/* ---------------------------------------------------------------- vti (vti.c) ---- */

/* VTK XML ImageData, point data, raw appended Float64 (UInt8 for regular and inside);
 * ParaView reads it. Names: density solid_fraction displacement_gradient strain_small
 * strain_green rotation volumetric_strain shear_strain stress regular inside.
 * LSDEM_ERR_IO. */
lsdem_status lsdem_fields_write_vti(const char *path, const lsdem_fields *f,
                                    lsdem_error *err);

#ifdef __cplusplus
}
#endif
#endif /* LSDEM_FIELDS_H */
