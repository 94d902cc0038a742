/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix nve/lsdem: leapfrog rigid-body integrator of the report (§2.2.7, eqs 2.17-2.29).
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(nve/lsdem,FixNVELsdem);
// clang-format on
#else

#ifndef LMP_FIX_NVE_LSDEM_H
#define LMP_FIX_NVE_LSDEM_H

#include "fix.h"

#include <string>

namespace LAMMPS_NS {

class FixNVELsdem : public Fix {
 public:
  FixNVELsdem(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void initial_integrate(int) override;

 protected:
  int integrated_count() const;
  int step_grains(int from, int to, const char *&what);
  void stop_if_unstable(int bad, const char *what);

 private:
  double xi;  // global damping, 1/time (eqs 2.18, 2.20)
  class AtomVecLsdem *avec;
  bool spheres_rotate;  // analytic spheres turn (keyword spheres, default rotate)
  int fixed_spin;       // group bits of atoms that keep 3 degrees of freedom: membrane balls
  double warned_dt;     // the time step last warned about (init runs at every run and write)

  void check_timestep();
  std::string unstable_message(int, double, const char *) const;
};

}    // namespace LAMMPS_NS

#endif
#endif
