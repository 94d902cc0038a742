/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   Nothing written is lost when a run stops with an error on one rank.

   LAMMPS built with exceptions (LAMMPS_EXCEPTIONS, as here) turns error->one() into an
   exception that main() answers with MPI_Abort(), without flushing: the error message, and
   whatever log, screen and dump output was still buffered, were lost (an empty log.lammps
   after a bad value in a data file). This MPI_Abort, through MPI's profiling interface,
   flushes every open stdio stream of this process, then aborts as before (PMPI_Abort).
------------------------------------------------------------------------- */

#include <mpi.h>

#include <cstdio>

#ifndef MPI_STUBS
extern "C" int MPI_Abort(MPI_Comm comm, int errorcode)
{
  fflush(nullptr);
  return PMPI_Abort(comm, errorcode);
}
#endif
