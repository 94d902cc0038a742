/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix wall/lsdem/omp: fix wall/lsdem with the wall's candidate grains shared among the
   threads of a rank (package omp N, or -sf omp). Each thread visits a contiguous run of
   the candidates in its own lane (contact path, pair-state lane, contact list, force and
   torque on the wall) and writes its grains' forces (each grain is visited by one
   thread). The wall's totals are sums of terms rounded to the force quanta: the same
   bits as fix wall/lsdem on any thread count (doc/howto_parallel.rst). Under fix
   impulse/lsdem the wall's detection (each_manifold) is shared the same way, each thread's
   manifolds in its lane, visited in lane order (the serial order).
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(wall/lsdem/omp,FixWallLsdemOMP);
// clang-format on
#else

#ifndef LMP_FIX_WALL_LSDEM_OMP_H
#define LMP_FIX_WALL_LSDEM_OMP_H

#include "fix_wall_lsdem.h"

namespace LAMMPS_NS {

class FixWallLsdemOMP : public FixWallLsdem {
 public:
  FixWallLsdemOMP(class LAMMPS *lmp, int narg, char **arg) : FixWallLsdem(lmp, narg, arg) {}
  void init() override;

 protected:
  int lanes_for_call() const override;
  void visit_all(const lsdem_pose &w) override;
  void detect_all(const lsdem_pose &w, const char *take, int n) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
