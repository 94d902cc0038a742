/* driver.c -- run an LSDEM scene from C through LAMMPS's C library interface (library.h)
 * and read back every grain's position, orientation quaternion and shape id.
 *
 *   mpirun -np 2 build/lsdem-c-driver in.driver [NSTEPS]
 *
 * Prints one line per grain, ordered by atom id: "id shape x y z qw qx qy qz"
 * (shape 1-based as in the data file; quaternion scalar-first, body -> world). */
#define LAMMPS_LIB_MPI
#include "library.h"

#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  if (argc < 2) {
    fprintf(stderr, "usage: lsdem-c-driver INPUT [NSTEPS]\n");
    MPI_Finalize();
    return 2;
  }
  const char *steps = argc > 2 ? argv[2] : "200";
  char *lmpargv[] = {"lsdem-c-driver", "-log", "log.driver", "-screen", "none"};
  void *lmp = lammps_open(5, lmpargv, MPI_COMM_WORLD, NULL);
  if (!lmp) {
    fprintf(stderr, "lsdem-c-driver: could not create a LAMMPS instance\n");
    MPI_Abort(MPI_COMM_WORLD, 1);
  }

  lammps_file(lmp, argv[1]);
  /* the atom style's custom fields reach the library interface through a per-atom compute */
  lammps_command(lmp, "compute orient all property/atom qw qx qy qz shape");
  char run[64];
  snprintf(run, sizeof run, "run %s", steps);
  lammps_command(lmp, run);
  if (lammps_has_error(lmp)) {
    char msg[1024];
    lammps_get_last_error_message(lmp, msg, sizeof msg);
    fprintf(stderr, "lsdem-c-driver: LAMMPS error: %s\n", msg);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }

  const int n = (int) lammps_get_natoms(lmp);
  double *x = malloc(sizeof(double) * 3 * (size_t) n);
  double *orient = malloc(sizeof(double) * 5 * (size_t) n);
  if (!x || !orient) MPI_Abort(MPI_COMM_WORLD, 1);
  /* gathered in atom-id order on every rank */
  lammps_gather_atoms(lmp, "x", 1, 3, x);
  lammps_gather(lmp, "c_orient", 1, 5, orient);

  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) {
    for (int i = 0; i < n; i++) {
      const double *o = orient + 5 * i;
      printf("%d %d %.15g %.15g %.15g %.15g %.15g %.15g %.15g\n", i + 1, (int) o[4], x[3 * i],
             x[3 * i + 1], x[3 * i + 2], o[0], o[1], o[2], o[3]);
    }
  }
  free(x);
  free(orient);
  lammps_close(lmp);
  MPI_Finalize();
  return 0;
}
