// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   bond_style lsdem/membrane axis cx cy
   bond_coeff N Knbb Ksbb r0 rest_hoop rest_axial

   Membrane springs of report §2.3.5, a net's bonds (bond_style lsdem/net: its force call,
   buffer, scatter, restart arrays) with the tangential spring added; the formula lives in
   the core (lsdem_membrane_bond_force on lsdem_bond_axial_force). Coefficients per bond
   type: lsdem-shape membrane gives each bond orientation class its own type with the rest
   geometry of the lattice.
------------------------------------------------------------------------- */

#include "bond_lsdem_membrane.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "lsdem_input.h"
#include "memory.h"

#include "lsdem_kernel.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

BondLsdemMembrane::BondLsdemMembrane(LAMMPS *lmp) :
    BondLsdemNet(lmp), ks(nullptr), rest(nullptr)
{
  axis[0] = axis[1] = 0.0;
}

/* ---------------------------------------------------------------------- */

BondLsdemMembrane::~BondLsdemMembrane()
{
  if (allocated && !copymode) {
    memory->destroy(ks);
    memory->destroy(rest);
  }
}

/* ---------------------------------------------------------------------- */

double BondLsdemMembrane::bond_force(const double *x1, const double *x2, int type,
                                     double *f2) const
{
  return lsdem_membrane_bond_force(x1, x2, axis, k[type], ks[type], r0[type],
                                   &rest[2 * type], f2);
}

/* no rupture (mode none): the stretch is not asked for */
double BondLsdemMembrane::bond_term(int i1, int i2, int type, double *f2,
                                    double *stretch) const
{
  *stretch = 0.0;
  return bond_force(atom->x[i1], atom->x[i2], type, f2);
}

/* the virial of the normal (central) spring only */
double BondLsdemMembrane::virial_fbond(int type, const double * /*del*/, double rsq,
                                       const double * /*f2*/) const
{
  return spring_fbond(type, rsq);
}

/* ---------------------------------------------------------------------- */

void BondLsdemMembrane::allocate()
{
  BondLsdemNet::allocate();
  const int n = atom->nbondtypes;
  memory->create(ks, n + 1, "bond:ks");
  memory->create(rest, 2 * (n + 1), "bond:rest");
}

/* the forces are not rounded: the membrane's sums in bond-list order, as they always were */
void BondLsdemMembrane::init_style()
{
  quantum.q = quantum.inv_q = 0.0;
}

/* ----------------------------------------------------------------------
   bond_style lsdem/membrane [axis cx cy]
------------------------------------------------------------------------- */

void BondLsdemMembrane::settings(int narg, char **arg)
{
  if (narg != 0 && !(narg == 3 && strcmp(arg[0], "axis") == 0))
    error->all(FLERR, "Illegal bond_style lsdem/membrane command: expected "
               "'bond_style lsdem/membrane [axis cx cy]'");
  axis[0] = axis[1] = 0.0;
  if (narg == 3) {
    axis[0] = LsdemInput::number(FLERR, arg[1], "bond_style lsdem/membrane", "axis cx", lmp);
    axis[1] = LsdemInput::number(FLERR, arg[2], "bond_style lsdem/membrane", "axis cy", lmp);
  }
}

/* ----------------------------------------------------------------------
   bond_coeff N Knbb Ksbb r0 rest_hoop rest_axial
------------------------------------------------------------------------- */

void BondLsdemMembrane::coeff(int narg, char **arg)
{
  if (narg != 6)
    error->all(FLERR, "Incorrect args for bond coefficients: bond_style lsdem/membrane needs "
               "'bond_coeff N Knbb Ksbb r0 rest_hoop rest_axial' (lsdem-shape membrane writes "
               "them)");
  if (!allocated) allocate();

  int ilo, ihi;
  utils::bounds(FLERR, arg[0], 1, atom->nbondtypes, ilo, ihi, error);
  double kn_one = LsdemInput::number(FLERR, arg[1], "bond_coeff lsdem/membrane", "kn", lmp);
  double ks_one = LsdemInput::number(FLERR, arg[2], "bond_coeff lsdem/membrane", "ks", lmp);
  double r0_one = LsdemInput::number(FLERR, arg[3], "bond_coeff lsdem/membrane", "r0", lmp);
  double hoop = LsdemInput::number(FLERR, arg[4], "bond_coeff lsdem/membrane", "hoop", lmp);
  double axial = LsdemInput::number(FLERR, arg[5], "bond_coeff lsdem/membrane", "axial", lmp);
  if (kn_one < 0.0 || ks_one < 0.0)
    error->all(FLERR, "Bond lsdem/membrane: Knbb ({}) and Ksbb ({}) must be >= 0", kn_one,
               ks_one);
  if (r0_one <= 0.0) error->all(FLERR, "Bond lsdem/membrane: r0 ({}) must be > 0", r0_one);

  set_types(ilo, ihi, kn_one, r0_one, 0.0, 0.0, LSDEM_NET_BREAK_NONE);
  for (int i = ilo; i <= ihi; i++) {
    ks[i] = ks_one;
    rest[2 * i] = hoop;
    rest[2 * i + 1] = axial;
  }
}

/* ---------------------------------------------------------------------- */

void BondLsdemMembrane::write_restart(FILE *fp)
{
  int n = atom->nbondtypes;
  fwrite(&k[1], sizeof(double), n, fp);
  fwrite(&ks[1], sizeof(double), n, fp);
  fwrite(&r0[1], sizeof(double), n, fp);
  fwrite(&rest[2], sizeof(double), 2 * n, fp);
}

void BondLsdemMembrane::read_restart(FILE *fp)
{
  allocate();
  const int n = atom->nbondtypes;
  restart_doubles(fp, &k[1], n);
  restart_doubles(fp, &ks[1], n);
  restart_doubles(fp, &r0[1], n);
  restart_doubles(fp, &rest[2], 2 * n);
  for (int i = 1; i <= n; i++) setflag[i] = 1;
}

void BondLsdemMembrane::write_restart_settings(FILE *fp)
{
  fwrite(axis, sizeof(double), 2, fp);
}

void BondLsdemMembrane::read_restart_settings(FILE *fp)
{
  restart_doubles(fp, axis, 2);
}

/* ---------------------------------------------------------------------- */

void BondLsdemMembrane::write_data(FILE *fp)
{
  for (int i = 1; i <= atom->nbondtypes; i++)
    fprintf(fp, "%d %.15g %.15g %.15g %.15g %.15g\n", i, k[i], ks[i], r0[i], rest[2 * i],
            rest[2 * i + 1]);
}

/* ----------------------------------------------------------------------
   compute bond/local: energy of both springs; fforce = the normal (central) part only
------------------------------------------------------------------------- */

double BondLsdemMembrane::single(int type, double rsq, int i, int j, double &fforce)
{
  fforce = spring_fbond(type, rsq);
  double f2[3];
  return bond_force(atom->x[i], atom->x[j], type, f2);
}

/* ---------------------------------------------------------------------- */

void *BondLsdemMembrane::extract(const char *str, int &dim)
{
  dim = 1;
  if (strcmp(str, "kn") == 0) return (void *) k;
  if (strcmp(str, "ks") == 0) return (void *) ks;
  return BondLsdemNet::extract(str, dim);
}
