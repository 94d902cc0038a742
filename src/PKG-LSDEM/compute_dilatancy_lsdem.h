/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute dilatancy/lsdem: dilatancy angle (report eq 3.10) from the increments of two
   equal-style strain variables between successive invocations.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(dilatancy/lsdem,ComputeDilatancyLsdem);
// clang-format on
#else

#ifndef LMP_COMPUTE_DILATANCY_LSDEM_H
#define LMP_COMPUTE_DILATANCY_LSDEM_H

#include "compute.h"

#include <string>

namespace LAMMPS_NS {

class ComputeDilatancyLsdem : public Compute {
 public:
  ComputeDilatancyLsdem(class LAMMPS *, int, char **);
  void init() override;
  double compute_scalar() override;

 private:
  std::string name[2];  // equal-style variables: volumetric, axial strain
  int ivar[2];
  double prev[2];       // their values at the previous invocation
  bigint prev_step;     // -1: none yet
};

}    // namespace LAMMPS_NS

#endif
#endif
