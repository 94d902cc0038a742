/* ball.c -- the ball guard of impulse mode: net balls against grains at the predicted
 * poses, overlaps closed by equal and opposite impulses (report §4.4.2, Figure 4.4). The
 * rule is in lsdem_impulse.h (lsdem_impulse_ball_guard_detect). World frame; a pair's
 * point acts on each body with its arm about that body's PREDICTED centroid, applied at the
 * same arm from the current one (as wall.c does). */
#include "lsdem_impulse.h"

#include <math.h>
#include <string.h>

/* the bodies' bounding spheres at the predicted centres x + v dt overlap */
static int predicted_spheres_overlap(const lsdem_impulse_body *a, const lsdem_impulse_grain *ga,
                                     const lsdem_impulse_body *b, const lsdem_impulse_grain *gb,
                                     double dt)
{
  double d[3];
  for (int i = 0; i < 3; i++) d[i] = (a->x[i] + dt * a->v[i]) - (b->x[i] + dt * b->v[i]);
  const double rsum = ga->radius + gb->radius;
  return lsdem_dot3(d, d) < rsum * rsum;
}

static void predicted_pose(const lsdem_impulse_body *b, const lsdem_impulse_grain *g,
                           double dt, lsdem_pose *pose)
{
  lsdem_impulse_predict_pose(b->x, g->q, b->v, b->omega, g->inertia, dt, pose);
}

static void current_pose(const lsdem_impulse_body *b, const lsdem_impulse_grain *g,
                         lsdem_pose *pose)
{
  lsdem_quat_to_matrix(g->q, pose->R);
  for (int i = 0; i < 3; i++) {
    pose->x[i] = b->x[i];
    pose->v[i] = b->v[i];
    pose->omega[i] = b->omega[i];
  }
}

/* the deepest overlap of master gm (body bm) in slave gs (bs) at their current poses (0:
 * none) */
static double current_overlap(const lsdem_impulse_body *bm, const lsdem_impulse_grain *gm,
                              const lsdem_impulse_body *bs, const lsdem_impulse_grain *gs,
                              const lsdem_detect_params *det, int64_t step,
                              lsdem_contact_point *points, int npoints)
{
  lsdem_pose pm, ps;
  current_pose(bm, gm, &pm);
  current_pose(bs, gs, &ps);
  lsdem_manifold m = lsdem_manifold_over(points, npoints);
  double deepest = 0.0;
  lsdem_detect(gm->shape, &pm, gs->shape, &ps, det, step, NULL, NULL, &m);
  for (int j = 0; j < m.n; j++) deepest = lsdem_max(m.point[j].depth, deepest);
  return deepest;
}

/* the rise of the relative normal velocity u_n (< 0: approaching; the master's relative to
 * the slave's along the slave's normal: the same for a and b) that closes the overlap d, or
 * for a collision (u_n < -rest_speed) gives it restitution e:
 * max(d / dt, -(1 + e) u_n) */
static double lift(double d, double u_n, double rest_speed, double e, double dt)
{
  const int collision = lsdem_wall_classify(u_n, rest_speed) == LSDEM_WALL_COLLIDING;
  return collision ? lsdem_max(d / dt, -(1.0 + e) * u_n) : d / dt;
}

/* Pair q at the predicted poses: 1 when its deepest point (after the push-out limit of the
 * overlap it has now) is deeper than p->depth_tol, with that point's depth, normal (b to a)
 * and arms in q. */
static int detect_pair(const lsdem_impulse_body *body, const lsdem_impulse_grain *grain,
                       lsdem_ball_guard_pair *q, const lsdem_detect_params *det,
                       const lsdem_wall_params *p, double e, double dt, int64_t step,
                       lsdem_contact_point *points, int npoints)
{
  const lsdem_impulse_body *a = &body[q->a], *b = &body[q->b];
  const lsdem_impulse_grain *ga = &grain[q->a], *gb = &grain[q->b];
  if (!predicted_spheres_overlap(a, ga, b, gb, dt)) return 0;
  /* the master's nodes (a ball: its centre) in the slave's level set */
  const int a_master =
      lsdem_contact_roles(ga->shape, lsdem_contact_node_scale(ga->shape), a->id, gb->shape,
                          lsdem_contact_node_scale(gb->shape), b->id, LSDEM_ROLES_ONEWAY) > 0.5;
  const lsdem_impulse_grain *gm = a_master ? ga : gb, *gs = a_master ? gb : ga;
  lsdem_pose pm, ps;
  predicted_pose(a_master ? a : b, gm, dt, &pm);
  predicted_pose(a_master ? b : a, gs, dt, &ps);
  lsdem_manifold m = lsdem_manifold_over(points, npoints);
  if (lsdem_detect(gm->shape, &pm, gs->shape, &ps, det, step, NULL, NULL, &m) == 0) return 0;
  /* a copy: m's storage is reused below */
  const lsdem_contact_point deep = m.point[lsdem_manifold_deepest(&m)];
  if (!(deep.depth > p->depth_tol)) return 0;
  const double d0 = current_overlap(a_master ? a : b, gm, a_master ? b : a, gs, det, step,
                                    points, npoints);
  /* the approach over the step that takes d0 to the predicted overlap: (d0 - d) / dt */
  const double depth =
      lsdem_push_out_limit(deep.depth, d0, (d0 - deep.depth) / dt, dt, p->rest_speed);
  if (!(depth > p->depth_tol)) return 0;
  const double sign = a_master ? 1.0 : -1.0; /* the manifold's normal points to the master */
  const lsdem_pose *pa = a_master ? &pm : &ps, *pb = a_master ? &ps : &pm;
  q->depth = depth;
  q->lift = lift(depth, lsdem_dot3(deep.vrel, deep.normal), p->rest_speed, e, dt);
  for (int i = 0; i < 3; i++) {
    q->normal[i] = sign * deep.normal[i];
    q->arm_a[i] = deep.point[i] - pa->x[i];
    q->arm_b[i] = deep.point[i] - pb->x[i];
  }
  return 1;
}

int lsdem_impulse_ball_guard_detect(const lsdem_impulse_body *body,
                                    const lsdem_impulse_grain *grain,
                                    lsdem_ball_guard_pair *pairs, int n,
                                    const lsdem_detect_params *det, const lsdem_wall_params *p,
                                    double e, double dt, int64_t step,
                                    lsdem_contact_point *points, int npoints, int32_t *count)
{
  int overlapping = 0;
  for (int k = 0; k < n; k++) {
    lsdem_ball_guard_pair *q = &pairs[k];
    q->overlapping = detect_pair(body, grain, q, det, p, e, dt, step, points, npoints);
    if (!q->overlapping) {
      q->depth = q->lift = 0.0;
      continue;
    }
    count[q->a]++;
    count[q->b]++;
    overlapping++;
  }
  return overlapping;
}

/* n . M n of body b at arm r with its inverse mass and inertia times c (mass splitting):
 * c (1/m + n . (I^-1 (r x n)) x r)  (eq 4.8) */
static double split_response(const lsdem_impulse_body *b, const double r[3], const double n[3],
                             int32_t c)
{
  double p[3], M[9], Mn[3];
  for (int i = 0; i < 3; i++) p[i] = b->x[i] + r[i];
  lsdem_impulse_point_response(b, p, M);
  lsdem_mat_vec(M, n, Mn);
  return (double)c * lsdem_dot3(n, Mn);
}

void lsdem_ball_guard_impulse(const lsdem_impulse_body *body, const lsdem_ball_guard_pair *q,
                              const int32_t *count, double P[3])
{
  P[0] = P[1] = P[2] = 0.0;
  if (!q->overlapping) return;
  /* n . K n with K the sum of the two split point responses (eq 4.13) */
  const double keff = split_response(&body[q->a], q->arm_a, q->normal, count[q->a]) +
                      split_response(&body[q->b], q->arm_b, q->normal, count[q->b]);
  if (!(keff > 0.0)) return; /* two bodies of infinite mass */
  const double lambda = q->lift / keff; /* Delta u_n = n . K P = lift */
  for (int i = 0; i < 3; i++) P[i] = lambda * q->normal[i];
}

/* impulse P on body b at arm r from its predicted centroid (eqs 4.31-4.32); its work */
static double apply_at_arm(lsdem_impulse_body *b, const double r[3], const double P[3])
{
  double p[3];
  for (int i = 0; i < 3; i++) p[i] = b->x[i] + r[i];
  return lsdem_impulse_apply_work(b, p, P);
}

int lsdem_impulse_ball_guard_correct(lsdem_impulse_body *body,
                                     const lsdem_ball_guard_pair *pairs, int n,
                                     const int32_t *count, int nown, double *work)
{
  double w = 0.0;
  int corrected = 0;
  for (int k = 0; k < n; k++) {
    const lsdem_ball_guard_pair *q = &pairs[k];
    double P[3];
    lsdem_ball_guard_impulse(body, q, count, P);
    if (P[0] == 0.0 && P[1] == 0.0 && P[2] == 0.0) continue;
    const double minus[3] = {-P[0], -P[1], -P[2]};
    if (q->a < nown) w += apply_at_arm(&body[q->a], q->arm_a, P);
    if (q->b < nown) w += apply_at_arm(&body[q->b], q->arm_b, minus);
    corrected += q->a < nown;
  }
  if (work) *work += w;
  return corrected;
}
