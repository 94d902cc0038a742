// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: pair_style lsdem/impulse/omp (pair_lsdem_impulse_omp.h).
------------------------------------------------------------------------- */

#include "pair_lsdem_impulse_omp.h"

#include "comm.h"
#include "lsdem_pair_threads.h"
#include "neigh_list.h"
#include "suffix.h"

using namespace LAMMPS_NS;

PairLsdemImpulseOMP::PairLsdemImpulseOMP(LAMMPS *lmp) : PairLsdemImpulse(lmp), ThrOMP(lmp, THR_PAIR)
{
  suffix_flag |= Suffix::OMP;
  respa_enable = 0;
}

/* ---------------------------------------------------------------------- */

void PairLsdemImpulseOMP::init_style()
{
  PairLsdemImpulse::init_style();
  set_lanes(comm->nthreads);
}

/* ----------------------------------------------------------------------
   the detection of pair_style lsdem/impulse with its loop threaded, each thread's grains
   into its lane
------------------------------------------------------------------------- */

void PairLsdemImpulseOMP::compute(int eflag, int vflag)
{
  const int nthreads = comm->nthreads;  // lanes set up for them at init_style
  const int inum = list->inum;
  begin_detection(eflag, vflag, nthreads);

  lsdem_pair_threads(fix, inum, nthreads, [&](int tid, int from, int to, ThrData *) {
    detect_range(tid, from, to);
  });
  end_detection();
}

/* ---------------------------------------------------------------------- */

double PairLsdemImpulseOMP::memory_usage()
{
  return PairLsdemImpulse::memory_usage() + memory_usage_thr();
}
