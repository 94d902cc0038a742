/* lsdem_impulse.h -- impulse-based LS-DEM (report chapter 4), kernel module core/impulse.
 *
 * What a time step of impulse mode needs, without LAMMPS or MPI:
 *   body.c      the island's body record (mass, world inverse inertia, x, v, omega; walls
 *               of infinite mass with a prescribed motion), the collision matrix K
 *               (eq 4.13), impulses on bodies (eqs 4.31-4.32), validation of an island
 *   glue.c      a pair's contact manifold -> impulse contacts (§4.3.3 "glued" points)
 *   coulomb.c   the Coulomb-limited impulse of one increment (eqs 4.14-4.20)
 *   etm.c       the Energy Tracking Method on one island (Algorithm 3, eqs 4.1, 4.24-4.30,
 *               §4.4.3 mass weighting), in caller-provided workspace, with an island
 *               report when it does not converge
 *   integrate.c symplectic Euler (eqs 4.37-4.40) and global damping (eqs 4.44-4.46)
 *   wall.c      resting contact on rigid walls: the predicted-position velocity
 *               correction of §4.4.1 (Figures 4.4-4.5)
 *   ball.c      the same check for net balls against grains, two-sided (§4.4.2, Fig. 4.4)
 *   islands.c   contact islands: union-find, labels, the cross-rank label merge (§4.5)
 *   cap.c       at most a few contacts per pair (the manifold cap)
 *   sleep.c     the sleep clock of sleeping islands
 *   resting.c   resting contacts as warm-started constraints (projected Gauss-Seidel)
 *   island_solve.c  one island's solve: resting contacts, then collisions by ETM
 *   step.c      the step's stages over the solver's arrays (below)
 *
 * One step (Figure 4.4) as named stages. The caller (fix impulse/lsdem) gathers the solver's
 * arrays once from its own storage (bodies lsdem_impulse_body, grains lsdem_impulse_grain,
 * contacts lsdem_impulse_step_contact), runs the stages, does the communication between
 * them (ghosts' velocities, reductions, islands across ranks) and scatters once:
 *   1. kick (lsdem_impulse_stage_kick): v, omega += external forces and torques over dt
 *      (eqs 4.37, 4.39); the largest acceleration gives the resting speed
 *      (lsdem_impulse_auto_rest_speed), and that the step's thresholds
 *      (lsdem_impulse_step_thresholds);
 *   2. contacts: the manifolds of touching pairs and grain-wall pairs at the current poses
 *      (lsdem_detect), glued (lsdem_impulse_glue, §4.3.3), capped
 *      (lsdem_impulse_cap_contacts);
 *   3. classify (lsdem_impulse_stage_classify; method split): resting or colliding by
 *      the velocities before the kick, the resting ones warm-started from the last step's
 *      impulses (the caller's store);
 *   4. passes: the contacts an island pass takes (lsdem_impulse_stage_select), islands
 *      (lsdem_islands_build and, across ranks, lsdem_islands_merge), each island's contacts
 *      sorted by global ids (the tie-breaking order) and solved (lsdem_island_solve: the
 *      resting solve, then collisions by ETM; the report's method: ETM alone);
 *   5. wall guard (lsdem_impulse_stage_wall_guard): every grain against every wall at its
 *      predicted pose (lsdem_impulse_predict_pose), resting contacts corrected
 *      (lsdem_wall_limit_push_out, lsdem_wall_correct; §4.4.1), then, when the caller
 *      names net balls, the ball guard (lsdem_impulse_ball_guard_detect,
 *      lsdem_impulse_ball_guard_correct; §4.4.2, Figure 4.4): every ball-grain pair at the
 *      predicted poses, overlaps closed by equal and opposite impulses; while they
 *      correct, the collisions they make are resolved by another pass (4) and 5 repeats,
 *      up to a cap (the report used 10), after which one more pass closes the step;
 *   6. CFL check (lsdem_impulse_stage_cfl, §4.3.4);
 *   7. damp and drift (lsdem_impulse_stage_damp_drift): global damping (eqs 4.44-4.46),
 *      positions and orientations (eqs 4.38, 4.40).
 *
 * Frames and signs: everything is world frame. A contact's normal n points from body b
 * towards body a (the manifold's convention: B's outward normal, A's nodes inside B); the
 * impulse P of a contact acts on a, -P on b; the relative velocity is u = u_a - u_b at
 * the contact point (eq 4.7), its normal part u_n = n . u < 0 when approaching. Units are
 * the caller's (mass, length, time); energies are mass length^2 / time^2. */
#ifndef LSDEM_IMPULSE_H
#define LSDEM_IMPULSE_H

#include "../boundary/lsdem_boundary.h"
#include "../contact/lsdem_contact.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- bodies ---- */

/* One body of an island (a grain, a wall or a platen). A wall is a body of infinite
 * mass (inv_mass = 0, inv_inertia = 0) whose v and omega are prescribed: impulses leave
 * them unchanged. The record is a view rebuilt every step from a grain's state. */
typedef struct {
  int64_t id;            /* global id (LAMMPS tag); walls: any id, for reports */
  double inv_mass;       /* 1/m; 0: infinite mass */
  double inv_inertia[9]; /* world-frame I^-1 = R I0^-1 R^T (eq 4.13, I = R I0 R^T) */
  double x[3];           /* centre of mass */
  double v[3];           /* its velocity */
  double omega[3];       /* angular velocity, world frame */
} lsdem_impulse_body;

/* A grain of mass m and principal moments I0 (absolute: density times the shape's
 * per-unit-density inertia; all > 0) at orientation q (body -> world). Refuses
 * non-finite or non-positive mass and moments and non-finite state. */
lsdem_status lsdem_impulse_body_grain(lsdem_impulse_body *b, int64_t id, double mass,
                                      const double inertia[3], const double q[4],
                                      const double x[3], const double v[3],
                                      const double omega[3], lsdem_error *err);
/* A wall or platen: infinite mass, reference point x, prescribed v and omega (the wall's
 * velocity at point p is v + omega x (p - x)). */
lsdem_status lsdem_impulse_body_wall(lsdem_impulse_body *b, int64_t id, const double x[3],
                                     const double v[3], const double omega[3],
                                     lsdem_error *err);
static inline int lsdem_impulse_body_is_wall(const lsdem_impulse_body *b)
{
  return b->inv_mass == 0.0;
}
/* Velocity of the body's material point at p: v + omega x (p - x)  (eq 4.7). Inline: ETM
 * evaluates it several times per contact and iteration. */
static inline void lsdem_impulse_point_velocity(const lsdem_impulse_body *b,
                                                const double p[3], double u[3])
{
  double r[3], wr[3];
  lsdem_sub3(p, b->x, r);
  lsdem_cross3(b->omega, r, wr);
  for (int i = 0; i < 3; i++) u[i] = b->v[i] + wr[i]; /* eq 4.7 */
}
/* Impulse P applied at p: v += P/m (eq 4.31), omega += I^-1 ((p - x) x P) (eq 4.32).
 * No effect on a wall. */
void lsdem_impulse_apply(lsdem_impulse_body *b, const double p[3], const double P[3]);
/* The energy audit (fix impulse/lsdem): the kinetic energy a linear impulse J and an
 * angular impulse L (about the centre of mass; world) give body b at its current v and
 * omega, J . v + |J|^2 / 2m + L . omega + L . I^-1 L / 2 -- the exact change of
 * 1/2 m v^2 + 1/2 omega . I omega under eqs 4.31-4.32 (0 for a wall). The kick's
 * (J = f dt, L = torque dt) is f . v dt + |f|^2 dt^2 / 2m plus the torque's. */
double lsdem_impulse_work(const lsdem_impulse_body *b, const double J[3], const double L[3]);
/* lsdem_impulse_apply (the same velocities, bit for bit), returning the impulse's work on
 * b (lsdem_impulse_work with L = (p - x) x P): impulses applied one after the other each
 * booked so sum to the body's kinetic energy change exactly (to round-off). */
double lsdem_impulse_apply_work(lsdem_impulse_body *b, const double p[3], const double P[3]);
/* The change of the point velocity at p per unit impulse there, as a matrix:
 * (1/m) 1 - r~ I^-1 r~ with r = p - x (eq 4.8); symmetric, 0 for a wall. */
void lsdem_impulse_point_response(const lsdem_impulse_body *b, const double p[3],
                                  double M[9]);
/* Collision matrix of a contact at p between a and b (eq 4.13): the sum of the two
 * point responses, so that Delta u = K P (eq 4.12). Symmetric positive definite unless
 * both bodies are walls. */
void lsdem_impulse_collision_matrix(const lsdem_impulse_body *a,
                                    const lsdem_impulse_body *b, const double p[3],
                                    double K[9]);

/* ---------------------------------------------------------------- contacts ---- */

/* One contact of an island: a point of impulse exchange between bodies a and b (indices
 * into the island's body array; b may be a wall, a may not be the same body as b). */
typedef struct {
  int32_t a, b;
  double point[3];    /* world */
  double normal[3];   /* unit, from b towards a */
  double depth;       /* penetration there (>= 0; information only, 0 if unknown) */
  double mu;          /* Coulomb friction coefficient of the pair (>= 0) */
  double restitution; /* Stronge's coefficient e of the pair, 0 <= e <= 1 (eq 4.1) */
} lsdem_impulse_contact;

/* The point velocities u_a, u_b of the contact's bodies there and u = u_a - u_b (eq 4.7);
 * returns the normal part u_n = n . u (< 0: approaching). Inline, as
 * lsdem_impulse_point_velocity. */
static inline double lsdem_impulse_contact_velocities(const lsdem_impulse_body *bodies,
                                                      const lsdem_impulse_contact *c,
                                                      double ua[3], double ub[3], double u[3])
{
  lsdem_impulse_point_velocity(&bodies[c->a], c->point, ua);
  lsdem_impulse_point_velocity(&bodies[c->b], c->point, ub);
  lsdem_sub3(ua, ub, u);
  return lsdem_dot3(c->normal, u);
}
/* Relative velocity u = u_a - u_b at the contact (eq 4.7); returns u_n. */
static inline double lsdem_impulse_relative_velocity(const lsdem_impulse_body *bodies,
                                                     const lsdem_impulse_contact *c,
                                                     double u[3])
{
  double ua[3], ub[3];
  return lsdem_impulse_contact_velocities(bodies, c, ua, ub, u);
}
/* u_n alone (the classify stage's, the island solve's trigger). */
double lsdem_impulse_normal_velocity(const lsdem_impulse_body *bodies,
                                     const lsdem_impulse_contact *c);
/* Whether contact c approaches (the collision selection's): u_n (returned in *u_n; the
 * same as lsdem_impulse_normal_velocity's) below -floor and below the round-off
 * of its velocities, -1e-12 (|u_a| + |u_b|) (an island whose fastest approach is round-off
 * would never converge to a tolerance relative to it). floor: velocity >= 0. */
int lsdem_impulse_approaching(const lsdem_impulse_body *bodies, const lsdem_impulse_contact *c,
                              double floor, double *u_n);

/* Checks an island before a solve: 0 <= a, b < nbodies, a != b, not both walls, finite
 * positions, velocities and inverse inertias, inv_mass >= 0, unit normals (to 1e-6),
 * mu >= 0, 0 <= e <= 1. LSDEM_ERR_ARG (indices) or LSDEM_ERR_NUMERIC, naming the first
 * offending body or contact. */
lsdem_status lsdem_impulse_validate(const lsdem_impulse_body *bodies, int nbodies,
                                    const lsdem_impulse_contact *contacts, int ncontacts,
                                    lsdem_error *err);

/* Gluing (report §4.3.3: "a group of adjacent contact points is glued together and
 * treated as a single contact"). The rule, applied in the manifold's point order (so
 * the result is deterministic): the first point not yet in a group seeds a new group,
 * and every later free point joins it when it lies within `distance` of the seed's point
 * and its normal is within `max_angle` of the seed's normal. A group becomes one
 * contact at the area-weighted mean point, with the area-weighted mean normal
 * (normalised; never zero since max_angle < pi/2) and the largest depth of its points.
 * Seeding bounds a group's extent by 2 distance and its normals' spread by 2 max_angle,
 * so a curved surface is never glued into one flat contact however dense its nodes. */
typedef struct {
  double distance;  /* length; 0: no gluing (every point its own contact). A good choice
                       is about twice the node spacing: neighbouring nodes glue, the
                       corners of a flat face stay apart and keep the torque they carry */
  double max_angle; /* radians, in [0, pi/2); default 15 degrees */
} lsdem_glue_params;

void lsdem_glue_params_default(lsdem_glue_params *g); /* distance 0, max_angle 15 deg */

/* The contacts of one pair from its manifold m (A = body a, B = body b, as detected),
 * with the pair's friction mu and restitution e. out holds m->n contacts at least;
 * group[k] (m->n entries, required: also the scratch of the rule) receives the contact
 * index of point k.
 * Returns the number of contacts, or -1 with err set for bad parameters. */
int lsdem_impulse_glue(const lsdem_manifold *m, int32_t a, int32_t b, double mu, double e,
                       const lsdem_glue_params *g, lsdem_impulse_contact *out,
                       int32_t *group, lsdem_error *err);

/* The manifold cap (issue 33): at most a few contacts per pair after gluing, so that a
 * pair's cost no longer grows with node density. */
/* Keeps at most max of a pair's n contacts (those lsdem_impulse_glue made), in place, in
 * their original relative order. The rule (Jolt's PruneContactPoints, Bullet's
 * sortCachedPoints: the deepest point kept, the area the kept points span maximised),
 * every distance and area measured in the plane normal to the deepest contact's normal n0
 * (world frame; the contacts of one pair share that plane up to their normals' spread):
 *   1. the deepest contact (largest depth; ties: lowest index);
 *   2. the contact farthest from it;
 *   3. the contact that spans the largest triangle with the two kept;
 *   4. the contact that adds the largest area to that triangle (the area of the hull of
 *      the four minus the triangle's: 0 for a point inside it), so that the four span
 *      the largest quadrilateral the greedy choice reaches;
 *   5. and further (max > 4): the contact farthest from the kept set (the largest
 *      distance to its nearest kept contact: farthest-point sampling).
 * Ties in a pick go to the larger distance to the kept set (which separates points in a
 * line, where every area is 0: an edge contact keeps both its ends), then to the lowest
 * index. Deterministic: the choice depends on the contacts' values and their order
 * alone, and on the order only through exact ties.
 * Dropped contacts are discarded; the kept ones keep every field unchanged (point, normal,
 * depth, mu, restitution): the deepest is always kept, so the pair's largest depth
 * survives, and depth is information only in impulse mode.
 * max < 1 is taken as 1. Returns the new count, min(n, max); n <= max leaves c untouched.
 * O(n max) time; no allocation: scratch holds n int32 (on return, scratch[i] == i exactly
 * for the kept contacts' original indices i when n > max). */
int lsdem_impulse_cap_contacts(lsdem_impulse_contact *c, int n, int max, int32_t *scratch);

/* ------------------------------------------------------- one increment ---- */

/* The impulse P that raises the relative normal velocity of a contact by du_n > 0,
 * given its collision matrix K, unit normal n, current relative velocity u and friction
 * mu (Algorithm 3 lines 11-14 and 27-30). Friction acts along t = -w / |w| only, w the
 * slip a frictionless increment would leave: u_t plus what its normal impulse drives
 * sideways through K, (K n - (n . K n) n) du_n / (n . K n). So it always opposes a slip
 * and never drives motion across it, and its direction is set by the contact, not by
 * round-off in a slip near zero (the report's stick impulse K^-1 Delta u, taken by the
 * four corners of a block landing flat, sets it drifting sideways and spinning):
 *   stick  P = P_n n + P_t t with n . K P = du_n and t . K P = t . K n du_n / (n . K n)
 *          + s |w| (eq 4.14 in the plane of n and t): the normal change du_n, and the
 *          fraction s = slip_share in (0, 1] of w removed (zero tangential restitution,
 *          report §4.6.1, for s = 1; 1/k when k contacts on one body take impulses
 *          together); kept when P_n > 0 and P_t <= mu P_n (eqs 4.16-4.17);
 *   slide  P = P_n (n + mu t), P_n = du_n / (n . K (n + mu t))  (eqs 4.18-4.20);
 *   none   P = du_n / (n . K n) n when mu = 0, w = 0, or for a non-positive eq 4.20
 *          denominator.
 * In every case n . K P = du_n. Returns 1 when sliding (or frictionless), 0 sticking. */
int lsdem_coulomb_impulse(const double K[9], const double n[3], const double u[3],
                          double du_n, double mu, double slip_share, double P[3]);

/* ------------------------------------------------------------------- ETM ---- */

/* How a group's increment is shared out among its members (Algorithm 3 line 9). */
typedef enum {
  /* 1/(alpha n), n the most members of the group that push on one of the member's two
   * moving bodies (itself included): |Gamma| for a group on one body (a block landing flat,
   * a grain in a grain, each of the report's figures), while collisions in one island
   * that share no body go at the speed they would go alone (an island of 1344 contacts
   * in a cubic packing: 25 s with |Gamma|, 0.1 s like this). The default */
  LSDEM_ETM_SHARE_BODIES = 0,
  LSDEM_ETM_SHARE_GROUP = 1 /* 1/(alpha |Gamma|), as printed */
} lsdem_etm_share;

/* Parameters of the Energy Tracking Method (Algorithm 3). */
typedef struct {
  double alpha;           /* >= 1: a member's increment is 1/(alpha n) of the group's
                             largest deficit (line 9) or stored energy (separation), n as
                             `share` says; 1 resolves a lone contact at once. Default 2 */
  lsdem_etm_share share;  /* default LSDEM_ETM_SHARE_BODIES */
  double beta;            /* similarity, [0, 1): a group takes every contact whose key is
                             within beta |key_min| of the extreme one (lines 8, 24).
                             Default 0.1 */
  int mass_weighted;      /* 1 (default): order the compression queue by the weighted
                             u~ = m_a m_b / (m_a + m_b) u_n (§4.4.3; m_a for a wall);
                             0: by u_n (the original ETM) */
  double velocity_tol;    /* truncation: a contact counts as approaching while u_n <
                             -velocity_tol u_0, u_0 the island's largest initial approach
                             speed. Default 1e-6 */
  double energy_tol;      /* truncation: stored energy below energy_tol times the round's
                             absorbed energy is dropped (counted as truncated). Default
                             1e-12 (the square of velocity_tol: energies go as u^2) */
  int64_t max_iterations; /* cap on group iterations (one queue pop each), all phases
                             and rounds together. Default 1000000 */
  int max_rounds;         /* cap on compression-separation rounds (re-entries, lines
                             34-35). Default 1000 */
  const uint8_t *resting; /* per contact (NULL: none): a resting contact (lsdem_island_solve)
                             takes its restitution only when an impulse of the solve made it
                             approach faster than resting_speed (it became a collision,
                             so a Newton's cradle still rebounds); else e = 0. Default NULL */
  double resting_speed;   /* velocity. Default 0 */
  double *impulse;        /* 3 per contact (NULL: not wanted): each contact's impulses of
                             the solve are added here (world, on a). Default NULL */
  double min_approach;    /* velocity: a contact approaching slower than this, or than
                             0.3 u_0 if that is less, never counts as approaching (fix
                             impulse/lsdem: what the next step's resting solve takes up).
                             Default 0 */
} lsdem_etm_params;

void lsdem_etm_params_default(lsdem_etm_params *p);

/* What a solve did, and the island report when it did not converge. */
typedef struct {
  int converged;      /* 1: no contact approaching, all stored energy released */
  int64_t iterations; /* group iterations, all phases */
  int rounds;         /* compression-separation rounds */
  int nbodies, ncontacts;
  double mass_ratio;       /* largest / smallest finite mass of the island (1: one grain) */
  int64_t lightest_id;     /* id of the lightest grain */
  double initial_approach; /* u_0: the largest initial approach speed (-u_n) */
  double approach;         /* the largest approach speed left (0 when converged) */
  double absorbed;         /* elastic energy stored in compression, all rounds (eq 4.24) */
  double dissipated;       /* lost at restitution: (1 - e^2) of it (eq 4.1) */
  double released;         /* given back in separation (eqs 4.29-4.30) */
  double truncated;        /* stored energy dropped below energy_tol */
  double work;             /* the kinetic energy the solve's impulses gave the moving
                              bodies (negative: taken), friction included: each impulse's
                              exact work as applied (lsdem_impulse_apply_work) */
} lsdem_etm_result;

/* The solver's state on one island; lives in the caller's workspace. */
typedef struct lsdem_etm lsdem_etm;

/* Bytes of workspace a solve of this size needs (any alignment: it aligns itself). */
size_t lsdem_etm_workspace_size(int nbodies, int ncontacts);

/* The whole of Algorithm 3 on an island: bodies' v and omega (walls untouched) are
 * updated in place. The contacts' order is the tie-break order of both queues (sort them
 * by global ids): the same island gives bit-identical velocities whatever the order of
 * its bodies. No allocation: ws holds lsdem_etm_workspace_size bytes. Returns
 * LSDEM_ERR_ARG / LSDEM_ERR_NUMERIC on bad input (lsdem_impulse_validate),
 * LSDEM_ERR_NOMEM when ws is too small, and LSDEM_ERR_NUMERIC with the island report in
 * err (size, the bodies' ids, mass ratio, iterations, what to change) when a cap is hit
 * (velocities are then those reached, finite). res (NULL: not wanted) is filled in
 * every case past validation. */
lsdem_status lsdem_etm_solve(lsdem_impulse_body *bodies, int nbodies,
                             const lsdem_impulse_contact *contacts, int ncontacts,
                             const lsdem_etm_params *p, void *ws, size_t wsize,
                             lsdem_etm_result *res, lsdem_error *err);

/* The phases one by one, for callers that watch the energies (tests, Figure 4.2).
 * lsdem_etm_solve is: begin; while (lsdem_etm_approaching) { compress; restitute;
 * separate; } -- each returning the capped status as solve does. */
lsdem_status lsdem_etm_begin(lsdem_etm **s, void *ws, size_t wsize,
                             lsdem_impulse_body *bodies, int nbodies,
                             const lsdem_impulse_contact *contacts, int ncontacts,
                             const lsdem_etm_params *p, lsdem_error *err);
/* Lines 34-35 (and 4 on the first call): queue the approaching contacts; their number.
 * Only contacts on bodies an impulse moved since the last completed compression are
 * measured (the others are known not to approach): between the calls the bodies'
 * velocities are the solver's alone. */
int lsdem_etm_approaching(lsdem_etm *s);
/* Compression phase, lines 6-17; starts a round when anything approaches. */
lsdem_status lsdem_etm_compress(lsdem_etm *s, lsdem_error *err);
/* Restitution, lines 18-20: W <- e^2 W per contact (Stronge, eq 4.1: the user gives the
 * coefficient of restitution e; the printed "W <- eps W" scales energy, so eps = e^2). */
void lsdem_etm_restitute(lsdem_etm *s);
/* Separation phase, lines 21-33: each increment from eq 4.30 with u_n taken >= 0 (a
 * contact still approaching would get the elastic reversal -u_n -> u_n on top of its
 * share, and such reversals of a group applied together add up on a shared body far
 * beyond the energy stored); an approaching contact is left to the next round. */
lsdem_status lsdem_etm_separate(lsdem_etm *s, lsdem_error *err);
/* Elastic energy stored at the contacts now. */
double lsdem_etm_stored_energy(const lsdem_etm *s);
/* Progress so far (converged set when nothing approaches and nothing is stored). */
void lsdem_etm_report(const lsdem_etm *s, lsdem_etm_result *res);

/* ----------------------------------------------------------- integration ---- */

/* Velocity change from external forces over dt (eqs 4.37, 4.39 with Delta v = f dt/m,
 * Delta omega = I^-1 tau dt): force and torque world frame, torque about the centre of
 * mass. No effect on a wall. */
void lsdem_impulse_kick(lsdem_impulse_body *b, const double force[3],
                        const double torque[3], double dt);
/* Global damping (eqs 4.44-4.45): v, omega *= (1 - xi dt); LSDEM_ERR_ARG unless
 * 0 <= xi dt <= 1 (eq 4.46). */
lsdem_status lsdem_impulse_damp(lsdem_impulse_body *b, double xi, double dt,
                                lsdem_error *err);
/* Positions and orientations (eqs 4.38, 4.40): x += v dt; q turns over dt with the
 * torque-free motion of the angular momentum L = R I0 R^T omega, which is kept (the
 * gyroscopic term of Euler's equations that eq 4.39 leaves out): by the angular velocity
 * of L at mid-step (explicit midpoint, lsdem_quat_advance), energy kept to O(dt^2)
 * without drift, exact for an isotropic body or a spin about a principal axis; omega
 * becomes that of L at the new orientation. inertia: principal moments. Returns the
 * kinetic energy change of the turn, 1/2 L . (omega' - omega) (the energy audit): the
 * midpoint's truncation error (energy is not kept exactly by the discrete turn of an
 * anisotropic tumbling body), 0 to round-off for an isotropic body or a principal-axis
 * spin. The translation changes no kinetic energy. */
double lsdem_impulse_drift(double x[3], double q[4], double omega[3], const double v[3],
                           const double inertia[3], double dt);
/* The predicted pose of §4.4.1, x' = x + v dt and q' where lsdem_impulse_drift would
 * take them, carrying the current v and omega (so that a manifold detected there has the
 * current relative velocities). */
void lsdem_impulse_predict_pose(const double x[3], const double q[4], const double v[3],
                                const double omega[3], const double inertia[3], double dt,
                                lsdem_pose *pose);

/* ------------------------------------------------------- rigid boundaries ---- */

/* Resting contact with a rigid wall (report §4.4.1): the grain's manifold against the
 * wall is taken at its PREDICTED pose (lsdem_impulse_predict_pose; the wall's pose
 * predicted alike, with its prescribed velocity), and the grain's current v and omega are
 * corrected so that its deepest point no longer penetrates at the next step. */
typedef struct {
  double rest_speed; /* a contact is resting when the relative normal velocity at its
                        deepest point is within +-rest_speed (velocity). A grain resting
                        under gravity g approaches at about |g| dt each step, an impact
                        at much more: lsdem_wall_params_default takes 2 |g| dt */
  double depth_tol;  /* penetrations up to this depth count as none (length): a
                        correction leaves the deepest point clear to first order, so
                        without it second-order remainders would be corrected again and
                        again. lsdem_wall_params_default takes 1 % of |g| dt^2, the depth
                        gravity sinks a resting grain by in one step */
  double mu;         /* grain-wall Coulomb friction */
} lsdem_wall_params;

void lsdem_wall_params_default(lsdem_wall_params *p, double gravity, double dt, double mu);

typedef enum {
  LSDEM_WALL_CLEAR = 0, /* no point penetrates deeper than depth_tol (predicted pose) */
  LSDEM_WALL_RESTING,   /* resting contact: v and omega corrected */
  LSDEM_WALL_COLLIDING, /* approaching faster than rest_speed: ETM's, not corrected */
  LSDEM_WALL_SEPARATING /* leaving faster than rest_speed: not corrected */
} lsdem_wall_contact_kind;

/* The low-relative-velocity criterion: u_n < -rest_speed colliding, u_n > rest_speed
 * separating, else resting. */
lsdem_wall_contact_kind lsdem_wall_classify(double u_n, double rest_speed);

/* The correction lifts the deepest point clear of the wall at the next step: from its
 * depth d at the predicted pose it raises u_n by d / dt, to d0 / dt, d0 = d + u_n dt the
 * overlap the grain has now. An overlap the grain did not make in this step (a start from
 * a penalty run's state, a grain placed into a wall: d0 far above the resting speed times
 * dt) would be thrown off at d0 / dt, faster than anything else in the scene. So the lift
 * is capped at the larger of the resting speed and sqrt(2 a d0), the speed of a fall
 * through the overlap under the external acceleration a = rest_speed / (2 dt): the kinetic
 * energy it gives is at most the work gravity would do over the overlap. This scales the
 * manifold's depths (m, at the predicted pose, arms about the predicted centroid) so that
 * u_n becomes that cap (lsdem_push_out_cap); the rest of the overlap goes in the next
 * steps. */
void lsdem_wall_limit_push_out(lsdem_manifold *m, double dt, double rest_speed);
/* The push-out limit of one contact (the wall guard's and the ball guard's, §4.4.1-4.4.2):
 * its predicted overlap d when the overlap it has now, d0, is within the cap (d0 / dt <=
 * lsdem_push_out_cap), else the depth that lifts its relative normal velocity u_n over the
 * step (d0 - d) / dt to the cap, max(cap - u_n, 0) dt, at most d. The wall guard takes
 * u_n at its deepest point and d0 = d + u_n dt, the ball guard d0 measured. */
double lsdem_push_out_limit(double d, double d0, double u_n, double dt, double rest_speed);
/* The index of the manifold's deepest point (ties: the first; 0 for an empty manifold). */
int lsdem_manifold_deepest(const lsdem_manifold *m);
/* The push-out cap of an overlap d0 the body has now: max(rest_speed, sqrt(2 a d0)),
 * a = rest_speed / (2 dt) (above). */
double lsdem_push_out_cap(double d0, double dt, double rest_speed);

typedef struct {
  lsdem_wall_contact_kind kind;
  int deepest;       /* manifold index of the deepest point, -1 for an empty manifold */
  double depth;      /* its depth at the predicted pose */
  double u_n;        /* relative normal velocity there before the correction */
  double impulse[3]; /* the impulse given to the grain (0 unless resting); the wall's
                        reaction, divided by dt, is the force on the wall */
  int sliding;       /* resting: friction reached mu times the normal impulse */
  double work;       /* the kinetic energy the correction gave the grain (normal and
                        friction; exact, lsdem_impulse_work); 0 unless resting */
} lsdem_wall_result;

/* The correction (Figure 4.5), for manifold m of the grain (A) against the wall (B) at
 * the predicted pose, whose arms p - m->xa are taken about the predicted centroid:
 *   1. the deepest point k (depth d, normal n, ties: the first) classifies the contact:
 *      clear if d <= depth_tol, else lsdem_wall_classify of u_n = vrel_k . n; only a
 *      resting one is corrected;
 *   2. normal part: the overlaps give repulsive weights w_j = area_j d_j (a penalty
 *      force per point, "the repulsive forces due to temporary grain-wall overlaps"), and
 *      the grain receives the impulse lambda w_j n_j at every point p_j -- linear
 *      lambda F, angular lambda sum (p_j - xa) x w_j n_j, so the angular correction comes
 *      from the overlaps -- with lambda such that the deepest point's normal velocity
 *      rises by d/dt: it is then clear of the wall at the next predicted pose, to first
 *      order. (Should the overlaps' torque turn the deepest point towards the wall, so
 *      that no positive lambda exists, the deepest point alone is pushed out.)
 *   3. friction: at the overlaps' weighted centre c, with their mean normal, a tangential
 *      impulse stops the slip there if it needs at most mu times the normal impulse of
 *      step 2, else it is mu times that, against the slip (Coulomb, eqs 4.18-4.19).
 * The caller repeats detection and correction until LSDEM_WALL_CLEAR or a cap (the
 * report: 10). dt > 0. LSDEM_ERR_ARG for a wall grain or bad parameters. */
lsdem_status lsdem_wall_correct(lsdem_impulse_body *grain, const lsdem_manifold *m,
                                double dt, const lsdem_wall_params *p,
                                lsdem_wall_result *res, lsdem_error *err);

/* ------------------------------------------------------ resting contacts ---- */

/* Resting contacts as constraints (not in the report; Guendelman et al. 2003, the report's
 * reference for its wall sequence, and every rigid-body engine): a contact whose pair
 * touched in the previous step and whose approach is slower than a resting speed that
 * vanishes with dt is inelastic (e = 0) and solved by projected Gauss-Seidel on
 * ACCUMULATED impulses P (one per contact, world frame, on a; -P on b), warm-started from
 * the previous step's. Each update makes the contact stick at its target normal speed,
 * dP = K^-1 (target n - u) (K eq 4.13), adds dP to P and projects the sum on Coulomb's
 * cone (P . n >= 0, |P_t| <= mu P . n: eqs 4.15-4.16 on the total), applying the
 * difference; so a contact's total impulse can shrink again (a load that moves away),
 * unlike ETM's monotone increments. Overlaps are taken out at a rate: the target normal
 * speed is bias (depth - slop) / dt, at most max_push, on a wall at most the wall guard's
 * push-out cap of the excess (lsdem_push_out_cap; lsdem_resting_target), so a
 * resting pile keeps its overlaps near the slop instead of sinking, and keeps touching
 * (so its contacts stay resting, their impulses warm). */
typedef struct {
  int max_sweeps;   /* Gauss-Seidel sweeps per solve, at most. Default 30 */
  double tolerance; /* stop when a sweep found no contact with |u - target n| above
                       tolerance x ref_speed (velocity residual). Default 1e-2;
                       lsdem_resting_set_colours sets 1e-3 with colours */
  double ref_speed; /* the velocity scale of tolerance: the resting speed (the caller's;
                       0: all sweeps run) */
  double dt;        /* time step (bias); 0: no bias */
  double bias;      /* in [0, 1]: the fraction of the overlap beyond slop removed per step.
                       Default 0.2 */
  double slop;      /* overlap left alone (length). Default 0 */
  double max_push;  /* cap on the target normal speed (velocity); a deep overlap on a
                       wall's is sqrt(max_push excess / dt) (lsdem_push_out_cap).
                       Default unbounded */
  double warm;      /* in [0, 1]: the fraction of last step's impulse re-applied. Default 1 */
  int shock;        /* 1: after the sweeps, one shock-propagation sweep: contacts ordered by the breadth-first level of their bodies
                       from the walls, the lower side frozen (infinite mass), so that a
                       stack stops in one sweep whatever its height and mass ratios
                       (Guendelman et al. 2003). It does not conserve momentum in the
                       step (the frozen side misses its reaction); its impulses enter P,
                       so the next step's warm start applies them to both sides and a
                       stack's load reaches the floor one level per step. Default 1 */
  int colours;      /* 1: the sweeps visit the contacts in colours -- runs of one pair's
                       contacts, coloured greedily in which's order so that no two runs of
                       a colour share a moving body -- colour by colour, and threads share
                       each colour: the same bits on any thread count; 0: in which's order,
                       on one thread. Default 0 */
  int threads;      /* with colours: OpenMP threads sharing the sweeps and the rows (>= 1;
                       an island of fewer than 64 pairs per thread takes one). Default 1 */
} lsdem_resting_params;

void lsdem_resting_params_default(lsdem_resting_params *p);
/* colours on (1) or off (0), with the tolerance that serves that order: 1e-3 in colours,
 * 1e-2 (the default) in the island's order */
void lsdem_resting_set_colours(lsdem_resting_params *p, int colours);
double lsdem_resting_target(const lsdem_resting_params *p, double depth, int on_wall);

typedef struct {
  int sweeps;       /* sweeps run */
  double residual;  /* the largest |u - target n| found in the last sweep (velocity) */
  double work;      /* kinetic energy the resting impulses added, warm start included
                       (negative: dissipated), the exact sum of dP . (u- + u+) / 2 */
  double warm_work; /* of which the warm start */
  int threads;      /* threads that shared the sweeps (lsdem_resting_params.threads) */
  int cold;         /* 1: the solve added more energy than the bias may (sum of m v^2
                       over the island's grains, v the largest of max_push and the
                       contacts' target speeds) and was done again from the
                       entry state, cold and without the shock sweep */
} lsdem_resting_result;

size_t lsdem_resting_workspace_size(int nbodies, int ncontacts);

/* The resting solve over the contacts which[0..nwhich) of an island (bodies and contacts
 * as for ETM) in that order, or the sweeps in colours made from it
 * (lsdem_resting_params.colours); sort it by global keys for rank-independent bits.
 * impulse[c] holds contact c's accumulated impulse: the previous step's (re-projected on
 * this step's cone, scaled by warm and applied first when warm_start) or the one an
 * earlier solve of this step left (warm_start 0: not applied again); on return the new
 * totals. Bodies' velocities change in place; walls do not. LSDEM_ERR_ARG for bad
 * parameters or indices, LSDEM_ERR_NOMEM when ws (lsdem_resting_workspace_size bytes) is
 * too small. res is always filled. */
lsdem_status lsdem_resting_solve(lsdem_impulse_body *bodies, int nbodies,
                                 const lsdem_impulse_contact *contacts, int ncontacts,
                                 const int32_t *which, int nwhich, double (*impulse)[3],
                                 int warm_start, const lsdem_resting_params *p, void *ws,
                                 size_t wsize, lsdem_resting_result *res, lsdem_error *err);

/* ------------------------------------------------------ one island's solve ---- */

/* The velocity solve of one contact island, in stages (issue 33: collisions are events,
 * resting contacts constraints):
 *   1. resting contacts (resting[k] != 0; e = 0): lsdem_resting_solve, warm-started;
 *   2. collisions: when a colliding contact (resting[k] == 0) approaches faster than
 *      approach_floor, or a resting one still approaches faster than collide_speed (an
 *      impulse of this step made it collide), ETM (lsdem_etm_solve) over all the island's
 *      contacts; a resting contact takes its restitution only if the solve makes it
 *      approach faster than collide_speed (then a collision's impulse travels through a
 *      pile elastically: a Newton's cradle), else e = 0; a quiet island costs no ETM.
 * resting NULL: every contact is a collision (the report's method: ETM alone, and only
 * when something approaches faster than approach_floor -- 0 takes any approach).
 * impulse: as for lsdem_resting_solve (read and written for resting contacts only);
 * collision (NULL: not wanted): receives each contact's impulse of stage 2 (0 if none). */
typedef struct {
  lsdem_etm_params etm;
  lsdem_resting_params rest;
  double approach_floor; /* velocity >= 0 */
  double collide_speed;  /* velocity >= 0; the resting speed */
} lsdem_island_params;

void lsdem_island_params_default(lsdem_island_params *p); /* the stages' defaults, 0, 0 */

typedef struct {
  int nresting;               /* resting contacts solved in stage 1 */
  int etm_ran;                /* 1: stage 2 ran */
  lsdem_resting_result rest;  /* stage 1 */
  lsdem_etm_result etm;       /* stage 2 (zero when it did not run) */
  double rest_seconds;        /* wall-clock time of stage 1 */
} lsdem_island_result;

size_t lsdem_island_workspace_size(int nbodies, int ncontacts);

/* Returns the stages' status (their errors, with err set); LSDEM_ERR_NOMEM when ws
 * (lsdem_island_workspace_size bytes) is too small. */
lsdem_status lsdem_island_solve(lsdem_impulse_body *bodies, int nbodies,
                                const lsdem_impulse_contact *contacts, int ncontacts,
                                const uint8_t *resting, double (*impulse)[3],
                                double (*collision)[3], int warm_start,
                                const lsdem_island_params *p, void *ws, size_t wsize,
                                lsdem_island_result *res, lsdem_error *err);

/* ------------------------------------------------------ the step's stages ---- */

/* The stages of one step (step.c) over the solver's arrays, which the caller gathers once
 * from its own storage and scatters once after the drift: grain k has the step body
 * body[k] (lsdem_impulse_body_grain; a sphere's with zero inverse inertia: it never turns),
 * grain[k] what the stages need beyond it, and moving[k] != 0 when it is integrated (else
 * it is a body of prescribed velocity, which every stage leaves alone). A stage runs over
 * grains 0..n-1 (the caller's own: on a rank, its owned grains); reductions over ranks are
 * the caller's. */
typedef struct {
  double q[4];                /* orientation, body -> world, scalar first */
  double inertia[3];          /* principal moments (absolute) */
  double mass;
  double radius;              /* bounding radius */
  double force[3], torque[3]; /* the step's external force and torque (world; the torque
                                 about the centre of mass) */
  const lsdem_shape *shape;   /* an analytic sphere (sdf kind LSDEM_SDF_SPHERE) drifts
                                 without turning */
  int32_t groups;             /* the caller's group bits: a wall acts on the grains whose
                                 groups meet its own */
} lsdem_impulse_grain;

/* One contact of the step as the stages keep it: the island contact c (c.a, c.b: indices
 * into the step's bodies) with its pair and what the stages decided about it. */
typedef struct {
  int32_t i, j;        /* grain of a (the caller's index); of b, or -1 - w for wall w */
  int64_t ta, tb;      /* their global ids (wall w: -(w + 1)) */
  int32_t key;         /* the contact's place among its pair's contacts (gluing order) */
  int32_t approaching; /* 1: its island needs solving now (lsdem_impulse_stage_select) */
  int32_t resting;     /* 1: a resting contact (lsdem_impulse_stage_classify) */
  double P[3];         /* resting: its accumulated impulse (world; on a, -P on b) */
  double J[3];         /* the collision solves' impulses on it this step (world, on a) */
  lsdem_impulse_contact c;
} lsdem_impulse_step_contact;

/* What the stages of a step share: the method, dt and the thresholds derived from the
 * resting speed (lsdem_impulse_step_thresholds). */
typedef struct {
  int split;                   /* 1: resting contacts as constraints, collisions by ETM
                                  (issue 33); 0: the report's method, ETM alone */
  int wall_etm;                /* report's method: resting wall contacts that approach go
                                  into ETM too, inelastic (e = 0) */
  double dt;
  double residual;             /* split: ETM leaves approaches slower than residual times
                                  the resting speed to the next step's resting solve */
  double approach_floor;       /* a contact approaches below -approach_floor
                                  (lsdem_impulse_approaching) */
  lsdem_wall_params wall;      /* the wall guard's (mu: 0, the caller sets it per wall) */
  lsdem_island_params island;  /* the islands' solve */
} lsdem_impulse_step;

/* 1/2 m v^2 + 1/2 omega . I omega, I = R I0 R^T from the principal moments and q. */
double lsdem_impulse_kinetic_energy(double mass, const double inertia[3], const double q[4],
                                    const double v[3], const double omega[3]);
/* The moving grains' kinetic energy at their step velocities, summed in grain order. */
double lsdem_impulse_stage_kinetic_energy(const lsdem_impulse_body *body,
                                          const lsdem_impulse_grain *grain,
                                          const char *moving, int n);

/* Stage 1, kick: every moving grain's v, omega += dt f/m, dt I^-1 torque (eqs 4.37, 4.39,
 * lsdem_impulse_kick). Returns the largest external acceleration |f|/m among them (0 for
 * none), whose maximum over all grains sets the resting speed. work (NULL: not wanted) is
 * raised by the kick's exact work, lsdem_impulse_work of f dt and torque dt per grain. */
double lsdem_impulse_stage_kick(lsdem_impulse_body *body, const lsdem_impulse_grain *grain,
                                const char *moving, int n, double dt, double *work);

/* The resting speed when the caller does not set one: the speed the largest external
 * acceleration amax gives in `steps` steps, steps amax dt. */
double lsdem_impulse_auto_rest_speed(double steps, double amax, double dt);

/* The step's thresholds from the resting speed r (velocity) and s->dt, s->split:
 *   wall guard: rest_speed r; depth_tol r dt / 200 (lsdem_wall_params_default's rule,
 *     1 % of |g| dt^2 with r = 2 |g| dt), with split twice the resting slop (what the
 *     resting solve leaves, the guard leaves alone); mu 0;
 *   resting solve (from rest, the user's sweeps, tolerance, bias and warm): dt, ref_speed
 *     r, slop r dt (the depth a resting grain sinks by in two steps; overlaps beyond it
 *     are taken out at up to max_push r, a deep one on a wall at the wall guard's cap);
 *   islands (from etm): collide_speed r; split: approach_floor velocity_tol r and ETM's
 *     min_approach s->residual r (an approach slower than that is left to the next step's
 *     resting solve, which takes it as resting, not a collision); the report's method: approach_floor 0 (ETM on every
 *     island with an approaching contact, as selected);
 *   selection: approach_floor velocity_tol r (ETM's tolerance, taken relative to r). */
void lsdem_impulse_step_thresholds(lsdem_impulse_step *s, double rest_speed,
                                   const lsdem_etm_params *etm,
                                   const lsdem_resting_params *rest);

/* Stage 3 (split), classify: a contact is resting when it does not approach faster than
 * the resting speed (lsdem_wall_classify not colliding: the report's rule for walls,
 * §4.4.1, for every contact), else colliding; sets c[k].resting. The approach is taken at
 * the velocities body holds: the caller passes the bodies as they were BEFORE the step's
 * kick (Guendelman et al. 2003's order: the kick's |g| dt is what every resting contact
 * approaches with, not an impact; taken after it, a ball on a floor with e = 0.65 at the
 * impact speed it gains from the kick and from sinking one step below the floor kept a
 * 4-step micro-bounce at 3.3 g dt for ever). The caller warm-starts the resting ones. */
void lsdem_impulse_stage_classify(const lsdem_impulse_body *body,
                                  lsdem_impulse_step_contact *c, int n, double rest_speed);

/* Stage 4, which contacts a pass of the islands' solve takes (the collision selection;
 * "approaching" as lsdem_impulse_approaching with s->approach_floor):
 *   split: every contact, flagged approaching when it approaches, or in the first pass
 *     when it is resting (an island is solved when it has a flagged contact: in the first
 *     pass those with a resting or an approaching contact, later only those a wall
 *     correction made approach);
 *   report's method: the contacts are copied to coll (*ncoll of them, flagged): every
 *     contact between two grains (an island is a chain of touching grains, §4.5: impulses
 *     propagate along it, so a contact that does not approach now takes part when the
 *     solve makes it approach); a wall's when it collides (approaches faster than the
 *     resting speed, lsdem_wall_classify), and with wall_etm its resting contacts that
 *     approach, with e = 0; the other wall contacts are the wall guard's (§4.4.1: "only
 *     dynamic collisions are considered"). coll holds n, and is not touched with split.
 * Returns the number of colliding contacts that approach (split: not resting). */
int lsdem_impulse_stage_select(const lsdem_impulse_body *body,
                               lsdem_impulse_step_contact *contacts, int n,
                               const lsdem_impulse_step *s, int first_pass,
                               lsdem_impulse_step_contact *coll, int *ncoll);

/* What the wall guard knows of a grain against a wall within a step (zero it at the step's
 * start): a grain whose velocities are those it had when last checked and which was clear
 * then is not checked again (its predicted pose, so its manifold and result, are the same). */
typedef struct {
  double v[3], omega[3]; /* the grain's velocities when last checked */
  int clear;             /* 1: it was clear then */
  int corrected;         /* 1: corrected by the last pass (lsdem_impulse_stage_wall_guard) */
  double impulse[3];     /* the impulse it was given then (the wall takes minus it) */
  double work;           /* the kinetic energy that correction gave it (lsdem_wall_result);
                            0 when not corrected by the last pass */
} lsdem_wall_guard_seen;

/* One wall as the guard meets it in a step. */
typedef struct {
  const lsdem_boundary *boundary;
  int32_t groups;             /* it acts on the grains whose groups meet these bits */
  lsdem_pose pose;            /* its pose at the step's end */
  lsdem_detect_params detect; /* the detection against it */
  lsdem_wall_params prm;      /* the step's (lsdem_impulse_step.wall) with its friction */
  /* cheap rejection before any lookup (NULL: none): grain k with near[k] == 0 reaches the
   * wall only after its centre moves farther than far_gap, so it is skipped when
   * dt |v| < far_gap (the wall fix's candidates, their margin less what the grains and the
   * wall moved since they were found) */
  const unsigned char *near;
  double far_gap;
  /* grain k's node list against the wall from the step's detection (lists[k].valid 0, or
   * lists NULL: none), looked up read-only while it holds at the predicted pose
   * (detect.node_skin > 0): a list changes the work, never the result */
  const lsdem_nodelist *lists;
} lsdem_impulse_guard_wall;

/* Stage 5, the wall guard of one wall (report §4.4.1, Figures 4.4-4.5): every moving grain
 * whose groups meet the wall's and that w->near does not reject, at its predicted pose
 * (lsdem_impulse_predict_pose; first its centre alone, against the wall's bounding test),
 * is detected against the wall, its
 * push-out limited (lsdem_wall_limit_push_out) and its resting contact corrected
 * (lsdem_wall_correct). seen: one per grain (seen[k] for grain k), as above. points,
 * npoints: manifold storage (a grain's manifold capacity). Returns the number of grains
 * corrected, or -1 - k when grain k's correction failed (err set). */
int lsdem_impulse_stage_wall_guard(lsdem_impulse_body *body, const lsdem_impulse_grain *grain,
                                   const char *moving, int n, const lsdem_impulse_guard_wall *w,
                                   int64_t step, double dt, lsdem_contact_point *points,
                                   int npoints, lsdem_wall_guard_seen *seen, lsdem_error *err);

/* Stage 5b, the ball guard (report §4.4.2 and Figure 4.4: "membrane sphere velocity was
 * corrected after it advanced to the next time step to ensure impenetrability"; the order
 * matters, "as the grain may otherwise pass through the membrane"). After the collisions
 * are resolved, each pair of a net ball and a grain is tested at the PREDICTED poses
 * x' = x + v dt (lsdem_impulse_predict_pose), as the wall guard tests a grain against a
 * wall (§4.4.1). A pair that overlaps there deeper than depth_tol gets, at its deepest
 * point p (normal n from b towards a, arms r_a, r_b about the predicted centroids), the
 * normal impulse P = lambda n on a and -P on b (eqs 4.31-4.32) that raises the point's
 * relative normal velocity by d/dt, so that the overlap the advance would leave closes
 * (§4.4.1: x^{t+1} = x^t + v* dt with v* corrected at x' = x + v dt):
 *   Delta u_n = n . K P = d / dt,  lambda = (d / dt) / (n . K n)  (K: eqs 4.8, 4.13)
 * A ball is not a wall: the grain takes -P, so momentum and angular momentum are kept.
 * Unlike the wall guard, it also takes the pairs that approach faster than the resting
 * speed (u_n < -rest_speed at the deepest point, lsdem_wall_classify: a collision within
 * the step, which ETM did not see at the current poses), so that a fast grain is not
 * carried between two balls; such a pair bounces as a collision of restitution e would
 * (its normal velocity to -e u_n; e is eq 4.1's, a velocity ratio for one frictionless
 * contact), or more if that does not close the overlap:
 *   Delta u_n = max(d / dt, -(1 + e) u_n)   (a collision),   d / dt   (otherwise)
 * Normal only (the collisions' friction is ETM's).
 * Every pair of a pass is corrected from the same state (Jacobi: lambda depends on the
 * geometry and masses alone, not on the velocities the other pairs change), with each
 * body's mass split among its overlapping pairs (its inverse mass and inertia times their
 * number c, "mass splitting", Tonge, Benevolenski and Voroshilov 2012): a grain on c balls
 * is pushed once, not c times (c parallel contacts whose arms add no turn together raise
 * each one's u_n by exactly d/dt; with a turn a pass lifts less, and the next goes on). The
 * caller repeats the passes (islands, walls, balls) until nothing is corrected or a cap. */
typedef struct {
  int32_t a, b;      /* bodies: indices into the step's bodies and grains, a != b */
  /* set by lsdem_impulse_ball_guard_detect */
  int32_t overlapping; /* 1: deeper than depth_tol at the predicted poses */
  double depth;      /* the deepest point's overlap there (after the push-out limit) */
  double lift;       /* the rise of its relative normal velocity the correction makes */
  double normal[3];  /* its unit normal, from b towards a */
  double arm_a[3], arm_b[3]; /* its arms about a's and b's predicted centroids */
} lsdem_ball_guard_pair;

/* Detection of the ball guard: pairs[k] at the predicted poses of its bodies (first their
 * bounding spheres' centres; the master by lsdem_contact_roles, one-way: a ball against a
 * grain is its centre looked up in the grain's level set), its deepest point kept when
 * deeper than p->depth_tol (p->mu is not used). An overlap d0 the pair has now (detected
 * at the current poses: the wall guard's linear estimate d + u_n dt fails for a ball
 * sliding round a grain, whose normal turns within the step) is taken out no faster than
 * the wall guard's cap (lsdem_push_out_cap with p->rest_speed): the depth becomes
 * d - d0 + cap dt when d0 / dt exceeds the cap (the step's new overlap closed at once).
 * The lift: d / dt, or for a collision max(d / dt, -(1 + e) u_n) (e: restitution, [0, 1]); count[i] (the caller zeroes it, one
 * per body) is raised by one for each body of an overlapping pair. points, npoints:
 * manifold storage (the master's capacity). Returns the number of overlapping pairs. */
int lsdem_impulse_ball_guard_detect(const lsdem_impulse_body *body,
                                    const lsdem_impulse_grain *grain,
                                    lsdem_ball_guard_pair *pairs, int n,
                                    const lsdem_detect_params *det, const lsdem_wall_params *p,
                                    double e, double dt, int64_t step,
                                    lsdem_contact_point *points, int npoints, int32_t *count);

/* The pair's impulse lambda n on a, lambda = lift / (n . K n) (eqs 4.8, 4.13 with each
 * body's inverse mass and inertia times its count; 0 when the pair does not overlap or both
 * bodies have infinite mass), returned in P. */
void lsdem_ball_guard_impulse(const lsdem_impulse_body *body, const lsdem_ball_guard_pair *q,
                              const int32_t *count, double P[3]);

/* The correction: every overlapping pair's impulse (lsdem_ball_guard_impulse) on its bodies
 * whose index is below nown (the caller's own: a ghost's change comes from its owner, which
 * lists the same pair), in pair order. Returns the number of pairs corrected whose a is
 * below nown (summed over ranks that own each a once: every pair counted once). work (NULL:
 * not wanted) is raised by the impulses' exact work on those bodies
 * (lsdem_impulse_apply_work; the energy audit). */
int lsdem_impulse_ball_guard_correct(lsdem_impulse_body *body,
                                     const lsdem_ball_guard_pair *pairs, int n,
                                     const int32_t *count, int nown, double *work);

/* Stage 6, the CFL check (report §4.3.4): the largest |v| dt / radius of the moving grains (a
 * non-finite ratio counts as HUGE_VAL) and its grain in *worst (-1: none, the ratio 0). */
double lsdem_impulse_stage_cfl(const lsdem_impulse_body *body,
                               const lsdem_impulse_grain *grain, const char *moving, int n,
                               double dt, int *worst);

/* Stage 7, damp and drift: every moving grain's v, omega *= 1 - xi dt (eqs 4.44-4.46,
 * lsdem_impulse_damp), the kinetic energy it takes added to *damped grain by grain, from
 * the scale factor: KE (1 - (1 - xi dt)^2); then x += v dt and q turned (eqs 4.38, 4.40,
 * lsdem_impulse_drift) in body[k].x and grain[k].q (an analytic sphere: x only, omega set
 * to 0), the kinetic energy change of the turn (lsdem_impulse_drift's; a sphere's: minus
 * its rotational energy) added to *drift (NULL: not wanted). LSDEM_ERR_ARG unless
 * 0 <= xi dt <= 1. */
lsdem_status lsdem_impulse_stage_damp_drift(lsdem_impulse_body *body,
                                            lsdem_impulse_grain *grain, const char *moving,
                                            int n, double xi, double dt, double *damped,
                                            double *drift, lsdem_error *err);

/* The energy audit of a step: the moving grains' kinetic energy change over the step
 * (translation and rotation, measured) against the work each stage books by its own
 * arithmetic -- never by measuring the energy around the stage:
 *   kick     lsdem_impulse_stage_kick: f . v dt + |f|^2 dt^2 / 2m plus the torque's;
 *   etm      lsdem_etm_result.work: each collision impulse's work as applied;
 *   resting  lsdem_resting_result.work: each increment's dP . u + dP . K dP / 2;
 *   wall     lsdem_wall_result.work: the correction's normal and friction impulses;
 *   ball     lsdem_impulse_ball_guard_correct's: each impulse's work as applied;
 *   damping  minus the damped energy, KE (1 - (1 - xi dt)^2) per grain (eqs 4.44-4.45);
 *   drift    the free rotation's 1/2 L . (omega' - omega) (lsdem_impulse_drift);
 *   sleep    minus the energy of the grains put to sleep (the caller's).
 * Each is exact in real arithmetic, so the residual is round-off. Units: energy. */
typedef struct {
  double kick, etm, resting, wall, ball, damping, drift, sleep;
} lsdem_impulse_audit;

/* The terms' sum, and the sum of their magnitudes in *scale (NULL: not wanted). */
double lsdem_impulse_audit_sum(const lsdem_impulse_audit *a, double *scale);
/* |(ke_after - ke_before) - sum of the terms| relative to the step's energy scale, the
 * largest of ke_before, ke_after and the sum of the terms' magnitudes (0 when all are 0). */
double lsdem_impulse_audit_residual(double ke_before, double ke_after,
                                    const lsdem_impulse_audit *a);

/* ------------------------------------------------------------ sleeping ---- */

/* Sleeping islands (Box2D's and Bullet's rule, an option of fix impulse/lsdem): an island
 * falls asleep when every grain of it has been slow for a time; a sleeping island skips
 * detection and the solve until an awake body comes within reach. A grain is slow when
 * |v| < speed and |omega| radius < speed (radius: its bounding radius, so both terms are
 * surface speeds). Returns the grain's new sleep clock: clock + dt when slow, else 0.
 * Units: speed length/time, radius length, dt and the clock time. */
double lsdem_sleep_clock(double clock, const double v[3], const double omega[3],
                         double radius, double speed, double dt);

/* ------------------------------------------------------------ islands ---- */

/* Contact islands (report §4.5) as connected components of the contact graph, by
 * union-find with path halving and union by size. Walls are not graph vertices (a wall
 * would join every grain touching it into one island): a pair naming a negative index
 * (LSDEM_ISLAND_NONE) is skipped, its wall contact belongs to the grain's island.
 * Labels are the smallest global id of each island: independent of the order of pairs
 * and bodies, and comparable across ranks. */
#define LSDEM_ISLAND_NONE (-1)

/* parent and size hold n entries; label (n) receives each body's island label. pairs
 * holds 2 npairs body indices (pairs[2k], pairs[2k+1]). Returns the number of islands. */
int lsdem_islands_build(int n, const int64_t *id, int npairs, const int32_t *pairs,
                        int32_t *parent, int32_t *size, int64_t *label);
/* The root of i's island (with path halving). */
int32_t lsdem_islands_find(int32_t *parent, int32_t i);
/* One step of the cross-rank merge: body[k] (a local index) has a neighbour (a ghost's
 * owner, or a ghost of ours on another rank) whose label is nlabel[k]. Every local island
 * takes the smallest label among its own and those its members received; returns 1 if any
 * label changed. Iterated with the exchange of labels between ranks until no rank
 * changes, every island ends labelled by the smallest id of its global island. parent
 * and label as left by lsdem_islands_build (or a previous merge). */
int lsdem_islands_merge(int n, int32_t *parent, int64_t *label, int m, const int32_t *body,
                        const int64_t *nlabel);
/* Invariants: parent indices in range, no cycles other than roots, every body's label
 * that of its root. LSDEM_ERR_ARG naming the first broken one. */
lsdem_status lsdem_islands_validate(int n, const int32_t *parent, const int64_t *label,
                                    lsdem_error *err);

#ifdef __cplusplus
}
#endif
#endif /* LSDEM_IMPULSE_H */
