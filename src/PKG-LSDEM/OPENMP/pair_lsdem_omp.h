/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   pair_style lsdem/omp: pair_style lsdem with the grains of a rank shared among threads
   (package omp N, or -sf omp). Each thread tests the master pairs of a contiguous run of
   the neighbor list's grains (runs of about equal work: a grain weighs its node tests on
   the last force call) in its own lane (contact path, manifold storage, pair-state lane,
   contact list) and applies their forces to its own force and torque arrays, which
   LAMMPS's OPENMP package sums. Every term is rounded to the force quanta (pair_lsdem.cpp),
   so that the sums do not depend on the order: the same bits as pair_style lsdem on any
   thread count (doc/howto_parallel.rst).
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(lsdem/omp,PairLsdemOMP);
// clang-format on
#else

#ifndef LMP_PAIR_LSDEM_OMP_H
#define LMP_PAIR_LSDEM_OMP_H

#include "pair_lsdem.h"
#include "thr_omp.h"

#include <vector>

namespace LAMMPS_NS {

class PairLsdemOMP : public PairLsdem, public ThrOMP {
 public:
  PairLsdemOMP(class LAMMPS *);
  void compute(int, int) override;
  void init_style() override;
  double memory_usage() override;

 private:
  std::vector<int> cuts;  // thread t tests the grains ilist[cuts[t]..cuts[t + 1])
  void apply_lane(Lane &, int eflag, int vflag, class ThrData *);
};

}    // namespace LAMMPS_NS

#endif
#endif
