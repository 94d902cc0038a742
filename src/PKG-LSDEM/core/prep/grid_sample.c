/* grid_sample.c -- making signed-distance grids: allocating a grid over a box and
 * sampling an SDF onto it (preparation; the kernel only reads grids, geom/levelset.c). */
#include "lsdem_prep.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

lsdem_status lsdem_grid_alloc(const double lo[3], const double hi[3], double h, int margin,
                              lsdem_grid *g, float **values, lsdem_error *err)
{
  if (!lo || !hi || !g || !values) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  if (!(h > 0.0) || !isfinite(h))
    return lsdem_fail(err, LSDEM_ERR_ARG, "grid spacing h = %g: must be positive", h);
  if (margin < 0) return lsdem_fail(err, LSDEM_ERR_ARG, "margin %d is negative", margin);
  lsdem_grid out = {{0, 0, 0}, h, {0, 0, 0}, NULL, 0.0, 0.0};
  for (int a = 0; a < 3; a++) {
    const double span = hi[a] - lo[a];
    if (!isfinite(lo[a]) || !isfinite(span) || span < 0.0)
      return lsdem_fail(err, LSDEM_ERR_ARG, "grid box axis %d: [%g, %g] is not a range", a,
                        lo[a], hi[a]);
    /* enough cells to reach hi, tolerating round-off in span/h */
    const double cells = ceil(span / h * (1.0 - 1e-12));
    const double total = (cells < 1.0 ? 1.0 : cells) + 1.0 + 2.0 * margin;
    if (total > (double)(INT32_MAX / 4))
      return lsdem_fail(err, LSDEM_ERR_NOMEM, "grid axis %d needs %.0f samples", a, total);
    out.n[a] = (int)total;
    out.origin[a] = lo[a] - margin * h;
  }
  const size_t n01 = (size_t)out.n[0] * (size_t)out.n[1];
  if (n01 > SIZE_MAX / sizeof(float) / (size_t)out.n[2])
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "grid size %d x %d x %d overflows", out.n[0],
                      out.n[1], out.n[2]);
  float *phi = malloc(n01 * (size_t)out.n[2] * sizeof(float));
  if (!phi)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate a %d x %d x %d grid", out.n[0],
                      out.n[1], out.n[2]);
  out.phi = phi;
  *g = out;
  *values = phi;
  return LSDEM_OK;
}

lsdem_status lsdem_grid_sample(const lsdem_sdf *s, const double lo[3], const double hi[3],
                               double h, int margin, lsdem_grid *g, lsdem_error *err)
{
  if (!s) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL SDF");
  if (s->kind == LSDEM_SDF_SUPERELLIPSOID && !s->inverted) /* no closed-form distance */
    return lsdem_grid_from_star(lsdem_superellipsoid_radius, s, lo, hi, h, margin, g, err);
  lsdem_grid out;
  float *phi;
  const lsdem_status st = lsdem_grid_alloc(lo, hi, h, margin, &out, &phi, err);
  if (st != LSDEM_OK) return st;
  double grad[3];
  size_t m = 0;
  for (int k = 0; k < out.n[2]; k++)
    for (int j = 0; j < out.n[1]; j++)
      for (int i = 0; i < out.n[0]; i++) {
        const double p[3] = {out.origin[0] + h * i, out.origin[1] + h * j,
                             out.origin[2] + h * k};
        const double v = lsdem_sdf_eval(s, p, grad);
        if (isnan(v)) {
          lsdem_grid_free(&out);
          return lsdem_fail(err, LSDEM_ERR_NUMERIC, "the SDF is NaN at (%g, %g, %g)", p[0],
                            p[1], p[2]);
        }
        /* an unbounded SDF may exceed float range far away; keep values finite */
        phi[m++] = (float)fmax(fmin(v, (double)FLT_MAX), -(double)FLT_MAX);
      }
  *g = out;
  return LSDEM_OK;
}
