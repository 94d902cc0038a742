/* nodelist.c -- per-pair node lists of detection (a Verlet list of a master's nodes; the
 * record types and what they guarantee are in lsdem_contact.h). A list changes the work,
 * never the result: it leaves out only nodes that provably cannot touch B before it is
 * rebuilt. */
#include "nodelist.h"

#include <math.h>
#include <string.h>

/* The node-list reach L s for skin s: a node looked up with phi >= L s cannot reach
 * phi < 0 by moving less than s, L bounding |grad phi| where 0 <= phi <= L s (exact
 * distances: 1; bands: LSDEM_BAND_LIPSCHITZ; grids that are not inverted:
 * lsdem_grid_outer_lipschitz, within its limit). HUGE_VAL when there is no such bound:
 * every looked-up node is listed. */
static double list_reach(const lsdem_sdf *s, double skin)
{
  const double lip = lsdem_sdf_lipschitz(s);
  if (lip > 0.0) return lip * skin;
  /* the grid's bound holds where its own phi >= 0, not where an inverted one is */
  const lsdem_grid *g = &s->grid;
  if (s->kind == LSDEM_SDF_GRID && !s->inverted && g->lip > 0.0 && g->lip * skin < g->lip_reach)
    return g->lip * skin;
  return HUGE_VAL;
}

/* How far any node of A (radius ra) may have moved relative to B since the list was
 * built at M0, t0: |M - M0| ra + |t - t0|, the rotation part exact for rotations as
 * |M - M0|_F / sqrt(2). The head keeps M0 and t0 rounded to float (M0f, t0f, each entry
 * within 2^-24 of its own size): |M - M0|_F <= |M - M0f|_F + 2^-24 |M0|_F (= sqrt 3) and
 * |t - t0| <= |t - t0f| + 2^-24 |t0|, covered by FLOAT_POSE_ALLOWANCE (ra + |t0f|_1), twice
 * those terms. */
#define FLOAT_POSE_ALLOWANCE 1.2e-7

static double list_motion(const lsdem_nodelist_head *h, const double M[9], const double t[3],
                          double ra)
{
  double dm = 0.0, dt = 0.0, t0 = 0.0; /* t0: |t0f|_1 >= |t0f| */
  for (int i = 0; i < 9; i++) dm += (M[i] - h->M[i]) * (M[i] - h->M[i]);
  for (int i = 0; i < 3; i++) {
    dt += (t[i] - h->t[i]) * (t[i] - h->t[i]);
    t0 += fabs((double)h->t[i]);
  }
  return (sqrt(0.5 * dm) + 1e-12) * ra + sqrt(dt) + FLOAT_POSE_ALLOWANCE * (ra + t0);
}

/* Skin of a list built now against B, for the base skin s: a list that lasted fewer than
 * LIST_LIFETIME steps (the pair rattles) is followed by one wide enough to last that long
 * at the pair's rate of motion since, within [s, LIST_SKIN_GROWTH s], unless B's gradient
 * bound covers s but not the wider skin (every looked-up node would then be listed);
 * otherwise s, which costs the fewest lookups per step. */
enum { LIST_LIFETIME = 8, LIST_SKIN_GROWTH = 4 };

static double adapted_skin(double skin, const lsdem_sdf *sdfB, const lsdem_nodelist_head *h,
                           double motion, int64_t step)
{
  const int64_t age = step - h->built;
  if (age <= 0 || age >= LIST_LIFETIME) return skin;
  const double want = LIST_LIFETIME * motion / (double)age;
  const double wide = want < skin                      ? skin
                      : want > LIST_SKIN_GROWTH * skin ? LIST_SKIN_GROWTH * skin
                                                       : want;
  const int bound_lost = !isfinite(list_reach(sdfB, wide)) && isfinite(list_reach(sdfB, skin));
  return bound_lost ? skin : wide;
}

/* Whether the list holds: built with this stride, no node moved by its validity radius,
 * and not a wide list (radius above LIST_SKIN_GROWTH / 2 times the base skin) older than
 * 4 LIST_LIFETIME steps: a pair that has settled gets the base skin back. */
static int list_holds(const lsdem_nodelist_head *h, double motion, double skin, int64_t step,
                      int stride)
{
  const int wide = h->radius > 0.5 * LIST_SKIN_GROWTH * skin;
  if (wide && step - h->built > 4 * LIST_LIFETIME) return 0;
  return h->stride == stride && motion < h->radius * (1.0 - 1e-9);
}

void nodelist_begin(node_list *L, const lsdem_shape *A, const lsdem_sdf *sdfB,
                    const lsdem_detect_params *det, int64_t step, const lsdem_nodelist *in,
                    lsdem_nodelist *out, const double M[9], const double t[3])
{
  L->skin = det->node_skin > 0.0 ? det->node_skin : 0.0;
  L->use = L->cached = L->building = 0;
  L->moved = L->slack_unit = L->slack_per_length = L->inv_lip = 0.0;
  L->nslack = 0;
  L->head_in = NULL;
  L->node_in = NULL;
  L->nnode_in = L->node_cursor = 0;
  L->out = NULL;
  if (out) out->valid = 0;
  if (L->skin == 0.0) return;
  L->margin = HUGE_VAL;
  L->cached = sdfB->kind == LSDEM_SDF_GRID && !sdfB->inverted;
  const int stride = det->node_stride > 1 ? det->node_stride : 1;
  if (in && in->valid) {
    L->head_in = in->head;
    if (in->head->count > 0) {
      L->node_in = in->entry;
      L->nnode_in = in->head->count;
    }
    const double motion = list_motion(in->head, M, t, A->radius);
    L->use = list_holds(in->head, motion, L->skin, step, stride);
    if (!L->use) L->skin = adapted_skin(L->skin, sdfB, in->head, motion, step);
    L->moved = motion;
    L->slack_unit = in->head->slack_unit;
  }
  L->reach = list_reach(sdfB, L->skin);
  L->lip = isfinite(L->reach) ? L->reach / L->skin : 0.0;
  L->cap = sdfB->kind == LSDEM_SDF_GRID && L->lip > 0.0 ? sdfB->grid.lip_reach / L->lip
                                                         : HUGE_VAL;
  if (!out) return;
  L->out = out;
  out->valid = 1;
  if (L->use) {
    *out->head = *in->head;
    out->head->count = out->head->words = 0;
    return;
  }
  L->building = 1;
  out->head->count = out->head->words = 0;
  out->head->cells = L->cached;
  for (int i = 0; i < 9; i++) out->head->M[i] = (float)M[i];
  for (int i = 0; i < 3; i++) out->head->t[i] = (float)t[i];
  out->head->built = step;
  out->head->stride = stride; /* radius: when the list is finished */
  out->head->slack_unit = L->lip > 0.0 ? nodelist_float_below(L->skin / 31.0) : 0.0f;
  if (L->lip > 0.0) {
    L->slack_per_length = 31.0 / L->skin * (1.0 - 1e-12);
    L->inv_lip = 1.0 / L->lip * (1.0 - 1e-12);
  }
}

/* A list keeps its slack when at least this fraction of its entries have some (fewer:
 * the test per entry costs more than the lookups it saves; measured on the reference
 * scene, where most listed nodes touch: bench/README.md). */
#define SLACK_MIN_FRACTION 0.5

void nodelist_finish(node_list *L)
{
  if (!L->building) return;
  lsdem_nodelist_head *h = L->out->head;
  const double radius = L->margin < L->cap ? L->margin : L->cap;
  h->radius = nodelist_float_below(radius > L->skin ? radius : L->skin);
  if (L->nslack < SLACK_MIN_FRACTION * h->count) h->slack_unit = 0.0f;
}
