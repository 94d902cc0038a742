/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   abort_flush.cpp's MPI_Abort: what it needs to know of this rank's output; and the
   SIGTERM handler that flushes the ranks mpirun terminates after an abort.
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_ABORT_FLUSH_H
#define LMP_LSDEM_ABORT_FLUSH_H

namespace LAMMPS_NS {

// Whether this rank shows LAMMPS's error messages (it has a screen or a log file). A rank
// that does not (ranks > 0 under -screen none) writes the message of an error that aborts
// the run to standard error instead, so that it is not lost.
void lsdem_note_error_output(bool shown);

// SIGTERM (how mpirun ends the ranks left when one aborts) flushes this rank's stdio streams
// first: dumps with 'flush no' keep their frames. Only replaces the default action.
void lsdem_flush_on_terminate();

}    // namespace LAMMPS_NS

#endif
