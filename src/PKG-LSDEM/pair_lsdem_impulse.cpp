// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   pair_style lsdem/impulse (doc/pair_lsdem_impulse.rst): detection only. Everything but
   the force is pair_style lsdem's (neighbor list, poses, master pairs, node lists through
   the shared contact path); the manifolds are kept for fix impulse/lsdem.
------------------------------------------------------------------------- */

#include "pair_lsdem_impulse.h"

#include "atom.h"
#include "error.h"
#include "memory.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cstring>
#include <mpi.h>

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

PairLsdemImpulse::PairLsdemImpulse(LAMMPS *lmp) : PairLsdem(lmp), touch_step(-1), seconds(0.0),
  t_start(0.0), sleeping(nullptr)
{
  comm_forward = comm_reverse = 0;
}

/* ----------------------------------------------------------------------
   pair_style lsdem/impulse [stride N] [nodelist auto|off|skin]
------------------------------------------------------------------------- */

void PairLsdemImpulse::settings(int narg, char **arg)
{
  mode = LSDEM_ROLES_ONEWAY;
  global = LsdemContactOptions();
  zcap = 0;
  for (int iarg = 0; iarg < narg; iarg += 2) {
    if (iarg + 1 >= narg)
      error->all(FLERR, "pair_style lsdem/impulse: keyword {} needs a value", arg[iarg]);
    if (!global.read_keyword(lmp, "pair_style lsdem/impulse", arg[iarg], arg[iarg + 1],
                             LsdemContactOptions::DETECT))
      error->all(FLERR, "pair_style lsdem/impulse: unknown keyword {} (allowed: stride, "
                 "nodelist; restitution and friction belong to fix impulse/lsdem)", arg[iarg]);
  }
}

/* ----------------------------------------------------------------------
   pair_coeff I J: the type pair touches (no law: fix impulse/lsdem has it)
------------------------------------------------------------------------- */

void PairLsdemImpulse::coeff(int narg, char **arg)
{
  if (narg != 2)
    error->all(FLERR, "pair_coeff for lsdem/impulse: expected I J and nothing else (the "
               "impulse law's restitution and friction are fix impulse/lsdem keywords)");
  if (!allocated) allocate();
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  int count = 0;
  for (int i = ilo; i <= ihi; i++)
    for (int j = std::max(jlo, i); j <= jhi; j++) {
      memset(&params[i][j], 0, sizeof(lsdem_contact_params));
      setflag[i][j] = 1;
      count++;
    }
  if (count == 0) error->all(FLERR, "Incorrect args for pair coefficients");
}

/* ----------------------------------------------------------------------
   every master pair whose bounding spheres overlap: its manifold, no force
------------------------------------------------------------------------- */

void PairLsdemImpulse::compute(int eflag, int vflag)
{
  begin_detection(eflag, vflag, 1);
  detect_range(0, 0, list->inum);
  end_detection();
}

/* a force call's start: poses, master pairs, n lanes emptied */

void PairLsdemImpulse::begin_detection(int eflag, int vflag, int n)
{
  t_start = MPI_Wtime();
  ev_init(eflag, vflag);
  begin_force_call(n);
  update_poses(0, atom->nlocal + atom->nghost);
  if ((int) found.size() < n) found.resize(n);
  for (int l = 0; l < n; l++) {
    found[l].touch.clear();
    found[l].points.clear();
  }
  touch_step = update->ntimestep;
  if (neighbor->ago == 0 || !master_built) build_master_pairs();
}

/* the master pairs of the neighbor list's grains iifrom..iito-1, into lane l (a thread's) */

void PairLsdemImpulse::detect_range(int l, int iifrom, int iito)
{
  const int *ilist = list->ilist;
  Lane &lane = *lanes[l];
  LsdemContactPath &path = lane.path;
  Found &out = found[l];
  for (int ii = iifrom; ii < iito; ii++) {
    const int i = ilist[ii];
    path.begin_atom();
    const int *js = master_j + master_first[i];
    for (int k = 0; k < master_num[i]; k++) {
      const int j = js[k];
      if (!bounding_spheres_overlap(i, j) ||
          (sleeping && sleeping[i] != 0.0 && sleeping[j] != 0.0))
        continue;
      const lsdem_contact_params &p = params[atom->type[i]][atom->type[j]];
      const int npen = path.detect(i, atom->tag[j], shape[i], pose[i], shape[j], pose[j],
                                   p.detect, touch_step);
      lane.ntested_pairs++;  // the workload, as pair_style lsdem counts it (compute pair)
      lane.ntested_nodes += path.manifold().ntested;
      lane.npen_nodes += npen;
      if (npen > 0) keep(out, i, j, path.manifold());
    }
    path.end_atom(i);
  }
}

/* the lanes' manifolds one after the other (lanes hold consecutive runs of the neighbor
   list: the serial order, whatever the thread count) */

void PairLsdemImpulse::end_detection()
{
  end_force_call();
  if (nlanes == 1) {
    touch.swap(found[0].touch);
    points.swap(found[0].points);
  } else {
    touch.clear();
    points.clear();
    for (int l = 0; l < nlanes; l++) {
      const int offset = (int) points.size();
      for (Touch t : found[l].touch) {
        t.first += offset;
        touch.push_back(t);
      }
      points.insert(points.end(), found[l].points.begin(), found[l].points.end());
    }
  }
  if (eflag_global) tally_workload((double) touch.size());  // compute pair reads it then
  seconds += MPI_Wtime() - t_start;
}

/* ---------------------------------------------------------------------- */

void PairLsdemImpulse::keep(Found &out, int i, int j, const lsdem_manifold &m)
{
  Touch t;
  t.i = i;
  t.j = j;
  t.first = (int) out.points.size();
  t.n = m.n;
  t.stride = m.stride;
  for (int d = 0; d < 3; d++) {
    t.xa[d] = m.xa[d];
    t.dab[d] = m.dab[d];
  }
  out.touch.push_back(t);
  out.points.insert(out.points.end(), m.point, m.point + m.n);
}

/* ---------------------------------------------------------------------- */

lsdem_manifold PairLsdemImpulse::manifold(int k)
{
  const Touch &t = touch[k];
  lsdem_manifold m = lsdem_manifold_over(points.data() + t.first, t.n);
  m.n = t.n;
  m.stride = t.stride;
  for (int d = 0; d < 3; d++) {
    m.xa[d] = t.xa[d];
    m.dab[d] = t.dab[d];
  }
  m.ntested = 0;
  return m;
}

/* ---------------------------------------------------------------------- */

double PairLsdemImpulse::memory_usage()
{
  double bytes = PairLsdem::memory_usage() + (double) touch.capacity() * sizeof(Touch) +
      (double) points.capacity() * sizeof(lsdem_contact_point);
  for (const Found &f : found)
    bytes += (double) f.touch.capacity() * sizeof(Touch) +
        (double) f.points.capacity() * sizeof(lsdem_contact_point);
  return bytes;
}
