/* lsdem_specimen.h -- the triaxial specimen: stress, strain and fabric measures (report §3.5)
 * and the flexible membrane (report §2.3.5, §3.3.2) (kernel). */
#ifndef LSDEM_SPECIMEN_H
#define LSDEM_SPECIMEN_H

#include "../base/lsdem_base.h"

#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

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

/* ------------------------------------------- local strain (local_strain.c) ---- */

/* Per-grain local strain (Falk & Langer 1998, PRE 57, 7192; the shear-band indicators of
 * report §3.5.3): the affine map F that best carries a grain's neighbour vectors d0_k
 * (reference configuration) to d_k (now), in the least-squares sense:
 *   X = sum d d0^T, Y = sum d0 d0^T, F = X Y^-1, D2min = sum_k |d_k - F d0_k|^2.
 * d0, d: n vectors each (3n doubles, world frame, length units, neighbour minus grain).
 * Strains are TENSION POSITIVE (continuum convention, unlike the specimen measures above):
 * small strain eps = (F + F^T)/2 - I or Green-Lagrange E = (F^T F - I)/2. */
typedef enum { LSDEM_STRAIN_SMALL = 0, LSDEM_STRAIN_GREEN = 1 } lsdem_strain_kind;
typedef struct {
  double F[9];        /* best-fit deformation gradient, row-major */
  double strain[9];   /* eps or E (symmetric) */
  double volumetric;  /* trace of strain */
  double shear;       /* von Mises shear invariant sqrt(e':e' / 2), e' the deviator */
  double d2min;       /* non-affine residual, the TOTAL over neighbours (length^2) */
  double rotation[4]; /* quaternion of R in the polar decomposition F = R U */
  double angle;       /* rotation angle of R in [0, pi] (radians) */
} lsdem_local_strain;
/* LSDEM_ERR_NUMERIC with every output NaN when the neighbourhood is singular: n < 3, the
 * d0 (nearly) coplanar or collinear (smallest eigenvalue of Y below 1e-10 of its largest),
 * or det F <= 0 (the neighbourhood turned inside out). */
lsdem_status lsdem_local_strain_fit(int n, const double *d0, const double *d,
                                    lsdem_strain_kind kind, lsdem_local_strain *out);
/* The measures of a deformation gradient F: out->F = F, strain of the kind, volumetric,
 * shear, rotation, angle (d2min untouched). LSDEM_ERR_NUMERIC with them NaN if det F <= 0. */
lsdem_status lsdem_strain_measures(const double F[9], lsdem_strain_kind kind,
                                   lsdem_local_strain *out);
/* Rotation angle in [0, pi] of a grain relative to its continuum: the angle of
 * (q qref^-1) qcont^-1, i.e. the grain's rotation since its reference orientation qref
 * with the local continuum's rotation qcont (lsdem_local_strain.rotation) taken out. */
double lsdem_rotation_from_continuum(const double q[4], const double qref[4],
                                     const double qcont[4]);


/* ------------------------------------------- force chains (chains.c) ---- */

/* Strong and weak contact networks (Radjai et al. 1998, PRL 80, 61; report §3.5.5): a
 * contact is STRONG when its normal force exceeds the mean over all n contacts. Returns the
 * count n, the mean, the strong count, their fraction of the contacts and their share of the
 * total normal force (sum over strong / sum over all; 0 when that sum is 0). */
typedef struct {
  int contacts, strong;
  double mean, strong_fraction, strong_share;
} lsdem_chain_stats;
void lsdem_strong_chains(int n, const double *fn, lsdem_chain_stats *out);

/* D50 of n grains of the given volumes (length^3): the diameter of the sphere of equal
 * volume at which half the grains' total volume (their mass, at one density) is finer, as a
 * sieve curve does, linear between consecutive grains of the sorted curve (each grain's
 * diameter at the middle of its share); 0 for n <= 0. Grains of zero volume count nothing. */
double lsdem_median_diameter(int n, const double *volume);

/* ------------------------------------------- shear bands (shearband.c) ---- */

/* Shear-band measurement (report §3.5.3): points (grain centres, world frame, length units)
 * carry a scalar indicator (rotation, von Mises shear, D2min, ...). A point is FLAGGED when
 * its value exceeds mean + k sd (population sd over the points with finite values; points
 * with non-finite values are never flagged). Up to two planes are fitted in turn, each to
 * the flagged points the earlier plane left (X bands):
 *  - RANSAC: `samples` planes through 3 flagged points drawn by a 64-bit LCG (Knuth's MMIX
 *    constants) started at `seed`; the plane with most flagged points within `threshold`
 *    of it wins (the first on ties);
 *  - refit: least squares (PCA): the plane through the inliers' centroid normal to the
 *    smallest-eigenvalue eigenvector of their covariance; inliers re-selected within
 *    `threshold` and refitted until the set no longer changes (at most 20 times).
 * The result depends only on the points' order and values, not on the machine's threads.
 * threshold should exceed half the band's width: the inliers are cut at it. */
typedef struct {
  double k;         /* flagging: value > mean + k sd (report: 2) */
  double threshold; /* inlier distance to a plane (length) */
  int planes;       /* 1 or 2 */
  int samples;      /* RANSAC samples per plane (> 0) */
  uint64_t seed;
} lsdem_shearband_params;
typedef struct {
  double normal[3];        /* unit normal pointing up (n_z >= 0; horizontal n: the first
                              nonzero of n_x, n_y positive) */
  double centre[3];        /* centroid of the inliers: a point of the plane */
  double dip;              /* degrees in [0, 90]: angle between the plane and the horizontal
                              (x-y) plane, acos(n_z) */
  double azimuth;          /* degrees in [0, 360): dip direction (the horizontal direction
                              in which the plane descends, that of (n_x, n_y)), from +x
                              counterclockwise; 0 for a horizontal plane */
  double inlier_fraction;  /* inliers / all flagged points */
  double thickness;        /* sqrt(12) x the sd of the inliers' signed distances: the width
                              of a uniformly filled slab (length) */
  int ninliers;
} lsdem_shearband_plane;
/* Flags, fits and classifies n points (x: 3n, value: n). Writes *nplanes (0..planes: a
 * plane needs 3 flagged points not on one line), plane[0..*nplanes-1], and per point
 * band[i] = the first plane p (1 or 2) within half its thickness of point i (flagged or
 * not), else 0. LSDEM_ERR_ARG for bad parameters, LSDEM_ERR_NOMEM. */
lsdem_status lsdem_shearband_fit(int n, const double *x, const double *value,
                                 const lsdem_shearband_params *p, lsdem_shearband_plane plane[2],
                                 int *nplanes, int *band);
/* The principal sizes of n >= 2 points (x: 3n): sizes[0] >= sizes[1] >= sizes[2] are
 * sqrt(12 l) of their covariance's eigenvalues l (the sides of a uniformly filled box of
 * that covariance: length, breadth, thickness); plane: their centroid, the unit axis of the
 * smallest pointing up with its dip and azimuth (as lsdem_shearband_fit's planes),
 * thickness sizes[2], ninliers n, inlier_fraction 1. LSDEM_ERR_ARG for n < 2,
 * LSDEM_ERR_NOMEM. */
lsdem_status lsdem_point_sizes(int n, const double *x, lsdem_shearband_plane *plane,
                               double sizes[3]);

/* Sheets in a point set: the planes of the micro-band count of a strain field
 * (tools/lsdem_bands.py, run through lsdem-shape bands). Planes are sought in turn among
 * the points not yet set aside: RANSAC as lsdem_shearband_fit's (`samples` planes through 3
 * points drawn by its LCG from `seed`, the one with most points within tol), then refitted
 * by least squares to the points within `slab` (>= tol: the band's whole thickness) until
 * that set no longer changes (at most 20 times). The plane is a SHEET when its points
 * within tol are at least min_length long and at least aspect times the slab's thickness
 * broad (length and breadth: lsdem_point_sizes of those points; thickness: sqrt(12) x the
 * sd of the slab's distances): a sheet, not a rod or a blob. Then its slab's points are set
 * aside and the next plane sought, until a plane is not a sheet, no plane has 3 points, or
 * cap sheets are found. */
typedef struct {
  double tol;        /* half-width of a sheet's slab of points (length) */
  double slab;       /* half-width of the refit's and the thickness's slab (>= tol) */
  double min_length; /* a sheet's points at least this long (length) */
  double aspect;     /* ... and at least this broad times its thickness */
  int samples;       /* RANSAC planes per sheet (> 0) */
  uint64_t seed;
} lsdem_sheet_params;
typedef struct {
  lsdem_shearband_plane plane; /* normal (up), centre, dip, azimuth, thickness (of the
                                  slab); ninliers: its points within tol; inlier_fraction:
                                  ninliers over all points */
  double length, breadth;      /* of its points within tol (lsdem_point_sizes) */
} lsdem_sheet;
/* The sheets of n points (x: 3n) into sheet[0..*nsheets-1]; label[i] the sheet whose points
 * within tol hold point i, else -1. The result depends only on the points' order and
 * values. LSDEM_ERR_ARG for bad parameters, LSDEM_ERR_NOMEM. */
lsdem_status lsdem_sheets_fit(int n, const double *x, const lsdem_sheet_params *p, int cap,
                              lsdem_sheet *sheet, int *nsheets, int *label);
/* Sheets found apart (say in the separate zones of a cut strain field) joined into planes:
 * in order of their point counts, largest first (ties: index order), a sheet joins the
 * first group whose leading sheet's normal lies within `angle` degrees of its own and whose
 * leading plane passes within `dist` of its centre, else leads a new group. Each group is
 * measured as one: its sheets' points (the points i with label[i] its sheets' indices: x
 * 3n, label n, as lsdem_sheets_fit's over all points) refitted (lsdem_point_sizes: centre,
 * normal, length, breadth, dip, azimuth), thickness its sheets' point-weighted mean; a group
 * at least min_length long is a BAND: band[0..*nbands-1] in the groups' order (at most ns).
 * group[k]: the band sheet k belongs to, else -1. LSDEM_ERR_ARG, LSDEM_ERR_NOMEM. */
lsdem_status lsdem_sheets_join(int n, const double *x, const int *label, int ns,
                               const lsdem_sheet *sheet, double angle, double dist,
                               double min_length, int *group, lsdem_sheet *band, int *nbands);

/* The band's width from the indicator's profile across a fitted plane (issue 35 item 3):
 * the finite values averaged in bins of width `bin` of the points' signed distance to the
 * plane (bins from the plane's centre outwards, one centred on it); the full width at half
 * maximum above the median of all finite values, from the highest bin within `reach` of
 * the plane outwards on both sides (each crossing interpolated linearly between bin
 * centres; empty bins skipped), into *fwhm (length; NaN when no bin is above the median, or
 * the profile does not fall to half on a side). *corrected = sqrt(fwhm^2 - kernel^2): the
 * width of a Gaussian band seen through a Gaussian smoothing of FWHM `kernel` (the
 * indicator's neighbourhood; 0: none), 0 when fwhm <= kernel. LSDEM_ERR_ARG for bin <= 0,
 * reach <= 0 or kernel < 0; LSDEM_ERR_NOMEM. */
lsdem_status lsdem_shearband_profile(int n, const double *x, const double *value,
                                     const lsdem_shearband_plane *plane, double bin,
                                     double reach, double kernel, double *fwhm,
                                     double *corrected);
/* Theoretical band inclinations from the horizontal in triaxial compression (sigma_1 axial:
 * the horizontal is the plane sigma_1 acts on; the band makes these angles with the sigma_3
 * direction), all in degrees from the friction angle phi and dilatancy angle psi in degrees:
 * angle[0] Coulomb 45 + phi/2, angle[1] Roscoe 45 + psi/2, angle[2] Arthur 45 + (phi+psi)/4. */
void lsdem_shearband_theory(double phi, double psi, double angle[3]);

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

/* Membrane bond force (bond_style lsdem/membrane): a net bond (lsdem_bond_axial_force,
 * undamped) with a tangential spring added. With d = xj - xi, u = d/|d|, a local
 * cylindrical frame at the bond midpoint (r = horizontal unit vector away from the axis
 * through axis[0..1], t = z x r hoop, z):
 *   normal spring      -kn (|d| - r0) u   (the net's axial spring)     on j
 *   tangential spring  -ks (e - (e.u) u),  e = (d.t - rest[0]) t + (d.z - rest[1]) z
 * The tangential spring resists the change of the bond's in-surface (hoop, axial) offset
 * from its rest value except along the bond, i.e. shear of the hexagonal pattern; it is
 * blind to radial motion (bulging) and to rigid rotation about / translation along the
 * axis, and needs no per-bond history. Writes the force on j (the force on i is -fj) and
 * returns the energy 0.5 kn (|d| - r0)^2 + 0.5 ks |e - (e.u)u|^2. */
double lsdem_membrane_bond_force(const double xi[3], const double xj[3], const double axis[2],
                                 double kn, double ks, double r0, const double rest[2],
                                 double fj[3]);


/* ------------------------------------------------ nets (net.c, net_file.c) ---- */

/* A net (report §4.4.2, Figure 4.6): balls of one radius on a plane lattice, joined by
 * permanent axial springs, some boundary balls clamped (anchors, never integrated).
 * Frame: the plane through `origin` spanned by e1 and e2 (e2 is made orthogonal to e1,
 * both unit), normal n = e1 x e2; a ball's height is (x - origin) . n, positive on the
 * normal's side. Lattices, with spacing a (the distance between bonded balls as built):
 *  - LSDEM_NET_SQUARE: n1 x n2 balls at origin + i a e1 + j a e2, bonds along e1 and e2;
 *  - LSDEM_NET_HEX: triangular lattice ("hexagonal pattern" of the report): rows j spaced
 *    a sqrt(3)/2 along e2, odd rows shifted by a/2 along e1; each ball bonded to its
 *    in-row neighbours and to the two nearest balls of the next row (6 bonds inside).
 * n1 = round(extent[0] / a) + 1 balls per row, n2 = round(extent[1] / row spacing) + 1
 * rows (extent[1] = 0: one row, a 1-D chain). Balls are numbered row by row, i fastest.
 * Clamp bits per ball: LSDEM_NET_EDGE_U0 (i = 0), _U1 (i = n1 - 1), _V0 (j = 0),
 * _V1 (j = n2 - 1); a ball is clamped when its bits meet the params' clamp mask.
 * Pretension: every bond's rest length is `rest` (< a pulls the net taut). */
enum { LSDEM_NET_SQUARE = 0, LSDEM_NET_HEX = 1 };
enum {
  LSDEM_NET_EDGE_U0 = 1, LSDEM_NET_EDGE_U1 = 2, LSDEM_NET_EDGE_V0 = 4, LSDEM_NET_EDGE_V1 = 8
};

typedef struct {
  int lattice;         /* LSDEM_NET_SQUARE or LSDEM_NET_HEX */
  double origin[3];    /* ball (0, 0) */
  double e1[3], e2[3]; /* in-plane directions (any length, not parallel) */
  double extent[2];    /* lengths along e1 and e2 to cover (>= 0) */
  double spacing;      /* a > 0 */
  double rest;         /* bond rest length r0 > 0 (pretension when r0 < a) */
  int clamp;           /* mask of LSDEM_NET_EDGE_* bits: boundary balls to clamp */
} lsdem_net_params;

typedef struct {
  int lattice, n1, n2, nballs, nbonds;
  double origin[3], e1[3], e2[3], normal[3]; /* unit e1, e2, n */
  double size[2];  /* footprint: ball in-plane coordinates lie in [0, size[0]] x [0, size[1]] */
  double spacing, rest;
  double *x;       /* 3 * nballs positions as built (NULL when read from a file) */
  long *id;        /* nballs atom IDs (set by the caller or read from a file; 0 = unset) */
  int *clamp;      /* nballs: 1 clamped, 0 free */
  int *bond;       /* 2 * nbonds ball indices (not IDs) */
} lsdem_net;

/* Generate the lattice (ids left 0). Allocates (free with lsdem_net_free). LSDEM_ERR_ARG
 * for a non-positive spacing or rest length, negative extents, parallel directions, or
 * more than 10^8 balls. */
lsdem_status lsdem_net_build(const lsdem_net_params *p, lsdem_net *net, lsdem_error *err);
void lsdem_net_free(lsdem_net *net);

/* The net's joints for bending (angle_style lsdem/net): every triple (p, b, q) of a ball b
 * and two of its bonded neighbours on opposite sides of it along one lattice line (x_p +
 * x_q = 2 x_b as built), each once with p < q: along both directions of a square lattice
 * and the three of a hexagonal one. *joint gets 3 * *njoints ball indices (malloc'ed; free
 * it); needs the positions as built (net->x). */
lsdem_status lsdem_net_joints(const lsdem_net *net, int **joint, int *njoints,
                              lsdem_error *err);

/* Height of x over the net's initial plane, (x - origin) . n, and in-plane coordinates
 * uv = ((x - origin) . e1, (x - origin) . e2). */
double lsdem_net_height(const lsdem_net *net, const double x[3], double uv[2]);

/* Which side of the net a point (a grain's centre) is on, the balls being at xball (3 per
 * ball, the net's order): over the footprint (0 <= u <= size[0], 0 <= v <= size[1]) it is
 * LSDEM_NET_THROUGH below the ball nearest to it in (u, v), LSDEM_NET_BEFORE at or above
 * it; beside the footprint LSDEM_NET_BEFORE on the normal's side of the initial plane
 * (height >= 0), LSDEM_NET_BESIDE below it (gone past the net around or over it). With the
 * normal pointing upslope, BEFORE is upslope of the net (retained). Cost: nballs. */
enum { LSDEM_NET_BESIDE = 0, LSDEM_NET_THROUGH = 1, LSDEM_NET_BEFORE = 2 };
int lsdem_net_side(const lsdem_net *net, const double *xball, const double x[3]);

/* The axis of a ball bond (nets and the membrane): d = xj - xi; returns L = |d| and
 * writes u = d / L (u = 0 unless L > 0). */
double lsdem_bond_axis(const double xi[3], const double xj[3], double u[3]);
/* The axial spring of every ball bond, the one formula of nets and the membrane: on j
 *   f_j = -(k stretch + w) u,   stretch = L - r0,
 * w the axial damping term c (v . u) of a net bond (0: none). Writes fj and returns the
 * spring energy 0.5 k stretch^2. */
double lsdem_bond_axial_force(const double u[3], double stretch, double k, double w,
                              double fj[3]);

/* Net bond force (bond_style lsdem/net), an axial spring with axial viscous damping:
 * with d = xj - xi, L = |d|, u = d / L, v = vj - vi,
 *   f_j = -(k (L - r0) + c (v . u)) u,   f_i = -f_j,
 * k a stiffness (force / length), c a damping coefficient (force time / length). Writes
 * fj, the stretch L - r0 into *stretch, and returns the spring energy 0.5 k (L - r0)^2
 * (zero force when L = 0). */
double lsdem_net_bond_force(const double xi[3], const double xj[3], const double vi[3],
                            const double vj[3], double k, double r0, double c, double fj[3],
                            double *stretch);

/* Power withdrawn by the net bond's damping force (lsdem_net_bond_force with this c):
 * c (v . u)^2 >= 0 (force times velocity; zero when L = 0). bond_style lsdem/net sums it
 * over the steps to the work of the damping forces (fix net/lsdem output 8). */
double lsdem_net_bond_damping_power(const double xi[3], const double xj[3], const double vi[3],
                                    const double vj[3], double c);

/* Net bending (angle_style lsdem/net): a joint of three balls along a lattice line, ball 2
 * in the middle, a = x1 - x2, b = x3 - x2, cos(theta) = a . b / (|a| |b|); the energy
 *   E = kb (1 + cos theta),
 * zero for a straight line (theta = pi) and kb (pi - theta)^2 / 2 to second order, so kb
 * (energy) is the joint's bending stiffness per radian squared: a chain of spacing s bends
 * like a beam of flexural rigidity EI = kb s. Writes the forces -dE/dx on balls 1 and 3
 * (ball 2 takes -(f1 + f3)) and returns E; zero forces when an arm has zero length. */
double lsdem_net_bend_force(const double x1[3], const double x2[3], const double x3[3],
                            double kb, double f1[3], double f3[3]);

/* Rupture criteria (bond_style lsdem/net ... break): by strain, (L - r0) / r0 > limit; by
 * force, the spring's tension k (L - r0) > limit (damping not counted). limit > 0. */
enum { LSDEM_NET_BREAK_NONE = 0, LSDEM_NET_BREAK_STRAIN = 1, LSDEM_NET_BREAK_FORCE = 2 };
int lsdem_net_bond_breaks(int mode, double limit, double k, double r0, double stretch);

/* Net files (net_file.c): the one text format lsdem-shape net writes and fix net/lsdem
 * reads (doc/fix_net_lsdem.rst):
 *   lsdem-net 1
 *   # comments anywhere (to the end of the line)
 *   lattice hex|square
 *   counts N1 N2
 *   origin X Y Z
 *   e1 X Y Z
 *   e2 X Y Z
 *   size U V
 *   spacing A
 *   rest R0
 *   balls N        then N lines: atom-ID clamp(0|1)
 *   bonds M        then M lines: atom-ID atom-ID
 * The normal is recomputed as e1 x e2. Reading checks the header, every count, unique
 * ball IDs, and that every bond joins two distinct balls of the file (LSDEM_ERR_FORMAT
 * naming the line). */
lsdem_status lsdem_net_write(const char *path, const lsdem_net *net, lsdem_error *err);
lsdem_status lsdem_net_read(const char *path, lsdem_net *net, lsdem_error *err);

/* The triaxial membrane's file (net_file.c, the same codec and line reader as the net
 * file): the triangles file lsdem-shape membrane writes and fix membrane/lsdem reads
 * (doc/fix_membrane_lsdem.rst):
 *   lsdem-membrane-triangles 1
 *   # comments anywhere
 *   axis CX CY
 *   specimen_radius RS
 *   sphere_radius RB RB_OUTER
 *   layers 1|2
 *   lateral_areas A_INNER A_OUTER
 *   vertices N       then N lines: atom-ID layer(0|1) end(0 middle, 1 bottom, 2 top)
 *   triangles N      then N lines: atom-ID atom-ID atom-ID layer
 *   cap_edges N      then N lines: atom-ID atom-ID layer end(1 bottom, 2 top)
 * Keywords in any order after the first line. Reading checks every value's range, that
 * every keyword came, and that triangles and cap edges name vertices of the file
 * (LSDEM_ERR_FORMAT naming the file and line). */
typedef struct {
  double axis[2], specimen_radius, sphere_radius[2], lateral_areas[2];
  int layers, nvertices, ntriangles, ncap_edges;
  long *vertex;      /* nvertices atom IDs */
  int *vertex_layer; /* 0 inner, 1 outer */
  int *vertex_end;   /* 0 middle, 1 bottom, 2 top */
  long *triangle;    /* 3 per triangle: atom IDs */
  int *triangle_layer;
  long *cap_edge;    /* 2 per edge: atom IDs */
  int *cap_layer;
  int *cap_end;      /* 1 bottom, 2 top */
} lsdem_membrane_file;

/* Prints the file to f (the caller opens and closes it), `about` (NULL: none) as a comment
 * line after the first. */
void lsdem_membrane_file_print(FILE *f, const lsdem_membrane_file *mf, const char *about);
lsdem_status lsdem_membrane_file_read(const char *path, lsdem_membrane_file *mf,
                                      lsdem_error *err);
void lsdem_membrane_file_free(lsdem_membrane_file *mf);

#ifdef __cplusplus
}
#endif
#endif /* LSDEM_SPECIMEN_H */
