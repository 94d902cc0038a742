/* penalty.c -- the penalty contact law of LS-DEM (report eqs 2.2-2.16) on a contact
 * manifold (lsdem_contact.h): per point a normal spring with optional viscous damping, a
 * tangential spring carried in per-node shear history, the Coulomb cap, and the sums of
 * force and torque on both grains. */
#include "lsdem_contact.h"

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

/* Weight of a point's springs: the node stride, times the node area under the traction
 * law (eq 2.2 per node, or a stress times the node's area). */
static double spring_weight(const law_ctx *c, const lsdem_contact_point *p)
{
  return c->law.normal == LSDEM_NORMAL_TRACTION ? c->stride * p->area : c->stride;
}

/* Normal force (eq 2.2, with damping) of each point, and the quantities the shear and
 * the torques need: the arm ra = p - xA, the relative tangential velocity vt (eq 2.6),
 * fn n in f. */
static void normal_forces(const law_ctx *restrict c, const lsdem_contact_point *restrict pt,
                          int n, double *restrict fn_out, double *restrict ra,
                          double *restrict vt, double *restrict f)
{
  const lsdem_penalty_law *law = &c->law;
  const int relative = law->cn > 0.0 || law->mu > 0.0;
  for (int m = 0; m < n; m++) {
    const lsdem_contact_point *p = &pt[m];
    double *r = &ra[3 * m];
    double fn = law->kn * spring_weight(c, p) * p->depth; /* eq 2.2: repulsive, +n on A */
    double vn = 0.0;
    for (int i = 0; i < 3; i++) r[i] = p->point[i] - c->xa[i];
    if (relative) vn = lsdem_dot3(p->vrel, p->normal);
    if (law->cn > 0.0) {
      fn -= law->cn * c->stride * vn;
      if (fn < 0.0) fn = 0.0; /* a penalty contact pushes, never pulls */
    }
    fn_out[m] = fn;
    for (int i = 0; i < 3; i++) {
      f[3 * m + i] = fn * p->normal[i];
      vt[3 * m + i] = relative ? p->vrel[i] - vn * p->normal[i] : 0.0;
    }
  }
}

/* Shear springs carried over (report eq 2.8): Z s_old, the stored spring rotated from
 * its normal to the current one; 0 for a new contact. An entry stamped with this step
 * was already advanced: it is taken as is and *fresh is 0 for it. */
static void carried_shear(law_ctx *restrict c, const lsdem_contact_point *restrict pt, int n,
                          double *restrict s, int *restrict fresh)
{
  for (int m = 0; m < n; m++) {
    const lsdem_shear_hist *h = find_history(c, pt[m].node);
    double *sm = &s[3 * m];
    fresh[m] = !(h && h->stamp == c->step);
    if (!h) {
      sm[0] = sm[1] = sm[2] = 0.0;
    } else if (!fresh[m]) {
      for (int i = 0; i < 3; i++) sm[i] = h->shear[i];
    } else {
      lsdem_rotate_between(h->shear, h->normal, pt[m].normal, sm); /* eq 2.8: Z */
    }
  }
}

/* Tangential forces (report eqs 2.7, 2.8, 2.10) added to f, and their history entries:
 * shear spring s = Z s_old - ks dt v_t (kept as is for an entry already advanced this
 * step); applied force ft = s - ct v_t, capped at mu fn, with the spring reset so that
 * spring + damping equals the capped force. */
static void tangential_forces(law_ctx *restrict c, const lsdem_contact_point *restrict pt,
                              int n, const double *restrict fn, const double *restrict vt,
                              double *restrict s, const int *restrict fresh, double *restrict f)
{
  const lsdem_penalty_law *law = &c->law;
  const double ct = law->ct * c->stride;
  for (int m = 0; m < n; m++) {
    const double *v = &vt[3 * m];
    double *sm = &s[3 * m], ft[3];
    if (fresh[m]) {
      const double ks = law->ks * spring_weight(c, &pt[m]);
      for (int i = 0; i < 3; i++) sm[i] = sm[i] - ks * c->dt * v[i]; /* eqs 2.7-2.8 */
    }
    for (int i = 0; i < 3; i++) ft[i] = sm[i] - ct * v[i];
    const double cap = law->mu * fn[m]; /* eq 2.10 */
    const double ft2 = lsdem_dot3(ft, ft);
    if (ft2 > cap * cap) {
      const double scale = cap / sqrt(ft2);
      for (int i = 0; i < 3; i++) {
        ft[i] *= scale;
        sm[i] = ft[i] + ct * v[i];
      }
    }
    for (int i = 0; i < 3; i++) f[3 * m + i] += ft[i];
    if (!c->hist_out) continue;
    lsdem_shear_hist *out = &c->hist_out[c->n_out++];
    out->node = pt[m].node;
    out->pad_ = 0;
    out->stamp = c->step;
    for (int i = 0; i < 3; i++) {
      out->shear[i] = sm[i];
      out->normal[i] = pt[m].normal[i];
    }
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
  lsdem_contact_result *sum = &c->sum;
  for (int m = 0; m < n; m++) {
    const double *fm = &f[3 * m], *p = pt[m].point;
    double ta[3];
    lsdem_cross3(&ra[3 * m], fm, ta);
    for (int i = 0; i < 3; i++) {
      sum->force[i] += fm[i];
      sum->torque_a[i] += ta[i];
      sum->point[i] += fn[m] * p[i];
    }
    c->weight += fn[m];
    const double d = pt[m].depth;
    sum->max_depth = d > sum->max_depth ? d : sum->max_depth; /* a max, not a branch */
  }
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
  /* the reaction's torque about B's centroid: (ra + dab) x (-f) summed is
   * -(sum of ra x f) - dab x (sum of f) */
  double dab_f[3];
  lsdem_cross3(m->dab, res->force, dab_f);
  for (int i = 0; i < 3; i++) res->torque_b[i] = -res->torque_a[i] - dab_f[i];
  if (c.weight > 0.0)
    for (int i = 0; i < 3; i++) res->point[i] /= c.weight;
  if (n_out) *n_out = c.n_out;
  return m->n;
}
