/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: the share of n items that the calling thread of an OpenMP parallel region
   takes: the serial order cut into nthreads contiguous runs, so that thread t's lane holds
   run t and the lanes read in order are the serial order (fix wall/lsdem/omp,
   fix nve/lsdem/omp; pair_style lsdem/omp cuts its grains by work, lsdem_pair_threads.h).
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_THREAD_RANGE_H
#define LMP_LSDEM_THREAD_RANGE_H

#if defined(_OPENMP)
#include <omp.h>
#endif

#include <algorithm>

namespace LAMMPS_NS {

struct LsdemThreadRange {
  int tid, from, to;  // this thread and its items [from, to)
  LsdemThreadRange(int n, int nthreads)
  {
#if defined(_OPENMP)
    tid = omp_get_thread_num();
#else
    tid = 0;
#endif
    const int chunk = 1 + n / nthreads;
    from = std::min(n, tid * chunk);
    to = std::min(n, from + chunk);
  }
};

}    // namespace LAMMPS_NS

#endif
