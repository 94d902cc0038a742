/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: the threaded loops of the /omp pair styles, timed as pair time: the grains
   of the neighbor list in contiguous runs, each run into its own lane, so that the lanes
   read in order are the serial order. pair_style lsdem/impulse/omp: one run per thread, of
   equal counts (lsdem_pair_threads); pair_style lsdem/omp: more runs than threads, of equal
   work (lsdem_work_cuts), taken by the threads as they come free (lsdem_pair_chunks).
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_PAIR_THREADS_H
#define LMP_LSDEM_PAIR_THREADS_H

#include "fix_omp.h"
#include "thr_data.h"
#include "thr_omp.h"
#include "timer.h"

#include <vector>

namespace LAMMPS_NS {

// cuts.size() - 1 chunks, chunk c the items [cuts[c], cuts[c + 1]), shared among the threads
// as they come free (dynamic schedule: a thread slowed by other work on its core takes fewer),
// body(c, from, to) on each; every chunk writes its own lane, so chunks read in order are the
// serial order whichever thread ran them
template <class Body> void lsdem_pair_chunks(FixOMP *fix, const std::vector<int> &cuts, Body body)
{
  const int nchunks = (int) cuts.size() - 1;
#if defined(_OPENMP)
#pragma omp parallel
#endif
  {
#if defined(_OPENMP)
    const int tid = omp_get_thread_num();
#else
    const int tid = 0;
#endif
    ThrData *thr = fix->get_thr(tid);
    thr->timer(Timer::START);
#if defined(_OPENMP)
#pragma omp for schedule(dynamic, 1) nowait
#endif
    for (int c = 0; c < nchunks; c++) body(c, cuts[c], cuts[c + 1]);
    thr->timer(Timer::PAIR);
  }
}

// n items in order cut into nruns contiguous runs of about equal summed work(k) (> 0):
// cut t is the first item whose preceding work reaches t / nruns of the total
template <class Work> void lsdem_work_cuts(int n, int nruns, Work work, std::vector<int> &cuts)
{
  double total = 0.0;
  for (int k = 0; k < n; k++) total += work(k);
  cuts.assign(nruns + 1, n);
  cuts[0] = 0;
  double before = 0.0;
  int t = 1;
  for (int k = 0; k < n && t < nruns; k++) {
    while (t < nruns && before >= total * t / nruns) cuts[t++] = k;
    before += work(k);
  }
}

// the loop over n grains in nthreads runs of equal count, thread t taking run t
template <class Body> void lsdem_pair_threads(FixOMP *fix, int n, int nthreads, Body body)
{
#if defined(_OPENMP)
#pragma omp parallel
#endif
  {
    int from, to, tid;
    loop_setup_thr(from, to, tid, n, nthreads);
    ThrData *thr = fix->get_thr(tid);
    thr->timer(Timer::START);
    body(tid, from, to, thr);
    thr->timer(Timer::PAIR);
  }
}

}    // namespace LAMMPS_NS

#endif
