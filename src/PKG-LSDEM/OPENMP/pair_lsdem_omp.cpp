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

#include "omp_compat.h"

using namespace LAMMPS_NS;

PairLsdemOMP::PairLsdemOMP(LAMMPS *lmp) : PairLsdem(lmp), ThrOMP(lmp, THR_PAIR)
{
  suffix_flag |= Suffix::OMP;
  respa_enable = 0;
}

/* ---------------------------------------------------------------------- */

// runs (lanes) per thread in the contact tests: enough that a thread which comes free takes
// over the tail of the other's share
static constexpr int RUNS_PER_THREAD = 8;

static int runs_for(int nthreads)
{
  return nthreads > 1 ? RUNS_PER_THREAD * nthreads : 1;
}

void PairLsdemOMP::init_style()
{
  PairLsdem::init_style();
  set_lanes(runs_for(comm->nthreads));
}

/* ----------------------------------------------------------------------
   pair_style lsdem's force call with its two loops threaded: the tests (runs of grains of
   equal work, each into its lane, taken by the threads as they come free), then, after the
   coordination count that zcap needs from every lane, the forces (each thread a share of
   the lanes, their contacts into its arrays)
------------------------------------------------------------------------- */

void PairLsdemOMP::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  const int nall = atom->nlocal + atom->nghost;
  const int nthreads = comm->nthreads;
  const int nruns = runs_for(nthreads);  // lanes set up for them at init_style
  begin_force_call(nruns);
  update_poses(0, nall);
  if (neighbor->ago == 0 || !master_built) build_master_pairs();

  // runs of equal work: a grain weighs 1 + its node tests on the last force call
  lsdem_work_cuts(list->inum, nruns,
                  [&](int ii) { return 1.0 + grain_node_tests[list->ilist[ii]]; }, cuts);
  lsdem_pair_chunks(fix, cuts, [&](int run, int from, int to) {
    test_pairs(*lanes[run], from, to);
  });
  end_force_call();
  if (zcap > 0) coordination(1);

#if defined(_OPENMP)
#pragma omp parallel LMP_DEFAULT_NONE LMP_SHARED(eflag, vflag)
#endif
  {
    const LsdemThreadRange r(nlanes, comm->nthreads);
    ThrData *thr = fix->get_thr(r.tid);
    thr->timer(Timer::START);
    ev_setup_thr(eflag, vflag, nall, eatom, vatom, nullptr, thr);
    for (int l = r.from; l < r.to; l++) apply_contacts(*lanes[l], thr->get_f(), thr->get_torque());
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
