// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute ID group inertial/lsdem RATE PRESSURE [warn LIMIT]
   (doc/compute_inertial_lsdem.rst). Scalar: I = |rate| d / sqrt(pressure / rho) (core
   lsdem_inertial_number, report eq 3.5) with d = mean equivalent-sphere diameter of the
   group's grains (6 V / pi)^(1/3) and rho = their total mass / total volume. RATE and
   PRESSURE are numbers or equal-style variables (v_name).
------------------------------------------------------------------------- */

#include "compute_inertial_lsdem.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "comm.h"
#include "error.h"
#include "input.h"
#include "lsdem_input.h"
#include "math_const.h"
#include "update.h"
#include "variable.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using MathConst::MY_PI;

/* ---------------------------------------------------------------------- */

ComputeInertialLsdem::ComputeInertialLsdem(LAMMPS *lmp, int narg, char **arg) :
  Compute(lmp, narg, arg), limit(1.0e-3), warned(false), avec(nullptr)
{
  if (narg != 5 && !(narg == 7 && strcmp(arg[5], "warn") == 0))
    error->all(FLERR, "Illegal compute inertial/lsdem command: "
               "compute ID group inertial/lsdem RATE PRESSURE [warn LIMIT]");
  parse_input(rate, arg[3]);
  parse_input(pressure, arg[4]);
  if (narg == 7) limit = LsdemInput::number(FLERR, arg[6], "compute inertial/lsdem", "warn", lmp);
  scalar_flag = 1;
  extscalar = 0;
}

/* ---------------------------------------------------------------------- */

void ComputeInertialLsdem::parse_input(Input &in, const char *s)
{
  in.value = 0.0;
  in.ivar = -1;
  if (utils::strmatch(s, "^v_")) in.var = s + 2;
  else in.value = LsdemInput::number(FLERR, s, "compute inertial/lsdem", "RATE or PRESSURE", lmp);
}

/* ---------------------------------------------------------------------- */

void ComputeInertialLsdem::init()
{
  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  if (!avec) error->all(FLERR, "Compute inertial/lsdem requires atom_style lsdem");
  for (Input *in : {&rate, &pressure}) {
    if (in->var.empty()) continue;
    in->ivar = input->variable->find(in->var.c_str());
    if (in->ivar < 0 || !input->variable->equalstyle(in->ivar))
      error->all(FLERR, "compute inertial/lsdem: {} is not an equal-style variable", in->var);
  }
}

/* ---------------------------------------------------------------------- */

double ComputeInertialLsdem::value_of(const Input &in)
{
  return in.ivar < 0 ? in.value : input->variable->compute_equal(in.ivar);
}

/* ---------------------------------------------------------------------- */

double ComputeInertialLsdem::compute_scalar()
{
  invoked_scalar = update->ntimestep;

  double local[3] = {0.0, 0.0, 0.0}, all[3];  // count, sum of diameters, sum of volumes
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const double v = avec->shape_of(i)->volume;
    local[0] += 1.0;
    local[1] += cbrt(6.0 * v / MY_PI);
    local[2] += v;
  }
  MPI_Allreduce(local, all, 3, MPI_DOUBLE, MPI_SUM, world);
  double mass = 0.0, mass_all;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) mass += atom->rmass[i];
  MPI_Allreduce(&mass, &mass_all, 1, MPI_DOUBLE, MPI_SUM, world);
  if (all[0] == 0.0) return scalar = 0.0;

  // unconfined (pressure <= 0, e.g. a ramp still at zero): I is infinite, and says nothing
  // about the shearing rate, so it warns of nothing
  const double p = value_of(pressure);
  scalar = lsdem_inertial_number(value_of(rate), all[1] / all[0], p, mass_all / all[2]);
  if (p > 0.0 && scalar > limit && !warned) {
    warned = true;
    if (comm->me == 0)
      error->warning(FLERR, "Inertial number {:.3g} > {:.3g} at step {}: shearing is not "
                     "quasi-static (report eq 3.5); lower the strain rate", scalar, limit,
                     update->ntimestep);
  }
  return scalar;
}
