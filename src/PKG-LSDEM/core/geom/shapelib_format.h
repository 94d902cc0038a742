/* shapelib_format.h -- the shape-library file format shared by its reader (geom/shapelib.c,
 * the kernel) and its writer (prep/library_write.c): field offsets, byte access, checksum
 * and the invariants both check (format byte by byte in doc/shape_library.rst).
 * Private to the core: not part of the public API. */
#ifndef LSDEM_SHAPELIB_FORMAT_H
#define LSDEM_SHAPELIB_FORMAT_H
#include "lsdem_geom.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/* --------------------------------------------------------------- constants ---- */

static const char LIB_MAGIC[8] __attribute__((unused)) = {'L', 'S', 'D', 'E', 'M', 'L', 'I', 'B'};
enum {
  LIB_VERSION = 1,
  LIB_HEADER_SIZE = 64,
  LIB_ENTRY_SIZE = 360,
  LIB_NAME_SIZE = LSDEM_LIBRARY_NAME_MAX, /* including the terminating NUL */
  LIB_NARRAYS = 5
};

/* Header field offsets. */
enum { H_MAGIC = 0, H_VERSION = 8, H_HSIZE = 12, H_ESIZE = 16, H_COUNT = 20, H_TOC = 24,
       H_FSIZE = 32, H_SUM = 56 };

/* TOC entry field offsets. */
enum { E_KIND = 0, E_INVERTED = 4, E_A = 8, E_N = 32, E_NNODES = 44, E_H = 48, E_ORIGIN = 56,
       E_NCLUSTERS = 80, E_RADIUS = 88, E_VOLUME = 96, E_INERTIA = 104, E_SEC_OFF = 128,
       E_SEC_LEN = 136, E_SEC_SUM = 144, E_ARRAYS = 152, E_NAME = 232 };

/* The arrays of a shape section, in the order the writer lays them out: the small
 * cluster tables first, the level-set grid last, so checking clusters at open time
 * leaves the grid pages untouched. */
enum { A_CSTART = 0, A_CSPHERE, A_NODES, A_AREA, A_PHI };
_Static_assert(sizeof(int) == 4 && sizeof(double) == 8 && sizeof(float) == 4,
               "the library format stores int32, float32 and float64 arrays in place");

/* ------------------------------------------------------ bytes and checksums ---- */

/* FNV-1a, 64-bit: h <- (h xor byte) * prime, starting from the offset basis. */
#define FNV_BASIS 0xcbf29ce484222325ULL
#define FNV_PRIME 0x100000001b3ULL

static inline uint64_t fnv1a_update(uint64_t h, const void *data, size_t len)
{
  const unsigned char *p = (const unsigned char *)data;
  for (size_t i = 0; i < len; i++) h = (h ^ p[i]) * FNV_PRIME;
  return h;
}

static inline int host_is_little_endian(void)
{
  const uint16_t one = 1;
  unsigned char b;
  memcpy(&b, &one, 1);
  return b == 1;
}

/* Field access in a byte buffer (the host is little-endian, checked before use). */
static inline uint32_t get_u32(const unsigned char *p) { uint32_t v; memcpy(&v, p, 4); return v; }
static inline int32_t get_i32(const unsigned char *p) { int32_t v; memcpy(&v, p, 4); return v; }
static inline uint64_t get_u64(const unsigned char *p) { uint64_t v; memcpy(&v, p, 8); return v; }
static inline double get_f64(const unsigned char *p) { double v; memcpy(&v, p, 8); return v; }
static inline void put_u32(unsigned char *p, uint32_t v) { memcpy(p, &v, 4); }
static inline void put_i32(unsigned char *p, int32_t v) { memcpy(p, &v, 4); }
static inline void put_u64(unsigned char *p, uint64_t v) { memcpy(p, &v, 8); }
static inline void put_f64(unsigned char *p, double v) { memcpy(p, &v, 8); }

static inline uint64_t pad8(uint64_t n) { return (n + 7u) & ~(uint64_t)7u; }

/* -------------------------------------------------------- shape invariants ---- */

/* Number of level-set samples of a grid shape, 0 for analytic kinds or bad dims. */
static inline uint64_t grid_samples(const lsdem_shape *s)
{
  if (s->sdf.kind != LSDEM_SDF_GRID) return 0;
  uint64_t total = 1;
  for (int k = 0; k < 3; k++) {
    if (s->sdf.grid.n[k] < 2) return 0;
    total *= (uint64_t)s->sdf.grid.n[k];
    if (total > LSDEM_LIBRARY_MAX_SAMPLES) return 0;
  }
  return total;
}

/* Byte length of each array of a shape, from its counts. */
static inline void array_lengths(const lsdem_shape *s, uint64_t len[LIB_NARRAYS])
{
  len[A_CSTART] = 4u * ((uint64_t)s->nclusters + 1u);
  len[A_CSPHERE] = 32u * (uint64_t)s->nclusters;
  len[A_NODES] = 24u * (uint64_t)s->nnodes;
  len[A_AREA] = 8u * (uint64_t)s->nnodes;
  len[A_PHI] = 4u * grid_samples(s);
}

static inline const void *array_data(const lsdem_shape *s, int a)
{
  static const int no_clusters[1] = {0};
  switch (a) {
  case A_CSTART: return s->cluster_start ? (const void *)s->cluster_start : no_clusters;
  case A_CSPHERE: return s->cluster_sphere;
  case A_NODES: return s->nodes;
  case A_AREA: return s->node_area;
  default: return s->sdf.grid.phi;
  }
}

static inline int all_finite(const double *v, int n)
{
  for (int i = 0; i < n; i++)
    if (!isfinite(v[i])) return 0;
  return 1;
}

/* Parameters a[0..n) an analytic kind uses (sphere R; cylinder R, half-length; box
 * half-extents; ellipsoid semi-axes). */
static inline int analytic_param_count(lsdem_sdf_kind kind)
{
  switch (kind) {
  case LSDEM_SDF_SPHERE: return 1;
  case LSDEM_SDF_CYLINDER: return 2;
  case LSDEM_SDF_BOX:
  case LSDEM_SDF_ELLIPSOID: return 3;
  default: return 0;
  }
}

/* Scalar fields shared by the writer's and the reader's checks. Returns the name of the
 * first bad field, or NULL. */
static inline const char *bad_scalar_field(const lsdem_shape *s)
{
  /* Planes are not grains; superellipsoids need exponents the format does not hold
   * (store them as grids). */
  if (s->sdf.kind < LSDEM_SDF_GRID || s->sdf.kind > LSDEM_SDF_ELLIPSOID ||
      s->sdf.kind == LSDEM_SDF_PLANE)
    return "kind (grid, sphere, cylinder, box or ellipsoid; a superellipsoid as a grid)";
  if (s->sdf.inverted != 0 && s->sdf.inverted != 1) return "inverted (0 or 1)";
  if (!all_finite(s->sdf.a, 3)) return "analytic parameters (not finite)";
  for (int k = 0; k < analytic_param_count(s->sdf.kind); k++)
      if (!(s->sdf.a[k] > 0.0)) return "analytic parameters (must be > 0: a bounded solid)";
  if (s->sdf.kind == LSDEM_SDF_GRID) {
    if (grid_samples(s) == 0) return "grid dims (each >= 2, product <= 2^31-1)";
    if (!(s->sdf.grid.h > 0.0) || !isfinite(s->sdf.grid.h)) return "grid spacing (> 0)";
    if (!all_finite(s->sdf.grid.origin, 3)) return "grid origin (not finite)";
  } else if (s->sdf.grid.n[0] || s->sdf.grid.n[1] || s->sdf.grid.n[2]) {
    return "grid dims (must be 0 for an analytic shape)";
  }
  if (s->nnodes < 0 || s->nnodes > LSDEM_LIBRARY_MAX_NODES) return "nnodes (0 .. 2^26)";
  if (s->nclusters < 0 || s->nclusters > s->nnodes || (s->nnodes > 0) != (s->nclusters > 0))
    return "nclusters (1..nnodes, or 0 without nodes)";
  if (!(s->radius >= 0.0) || !isfinite(s->radius)) return "radius (finite, >= 0)";
  /* a grain's mass and moments are the density times these: zero gives a NaN step */
  if (!(s->volume > 0.0) || !isfinite(s->volume)) return "volume (finite, > 0)";
  for (int k = 0; k < 3; k++)
    if (!(s->inertia[k] > 0.0) || !isfinite(s->inertia[k]))
      return "inertia (principal moments finite, > 0)";
  return NULL;
}

/* Cluster c owns nodes [start[c], start[c+1]): start[0] = 0, strictly increasing,
 * start[nclusters] = nnodes. Returns the first bad index or -1. */
static inline int bad_cluster_start(const int *start, int nclusters, int nnodes)
{
  if (!start) return nclusters == 0 ? -1 : 0; /* a writer may omit {0} without nodes */
  if (start[0] != 0) return 0;
  for (int c = 0; c < nclusters; c++)
    if (start[c + 1] <= start[c]) return c + 1;
  if (start[nclusters] != nnodes) return nclusters;
  return -1;
}
#endif
