/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute contact/lsdem: what pair_style lsdem found on its last force call.
   local array: one row per contact test with penetrating nodes (force chains), and one
   per grain touching a fix wall/lsdem;
   per-atom vector: coordination number (report eq 3.15).
   (The workload counters are pair lsdem's extra values: compute pair lsdem.)
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(contact/lsdem,ComputeContactLsdem);
// clang-format on
#else

#ifndef LMP_COMPUTE_CONTACT_LSDEM_H
#define LMP_COMPUTE_CONTACT_LSDEM_H

#include "compute.h"

#include <vector>

namespace LAMMPS_NS {

class ComputeContactLsdem : public Compute {
 public:
  ComputeContactLsdem(class LAMMPS *, int, char **);
  ~ComputeContactLsdem() override;
  void init() override;
  void compute_local() override;
  void compute_peratom() override;
  double memory_usage() override;

 private:
  class PairLsdem *pair;
  int nmax_local, nmax_atom;
  double **alocal;
  double *coord;
  bool with_walls;                          // rows for wall contacts (keyword walls)
  std::vector<class FixWallLsdem *> walls;  // the wall/lsdem fixes, in fix order

  void check_current();
  bool selected(int, int) const;
};

}    // namespace LAMMPS_NS

#endif
#endif
