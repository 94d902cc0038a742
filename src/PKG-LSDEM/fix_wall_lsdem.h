/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix wall/lsdem: a rigid wall (plane, cylindrical container, or a mesh or terrain as a
   narrow-band level set made by lsdem-shape wall / terrain) that the
   grains' nodes touch through the same core kernel as grain-grain contact (the wall
   is the slave level set, report §4.6.3). Optional wall velocity; optionally a plane
   pivots about the ram contact point behind it (report §3.2.1). The wall itself, its
   motion and its tests (may a grain touch it, has one crossed it, where is it) are the
   core's (core/boundary: lsdem_boundary).
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(wall/lsdem,FixWallLsdem);
// clang-format on
#else

#ifndef LMP_FIX_WALL_LSDEM_H
#define LMP_FIX_WALL_LSDEM_H

#include "fix.h"
#include "lsdem_contact_options.h"
#include "lsdem_contact_path.h"
#include "lsdem_kernel.h"
#include "lsdem_lane_padding.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixWallLsdem : public Fix {
 public:
  FixWallLsdem(class LAMMPS *, int, char **);
  ~FixWallLsdem() override;
  int setmask() override;
  void post_constructor() override;
  void init() override;
  void setup(int) override;
  void initial_integrate(int) override;
  void post_force(int) override;
  void reset_dt() override;
  double compute_vector(int) override;

  // grains touched on the last force call, for compute stress/lsdem (owned atoms)
  struct Contact {
    int i;                          // local index of the grain
    double force[3], point[3];      // force of the wall on the grain, contact point
    int npen;                       // penetrating nodes
    // for the force map (keyword map): the nearest triangle, the wall's normal at the
    // point, the grain's sliding distance |v_t| dt, whether the contact began this step
    int64_t tri;
    double normal[3], slide;
    bool began;
  };
  template <class Visit> void each_contact(Visit visit) const
  {
    for (int l = 0; l < nlanes; l++)
      for (const Contact &c : lanes[l]->contact) visit(c);
  }
  bigint contacts_step() const { return contact_step; }
  void write_restart(FILE *) override;
  void restart(char *) override;

  // for fix impulse/lsdem, which takes the wall over (report §4.4.1): the wall (its level
  // set, its pose now: moved in initial_integrate, whether it pivots), its friction;
  // passive = no penalty forces of its own
  const lsdem_boundary &boundary() const { return bnd; }
  double wall_friction() const { return opts.law.mu; }
  void set_passive(bool on);
  // the wall's pose s after now (lsdem_boundary_pose_at; s = -dt: at the step's start)
  lsdem_pose pose_at(double s) const;
  // the wall acts on grain i at pose w: i is of the wall's group and its bounding sphere
  // may reach the wall (lsdem_boundary_may_touch); the force path's rule
  bool reaches(int i, const lsdem_pose &w) const;
  bool reaches_at(int i, double phi) const;  // the same, phi the centre's distance to it
  // the wall's contacts as manifolds (detection, no law) at its pose s after now, by the
  // force path's visit (candidates, reaches, the contact path with its pair states: node
  // lists): visit(i, manifold) for each owned grain i with take[i] != 0 whose nodes touch
  // the wall. Once a step, in place of the force call (it writes the step's pair states).
  typedef std::function<void(int, const lsdem_manifold &)> ManifoldVisit;
  void each_manifold(double s, const char *take, const ManifoldVisit &visit);
  // the wall as the wall guard meets it (lsdem_impulse_stage_wall_guard) with the step's
  // parameters `step`: at its pose s after now, its group, its detection, the owned
  // grains' node lists from the step's detection (read only, where they still hold at the
  // predicted poses; no new list is made there), its friction, and its candidates as the
  // guard's cheap rejection (guard_gap)
  lsdem_impulse_guard_wall guard_wall(double s, const lsdem_wall_params &step);
  bool tests_points() const { return twoway; }  // keyword twoway yes
  // fix impulse/lsdem: the force its contacts put on this wall this step (added to the
  // wall's force output; passive walls start each step from zero)
  void add_reaction(const double force[3])
  {
    for (int d = 0; d < 3; d++) flocal[d] += force[d];
    fall_valid = 0;
  }

 protected:
  // one thread's share of a force call (fix wall/lsdem/omp: one lane per thread): its
  // grains' pair states, contacts, force and torque on the wall, and the first of its
  // grains that goes through the wall
  struct Lane {
    LsdemContactPath path;
    double f[3], t[3];
    std::vector<Contact> contact;
    std::string crossing;
    // each_manifold with several lanes: the lane's grains with manifolds, their manifolds
    // (point: offset into found_points) and points, in candidate order
    std::vector<int> found_i;
    std::vector<lsdem_manifold> found;
    std::vector<lsdem_contact_point> found_points;
    LsdemLanePadding apart;  // written by its thread at every test: off the next lane's lines
  };
  std::vector<std::unique_ptr<Lane>> lanes;
  int nlanes;  // lanes used by the last force call
  void set_lanes(int);
  virtual int lanes_for_call() const { return 1; }
  virtual void visit_all(const lsdem_pose &w);  // the candidates, by lanes_for_call() lanes
  void begin_force_call(int nlanes, lsdem_pose &w);
  void visit_candidates(Lane &, int from, int to, const lsdem_pose &w);
  void end_force_call();
  int ncand;   // candidate grains of this step (visit_candidates' range)
  // each_manifold's detection: candidates [from, to) by the lane, each manifold to visit
  // (nullptr: kept in the lane's found lists); detect_all: all candidates by n lanes into
  // their found lists (fix wall/lsdem/omp: one lane per thread)
  void detect_candidates(Lane &, int from, int to, const lsdem_pose &w, const char *take,
                         const ManifoldVisit *visit);
  virtual void detect_all(const lsdem_pose &w, const char *take, int n);

 private:
  lsdem_boundary bnd;          // the wall: kind, pose, velocity, pivoting platen
  lsdem_band_file *band_file;  // mesh and terrain walls: the mapped band (else nullptr)
  lsdem_band exact_band;       // keyword exact yes: the band with its pseudonormals (the
  lsdem_pseudonormals exact_pn;   // wall's level set then), else unused
  // keyword twoway yes: the band's sharp points (made once here) tested against the grains'
  // level sets too, and the most of them a grain can hold (manifold room)
  bool twoway;
  lsdem_band_points points;
  int point_cap;
  // a band wall's thinnest ridge (width across, where) found at init, HUGE_VAL when none
  // thinner than half the largest grain radius: the time-step bound for thin walls
  lsdem_thin_feature thinnest;
  bool thin_searched;
  LsdemContactOptions opts;    // the contact law and detection keywords
  lsdem_contact_params prm;    // what the core gets (node skin and dt set at init)
  lsdem_quantum force_q, torque_q;  // order-free sums of the wall's force and torque
  std::string history_id;
  class FixLsdemHistory *fix_history;  // nullptr when mu == 0 and node lists are off
  // the analytic spheres' springs, one slot per sphere (nullptr without friction or with
  // twoway); keeps_sphere_slot(i): sphere i's spring is there, not in fix_history
  std::string sphere_shear_id;
  class FixLsdemSphereShear *sphere_shear;
  bool keeps_sphere_slot(int i) const;
  void assign_sphere_slots();
  class AtomVecLsdem *avec;

  double flocal[3], fall[3];   // force of the grains on the wall: this rank, all ranks
  int fall_valid;
  // motion given as equal-style variables: velocity (0-2) and spin angular velocity (3-5)
  // components, nullptr for a number
  char *vstr[6];
  int vvar[6];
  bool moving;                 // a velocity is set (constant or variable)
  bool passive;                // taken over by fix impulse/lsdem: no forces of its own

  bigint contact_step;
  double tlocal[3];            // torque of the grains on the wall about its point, this rank

  // grains that may touch the wall until the next reneighbouring (local indices), built
  // with the neighbour skin as margin; rebuilt every step when that does not hold
  int *cand;
  int maxcand, cand_nlocal;
  bigint cand_built;           // neighbor->lastcall when cand was built; -1: stale
  double cand_wall_x[3];       // the wall's point then
  // for the wall guard of fix impulse/lsdem (passive walls): the candidates' margin, the
  // step they were found at, the grains' positions then and which grains they are
  double cand_margin;
  bigint cand_step;
  std::vector<double> cand_x;
  std::vector<unsigned char> cand_near;
  std::vector<lsdem_nodelist> guard_lists;  // the owned grains' lists for the wall guard
  bigint drift_step;           // the step of cand_drift
  double cand_drift;           // the most a grain outside the candidates moved since then
  double guard_gap(const lsdem_pose &w);
  void add_contact(Lane &, int, const lsdem_contact_result &, const lsdem_pose &w, bool began);
  void apply_contact(Lane &, int, const lsdem_contact_result &, const lsdem_pose &w, bool began,
                     bool through_band);
  void test_points(Lane &, int, const lsdem_pose &p, const lsdem_pose &w);
  void test_grain(Lane &, int, const lsdem_pose &w, bigint step);
  void test_sphere(Lane &, int, const lsdem_pose &w, lsdem_shear_hist &slot, double phi,
                   const double n[3]);
  void make_points(const char *path);
  template <class Visit>
  void each_candidate(Lane &, int from, int to, const lsdem_pose &w, const char *take,
                      Visit visit);
  bool candidates_can_last() const;
  double candidate_margin() const;
  bool candidates_hold(const lsdem_pose &w) const;
  void find_candidates(const lsdem_pose &w);
  int parse_pivot(int, int, char **, double[3]);
  void reduce_pivot_load();
  void update_velocity();
  void check_plane_in_box() const;
  void check_band_width() const;

  bool may_touch(int, const lsdem_pose &w, double margin) const;
  // grain i's velocity after this step's force, v + dt f / m (fix nve/lsdem's next v)
  void velocity_after_force(int i, double v[3]) const;
  std::string crossing(int, const lsdem_pose &wall) const;
  std::string tunnelled(int, double depth) const;
  void find_thinnest();
  std::string too_fast_for_thin(int) const;

  // per-triangle force maps of a mesh or terrain wall (keyword map N PREFIX)
  bigint map_every;               // 0: no map
  std::string map_prefix;
  lsdem_wall_map map;             // this rank's sums (allocated at the first init)
  std::vector<int64_t> map_restart;  // sums read from a restart file (rank 0), until init
  bigint map_restart_steps;
  bigint map_booked;              // last step whose contacts are in the map
  std::unique_ptr<class LsdemVtkSeries> map_series;
  void book_map();
  void write_map();
  void write_map_vtp(const std::string &path, const std::vector<int64_t> &sum) const;
  void open_band(const std::string &kind, const char *path);
  void use_exact_band(const char *path);
};

}    // namespace LAMMPS_NS

#endif
#endif
