// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   bond_style lsdem/net
   bond_coeff N K r0 [damp C] [break strain S | break force F]

   Net springs of report §4.4.2 (Figure 4.6); the formula and the rupture criteria live in
   the core (lsdem_net_bond_force, lsdem_net_bond_breaks). doc/bond_lsdem_net.rst.
------------------------------------------------------------------------- */

#include "bond_lsdem_net.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "lsdem_input.h"
#include "memory.h"
#include "neighbor.h"
#include "pair.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

BondLsdemNet::BondLsdemNet(LAMMPS *lmp) :
    Bond(lmp), k(nullptr), r0(nullptr), damp(nullptr), limit(nullptr), mode(nullptr),
    damping_work(nullptr), terms(nullptr), maxterms(0), terms_step(-1)
{
  quantum.q = quantum.inv_q = 0.0;
}

/* ---------------------------------------------------------------------- */

BondLsdemNet::~BondLsdemNet()
{
  if (allocated && !copymode) {
    memory->destroy(setflag);
    memory->destroy(k);
    memory->destroy(r0);
    memory->destroy(damp);
    memory->destroy(limit);
    memory->destroy(mode);
    memory->destroy(damping_work);
  }
  if (!copymode) memory->destroy(terms);
}

/* ----------------------------------------------------------------------
   switch bond n off: type 0 in the bond list and in the atoms' bond_type (both atoms'
   entries when this rank owns both; the owner of a ghost atom 2 breaks its own entry, as
   bond_style quartic does)
------------------------------------------------------------------------- */

void BondLsdemNet::break_bond(int n)
{
  int **bondlist = neighbor->bondlist;
  const int i1 = bondlist[n][0], i2 = bondlist[n][1];
  bondlist[n][2] = 0;
  for (int m = 0; m < atom->num_bond[i1]; m++)
    if (atom->bond_atom[i1][m] == atom->tag[i2]) atom->bond_type[i1][m] = 0;
  if (i2 < atom->nlocal)
    for (int m = 0; m < atom->num_bond[i2]; m++)
      if (atom->bond_atom[i2][m] == atom->tag[i1]) atom->bond_type[i2][m] = 0;
}

/* ---------------------------------------------------------------------- */

double BondLsdemNet::bond_term(int i1, int i2, int type, double *f2, double *stretch) const
{
  double **x = atom->x, **v = atom->v;
  return lsdem_net_bond_force(x[i1], x[i2], v[i1], v[i2], k[type], r0[type], damp[type], f2,
                              stretch);
}

void BondLsdemNet::bond_terms(int from, int to)
{
  int **bondlist = neighbor->bondlist;
  for (int n = from; n < to; n++) {
    if (bondlist[n][2] <= 0) continue;    // broken
    double *t = &terms[5 * n];
    t[3] = bond_term(bondlist[n][0], bondlist[n][1], bondlist[n][2], t, &t[4]);
  }
}

void BondLsdemNet::all_bond_terms()
{
  bond_terms(0, neighbor->nbondlist);
}

const double *BondLsdemNet::force_on_atom2(int n) const
{
  return terms_step == update->ntimestep ? &terms[5 * n] : nullptr;
}

/* f on atom 1 = fbond * del: the force is axial */
double BondLsdemNet::virial_fbond(int /*type*/, const double *del, double rsq,
                                  const double *f2) const
{
  return rsq > 0.0 ? -(f2[0] * del[0] + f2[1] * del[1] + f2[2] * del[2]) / rsq : 0.0;
}

/* ----------------------------------------------------------------------
   phase two for entry n: rupture, the damping work, the rounded force onto the atoms
------------------------------------------------------------------------- */

void BondLsdemNet::apply_term(int n)
{
  int **bondlist = neighbor->bondlist;
  const int type = bondlist[n][2];
  if (type <= 0) return;    // broken
  double **x = atom->x, **v = atom->v, **f = atom->f;
  const int i1 = bondlist[n][0], i2 = bondlist[n][1];
  const int nlocal = atom->nlocal;
  const int newton_bond = force->newton_bond;
  double *f2 = &terms[5 * n];
  if (lsdem_net_bond_breaks(mode[type], limit[type], k[type], r0[type], f2[4])) {
    break_bond(n);
    return;
  }
  if (damp[type] > 0.0 && !update->setupflag) {
    // work of the damping force over this step (a bond seen by two ranks counts half on each)
    const double share = newton_bond || (i1 < nlocal && i2 < nlocal) ? 1.0 : 0.5;
    damping_work[type] += share * update->dt *
        lsdem_net_bond_damping_power(x[i1], x[i2], v[i1], v[i2], damp[type]);
  }
  lsdem_quantize3(f2, quantum, f2);
  if (newton_bond || i1 < nlocal)
    for (int d = 0; d < 3; d++) f[i1][d] -= f2[d];
  if (newton_bond || i2 < nlocal)
    for (int d = 0; d < 3; d++) f[i2][d] += f2[d];
  if (evflag) {
    const double del[3] = {x[i1][0] - x[i2][0], x[i1][1] - x[i2][1], x[i1][2] - x[i2][2]};
    const double rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
    ev_tally(i1, i2, nlocal, newton_bond, f2[3], virial_fbond(type, del, rsq, f2), del[0],
             del[1], del[2]);
  }
}

void BondLsdemNet::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  const int nbondlist = neighbor->nbondlist;
  if (nbondlist > maxterms) {
    maxterms = nbondlist;
    memory->destroy(terms);
    memory->create(terms, 5 * maxterms, "bond:terms");
  }
  all_bond_terms();
  terms_step = update->ntimestep;
  for (int n = 0; n < nbondlist; n++) apply_term(n);
}

/* ----------------------------------------------------------------------
   the quantum: the stiffest type's force at 100 % strain or its break force, and at
   least pair_style lsdem's (its contact terms on the balls are in the same sums); under
   bond_style hybrid, of this style's types only
------------------------------------------------------------------------- */

void BondLsdemNet::init_style()
{
  double scale = 0.0;
  for (int i = 1; i <= atom->nbondtypes; i++) {
    if (!setflag[i]) continue;
    scale = std::max(scale, k[i] * r0[i]);
    if (mode[i] == LSDEM_NET_BREAK_FORCE) scale = std::max(scale, limit[i]);
    if (damp[i] > 0.0 && !comm->ghost_velocity)
      error->all(FLERR, "Bond lsdem/net: bond type {} has damping, which needs the ghost atoms' "
                 "velocities: add 'comm_modify vel yes'", i);
  }
  quantum = lsdem_quantum_for(scale);
  int dim;
  const double *pair_q = force->pair
                             ? (const double *) force->pair->extract("force_quantum", dim)
                             : nullptr;
  if (pair_q && *pair_q > quantum.q) {
    quantum.q = *pair_q;
    quantum.inv_q = 1.0 / *pair_q;    // a power of two: exact
  }
}

/* ---------------------------------------------------------------------- */

void BondLsdemNet::allocate()
{
  allocated = 1;
  const int n = atom->nbondtypes;
  memory->create(k, n + 1, "bond:k");
  memory->create(r0, n + 1, "bond:r0");
  memory->create(damp, n + 1, "bond:damp");
  memory->create(limit, n + 1, "bond:limit");
  memory->create(mode, n + 1, "bond:mode");
  memory->create(setflag, n + 1, "bond:setflag");
  memory->create(damping_work, n + 1, "bond:damping_work");
  for (int i = 0; i <= n; i++) {
    setflag[i] = 0;
    damp[i] = limit[i] = damping_work[i] = 0.0;
    mode[i] = LSDEM_NET_BREAK_NONE;
  }
}

/* coefficients of types [ilo, ihi] */
void BondLsdemNet::set_types(int ilo, int ihi, double k_one, double r0_one, double damp_one,
                             double limit_one, int mode_one)
{
  int count = 0;
  for (int i = ilo; i <= ihi; i++) {
    k[i] = k_one;
    r0[i] = r0_one;
    damp[i] = damp_one;
    limit[i] = limit_one;
    mode[i] = mode_one;
    setflag[i] = 1;
    count++;
  }
  if (count == 0) error->all(FLERR, "Incorrect args for bond coefficients");
}

/* ---------------------------------------------------------------------- */

void BondLsdemNet::settings(int narg, char ** /*arg*/)
{
  if (narg != 0)
    error->all(FLERR, "Illegal bond_style lsdem/net command: it takes no arguments");
}

/* ----------------------------------------------------------------------
   bond_coeff N K r0 [damp C] [break strain S | break force F]
------------------------------------------------------------------------- */

void BondLsdemNet::coeff(int narg, char **arg)
{
  const char *usage = "'bond_coeff N K r0 [damp C] [break strain S | break force F]'";
  if (narg < 3) error->all(FLERR, "Incorrect args for bond coefficients: bond_style lsdem/net "
                           "needs {} (lsdem-shape net writes it)", usage);
  if (!allocated) allocate();

  int ilo, ihi;
  utils::bounds(FLERR, arg[0], 1, atom->nbondtypes, ilo, ihi, error);
  const double k_one = LsdemInput::number(FLERR, arg[1], "bond_coeff lsdem/net", "K", lmp);
  const double r0_one = LsdemInput::number(FLERR, arg[2], "bond_coeff lsdem/net", "r0", lmp);
  if (k_one <= 0.0) error->all(FLERR, "Bond lsdem/net: K ({}) must be > 0", k_one);
  if (r0_one <= 0.0) error->all(FLERR, "Bond lsdem/net: r0 ({}) must be > 0", r0_one);
  double damp_one = 0.0, limit_one = 0.0;
  int mode_one = LSDEM_NET_BREAK_NONE;
  for (int a = 3; a < narg;) {
    if (strcmp(arg[a], "damp") == 0 && a + 1 < narg) {
      damp_one = LsdemInput::number(FLERR, arg[a + 1], "bond_coeff lsdem/net", "damp", lmp);
      if (damp_one < 0.0)
        error->all(FLERR, "Bond lsdem/net: damp ({}) must be >= 0 (0: no damping)", damp_one);
      a += 2;
    } else if (strcmp(arg[a], "break") == 0 && a + 2 < narg &&
               (strcmp(arg[a + 1], "strain") == 0 || strcmp(arg[a + 1], "force") == 0)) {
      mode_one = strcmp(arg[a + 1], "strain") == 0 ? LSDEM_NET_BREAK_STRAIN
                                                   : LSDEM_NET_BREAK_FORCE;
      limit_one = LsdemInput::number(FLERR, arg[a + 2], "bond_coeff lsdem/net", "break", lmp);
      if (limit_one <= 0.0)
        error->all(FLERR, "Bond lsdem/net: break {} limit ({}) must be > 0: a bond breaks when "
                   "its {} exceeds it (leave 'break' out for bonds that never break)",
                   arg[a + 1], limit_one,
                   mode_one == LSDEM_NET_BREAK_STRAIN ? "strain (L - r0) / r0"
                                                      : "tension K (L - r0)");
      a += 3;
    } else {
      error->all(FLERR, "Incorrect args for bond coefficients: unknown or incomplete keyword "
                 "'{}' of bond_style lsdem/net; expected {}", arg[a], usage);
    }
  }

  set_types(ilo, ihi, k_one, r0_one, damp_one, limit_one, mode_one);
}

/* ---------------------------------------------------------------------- */

double BondLsdemNet::equilibrium_distance(int i)
{
  return r0[i];
}

/* ---------------------------------------------------------------------- */

void BondLsdemNet::write_restart(FILE *fp)
{
  const int n = atom->nbondtypes;
  fwrite(&k[1], sizeof(double), n, fp);
  fwrite(&r0[1], sizeof(double), n, fp);
  fwrite(&damp[1], sizeof(double), n, fp);
  fwrite(&limit[1], sizeof(double), n, fp);
  fwrite(&mode[1], sizeof(int), n, fp);
}

void BondLsdemNet::read_restart(FILE *fp)
{
  allocate();
  const int n = atom->nbondtypes;
  restart_doubles(fp, &k[1], n);
  restart_doubles(fp, &r0[1], n);
  restart_doubles(fp, &damp[1], n);
  restart_doubles(fp, &limit[1], n);
  if (comm->me == 0) utils::sfread(FLERR, &mode[1], sizeof(int), n, fp, nullptr, error);
  MPI_Bcast(&mode[1], n, MPI_INT, 0, world);
  for (int i = 1; i <= n; i++) setflag[i] = 1;
}

/* n doubles of a restart file: read on rank 0, sent to every rank */
void BondLsdemNet::restart_doubles(FILE *fp, double *a, int n)
{
  if (comm->me == 0) utils::sfread(FLERR, a, sizeof(double), n, fp, nullptr, error);
  MPI_Bcast(a, n, MPI_DOUBLE, 0, world);
}

/* ---------------------------------------------------------------------- */

void BondLsdemNet::write_data(FILE *fp)
{
  for (int i = 1; i <= atom->nbondtypes; i++) {
    fprintf(fp, "%d %.15g %.15g", i, k[i], r0[i]);
    if (damp[i] > 0.0) fprintf(fp, " damp %.15g", damp[i]);
    if (mode[i] != LSDEM_NET_BREAK_NONE)
      fprintf(fp, " break %s %.15g", mode[i] == LSDEM_NET_BREAK_STRAIN ? "strain" : "force",
              limit[i]);
    fprintf(fp, "\n");
  }
}

/* ----------------------------------------------------------------------
   compute bond/local: the spring alone (no velocities here: no damping)
------------------------------------------------------------------------- */

double BondLsdemNet::single(int type, double rsq, int /*i*/, int /*j*/, double &fforce)
{
  const double dr = sqrt(rsq) - r0[type];
  fforce = spring_fbond(type, rsq);
  return 0.5 * k[type] * dr * dr;
}

/* the axial spring alone as fbond (f on atom 1 = fbond * del): -K (r - r0) / r */
double BondLsdemNet::spring_fbond(int type, double rsq) const
{
  const double r = sqrt(rsq);
  return r > 0.0 ? -k[type] * (r - r0[type]) / r : 0.0;
}

/* ---------------------------------------------------------------------- */

double BondLsdemNet::memory_usage()
{
  return Bond::memory_usage() + 5.0 * maxterms * sizeof(double);
}

/* ---------------------------------------------------------------------- */

void *BondLsdemNet::extract(const char *str, int &dim)
{
  dim = 1;
  if (strcmp(str, "k") == 0) return (void *) k;
  if (strcmp(str, "r0") == 0) return (void *) r0;
  if (strcmp(str, "damping_work") == 0) return (void *) damping_work;    // this rank's, per type
  dim = 0;
  if (strcmp(str, "force_quantum") == 0) return (void *) &quantum.q;    // after init_style
  return nullptr;
}
