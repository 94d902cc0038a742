/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: the threaded loop of the /omp pair styles (pair_style lsdem/omp,
   lsdem/impulse/omp): n grains of the neighbor list cut into nthreads contiguous runs by
   LAMMPS's loop_setup_thr (thread t takes run t, so lanes read in order are the serial
   order), body(tid, from, to, thr) on each thread, timed as pair time.
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_PAIR_THREADS_H
#define LMP_LSDEM_PAIR_THREADS_H

#include "fix_omp.h"
#include "thr_data.h"
#include "thr_omp.h"
#include "timer.h"

namespace LAMMPS_NS {

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
