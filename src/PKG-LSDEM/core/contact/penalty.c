/* penalty.c -- the penalty contact law of LS-DEM (report eqs 2.2-2.16) on a contact
 * manifold (lsdem_contact.h): per point a normal spring with optional viscous damping, a
 * tangential spring carried in per-node shear history, the Coulomb cap, and the sums of
 * force and torque on both grains; the formulas at one point are point.h's. */
#include "point.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

/* What one evaluation shares between its points. Parameters and the running sums are
 * held by value, so the contact code reads and accumulates in memory that nothing else
 * aliases (passed as restrict). */
typedef struct {
  lsdem_penalty_law law;
  double dt, stride;
  double xa[3];
  int64_t step;
  const lsdem_shear_hist *hist_in; /* sorted by node; walked forward once (merge) */
  int n_in, cursor;
  lsdem_shear_hist *hist_out;
  int n_out;
  double weight; /* sum of normal-force magnitudes, for the mean contact point */
  lsdem_contact_result sum;
} law_ctx;

/* History entry of `node` in hist_in, or NULL. Nodes are visited in increasing order,
 * so the cursor only moves forward: O(1) amortised per call. */
static const lsdem_shear_hist *find_history(law_ctx *restrict c, int node)
{
  while (c->cursor < c->n_in && c->hist_in[c->cursor].node < node) c->cursor++;
  if (c->cursor < c->n_in && c->hist_in[c->cursor].node == node)
    return &c->hist_in[c->cursor];
  return NULL;
}

/* Points computed together, at most: each step below is a short loop whose iterations
 * are independent, so that the points' long chains of dependent arithmetic (a division
 * in Z, the cap's square root) overlap. */
enum { LAW_BATCH = 64 };

/* Normal force (law_normal) of each point, with its arm ra, relative tangential velocity
 * vt and fn n in f. */
static void normal_forces(const law_ctx *restrict c, const lsdem_contact_point *restrict pt,
                          int n, double *restrict fn_out, double *restrict ra,
                          double *restrict vt, double *restrict f)
{
  for (int m = 0; m < n; m++)
    fn_out[m] = law_normal(&c->law, c->stride, c->xa, &pt[m], &ra[3 * m], &vt[3 * m],
                           &f[3 * m]);
}

/* Shear springs carried over (law_carried_shear), each point's from its entry in hist_in. */
static void carried_shear(law_ctx *restrict c, const lsdem_contact_point *restrict pt, int n,
                          double *restrict s, int *restrict fresh)
{
  for (int m = 0; m < n; m++)
    fresh[m] = law_carried_shear(find_history(c, pt[m].node), c->step, pt[m].normal, &s[3 * m]);
}

/* Tangential forces (law_tangential) added to f, and their history entries. */
static void tangential_forces(law_ctx *restrict c, const lsdem_contact_point *restrict pt,
                              int n, const double *restrict fn, const double *restrict vt,
                              double *restrict s, const int *restrict fresh, double *restrict f)
{
  for (int m = 0; m < n; m++) {
    law_tangential(&c->law, c->stride, c->dt, pt[m].area, fn[m], &vt[3 * m], &s[3 * m],
                   fresh[m], &f[3 * m]);
    if (c->hist_out)
      law_history(&c->hist_out[c->n_out++], pt[m].node, c->step, &s[3 * m], pt[m].normal);
  }
}

/* n (<= LAW_BATCH) points, accumulated into the sums in node order (eqs 2.14-2.16: force
 * and torque on A; B's reaction torque follows at the end). */
static void apply_points(law_ctx *restrict c, const lsdem_contact_point *restrict pt, int n)
{
  double fn[LAW_BATCH], ra[3 * LAW_BATCH], vt[3 * LAW_BATCH], f[3 * LAW_BATCH];
  normal_forces(c, pt, n, fn, ra, vt, f);
  if (c->law.mu > 0.0) {
    double s[3 * LAW_BATCH];
    int fresh[LAW_BATCH];
    carried_shear(c, pt, n, s, fresh);
    tangential_forces(c, pt, n, fn, vt, s, fresh, f);
  }
  for (int m = 0; m < n; m++)
    law_sum_point(&c->sum, &c->weight, &ra[3 * m], &f[3 * m], fn[m], pt[m].point, pt[m].depth);
}

int lsdem_penalty_apply(const lsdem_manifold *m, const lsdem_penalty_law *law, double dt,
                        int64_t step, const lsdem_shear_hist *hist_in, int n_in,
                        lsdem_shear_hist *hist_out, int *n_out, lsdem_contact_result *res)
{
  static const lsdem_contact_result no_result; /* all zero */
  law_ctx c;
  c.sum = no_result;
  c.law = *law;
  c.dt = dt;
  c.stride = (double)m->stride;
  for (int i = 0; i < 3; i++) c.xa[i] = m->xa[i];
  c.step = step;
  c.hist_in = law->mu > 0.0 ? hist_in : NULL;
  c.n_in = c.hist_in ? n_in : 0;
  c.cursor = 0;
  c.hist_out = law->mu > 0.0 ? hist_out : NULL;
  c.n_out = 0;
  c.weight = 0.0;
  for (int first = 0; first < m->n; first += LAW_BATCH) {
    const int count = m->n - first < LAW_BATCH ? m->n - first : LAW_BATCH;
    apply_points(&c, m->point + first, count);
  }
  *res = c.sum;
  res->npen = m->n;
  res->ntested = m->ntested;
  law_finish(res, c.weight, m->dab, m->n == 1 ? m->point[0].point : NULL);
  if (n_out) *n_out = c.n_out;
  return m->n;
}
