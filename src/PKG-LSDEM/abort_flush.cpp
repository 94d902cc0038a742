/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   Nothing written is lost when a run stops with an error on one rank.

   LAMMPS built with exceptions (LAMMPS_EXCEPTIONS, as here) turns error->one() into an
   exception that main() answers with MPI_Abort(), without flushing: the error message, and
   whatever log, screen and dump output was still buffered, were lost (an empty log.lammps
   after a bad value in a data file). This MPI_Abort, through MPI's profiling interface,
   flushes every open stdio stream of this process, then aborts as before (PMPI_Abort).
   On a rank that shows no output (ranks > 0 under -screen none), the message of the error
   being handled goes to standard error first: LAMMPS wrote it nowhere.
------------------------------------------------------------------------- */

#include "abort_flush.h"

#include <mpi.h>

#include <cstdio>
#include <exception>

namespace {
bool error_output_shown = true;

// Writes the message of the exception being handled (main() calls MPI_Abort inside its
// catch of LAMMPS's abort exception); nothing outside a handler.
void print_handled_error(FILE *out)
{
  std::exception_ptr e = std::current_exception();
  if (!e) return;
  try {
    std::rethrow_exception(e);
  } catch (const std::exception &x) {
    fputs(x.what(), out);
  } catch (...) {
  }
}
}    // namespace

void LAMMPS_NS::lsdem_note_error_output(bool shown)
{
  error_output_shown = shown;
}

#ifndef MPI_STUBS
extern "C" int MPI_Abort(MPI_Comm comm, int errorcode)
{
  if (!error_output_shown) print_handled_error(stderr);
  fflush(nullptr);
  return PMPI_Abort(comm, errorcode);
}
#endif
