/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: the threaded loop of the /omp pair styles (pair_style lsdem/omp,
   lsdem/impulse/omp): n grains of the neighbor list cut into nthreads contiguous runs
   (thread t takes run t, so lanes read in order are the serial order), body(tid, from, to,
   thr) on each thread, timed as pair time. The runs: LAMMPS's loop_setup_thr (equal
   counts), or given as cuts (run t is [cuts[t], cuts[t+1]), lsdem_work_cuts).
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_PAIR_THREADS_H
#define LMP_LSDEM_PAIR_THREADS_H

#include "fix_omp.h"
#include "thr_data.h"
#include "thr_omp.h"
#include "timer.h"

#include <algorithm>
#include <vector>

namespace LAMMPS_NS {

template <class Body> void lsdem_pair_threads(FixOMP *fix, const std::vector<int> &cuts, Body body)
{
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
    body(tid, cuts[tid], cuts[tid + 1], thr);
    thr->timer(Timer::PAIR);
  }
}

// n items cut into nthreads runs of equal count (loop_setup_thr's cut)
inline void lsdem_count_cuts(int n, int nthreads, std::vector<int> &cuts)
{
  const int chunk = 1 + n / nthreads;
  cuts.resize(nthreads + 1);
  for (int t = 0; t <= nthreads; t++) cuts[t] = std::min(n, t * chunk);
}

// n items in order cut into nthreads contiguous runs of about equal summed work(k) (> 0):
// cut t is the first item whose preceding work reaches t / nthreads of the total
template <class Work> void lsdem_work_cuts(int n, int nthreads, Work work, std::vector<int> &cuts)
{
  double total = 0.0;
  for (int k = 0; k < n; k++) total += work(k);
  cuts.assign(nthreads + 1, n);
  cuts[0] = 0;
  double before = 0.0;
  int t = 1;
  for (int k = 0; k < n && t < nthreads; k++) {
    while (t < nthreads && before >= total * t / nthreads) cuts[t++] = k;
    before += work(k);
  }
}

// the loop over n grains in runs of equal count
template <class Body> void lsdem_pair_threads(FixOMP *fix, int n, int nthreads, Body body)
{
  std::vector<int> cuts;
  lsdem_count_cuts(n, nthreads, cuts);
  lsdem_pair_threads(fix, cuts, body);
}

}    // namespace LAMMPS_NS

#endif
