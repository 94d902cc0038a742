// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   angle_style lsdem/net
   angle_coeff N Kb

   Bending of a net's joints (report §4.4.2 names the net's springs; this adds the bending
   stiffness its bond style lacks); the formula lives in the core (lsdem_net_bend_force).
   doc/angle_lsdem_net.rst.
------------------------------------------------------------------------- */

#include "angle_lsdem_net.h"

#include "atom.h"
#include "bond.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "lsdem_input.h"
#include "math_const.h"
#include "memory.h"
#include "neighbor.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

AngleLsdemNet::AngleLsdemNet(LAMMPS *lmp) : Angle(lmp), kb(nullptr)
{
  quantum.q = quantum.inv_q = 0.0;
}

AngleLsdemNet::~AngleLsdemNet()
{
  if (allocated && !copymode) {
    memory->destroy(setflag);
    memory->destroy(kb);
  }
}

/* ---------------------------------------------------------------------- */

void AngleLsdemNet::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);

  double **x = atom->x, **f = atom->f;
  int **anglelist = neighbor->anglelist;
  const int nanglelist = neighbor->nanglelist;
  const int nlocal = atom->nlocal;
  const int newton_bond = force->newton_bond;

  for (int n = 0; n < nanglelist; n++) {
    const int i1 = anglelist[n][0], i2 = anglelist[n][1], i3 = anglelist[n][2];
    const int type = anglelist[n][3];
    double f1[3], f3[3];
    const double e = lsdem_net_bend_force(x[i1], x[i2], x[i3], kb[type], f1, f3);
    lsdem_quantize3(f1, quantum, f1);
    lsdem_quantize3(f3, quantum, f3);
    if (newton_bond || i1 < nlocal)
      for (int d = 0; d < 3; d++) f[i1][d] += f1[d];
    if (newton_bond || i2 < nlocal)
      for (int d = 0; d < 3; d++) f[i2][d] -= f1[d] + f3[d];    // exact: multiples of q
    if (newton_bond || i3 < nlocal)
      for (int d = 0; d < 3; d++) f[i3][d] += f3[d];
    if (evflag)
      ev_tally(i1, i2, i3, nlocal, newton_bond, e, f1, f3, x[i1][0] - x[i2][0],
               x[i1][1] - x[i2][1], x[i1][2] - x[i2][2], x[i3][0] - x[i2][0],
               x[i3][1] - x[i2][1], x[i3][2] - x[i2][2]);
  }
}

/* ----------------------------------------------------------------------
   the quantum of bond_style lsdem/net (itself at least pair_style lsdem's): the joints'
   forces go into the same order-free sums on the balls
------------------------------------------------------------------------- */

void AngleLsdemNet::init_style()
{
  int dim;
  const double *q = force->bond && force->bond_match("lsdem/net")
                        ? (const double *) force->bond->extract("force_quantum", dim)
                        : nullptr;
  if (!q)
    error->all(FLERR, "Angle lsdem/net bends the joints of a net: it needs bond_style "
               "lsdem/net (lsdem-shape net --bending writes both into PREFIX.in)");
  quantum.q = *q;
  quantum.inv_q = 1.0 / *q;    // a power of two: exact
}

/* ---------------------------------------------------------------------- */

void AngleLsdemNet::allocate()
{
  allocated = 1;
  const int n = atom->nangletypes;
  memory->create(kb, n + 1, "angle:kb");
  memory->create(setflag, n + 1, "angle:setflag");
  for (int i = 0; i <= n; i++) setflag[i] = 0;
}

/* ----------------------------------------------------------------------
   angle_coeff N Kb
------------------------------------------------------------------------- */

void AngleLsdemNet::coeff(int narg, char **arg)
{
  if (narg != 2)
    error->all(FLERR, "Incorrect args for angle coefficients: angle_style lsdem/net needs "
               "'angle_coeff N Kb' (lsdem-shape net --bending writes it)");
  if (!allocated) allocate();
  int ilo, ihi;
  utils::bounds(FLERR, arg[0], 1, atom->nangletypes, ilo, ihi, error);
  const double kb_one = LsdemInput::number(FLERR, arg[1], "angle_coeff lsdem/net", "Kb", lmp);
  if (kb_one < 0.0)
    error->all(FLERR, "Angle lsdem/net: Kb ({}) must be >= 0 (0: joints that bend freely)",
               kb_one);
  int count = 0;
  for (int i = ilo; i <= ihi; i++, count++) {
    kb[i] = kb_one;
    setflag[i] = 1;
  }
  if (count == 0) error->all(FLERR, "Incorrect args for angle coefficients");
}

/* ---------------------------------------------------------------------- */

double AngleLsdemNet::equilibrium_angle(int /*i*/)
{
  return MathConst::MY_PI;
}

void AngleLsdemNet::write_restart(FILE *fp)
{
  fwrite(&kb[1], sizeof(double), atom->nangletypes, fp);
}

void AngleLsdemNet::read_restart(FILE *fp)
{
  allocate();
  const int n = atom->nangletypes;
  if (comm->me == 0) utils::sfread(FLERR, &kb[1], sizeof(double), n, fp, nullptr, error);
  MPI_Bcast(&kb[1], n, MPI_DOUBLE, 0, world);
  for (int i = 1; i <= n; i++) setflag[i] = 1;
}

void AngleLsdemNet::write_data(FILE *fp)
{
  for (int i = 1; i <= atom->nangletypes; i++) fprintf(fp, "%d %.15g\n", i, kb[i]);
}

/* ---------------------------------------------------------------------- */

double AngleLsdemNet::single(int type, int i1, int i2, int i3)
{
  double **x = atom->x, f1[3], f3[3];
  return lsdem_net_bend_force(x[i1], x[i2], x[i3], kb[type], f1, f3);
}
