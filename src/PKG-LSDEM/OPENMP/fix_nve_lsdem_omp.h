/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix nve/lsdem/omp: fix nve/lsdem with the rank's grains shared among threads
   (package omp N, or -sf omp); each grain's step is independent of the others', so the
   result is fix nve/lsdem's to the bit.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(nve/lsdem/omp,FixNVELsdemOMP);
// clang-format on
#else

#ifndef LMP_FIX_NVE_LSDEM_OMP_H
#define LMP_FIX_NVE_LSDEM_OMP_H

#include "fix_nve_lsdem.h"

#include <vector>

namespace LAMMPS_NS {

class FixNVELsdemOMP : public FixNVELsdem {
 public:
  FixNVELsdemOMP(class LAMMPS *lmp, int narg, char **arg) : FixNVELsdem(lmp, narg, arg) {}
  void init() override;
  void initial_integrate(int) override;

 private:
  std::vector<int> first_bad;      // per thread: its first unstable grain, or -1
  std::vector<const char *> why;   // and how
};

}    // namespace LAMMPS_NS

#endif
#endif
