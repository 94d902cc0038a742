/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute strain/lsdem: per-grain local strain, the best-fit affine deformation of each
   grain's neighbourhood since a reference configuration (Falk & Langer 1998).
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(strain/lsdem,ComputeStrainLsdem);
// clang-format on
#else

#ifndef LMP_COMPUTE_STRAIN_LSDEM_H
#define LMP_COMPUTE_STRAIN_LSDEM_H

#include "compute.h"
#include "lsdem_kernel.h"
#include "lsdem_lammps_compat.h"

namespace LAMMPS_NS {

class ComputeStrainLsdem : public Compute {
 public:
  ComputeStrainLsdem(class LAMMPS *, int, char **);
  ~ComputeStrainLsdem() override;
  void init() override;
  void init_list(int, class NeighList *) override;
  void compute_peratom() override;
  double memory_usage() override;

 private:
  double cutoff;                // neighbourhood radius in the reference (length units)
  lsdem_strain_kind kind;
  int maxneigh;                 // neighbour slots per grain in the store
  char *id_fix;                 // fix STORE: per grain its reference (see store_reference)
  LsdemCompat::FixStorePeratom *fix;
  bool have_reference;
  class AtomVecLsdem *avec;
  class NeighList *list;
  int nmax;
  double **out;                 // per atom: the output columns
  double *dnow;                 // 3 * maxneigh: one grain's neighbour vectors now

  void store_reference();
  int gather_neighbours(int i, const double *ref);
  void write_grain(int i, const double *ref, int n);
};

}    // namespace LAMMPS_NS

#endif
#endif
