// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute ID group strain/lsdem cutoff Rc [strain small|green] [maxneigh N]
   (doc/compute_strain_lsdem.rst). Per-atom array, for each grain of the group: the local
   strain of its neighbourhood (core lsdem_local_strain_fit, Falk & Langer 1998; report
   §3.5.3): xx yy zz xy xz yz, volumetric, von Mises shear, D2min, continuum rotation angle,
   the grain's rotation relative to it (radians), number of neighbours.

   The reference is the configuration at the compute's first invocation: each grain's
   quaternion and, for its group neighbours within Rc (centre to centre), their tags and
   vectors d0 = x_j - x_i (from an occasional full neighbour list, so periodic images are
   the list's). They sit in a fix STORE row, so they migrate with the grain and survive a
   restart, and no rank needs a neighbour's reference position. Later the neighbours are
   found by tag (atom->map, nearest image) among the owned and ghost atoms.
------------------------------------------------------------------------- */

#include "compute_strain_lsdem.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "pair.h"
#include "update.h"

#include <algorithm>
#include <cstring>

using namespace LAMMPS_NS;

static constexpr int NCOLS = 12;
// a store row: reference quaternion, neighbour count, maxneigh tags, maxneigh d0 vectors
static constexpr int REF_QUAT = 0, REF_COUNT = 4, REF_TAGS = 5;
static constexpr int DEFAULT_MAXNEIGH = 32;

/* ---------------------------------------------------------------------- */

ComputeStrainLsdem::ComputeStrainLsdem(LAMMPS *lmp, int narg, char **arg) :
  Compute(lmp, narg, arg), cutoff(0.0), kind(LSDEM_STRAIN_GREEN), maxneigh(DEFAULT_MAXNEIGH),
  id_fix(nullptr), fix(nullptr), have_reference(false), avec(nullptr), list(nullptr), nmax(0),
  out(nullptr), dnow(nullptr)
{
  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  if (!avec) error->all(FLERR, "Compute strain/lsdem requires atom_style lsdem");
  for (int iarg = 3; iarg < narg; iarg += 2) {
    if (iarg + 1 >= narg) error->all(FLERR, "Compute strain/lsdem: {} needs a value", arg[iarg]);
    if (strcmp(arg[iarg], "cutoff") == 0) {
      cutoff = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    } else if (strcmp(arg[iarg], "strain") == 0) {
      if (strcmp(arg[iarg + 1], "small") == 0) kind = LSDEM_STRAIN_SMALL;
      else if (strcmp(arg[iarg + 1], "green") == 0) kind = LSDEM_STRAIN_GREEN;
      else error->all(FLERR, "Compute strain/lsdem: strain {}: expected small or green",
                      arg[iarg + 1]);
    } else if (strcmp(arg[iarg], "maxneigh") == 0) {
      maxneigh = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (maxneigh < 3) error->all(FLERR, "Compute strain/lsdem: maxneigh {} < 3", maxneigh);
    } else {
      error->all(FLERR, "Compute strain/lsdem: unknown keyword {}", arg[iarg]);
    }
  }
  if (!(cutoff > 0.0)) error->all(FLERR, "Compute strain/lsdem needs cutoff Rc > 0");

  peratom_flag = 1;
  size_peratom_cols = NCOLS;
  memory->create(dnow, 3 * maxneigh, "strain/lsdem:dnow");

  id_fix = utils::strdup(id + std::string("_COMPUTE_STORE"));
  fix = LsdemCompat::add_peratom_store(modify, id_fix, group->names[igroup],
                                       REF_TAGS + 4 * maxneigh);
  have_reference = fix->restart_reset;
  fix->restart_reset = 0;
}

/* ---------------------------------------------------------------------- */

ComputeStrainLsdem::~ComputeStrainLsdem()
{
  if (modify->nfix) modify->delete_fix(id_fix);
  delete[] id_fix;
  memory->destroy(out);
  memory->destroy(dnow);
}

/* ---------------------------------------------------------------------- */

void ComputeStrainLsdem::init()
{
  fix = LsdemCompat::find_peratom_store(modify, id_fix);
  if (!fix) error->all(FLERR, "Could not find compute strain/lsdem fix {}", id_fix);
  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  if (atom->map_style == Atom::MAP_NONE)
    error->all(FLERR, "Compute strain/lsdem needs an atom map (atom_modify map array)");
  for (int k = 0; k < 3; k++)
    if (domain->periodicity[k] && 2.0 * cutoff >= domain->prd[k])
      error->all(FLERR, "Compute strain/lsdem: cutoff {} is not below half the periodic box "
                 "length {}", cutoff, domain->prd[k]);
  // the neighbourhood and its ghosts: the list's cutoff as LAMMPS's own lists (plus skin)
  const double cutlist = cutoff + neighbor->skin;
  const double cutghost = force->pair ? std::max(force->pair->cutforce + neighbor->skin,
                                                 comm->cutghostuser)
                                      : comm->cutghostuser;
  if (cutlist > cutghost)
    error->all(FLERR, "Compute strain/lsdem: cutoff plus skin {} exceeds the ghost atom range "
               "{}: raise it with comm_modify cutoff", cutlist, cutghost);
  LsdemCompat::request_occasional_full_list(neighbor, this, instance_me, cutlist);
}

/* ---------------------------------------------------------------------- */

void ComputeStrainLsdem::init_list(int /*id*/, NeighList *ptr)
{
  list = ptr;
}

/* ----------------------------------------------------------------------
   the reference of every owned grain of the group: quaternion, then its group neighbours
   within cutoff: count, tags, vectors d0 (world frame, the list's image)
------------------------------------------------------------------------- */

void ComputeStrainLsdem::store_reference()
{
  neighbor->build_one(list);
  double **x = atom->x;
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  const double cutsq = cutoff * cutoff;
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    if (!(mask[i] & groupbit)) continue;
    double *ref = fix->astore[i];
    std::copy(avec->quat[i], avec->quat[i] + 4, ref + REF_QUAT);
    double *d0 = ref + REF_TAGS + maxneigh;
    int n = 0;
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = list->firstneigh[i][jj] & NEIGHMASK;
      double d[3];
      lsdem_sub3(x[j], x[i], d);
      if (!(mask[j] & groupbit) || lsdem_dot3(d, d) >= cutsq) continue;
      if (n == maxneigh)
        error->one(FLERR, "Compute strain/lsdem: grain {} has more than maxneigh {} neighbours "
                   "within cutoff {}", tag[i], maxneigh, cutoff);
      ref[REF_TAGS + n] = (double) tag[j];
      std::copy(d, d + 3, d0 + 3 * n);
      n++;
    }
    ref[REF_COUNT] = n;
  }
  have_reference = true;
}

/* ----------------------------------------------------------------------
   grain i's neighbour vectors now, in the reference's order, into dnow; their count
------------------------------------------------------------------------- */

int ComputeStrainLsdem::gather_neighbours(int i, const double *ref)
{
  double **x = atom->x;
  const int n = (int) ref[REF_COUNT];
  for (int k = 0; k < n; k++) {
    const tagint tj = (tagint) ref[REF_TAGS + k];
    const int j = domain->closest_image(i, atom->map(tj));
    if (j < 0)
      error->one(FLERR, "Compute strain/lsdem: neighbour {} of grain {} is beyond the ghost "
                 "atom range: raise it with comm_modify cutoff", tj, atom->tag[i]);
    lsdem_sub3(x[j], x[i], dnow + 3 * k);
  }
  return n;
}

/* ---------------------------------------------------------------------- */

void ComputeStrainLsdem::write_grain(int i, const double *ref, int n)
{
  lsdem_local_strain s;
  lsdem_local_strain_fit(n, ref + REF_TAGS + maxneigh, dnow, kind, &s);  // singular: NaN
  double *o = out[i];
  lsdem_sym_to_voigt(s.strain, o);
  o[6] = s.volumetric;
  o[7] = s.shear;
  o[8] = s.d2min;
  o[9] = s.angle;
  o[10] = lsdem_rotation_from_continuum(avec->quat[i], ref + REF_QUAT, s.rotation);
  o[11] = n;
}

/* ---------------------------------------------------------------------- */

void ComputeStrainLsdem::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  if (atom->nmax > nmax) {
    memory->destroy(out);
    nmax = atom->nmax;
    memory->create(out, nmax, NCOLS, "strain/lsdem:out");
    array_atom = out;
  }
  if (!have_reference) store_reference();
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    if (mask[i] & groupbit) write_grain(i, fix->astore[i], gather_neighbours(i, fix->astore[i]));
    else std::fill(out[i], out[i] + NCOLS, 0.0);
  }
}

/* ---------------------------------------------------------------------- */

double ComputeStrainLsdem::memory_usage()
{
  return (double) nmax * NCOLS * sizeof(double) + 3.0 * maxneigh * sizeof(double);
}
