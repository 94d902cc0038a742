/* glue.c -- a pair's contact manifold as impulse contacts: adjacent points glued into one
 * contact (report §4.3.3). The rule is in lsdem_impulse.h (lsdem_glue_params). */
#include "lsdem_impulse.h"

#include <math.h>
#include <string.h>

void lsdem_glue_params_default(lsdem_glue_params *g)
{
  g->distance = 0.0;
  g->max_angle = 15.0 * M_PI / 180.0;
}

static int joins(const lsdem_contact_point *seed, const lsdem_contact_point *p,
                 double dist2, double cos_max)
{
  double d[3];
  lsdem_sub3(p->point, seed->point, d);
  return lsdem_dot3(d, d) <= dist2 && lsdem_dot3(p->normal, seed->normal) >= cos_max;
}

/* Adds point p to contact c with its area as weight (sums, normalised by finish). */
static double accumulate(lsdem_impulse_contact *c, const lsdem_contact_point *p)
{
  for (int i = 0; i < 3; i++) {
    c->point[i] += p->area * p->point[i];
    c->normal[i] += p->area * p->normal[i];
  }
  c->depth = lsdem_max(p->depth, c->depth);
  return p->area;
}

static void finish(lsdem_impulse_contact *c, double area)
{
  const double len = sqrt(lsdem_dot3(c->normal, c->normal));
  for (int i = 0; i < 3; i++) {
    c->point[i] /= area;
    c->normal[i] /= len;
  }
}

int lsdem_impulse_glue(const lsdem_manifold *m, int32_t a, int32_t b, double mu, double e,
                       const lsdem_glue_params *g, lsdem_impulse_contact *out,
                       int32_t *group, lsdem_error *err)
{
  if (!(g->distance >= 0.0) || !isfinite(g->distance) ||
      !(g->max_angle >= 0.0 && g->max_angle < 0.5 * M_PI) || !group) {
    lsdem_fail(err, LSDEM_ERR_ARG,
               "gluing: distance %g (>= 0), max_angle %g (in [0, pi/2)) or group storage "
               "missing",
               g->distance, g->max_angle);
    return -1;
  }
  const double dist2 = g->distance * g->distance, cos_max = cos(g->max_angle);
  int n = 0;
  for (int k = 0; k < m->n; k++) group[k] = -1;
  for (int k = 0; k < m->n; k++) {
    if (group[k] >= 0) continue; /* glued to an earlier seed */
    const lsdem_contact_point *seed = &m->point[k];
    lsdem_impulse_contact *c = &out[n];
    memset(c, 0, sizeof *c);
    c->a = a;
    c->b = b;
    c->mu = mu;
    c->restitution = e;
    group[k] = n;
    double area = accumulate(c, seed);
    for (int j = k + 1; j < m->n; j++)
      if (group[j] < 0 && joins(seed, &m->point[j], dist2, cos_max)) {
        group[j] = n;
        area += accumulate(c, &m->point[j]);
      }
    finish(c, area);
    n++;
  }
  return n;
}
