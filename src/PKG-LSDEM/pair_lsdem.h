/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   pair_style lsdem: node-to-surface contact between level-set grains (report
   Algorithm 2, eqs 2.2-2.16). Thin glue over the core (core/contact): gathers poses,
   asks the core who is master of each pair (lsdem_contact_roles), runs each pair through
   the path it shares with fix wall/lsdem (lsdem_contact_path.h: state, manifold, law,
   commit), applies force/torque to both grains (ghost forces are summed back by
   LAMMPS: newton pair on).
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(lsdem,PairLsdem);
// clang-format on
#else

#ifndef LMP_PAIR_LSDEM_H
#define LMP_PAIR_LSDEM_H

#include "atom.h"
#include "pair.h"
#include "lsdem_contact_options.h"
#include "lsdem_contact_path.h"
#include "lsdem_kernel.h"
#include "lsdem_lane_padding.h"

#include <memory>
#include <vector>

namespace LAMMPS_NS {

class PairLsdem : public Pair {
 public:
  // the bounding spheres of atoms i and j (local or ghost) overlap at their positions now
  // (report eq 2.1): the pair is tested
  bool bounding_spheres_overlap(int i, int j) const
  {
    const double *a = atom->x[i], *b = atom->x[j];
    const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    const double rsum = atom->radius[i] + atom->radius[j];
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < rsum * rsum;
  }
  // one master-on-slave test that found penetrating nodes on the last force call
  struct Contact {
    int i, j;       // master (owned) and slave (owned or ghost) local indices
    int counts;     // 1 if this test decides the pair's contact status (coordination)
    double scale;   // factor applied to res's forces (two-way half, zcap)
    lsdem_contact_result res;
    Contact() {}  // left unset: a test fills it (PairLsdem::test_pair)
  };

  PairLsdem(class LAMMPS *);
  ~PairLsdem() override;
  // the pair style lsdem (or lsdem/omp) of this run, alone or in pair_style hybrid; nullptr
  static PairLsdem *of(class Force *);
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void reset_dt() override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  void *extract(const char *, int &) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;
  double atom2cut(int) override;
  double radii2cut(double, double) override;

  // read-only access for compute contact/lsdem and compute stress/lsdem: the contacts of
  // the last force call, lane by lane (one lane per thread of pair_style lsdem/omp), in
  // the neighbor list's order of their masters
  template <class Visit> void each_contact(Visit visit) const
  {
    for (int l = 0; l < nlanes; l++)
      for (const Contact &c : lanes[l]->contact) visit(c);
  }
  bigint contacts_step() const { return contact_step; }
  // the normal stiffness of the stiffest contact a grain of library shape s can form: the
  // stiffest type pair's kn times the node springs one flat contact presses
  // (lsdem_flat_contact_nodes, returned in `nodes`); for fix nve/lsdem's time-step check
  double stiffest_contact(int s, double &nodes);
  bool traction() const { return global.law.normal == LSDEM_NORMAL_TRACTION; }
  const double *coordination(int to_ghosts);

 protected:
  lsdem_roles_rule mode;        // oneway (report) or twoway (symmetric average)
  LsdemContactOptions global;   // pair_style's normal law, stride and node lists
  int zcap;                     // coordination cap (report §3.3.3), 0 = off

  lsdem_contact_params **params;  // per type pair
  double *onerad, *maxrad;        // largest bounding radius per type (local, global)
  double kn_max;                  // stiffest per-node normal spring (quanta, membrane)
  double kn_law_max;              // stiffest type pair's kn (per node or per area)
  std::vector<double> flat_nodes; // per library shape: lsdem_flat_contact_nodes, -1 = not yet
  std::vector<double> node_scale; // per library shape: lsdem_contact_node_scale (roles)
  lsdem_quantum force_q, torque_q;  // order-free sums of the grains' forces and torques

  class AtomVecLsdem *avec;
  class FixLsdemHistory *fix_history;  // nullptr when mu == 0 for every type pair
  // sphere masters' springs, one slot per master pair; nullptr when mu == 0 everywhere
  class FixLsdemSphereShear *sphere_shear;
  std::vector<tagint> partner_tags;  // scratch of assign_sphere_slots

  // one thread's share of a force call (pair_style lsdem/omp; one lane without threads):
  // its contact path (manifold storage, the history's lane), the contacts it found, its
  // workload counters
  struct Lane {
    LsdemContactPath path;
    std::vector<Contact> contact;
    bigint ntested_pairs = 0, ntested_nodes = 0, npen_nodes = 0;
    LsdemLanePadding apart;  // written by its thread at every test: off the next lane's lines
  };
  std::vector<std::unique_ptr<Lane>> lanes;
  int nlanes;  // lanes used by the last force call

  // per local+ghost atom, refreshed every force call; grown only when nmax grows
  int nmax_atom;
  lsdem_pose *pose;
  const lsdem_shape **shape;
  double *ncount;  // contacts per atom (coordination number, eq 3.15)
  // per local atom: its master pairs' node tests on the last force call, the measure of
  // its cost by which pair_style lsdem/omp cuts the grains into threads' runs
  int *grain_node_tests;

  // the neighbor list's pairs (i, j) in which i is master, with their scale; rebuilt in
  // the force call that follows each neighbor list build (neighbor->ago == 0)
  int master_built;
  int nmax_master, maxmaster;
  int *master_first, *master_num;  // per local atom: its run in master_j / master_scale
  int *master_j;
  double *master_scale_of;

  bigint contact_step;

  void allocate();
  void set_lanes(int);
  void begin_force_call(int nlanes);
  void update_poses(int from, int to);
  void build_master_pairs();
  void test_pairs(Lane &, int iifrom, int iito);
  void test_grain(Lane &, int i);
  void test_pair(Lane &, int, int, double, lsdem_shear_hist *slot);
  // owned grain i is a sphere keeping its springs in slots (sphere_shear)
  bool keeps_sphere_slots(int i) const
  {
    return sphere_shear && shape[i]->sdf.kind == LSDEM_SDF_SPHERE;
  }
  void assign_sphere_slots(int i);
  template <class F> F *internal_fix(const char *fix_id, const char *style);
  void end_force_call();
  void apply_contacts(Lane &, double **f, double **torque) const;
  // the workload of the last force call into pvector (compute pair), touching: the grain
  // pairs in contact it found
  void tally_workload(double touching);
  double contacting_pairs() const;
  void check_periodic_length() const;
  double reverse_depth(int, int);
  void report_overlaps();
  double stiffest_node_spring();
};

}    // namespace LAMMPS_NS

#endif
#endif
