/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix impulse/lsdem: impulse-based LS-DEM (report chapter 4). The time integrator of its
   group (in place of fix nve/lsdem): external forces kick the velocities; the contacts
   found by pair_style lsdem/impulse and against the fix wall/lsdem walls are solved on
   contact islands (across ranks: lsdem_impulse_islands) -- method split (default): resting
   contacts as warm-started constraints, collisions by the Energy Tracking Method; method
   etm: the report's, every collision by ETM and resting wall contacts corrected at the
   predicted positions (§4.4.1) -- then damping and the symplectic Euler drift. The physics
   is the core's (core/impulse); this file is the step's glue.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(impulse/lsdem,FixImpulseLsdem);
// clang-format on
#else

#ifndef LMP_FIX_IMPULSE_LSDEM_H
#define LMP_FIX_IMPULSE_LSDEM_H

#include "fix.h"
#include "lsdem_impulse_islands.h"
#include "lsdem_impulse_warm.h"
#include "lsdem_kernel.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixImpulseLsdem : public Fix {
 public:
  FixImpulseLsdem(class LAMMPS *, int, char **);
  ~FixImpulseLsdem() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void setup_pre_force(int) override;
  void pre_force(int) override;
  void final_integrate() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;

 private:
  // what the user sets
  enum Method { SPLIT, ETM_ONLY };
  Method method;             // split: resting contacts as constraints; etm: the report's
  double restitution, friction, xi;
  lsdem_etm_params etm;
  lsdem_resting_params resting;  // the user's; the step's (dt, speeds, slop) in stage
  int max_points;            // contacts kept per pair after gluing (0: all)
  int max_passes;            // wall-correction passes per step (report: 10)
  double rest_setting;       // resting speed with walls; < 0: auto, rest_steps |a| dt
  double rest_steps;         // keyword rest_steps
  double residual;           // keyword residual: ETM's floor, a fraction of the resting speed
  double glue_setting;       // gluing distance; < 0: auto, twice a shape's node spacing
  double glue_angle;         // radians
  double cfl;                // largest |v| dt per bounding radius
  int cfl_stop;              // 1: stop, 0: warn
  int wall_etm;              // 1: resting wall contacts also in ETM (inelastic)
  double sleep_speed;        // keyword sleep: a grain is slow below this surface speed
  double sleep_after;        // ... and an island sleeps when all its grains were slow this
                             // long (time units); < 0: no sleeping (the default)
  int balls_bit;             // keyword balls: the net balls' group bit (0: no ball guard)

  // what it works with (found at init)
  class AtomVecLsdem *avec;
  class PairLsdemImpulse *pair;
  std::vector<class FixWallLsdem *> walls;
  LsdemImpulseIslands *islands;
  std::vector<double> glue_of_shape;
  LsdemImpulseWarm warm;     // per owned grain: its contacts' impulses at the last step
  // per atom (sleep keyword): time slow (owned grains); the label of the island it sleeps
  // in (its smallest tag when it fell asleep; 0: awake), ghosts' sent in pre_force
  double *sleep_clock, *sleep_label;
  bool sending_sleep;        // forward communication carries sleep_label
  bool sending_counts;       // forward communication carries ball_count
  bool sending_anchor;       // reverse communication carries anchor_f (ghosts' to owners)
  bool has_outside;          // some atom is integrated by no fix (init): anchors' forces kept
  int integrated_bits;       // the groups of every time integrator, this fix's included
  std::vector<int64_t> wake_mine, wake_all, ready_mine, ready_all;
  std::vector<int> counts, displs;
  std::vector<char> blocked;

  // per-step storage, grown only: the solver's arrays (core/impulse, the step's stages)
  std::vector<lsdem_impulse_body> body;    // atoms (local, ghost), then the walls
  std::vector<lsdem_impulse_body> unkicked;  // body before the step's kick (classify)
  std::vector<lsdem_impulse_grain> grain;  // per atom: what the stages need beyond its body
  std::vector<char> moving;                // per atom: in the group
  std::vector<LsdemImpulseContact> contacts, coll;
  std::vector<lsdem_impulse_contact> glued;
  std::vector<int32_t> group, kept;
  std::vector<lsdem_contact_point> wpoints;  // the guards' manifold of one grain
  lsdem_impulse_step stage;                  // this step's method, dt and thresholds
  std::vector<lsdem_wall_guard_seen> wall_seen;  // per wall, then local grain
  std::vector<lsdem_ball_guard_pair> ball_pairs;  // ball-grain pairs of the step (balls)
  std::vector<int32_t> ball_count;                // per atom: its overlapping ball pairs
  // the step's impulses on atoms outside the group (clamped balls: anchors) as forces,
  // one term per contact, pass and kind; summed rounded (anchor_f, 3 per atom) into f
  struct AnchorTerm {
    int i;
    double f[3];
  };
  std::vector<AnchorTerm> anchor_terms;
  std::vector<double> anchor_f;

  // what the step did (this rank), reduced over ranks when output asks
  struct Step {
    LsdemIslandStats first;   // the first pass's islands
    bigint iterations, sweeps;  // ETM iterations, resting sweeps x contacts, all passes
    int largest, rounds, passes, corrections, collisions, max_sweeps, etm_islands, etm_rounds;
    int rest_threads;  // the most threads that shared an island's resting sweeps
    int resting, contacts, pairs;  // resting contacts, contacts (capped), touching pairs
    double absorbed, dissipated, released, resting_work, contact_work;
    double depth, wall_depth;  // deepest grain-grain and grain-wall penetration
    int woken;                 // grains woken (pre_force) before this step
    int ball_corrections;      // ball-grain pairs corrected (all passes)
    double ball_depth;         // deepest ball-grain overlap at the predicted poses (pass 1)
    // the energy audit: the moving grains' kinetic energy at the step's start and end
    // (this rank's owned grains) and each stage's own booking of its work
    double ke_start, ke_end;
    lsdem_impulse_audit audit;
  } now;
  // the audit over all ranks, every step: the last step's residual and the largest since
  // the run's setup (relative to the step's energy scale)
  // the step's audit sums over ranks: KE at start and end, then the terms (close_audit)
  double audit_residual, audit_worst, audit_all[10];
  int woken_pending;           // grains woken in this step's pre_force (now is reset later)
  // this rank's share since start; damped: by global damping and by putting grains to sleep
  double total_dissipated, total_damped, total_truncated;
  double ke_after_kick;      // this rank's grains' kinetic energy before the contacts act
  double t_detect, t_islands, t_etm, t_walls, t_comm;      // seconds since setup
  double t_rest;                                           // of t_etm: resting stages
  double pair_seconds0;
  bigint reduced_step;
  double reduced[48];
  bool cfl_warned;

  void check_integrators();
  bool asleep(int i) const { return sleep_after >= 0.0 && sleep_label[i] != 0.0; }
  void send_sleep_labels();
  int gather_labels(std::vector<int64_t> &mine, std::vector<int64_t> &all);
  void collect_wakers();
  int wake_labels();
  void fall_asleep();
  void report_sleeping_walls();
  void find_walls();
  void set_glue();
  void make_bodies();
  void gather_grain(int i);
  void kick();
  void forward_velocities();
  void gather_contacts();
  void add_pair_contacts();
  void add_wall_contacts();
  void add_glued(int i, int j, tagint ta, tagint tb, int bindex, const lsdem_manifold &m,
                 double mu, double glue);
  void classify();
  void remember_contacts();
  void report_wall_resting();
  void push_on_wall(int w, const double impulse[3]) const;
  bool outside(int i) const;
  void push_on_atoms(const LsdemImpulseContact &c, const double impulse[3]);
  void push_on_atom(int i, const double impulse[3]);
  void report_anchor_forces();
  void body_frame_point(const LsdemImpulseContact &c, double xb[3]) const;
  double group_kinetic_energy() const;
  void solve_contacts();
  void resolve_islands(int pass);
  int correct_walls();
  void find_ball_pairs();
  int correct_balls(int pass);
  void check_cfl();
  void damp_and_drift();
  double moving_kinetic_energy() const;
  void close_audit();
  void scatter_grains();
  double step_start() const;
  double kinetic_energy(int i, const double v[3], const double omega[3]) const;
  void reduce_output();
};

}    // namespace LAMMPS_NS

#endif
#endif
