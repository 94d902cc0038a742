// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute stress/lsdem (doc/compute_stress_lsdem.rst). Sums, over every contact of every
   grain of the group, the moment f (x) (x_c - x_grain) of the contact force on that grain
   (core lsdem_love_weber_add): grain-grain contacts from pair_style lsdem's contact list
   of its last force call (each test is listed once, on the rank owning its master), wall
   and platen contacts from the listed fix wall/lsdem. A membrane sphere is an atom that
   pair_style lsdem touches like any other, so grain-membrane contacts are in the pair list
   and count for the grain side only (membrane spheres are not in the group).
------------------------------------------------------------------------- */

#include "compute_stress_lsdem.h"

#include "atom.h"
#include "error.h"
#include "fix_wall_lsdem.h"
#include "input.h"
#include "lsdem_input.h"
#include "math_const.h"
#include "pair_lsdem.h"
#include "update.h"
#include "variable.h"

#include <cstring>

using namespace LAMMPS_NS;
using MathConst::MY_PI;

// vector: sxx syy szz sxy sxz syz p q phi_mob(deg) sigma1 sigma3
static constexpr int NVALUES = 11;

/* ---------------------------------------------------------------------- */

ComputeStressLsdem::ComputeStressLsdem(LAMMPS *lmp, int narg, char **arg) :
  Compute(lmp, narg, arg), volume_value(0.0), ivar(-1)
{
  const char *usage = "compute ID group stress/lsdem volume V|v_name [wall fixID ...]";
  if (narg < 5 || strcmp(arg[3], "volume") != 0)
    error->all(FLERR, "Illegal compute stress/lsdem command: {}", usage);
  if (utils::strmatch(arg[4], "^v_")) volume_var = arg[4] + 2;
  else {
    volume_value = LsdemInput::number(FLERR, arg[4], "compute stress/lsdem", "volume", lmp);
    if (volume_value <= 0.0) error->all(FLERR, "compute stress/lsdem: volume must be > 0");
  }
  int iarg = 5;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "wall") != 0 || iarg + 1 >= narg)
      error->all(FLERR, "Illegal compute stress/lsdem command: {}", usage);
    iarg++;
    while (iarg < narg && strcmp(arg[iarg], "wall") != 0) wall_ids.emplace_back(arg[iarg++]);
  }

  vector_flag = 1;
  size_vector = NVALUES;
  extvector = 0;
  vector = new double[NVALUES];
}

/* ---------------------------------------------------------------------- */

ComputeStressLsdem::~ComputeStressLsdem()
{
  delete[] vector;
}

/* ---------------------------------------------------------------------- */

void ComputeStressLsdem::init()
{
  sources.find(lmp, wall_ids, "compute stress/lsdem");
  if (!sources.pair && sources.walls.empty())
    error->all(FLERR, "compute stress/lsdem needs pair_style lsdem or a wall/lsdem fix");
  if (!volume_var.empty()) {
    ivar = input->variable->find(volume_var.c_str());
    if (ivar < 0) error->all(FLERR, "compute stress/lsdem: variable {} does not exist", volume_var);
    if (!input->variable->equalstyle(ivar))
      error->all(FLERR, "compute stress/lsdem: variable {} is not equal-style", volume_var);
  }
}

/* ---------------------------------------------------------------------- */

double ComputeStressLsdem::specimen_volume()
{
  if (ivar < 0) return volume_value;
  double v = input->variable->compute_equal(ivar);
  if (!(v > 0.0))
    error->all(FLERR, "compute stress/lsdem: volume variable {} = {} (must be > 0)", volume_var, v);
  return v;
}

/* ----------------------------------------------------------------------
   pair contacts: the force scale * res.force acts on master i at the contact point,
   its reaction on slave j (a ghost keeps the image coordinates the pair used)
------------------------------------------------------------------------- */

void ComputeStressLsdem::add_pair_contacts(double M[9]) const
{
  const int *mask = atom->mask;
  double **x = atom->x;
  sources.pair->each_contact([&](const PairLsdem::Contact &c) {
    const double s = c.scale;
    const double fi[3] = {s * c.res.force[0], s * c.res.force[1], s * c.res.force[2]};
    const double fj[3] = {-fi[0], -fi[1], -fi[2]};
    if (mask[c.i] & groupbit) lsdem_love_weber_add(M, fi, c.res.point, x[c.i]);
    if (mask[c.j] & groupbit) lsdem_love_weber_add(M, fj, c.res.point, x[c.j]);
  });
}

/* ---------------------------------------------------------------------- */

void ComputeStressLsdem::add_wall_contacts(double M[9]) const
{
  const int *mask = atom->mask;
  double **x = atom->x;
  for (const FixWallLsdem *w : sources.walls)
    w->each_contact([&](const FixWallLsdem::Contact &c) {
      if (mask[c.i] & groupbit) lsdem_love_weber_add(M, c.force, c.point, x[c.i]);
    });
}

/* ---------------------------------------------------------------------- */

void ComputeStressLsdem::compute_vector()
{
  invoked_vector = update->ntimestep;

  double Mlocal[9] = {0.0}, M[9], sigma[9], s[3];
  sources.check_current(lmp, "compute stress/lsdem");
  if (sources.pair) add_pair_contacts(Mlocal);
  add_wall_contacts(Mlocal);
  MPI_Allreduce(Mlocal, M, 9, MPI_DOUBLE, MPI_SUM, world);

  lsdem_love_weber_stress(M, specimen_volume(), sigma);
  lsdem_stress_principal(sigma, s);
  lsdem_sym_to_voigt(sigma, vector);
  vector[6] = lsdem_stress_mean(sigma);
  vector[7] = lsdem_stress_deviatoric(sigma);
  vector[8] = (180.0 / MY_PI) * lsdem_friction_angle(s[0], s[2]);
  vector[9] = s[0];
  vector[10] = s[2];
}
