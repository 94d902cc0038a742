// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: the shear springs of analytic spheres' pairs (internal fix).
   See fix_lsdem_sphere_shear.h.
------------------------------------------------------------------------- */

#include "fix_lsdem_sphere_shear.h"

#include "atom.h"
#include "error.h"
#include "fix_lsdem_history.h"
#include "memory.h"

#include <algorithm>
#include <cstring>

using namespace LAMMPS_NS;

// doubles per packed spring: partner, stamp, shear[3], normal[3]
static constexpr int SPRING_DOUBLES = 8;

/* ---------------------------------------------------------------------- */

FixLsdemSphereShear::FixLsdemSphereShear(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), nmax_atom(0), rows(0), cap(0), nslot(nullptr), partner(nullptr),
  slot(nullptr)
{
  if (narg != 3) error->all(FLERR, "Illegal fix LSDEM_SPHERE_SHEAR command (internal fix)");
  restart_peratom = 1;
  create_attribute = 1;
  maxexchange_dynamic = 1;
  maxexchange = 1;
  FixLsdemSphereShear::grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
}

FixLsdemSphereShear::~FixLsdemSphereShear()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(nslot);
  memory->sfree(partner);
  memory->sfree(slot);
}

/* ----------------------------------------------------------------------
   per-atom arrays: nslot for nmax atoms (owned and ghosts); the slots, cap per atom, only
   for the rows of owned spheres that keep some (ensure_rows), never for ghosts
------------------------------------------------------------------------- */

void FixLsdemSphereShear::grow_arrays(int nmax)
{
  if (nmax <= nmax_atom) return;
  memory->grow(nslot, nmax, "lsdem/sphere_shear:nslot");
  for (int i = nmax_atom; i < nmax; i++) nslot[i] = 0;
  nmax_atom = nmax;
}

void FixLsdemSphereShear::realloc_slots(int new_rows, int new_cap)
{
  partner = (tagint *) memory->srealloc(partner, sizeof(tagint) * std::max(new_rows * new_cap, 1),
                                        "lsdem/sphere_shear:partner");
  slot = (lsdem_shear_hist *) memory->srealloc(slot, sizeof(lsdem_shear_hist) *
                                               std::max(new_rows * new_cap, 1),
                                               "lsdem/sphere_shear:slot");
}

/* rows for atoms 0..n-1 */
void FixLsdemSphereShear::ensure_rows(int n)
{
  if (n <= rows) return;
  rows = std::max(n, rows + rows / 4);
  realloc_slots(rows, cap);
}

/* more slots per atom: each atom's run moves to its place at the new stride (from the last
   atom down, so that no run is overwritten before it moves) */
void FixLsdemSphereShear::grow_cap(int need)
{
  if (need <= cap) return;
  const int old = cap;
  cap = std::max(need, cap + cap / 2);
  realloc_slots(rows, cap);
  for (int i = rows - 1; i > 0; i--) {
    if (i >= nmax_atom || nslot[i] == 0) continue;
    memmove(partner + (bigint) i * cap, partner + (bigint) i * old, sizeof(tagint) * nslot[i]);
    memmove(slot + (bigint) i * cap, slot + (bigint) i * old, sizeof(lsdem_shear_hist) * nslot[i]);
  }
  note_exchange_size();
}

void FixLsdemSphereShear::note_exchange_size()
{
  maxexchange = 1 + SPRING_DOUBLES * cap;
}

/* ----------------------------------------------------------------------
   the slots of sphere i := one per partner, in the given order, each with the spring i
   held for that partner (or none)
------------------------------------------------------------------------- */

void FixLsdemSphereShear::assign(int i, const tagint *partners, int n)
{
  ensure_rows(i + 1);
  const int had = nslot[i];
  old_partner.assign(partner + (bigint) i * cap, partner + (bigint) i * cap + had);
  old_slot.assign(slots(i), slots(i) + had);
  grow_cap(n);
  tagint *p = partner + (bigint) i * cap;
  lsdem_shear_hist *s = slots(i);
  for (int k = 0; k < n; k++) {
    p[k] = partners[k];
    drop(s[k]);
    for (int o = 0; o < had; o++)  // a few partners: a scan
      if (old_partner[o] == partners[k] && held(old_slot[o])) {
        s[k] = old_slot[o];
        break;
      }
  }
  nslot[i] = n;
}

/* ----------------------------------------------------------------------
   slots of sphere i without a spring take the one history holds for their partner (the
   kernel's one entry, node 0), where a restart file of an earlier version left it
------------------------------------------------------------------------- */

void FixLsdemSphereShear::take_over(int i, const FixLsdemHistory *history)
{
  if (!history || !history->holds(i)) return;
  lsdem_shear_hist *s = slots(i);
  for (int k = 0; k < nslot[i]; k++) {
    lsdem_pair_state in;
    if (!held(s[k]) && history->find(i, partner[(bigint) i * cap + k], in) && in.nshear > 0 &&
        in.shear[0].node == 0)
      s[k] = in.shear[0];
  }
}

void FixLsdemSphereShear::drop_all()
{
  for (int i = 0; i < atom->nlocal; i++)
    for (int k = 0; k < nslot[i]; k++) drop(slot[(bigint) i * cap + k]);
}

/* ---------------------------------------------------------------------- */

int FixLsdemSphereShear::count_held(int i) const
{
  int n = 0;
  for (int k = 0; k < nslot[i]; k++) n += held(slot[(bigint) i * cap + k]);
  return n;
}

double FixLsdemSphereShear::springs_held() const
{
  double n = 0.0;
  for (int i = 0; i < atom->nlocal; i++) n += count_held(i);
  return n;
}

/* ---------------------------------------------------------------------- */

void FixLsdemSphereShear::copy_arrays(int i, int j, int /*delflag*/)
{
  nslot[j] = nslot[i];
  if (nslot[i] == 0) return;
  ensure_rows(j + 1);
  memcpy(partner + (bigint) j * cap, partner + (bigint) i * cap, sizeof(tagint) * nslot[i]);
  memcpy(slots(j), slots(i), sizeof(lsdem_shear_hist) * nslot[i]);
}

void FixLsdemSphereShear::set_arrays(int i)
{
  nslot[i] = 0;
}

/* ----------------------------------------------------------------------
   count, then per held spring: partner, stamp, shear[3], normal[3]
------------------------------------------------------------------------- */

int FixLsdemSphereShear::pack_held(int i, double *buf) const
{
  int m = 0;
  buf[m++] = ubuf(count_held(i)).d;
  for (int k = 0; k < nslot[i]; k++) {
    const lsdem_shear_hist &h = slot[(bigint) i * cap + k];
    if (!held(h)) continue;
    buf[m++] = ubuf(partner[(bigint) i * cap + k]).d;
    buf[m++] = ubuf((int64_t) h.stamp).d;
    for (int d = 0; d < 3; d++) buf[m++] = h.shear[d];
    for (int d = 0; d < 3; d++) buf[m++] = h.normal[d];
  }
  return m;
}

/* the springs become atom i's slots (the next neighbour-list build assigns them) */
int FixLsdemSphereShear::unpack_held(int i, const double *buf)
{
  const int n = (int) ubuf(buf[0]).i;
  nslot[i] = 0;
  if (n == 0) return 1;
  ensure_rows(i + 1);
  grow_cap(n);
  int m = 1;
  for (int k = 0; k < n; k++) {
    lsdem_shear_hist &h = slots(i)[k];
    partner[(bigint) i * cap + k] = (tagint) ubuf(buf[m++]).i;
    h.node = 0;
    h.stamp = lsdem_shear_stamp((int64_t) ubuf(buf[m++]).i);
    for (int d = 0; d < 3; d++) h.shear[d] = buf[m++];
    for (int d = 0; d < 3; d++) h.normal[d] = buf[m++];
  }
  nslot[i] = n;
  return m;
}

int FixLsdemSphereShear::pack_exchange(int i, double *buf)
{
  return pack_held(i, buf);
}

int FixLsdemSphereShear::unpack_exchange(int nlocal, double *buf)
{
  return unpack_held(nlocal, buf);
}

/* ----------------------------------------------------------------------
   restart: buf[0] = total size, as every per-atom restart fix packs it
------------------------------------------------------------------------- */

int FixLsdemSphereShear::pack_restart(int i, double *buf)
{
  const int m = 1 + pack_held(i, buf + 1);
  buf[0] = m;
  return m;
}

void FixLsdemSphereShear::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int k = 0; k < nth; k++) m += static_cast<int>(extra[nlocal][m]);
  unpack_held(nlocal, &extra[nlocal][m + 1]);
}

int FixLsdemSphereShear::size_restart(int nlocal)
{
  return 2 + SPRING_DOUBLES * count_held(nlocal);
}

int FixLsdemSphereShear::maxsize_restart()
{
  int mine = 0, all = 0;
  for (int i = 0; i < atom->nlocal; i++) mine = std::max(mine, count_held(i));
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MAX, world);
  return 2 + SPRING_DOUBLES * all;
}

/* ---------------------------------------------------------------------- */

double FixLsdemSphereShear::memory_usage()
{
  return (double) nmax_atom * sizeof(int) +
         (double) rows * cap * (sizeof(tagint) + sizeof(lsdem_shear_hist)) +
         (double) old_slot.capacity() * sizeof(lsdem_shear_hist) +
         (double) old_partner.capacity() * sizeof(tagint);
}
