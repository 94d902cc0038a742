// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: fix wall/lsdem/omp (fix_wall_lsdem_omp.h).
------------------------------------------------------------------------- */

#include "fix_wall_lsdem_omp.h"

#include "comm.h"

#include "lsdem_thread_range.h"
#include "omp_compat.h"

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

void FixWallLsdemOMP::init()
{
  FixWallLsdem::init();
  set_lanes(comm->nthreads);
}

/* ---------------------------------------------------------------------- */

int FixWallLsdemOMP::lanes_for_call() const
{
  return comm->nthreads;
}

/* ----------------------------------------------------------------------
   fix wall/lsdem's force call with its candidates split among the threads
------------------------------------------------------------------------- */

void FixWallLsdemOMP::visit_all(const lsdem_pose &w)
{
  const int nthreads = comm->nthreads;  // lanes set up for them at init
  const int n = ncand;

#if defined(_OPENMP)
#pragma omp parallel LMP_DEFAULT_NONE LMP_SHARED(w)
#endif
  {
    const LsdemThreadRange r(n, nthreads);
    visit_candidates(*lanes[r.tid], r.from, r.to, w);
  }
}
