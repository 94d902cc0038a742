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

   The other ranks do not call MPI_Abort: mpirun terminates them (Open MPI: SIGTERM, then
   SIGKILL after odls_base_sigkill_timeout, 1 s). Rank 0 writes LAMMPS's dumps, so a dump with
   'flush no' lost the frames in its buffer (an empty file after an error on rank 1). SIGTERM
   therefore flushes every stdio stream before it ends the process as before. fflush is not
   async-signal-safe: a rank terminated while itself writing to a stream may leave that
   frame cut (a rank terminated this way waits in MPI, not in stdio).
------------------------------------------------------------------------- */

#include "abort_flush.h"

#include <mpi.h>

#include <csignal>
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

namespace {
// flush, then end of the signal as without a handler
void flush_and_terminate(int sig)
{
  fflush(nullptr);
  signal(sig, SIG_DFL);
  raise(sig);
}
}    // namespace

void LAMMPS_NS::lsdem_flush_on_terminate()
{
  struct sigaction old;
  if (sigaction(SIGTERM, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) return;
  struct sigaction act = {};
  act.sa_handler = flush_and_terminate;
  sigemptyset(&act.sa_mask);
  sigaction(SIGTERM, &act, nullptr);
}

#ifndef MPI_STUBS
extern "C" int MPI_Abort(MPI_Comm comm, int errorcode)
{
  if (!error_output_shown) print_handled_error(stderr);
  fflush(nullptr);
  return PMPI_Abort(comm, errorcode);
}
#endif
