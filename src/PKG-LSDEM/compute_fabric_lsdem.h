/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute fabric/lsdem: deviatoric fabric tensor and anisotropy factor of the grains'
   long axes (report §3.5.4), and per grain the rotation since a reference orientation
   with a flag for grains rotated more than mean + 2 sigma (shear band, report §3.5.3).
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(fabric/lsdem,ComputeFabricLsdem);
// clang-format on
#else

#ifndef LMP_COMPUTE_FABRIC_LSDEM_H
#define LMP_COMPUTE_FABRIC_LSDEM_H

#include "compute.h"
#include "lsdem_lammps_compat.h"

namespace LAMMPS_NS {

class ComputeFabricLsdem : public Compute {
 public:
  ComputeFabricLsdem(class LAMMPS *, int, char **);
  ~ComputeFabricLsdem() override;
  void init() override;
  void compute_vector() override;
  void compute_peratom() override;
  double memory_usage() override;

 private:
  char *id_fix;               // fix STORE holding each grain's reference quaternion
  LsdemCompat::FixStorePeratom *fix;
  class AtomVecLsdem *avec;
  int nmax;
  double **rot;               // per atom: rotation angle (rad), flag, long axis (3)

  void rotation_stats(double &mean, double &sd, double &nflag);
};

}    // namespace LAMMPS_NS

#endif
#endif
