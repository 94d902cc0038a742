// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute ID group dilatancy/lsdem v_epsv v_epsa (doc/compute_dilatancy_lsdem.rst).
   Scalar: the dilatancy angle in degrees (core lsdem_dilatancy_angle, report eq 3.10,
   compression-positive strains, psi > 0 for dilation) from the strain increments since the
   previous invocation; 0 on the first one. The group is ignored.
------------------------------------------------------------------------- */

#include "compute_dilatancy_lsdem.h"

#include "error.h"
#include "input.h"
#include "lsdem_kernel.h"
#include "math_const.h"
#include "update.h"
#include "variable.h"

using namespace LAMMPS_NS;
using MathConst::MY_PI;

/* ---------------------------------------------------------------------- */

ComputeDilatancyLsdem::ComputeDilatancyLsdem(LAMMPS *lmp, int narg, char **arg) :
  Compute(lmp, narg, arg), prev_step(-1)
{
  if (narg != 5 || !utils::strmatch(arg[3], "^v_") || !utils::strmatch(arg[4], "^v_"))
    error->all(FLERR, "Illegal compute dilatancy/lsdem command: "
               "compute ID group dilatancy/lsdem v_epsv v_epsa");
  for (int k = 0; k < 2; k++) {
    name[k] = arg[3 + k] + 2;
    ivar[k] = -1;
    prev[k] = 0.0;
  }
  scalar_flag = 1;
  extscalar = 0;
  scalar = 0.0;
}

/* ---------------------------------------------------------------------- */

void ComputeDilatancyLsdem::init()
{
  for (int k = 0; k < 2; k++) {
    ivar[k] = input->variable->find(name[k].c_str());
    if (ivar[k] < 0 || !input->variable->equalstyle(ivar[k]))
      error->all(FLERR, "compute dilatancy/lsdem: {} is not an equal-style variable", name[k]);
  }
}

/* ---------------------------------------------------------------------- */

double ComputeDilatancyLsdem::compute_scalar()
{
  if (invoked_scalar == update->ntimestep) return scalar;  // same step: same increments
  invoked_scalar = update->ntimestep;
  double now[2];
  for (int k = 0; k < 2; k++) now[k] = input->variable->compute_equal(ivar[k]);
  scalar = prev_step < 0 ? 0.0
                         : (180.0 / MY_PI) * lsdem_dilatancy_angle(now[0] - prev[0], now[1] - prev[1]);
  prev[0] = now[0];
  prev[1] = now[1];
  prev_step = update->ntimestep;
  return scalar;
}
