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
#include <climits>
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
  Fix(lmp, narg, arg), cur(0), nmax_atom(0), first(nullptr), nhist(nullptr), sfirst(nullptr),
  nslice(nullptr), visited(nullptr), generation(0), atom_entry(0), atom_slice(0), maxcount(0)
{
  if (narg != 3) error->all(FLERR, "Illegal fix LSDEM_HISTORY command (internal fix)");

  restart_peratom = 1;
  create_attribute = 1;
  maxexchange_dynamic = 1;
  maxexchange = 1;
  for (Pool &p : pool) p = {nullptr, 0, 0, nullptr, 0, 0};

  FixLsdemHistory::grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
}

/* ---------------------------------------------------------------------- */

FixLsdemHistory::~FixLsdemHistory()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  for (Pool &p : pool) {
    memory->sfree(p.entry);
    memory->sfree(p.slice);
  }
  memory->destroy(first);
  memory->destroy(nhist);
  memory->destroy(sfirst);
  memory->destroy(nslice);
  memory->destroy(visited);
}

/* ---------------------------------------------------------------------- */

int FixLsdemHistory::setmask()
{
  return 0;
}

/* ----------------------------------------------------------------------
   room in pool p for n more entries and ns more slice headers (grows by doubling)
------------------------------------------------------------------------- */

void FixLsdemHistory::pool_room(Pool &p, int n, int ns)
{
  if (p.n + n > p.max) {
    p.max = std::max(2 * p.max, p.n + n);
    p.entry = (lsdem_node_hist *) memory->srealloc(p.entry, sizeof(lsdem_node_hist) * p.max,
                                                   "lsdem/history:entries");
  }
  if (p.ns + ns > p.maxs) {
    p.maxs = std::max({16, 2 * p.maxs, p.ns + ns});
    p.slice = (Slice *) memory->srealloc(p.slice, sizeof(Slice) * p.maxs, "lsdem/history:slices");
  }
}

/* ----------------------------------------------------------------------
   slice of atom i's list against one partner (sorted by node), n entries
------------------------------------------------------------------------- */

const lsdem_node_hist *FixLsdemHistory::find(int i, tagint ptag, int &n) const
{
  const Slice *s = pool[cur].slice + sfirst[i];
  for (int k = 0; k < nslice[i]; k++)  // a few partners: a scan beats a binary search
    if (s[k].partner == ptag) {
      n = s[k].n;
      return pool[cur].entry + first[i] + s[k].start;
    }
  n = 0;
  return nullptr;
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::begin_step()
{
  Pool &next = pool[1 - cur];
  next.n = next.ns = 0;
  generation = generation < INT_MAX ? generation + 1 : 1;  // wraps, never to 0 (new atoms)
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::begin_atom()
{
  atom_entry = pool[1 - cur].n;
  atom_slice = pool[1 - cur].ns;
}

/* ----------------------------------------------------------------------
   room for cap new entries after the committed ones
------------------------------------------------------------------------- */

lsdem_node_hist *FixLsdemHistory::reserve(int cap)
{
  Pool &next = pool[1 - cur];
  pool_room(next, cap, 1);
  return next.entry + next.n;
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::commit(tagint ptag, int n)
{
  if (n <= 0) return;
  Pool &next = pool[1 - cur];
  pool_room(next, 0, 1);
  next.slice[next.ns++] = {ptag, next.n - atom_entry, n};
  next.n += n;
}

/* ----------------------------------------------------------------------
   atom i's list := the committed slices, headers ordered by partner tag
   (each slice is already sorted by node: the kernel writes it that way)
------------------------------------------------------------------------- */

void FixLsdemHistory::end_atom(int i)
{
  Pool &next = pool[1 - cur];
  Slice *s = next.slice + atom_slice;
  const int ns = next.ns - atom_slice;
  for (int a = 1; a < ns; a++) {  // few partners per grain: insertion sort
    Slice t = s[a];
    int b = a - 1;
    while (b >= 0 && s[b].partner > t.partner) {
      s[b + 1] = s[b];
      b--;
    }
    s[b + 1] = t;
  }
  first[i] = atom_entry;
  nhist[i] = next.n - atom_entry;
  sfirst[i] = atom_slice;
  nslice[i] = ns;
  visited[i] = generation;
  note_count(nhist[i]);
}

/* ----------------------------------------------------------------------
   the written pool becomes the current one; owned atoms the step did not visit have
   nothing in it
------------------------------------------------------------------------- */

void FixLsdemHistory::end_step()
{
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++)
    if (visited[i] != generation) nhist[i] = nslice[i] = 0;
  cur = 1 - cur;
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
  memory->grow(first, nmax, "lsdem/history:first");
  memory->grow(nhist, nmax, "lsdem/history:nhist");
  memory->grow(sfirst, nmax, "lsdem/history:sfirst");
  memory->grow(nslice, nmax, "lsdem/history:nslice");
  memory->grow(visited, nmax, "lsdem/history:visited");
  for (int i = nmax_atom; i < nmax; i++) first[i] = nhist[i] = sfirst[i] = nslice[i] = visited[i] = 0;
  nmax_atom = nmax;
}

/* ----------------------------------------------------------------------
   atom j takes over atom i's list (its place in the pool: lists are never written in
   place, so two atoms may share one until the next step rewrites the pool)
------------------------------------------------------------------------- */

void FixLsdemHistory::copy_arrays(int i, int j, int /*delflag*/)
{
  first[j] = first[i];
  nhist[j] = nhist[i];
  sfirst[j] = sfirst[i];
  nslice[j] = nslice[i];
  visited[j] = visited[i];
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
  const Pool &p = pool[cur];
  for (int s = 0; s < nslice[i]; s++) {
    const Slice &sl = p.slice[sfirst[i] + s];
    for (int k = sl.start; k < sl.start + sl.n; k++) {
      const lsdem_node_hist &h = p.entry[first[i] + k];
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
   entries come grouped by partner: each run of one partner is a slice. They are
   appended to the current pool (the next step rewrites it without the dropped ones).
------------------------------------------------------------------------- */

int FixLsdemHistory::unpack_entries(int i, const double *buf)
{
  const int n = (int) ubuf(buf[0]).i;
  int ns = 0;
  for (int k = 0; k < n; k++)
    if (k == 0 || ubuf(buf[1 + k * ENTRY_DOUBLES]).i != ubuf(buf[1 + (k - 1) * ENTRY_DOUBLES]).i)
      ns++;
  Pool &p = pool[cur];
  pool_room(p, n, ns);
  first[i] = p.n;
  sfirst[i] = p.ns;
  int m = 1;
  for (int k = 0; k < n; k++) {
    lsdem_node_hist &h = p.entry[p.n + k];
    const tagint ptag = (tagint) ubuf(buf[m++]).i;
    if (p.ns == sfirst[i] || p.slice[p.ns - 1].partner != ptag) p.slice[p.ns++] = {ptag, k, 0};
    p.slice[p.ns - 1].n++;
    unpack_node(ubuf(buf[m++]).i, h);
    h.stamp = (int64_t) ubuf(buf[m++]).i;
    for (int d = 0; d < 3; d++) h.shear[d] = buf[m++];
    for (int d = 0; d < 3; d++) h.normal[d] = buf[m++];
  }
  p.n += n;
  nhist[i] = n;
  nslice[i] = p.ns - sfirst[i];
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
  double bytes = (double) nmax_atom * 5 * sizeof(int);
  for (const Pool &p : pool)
    bytes += (double) p.max * sizeof(lsdem_node_hist) + (double) p.maxs * sizeof(Slice);
  return bytes;
}
