// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: bond_style lsdem/membrane/omp (bond_lsdem_membrane_omp.h).
------------------------------------------------------------------------- */

#include "bond_lsdem_membrane_omp.h"

#include "comm.h"
#include "lsdem_thread_range.h"
#include "neighbor.h"

#include "omp_compat.h"

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

void BondLsdemMembraneOMP::all_bond_terms()
{
  const int nthreads = comm->nthreads;
  const int n = neighbor->nbondlist;
#if defined(_OPENMP)
#pragma omp parallel LMP_DEFAULT_NONE
#endif
  {
    const LsdemThreadRange r(n, nthreads);
    bond_terms(r.from, r.to);
  }
}
