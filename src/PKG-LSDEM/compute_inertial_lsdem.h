/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute inertial/lsdem: inertial number of a sheared specimen (report eq 3.5) from the
   strain rate and the confining pressure, with the group's mean equivalent diameter and
   density; warns once when it exceeds the quasi-static limit.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(inertial/lsdem,ComputeInertialLsdem);
// clang-format on
#else

#ifndef LMP_COMPUTE_INERTIAL_LSDEM_H
#define LMP_COMPUTE_INERTIAL_LSDEM_H

#include "compute.h"

#include <string>

namespace LAMMPS_NS {

class ComputeInertialLsdem : public Compute {
 public:
  ComputeInertialLsdem(class LAMMPS *, int, char **);
  void init() override;
  double compute_scalar() override;

 private:
  struct Input {
    double value;
    std::string var;  // equal-style variable name, or empty
    int ivar;
  };
  Input rate, pressure;
  double limit;  // warn once when I > limit
  bool warned;
  class AtomVecLsdem *avec;

  void parse_input(Input &, const char *);
  double value_of(const Input &);
};

}    // namespace LAMMPS_NS

#endif
#endif
