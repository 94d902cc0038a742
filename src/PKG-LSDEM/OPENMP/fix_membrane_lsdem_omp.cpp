// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: fix membrane/lsdem/omp (fix_membrane_lsdem_omp.h).
------------------------------------------------------------------------- */

#include "fix_membrane_lsdem_omp.h"

#include "comm.h"
#include "lsdem_thread_range.h"

#include "omp_compat.h"

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

void FixMembraneLsdemOMP::for_triangles(TrianglePhase phase)
{
  const int nthreads = comm->nthreads;
  const int n = ntriangles();
#if defined(_OPENMP)
#pragma omp parallel LMP_DEFAULT_NONE LMP_SHARED(phase)
#endif
  {
    const LsdemThreadRange r(n, nthreads);
    (this->*phase)(r.from, r.to);
  }
}
