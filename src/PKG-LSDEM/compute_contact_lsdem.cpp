// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute contact/lsdem (doc/compute_contact_lsdem.rst). Reads the contact list
   that pair_style lsdem keeps from its last force call; computes nothing physical.
------------------------------------------------------------------------- */

#include "compute_contact_lsdem.h"

#include "atom.h"
#include "error.h"
#include "fix_wall_lsdem.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "pair_lsdem.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;

// local columns: id_i id_j px py pz fx fy fz npen
static constexpr int NCOLS = 9;

/* ---------------------------------------------------------------------- */

ComputeContactLsdem::ComputeContactLsdem(LAMMPS *lmp, int narg, char **arg) :
  Compute(lmp, narg, arg), pair(nullptr), nmax_local(0), nmax_atom(0), alocal(nullptr),
  coord(nullptr), with_walls(true)
{
  if (narg == 5 && strcmp(arg[3], "walls") == 0 &&
      (strcmp(arg[4], "yes") == 0 || strcmp(arg[4], "no") == 0))
    with_walls = strcmp(arg[4], "yes") == 0;
  else if (narg != 3)
    error->all(FLERR, "Illegal compute contact/lsdem command: compute ID group contact/lsdem "
               "[walls yes|no]");
  local_flag = 1;
  size_local_rows = 0;
  size_local_cols = NCOLS;
  peratom_flag = 1;
  size_peratom_cols = 0;
}

/* ---------------------------------------------------------------------- */

ComputeContactLsdem::~ComputeContactLsdem()
{
  memory->destroy(alocal);
  memory->destroy(coord);
}

/* ---------------------------------------------------------------------- */

void ComputeContactLsdem::init()
{
  pair = PairLsdem::of(force);
  if (!pair) error->all(FLERR, "Compute contact/lsdem requires pair_style lsdem");
  walls.clear();
  for (int f = 0; with_walls && f < modify->nfix; f++)
    if (FixWallLsdem *w = dynamic_cast<FixWallLsdem *>(modify->fix[f])) walls.push_back(w);
}

/* ----------------------------------------------------------------------
   the pair's contact list refers to local indices of its last force call
------------------------------------------------------------------------- */

void ComputeContactLsdem::check_current()
{
  if (pair->contacts_step() != update->ntimestep)
    error->all(FLERR, "Compute contact/lsdem needs pair lsdem forces of step {} (it has {})",
               update->ntimestep, pair->contacts_step());
  for (const FixWallLsdem *w : walls)
    if (w->contacts_step() != update->ntimestep)
      error->all(FLERR, "Compute contact/lsdem needs wall forces of step {} from fix {}",
                 update->ntimestep, w->id);
}

/* ---------------------------------------------------------------------- */

bool ComputeContactLsdem::selected(int i, int j) const
{
  return (atom->mask[i] & groupbit) && (atom->mask[j] & groupbit);
}

/* ----------------------------------------------------------------------
   one row per test with penetrating nodes, for tests whose master is owned here:
   ids (master, slave), force-weighted contact point, force applied on the master
   by this test (the slave got the opposite), penetrating nodes; then one row per grain
   of the group touching a wall/lsdem fix, with the other id -(the fix's index among
   the walls + 1) and the force of the wall on the grain
------------------------------------------------------------------------- */

void ComputeContactLsdem::compute_local()
{
  invoked_local = update->ntimestep;
  check_current();
  int rows = 0;
  pair->each_contact([&](const PairLsdem::Contact &c) {
    if (selected(c.i, c.j)) rows++;
  });
  for (const FixWallLsdem *w : walls)
    w->each_contact([&](const FixWallLsdem::Contact &c) {
      if (atom->mask[c.i] & groupbit) rows++;
    });
  if (rows > nmax_local) {
    nmax_local = rows;
    memory->destroy(alocal);
    memory->create(alocal, nmax_local, NCOLS, "contact/lsdem:alocal");
  }
  array_local = alocal;
  size_local_rows = rows;

  int m = 0;
  pair->each_contact([&](const PairLsdem::Contact &c) {
    if (!selected(c.i, c.j)) return;
    double *row = alocal[m++];
    row[0] = (double) atom->tag[c.i];
    row[1] = (double) atom->tag[c.j];
    for (int d = 0; d < 3; d++) {
      row[2 + d] = c.res.point[d];
      row[5 + d] = c.scale * c.res.force[d];
    }
    row[8] = (double) c.res.npen;
  });
  for (int k = 0; k < (int) walls.size(); k++)
    walls[k]->each_contact([&](const FixWallLsdem::Contact &c) {
      if (!(atom->mask[c.i] & groupbit)) return;
      double *row = alocal[m++];
      row[0] = (double) atom->tag[c.i];
      row[1] = -(double) (k + 1);
      for (int d = 0; d < 3; d++) {
        row[2 + d] = c.point[d];
        row[5 + d] = c.force[d];
      }
      row[8] = (double) c.npen;
    });
}

/* ---------------------------------------------------------------------- */

void ComputeContactLsdem::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  check_current();
  if (atom->nmax > nmax_atom) {
    nmax_atom = atom->nmax;
    memory->destroy(coord);
    memory->create(coord, nmax_atom, "contact/lsdem:coord");
    vector_atom = coord;
  }
  const double *count = pair->coordination(0);
  for (int i = 0; i < atom->nlocal; i++)
    coord[i] = (atom->mask[i] & groupbit) ? count[i] : 0.0;
}

/* ---------------------------------------------------------------------- */

double ComputeContactLsdem::memory_usage()
{
  return (double) nmax_local * NCOLS * sizeof(double) + (double) nmax_atom * sizeof(double);
}
