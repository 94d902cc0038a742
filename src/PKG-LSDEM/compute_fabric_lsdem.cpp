// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute fabric/lsdem (doc/compute_fabric_lsdem.rst).
     vector: Dxx Dyy Dzz Dxy Dxz Dyz (deviatoric fabric of long axes, Kanatani's second
             kind, core lsdem_fabric_deviator), anisotropy factor a, mean and standard
             deviation of the rotation angle since the reference (radians), number of
             grains rotated more than mean + 2 sd
     per-atom array: rotation angle since the reference (radians), flag (1 if more than
             mean + 2 sd of the group, else 0)
   The reference orientation of each grain is taken when the compute is defined (kept in
   a fix STORE, so it migrates with the grain and survives a restart).
------------------------------------------------------------------------- */

#include "compute_fabric_lsdem.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "error.h"
#include "group.h"
#include "memory.h"
#include "modify.h"
#include "update.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;

static constexpr int NVALUES = 10;
// smallest rotation (radians) that flags a grain: far above the ~1e-16 of quaternion
// round-off, far below any rotation that marks a shear band
static constexpr double ROTATION_FLOOR = 1e-9;

/* ---------------------------------------------------------------------- */

ComputeFabricLsdem::ComputeFabricLsdem(LAMMPS *lmp, int narg, char **arg) :
  Compute(lmp, narg, arg), id_fix(nullptr), fix(nullptr), avec(nullptr), nmax(0), rot(nullptr)
{
  if (narg != 3) error->all(FLERR, "Illegal compute fabric/lsdem command: no arguments expected");
  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  if (!avec) error->all(FLERR, "Compute fabric/lsdem requires atom_style lsdem");

  vector_flag = 1;
  size_vector = NVALUES;
  extvector = 0;
  vector = new double[NVALUES];
  peratom_flag = 1;
  size_peratom_cols = 5;

  id_fix = utils::strdup(id + std::string("_COMPUTE_STORE"));
  fix = LsdemCompat::add_peratom_store(modify, id_fix, group->names[igroup], 4);
  if (fix->restart_reset) fix->restart_reset = 0;
  else {
    for (int i = 0; i < atom->nlocal; i++)
      for (int k = 0; k < 4; k++) fix->astore[i][k] = avec->quat[i][k];
  }
}

/* ---------------------------------------------------------------------- */

ComputeFabricLsdem::~ComputeFabricLsdem()
{
  if (modify->nfix) modify->delete_fix(id_fix);
  delete[] id_fix;
  delete[] vector;
  memory->destroy(rot);
}

/* ---------------------------------------------------------------------- */

void ComputeFabricLsdem::init()
{
  fix = LsdemCompat::find_peratom_store(modify, id_fix);
  if (!fix) error->all(FLERR, "Could not find compute fabric/lsdem fix {}", id_fix);
  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
}

/* ----------------------------------------------------------------------
   rotation angle of every owned group grain into rot[i][0], its long axis into rot[i][2..4];
   group mean, standard deviation and the count above mean + 2 sd (flags into rot[i][1])
------------------------------------------------------------------------- */

void ComputeFabricLsdem::rotation_stats(double &mean, double &sd, double &nflag)
{
  if (atom->nmax > nmax) {
    memory->destroy(rot);
    nmax = atom->nmax;
    memory->create(rot, nmax, 5, "fabric/lsdem:rot");
    array_atom = rot;
  }
  const int *mask = atom->mask;
  double sum[3] = {0.0, 0.0, 0.0}, all[3];  // count, sum, sum of squares
  for (int i = 0; i < atom->nlocal; i++) {
    for (int k = 0; k < 5; k++) rot[i][k] = 0.0;
    if (!(mask[i] & groupbit)) continue;
    lsdem_long_axis(avec->quat[i], avec->inertia[i], &rot[i][2]);
    const double th = lsdem_rotation_angle(avec->quat[i], fix->astore[i]);
    rot[i][0] = th;
    sum[0] += 1.0;
    sum[1] += th;
    sum[2] += th * th;
  }
  MPI_Allreduce(sum, all, 3, MPI_DOUBLE, MPI_SUM, world);
  mean = all[0] > 0.0 ? all[1] / all[0] : 0.0;
  sd = all[0] > 0.0 ? sqrt(std::max(0.0, all[2] / all[0] - mean * mean)) : 0.0;
  // at least ROTATION_FLOOR: before any grain has turned, round-off alone must flag none
  const double cut = std::max(mean + 2.0 * sd, ROTATION_FLOOR);
  double nlocal_flag = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if ((mask[i] & groupbit) && rot[i][0] > cut) {
      rot[i][1] = 1.0;
      nlocal_flag += 1.0;
    }
  MPI_Allreduce(&nlocal_flag, &nflag, 1, MPI_DOUBLE, MPI_SUM, world);
}

/* ---------------------------------------------------------------------- */

void ComputeFabricLsdem::compute_vector()
{
  invoked_vector = update->ntimestep;

  const int *mask = atom->mask;
  double local[10] = {0.0}, all[10];  // F (9) and the count
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double n[3];
    lsdem_long_axis(avec->quat[i], avec->inertia[i], n);
    lsdem_fabric_add(local, n);
    local[9] += 1.0;
  }
  MPI_Allreduce(local, all, 10, MPI_DOUBLE, MPI_SUM, world);
  double D[9];
  lsdem_fabric_deviator(all, all[9], D);
  lsdem_sym_to_voigt(D, vector);
  vector[6] = lsdem_fabric_anisotropy(D);
  rotation_stats(vector[7], vector[8], vector[9]);
}

/* ---------------------------------------------------------------------- */

void ComputeFabricLsdem::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  double mean, sd, nflag;
  rotation_stats(mean, sd, nflag);
}

/* ---------------------------------------------------------------------- */

double ComputeFabricLsdem::memory_usage()
{
  return 5.0 * nmax * sizeof(double);
}
