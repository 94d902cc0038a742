/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   bond_style lsdem/membrane/omp: bond_style lsdem/membrane with the bonds' forces computed
   by the threads of a rank (package omp N, or -sf omp), each a contiguous run of the bond
   list, into the style's per-bond buffer; the scatter onto the atoms stays in bond-list
   order on one thread, so the forces are those of lsdem/membrane bit for bit. It writes
   atom->f itself, after the threaded styles' reduction: not an OPENMP-package /omp style
   in fix omp's sense (no per-thread force arrays; doc/howto_parallel.rst).
------------------------------------------------------------------------- */

#ifdef BOND_CLASS
// clang-format off
BondStyle(lsdem/membrane/omp,BondLsdemMembraneOMP);
// clang-format on
#else

#ifndef LMP_BOND_LSDEM_MEMBRANE_OMP_H
#define LMP_BOND_LSDEM_MEMBRANE_OMP_H

#include "bond_lsdem_membrane.h"

namespace LAMMPS_NS {

class BondLsdemMembraneOMP : public BondLsdemMembrane {
 public:
  BondLsdemMembraneOMP(class LAMMPS *lmp) : BondLsdemMembrane(lmp) {}

 protected:
  void all_bond_terms() override;
};

}    // namespace LAMMPS_NS

#endif
#endif
