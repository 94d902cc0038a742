/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute erotate/lsdem: rotational kinetic energy of rigid grains (scalar) and their
   total spin angular momentum about their own centroids (vector, world frame).
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(erotate/lsdem,ComputeERotateLsdem);
// clang-format on
#else

#ifndef LMP_COMPUTE_EROTATE_LSDEM_H
#define LMP_COMPUTE_EROTATE_LSDEM_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeERotateLsdem : public Compute {
 public:
  ComputeERotateLsdem(class LAMMPS *, int, char **);
  ~ComputeERotateLsdem() override;
  void init() override;
  double compute_scalar() override;
  void compute_vector() override;

 private:
  class AtomVecLsdem *avec;
};

}    // namespace LAMMPS_NS

#endif
#endif
