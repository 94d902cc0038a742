// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: fix wall/lsdem/omp (fix_wall_lsdem_omp.h).
------------------------------------------------------------------------- */

#include "fix_wall_lsdem_omp.h"

#include "comm.h"

#include "omp_compat.h"
#if defined(_OPENMP)
#include <omp.h>
#endif

#include <algorithm>

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

void FixWallLsdemOMP::init()
{
  FixWallLsdem::init();
  set_lanes(comm->nthreads);
}

/* ----------------------------------------------------------------------
   fix wall/lsdem's force call with its candidates split among the threads
------------------------------------------------------------------------- */

void FixWallLsdemOMP::post_force(int /*vflag*/)
{
  const int nthreads = comm->nthreads;
  if ((int) lanes.size() < nthreads) set_lanes(nthreads);  // package omp changed
  lsdem_pose tilting;
  const lsdem_pose *w = begin_force_call(nthreads, tilting);
  const int n = ncand;

#if defined(_OPENMP)
#pragma omp parallel LMP_DEFAULT_NONE LMP_SHARED(w)
#endif
  {
#if defined(_OPENMP)
    const int tid = omp_get_thread_num();
#else
    const int tid = 0;
#endif
    const int chunk = 1 + n / nthreads;
    const int from = std::min(n, tid * chunk), to = std::min(n, from + chunk);
    visit_candidates(*lanes[tid], from, to, *w);
  }
  end_force_call();
}
