// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: per-node tangential contact history (internal fix).
   See fix_lsdem_history.h for the usage pattern.
------------------------------------------------------------------------- */

#include "fix_lsdem_history.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "memory.h"

#include <algorithm>
#include <cstring>

using namespace LAMMPS_NS;

// doubles per packed entry: partner, node and pad_ (pad_ << 32 | node: the node lists'
// entries use pad_), stamp, shear[3], normal[3]
static constexpr int ENTRY_DOUBLES = 9;

static int64_t pack_node(const lsdem_node_hist &h)
{
  return (int64_t) (((uint64_t) (uint32_t) h.pad_ << 32) | (uint32_t) h.node);
}

static void unpack_node(int64_t v, lsdem_node_hist &h)
{
  h.node = (int32_t) (uint32_t) ((uint64_t) v & 0xffffffffu);
  h.pad_ = (int32_t) (uint32_t) ((uint64_t) v >> 32);
}

/* ---------------------------------------------------------------------- */

FixLsdemHistory::FixLsdemHistory(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), nmax_atom(0), nhist(nullptr), maxhist(nullptr), hist(nullptr),
  nslice(nullptr), maxslice(nullptr), slice(nullptr), maxcount(0), scratch(nullptr),
  nscratch(0), maxscratch(0), slices(nullptr), nslices(0), maxslices(0)
{
  if (narg != 3) error->all(FLERR, "Illegal fix LSDEM_HISTORY command (internal fix)");

  restart_peratom = 1;
  create_attribute = 1;
  maxexchange_dynamic = 1;
  maxexchange = 1;

  FixLsdemHistory::grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
}

/* ---------------------------------------------------------------------- */

FixLsdemHistory::~FixLsdemHistory()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  for (int i = 0; i < nmax_atom; i++) {
    memory->sfree(slice[i]);
    memory->sfree(hist[i]);
  }
  memory->sfree(slice);
  memory->sfree(hist);
  memory->destroy(nhist);
  memory->destroy(maxhist);
  memory->destroy(nslice);
  memory->destroy(maxslice);
  memory->sfree(scratch);
  memory->sfree(slices);
}

/* ---------------------------------------------------------------------- */

int FixLsdemHistory::setmask()
{
  return 0;
}

/* ----------------------------------------------------------------------
   slice of atom i's list against one partner (sorted by node), n entries
------------------------------------------------------------------------- */

const lsdem_node_hist *FixLsdemHistory::find(int i, tagint ptag, int &n) const
{
  const Slice *s = slice[i];
  for (int k = 0; k < nslice[i]; k++)  // a few partners: a scan beats a binary search
    if (s[k].partner == ptag) {
      n = s[k].n;
      return hist[i] + s[k].start;
    }
  n = 0;
  return nullptr;
}

/* ----------------------------------------------------------------------
   the lists are touched once per step, so they are out of cache when an atom's
   turn comes: the styles ask for the next atom's list while they work on one
------------------------------------------------------------------------- */

void FixLsdemHistory::prefetch(int i) const
{
  static constexpr int LINES = 64;  // up to 4 KB: a grain's usual list
  const int n = std::min(nhist[i], LINES * 64 / (int) sizeof(lsdem_node_hist));
  __builtin_prefetch(slice[i]);
  for (int k = 0; k < n; k++) __builtin_prefetch(&hist[i][k]);
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::begin_atom()
{
  nscratch = 0;
  nslices = 0;
}

/* ----------------------------------------------------------------------
   room for cap new entries after the committed ones
------------------------------------------------------------------------- */

lsdem_node_hist *FixLsdemHistory::reserve(int cap)
{
  if (nscratch + cap > maxscratch) {
    maxscratch = std::max(2 * maxscratch, nscratch + cap);
    scratch = (lsdem_node_hist *) memory->srealloc(scratch, sizeof(lsdem_node_hist) * maxscratch,
                                                   "lsdem/history:scratch");
  }
  return scratch + nscratch;
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::commit(tagint ptag, int n)
{
  if (n <= 0) return;
  if (nslices == maxslices) {
    maxslices = std::max(16, 2 * maxslices);
    slices = (Slice *) memory->srealloc(slices, sizeof(Slice) * maxslices, "lsdem/history:slices");
  }
  slices[nslices].partner = ptag;
  slices[nslices].start = nscratch;
  slices[nslices].n = n;
  nslices++;
  nscratch += n;
}

/* ----------------------------------------------------------------------
   replace atom i's list by the committed slices, ordered by partner tag
   (each slice is already sorted by node: the kernel writes it that way)
------------------------------------------------------------------------- */

void FixLsdemHistory::end_atom(int i)
{
  // few partners per grain: insertion sort of the slice headers
  for (int a = 1; a < nslices; a++) {
    Slice s = slices[a];
    int b = a - 1;
    while (b >= 0 && slices[b].partner > s.partner) {
      slices[b + 1] = slices[b];
      b--;
    }
    slices[b + 1] = s;
  }
  ensure_capacity(i, nscratch, nslices);
  int m = 0;
  for (int s = 0; s < nslices; s++) {
    memcpy(hist[i] + m, scratch + slices[s].start, sizeof(lsdem_node_hist) * slices[s].n);
    slice[i][s] = {slices[s].partner, m, slices[s].n};
    m += slices[s].n;
  }
  nhist[i] = m;
  nslice[i] = nslices;
  note_count(m);
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::ensure_capacity(int i, int n, int ns)
{
  if (n > maxhist[i]) {
    maxhist[i] = std::max(n, 2 * maxhist[i]);
    hist[i] = (lsdem_node_hist *) memory->srealloc(hist[i], sizeof(lsdem_node_hist) * maxhist[i],
                                                   "lsdem/history:hist");
  }
  if (ns > maxslice[i]) {
    maxslice[i] = std::max(ns, 2 * maxslice[i]);
    slice[i] = (Slice *) memory->srealloc(slice[i], sizeof(Slice) * maxslice[i],
                                          "lsdem/history:slice");
  }
}

/* ----------------------------------------------------------------------
   the exchange buffer must hold the largest list; it only ever grows
------------------------------------------------------------------------- */

void FixLsdemHistory::note_count(int n)
{
  if (n <= maxcount) return;
  maxcount = n;
  maxexchange = 1 + ENTRY_DOUBLES * maxcount;
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::grow_arrays(int nmax)
{
  if (nmax <= nmax_atom) return;
  memory->grow(nhist, nmax, "lsdem/history:nhist");
  memory->grow(maxhist, nmax, "lsdem/history:maxhist");
  memory->grow(nslice, nmax, "lsdem/history:nslice");
  memory->grow(maxslice, nmax, "lsdem/history:maxslice");
  hist = (lsdem_node_hist **) memory->srealloc(hist, sizeof(lsdem_node_hist *) * nmax,
                                               "lsdem/history:hist");
  slice = (Slice **) memory->srealloc(slice, sizeof(Slice *) * nmax, "lsdem/history:slice");
  for (int i = nmax_atom; i < nmax; i++) {
    nhist[i] = maxhist[i] = nslice[i] = maxslice[i] = 0;
    hist[i] = nullptr;
    slice[i] = nullptr;
  }
  nmax_atom = nmax;
}

/* ----------------------------------------------------------------------
   atom j takes over atom i's list. LAMMPS never reads atom i again after
   copy(i,j) (deletion, sorting), so the two buffers are swapped rather than
   copied: no allocation, and every buffer keeps exactly one owner.
------------------------------------------------------------------------- */

void FixLsdemHistory::copy_arrays(int i, int j, int /*delflag*/)
{
  if (i == j) return;
  std::swap(nhist[i], nhist[j]);
  std::swap(maxhist[i], maxhist[j]);
  std::swap(hist[i], hist[j]);
  std::swap(nslice[i], nslice[j]);
  std::swap(maxslice[i], maxslice[j]);
  std::swap(slice[i], slice[j]);
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::set_arrays(int i)
{
  nhist[i] = nslice[i] = 0;
}

/* ----------------------------------------------------------------------
   count, then per entry: partner, node/pad_, stamp, shear[3], normal[3]
------------------------------------------------------------------------- */

int FixLsdemHistory::pack_entries(int i, double *buf) const
{
  int m = 0;
  buf[m++] = ubuf(nhist[i]).d;
  for (int s = 0; s < nslice[i]; s++) {
    const Slice &sl = slice[i][s];
    for (int k = sl.start; k < sl.start + sl.n; k++) {
      const lsdem_node_hist &h = hist[i][k];
      buf[m++] = ubuf(sl.partner).d;
      buf[m++] = ubuf(pack_node(h)).d;
      buf[m++] = ubuf((int64_t) h.stamp).d;
      for (int d = 0; d < 3; d++) buf[m++] = h.shear[d];
      for (int d = 0; d < 3; d++) buf[m++] = h.normal[d];
    }
  }
  return m;
}

/* ----------------------------------------------------------------------
   entries come sorted by partner: each run of one partner is a slice
------------------------------------------------------------------------- */

int FixLsdemHistory::unpack_entries(int i, const double *buf)
{
  const int n = (int) ubuf(buf[0]).i;
  int ns = 0;
  for (int k = 0; k < n; k++)
    if (k == 0 || ubuf(buf[1 + k * ENTRY_DOUBLES]).i != ubuf(buf[1 + (k - 1) * ENTRY_DOUBLES]).i)
      ns++;
  ensure_capacity(i, n, ns);
  int m = 1;
  nslice[i] = 0;
  for (int k = 0; k < n; k++) {
    lsdem_node_hist &h = hist[i][k];
    const tagint ptag = (tagint) ubuf(buf[m++]).i;
    if (nslice[i] == 0 || slice[i][nslice[i] - 1].partner != ptag)
      slice[i][nslice[i]++] = {ptag, k, 0};
    slice[i][nslice[i] - 1].n++;
    unpack_node(ubuf(buf[m++]).i, h);
    h.stamp = (int64_t) ubuf(buf[m++]).i;
    for (int d = 0; d < 3; d++) h.shear[d] = buf[m++];
    for (int d = 0; d < 3; d++) h.normal[d] = buf[m++];
  }
  nhist[i] = n;
  note_count(n);
  return m;
}

/* ---------------------------------------------------------------------- */

int FixLsdemHistory::pack_exchange(int i, double *buf)
{
  return pack_entries(i, buf);
}

/* ---------------------------------------------------------------------- */

int FixLsdemHistory::unpack_exchange(int nlocal, double *buf)
{
  return unpack_entries(nlocal, buf);
}

/* ----------------------------------------------------------------------
   restart: buf[0] = total size, as every per-atom restart fix packs it
------------------------------------------------------------------------- */

int FixLsdemHistory::pack_restart(int i, double *buf)
{
  int m = 1 + pack_entries(i, buf + 1);
  buf[0] = m;
  return m;
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int k = 0; k < nth; k++) m += static_cast<int>(extra[nlocal][m]);
  unpack_entries(nlocal, &extra[nlocal][m + 1]);
}

/* ---------------------------------------------------------------------- */

int FixLsdemHistory::size_restart(int nlocal)
{
  return 2 + ENTRY_DOUBLES * nhist[nlocal];
}

/* ---------------------------------------------------------------------- */

int FixLsdemHistory::maxsize_restart()
{
  int nlocal = atom->nlocal, mine = 0, all = 0;
  for (int i = 0; i < nlocal; i++) mine = std::max(mine, nhist[i]);
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MAX, world);
  return 2 + ENTRY_DOUBLES * all;
}

/* ---------------------------------------------------------------------- */

double FixLsdemHistory::memory_usage()
{
  double bytes = (double) nmax_atom * (4 * sizeof(int) + 2 * sizeof(void *));
  for (int i = 0; i < nmax_atom; i++)
    bytes += (double) maxhist[i] * sizeof(lsdem_node_hist) + (double) maxslice[i] * sizeof(Slice);
  bytes += (double) maxscratch * sizeof(lsdem_node_hist) + (double) maxslices * sizeof(Slice);
  return bytes;
}
