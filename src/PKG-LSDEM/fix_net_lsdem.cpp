// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix ID group-ID net/lsdem FILE clamp CLAMP-GROUP [grains GRAIN-GROUP]

   group-ID: the net's balls (group net of lsdem-shape net's PREFIX.in). Global vector
   (doc/fix_net_lsdem.rst):
     1-3  anchors' reaction force on the net, -sum of f over the clamped balls
     4    largest strain (L - r0) / r0 of an intact bond
     5    residual height: lowest ball height over the net's initial plane (along n)
     6    bonds broken (bond type 0 among the net's bonds)
     7    grains through the net: grain centres in the footprint below the nearest ball
     8    work of the damping forces of the net's bond types, summed over ranks
     9    peak anchor force: the largest |R| (1-3) at the end of any step since the fix began
     10   grains before the net (upslope of it when its normal points upslope): in the
          footprint at or above the nearest ball, beside it on the normal's side
------------------------------------------------------------------------- */

#include "fix_net_lsdem.h"

#include "atom.h"
#include "bond.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

/* ---------------------------------------------------------------------- */

FixNetLsdem::FixNetLsdem(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), clamp_group(-1), clamp_bit(0), grain_group(-1), grain_bit(0),
    peak(0.0), out_step(-1)
{
  std::memset(&net, 0, sizeof(net));
  const char *usage = "'fix ID net net/lsdem FILE clamp CLAMP-GROUP [grains GRAIN-GROUP]'";
  if (narg < 6) error->all(FLERR, "Illegal fix net/lsdem command: expected {}", usage);
  file = arg[3];
  for (int a = 4; a < narg; a += 2) {
    if (a + 1 >= narg || (strcmp(arg[a], "clamp") != 0 && strcmp(arg[a], "grains") != 0))
      error->all(FLERR, "Illegal fix net/lsdem command: unknown or incomplete keyword '{}'; "
                 "expected {}", arg[a], usage);
    const int g = group->find(arg[a + 1]);
    if (g < 0)
      error->all(FLERR, "fix net/lsdem: {} group '{}' does not exist (PREFIX.in of "
                 "lsdem-shape net defines net, net_free, net_clamp and grains)", arg[a],
                 arg[a + 1]);
    if (strcmp(arg[a], "clamp") == 0) clamp_group = g;
    else grain_group = g;
  }
  if (clamp_group < 0) error->all(FLERR, "fix net/lsdem: the clamp keyword is required: {}", usage);
  clamp_bit = group->bitmask[clamp_group];
  grain_bit = grain_group >= 0 ? group->bitmask[grain_group] : 0;

  lsdem_error err;
  if (lsdem_net_read(file.c_str(), &net, &err) != LSDEM_OK)
    error->all(FLERR, "fix net/lsdem: {}", err.msg);
  for (int b = 0; b < net.nballs; b++) index[(tagint) net.id[b]] = b;
  xball.resize(3 * (size_t) net.nballs);

  vector_flag = 1;
  size_vector = 10;
  global_freq = 1;
  extvector = 0;
}

/* ---------------------------------------------------------------------- */

FixNetLsdem::~FixNetLsdem()
{
  lsdem_net_free(&net);
}

/* ---------------------------------------------------------------------- */

int FixNetLsdem::setmask()
{
  return END_OF_STEP;
}

/* ----------------------------------------------------------------------
   the group and the file agree: the same number of balls, each ball an atom of the group,
   and at least one anchor
------------------------------------------------------------------------- */

void FixNetLsdem::check_balls()
{
  const bigint nclamp = group->count(clamp_group), ngroup = group->count(igroup);
  if (nclamp == 0)
    error->all(FLERR, "fix net/lsdem: clamp group '{}' is empty: the net has no anchors and "
               "would fall freely (make the net with lsdem-shape net --clamp EDGES and use its "
               "net_clamp group)", group->names[clamp_group]);
  if (ngroup != net.nballs)
    error->all(FLERR, "fix net/lsdem: group '{}' has {} atoms but net file {} lists {} balls "
               "(use the net group of the PREFIX.in written with the file)",
               group->names[igroup], ngroup, file, net.nballs);
  bigint mine = 0, found = 0;
  for (int i = 0; i < atom->nlocal; i++)
    if ((atom->mask[i] & groupbit) && index.count(atom->tag[i])) mine++;
  MPI_Allreduce(&mine, &found, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (found != net.nballs)
    error->all(FLERR, "fix net/lsdem: only {} of the {} balls of net file {} are atoms of "
               "group '{}' (was the data file written with this net file read?)", found,
               net.nballs, file, group->names[igroup]);
}

void FixNetLsdem::init()
{
  if (!force->bond || !force->bond_match("lsdem/net"))
    error->all(FLERR, "fix net/lsdem requires bond_style lsdem/net");
  check_balls();
  find_bond_types();
  out_step = -1;
}

/* the bond types among the intact bonds of the net's balls (the damping work is booked by
   type: a net made by lsdem-shape net has a bond type of its own) */
void FixNetLsdem::find_bond_types()
{
  std::vector<int> mine(atom->nbondtypes + 1, 0);
  net_types.assign(atom->nbondtypes + 1, 0);
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit)
      for (int m = 0; m < atom->num_bond[i]; m++)
        if (atom->bond_type[i][m] > 0) mine[atom->bond_type[i][m]] = 1;
  MPI_Allreduce(mine.data(), net_types.data(), (int) mine.size(), MPI_INT, MPI_MAX, world);
}

/* the peak anchor force, at the start of a run and after every step */
void FixNetLsdem::setup(int /*vflag*/)
{
  end_of_step();
}

void FixNetLsdem::end_of_step()
{
  double r[3];
  anchor_reaction(r);
  peak = std::max(peak, std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]));
}

/* ----------------------------------------------------------------------
   -sum f over the clamped balls; each term rounded to a quantum of the largest, so the
   sum over ranks is the same in any order
------------------------------------------------------------------------- */

void FixNetLsdem::anchor_reaction(double *r)
{
  double **f = atom->f;
  const int *mask = atom->mask;
  double big = 0.0, scale = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & clamp_bit)
      for (int d = 0; d < 3; d++) big = std::max(big, std::fabs(f[i][d]));
  MPI_Allreduce(&big, &scale, 1, MPI_DOUBLE, MPI_MAX, world);
  const lsdem_quantum q = lsdem_quantum_for(scale);
  double mine[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & clamp_bit)
      for (int d = 0; d < 3; d++) mine[d] -= lsdem_quantize(f[i][d], q);
  MPI_Allreduce(mine, r, 3, MPI_DOUBLE, MPI_SUM, world);
}

/* the largest (L - r0) / r0 over this rank's intact bonds of the net, over all ranks */
double FixNetLsdem::largest_strain()
{
  int dim;
  const double *r0 = (const double *) force->bond->extract("r0", dim);
  double **x = atom->x;
  int **bondlist = neighbor->bondlist;
  double mine = -DBL_MAX, all;
  for (int n = 0; n < neighbor->nbondlist; n++) {
    const int i1 = bondlist[n][0], i2 = bondlist[n][1], type = bondlist[n][2];
    if (type <= 0 || !(atom->mask[i1] & groupbit)) continue;
    const double d[3] = {x[i2][0] - x[i1][0], x[i2][1] - x[i1][1], x[i2][2] - x[i1][2]};
    mine = std::max(mine, (std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) - r0[type]) /
                              r0[type]);
  }
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_MAX, world);
  return all == -DBL_MAX ? 0.0 : all;
}

/* every ball's position into xball (file order; each slot set by its owner alone, so the
   sum over ranks is exact) and the lowest height over the initial plane */
double FixNetLsdem::lowest_height()
{
  std::vector<double> mine(xball.size(), 0.0);
  double low = DBL_MAX, all;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const int b = index.at(atom->tag[i]);
    for (int d = 0; d < 3; d++) mine[3 * b + d] = atom->x[i][d];
    double uv[2];
    low = std::min(low, lsdem_net_height(&net, atom->x[i], uv));
  }
  MPI_Allreduce(mine.data(), xball.data(), (int) xball.size(), MPI_DOUBLE, MPI_SUM, world);
  MPI_Allreduce(&low, &all, 1, MPI_DOUBLE, MPI_MIN, world);
  return all;
}

/* the net's bonds of type 0 (broken), each once (twice stored when newton_bond is off) */
double FixNetLsdem::bonds_broken()
{
  bigint mine = 0, all;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit)
      for (int m = 0; m < atom->num_bond[i]; m++) mine += atom->bond_type[i][m] <= 0;
  MPI_Allreduce(&mine, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  return force->newton_bond ? (double) all : 0.5 * (double) all;
}

/* grain centres through the net and before it (lsdem_net_side); needs xball of this
   step. Cost: grains over the footprint x balls. */
void FixNetLsdem::grain_sides(double *through, double *before)
{
  bigint mine[2] = {0, 0}, all[2] = {0, 0};
  if (grain_group >= 0)
    for (int i = 0; i < atom->nlocal; i++) {
      if (!(atom->mask[i] & grain_bit)) continue;
      const int side = lsdem_net_side(&net, xball.data(), atom->x[i]);
      mine[0] += side == LSDEM_NET_THROUGH;
      mine[1] += side == LSDEM_NET_BEFORE;
    }
  MPI_Allreduce(mine, all, 2, MPI_LMP_BIGINT, MPI_SUM, world);
  *through = (double) all[0];
  *before = (double) all[1];
}

/* the bond style's work of the damping forces of the net's bond types, this rank's part
   summed over ranks (in rank order: the same to round-off, not to the bit, on another rank
   count) */
double FixNetLsdem::damping_work()
{
  int dim;
  const double *work = (const double *) force->bond->extract("damping_work", dim);
  double mine = 0.0, all = 0.0;
  for (int t = 1; t < (int) net_types.size(); t++)
    if (net_types[t]) mine += work[t];
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_SUM, world);
  return all;
}

/* ---------------------------------------------------------------------- */

void FixNetLsdem::compute_outputs()
{
  anchor_reaction(out);
  out[3] = largest_strain();
  out[4] = lowest_height();
  out[5] = bonds_broken();
  grain_sides(&out[6], &out[9]);
  out[7] = damping_work();
  out[8] = peak;
  out_step = update->ntimestep;
}

double FixNetLsdem::compute_vector(int n)
{
  if (out_step != update->ntimestep) compute_outputs();
  return out[n];
}
