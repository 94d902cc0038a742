/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   pair_style lsdem/omp: pair_style lsdem with the grains of a rank shared among threads
   (package omp N, or -sf omp). The neighbor list's grains are cut into contiguous runs of
   about equal work (8 per thread; a grain weighs its node tests on the last force call),
   each tested into its own lane (contact path, manifold storage, pair-state lane, contact
   list) by whichever thread comes free first; each thread then applies a share of the
   lanes' forces to its own force and torque arrays, which LAMMPS's OPENMP package sums.
   Every term is rounded to the force quanta (pair_lsdem.cpp), so that the sums do not
   depend on the order: the same bits as pair_style lsdem on any thread count
   (doc/howto_parallel.rst).
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
  std::vector<int> cuts;  // run (lane) l tests the grains ilist[cuts[l]..cuts[l + 1])
};

}    // namespace LAMMPS_NS

#endif
#endif
