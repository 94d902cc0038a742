/* thin_features.c -- ridges and slots of a wall narrower than a band can hold (lsdem-shape
 * wall/terrain's report; fix wall/lsdem's time-step bound for thin walls): from each
 * triangle's centroid a ray along the inward normal (into the solid) and one along the
 * outward normal (into the open side); a ray that meets the surface again within `limit`
 * marks the triangle as part of a ridge (solid thinner than limit) or a slot (a gap
 * narrower than limit). Marked triangles joined by edges, or facing each other across the
 * feature, are one feature. Rays meet triangles found through the band's brick lists
 * (every triangle through a point of a brick is listed for it). */
#include "lsdem_geom.h"
#include "ray_triangle.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Distance along unit d from o to triangle t, or HUGE_VAL when the ray misses it. */
static double ray_triangle(const lsdem_band *b, int32_t t, const double o[3], const double d[3])
{
  const int32_t *v = &b->tris[3 * (int64_t)t];
  const double s = lsdem_ray_triangle(o, d, &b->verts[3 * (int64_t)v[0]],
                                      &b->verts[3 * (int64_t)v[1]], &b->verts[3 * (int64_t)v[2]]);
  return s > 0.0 ? s : HUGE_VAL;
}

/* Nearest hit of the ray from o along d within limit on a triangle other than self (in
 * *hit, else HUGE_VAL and -1). */
static double ray_hit(const lsdem_band *b, int32_t self, const double o[3], const double d[3],
                      double limit, int32_t *hit)
{
  int lo[3], hi[3];
  for (int a = 0; a < 3; a++) {
    const double e = o[a] + limit * d[a];
    const double u0 = (fmin(o[a], e) - b->origin[a]) / b->h, u1 = (fmax(o[a], e) - b->origin[a]) / b->h;
    lo[a] = (int)floor(u0) >> LSDEM_BAND_BRICK_LOG2, hi[a] = (int)floor(u1) >> LSDEM_BAND_BRICK_LOG2;
    lo[a] = lo[a] < 0 ? 0 : lo[a], hi[a] = hi[a] >= b->nb[a] ? b->nb[a] - 1 : hi[a];
  }
  double best = HUGE_VAL;
  *hit = -1;
  for (int z = lo[2]; z <= hi[2]; z++)
    for (int y = lo[1]; y <= hi[1]; y++)
      for (int x = lo[0]; x <= hi[0]; x++) {
        const int32_t k = b->index[x + (int64_t)b->nb[0] * (y + (int64_t)b->nb[1] * z)];
        if (k < 0) continue;
        for (int64_t e = b->brick_tri_start[k]; e < b->brick_tri_start[k + 1]; e++) {
          const int32_t t = b->brick_tris[e];
          const double s = t != self ? ray_triangle(b, t, o, d) : HUGE_VAL;
          if (s < best) best = s, *hit = t;
        }
      }
  if (best < limit) return best;
  *hit = -1;
  return HUGE_VAL;
}

/* Width across triangle t into the solid (ridge, side -1) or the open side (slot, +1),
 * the triangle across in *hit. */
static double width_across(const lsdem_band *b, int32_t t, int side, double limit,
                           int32_t *hit)
{
  const int32_t *v = &b->tris[3 * (int64_t)t];
  double c[3], e1[3], e2[3], n[3];
  for (int a = 0; a < 3; a++)
    c[a] = (b->verts[3 * (int64_t)v[0] + a] + b->verts[3 * (int64_t)v[1] + a] +
            b->verts[3 * (int64_t)v[2] + a]) / 3.0;
  lsdem_sub3(&b->verts[3 * (int64_t)v[1]], &b->verts[3 * (int64_t)v[0]], e1);
  lsdem_sub3(&b->verts[3 * (int64_t)v[2]], &b->verts[3 * (int64_t)v[0]], e2);
  lsdem_cross3(e1, e2, n);
  const double len = sqrt(lsdem_dot3(n, n));
  *hit = -1;
  if (!(len > 0.0)) return HUGE_VAL;
  for (int a = 0; a < 3; a++) n[a] *= side / len;
  return ray_hit(b, t, c, n, limit, hit);
}

lsdem_status lsdem_band_thin_features(const lsdem_band *b, double limit,
                                      lsdem_thin_feature **out, int *nout, lsdem_error *err)
{
  *out = NULL, *nout = 0;
  if (b->ntris <= 0 || !b->nbr || b->heights)
    return lsdem_fail(err, LSDEM_ERR_ARG, "thin features: the band keeps no surface");
  const size_t nt = (size_t)b->ntris;
  double *across = malloc(nt * sizeof(double));
  int32_t *hit = malloc(nt * sizeof(int32_t)), *stack = malloc(nt * sizeof(int32_t));
  char *seen = calloc(nt, 1);
  lsdem_thin_feature *f = NULL;
  int nf = 0, cap = 0;
  lsdem_status st = across && hit && stack && seen ? LSDEM_OK
                                            : lsdem_fail(err, LSDEM_ERR_NOMEM, "thin features: "
                                                         "out of memory (%lld triangles)",
                                                         (long long)nt);
  for (int kind = 0; kind < 2 && st == LSDEM_OK; kind++) { /* 0 ridges, 1 slots */
    for (size_t t = 0; t < nt; t++)
      across[t] = width_across(b, (int32_t)t, kind ? 1 : -1, limit, &hit[t]);
    memset(seen, 0, nt);
    for (size_t t0 = 0; t0 < nt && st == LSDEM_OK; t0++) {
      if (seen[t0] || across[t0] == HUGE_VAL) continue;
      if (nf == cap) { /* grow the list */
        cap = cap ? 2 * cap : 16;
        lsdem_thin_feature *g = realloc(f, (size_t)cap * sizeof *g);
        if (!g) {
          st = lsdem_fail(err, LSDEM_ERR_NOMEM, "thin features: out of memory");
          break;
        }
        f = g;
      }
      lsdem_thin_feature *ft = &f[nf++];
      memset(ft, 0, sizeof *ft);
      ft->ridge = kind == 0;
      ft->thinnest = HUGE_VAL;
      int64_t top = 0;
      stack[top++] = (int32_t)t0, seen[t0] = 1;
      while (top > 0) { /* the marked triangles joined to t0 by edges or across */
        const int32_t t = stack[--top];
        ft->ntris++;
        if (across[t] < ft->thinnest) ft->thinnest = across[t], ft->tri = t;
        const int32_t next[4] = {b->nbr[3 * (int64_t)t], b->nbr[3 * (int64_t)t + 1],
                                 b->nbr[3 * (int64_t)t + 2], hit[t]};
        for (int e = 0; e < 4; e++) {
          const int32_t u = next[e];
          if (u >= 0 && !seen[u] && across[u] != HUGE_VAL) stack[top++] = u, seen[u] = 1;
        }
      }
      const int32_t *v = &b->tris[3 * (int64_t)ft->tri];
      for (int a = 0; a < 3; a++)
        ft->at[a] = (b->verts[3 * (int64_t)v[0] + a] + b->verts[3 * (int64_t)v[1] + a] +
                     b->verts[3 * (int64_t)v[2] + a]) / 3.0;
    }
  }
  free(across), free(hit), free(stack), free(seen);
  if (st != LSDEM_OK) {
    free(f);
    return st;
  }
  *out = f, *nout = nf;
  return LSDEM_OK;
}
