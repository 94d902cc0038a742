/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix membrane/lsdem/omp: fix membrane/lsdem with the first phase of its triangle loops
   (each triangle's vertices, pressure forces, specimen-area share, volume term and area)
   shared among the threads of a rank (package omp N, or -sf omp), each a contiguous run of
   the triangles; the sums and the scatter onto the vertices stay in triangle order on one
   thread, so the forces and outputs are those of fix membrane/lsdem bit for bit.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(membrane/lsdem/omp,FixMembraneLsdemOMP);
// clang-format on
#else

#ifndef LMP_FIX_MEMBRANE_LSDEM_OMP_H
#define LMP_FIX_MEMBRANE_LSDEM_OMP_H

#include "fix_membrane_lsdem.h"

namespace LAMMPS_NS {

class FixMembraneLsdemOMP : public FixMembraneLsdem {
 public:
  FixMembraneLsdemOMP(class LAMMPS *lmp, int narg, char **arg) :
      FixMembraneLsdem(lmp, narg, arg) {}

 protected:
  void for_triangles(TrianglePhase phase) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
