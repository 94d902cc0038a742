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

#include "pair.h"
#include "lsdem_contact_options.h"
#include "lsdem_contact_path.h"
#include "lsdem_kernel.h"

namespace LAMMPS_NS {

class PairLsdem : public Pair {
 public:
  // one master-on-slave test that found penetrating nodes on the last force call
  struct Contact {
    int i, j;       // master (owned) and slave (owned or ghost) local indices
    int counts;     // 1 if this test decides the pair's contact status (coordination)
    double scale;   // factor applied to res's forces (two-way half, zcap)
    lsdem_contact_result res;
  };

  PairLsdem(class LAMMPS *);
  ~PairLsdem() override;
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

  // read-only access for compute contact/lsdem
  int ncontacts() const { return ncontact; }
  const Contact *contacts() const { return contact; }
  bigint contacts_step() const { return contact_step; }
  const double *coordination(int to_ghosts);

 protected:
  lsdem_roles_rule mode;        // oneway (report) or twoway (symmetric average)
  LsdemContactOptions global;   // pair_style's normal law, stride and node lists
  int zcap;                     // coordination cap (report §3.3.3), 0 = off

  lsdem_contact_params **params;  // per type pair
  double *onerad, *maxrad;        // largest bounding radius per type (local, global)
  double kn_max;                  // stiffest per-node normal spring, for dt checks

  class AtomVecLsdem *avec;
  class FixLsdemHistory *fix_history;  // nullptr when mu == 0 for every type pair
  LsdemContactPath path;               // each pair's state, manifold, law, commit

  // per local+ghost atom, refreshed every force call; grown only when nmax grows
  int nmax_atom;
  lsdem_pose *pose;
  const lsdem_shape **shape;
  double *ncount;  // contacts per atom (coordination number, eq 3.15)

  // the neighbor list's pairs (i, j) in which i is master, with their scale; rebuilt in
  // the force call that follows each neighbor list build (neighbor->ago == 0)
  int master_built;
  int nmax_master, maxmaster;
  int *master_first, *master_num;  // per local atom: its run in master_j / master_scale
  int *master_j;
  double *master_scale_of;

  Contact *contact;
  int ncontact, maxcontact;
  bigint contact_step;
  bigint ntested_pairs, ntested_nodes, npen_nodes;  // workload of the last force call

  void allocate();
  void update_poses();
  void build_master_pairs();
  void test_pair(int, int, double, bigint);
  void add_contact(int, int, double, const lsdem_contact_result &);
  void apply_contacts();
  void tally_workload();
  void check_periodic_length() const;
  bool bounding_spheres_overlap(int, int) const;
  double reverse_depth(int, int);
  void report_overlaps();
  double stiffest_node_spring() const;
};

}    // namespace LAMMPS_NS

#endif
#endif
