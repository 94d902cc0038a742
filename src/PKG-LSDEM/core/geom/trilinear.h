/* trilinear.h -- the trilinear cell of report Algorithm 1, shared by the dense grids
 * (levelset.c) and the narrow bands (band.c): one implementation of the formula.
 * Private to core/geom. */
#ifndef LSDEM_GEOM_TRILINEAR_H
#define LSDEM_GEOM_TRILINEAR_H

#include <math.h>
#include <stddef.h>

/* The 8 samples of the cell whose (0,0,0) sample is at p, in a block of samples laid out
 * x fastest with row stride sy and plane stride sz (a dense grid, a grain brick, a band
 * brick), in trilinear_cell's order. */
static inline void load_cell_strided(const float *p, size_t sy, size_t sz, float v[8])
{
  v[0] = p[0];
  v[1] = p[1];
  v[2] = p[sy];
  v[3] = p[sy + 1];
  v[4] = p[sz];
  v[5] = p[sz + 1];
  v[6] = p[sz + sy];
  v[7] = p[sz + sy + 1];
}

/* Trilinear interpolation in one cell from its 8 samples v (x fastest: v000, v100, v010,
 * v110, v001, v101, v011, v111) at fractions f (report Algorithm 1, written as nested
 * lerps). When du is not NULL it receives the derivative with respect to the grid
 * coordinates (per grid spacing, not per length). Inlined into each caller, so the
 * value-only path carries no gradient code. */
static inline double trilinear_cell(const float v[8], const double f[3], double du[3])
{
  const double v000 = v[0], v100 = v[1], v010 = v[2], v110 = v[3];
  const double v001 = v[4], v101 = v[5], v011 = v[6], v111 = v[7];
  const double fx = f[0], fy = f[1], fz = f[2];
  /* lerp along x on the four cell edges */
  const double e00 = v000 + fx * (v100 - v000), e10 = v010 + fx * (v110 - v010);
  const double e01 = v001 + fx * (v101 - v001), e11 = v011 + fx * (v111 - v011);
  /* then along y on the two faces, then along z */
  const double f0 = e00 + fy * (e10 - e00), f1 = e01 + fy * (e11 - e01);
  if (du) {
    const double gx0 = (v100 - v000) + fy * ((v110 - v010) - (v100 - v000));
    const double gx1 = (v101 - v001) + fy * ((v111 - v011) - (v101 - v001));
    du[0] = gx0 + fz * (gx1 - gx0);
    du[1] = (e10 - e00) + fz * ((e11 - e01) - (e10 - e00));
    du[2] = f1 - f0;
  }
  return f0 + fz * (f1 - f0);
}

/* Unit gradient from the raw trilinear derivative (+x when it vanishes); h cancels. */
static inline void unit_gradient(const double du[3], double grad[3])
{
  const double n2 = du[0] * du[0] + du[1] * du[1] + du[2] * du[2];
  if (n2 > 0.0) {
    const double s = 1.0 / sqrt(n2);
    grad[0] = du[0] * s;
    grad[1] = du[1] * s;
    grad[2] = du[2] * s;
  } else {
    grad[0] = 1.0;
    grad[1] = grad[2] = 0.0;
  }
}

#endif /* LSDEM_GEOM_TRILINEAR_H */
