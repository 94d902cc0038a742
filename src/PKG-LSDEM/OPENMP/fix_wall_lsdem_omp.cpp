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

/* ----------------------------------------------------------------------
   fix impulse/lsdem's wall detection (each_manifold) with the candidates split among the
   threads, each thread's manifolds kept in its lane (read in lane order: the serial order)
------------------------------------------------------------------------- */

void FixWallLsdemOMP::detect_all(const lsdem_pose &w, const char *take, int n)
{
  const int nthreads = n;  // lanes set up for comm->nthreads at init
  const int ncands = ncand;

#if defined(_OPENMP)
#pragma omp parallel LMP_DEFAULT_NONE LMP_SHARED(w, take)
#endif
  {
    const LsdemThreadRange r(ncands, nthreads);
    detect_candidates(*lanes[r.tid], r.from, r.to, w, take, nullptr);
  }
}
