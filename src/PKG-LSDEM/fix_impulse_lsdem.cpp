// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix impulse/lsdem e mu [keywords] (doc/fix_impulse_lsdem.rst). One step, in
   final_integrate, where f and torque hold this step's external forces at the positions
   the pair style just detected contacts at (report Figure 4.4). The stages are the core's
   (core/impulse/lsdem_impulse.h, step.c) over the solver's arrays, which this fix gathers
   from the atom arrays (make_bodies) and scatters back (scatter_grains); it adds the
   contacts, the communication and the output:
     1. kick (lsdem_impulse_stage_kick), the velocities sent to the ghosts; the resting
        speed (reduced over ranks) and the step's thresholds;
     2. contacts: pair_style lsdem/impulse's manifolds and each grain's against each wall
        at the current poses (the wall's own detection, fix wall/lsdem each_manifold),
        glued (report §4.3.3), at most `points` per pair (lsdem_impulse_cap_contacts);
        method split: classified resting or colliding (lsdem_impulse_stage_classify), a
        resting one warm-started from the grain's LsdemImpulseWarm entries;
     3. passes, at most `passes` (report: 10): the contacts selected
        (lsdem_impulse_stage_select) and the islands solved (lsdem_impulse_islands, core
        lsdem_island_solve) -- method split: resting contacts as constraints, then
        collisions by ETM; method etm: the collisions by ETM -- then the wall guard
        (lsdem_impulse_stage_wall_guard, report §4.4.1; with method split a guard that
        rarely acts); a pass with no correction ends the loop, otherwise the corrected
        velocities go to the ghosts and the collisions they make are resolved in the next
        pass;
     4. the contacts' impulses kept per grain (split), the walls' forces reported, the CFL
        check (lsdem_impulse_stage_cfl), damping and drift (lsdem_impulse_stage_damp_drift);
     5. (keyword sleep) islands fall asleep; the energy audit (close_audit): the moving
        grains' kinetic-energy change against each stage's own booking of its work.
   Positions and velocities are then those of the step's end, as thermo and dumps print
   them. Between steps the fix carries the positions and velocities and (split) each
   grain's resting impulses, in restart files too: a run continued from a restart file is
   the uninterrupted run.
------------------------------------------------------------------------- */

#include "fix_impulse_lsdem.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_wall_lsdem.h"
#include "force.h"
#include "group.h"
#include "lsdem_lammps_compat.h"
#include "math_const.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "pair_lsdem_impulse.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;
using MathConst::MY_PI;

/* a body with zero velocity and angular velocity (a sleeping grain, a still wall) */

static bool still(const double v[3], const double omega[3])
{
  return v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0 && omega[0] == 0.0 && omega[1] == 0.0 &&
      omega[2] == 0.0;
}

// output vector (f_ID[1..N]); see compute_vector and doc/fix_impulse_lsdem.rst
enum {
  V_ISLANDS, V_LARGEST, V_CROSS, V_ITERATIONS, V_PASSES, V_CORRECTIONS, V_COLLISIONS,
  V_ROUNDS, V_KE, V_ABSORBED, V_DISSIPATED, V_RELEASED, V_TOTAL_DISSIPATED, V_TOTAL_DAMPED,
  V_T_DETECT, V_T_ISLANDS, V_T_ETM, V_T_WALLS, V_T_COMM, V_DEPTH, V_WALL_DEPTH,
  V_RESTING, V_SWEEPS, V_ETM_ISLANDS, V_CONTACTS, V_PAIRS, V_PER_PAIR, V_RESTING_WORK,
  V_CONTACT_WORK, V_ETM_ROUNDS, V_T_REST, V_SLEEPING, V_WOKEN, V_BALL_CORRECTIONS,
  V_BALL_DEPTH, V_KICK_WORK, V_ETM_WORK, V_WALL_WORK, V_BALL_WORK, V_DAMP_WORK,
  V_DRIFT_WORK, V_SLEEP_WORK, V_KE_CHANGE, V_AUDIT, V_AUDIT_WORST, V_REST_THREADS, V_SIZE
};

static const char USAGE[] = "fix ID group impulse/lsdem e mu [keyword value ...]";

/* ---------------------------------------------------------------------- */

FixImpulseLsdem::FixImpulseLsdem(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), method(SPLIT), restitution(0.0), friction(0.0), xi(0.0), max_points(-1),
  max_passes(10),
  rest_setting(-1.0), rest_steps(2.0), residual(0.1), glue_setting(-1.0), glue_angle(15.0 * MY_PI / 180.0), cfl(0.5),
  cfl_stop(0), wall_etm(0), sleep_speed(0.0), sleep_after(-1.0), balls_bit(0), avec(nullptr), pair(nullptr), islands(nullptr), total_dissipated(0.0),
  total_damped(0.0), total_truncated(0.0), t_detect(0.0), t_islands(0.0), t_etm(0.0),
  t_rest(0.0),
  t_walls(0.0), t_comm(0.0), pair_seconds0(0.0), reduced_step(-1), cfl_warned(false),
  sleep_clock(nullptr), sleep_label(nullptr), sending_sleep(false), sending_counts(false),
  sending_anchor(false), has_outside(false), integrated_bits(0), woken_pending(0)
{
  if (narg < 5) error->all(FLERR, "Illegal fix impulse/lsdem command: {}", USAGE);
  time_integrate = 1;
  vector_flag = 1;
  size_vector = V_SIZE;
  audit_residual = audit_worst = 0.0;
  memset(audit_all, 0, sizeof(audit_all));
  global_freq = 1;
  extvector = 0;
  restart_global = 1;
  comm_forward = 6;
  comm_reverse = 3;  // islands' labels and flags (1); the anchors' forces (3)
  restart_peratom = 1;
  create_attribute = 1;
  maxexchange_dynamic = 1;
  maxexchange = 3;
  memset(&now, 0, sizeof(now));
  lsdem_resting_params_default(&resting);
  resting.max_sweeps = 10;
  // the core's defaults but alpha 1 and tolerance 1e-3: a pile's islands of ~1000 grains
  // took 1e6 iterations (and more) to reach the core's 1e-6; a residual approach of 1e-3
  // of the island's fastest, taken up again at the next step, moves a grain by 1e-3 u dt
  lsdem_etm_params_default(&etm);
  etm.alpha = 1.0;
  etm.velocity_tol = 1e-3;
  etm.energy_tol = 1e-6;

  restitution = utils::numeric(FLERR, arg[3], false, lmp);
  friction = utils::numeric(FLERR, arg[4], false, lmp);
  if (!(restitution >= 0.0 && restitution <= 1.0))
    error->all(FLERR, "fix impulse/lsdem: restitution e = {} must be in [0, 1] (Stronge's "
               "coefficient: the energy released is e^2 times the energy absorbed)", arg[3]);
  if (!(friction >= 0.0) || !std::isfinite(friction))
    error->all(FLERR, "fix impulse/lsdem: friction mu = {} must be >= 0 and finite", arg[4]);

  for (int iarg = 5; iarg < narg; iarg += 2) {
    const std::string key = arg[iarg];
    const int nval = (key == "cfl" || (key == "sleep" && iarg + 1 < narg &&
                                       strcmp(arg[iarg + 1], "no") != 0)) ? 2 : 1;
    if (iarg + nval >= narg)
      error->all(FLERR, "fix impulse/lsdem: keyword {} needs {} value{}", key, nval,
                 nval > 1 ? "s" : "");
    const char *val = arg[iarg + 1];
    auto number = [&]() { return utils::numeric(FLERR, val, false, lmp); };
    auto count = [&]() { return utils::bnumeric(FLERR, val, false, lmp); };
    if (key == "method") {
      if (strcmp(val, "split") == 0) method = SPLIT;
      else if (strcmp(val, "etm") == 0) method = ETM_ONLY;
      else error->all(FLERR, "fix impulse/lsdem: method must be split (resting contacts as "
                      "constraints, collisions by ETM) or etm (every contact by ETM, the "
                      "report's), not {}", val);
    } else if (key == "points") {
      max_points = strcmp(val, "all") == 0 ? 0 : utils::inumeric(FLERR, val, false, lmp);
      if (max_points < 1 && strcmp(val, "all") != 0)
        error->all(FLERR, "fix impulse/lsdem: points = {} must be all or >= 1 (contacts kept "
                   "per pair after gluing)", val);
    } else if (key == "sweeps") {
      resting.max_sweeps = utils::inumeric(FLERR, val, false, lmp);
      if (resting.max_sweeps < 1)
        error->all(FLERR, "fix impulse/lsdem: sweeps = {} must be >= 1 (Gauss-Seidel sweeps "
                   "over an island's resting contacts per step)", val);
    } else if (key == "colours") {
      if (strcmp(val, "yes") == 0) lsdem_resting_set_colours(&resting, 1);
      else if (strcmp(val, "no") == 0) lsdem_resting_set_colours(&resting, 0);
      else error->all(FLERR, "fix impulse/lsdem: colours must be yes or no, not {}", val);
    } else if (key == "bias") {
      resting.bias = number();
      if (!(resting.bias >= 0.0 && resting.bias <= 1.0))
        error->all(FLERR, "fix impulse/lsdem: bias = {} must be in [0, 1] (the fraction of a "
                   "resting contact's overlap beyond the slop removed per step)", val);
    } else if (key == "damping") {
      xi = number();
      if (!(xi >= 0.0) || !std::isfinite(xi))
        error->all(FLERR, "fix impulse/lsdem: damping xi = {} must be >= 0 (1/time)", val);
    } else if (key == "alpha") {
      etm.alpha = number();
      if (!(etm.alpha >= 1.0) || !std::isfinite(etm.alpha))
        error->all(FLERR, "fix impulse/lsdem: alpha = {} must be >= 1 (each increment is "
                   "1/(alpha n) of the largest deficit; 1 resolves a lone contact at once)", val);
    } else if (key == "beta") {
      etm.beta = number();
      if (!(etm.beta >= 0.0 && etm.beta < 1.0))
        error->all(FLERR, "fix impulse/lsdem: beta = {} must be in [0, 1) (similarity of "
                   "contacts taken together)", val);
    } else if (key == "iterations") {
      etm.max_iterations = count();
      if (etm.max_iterations < 1)
        error->all(FLERR, "fix impulse/lsdem: iterations = {} must be >= 1 (ETM cap per island)", val);
    } else if (key == "rounds") {
      etm.max_rounds = utils::inumeric(FLERR, val, false, lmp);
      if (etm.max_rounds < 1)
        error->all(FLERR, "fix impulse/lsdem: rounds = {} must be >= 1 (compression-separation "
                   "rounds per island)", val);
    } else if (key == "passes") {
      max_passes = utils::inumeric(FLERR, val, false, lmp);
      if (max_passes < 1)
        error->all(FLERR, "fix impulse/lsdem: passes = {} must be >= 1 (wall-correction passes "
                   "per step; the report used 10)", val);
    } else if (key == "share") {
      if (strcmp(val, "bodies") == 0) etm.share = LSDEM_ETM_SHARE_BODIES;
      else if (strcmp(val, "group") == 0) etm.share = LSDEM_ETM_SHARE_GROUP;
      else error->all(FLERR, "fix impulse/lsdem: share must be bodies or group, not {}", val);
    } else if (key == "weighted") {
      if (strcmp(val, "yes") == 0) etm.mass_weighted = 1;
      else if (strcmp(val, "no") == 0) etm.mass_weighted = 0;
      else error->all(FLERR, "fix impulse/lsdem: weighted must be yes or no, not {}", val);
    } else if (key == "tolerance") {
      etm.velocity_tol = number();
      if (!(etm.velocity_tol > 0.0 && etm.velocity_tol < 1.0))
        error->all(FLERR, "fix impulse/lsdem: tolerance = {} must be in (0, 1) (relative "
                   "approach speed left)", val);
      etm.energy_tol = etm.velocity_tol * etm.velocity_tol;
    } else if (key == "residual") {
      residual = number();
      if (!(residual >= 0.0 && residual <= 1.0))
        error->all(FLERR, "fix impulse/lsdem: residual = {} must be in [0, 1] (fraction of "
                   "the resting speed that ETM leaves to the next step's resting solve)", val);
    } else if (key == "rest_steps") {
      rest_steps = number();
      if (!(rest_steps > 0.0) || !std::isfinite(rest_steps))
        error->all(FLERR, "fix impulse/lsdem: rest_steps = {} must be > 0 (rest auto: the "
                   "speed the largest external acceleration gives in this many steps)", val);
    } else if (key == "glue") {
      glue_setting = strcmp(val, "auto") == 0 ? -1.0 : number();
      if (strcmp(val, "auto") != 0 && !(glue_setting >= 0.0))
        error->all(FLERR, "fix impulse/lsdem: glue = {} must be auto or a distance >= 0", val);
    } else if (key == "glue_angle") {
      const double deg = number();
      if (!(deg >= 0.0 && deg < 90.0))
        error->all(FLERR, "fix impulse/lsdem: glue_angle = {} must be in [0, 90) degrees", val);
      glue_angle = deg * MY_PI / 180.0;
    } else if (key == "wall_etm") {
      if (strcmp(val, "yes") == 0) wall_etm = 1;
      else if (strcmp(val, "no") == 0) wall_etm = 0;
      else error->all(FLERR, "fix impulse/lsdem: wall_etm must be yes or no, not {}", val);
    } else if (key == "rest") {
      rest_setting = strcmp(val, "auto") == 0 ? -1.0 : number();
      if (strcmp(val, "auto") != 0 && !(rest_setting >= 0.0))
        error->all(FLERR, "fix impulse/lsdem: rest = {} must be auto or a speed >= 0", val);
    } else if (key == "sleep") {
      if (strcmp(val, "no") == 0) {
        sleep_after = -1.0;
      } else {
        sleep_speed = number();
        sleep_after = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        if (!(sleep_speed > 0.0) || !std::isfinite(sleep_speed) || !(sleep_after >= 0.0) ||
            !std::isfinite(sleep_after))
          error->all(FLERR, "fix impulse/lsdem: sleep {} {}: needs no, or a speed > 0 "
                     "(velocity units: a grain is slow when |v| and |omega| r are below "
                     "it) and a time >= 0 (an island sleeps when all its grains were slow "
                     "this long)", val, arg[iarg + 2]);
      }
    } else if (key == "balls") {
      const int g = lmp->group->find(val);
      if (g < 0)
        error->all(FLERR, "fix impulse/lsdem: balls group {} does not exist (the net's balls: "
                   "group net of lsdem-shape net's PREFIX.in)", val);
      balls_bit = lmp->group->bitmask[g];
    } else if (key == "cfl") {
      cfl = number();
      if (!(cfl > 0.0) || !std::isfinite(cfl))
        error->all(FLERR, "fix impulse/lsdem: cfl fraction = {} must be > 0", val);
      const std::string act = arg[iarg + 2];
      if (act == "warn") cfl_stop = 0;
      else if (act == "stop") cfl_stop = 1;
      else error->all(FLERR, "fix impulse/lsdem: cfl action must be warn or stop, not {}", act);
    } else error->all(FLERR, "fix impulse/lsdem: unknown keyword {}", key);
    iarg += nval - 1;
  }

  // points auto: the report's method keeps every glued contact (as the report), the split
  // method four per pair
  if (max_points < 0) max_points = method == SPLIT ? 4 : 0;

  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  if (!avec) error->all(FLERR, "Fix impulse/lsdem requires atom_style lsdem");
  islands = new LsdemImpulseIslands(lmp, this, avec);
  FixImpulseLsdem::grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
}

/* ---------------------------------------------------------------------- */

FixImpulseLsdem::~FixImpulseLsdem()
{
  delete islands;
  memory->destroy(sleep_clock);
  memory->destroy(sleep_label);
  if (force) {  // the pair style outlives the fix: it must not read freed flags
    auto *p = dynamic_cast<PairLsdemImpulse *>(force->pair_match("^lsdem/impulse", 0));
    if (p) p->set_sleeping(nullptr);
  }
  if (atom) {
    atom->delete_callback(id, Atom::GROW);
    atom->delete_callback(id, Atom::RESTART);
  }
  // the walls still defined are made active again; a wall fix deleted before this one
  // (LAMMPS's teardown deletes fixes in order) is no longer in the list and is not touched:
  // pointers are compared, never dereferenced before they are found
  if (modify)
    for (FixWallLsdem *w : walls)
      for (int k = 0; k < modify->nfix; k++)
        if (modify->fix[k] == w) w->set_passive(false);
}

int FixImpulseLsdem::setmask()
{
  return FINAL_INTEGRATE | (sleep_after >= 0.0 ? PRE_FORCE : 0);
}

/* ---------------------------------------------------------------------- */

void FixImpulseLsdem::init()
{
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "Fix impulse/lsdem does not support run_style respa");
  pair = dynamic_cast<PairLsdemImpulse *>(force->pair_match("^lsdem/impulse", 0));
  if (!pair)
    error->all(FLERR, "Fix impulse/lsdem requires pair_style lsdem/impulse (contact detection "
               "without penalty forces){}", force->pair_style
                   ? fmt::format("; pair_style {} is set", force->pair_style) : "");
  if (domain->xperiodic || domain->yperiodic || domain->zperiodic)
    error->all(FLERR, "Fix impulse/lsdem: periodic boundaries are not supported (an island "
               "wrapping around the box has no single position per grain); use boundary f "
               "or s and walls");
  if (xi * update->dt > 1.0)
    error->all(FLERR, "Fix impulse/lsdem: damping xi * timestep = {} * {} = {} must be <= 1 "
               "(report eq 4.46)", xi, update->dt, xi * update->dt);
  if (sleep_after < 0.0) pair->set_sleeping(nullptr);
  resting.threads = comm->nthreads;  // package omp N: with colours, the colours shared
  // the atoms whose f gets the contacts' impulses: those no time integrator moves (clamped
  // net balls); an atom another fix integrates keeps its f as it was (a force added here
  // would enter that fix's next half-kick)
  integrated_bits = 0;
  for (int f = 0; f < modify->nfix; f++)
    if (modify->fix[f]->time_integrate) integrated_bits |= modify->fix[f]->groupbit;
  int mine = 0, any = 0;
  for (int i = 0; i < atom->nlocal; i++) mine |= outside(i) ? 1 : 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, world);
  has_outside = any != 0;
  check_integrators();
  find_walls();
  set_glue();
  int cap = 1;
  for (int s = 0; s < avec->nshapes(); s++)
    cap = std::max(cap, lsdem_manifold_capacity(lsdem_library_shape(avec->library(), s)));
  wpoints.resize(cap);
  glued.resize(cap);
  group.resize(cap);
  kept.resize(cap);
}

/* ----------------------------------------------------------------------
   a grain has one time integrator: no other fix with time_integrate may share grains
------------------------------------------------------------------------- */

void FixImpulseLsdem::check_integrators()
{
  for (int f = 0; f < modify->nfix; f++) {
    Fix *other = modify->fix[f];
    if (other == this || !other->time_integrate) continue;
    bigint shared = 0, all = 0;
    for (int i = 0; i < atom->nlocal; i++)
      if ((atom->mask[i] & groupbit) && (atom->mask[i] & other->groupbit)) shared++;
    MPI_Allreduce(&shared, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
    if (all > 0)
      error->all(FLERR, "Fix impulse/lsdem {}: fix {} ({}, group {}) also integrates {} of "
                 "its grains; a grain takes one time integrator (unfix {}, or give the two "
                 "fixes disjoint groups)", id, other->id, other->style,
                 lmp->group->names[other->igroup], all, other->id);
  }
}

/* ----------------------------------------------------------------------
   the fix wall/lsdem walls become this fix's: passive (no penalty force), their contacts
   resolved here
------------------------------------------------------------------------- */

void FixImpulseLsdem::find_walls()
{
  walls.clear();
  for (int f = 0; f < modify->nfix; f++) {
    FixWallLsdem *w = dynamic_cast<FixWallLsdem *>(modify->fix[f]);
    if (!w) continue;
    if (w->boundary().pivots)
      error->all(FLERR, "Fix impulse/lsdem: fix wall/lsdem {} pivots (keyword pivot), which "
                 "impulse mode does not support; use a fixed or moving wall", w->id);
    if (w->tests_points())
      error->all(FLERR, "Fix impulse/lsdem: fix wall/lsdem {} has twoway yes, whose sharp-edge "
                 "points impulse mode does not test (only the grains' nodes meet the wall "
                 "there); drop twoway, or use the penalty method", w->id);
    w->set_passive(true);
    walls.push_back(w);
  }
}

/* ----------------------------------------------------------------------
   gluing distance per shape: the user's, or (auto) twice the shape's node spacing, the
   square root of its mean node area (spheres: a single point, nothing to glue)
------------------------------------------------------------------------- */

void FixImpulseLsdem::set_glue()
{
  glue_of_shape.assign(avec->nshapes(), 0.0);
  for (int s = 0; s < avec->nshapes(); s++) {
    const lsdem_shape *sh = lsdem_library_shape(avec->library(), s);
    if (glue_setting >= 0.0) {
      glue_of_shape[s] = glue_setting;
      continue;
    }
    if (sh->nnodes == 0 || !sh->node_area) continue;
    double area = 0.0;
    for (int k = 0; k < sh->nnodes; k++) area += sh->node_area[k];
    glue_of_shape[s] = 2.0 * std::sqrt(area / sh->nnodes);
  }
}

/* ---------------------------------------------------------------------- */

void FixImpulseLsdem::setup(int /*vflag*/)
{
  t_detect = t_islands = t_etm = t_walls = t_comm = t_rest = 0.0;
  pair_seconds0 = pair->detect_seconds();
  memset(&now, 0, sizeof(now));
  reduced_step = -1;
  cfl_warned = false;
  audit_residual = audit_worst = 0.0;
  memset(audit_all, 0, sizeof(audit_all));
}

/* ---------------------------------------------------------------------- */

void FixImpulseLsdem::final_integrate()
{
  if (pair->touches_step() != update->ntimestep)
    error->all(FLERR, "Fix impulse/lsdem: pair_style lsdem/impulse found no contacts at step "
               "{} (its last call was at step {}); the pair style must run every step",
               update->ntimestep, pair->touches_step());
  memset(&now, 0, sizeof(now));
  now.woken = woken_pending;
  woken_pending = 0;
  // the step works on the solver's arrays (bodies: atoms local and ghost, then walls;
  // grains: per atom): gathered here from the atom arrays, scattered back after the drift;
  // ghosts' velocities follow their owners' through forward_velocities
  make_bodies();
  now.ke_start = group_kinetic_energy();
  anchor_terms.clear();
  if (method == SPLIT) unkicked = body;  // classify() takes the approach before the kick
  kick();  // external forces (eqs 4.37, 4.39), the step's thresholds
  forward_velocities();
  ke_after_kick = group_kinetic_energy();
  double t0 = MPI_Wtime();
  gather_contacts();  // the pair style's and the walls' manifolds, glued, capped
  classify();         // method split: resting or colliding, resting ones warm-started
  t_detect += MPI_Wtime() - t0;
  solve_contacts();  // islands: resting solve, collisions by ETM; the wall guard
  remember_contacts();
  report_wall_resting();
  report_anchor_forces();
  // what every stage of the contacts did to the kinetic energy (ETM's restitution and
  // friction, the resting solve, the wall guard): measured, not summed from the parts
  const double contact_work = group_kinetic_energy() - ke_after_kick;
  now.contact_work = contact_work;
  total_dissipated -= contact_work;
  check_cfl();
  damp_and_drift();  // global damping (eqs 4.44-4.46), positions (eqs 4.38, 4.40)
  scatter_grains();
  if (sleep_after >= 0.0) fall_asleep();
  close_audit();
}

/* ----------------------------------------------------------------------
   the islands' solves alternating with the wall guard (report §4.4.1) until no grain is
   corrected or the passes' cap is reached
------------------------------------------------------------------------- */

void FixImpulseLsdem::solve_contacts()
{
  bool corrected = true;
  wall_seen.assign((size_t) atom->nlocal * walls.size(), lsdem_wall_guard_seen());
  if (balls_bit) find_ball_pairs();
  for (int pass = 0; pass < max_passes && corrected; pass++) {
    resolve_islands(pass);
    double t0 = MPI_Wtime();
    const int walls_mine = correct_walls();
    t_walls += MPI_Wtime() - t0;
    const int mine = walls_mine + (balls_bit ? correct_balls(pass) : 0);
    int all = 0;
    t0 = MPI_Wtime();
    MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_SUM, world);
    t_comm += MPI_Wtime() - t0;
    now.passes++;
    now.corrections += walls_mine;
    corrected = all > 0;
    if (corrected) forward_velocities();
  }
  // the cap reached with corrections in the last pass: the collisions they made are
  // resolved, so that no grain approaches another as the step ends
  if (corrected) resolve_islands(max_passes);
}

/* ----------------------------------------------------------------------
   one ETM pass over the islands, velocities sent to the ghosts after it
------------------------------------------------------------------------- */

void FixImpulseLsdem::resolve_islands(int pass)
{
  coll.resize(method == SPLIT ? 0 : contacts.size());  // the report's: the selected copies
  int ncoll = 0;
  const int napproach = lsdem_impulse_stage_select(body.data(), contacts.data(),
                                                   (int) contacts.size(), &stage, pass == 0,
                                                   coll.data(), &ncoll);
  coll.resize(ncoll);
  std::vector<LsdemImpulseContact> &list = method == SPLIT ? contacts : coll;
  LsdemIslandStats st;
  st.clear();
  const std::string mesg = islands->resolve(list.data(), (int) list.size(), body.data(),
                                            moving.data(), stage.island, pass == 0, st);
  // the collision impulses of this pass on the walls and on the atoms outside the group
  // (clamped balls), as forces on them (with method etm list holds this pass's copies)
  for (LsdemImpulseContact &c : list) {
    if (c.j < 0) push_on_wall(-1 - c.j, c.J);
    else if (has_outside) push_on_atoms(c, c.J);
    c.J[0] = c.J[1] = c.J[2] = 0.0;
  }
  if (pass == 0) {
    now.first = st;
    now.collisions = napproach;
    now.resting = (int) st.resting;
  }
  now.iterations += st.iterations;
  now.sweeps += st.sweeps;
  now.max_sweeps = std::max(now.max_sweeps, st.max_sweeps);
  now.rest_threads = std::max(now.rest_threads, st.rest_threads);
  now.etm_islands += st.etm_islands;
  now.etm_rounds = std::max(now.etm_rounds, st.etm_rounds);
  now.largest = std::max(now.largest, st.largest);
  now.rounds = std::max(now.rounds, st.rounds);
  now.absorbed += st.absorbed;
  now.dissipated += st.dissipated;
  now.released += st.released;
  now.resting_work += st.resting_work;
  now.audit.resting += st.resting_work;
  now.audit.etm += st.etm_work;
  total_truncated += st.truncated;
  t_islands += st.t_islands;
  t_etm += st.t_etm - st.t_rest;
  t_rest += st.t_rest;
  t_comm += st.t_comm;
  AtomVecLsdem::stop_if_any_rank(
      lmp, FLERR, mesg.empty() ? mesg : fmt::format(
          "Fix impulse/lsdem: step {}, pass {}: {}. Fix keywords: iterations (now {}), rounds "
          "(now {}), alpha, beta, damping{}", update->ntimestep, pass + 1, mesg,
          etm.max_iterations, etm.max_rounds,
          method == SPLIT ? fmt::format(", residual (now {}; smaller)", residual) : ""));
  forward_velocities();
}

/* ----------------------------------------------------------------------
   the step's bodies: every atom (local and ghost) as a grain of the group, or else a body
   of prescribed velocity, and its grain record; then the walls at their current poses
------------------------------------------------------------------------- */

void FixImpulseLsdem::make_bodies()
{
  const int nall = atom->nlocal + atom->nghost;
  body.resize(nall + walls.size());
  grain.resize(nall);
  moving.resize(nall);
  std::string bad;
  lsdem_error err;
  LsdemImpulseIslands::Item it;
  for (int i = 0; i < nall; i++) {
    moving[i] = ((atom->mask[i] & groupbit) && !asleep(i)) ? 1 : 0;  // sleeping: at rest
    if (moving[i]) {
      islands->body_item(i, it);
      if (LsdemImpulseIslands::grain_body(it, body[i], &err) != LSDEM_OK && bad.empty() &&
          i < atom->nlocal)
        bad = fmt::format("Fix impulse/lsdem: step {}: grain {}: {}", update->ntimestep,
                          atom->tag[i], err.msg);
    } else {
      lsdem_impulse_body_wall(&body[i], atom->tag[i], atom->x[i], atom->v[i], atom->omega[i],
                              nullptr);
    }
    gather_grain(i);
  }
  for (size_t w = 0; w < walls.size(); w++) {
    const lsdem_pose p = walls[w]->pose_at(step_start());
    lsdem_impulse_body_wall(&body[nall + w], -(int64_t) (w + 1), p.x, p.v, p.omega, nullptr);
  }
  AtomVecLsdem::stop_if_any_rank(lmp, FLERR, bad);
}

/* atom i's grain record: orientation, moments, mass, bounding radius, shape, groups and
   its external force and torque (force units through ftm2v) */

void FixImpulseLsdem::gather_grain(int i)
{
  lsdem_impulse_grain &g = grain[i];
  const double ftm2v = force->ftm2v;
  for (int d = 0; d < 4; d++) g.q[d] = avec->quat[i][d];
  for (int d = 0; d < 3; d++) {
    g.inertia[d] = avec->inertia[i][d];
    g.force[d] = ftm2v * atom->f[i][d];
    g.torque[d] = ftm2v * atom->torque[i][d];
  }
  g.mass = atom->rmass[i];
  g.radius = atom->radius[i];
  g.shape = avec->shape_of(i);
  g.groups = atom->mask[i];
}

/* the moving grains' state at the step's end back into the atom arrays */

void FixImpulseLsdem::scatter_grains()
{
  for (int i = 0; i < atom->nlocal; i++) {
    if (!moving[i]) continue;
    for (int d = 0; d < 3; d++) {
      atom->x[i][d] = body[i].x[d];
      atom->v[i][d] = body[i].v[d];
      atom->omega[i][d] = body[i].omega[d];
    }
    for (int d = 0; d < 4; d++) avec->quat[i][d] = grain[i].q[d];
  }
}

/* ----------------------------------------------------------------------
   the time of the grains' current poses, as a wall's pose_at takes it: the walls moved to
   the end of this step in initial_integrate (fix wall/lsdem), the grains move in
   final_integrate, so they are still at the step's start, -dt
------------------------------------------------------------------------- */

double FixImpulseLsdem::step_start() const
{
  return -update->dt;
}

/* ----------------------------------------------------------------------
   external forces over dt (eqs 4.37, 4.39); the resting speed from the largest external
   acceleration of the group (auto) or the user's, and the step's thresholds from it
------------------------------------------------------------------------- */

void FixImpulseLsdem::kick()
{
  const double amax = lsdem_impulse_stage_kick(body.data(), grain.data(), moving.data(),
                                               atom->nlocal, update->dt, &now.audit.kick);
  double rest = rest_setting;
  if (rest < 0.0) {
    double all = 0.0;
    MPI_Allreduce(&amax, &all, 1, MPI_DOUBLE, MPI_MAX, world);
    rest = lsdem_impulse_auto_rest_speed(rest_steps, all, update->dt);
  }
  stage.split = method == SPLIT;
  stage.wall_etm = wall_etm;
  stage.dt = update->dt;
  stage.residual = residual;
  lsdem_impulse_step_thresholds(&stage, rest, &etm, &resting);
}

/* ----------------------------------------------------------------------
   owned grains' velocities (their step bodies) to their ghost copies' bodies
------------------------------------------------------------------------- */

void FixImpulseLsdem::forward_velocities()
{
  const double t0 = MPI_Wtime();
  LsdemCompat::forward_comm(comm, this, 6);
  t_comm += MPI_Wtime() - t0;
}

/* ---------------------------------------------------------------------- */

void FixImpulseLsdem::gather_contacts()
{
  contacts.clear();
  add_pair_contacts();
  add_wall_contacts();
}

/* manifold m of a and b, glued (report §4.3.3), as contacts; bindex: b's body index */

void FixImpulseLsdem::add_glued(int i, int j, tagint ta, tagint tb, int bindex,
                                const lsdem_manifold &m, double mu, double glue)
{
  lsdem_glue_params gp;
  gp.distance = glue;
  gp.max_angle = glue_angle;
  if ((int) glued.size() < m.n) {  // the scratch of gluing and of the cap: m.n each
    glued.resize(m.n);
    group.resize(m.n);
    kept.resize(m.n);
  }
  lsdem_error err;
  int n = lsdem_impulse_glue(&m, i, bindex, mu, restitution, &gp, glued.data(),
                             group.data(), &err);
  if (n < 0) error->one(FLERR, "Fix impulse/lsdem: {}", err.msg);
  if (max_points > 0 && n > max_points)
    n = lsdem_impulse_cap_contacts(glued.data(), n, max_points, kept.data());
  double &deepest = j < 0 ? now.wall_depth : now.depth;
  now.pairs += n > 0;
  now.contacts += n;
  for (int k = 0; k < n; k++) {
    deepest = std::max(deepest, glued[k].depth);
    LsdemImpulseContact c;
    c.i = i;
    c.j = j;
    c.ta = ta;
    c.tb = tb;
    c.key = k;
    c.c = glued[k];
    c.approaching = 0;
    c.resting = 0;
    c.P[0] = c.P[1] = c.P[2] = 0.0;
    c.J[0] = c.J[1] = c.J[2] = 0.0;
    contacts.push_back(c);
  }
}

/* ----------------------------------------------------------------------
   method split: the contacts classified resting or colliding (lsdem_impulse_stage_classify:
   by their approach before the step's kick, at the bodies kept in unkicked; a pair that
   touched at the last step is not
   required: in a settled heap ~5 % of the contacts per step are pairs that flicker in and
   out of touch by a node, and each made a collision of its island); a resting contact
   starts from the impulse of the matching contact of the last step (LsdemImpulseWarm,
   within a radius of the gluing distance or a tenth of the grain's bounding radius, in
   the grain's body frame)
------------------------------------------------------------------------- */

void FixImpulseLsdem::classify()
{
  if (method != SPLIT) return;
  lsdem_impulse_stage_classify(unkicked.data(), contacts.data(), (int) contacts.size(),
                               stage.wall.rest_speed);
  for (LsdemImpulseContact &c : contacts) {
    if (!c.resting) continue;
    double xb[3];
    body_frame_point(c, xb);
    const double glue = glue_of_shape[avec->shape[c.i]];
    warm.take(c.i, (tagint) c.tb, xb, std::max(glue, 0.1 * atom->radius[c.i]), c.P);
  }
}

/* contact c's point in the body frame of its owned grain c.i (at this step's pose) */

void FixImpulseLsdem::body_frame_point(const LsdemImpulseContact &c, double xb[3]) const
{
  double r[3];
  for (int d = 0; d < 3; d++) r[d] = c.c.point[d] - atom->x[c.i][d];
  lsdem_quat_rotate_inv(avec->quat[c.i], r, xb);
}

/* the impulse given to a grain by wall w, as the force on the wall: -impulse / dt
   (force units through ftm2v), into the wall's force output */

void FixImpulseLsdem::push_on_wall(int w, const double impulse[3]) const
{
  const double to_force = -1.0 / (update->dt * force->ftm2v);
  const double f[3] = {to_force * impulse[0], to_force * impulse[1], to_force * impulse[2]};
  walls[w]->add_reaction(f);
}

/* ----------------------------------------------------------------------
   the anchors' share (atoms outside the group that no other fix integrates either: clamped
   net balls, which the contacts treat as bodies of prescribed velocity): the impulse a
   contact gives such an atom (impulse on a: +impulse; on b: -impulse) becomes a force on
   it, impulse / (dt ftm2v), so that its f (fix net/lsdem's anchor reaction, dumps) reads
   the load the grains put on it, as a wall's force output does
------------------------------------------------------------------------- */

bool FixImpulseLsdem::outside(int i) const
{
  return !(atom->mask[i] & integrated_bits);
}

void FixImpulseLsdem::push_on_atoms(const LsdemImpulseContact &c, const double impulse[3])
{
  if (impulse[0] == 0.0 && impulse[1] == 0.0 && impulse[2] == 0.0) return;
  if (outside(c.i)) push_on_atom(c.i, impulse);
  if (c.j >= 0 && outside(c.j)) {
    const double minus[3] = {-impulse[0], -impulse[1], -impulse[2]};
    push_on_atom(c.j, minus);
  }
}

/* impulse on atom i (local or ghost) as a force term, kept for report_anchor_forces */

void FixImpulseLsdem::push_on_atom(int i, const double impulse[3])
{
  const double to_force = 1.0 / (update->dt * force->ftm2v);
  AnchorTerm t;
  t.i = i;
  for (int d = 0; d < 3; d++) t.f[d] = to_force * impulse[d];
  anchor_terms.push_back(t);
}

/* ----------------------------------------------------------------------
   the step's force terms on the atoms outside the group into their f: each term rounded
   to a power-of-two quantum of the largest term of the step (over all ranks;
   lsdem_quantum_for), so that a ball's sum -- its own contacts' terms and those its ghost
   copies gathered on other ranks, added to it by a reverse communication -- is exact and
   the same in any order, on any rank count. Collective.
------------------------------------------------------------------------- */

void FixImpulseLsdem::report_anchor_forces()
{
  if (!has_outside) return;
  const double t0 = MPI_Wtime();
  double big = 0.0, scale = 0.0;
  for (const AnchorTerm &t : anchor_terms)
    for (int d = 0; d < 3; d++) big = std::max(big, std::fabs(t.f[d]));
  MPI_Allreduce(&big, &scale, 1, MPI_DOUBLE, MPI_MAX, world);
  if (scale == 0.0) {  // no impulse on such an atom anywhere this step
    t_comm += MPI_Wtime() - t0;
    return;
  }
  const lsdem_quantum q = lsdem_quantum_for(scale);
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  anchor_f.assign(3 * (size_t) nall, 0.0);
  for (const AnchorTerm &t : anchor_terms)
    for (int d = 0; d < 3; d++) anchor_f[3 * (size_t) t.i + d] += lsdem_quantize(t.f[d], q);
  sending_anchor = true;
  LsdemCompat::reverse_comm(comm, this, 3);
  sending_anchor = false;
  for (int i = 0; i < nlocal; i++)
    if (outside(i))
      for (int d = 0; d < 3; d++) atom->f[i][d] += anchor_f[3 * (size_t) i + d];
  t_comm += MPI_Wtime() - t0;
}

/* ----------------------------------------------------------------------
   the force of the step's resting contacts on each wall, -(impulse on the grains) / dt,
   into the wall's force output (the collision solves' and the wall guard's are added as
   they act): a base pressure or a platen servo reads what the grains do to the wall
------------------------------------------------------------------------- */

void FixImpulseLsdem::report_wall_resting()
{
  for (const LsdemImpulseContact &c : contacts) {
    if (!c.resting) continue;
    if (c.j < 0) push_on_wall(-1 - c.j, c.P);
    else if (has_outside) push_on_atoms(c, c.P);
  }
  if (sleep_after >= 0.0) report_sleeping_walls();
}

/* a sleeping grain pushes on its walls with the resting impulses of its last awake step */

void FixImpulseLsdem::report_sleeping_walls()
{
  for (int i = 0; i < atom->nlocal; i++)
    if (asleep(i))
      warm.each(i, [&](tagint partner, const double P[3]) {
        if (partner < 0) push_on_wall((int) (-1 - partner), P);
      });
}

/* ----------------------------------------------------------------------
   method split: the step's contacts, with their resting impulses, become the owned
   grains' warm-start entries (point in the grain's body frame at this step's pose)
------------------------------------------------------------------------- */

void FixImpulseLsdem::remember_contacts()
{
  if (method != SPLIT) return;
  for (int i = 0; i < atom->nlocal; i++)
    if (!asleep(i)) warm.clear(i);  // a sleeping grain keeps its last impulses
  const double zero[3] = {0.0, 0.0, 0.0};
  for (const LsdemImpulseContact &c : contacts) {
    double xb[3];
    body_frame_point(c, xb);
    warm.add(c.i, (tagint) c.tb, xb, c.resting ? c.P : zero);
  }
  maxexchange = 3 + LsdemImpulseWarm::DOUBLES * warm.largest();
}

void FixImpulseLsdem::add_pair_contacts()
{
  for (int k = 0; k < pair->ntouches(); k++) {
    const PairLsdemImpulse::Touch &t = pair->touch_at(k);
    if (!moving[t.i] && !moving[t.j]) continue;
    const lsdem_manifold m = pair->manifold(k);
    add_glued(t.i, t.j, atom->tag[t.i], atom->tag[t.j], t.j, m, friction,
              glue_of_shape[avec->shape[t.i]]);
  }
}

/* each moving grain's manifold against each wall, by the wall's own detection (fix
   wall/lsdem's each_manifold) at the grains' current poses */

void FixImpulseLsdem::add_wall_contacts()
{
  const int nall = atom->nlocal + atom->nghost;
  for (size_t w = 0; w < walls.size(); w++) {
    const double mu = walls[w]->wall_friction();
    walls[w]->each_manifold(step_start(), moving.data(), [&](int i, const lsdem_manifold &m) {
      add_glued(i, -1 - (int) w, atom->tag[i], -(tagint) (w + 1), nall + (int) w, m, mu,
                glue_of_shape[avec->shape[i]]);
    });
  }
}

/* ----------------------------------------------------------------------
   the wall guard (report §4.4.1; lsdem_impulse_stage_wall_guard): every grain against
   every wall at its predicted pose, resting contacts corrected, their impulses on the
   walls as forces. Returns the corrections made on this rank.
------------------------------------------------------------------------- */

int FixImpulseLsdem::correct_walls()
{
  int corrected = 0;
  const int nlocal = atom->nlocal;
  for (size_t w = 0; w < walls.size(); w++) {
    const lsdem_impulse_guard_wall gw = walls[w]->guard_wall(0.0, stage.wall);  // step's end
    lsdem_wall_guard_seen *seen = wall_seen.data() + w * nlocal;
    lsdem_error err;
    const int n = lsdem_impulse_stage_wall_guard(body.data(), grain.data(), moving.data(), nlocal,
                                                 &gw, update->ntimestep, update->dt,
                                                 wpoints.data(), (int) wpoints.size(), seen, &err);
    if (n < 0)
      error->one(FLERR, "Fix impulse/lsdem: step {}, grain {}, wall {}: {}", update->ntimestep,
                 atom->tag[-1 - n], walls[w]->id, err.msg);
    for (int i = 0; i < nlocal; i++)
      if (seen[i].corrected) {
        push_on_wall((int) w, seen[i].impulse);
        now.audit.wall += seen[i].work;
      }
    corrected += n;
  }
  return corrected;
}

/* ----------------------------------------------------------------------
   the ball guard's pairs (keyword balls): from the pair style's full neighbor list, every
   pair of a ball and an atom outside the balls group with a moving body, listed once on a
   rank that owns one of them (by the owned ball, or by the owned grain when its ball is a
   ghost), a = the ball, b = the grain, sorted by their tags so that each body's impulses
   are summed in the same order on any rank count
------------------------------------------------------------------------- */

void FixImpulseLsdem::find_ball_pairs()
{
  ball_pairs.clear();
  const NeighList *list = pair->list;
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    const int *js = list->firstneigh[i];
    for (int k = 0; k < list->numneigh[i]; k++) {
      const int j = js[k] & NEIGHMASK;
      const bool ball_i = mask[i] & balls_bit, ball_j = mask[j] & balls_bit;
      if (ball_i == ball_j || !(moving[i] || moving[j])) continue;
      if (!ball_i && j < nlocal) continue;  // both owned: listed by the ball
      lsdem_ball_guard_pair q;
      q.a = ball_i ? i : j;
      q.b = ball_i ? j : i;
      ball_pairs.push_back(q);
    }
  }
  const tagint *tag = atom->tag;
  std::sort(ball_pairs.begin(), ball_pairs.end(),
            [tag](const lsdem_ball_guard_pair &p, const lsdem_ball_guard_pair &q) {
              return tag[p.a] != tag[q.a] ? tag[p.a] < tag[q.a] : tag[p.b] < tag[q.b];
            });
}

/* ----------------------------------------------------------------------
   the ball guard (report §4.4.2, Figure 4.4; lsdem_impulse_ball_guard_detect and _correct):
   the wall guard's corrections to the ghosts first (the pairs see the same velocities on
   every rank), each pair at the predicted poses, the owners' counts of overlapping pairs to
   the ghosts (mass splitting), the impulses on the owned bodies. Returns the pairs
   corrected (each counted by its ball's owner).
------------------------------------------------------------------------- */

int FixImpulseLsdem::correct_balls(int pass)
{
  forward_velocities();
  const double t0 = MPI_Wtime();
  const int nall = atom->nlocal + atom->nghost;
  ball_count.assign(nall, 0);
  lsdem_detect_params det;
  det.node_stride = 1;
  det.node_skin = 0.0;
  lsdem_impulse_ball_guard_detect(body.data(), grain.data(), ball_pairs.data(),
                                  (int) ball_pairs.size(), &det, &stage.wall, restitution,
                                  update->dt, update->ntimestep, wpoints.data(), (int) wpoints.size(),
                                  ball_count.data());
  if (pass == 0)
    for (const lsdem_ball_guard_pair &q : ball_pairs)
      now.ball_depth = std::max(now.ball_depth, q.depth);
  t_walls += MPI_Wtime() - t0;
  const double t1 = MPI_Wtime();
  sending_counts = true;
  LsdemCompat::forward_comm(comm, this, 1);
  sending_counts = false;
  t_comm += MPI_Wtime() - t1;
  const int n = lsdem_impulse_ball_guard_correct(body.data(), ball_pairs.data(),
                                                 (int) ball_pairs.size(), ball_count.data(),
                                                 atom->nlocal, &now.audit.ball);
  now.ball_corrections += n;
  // the impulse on an owned body outside the group (a clamped ball), as a force on it (a
  // pair may be listed on two ranks; each body's share is its owner's)
  if (has_outside)
    for (const lsdem_ball_guard_pair &q : ball_pairs) {
      const bool on_a = q.a < atom->nlocal && outside(q.a);
      const bool on_b = q.b < atom->nlocal && outside(q.b);
      if (!q.overlapping || !(on_a || on_b)) continue;
      double P[3];
      lsdem_ball_guard_impulse(body.data(), &q, ball_count.data(), P);
      const double minus[3] = {-P[0], -P[1], -P[2]};
      if (on_a) push_on_atom(q.a, P);
      if (on_b) push_on_atom(q.b, minus);
    }
  return n;
}

/* ----------------------------------------------------------------------
   CFL: a grain that would move more than cfl x its bounding radius in one step can pass
   through another (report §4.3.4); warn (once per run) or stop
------------------------------------------------------------------------- */

void FixImpulseLsdem::check_cfl()
{
  struct {
    double ratio;
    int rank;
  } mine = {0.0, comm->me}, worst;
  double info[4] = {0.0, 0.0, 0.0, 0.0};  // tag, speed, radius, x of the worst grain
  const double dt = update->dt;
  int i = -1;
  mine.ratio = lsdem_impulse_stage_cfl(body.data(), grain.data(), moving.data(), atom->nlocal,
                                       dt, &i);
  if (i >= 0) {
    info[0] = (double) atom->tag[i];
    info[1] = std::sqrt(lsdem_dot3(body[i].v, body[i].v));
    info[2] = atom->radius[i];
  }
  MPI_Allreduce(&mine, &worst, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
  if (worst.ratio <= cfl || (cfl_warned && !cfl_stop)) return;
  MPI_Bcast(info, 4, MPI_DOUBLE, worst.rank, world);
  const std::string mesg = fmt::format(
      "Fix impulse/lsdem: step {}: grain {} moves |v| dt = {:.6g} * {:.6g} = {:.6g} in one "
      "step, {:.3g} of its bounding radius {:.6g} (cfl {}): it may pass through a partner. "
      "Use a timestep below {:.3g}", update->ntimestep, (tagint) info[0], info[1], dt,
      info[1] * dt, worst.ratio, info[2], cfl, cfl * info[2] / info[1]);
  if (cfl_stop) error->all(FLERR, mesg);
  if (comm->me == 0) error->warning(FLERR, mesg + " (further CFL warnings of this run are not "
                                    "printed)");
  cfl_warned = true;
}

/* ----------------------------------------------------------------------
   global damping (eqs 4.44-4.46), then positions and orientations (eqs 4.38, 4.40)
------------------------------------------------------------------------- */

void FixImpulseLsdem::damp_and_drift()
{
  lsdem_error err;
  double damped = 0.0;
  if (lsdem_impulse_stage_damp_drift(body.data(), grain.data(), moving.data(), atom->nlocal,
                                     xi, update->dt, &damped, &now.audit.drift, &err) != LSDEM_OK)
    error->one(FLERR, err.msg);
  total_damped += damped;
  now.audit.damping = -damped;
}

/* ----------------------------------------------------------------------
   the energy audit of the step (lsdem_impulse_audit): the moving grains' kinetic energy
   at the step's end (after sleeping) against its start and the stages' bookings, summed
   over ranks (one reduction per step), the relative residual and its largest since setup
------------------------------------------------------------------------- */

double FixImpulseLsdem::moving_kinetic_energy() const
{
  double ke = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (moving[i]) ke += kinetic_energy(i, atom->v[i], atom->omega[i]);
  return ke;
}

void FixImpulseLsdem::close_audit()
{
  now.ke_end = moving_kinetic_energy();
  const lsdem_impulse_audit &a = now.audit;
  double mine[10] = {now.ke_start, now.ke_end, a.kick,   a.etm,   a.resting,
                     a.wall,       a.ball,       a.damping, a.drift, a.sleep};
  double *all = audit_all;
  const double t0 = MPI_Wtime();
  MPI_Allreduce(mine, all, 10, MPI_DOUBLE, MPI_SUM, world);
  t_comm += MPI_Wtime() - t0;
  const lsdem_impulse_audit sum = {all[2], all[3], all[4], all[5],
                                   all[6], all[7], all[8], all[9]};
  audit_residual = lsdem_impulse_audit_residual(all[0], all[1], &sum);
  if (!(audit_residual <= audit_worst)) audit_worst = audit_residual;  // NaN included
}

/* ----------------------------------------------------------------------
   sleeping islands (keyword sleep). Before the pair style detects contacts: the sleep
   labels to the ghosts, then every sleeping island within reach of an awake body wakes,
   whole: an awake grain of the group, an atom outside it that moves or a moving wall
   whose bounding test (the pair style's, or the wall's may-touch test) meets one of its
   grains, or one of its grains was given a velocity. Repeated until no island wakes (a woken island may reach another), so the
   pair style, which skips pairs of two sleeping grains, meets no pair of an awake and a
   sleeping grain. Decisions use labels gathered from all ranks: the same on any rank
   count.
------------------------------------------------------------------------- */

void FixImpulseLsdem::setup_pre_force(int vflag)
{
  pre_force(vflag);
}

void FixImpulseLsdem::pre_force(int /*vflag*/)
{
  const double t0 = MPI_Wtime();
  send_sleep_labels();
  pair->set_sleeping(sleep_label);
  woken_pending = 0;
  for (;;) {
    collect_wakers();
    if (gather_labels(wake_mine, wake_all) == 0) break;
    woken_pending += wake_labels();
  }
  t_islands += MPI_Wtime() - t0;
}

/* the owners' sleep labels to their ghost copies */

void FixImpulseLsdem::send_sleep_labels()
{
  sending_sleep = true;
  LsdemCompat::forward_comm(comm, this, 1);
  sending_sleep = false;
}

/* every rank's labels in all, sorted, each once; returns how many */

int FixImpulseLsdem::gather_labels(std::vector<int64_t> &mine, std::vector<int64_t> &all)
{
  std::sort(mine.begin(), mine.end());
  mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
  const int n = (int) mine.size();
  counts.resize(comm->nprocs);
  displs.resize(comm->nprocs);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  int total = 0;
  for (int r = 0; r < comm->nprocs; r++) {
    displs[r] = total;
    total += counts[r];
  }
  all.resize(total);
  MPI_Allgatherv(mine.data(), n, MPI_INT64_T, all.data(), counts.data(), displs.data(),
                 MPI_INT64_T, world);
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return (int) all.size();
}

/* the labels of the sleeping islands that an awake body reaches now, into wake_mine */

void FixImpulseLsdem::collect_wakers()
{
  wake_mine.clear();
  // an awake grain wakes what it reaches; an atom outside the group (never asleep) when
  // it moves
  auto moves = [&](int i) {
    return (atom->mask[i] & groupbit) || !still(atom->v[i], atom->omega[i]);
  };
  const NeighList *list = pair->list;
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    const int *js = list->firstneigh[i];
    for (int k = 0; k < list->numneigh[i]; k++) {
      const int j = js[k] & NEIGHMASK;
      if (asleep(i) == asleep(j)) continue;
      const int s = asleep(i) ? i : j, o = asleep(i) ? j : i;
      if (moves(o) && pair->bounding_spheres_overlap(i, j))
        wake_mine.push_back((int64_t) sleep_label[s]);
    }
  }
  // a sleeping grain given a velocity (the velocity or set command between runs) wakes
  for (int i = 0; i < atom->nlocal; i++)
    if (asleep(i) && !still(atom->v[i], atom->omega[i]))
      wake_mine.push_back((int64_t) sleep_label[i]);
  for (FixWallLsdem *w : walls) {
    const lsdem_pose wp = w->pose_at(0.0);
    if (still(wp.v, wp.omega)) continue;
    for (int i = 0; i < atom->nlocal; i++)
      if (asleep(i) && w->reaches(i, wp)) wake_mine.push_back((int64_t) sleep_label[i]);
  }
}

/* the grains (local and ghost) of the islands in wake_all wake; returns the owned ones */

int FixImpulseLsdem::wake_labels()
{
  int woken = 0;
  const int nall = atom->nlocal + atom->nghost;
  for (int i = 0; i < nall; i++) {
    if (!asleep(i) ||
        !std::binary_search(wake_all.begin(), wake_all.end(), (int64_t) sleep_label[i]))
      continue;
    sleep_label[i] = 0.0;
    if (i < atom->nlocal) {
      sleep_clock[i] = 0.0;
      woken++;
    }
  }
  return woken;
}

/* ----------------------------------------------------------------------
   after the step: the sleep clocks of the awake grains (lsdem_sleep_clock), then every
   island of the step's contacts whose grains have all been slow for the sleep time, and
   none of which touches a moving wall or a moving atom outside the group, falls asleep:
   its grains stop (their kinetic energy counts as damped, output 14) and keep their
   warm-start impulses (their walls read them as forces while they sleep). An island is
   labelled by its smallest tag; a grain with no contact is an island of its own.
------------------------------------------------------------------------- */

void FixImpulseLsdem::fall_asleep()
{
  const double t0 = MPI_Wtime();
  const double dt = update->dt;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++)
    if (moving[i])
      sleep_clock[i] = lsdem_sleep_clock(sleep_clock[i], atom->v[i], atom->omega[i],
                                         atom->radius[i], sleep_speed, dt);
  LsdemIslandStats st;
  st.clear();
  const int64_t *label = islands->island_labels(contacts.data(), (int) contacts.size(),
                                                moving.data(), st);
  t_comm += st.t_comm;
  // islands with a grain ready to sleep (on any rank), then those of them with a grain
  // that is not, or that touches a moving body (on any rank)
  ready_mine.clear();
  for (int i = 0; i < nlocal; i++)
    if (moving[i] && sleep_clock[i] >= sleep_after) ready_mine.push_back(label[i]);
  if (gather_labels(ready_mine, ready_all) == 0) {
    t_islands += MPI_Wtime() - t0;
    return;
  }
  blocked.assign(ready_all.size(), 0);
  auto block = [&](int64_t l) {
    auto it = std::lower_bound(ready_all.begin(), ready_all.end(), l);
    if (it != ready_all.end() && *it == l) blocked[it - ready_all.begin()] = 1;
  };
  for (int i = 0; i < nlocal; i++)
    if (moving[i] && sleep_clock[i] < sleep_after) block(label[i]);
  for (const LsdemImpulseContact &c : contacts) {  // against a prescribed body that moves
    const lsdem_impulse_body &a = body[c.c.a], &b = body[c.c.b];
    if (!moving[c.i] && c.j >= 0 && !still(a.v, a.omega)) block(label[c.j]);
    if ((c.j < 0 || !moving[c.j]) && !still(b.v, b.omega)) block(label[c.i]);
  }
  MPI_Allreduce(MPI_IN_PLACE, blocked.data(), (int) blocked.size(), MPI_SIGNED_CHAR, MPI_MAX,
                world);
  for (int i = 0; i < nlocal; i++) {
    if (!moving[i] || sleep_clock[i] < sleep_after) continue;
    const auto it = std::lower_bound(ready_all.begin(), ready_all.end(), label[i]);
    if (blocked[it - ready_all.begin()]) continue;
    const double ke = kinetic_energy(i, atom->v[i], atom->omega[i]);
    total_damped += ke;
    now.audit.sleep -= ke;
    sleep_label[i] = (double) label[i];
    for (int d = 0; d < 3; d++) atom->v[i][d] = atom->omega[i][d] = 0.0;
  }
  t_islands += MPI_Wtime() - t0;
}

/* the kinetic energy of this rank's moving grains at their step velocities */

double FixImpulseLsdem::group_kinetic_energy() const
{
  return lsdem_impulse_stage_kinetic_energy(body.data(), grain.data(), moving.data(),
                                            atom->nlocal);
}

/* 1/2 m v^2 + 1/2 omega . I omega of atom i at velocities v, omega (I from its principal
   moments and quat) */

double FixImpulseLsdem::kinetic_energy(int i, const double v[3], const double omega[3]) const
{
  return lsdem_impulse_kinetic_energy(atom->rmass[i], avec->inertia[i], avec->quat[i], v,
                                      omega);
}

/* ----------------------------------------------------------------------
   the output vector over all ranks, once per step
------------------------------------------------------------------------- */

void FixImpulseLsdem::reduce_output()
{
  if (reduced_step == update->ntimestep) return;
  double sum[21], max[15];
  double ke = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) ke += kinetic_energy(i, atom->v[i], atom->omega[i]);
  sum[0] = now.first.islands;
  sum[1] = now.first.cross;
  sum[2] = (double) now.iterations;
  sum[3] = now.corrections;
  sum[4] = now.collisions;
  sum[5] = ke;
  sum[6] = now.absorbed;
  sum[7] = now.dissipated;
  sum[8] = now.released;
  sum[9] = total_dissipated;
  sum[10] = total_damped;
  sum[11] = total_truncated;
  sum[12] = now.resting;
  sum[13] = now.etm_islands;
  sum[14] = now.contacts;
  sum[15] = now.pairs;
  sum[16] = now.resting_work;
  sum[17] = now.contact_work;
  int sleeping = 0;
  for (int i = 0; i < atom->nlocal; i++) sleeping += asleep(i);
  sum[18] = sleeping;
  sum[19] = now.woken;
  sum[20] = now.ball_corrections;
  max[0] = now.largest;
  max[1] = now.passes;
  max[2] = now.rounds;
  max[3] = t_detect + pair->detect_seconds() - pair_seconds0;
  max[4] = t_islands;
  max[5] = t_etm;
  max[6] = t_walls;
  max[7] = t_comm;
  max[8] = now.depth;
  max[9] = now.wall_depth;
  max[10] = now.max_sweeps;
  max[11] = now.etm_rounds;
  max[12] = t_rest;
  max[13] = now.ball_depth;
  max[14] = now.rest_threads;
  double s[21], m[15];
  MPI_Allreduce(sum, s, 21, MPI_DOUBLE, MPI_SUM, world);
  MPI_Allreduce(max, m, 15, MPI_DOUBLE, MPI_MAX, world);
  reduced[V_ISLANDS] = s[0];
  reduced[V_CROSS] = s[1];
  reduced[V_ITERATIONS] = s[2];
  reduced[V_CORRECTIONS] = s[3];
  reduced[V_COLLISIONS] = s[4];
  reduced[V_KE] = s[5];
  reduced[V_ABSORBED] = s[6];
  reduced[V_DISSIPATED] = s[7];
  reduced[V_RELEASED] = s[8];
  reduced[V_TOTAL_DISSIPATED] = s[9];
  reduced[V_TOTAL_DAMPED] = s[10];
  reduced[V_LARGEST] = m[0];
  reduced[V_PASSES] = m[1];
  reduced[V_ROUNDS] = m[2];
  reduced[V_T_DETECT] = m[3];
  reduced[V_T_ISLANDS] = m[4];
  reduced[V_T_ETM] = m[5];
  reduced[V_T_WALLS] = m[6];
  reduced[V_T_COMM] = m[7];
  reduced[V_DEPTH] = m[8];
  reduced[V_WALL_DEPTH] = m[9];
  reduced[V_RESTING] = s[12];
  reduced[V_SWEEPS] = m[10];
  reduced[V_ETM_ISLANDS] = s[13];
  reduced[V_CONTACTS] = s[14];
  reduced[V_PAIRS] = s[15];
  reduced[V_PER_PAIR] = s[15] > 0.0 ? s[14] / s[15] : 0.0;
  reduced[V_RESTING_WORK] = s[16];
  reduced[V_CONTACT_WORK] = s[17];
  reduced[V_ETM_ROUNDS] = m[11];
  reduced[V_T_REST] = m[12];
  reduced[V_SLEEPING] = s[18];
  reduced[V_WOKEN] = s[19];
  reduced[V_BALL_CORRECTIONS] = s[20];
  reduced[V_BALL_DEPTH] = m[13];
  reduced[V_REST_THREADS] = m[14];
  // the energy audit, reduced by close_audit every step (audit_all: KE start, end, terms)
  const int terms[] = {V_KICK_WORK, V_ETM_WORK, -1, V_WALL_WORK, V_BALL_WORK, V_DAMP_WORK,
                       V_DRIFT_WORK, V_SLEEP_WORK};  // -1: the resting solve's, value 28
  for (int k = 0; k < 8; k++)
    if (terms[k] >= 0) reduced[terms[k]] = audit_all[2 + k];
  reduced[V_KE_CHANGE] = audit_all[1] - audit_all[0];
  reduced[V_AUDIT] = audit_residual;
  reduced[V_AUDIT_WORST] = audit_worst;
  reduced_step = update->ntimestep;
}

/* ----------------------------------------------------------------------
   1 islands (first pass), 2 largest island (grains), 3 islands spanning ranks (first
   pass), 4 ETM iterations, 5 wall-correction passes, 6 wall corrections, 7 collisions
   (first pass), 8 label-exchange rounds (largest pass), 9 kinetic energy of the group,
   10 energy absorbed in compression, 11 dissipated at restitution, 12 released in
   separation (this step), 13 dissipated at contacts and 14 by global damping since the
   start, 15-19 seconds since the run's setup in detection, islands, ETM, walls and
   communication (largest rank), 20 the deepest penetration between two grains and 21 of
   a grain into a wall at the step's start (the impulse method's error: it resolves
   velocities, not overlaps); 22 resting contacts (first pass), 23 Gauss-Seidel sweeps
   of the resting solve (the most any island took, any pass), 24 island solves in which
   ETM ran (all passes), 25 contacts (after gluing and the cap), 26 touching pairs
   (grain-grain and grain-wall), 27 contacts per pair, 28 work of the resting impulses
   and 29 the kinetic-energy change by all contact stages (this step; energy, negative
   when dissipated), 30 ETM compression-separation rounds (the most of any island), 31
   seconds since the run's setup in the resting solve (17: the islands' assembly and ETM,
   without it). 13 is
   minus the sum of 29 since the start. 34 ball-grain pairs corrected by the ball guard
   (keyword balls; all passes) and 35 the deepest ball-grain overlap it found at the
   predicted poses (first pass; length). The energy audit (close_audit): 36-42 the work
   booked by the kick, ETM, the wall guard, the ball guard, damping, the drift's free
   rotation and sleeping (28: the resting solve's), 43 the moving grains' kinetic-energy
   change over the step, 44 the relative residual of 43 against the terms' sum, 45 its
   largest since setup; 46 the most threads that shared an island's resting sweeps
------------------------------------------------------------------------- */

double FixImpulseLsdem::compute_vector(int n)
{
  reduce_output();
  return reduced[n];
}

/* ----------------------------------------------------------------------
   restart: the energy totals (all ranks' shares; read back onto rank 0)
------------------------------------------------------------------------- */

void FixImpulseLsdem::write_restart(FILE *fp)
{
  double mine[3] = {total_dissipated, total_damped, total_truncated}, all[3];
  MPI_Allreduce(mine, all, 3, MPI_DOUBLE, MPI_SUM, world);
  if (comm->me == 0) {
    int size = 3 * sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(all, sizeof(double), 3, fp);
  }
}

void FixImpulseLsdem::restart(char *buf)
{
  const double *list = (const double *) buf;
  const bool root = comm->me == 0;
  total_dissipated = root ? list[0] : 0.0;
  total_damped = root ? list[1] : 0.0;
  total_truncated = root ? list[2] : 0.0;
}

/* ----------------------------------------------------------------------
   per-atom: the warm-start entries of the resting contacts (LsdemImpulseWarm) travel
   with their grain and go into restart files
------------------------------------------------------------------------- */

void FixImpulseLsdem::grow_arrays(int nmax)
{
  warm.grow(nmax);
  memory->grow(sleep_clock, nmax, "impulse/lsdem:sleep_clock");
  memory->grow(sleep_label, nmax, "impulse/lsdem:sleep_label");
}

void FixImpulseLsdem::copy_arrays(int i, int j, int /*delflag*/)
{
  warm.copy(i, j);
  sleep_clock[j] = sleep_clock[i];
  sleep_label[j] = sleep_label[i];
}

void FixImpulseLsdem::set_arrays(int i)
{
  warm.clear(i);
  sleep_clock[i] = sleep_label[i] = 0.0;
}

int FixImpulseLsdem::pack_exchange(int i, double *buf)
{
  buf[0] = sleep_clock[i];
  buf[1] = sleep_label[i];
  return 2 + warm.pack(i, buf + 2);
}

int FixImpulseLsdem::unpack_exchange(int nlocal, double *buf)
{
  sleep_clock[nlocal] = buf[0];
  sleep_label[nlocal] = buf[1];
  return 2 + warm.unpack(nlocal, buf + 2);
}

// restart: the count, the warm-start entries, then (since the sleep keyword) the sleep
// clock and label; a file without them reads as awake
int FixImpulseLsdem::pack_restart(int i, double *buf)
{
  int m = 1 + warm.pack(i, buf + 1);
  buf[m++] = sleep_clock[i];
  buf[m++] = sleep_label[i];
  buf[0] = m;
  return m;
}

void FixImpulseLsdem::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int k = 0; k < nth; k++) m += static_cast<int>(extra[nlocal][m]);
  const double *buf = &extra[nlocal][m];
  const int n = static_cast<int>(buf[0]);
  const int r = 1 + warm.unpack(nlocal, buf + 1);
  const bool has_sleep = n >= r + 2;
  sleep_clock[nlocal] = has_sleep ? buf[r] : 0.0;
  sleep_label[nlocal] = has_sleep ? buf[r + 1] : 0.0;
}

int FixImpulseLsdem::size_restart(int nlocal)
{
  return 4 + LsdemImpulseWarm::DOUBLES * warm.count(nlocal);
}

int FixImpulseLsdem::maxsize_restart()
{
  int mine = 0, all = 0;
  for (int i = 0; i < atom->nlocal; i++) mine = std::max(mine, warm.count(i));
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MAX, world);
  return 4 + LsdemImpulseWarm::DOUBLES * all;
}

/* ----------------------------------------------------------------------
   ghost communication: the step bodies' velocities (6 values), the sleep labels (1), or
   the islands' labels and flags
------------------------------------------------------------------------- */

int FixImpulseLsdem::pack_forward_comm(int n, int *list, double *buf, int, int *)
{
  if (islands->exchanging()) return islands->pack_forward(n, list, buf);
  if (sending_sleep) {
    for (int k = 0; k < n; k++) buf[k] = sleep_label[list[k]];
    return n;
  }
  if (sending_counts) {
    for (int k = 0; k < n; k++) buf[k] = ball_count[list[k]];
    return n;
  }
  int m = 0;
  for (int k = 0; k < n; k++) {
    const int j = list[k];
    for (int d = 0; d < 3; d++) buf[m++] = body[j].v[d];
    for (int d = 0; d < 3; d++) buf[m++] = body[j].omega[d];
  }
  return m;
}

void FixImpulseLsdem::unpack_forward_comm(int n, int first, double *buf)
{
  if (islands->exchanging()) return islands->unpack_forward(n, first, buf);
  if (sending_sleep) {
    for (int k = 0; k < n; k++) sleep_label[first + k] = buf[k];
    return;
  }
  if (sending_counts) {
    for (int k = 0; k < n; k++) ball_count[first + k] = (int32_t) buf[k];
    return;
  }
  int m = 0;
  for (int i = first; i < first + n; i++) {
    for (int d = 0; d < 3; d++) body[i].v[d] = buf[m++];
    for (int d = 0; d < 3; d++) body[i].omega[d] = buf[m++];
  }
}

int FixImpulseLsdem::pack_reverse_comm(int n, int first, double *buf)
{
  if (sending_anchor) {  // the ghosts' anchor forces, added to their owners'
    int m = 0;
    for (int i = first; i < first + n; i++)
      for (int d = 0; d < 3; d++) buf[m++] = anchor_f[3 * (size_t) i + d];
    return m;
  }
  return islands->pack_reverse(n, first, buf);
}

void FixImpulseLsdem::unpack_reverse_comm(int n, int *list, double *buf)
{
  if (sending_anchor) {
    int m = 0;
    for (int k = 0; k < n; k++)
      for (int d = 0; d < 3; d++) anchor_f[3 * (size_t) list[k] + d] += buf[m++];
    return;
  }
  islands->unpack_reverse(n, list, buf);
}

/* ---------------------------------------------------------------------- */

double FixImpulseLsdem::memory_usage()
{
  double bytes = (double) body.capacity() * sizeof(lsdem_impulse_body) + moving.capacity();
  bytes += (double) (contacts.capacity() + coll.capacity()) * sizeof(LsdemImpulseContact);
  bytes += (double) wpoints.capacity() * sizeof(lsdem_contact_point);
  bytes += (double) wall_seen.capacity() * sizeof(lsdem_wall_guard_seen);
  bytes += (double) grain.capacity() * sizeof(lsdem_impulse_grain);
  bytes += warm.memory_usage() + 2.0 * atom->nmax * sizeof(double);
  return bytes + islands->memory_usage();
}
