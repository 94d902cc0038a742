// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: fix nve/lsdem/omp (fix_nve_lsdem_omp.h).
------------------------------------------------------------------------- */

#include "fix_nve_lsdem_omp.h"

#include "comm.h"

#include "lsdem_thread_range.h"
#include "omp_compat.h"

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

void FixNVELsdemOMP::init()
{
  FixNVELsdem::init();
  first_bad.assign(comm->nthreads, -1);
  why.assign(comm->nthreads, nullptr);
}

/* ----------------------------------------------------------------------
   each thread steps a contiguous run of the grains; the unstable grain reported is the
   first in atom order, as without threads
------------------------------------------------------------------------- */

void FixNVELsdemOMP::initial_integrate(int /*vflag*/)
{
  const int n = integrated_count();
  const int nthreads = comm->nthreads;  // first_bad and why sized for them at init

#if defined(_OPENMP)
#pragma omp parallel LMP_DEFAULT_NONE
#endif
  {
    const LsdemThreadRange r(n, nthreads);
    first_bad[r.tid] = r.from < r.to ? step_grains(r.from, r.to, why[r.tid]) : -1;
  }
  for (int t = 0; t < nthreads; t++)
    if (first_bad[t] >= 0) {
      stop_if_unstable(first_bad[t], why[t]);
      return;
    }
  stop_if_unstable(-1, nullptr);
}
