// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   bond_style lsdem/membrane axis cx cy
   bond_coeff N Knbb Ksbb r0 rest_hoop rest_axial

   Membrane springs of report §2.3.5; the formula lives in the core
   (lsdem_membrane_bond_force). Coefficients per bond type: lsdem-shape membrane gives
   each bond orientation class its own type with the rest geometry of the lattice.
------------------------------------------------------------------------- */

#include "bond_lsdem_membrane.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "lsdem_input.h"
#include "memory.h"
#include "neighbor.h"
#include "update.h"

#include "lsdem_kernel.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

BondLsdemMembrane::BondLsdemMembrane(LAMMPS *lmp) :
    Bond(lmp), kn(nullptr), ks(nullptr), r0(nullptr), rest(nullptr), terms(nullptr),
    maxterms(0), terms_step(-1)
{
  axis[0] = axis[1] = 0.0;
}

/* ---------------------------------------------------------------------- */

BondLsdemMembrane::~BondLsdemMembrane()
{
  if (allocated && !copymode) {
    memory->destroy(setflag);
    memory->destroy(kn);
    memory->destroy(ks);
    memory->destroy(r0);
    memory->destroy(rest);
  }
  if (!copymode) memory->destroy(terms);
}

/* ---------------------------------------------------------------------- */

double BondLsdemMembrane::bond_force(const double *x1, const double *x2, int type,
                                     double *f2) const
{
  return lsdem_membrane_bond_force(x1, x2, axis, kn[type], ks[type], r0[type],
                                   &rest[2 * type], f2);
}

/* ---------------------------------------------------------------------- */

void BondLsdemMembrane::bond_terms(int from, int to)
{
  double **x = atom->x;
  int **bondlist = neighbor->bondlist;
  for (int n = from; n < to; n++) {
    double *t = &terms[4 * n];
    t[3] = bond_force(x[bondlist[n][0]], x[bondlist[n][1]], bondlist[n][2], t);
  }
}

void BondLsdemMembrane::all_bond_terms()
{
  bond_terms(0, neighbor->nbondlist);
}

const double *BondLsdemMembrane::force_on_atom2(int n) const
{
  return terms_step == update->ntimestep ? &terms[4 * n] : nullptr;
}

/* ---------------------------------------------------------------------- */

void BondLsdemMembrane::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);

  double **x = atom->x;
  double **f = atom->f;
  int **bondlist = neighbor->bondlist;
  int nbondlist = neighbor->nbondlist;
  int nlocal = atom->nlocal;
  int newton_bond = force->newton_bond;

  if (nbondlist > maxterms) {
    maxterms = nbondlist;
    memory->destroy(terms);
    memory->create(terms, 4 * maxterms, "bond:terms");
  }
  all_bond_terms();
  terms_step = update->ntimestep;

  for (int n = 0; n < nbondlist; n++) {
    int i1 = bondlist[n][0], i2 = bondlist[n][1], type = bondlist[n][2];
    const double *f2 = &terms[4 * n];
    if (newton_bond || i1 < nlocal)
      for (int k = 0; k < 3; k++) f[i1][k] -= f2[k];
    if (newton_bond || i2 < nlocal)
      for (int k = 0; k < 3; k++) f[i2][k] += f2[k];
    if (evflag) {
      // energy in full; virial of the normal (central) part only
      double del[3] = {x[i1][0] - x[i2][0], x[i1][1] - x[i2][1], x[i1][2] - x[i2][2]};
      double r = sqrt(del[0] * del[0] + del[1] * del[1] + del[2] * del[2]);
      double fbond = r > 0.0 ? -kn[type] * (r - r0[type]) / r : 0.0;
      ev_tally(i1, i2, nlocal, newton_bond, f2[3], fbond, del[0], del[1], del[2]);
    }
  }
}

/* ---------------------------------------------------------------------- */

void BondLsdemMembrane::allocate()
{
  allocated = 1;
  int n = atom->nbondtypes;
  memory->create(kn, n + 1, "bond:kn");
  memory->create(ks, n + 1, "bond:ks");
  memory->create(r0, n + 1, "bond:r0");
  memory->create(rest, 2 * (n + 1), "bond:rest");
  memory->create(setflag, n + 1, "bond:setflag");
  for (int i = 1; i <= n; i++) setflag[i] = 0;
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

  int count = 0;
  for (int i = ilo; i <= ihi; i++) {
    kn[i] = kn_one;
    ks[i] = ks_one;
    r0[i] = r0_one;
    rest[2 * i] = hoop;
    rest[2 * i + 1] = axial;
    setflag[i] = 1;
    count++;
  }
  if (count == 0) error->all(FLERR, "Incorrect args for bond coefficients");
}

/* ---------------------------------------------------------------------- */

double BondLsdemMembrane::equilibrium_distance(int i)
{
  return r0[i];
}

/* ---------------------------------------------------------------------- */

void BondLsdemMembrane::write_restart(FILE *fp)
{
  int n = atom->nbondtypes;
  fwrite(&kn[1], sizeof(double), n, fp);
  fwrite(&ks[1], sizeof(double), n, fp);
  fwrite(&r0[1], sizeof(double), n, fp);
  fwrite(&rest[2], sizeof(double), 2 * n, fp);
}

void BondLsdemMembrane::read_restart(FILE *fp)
{
  allocate();
  int n = atom->nbondtypes;
  if (comm->me == 0) {
    utils::sfread(FLERR, &kn[1], sizeof(double), n, fp, nullptr, error);
    utils::sfread(FLERR, &ks[1], sizeof(double), n, fp, nullptr, error);
    utils::sfread(FLERR, &r0[1], sizeof(double), n, fp, nullptr, error);
    utils::sfread(FLERR, &rest[2], sizeof(double), 2 * n, fp, nullptr, error);
  }
  MPI_Bcast(&kn[1], n, MPI_DOUBLE, 0, world);
  MPI_Bcast(&ks[1], n, MPI_DOUBLE, 0, world);
  MPI_Bcast(&r0[1], n, MPI_DOUBLE, 0, world);
  MPI_Bcast(&rest[2], 2 * n, MPI_DOUBLE, 0, world);
  for (int i = 1; i <= n; i++) setflag[i] = 1;
}

void BondLsdemMembrane::write_restart_settings(FILE *fp)
{
  fwrite(axis, sizeof(double), 2, fp);
}

void BondLsdemMembrane::read_restart_settings(FILE *fp)
{
  if (comm->me == 0) utils::sfread(FLERR, axis, sizeof(double), 2, fp, nullptr, error);
  MPI_Bcast(axis, 2, MPI_DOUBLE, 0, world);
}

/* ---------------------------------------------------------------------- */

void BondLsdemMembrane::write_data(FILE *fp)
{
  for (int i = 1; i <= atom->nbondtypes; i++)
    fprintf(fp, "%d %.15g %.15g %.15g %.15g %.15g\n", i, kn[i], ks[i], r0[i], rest[2 * i],
            rest[2 * i + 1]);
}

/* ----------------------------------------------------------------------
   compute bond/local: energy of both springs; fforce = the normal (central) part only
------------------------------------------------------------------------- */

double BondLsdemMembrane::single(int type, double rsq, int i, int j, double &fforce)
{
  double r = sqrt(rsq);
  fforce = r > 0.0 ? -kn[type] * (r - r0[type]) / r : 0.0;
  double f2[3];
  return bond_force(atom->x[i], atom->x[j], type, f2);
}

/* ---------------------------------------------------------------------- */

double BondLsdemMembrane::memory_usage()
{
  return Bond::memory_usage() + 4.0 * maxterms * sizeof(double);
}

/* ---------------------------------------------------------------------- */

void *BondLsdemMembrane::extract(const char *str, int &dim)
{
  dim = 1;
  if (strcmp(str, "kn") == 0) return (void *) kn;
  if (strcmp(str, "ks") == 0) return (void *) ks;
  if (strcmp(str, "r0") == 0) return (void *) r0;
  return nullptr;
}
