// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: pair_style lsdem/omp (pair_lsdem_omp.h).
------------------------------------------------------------------------- */

#include "pair_lsdem_omp.h"

#include "atom.h"
#include "comm.h"
#include "lsdem_pair_threads.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "suffix.h"
#include "update.h"

#include "omp_compat.h"

using namespace LAMMPS_NS;

PairLsdemOMP::PairLsdemOMP(LAMMPS *lmp) : PairLsdem(lmp), ThrOMP(lmp, THR_PAIR)
{
  suffix_flag |= Suffix::OMP;
  respa_enable = 0;
}

/* ---------------------------------------------------------------------- */

void PairLsdemOMP::init_style()
{
  PairLsdem::init_style();
  set_lanes(comm->nthreads);
}

/* ----------------------------------------------------------------------
   pair_style lsdem's force call with its two loops threaded: the tests (each thread's
   grains into its lane), then, after the coordination count that zcap needs from every
   lane, the forces (each lane's contacts into its thread's arrays)
------------------------------------------------------------------------- */

void PairLsdemOMP::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  const int nall = atom->nlocal + atom->nghost;
  const int nthreads = comm->nthreads;  // lanes set up for them at init_style
  const int inum = list->inum;
  begin_force_call(nthreads);
  update_poses(0, nall);
  if (neighbor->ago == 0 || !master_built) build_master_pairs();

  // runs of equal work: a grain weighs 1 + its node tests on the last force call
  lsdem_work_cuts(inum, nthreads,
                  [&](int ii) { return 1.0 + grain_node_tests[list->ilist[ii]]; }, cuts);
  lsdem_pair_threads(fix, cuts, [&](int tid, int from, int to, ThrData *) {
    test_pairs(*lanes[tid], from, to);
  });
  end_force_call();
  if (zcap > 0) coordination(1);

#if defined(_OPENMP)
#pragma omp parallel LMP_DEFAULT_NONE LMP_SHARED(eflag, vflag)
#endif
  {
    int ifrom, ito, tid;
    loop_setup_thr(ifrom, ito, tid, inum, nthreads);
    ThrData *thr = fix->get_thr(tid);
    thr->timer(Timer::START);
    ev_setup_thr(eflag, vflag, nall, eatom, vatom, nullptr, thr);
    apply_contacts(*lanes[tid], thr->get_f(), thr->get_torque());
    thr->timer(Timer::PAIR);
    reduce_thr(this, eflag, vflag, thr);  // every thread, inside the region (it syncs them)
  }

  if (eflag_global) tally_workload();
  if (update->setupflag) report_overlaps();
}

/* ---------------------------------------------------------------------- */

double PairLsdemOMP::memory_usage()
{
  return PairLsdem::memory_usage() + memory_usage_thr();
}
