/* wall_map.c -- per-triangle force maps of mesh and terrain walls (lsdem_boundary.h):
 * exact integer sums of quantised terms. */
#include "lsdem_boundary.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

lsdem_status lsdem_wall_map_init(lsdem_wall_map *m, int64_t ntris, lsdem_quantum force_q,
                                 double length_scale, lsdem_error *err)
{
  memset(m, 0, sizeof *m);
  if (ntris <= 0) return lsdem_fail(err, LSDEM_ERR_ARG, "wall map: the wall keeps no triangles");
  if (!(force_q.q > 0.0) || !(length_scale > 0.0))
    return lsdem_fail(err, LSDEM_ERR_ARG, "wall map: force quantum and length scale must be > 0");
  m->sum = calloc((size_t)ntris * LSDEM_MAP_FIELDS, sizeof(int64_t));
  if (!m->sum)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "wall map: cannot allocate %lld triangles' sums",
                      (long long)ntris);
  m->ntris = ntris;
  /* force_q's scale F: q = 2^(floor(log2 F) + 1 - LSDEM_EXACT_SUM_BITS) */
  const double force_scale = ldexp(force_q.q, LSDEM_EXACT_SUM_BITS - 1);
  m->force_q = force_q;
  m->work_q = lsdem_quantum_for(force_scale * length_scale);
  return LSDEM_OK;
}

void lsdem_wall_map_free(lsdem_wall_map *m)
{
  free(m->sum);
  memset(m, 0, sizeof *m);
}

/* x as a whole number of quanta (exact: lsdem_quantize makes it a multiple of q) */
static int64_t quanta(double x, lsdem_quantum q)
{
  return (int64_t)(lsdem_quantize(x, q) * q.inv_q);
}

void lsdem_wall_map_add(lsdem_wall_map *m, int64_t tri, const double force[3],
                        const double normal[3], double slide, int began)
{
  if (tri < 0 || tri >= m->ntris) return;
  const double fn = lsdem_dot3(force, normal);
  double ft[3];
  for (int d = 0; d < 3; d++) ft[d] = force[d] - fn * normal[d];
  int64_t *s = m->sum;
  const int64_t n = m->ntris;
  s[LSDEM_MAP_FN * n + tri] += quanta(fn, m->force_q);
  s[LSDEM_MAP_FT * n + tri] += quanta(sqrt(lsdem_dot3(ft, ft)), m->force_q);
  s[LSDEM_MAP_CONTACTS * n + tri] += 1;
  s[LSDEM_MAP_IMPACTS * n + tri] += began ? 1 : 0;
  s[LSDEM_MAP_WORK * n + tri] += quanta(fn * slide, m->work_q);
}

double lsdem_wall_map_value(const lsdem_wall_map *m, int field, int64_t t)
{
  const double v = (double)m->sum[field * m->ntris + t];
  switch (field) {
  case LSDEM_MAP_FN:
  case LSDEM_MAP_FT: return v * m->force_q.q;
  case LSDEM_MAP_WORK: return v * m->work_q.q;
  default: return v;
  }
}

void lsdem_wall_map_new_interval(lsdem_wall_map *m)
{
  const int64_t n = m->ntris;
  memset(m->sum + LSDEM_MAP_FN * n, 0, (size_t)n * sizeof(int64_t));
  memset(m->sum + LSDEM_MAP_FT * n, 0, (size_t)n * sizeof(int64_t));
  memset(m->sum + LSDEM_MAP_CONTACTS * n, 0, (size_t)n * sizeof(int64_t));
  m->steps = 0;
}
