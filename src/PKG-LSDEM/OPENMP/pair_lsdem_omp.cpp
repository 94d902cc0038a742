// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: pair_style lsdem/omp (pair_lsdem_omp.h).
------------------------------------------------------------------------- */

#include "pair_lsdem_omp.h"

#include "atom.h"
#include "comm.h"
#include "lsdem_pair_threads.h"
#include "lsdem_thread_range.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "suffix.h"
#include "update.h"

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
   grains into its lane), then the forces (each lane's contacts into its thread's arrays).
   Without zcap a thread applies its lane's forces as soon as it has tested its grains,
   in the same parallel region; zcap scales them by the contact counts of every lane, so
   the counts come between two regions
------------------------------------------------------------------------- */

void PairLsdemOMP::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  const int nthreads = comm->nthreads;  // lanes set up for them at init_style
  const int inum = list->inum;
  begin_force_call(nthreads);
  {
    const int nl = atom->nlocal, nall = nl + atom->nghost;
#if defined(_OPENMP)
#pragma omp parallel num_threads(nthreads)
#endif
    { // owned grains in the equal runs fix nve/lsdem/omp steps them in (when it steps all
      // local grains), so that their lines stay in one core's cache
      const LsdemThreadRange r(nl, nthreads), g(nall - nl, nthreads);
      update_poses(r.from, r.to);
      update_poses(nl + g.from, nl + g.to);
    }
  }
  if (neighbor->ago == 0 || !master_built) build_master_pairs();

  // runs of equal work: a grain weighs 1 + its node tests on the last force call
  lsdem_work_cuts(inum, nthreads,
                  [&](int ii) { return 1.0 + grain_node_tests[list->ilist[ii]]; }, cuts);
  const bool counts_first = zcap > 0;
  lsdem_pair_threads(fix, cuts, [&](int tid, int from, int to, ThrData *thr) {
    test_pairs(*lanes[tid], from, to);
    if (!counts_first) apply_lane(*lanes[tid], eflag, vflag, thr);
  });
  end_force_call();
  if (counts_first) {
    coordination(1);
    lsdem_pair_threads(fix, cuts, [&](int tid, int, int, ThrData *thr) {
      apply_lane(*lanes[tid], eflag, vflag, thr);
    });
  }

  if (eflag_global) tally_workload(contacting_pairs());
  if (update->setupflag) report_overlaps();
}

/* ----------------------------------------------------------------------
   a lane's contacts into its thread's force and torque arrays, then the threads' arrays
   summed (every thread calls it, inside the parallel region: it syncs them)
------------------------------------------------------------------------- */

void PairLsdemOMP::apply_lane(Lane &lane, int eflag, int vflag, ThrData *thr)
{
  ev_setup_thr(eflag, vflag, atom->nlocal + atom->nghost, eatom, vatom, nullptr, thr);
  apply_contacts(lane, thr->get_f(), thr->get_torque());
  thr->timer(Timer::PAIR);
  reduce_thr(this, eflag, vflag, thr);
}

/* ---------------------------------------------------------------------- */

double PairLsdemOMP::memory_usage()
{
  return PairLsdem::memory_usage() + memory_usage_thr();
}
