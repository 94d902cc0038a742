/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   pair_style lsdem/impulse/omp: pair_style lsdem/impulse's detection with the grains of a
   rank shared among threads (package omp N, or -sf omp). Each thread tests the master
   pairs of a contiguous run of the neighbor list's grains in its own lane (contact path,
   node-list lane, manifold storage); the lanes' manifolds are joined in lane order, which
   is the serial order: fix impulse/lsdem sees the same contacts in the same order, so the
   run has the same bits as without threads.
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(lsdem/impulse/omp,PairLsdemImpulseOMP);
// clang-format on
#else

#ifndef LMP_PAIR_LSDEM_IMPULSE_OMP_H
#define LMP_PAIR_LSDEM_IMPULSE_OMP_H

#include "pair_lsdem_impulse.h"
#include "thr_omp.h"

namespace LAMMPS_NS {

class PairLsdemImpulseOMP : public PairLsdemImpulse, public ThrOMP {
 public:
  PairLsdemImpulseOMP(class LAMMPS *);
  void compute(int, int) override;
  void init_style() override;
  double memory_usage() override;
};

}    // namespace LAMMPS_NS

#endif
#endif
