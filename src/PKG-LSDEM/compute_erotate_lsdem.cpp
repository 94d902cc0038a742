// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute ID group erotate/lsdem
     scalar: sum over grains of 0.5 sum_k I_k w_k^2, w = body-frame angular velocity
             (w = R(q)^T omega, I_k principal moments), in energy units
     vector: sum over grains of the spin angular momentum R(q) (I w), world frame,
             in mass*length^2/time (the orbital part m x cross v is not included)
------------------------------------------------------------------------- */

#include "compute_erotate_lsdem.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "error.h"
#include "force.h"
#include "update.h"

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

ComputeERotateLsdem::ComputeERotateLsdem(LAMMPS *lmp, int narg, char **arg) :
  Compute(lmp, narg, arg), avec(nullptr)
{
  if (narg != 3) error->all(FLERR, "Illegal compute erotate/lsdem command");

  scalar_flag = vector_flag = 1;
  size_vector = 3;
  extscalar = extvector = 1;
  vector = new double[3];

  if (!dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem")))
    error->all(FLERR, "Compute erotate/lsdem requires atom_style lsdem");
}

/* ---------------------------------------------------------------------- */

ComputeERotateLsdem::~ComputeERotateLsdem()
{
  delete[] vector;
}

/* ---------------------------------------------------------------------- */

void ComputeERotateLsdem::init()
{
  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  if (!avec) error->all(FLERR, "Compute erotate/lsdem requires atom_style lsdem");
}

/* ---------------------------------------------------------------------- */

double ComputeERotateLsdem::compute_scalar()
{
  invoked_scalar = update->ntimestep;

  double erot = 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    double wbody[3];
    lsdem_quat_rotate_inv(avec->quat[i], atom->omega[i], wbody);
    erot += lsdem_kinetic_rotational(avec->inertia[i], wbody);
  }
  MPI_Allreduce(&erot, &scalar, 1, MPI_DOUBLE, MPI_SUM, world);
  scalar *= force->mvv2e;
  return scalar;
}

/* ---------------------------------------------------------------------- */

void ComputeERotateLsdem::compute_vector()
{
  invoked_vector = update->ntimestep;

  double spin[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    double wbody[3], lbody[3], lworld[3];
    lsdem_quat_rotate_inv(avec->quat[i], atom->omega[i], wbody);
    for (int k = 0; k < 3; k++) lbody[k] = avec->inertia[i][k] * wbody[k];
    lsdem_quat_rotate(avec->quat[i], lbody, lworld);
    for (int k = 0; k < 3; k++) spin[k] += lworld[k];
  }
  MPI_Allreduce(spin, vector, 3, MPI_DOUBLE, MPI_SUM, world);
}
