/* cap.c -- at most a few contacts per pair (issue 33, item 4): the deepest, then those
 * spanning the contact area. The rule is in lsdem_impulse.h (lsdem_impulse_cap_contacts).
 *
 * Bookkeeping, in the caller's scratch of n int32: scratch[i] is the kept contact nearest
 * to contact i (in the plane), so scratch[i] == i exactly when i is kept. Each pick updates
 * it in O(n), so the distance to the kept set costs O(1) per candidate and the whole cap
 * O(n max). Everything is world frame; lengths are the caller's. */
#include "lsdem_impulse.h"

#include <math.h>

/* The first picks, by the area rule (picks 3 and 4), need the kept points in pick order. */
enum { AREA_PICKS = 4 };

/* Squared distance between p and q projected on the plane normal to the unit vector n:
 * |d - (d . n) n|^2 with d = q - p (length^2). */
static double plane_distance2(const double n[3], const double p[3], const double q[3])
{
  double d[3];
  lsdem_sub3(q, p, d);
  const double dn = lsdem_dot3(d, n);
  for (int i = 0; i < 3; i++) d[i] -= dn * n[i];
  return lsdem_dot3(d, d);
}

/* Twice the signed area of the triangle a, b, q projected on the plane normal to the unit
 * vector n: n . ((b - a) x (q - a)), positive counter-clockwise about n. The components
 * along n drop out of this triple product, so no projection is needed (length^2). */
static double plane_area2(const double n[3], const double a[3], const double b[3],
                          const double q[3])
{
  double ab[3], aq[3], x[3];
  lsdem_sub3(b, a, ab);
  lsdem_sub3(q, a, aq);
  lsdem_cross3(ab, aq, x);
  return lsdem_dot3(n, x);
}

/* Twice the area q adds to the projected triangle t (kept in pick order), i.e. the area of
 * the hull of t and q minus t's: the triangles q forms with the edges of t it sees from
 * outside (q beyond the edge's line, on the side away from t), which tile that difference;
 * 0 when q is inside. orient: the sign of t's signed area; 0 for a degenerate t (every
 * contact then lies on its line, since pick 3 maximised the area, and the gain is 0). */
static double area_gain2(const double n[3], const double *const t[3], double orient,
                         const double q[3])
{
  double gain = 0.0;
  for (int e = 0; e < 3; e++) {
    const double outside = -orient * plane_area2(n, t[e], t[(e + 1) % 3], q);
    if (outside > 0.0) gain += outside;
  }
  return gain;
}

/* Rule 1: the largest depth; ties, the lowest index. */
static int deepest_contact(const lsdem_impulse_contact *c, int n)
{
  int best = 0;
  for (int i = 1; i < n; i++)
    if (c[i].depth > c[best].depth) best = i;
  return best;
}

/* What the picks so far leave to the next one: the plane's normal (that of the deepest
 * contact), the kept contacts in pick order (the first AREA_PICKS) and the orientation
 * of the triangle of the first three. */
typedef struct {
  double normal[3];
  const double *point[AREA_PICKS];
  int nkept;
  double orient;
} cap_state;

/* Score of a candidate as the next pick, larger better (rules 2-5, lsdem_impulse.h); spread2 is its
 * squared distance to the kept set. */
static double pick_score(const cap_state *s, const double q[3], double spread2)
{
  switch (s->nkept) {
  case 2: return fabs(plane_area2(s->normal, s->point[0], s->point[1], q)); /* rule 3 */
  case 3: return area_gain2(s->normal, s->point, s->orient, q);             /* rule 4 */
  default: return spread2; /* rules 2 (one kept) and 5 */
  }
}

/* The next pick: the best score; ties, the larger distance to the kept set, then the
 * lowest index (the scan goes up and replaces only on a strict improvement). */
static int next_pick(const lsdem_impulse_contact *c, int n, const int32_t *nearest,
                     const cap_state *s)
{
  int best = -1;
  double best_score = 0.0, best_spread2 = 0.0;
  for (int i = 0; i < n; i++) {
    if (nearest[i] == i) continue; /* kept */
    const double spread2 = plane_distance2(s->normal, c[nearest[i]].point, c[i].point);
    const double score = pick_score(s, c[i].point, spread2);
    if (best < 0 || score > best_score || (score == best_score && spread2 > best_spread2)) {
      best = i;
      best_score = score;
      best_spread2 = spread2;
    }
  }
  return best;
}

/* Marks k kept and makes it the nearest kept contact of those it is nearer to than their
 * current one (strictly: an equidistant contact keeps its earlier nearest, whose distance
 * is the same). */
static void keep(const lsdem_impulse_contact *c, int n, int32_t *nearest,
                 const double normal[3], int k)
{
  for (int i = 0; i < n; i++) {
    if (nearest[i] == i) continue;
    if (plane_distance2(normal, c[k].point, c[i].point) <
        plane_distance2(normal, c[nearest[i]].point, c[i].point))
      nearest[i] = k;
  }
  nearest[k] = k; /* also when k coincides with a kept contact in the plane */
}

/* Moves the kept contacts (nearest[i] == i) to the front, in order; their count. */
static int compact_kept(lsdem_impulse_contact *c, int n, const int32_t *nearest)
{
  int m = 0;
  for (int i = 0; i < n; i++)
    if (nearest[i] == i) {
      if (m != i) c[m] = c[i];
      m++;
    }
  return m;
}

int lsdem_impulse_cap_contacts(lsdem_impulse_contact *c, int n, int max, int32_t *scratch)
{
  if (max < 1) max = 1;
  if (n <= max) return n;
  const int k0 = deepest_contact(c, n);
  cap_state s = {.nkept = 1, .orient = 0.0};
  for (int i = 0; i < 3; i++) s.normal[i] = c[k0].normal[i];
  s.point[0] = c[k0].point;
  for (int i = 0; i < n; i++) scratch[i] = k0;
  for (; s.nkept < max; s.nkept++) {
    const int k = next_pick(c, n, scratch, &s);
    keep(c, n, scratch, s.normal, k);
    if (s.nkept < AREA_PICKS) s.point[s.nkept] = c[k].point;
    if (s.nkept == 2) {
      const double a2 = plane_area2(s.normal, s.point[0], s.point[1], s.point[2]);
      s.orient = (a2 > 0.0) - (a2 < 0.0);
    }
  }
  return compact_kept(c, n, scratch);
}
