/* step.c -- the stages of an impulse step over the solver's arrays (lsdem_impulse.h, "the
 * step's stages"): kick, thresholds, classify, selection, wall guard, CFL, damp and drift;
 * and the energy audit's sum and residual. The per-body physics is integrate.c's and
 * wall.c's; here are the loops and the rules that decide what each body and contact takes. */
#include "lsdem_impulse.h"

#include <math.h>
#include <string.h>

double lsdem_impulse_kinetic_energy(double mass, const double inertia[3], const double q[4],
                                    const double v[3], const double omega[3])
{
  double wb[3];
  lsdem_quat_rotate_inv(q, omega, wb);
  return 0.5 * mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) +
         0.5 * (inertia[0] * wb[0] * wb[0] + inertia[1] * wb[1] * wb[1] +
                inertia[2] * wb[2] * wb[2]);
}

static double grain_kinetic_energy(const lsdem_impulse_body *b, const lsdem_impulse_grain *g)
{
  return lsdem_impulse_kinetic_energy(g->mass, g->inertia, g->q, b->v, b->omega);
}

double lsdem_impulse_stage_kinetic_energy(const lsdem_impulse_body *body,
                                          const lsdem_impulse_grain *grain,
                                          const char *moving, int n)
{
  double ke = 0.0;
  for (int k = 0; k < n; k++)
    if (moving[k]) ke += grain_kinetic_energy(&body[k], &grain[k]);
  return ke;
}

/* the kick's exact work: the impulse f dt and angular impulse torque dt (eqs 4.37, 4.39) */
static double kick_work(const lsdem_impulse_body *b, const lsdem_impulse_grain *g, double dt)
{
  const double J[3] = {dt * g->force[0], dt * g->force[1], dt * g->force[2]};
  const double L[3] = {dt * g->torque[0], dt * g->torque[1], dt * g->torque[2]};
  return lsdem_impulse_work(b, J, L);
}

double lsdem_impulse_stage_kick(lsdem_impulse_body *body, const lsdem_impulse_grain *grain,
                                const char *moving, int n, double dt, double *work)
{
  double amax = 0.0;
  for (int k = 0; k < n; k++) {
    if (!moving[k]) continue;
    const lsdem_impulse_grain *g = &grain[k];
    if (work) *work += kick_work(&body[k], g, dt);
    lsdem_impulse_kick(&body[k], g->force, g->torque, dt); /* eqs 4.37, 4.39 */
    amax = lsdem_max(sqrt(lsdem_dot3(g->force, g->force)) / g->mass, amax);
  }
  return amax;
}

double lsdem_impulse_auto_rest_speed(double steps, double amax, double dt)
{
  return steps * amax * dt;
}

void lsdem_impulse_step_thresholds(lsdem_impulse_step *s, double rest_speed,
                                   const lsdem_etm_params *etm,
                                   const lsdem_resting_params *rest)
{
  const double r = rest_speed, dt = s->dt;
  lsdem_resting_params *rp = &s->island.rest;
  *rp = *rest;
  rp->dt = dt;
  rp->ref_speed = r;
  rp->slop = r * dt;
  rp->max_push = r;
  s->wall.rest_speed = r;
  s->wall.depth_tol = s->split ? 2.0 * rp->slop : 0.005 * r * dt;
  s->wall.mu = 0.0;
  s->approach_floor = etm->velocity_tol * r;
  s->island.etm = *etm;
  s->island.approach_floor = s->split ? s->approach_floor : 0.0;
  s->island.collide_speed = r;
  if (s->split) s->island.etm.min_approach = s->residual * r;
}

/* u_n < -rest_speed: faster than a resting contact approaches */
static int collides(double u_n, double rest_speed)
{
  return lsdem_wall_classify(u_n, rest_speed) == LSDEM_WALL_COLLIDING;
}

void lsdem_impulse_stage_classify(const lsdem_impulse_body *body,
                                  lsdem_impulse_step_contact *c, int n, double rest_speed)
{
  for (int k = 0; k < n; k++)
    c[k].resting = !collides(lsdem_impulse_normal_velocity(body, &c[k].c), rest_speed);
}

int lsdem_impulse_stage_select(const lsdem_impulse_body *body,
                               lsdem_impulse_step_contact *contacts, int n,
                               const lsdem_impulse_step *s, int first_pass,
                               lsdem_impulse_step_contact *coll, int *ncoll)
{
  int napproach = 0, kept = 0;
  for (int k = 0; k < n; k++) {
    lsdem_impulse_step_contact *c = &contacts[k];
    double un;
    const int approaching = lsdem_impulse_approaching(body, &c->c, s->approach_floor, &un);
    if (s->split) {
      c->approaching = (first_pass && c->resting) || approaching;
      napproach += approaching && !c->resting;
      continue;
    }
    const int resting = c->j < 0 && !collides(un, s->wall.rest_speed);
    if (resting && !(s->wall_etm && approaching)) continue;
    coll[kept] = *c;
    coll[kept].approaching = approaching;
    if (resting) coll[kept].c.restitution = 0.0;
    kept++;
    napproach += approaching;
  }
  if (!s->split) *ncoll = kept;
  return napproach;
}

/* Grain g (body b) against the wall at its predicted pose: 1 when corrected (a resting
 * contact; its impulse in res), 0 when not, -1 on error. */
static int guard_grain(lsdem_impulse_body *b, const lsdem_impulse_grain *g,
                       const lsdem_impulse_guard_wall *w, const lsdem_nodelist *list,
                       int64_t step, double dt, lsdem_contact_point *points, int npoints,
                       lsdem_wall_result *res, lsdem_error *err)
{
  /* the centre's predicted position first: the turn of the orientation costs more */
  const double xp[3] = {b->x[0] + dt * b->v[0], b->x[1] + dt * b->v[1],
                        b->x[2] + dt * b->v[2]};
  if (!lsdem_boundary_may_touch(w->boundary, &w->pose, xp, g->radius)) return 0;
  lsdem_pose gp;
  lsdem_impulse_predict_pose(b->x, g->q, b->v, b->omega, g->inertia, dt, &gp);
  lsdem_manifold m = lsdem_manifold_over(points, npoints);
  if (lsdem_detect(g->shape, &gp, &w->boundary->shape, &w->pose, &w->detect, step,
                   list && list->valid ? list : NULL, NULL, &m) == 0)
    return 0;
  lsdem_wall_limit_push_out(&m, dt, w->prm.rest_speed);
  if (lsdem_wall_correct(b, &m, dt, &w->prm, res, err) != LSDEM_OK) return -1;
  return res->kind == LSDEM_WALL_RESTING;
}

int lsdem_impulse_stage_wall_guard(lsdem_impulse_body *body, const lsdem_impulse_grain *grain,
                                   const char *moving, int n, const lsdem_impulse_guard_wall *w,
                                   int64_t step, double dt, lsdem_contact_point *points,
                                   int npoints, lsdem_wall_guard_seen *seen, lsdem_error *err)
{
  int corrected = 0;
  for (int k = 0; k < n; k++) {
    lsdem_wall_guard_seen *sk = &seen[k];
    sk->corrected = 0;
    sk->work = 0.0;
    if (!moving[k] || !(grain[k].groups & w->groups)) continue;
    lsdem_impulse_body *b = &body[k];
    if (w->near && !w->near[k] && w->far_gap > 0.0 &&
        dt * dt * lsdem_dot3(b->v, b->v) < w->far_gap * w->far_gap)
      continue; /* far from the wall, and slow: not even its centre's lookup */
    if (sk->clear && memcmp(sk->v, b->v, sizeof sk->v) == 0 &&
        memcmp(sk->omega, b->omega, sizeof sk->omega) == 0)
      continue;
    memcpy(sk->v, b->v, sizeof sk->v);
    memcpy(sk->omega, b->omega, sizeof sk->omega);
    lsdem_wall_result res;
    const int r = guard_grain(b, &grain[k], w, w->lists ? &w->lists[k] : NULL, step, dt,
                              points, npoints, &res, err);
    if (r < 0) return -1 - k;
    sk->clear = !r;
    sk->corrected = r;
    if (r) {
      memcpy(sk->impulse, res.impulse, sizeof sk->impulse);
      sk->work = res.work;
    }
    corrected += r;
  }
  return corrected;
}

double lsdem_impulse_stage_cfl(const lsdem_impulse_body *body,
                               const lsdem_impulse_grain *grain, const char *moving, int n,
                               double dt, int *worst)
{
  double largest = 0.0;
  *worst = -1;
  for (int k = 0; k < n; k++) {
    if (!moving[k]) continue;
    const double ratio = sqrt(lsdem_dot3(body[k].v, body[k].v)) * dt / grain[k].radius;
    if (!(ratio <= largest)) { /* NaN counts as the worst */
      largest = isfinite(ratio) ? ratio : HUGE_VAL;
      *worst = k;
    }
  }
  return largest;
}

/* x += v dt and q turned over dt (eqs 4.38, 4.40); an analytic sphere does not turn, and
 * loses its rotational energy (0 in fix impulse/lsdem: its step body never spins). Returns
 * the kinetic energy change. */
static double drift(lsdem_impulse_body *b, lsdem_impulse_grain *g, double dt)
{
  if (g->shape->sdf.kind == LSDEM_SDF_SPHERE) {
    const double zero[3] = {0.0, 0.0, 0.0};
    const double spin = lsdem_impulse_kinetic_energy(g->mass, g->inertia, g->q, zero, b->omega);
    for (int d = 0; d < 3; d++) {
      b->x[d] += dt * b->v[d];
      b->omega[d] = 0.0;
    }
    return -spin;
  }
  return lsdem_impulse_drift(b->x, g->q, b->omega, b->v, g->inertia, dt);
}

/* the kinetic energy global damping takes from a grain of energy ke: v and omega scaled
 * by 1 - xi dt (eqs 4.44-4.45) scale it by (1 - xi dt)^2 */
static double damping_taken(double ke, double xi, double dt)
{
  const double h = xi * dt;
  return ke * h * (2.0 - h);
}

lsdem_status lsdem_impulse_stage_damp_drift(lsdem_impulse_body *body,
                                            lsdem_impulse_grain *grain, const char *moving,
                                            int n, double xi, double dt, double *damped,
                                            double *drift_work, lsdem_error *err)
{
  for (int k = 0; k < n; k++) {
    if (!moving[k]) continue;
    lsdem_impulse_body *b = &body[k];
    const double before = xi != 0.0 ? grain_kinetic_energy(b, &grain[k]) : 0.0;
    const lsdem_status st = lsdem_impulse_damp(b, xi, dt, err); /* eqs 4.44-4.46 */
    if (st != LSDEM_OK) return st;
    *damped += damping_taken(before, xi, dt);
    const double turn = drift(b, &grain[k], dt);
    if (drift_work) *drift_work += turn;
  }
  return LSDEM_OK;
}

double lsdem_impulse_audit_sum(const lsdem_impulse_audit *a, double *scale)
{
  const double t[8] = {a->kick, a->etm, a->resting, a->wall,
                       a->ball, a->damping, a->drift, a->sleep};
  double sum = 0.0, mag = 0.0;
  for (int k = 0; k < 8; k++) {
    sum += t[k];
    mag += fabs(t[k]);
  }
  if (scale) *scale = mag;
  return sum;
}

double lsdem_impulse_audit_residual(double ke_before, double ke_after,
                                    const lsdem_impulse_audit *a)
{
  double mag;
  const double sum = lsdem_impulse_audit_sum(a, &mag);
  const double scale = fmax(fmax(ke_before, ke_after), mag);
  return scale > 0.0 ? fabs((ke_after - ke_before) - sum) / scale : 0.0;
}
