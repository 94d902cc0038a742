// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: the contact state of each grain's pairs (internal fix).
   See fix_lsdem_history.h for the usage pattern.
------------------------------------------------------------------------- */

#include "fix_lsdem_history.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "comm.h"
#include "error.h"
#include "memory.h"

#include <algorithm>
#include <climits>
#include <cstring>

using namespace LAMMPS_NS;

// doubles per packed record: partner, id and aux (aux << 32 | id), stamp, a[3], b[3]
static constexpr int RECORD_DOUBLES = 9;

static int64_t pack_ids(const lsdem_state_record &r)
{
  return (int64_t) (((uint64_t) (uint32_t) r.aux << 32) | (uint32_t) r.id);
}

static void unpack_ids(int64_t v, lsdem_state_record &r)
{
  r.id = (int32_t) (uint32_t) ((uint64_t) v & 0xffffffffu);
  r.aux = (int32_t) (uint32_t) ((uint64_t) v >> 32);
}

/* ---------------------------------------------------------------------- */

FixLsdemHistory::FixLsdemHistory(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), nlanes(1), cur(0), nmax_atom(0), lane_of(nullptr), sfirst(nullptr),
  nslice(nullptr), visited(nullptr), generation(0), maxrecords(0)
{
  if (narg != 3) error->all(FLERR, "Illegal fix LSDEM_HISTORY command (internal fix)");

  restart_peratom = 1;
  create_attribute = 1;
  maxexchange_dynamic = 1;
  maxexchange = 1;
  lanes.resize(1);
  init_lane(lanes[0]);
  static_assert(sizeof(Slot) == 64 && sizeof(lsdem_nodelist_head) <= HEAD_SLOTS * sizeof(Slot),
                "a list head fits two slots");

  FixLsdemHistory::grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
}

/* ---------------------------------------------------------------------- */

FixLsdemHistory::~FixLsdemHistory()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  for (Lane &l : lanes) {
    release_chunks(l.chunk);
    memory->sfree(l.scratch);
  }
  memory->destroy(lane_of);
  memory->destroy(sfirst);
  memory->destroy(nslice);
  memory->destroy(visited);
}

/* ---------------------------------------------------------------------- */

int FixLsdemHistory::setmask()
{
  return 0;
}

void FixLsdemHistory::init_lane(Lane &l)
{
  l.ns[0] = l.ns[1] = 0;
  l.scratch = nullptr;
  l.maxscratch = l.atom_slice = l.atom_records = l.maxrecords = 0;
}

void FixLsdemHistory::release_chunks(std::vector<Chunk> &chunks)
{
  for (Chunk &c : chunks) memory->sfree(c.slot);
  chunks.clear();
}

/* ----------------------------------------------------------------------
   n slots for a new run from lane l's chunks; a new chunk (at least a quarter of what
   the lane holds, so that they stay few) when the last one is full. Chunks never move:
   other lanes may be reading runs in them.
------------------------------------------------------------------------- */

FixLsdemHistory::Slot *FixLsdemHistory::take_slots(Lane &l, int n)
{
  if (l.chunk.empty() || l.chunk.back().cap - l.chunk.back().used < n) {
    size_t held = 0;
    for (const Chunk &c : l.chunk) held += c.cap;
    Chunk c;
    c.cap = (int) std::max({(size_t) n, held / 4, (size_t) MIN_CHUNK_SLOTS});
    c.used = 0;
    c.slot = (Slot *) memory->smalloc(sizeof(Slot) * c.cap, "lsdem/history:chunk");
    l.chunk.push_back(c);
  }
  Chunk &c = l.chunk.back();
  Slot *run = c.slot + c.used;
  c.used += n;
  return run;
}

/* the slots a pair's state takes: head and entries when it has a list, its shear entries */
int FixLsdemHistory::slots_of(const lsdem_pair_state &st)
{
  return (st.list.valid ? HEAD_SLOTS + st.list.head->count : 0) + st.nshear;
}

/* a new run's slots for a state of `used`: an eighth more, so that a pair whose contact
   gains a node is mostly rewritten in place */
int FixLsdemHistory::run_capacity(int used)
{
  return used + used / 8;
}

/* ----------------------------------------------------------------------
   a stored pair's state as the kernel reads it: head and entries when it has a list,
   the shear entries behind them
------------------------------------------------------------------------- */

void FixLsdemHistory::slice_state(const Slice &s, lsdem_pair_state &st)
{
  st.list.valid = s.nentry >= 0;
  st.list.head = reinterpret_cast<lsdem_nodelist_head *>(s.run);
  st.list.entry = &s.run[HEAD_SLOTS].entry;
  st.shear = &s.run[st.list.valid ? HEAD_SLOTS + s.nentry : 0].shear;
  st.nshear = s.nshear;
}

/* ----------------------------------------------------------------------
   a run's head and first entries on their way into the cache: runs are read in the order
   of the slices, but they need not lie in that order (runs rewritten in place stay where
   they are; a state that outgrew its run moved to the end)
------------------------------------------------------------------------- */

void FixLsdemHistory::prefetch_run(const Slice &s)
{
  const int lines = std::min(s.cap, PREFETCH_SLOTS);
  for (int k = 0; k < lines; k++) __builtin_prefetch(s.run + k);
}

/* ----------------------------------------------------------------------
   the state of atom i against one partner; false when it keeps none
------------------------------------------------------------------------- */

const FixLsdemHistory::Slice *FixLsdemHistory::slice_of(int i, tagint ptag) const
{
  const Slice *s = lanes[lane_of[i]].slice[cur].data() + sfirst[i];
  for (int k = 0; k < nslice[i]; k++)  // a few partners: a scan beats a binary search
    if (s[k].partner == ptag) return &s[k];
  return nullptr;
}

bool FixLsdemHistory::find(int i, tagint ptag, lsdem_pair_state &in) const
{
  const Slice *s = slice_of(i, ptag);
  if (!s) return false;
  slice_state(*s, in);
  const Lane &l = lanes[lane_of[i]];
  if (s + 1 < l.slice[cur].data() + l.ns[cur])
    prefetch_run(s[1]);  // the pair visited next, most likely (slices: in visit order)
  return true;
}

/* ----------------------------------------------------------------------
   the lanes of this step; those of the last one stay until the pool is compacted (their
   chunks hold runs that are read, and rewritten in place, this step)
------------------------------------------------------------------------- */

void FixLsdemHistory::begin_step(int n)
{
  const int had = (int) lanes.size();
  if (n > had) {
    lanes.resize(n);
    for (int l = had; l < n; l++) init_lane(lanes[l]);
  }
  nlanes = n;
  for (Lane &l : lanes) l.ns[1 - cur] = l.maxrecords = 0;
  generation = generation < INT_MAX ? generation + 1 : 1;  // wraps, never to 0 (new atoms)
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::begin_atom(int lane)
{
  Lane &l = lanes[lane];
  l.atom_slice = l.ns[1 - cur];
  l.atom_records = 0;
}

/* ----------------------------------------------------------------------
   room for the kernel's output of one pair in lane l's scratch: head, list_cap entries,
   then the shear entries wherever place_shear puts them
------------------------------------------------------------------------- */

lsdem_pair_state FixLsdemHistory::scratch_state(Lane &l, int list_cap, int shear_cap)
{
  const int need = HEAD_SLOTS + list_cap + shear_cap;
  if (need > l.maxscratch) {
    memory->sfree(l.scratch);
    l.scratch = (Slot *) memory->smalloc(sizeof(Slot) * need, "lsdem/history:scratch");
    l.maxscratch = need;
  }
  lsdem_pair_state st;
  st.list.valid = 0;
  st.list.head = reinterpret_cast<lsdem_nodelist_head *>(l.scratch);
  st.list.entry = &l.scratch[HEAD_SLOTS].entry;
  st.shear = &l.scratch[HEAD_SLOTS + list_cap].shear;  // until place_shear knows the list
  st.nshear = 0;
  return st;
}

lsdem_pair_state FixLsdemHistory::reserve(int lane, int list_cap, int shear_cap)
{
  return scratch_state(lanes[lane], list_cap, shear_cap);
}

void FixLsdemHistory::place_shear(lsdem_pair_state &out)
{
  Slot *run = reinterpret_cast<Slot *>(out.list.head);
  out.shear = &run[out.list.valid ? HEAD_SLOTS + out.list.head->count : 0].shear;
}

/* ----------------------------------------------------------------------
   keeping a pair's state st (one run from st.list.head, place_shear's layout) as the
   next slice of lane l's slice list `which`: copied over the run of its old slice when
   that fits and no other pair took it this step, else into a new run; returns the
   records it takes (0: nothing kept)
------------------------------------------------------------------------- */

int FixLsdemHistory::keep_pair(Lane &l, int which, tagint ptag, const lsdem_pair_state &st,
                               Slice *old)
{
  const int used = slots_of(st);
  if (used <= 0) return 0;
  if ((int) l.slice[which].size() <= l.ns[which])
    l.slice[which].resize(std::max(l.slice[which].size() + l.slice[which].size() / 4,
                                   (size_t) 16));
  Slice &s = l.slice[which][l.ns[which]++];
  const bool in_place = old && old->claimed != generation && old->cap >= used;
  s.cap = in_place ? old->cap : run_capacity(used);
  s.run = in_place ? old->run : take_slots(l, s.cap);
  if (in_place) old->claimed = generation;
  memmove(s.run, st.list.head, sizeof(Slot) * used);
  s.partner = ptag;
  s.nentry = st.list.valid ? st.list.head->count : -1;
  s.nshear = st.nshear;
  s.claimed = 0;
  return (st.list.valid ? 2 + st.list.head->count : 0) + st.nshear;
}

/* ----------------------------------------------------------------------
   keeping the state the kernel wrote into the scratch, in place of atom i's last one
   with this partner when it fits
------------------------------------------------------------------------- */

void FixLsdemHistory::commit(int lane, int i, tagint ptag, const lsdem_pair_state &out)
{
  Lane &l = lanes[lane];
  // the old slice is this fix's own (found through the atom's index): marked as taken
  Slice *old = const_cast<Slice *>(slice_of(i, ptag));
  l.atom_records += keep_pair(l, 1 - cur, ptag, out, old);
}

/* ----------------------------------------------------------------------
   atom i's state := the committed pairs, in the order they were committed (the order
   of the next step's visit: its runs are read in the order they lie)
------------------------------------------------------------------------- */

void FixLsdemHistory::end_atom(int lane, int i)
{
  Lane &l = lanes[lane];
  lane_of[i] = lane;
  sfirst[i] = l.atom_slice;
  nslice[i] = l.ns[1 - cur] - l.atom_slice;
  visited[i] = generation;
  l.maxrecords = std::max(l.maxrecords, l.atom_records);
}

/* ----------------------------------------------------------------------
   the written slices become the current ones; owned atoms the step did not visit have
   nothing in them
------------------------------------------------------------------------- */

void FixLsdemHistory::end_step()
{
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++)
    if (visited[i] != generation) nslice[i] = lane_of[i] = 0;
  for (const Lane &l : lanes) note_records(l.maxrecords);
  cur = 1 - cur;
  compact_if_wasteful();
}

/* ----------------------------------------------------------------------
   when a quarter of the chunks' used slots are no state's (runs left behind by states
   that outgrew them, pairs dropped) or lanes have gone: each lane's runs copied, in the
   order of its slices, into one new chunk with room for an eighth more, the old chunks
   freed
------------------------------------------------------------------------- */

void FixLsdemHistory::compact_if_wasteful()
{
  size_t used = 0, live = 0;
  for (const Lane &l : lanes) {
    for (const Chunk &c : l.chunk) used += c.used;
    for (int k = 0; k < l.ns[cur]; k++) live += l.slice[cur][k].cap;
  }
  if ((int) lanes.size() <= nlanes && 8 * (used - live) <= used) return;
  std::vector<std::vector<Chunk>> old(lanes.size());
  for (size_t l = 0; l < lanes.size(); l++) old[l].swap(lanes[l].chunk);
  for (Lane &l : lanes) {
    size_t need = 0;
    for (int k = 0; k < l.ns[cur]; k++) need += l.slice[cur][k].cap;
    if (need == 0) continue;
    Chunk c;
    c.cap = (int) std::max(need + need / 8, (size_t) MIN_CHUNK_SLOTS);
    c.used = 0;
    c.slot = (Slot *) memory->smalloc(sizeof(Slot) * c.cap, "lsdem/history:chunk");
    for (int k = 0; k < l.ns[cur]; k++) {
      Slice &s = l.slice[cur][k];
      memcpy(c.slot + c.used, s.run, sizeof(Slot) * s.cap);
      s.run = c.slot + c.used;
      c.used += s.cap;
    }
    l.chunk.push_back(c);
  }
  for (auto &chunks : old) release_chunks(chunks);
  for (int l = nlanes; l < (int) lanes.size(); l++) memory->sfree(lanes[l].scratch);
  lanes.resize(std::max(nlanes, 1));
}

/* ----------------------------------------------------------------------
   records of atom i's state; the exchange buffer must hold the largest, and it only ever
   grows
------------------------------------------------------------------------- */

int FixLsdemHistory::count_records(int i) const
{
  const Slice *s = lanes[lane_of[i]].slice[cur].data() + sfirst[i];
  int n = 0;
  for (int k = 0; k < nslice[i]; k++) n += (s[k].nentry >= 0 ? 2 + s[k].nentry : 0) + s[k].nshear;
  return n;
}

void FixLsdemHistory::note_records(int n)
{
  if (n <= maxrecords) return;
  maxrecords = n;
  maxexchange = 1 + RECORD_DOUBLES * maxrecords;
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::grow_arrays(int nmax)
{
  if (nmax <= nmax_atom) return;
  memory->grow(lane_of, nmax, "lsdem/history:lane_of");
  memory->grow(sfirst, nmax, "lsdem/history:sfirst");
  memory->grow(nslice, nmax, "lsdem/history:nslice");
  memory->grow(visited, nmax, "lsdem/history:visited");
  for (int i = nmax_atom; i < nmax; i++) lane_of[i] = sfirst[i] = nslice[i] = visited[i] = 0;
  nmax_atom = nmax;
}

/* ----------------------------------------------------------------------
   atom j takes over atom i's state (its slices: i is then gone or a copy the caller
   discards, so that one state has one owner)
------------------------------------------------------------------------- */

void FixLsdemHistory::copy_arrays(int i, int j, int /*delflag*/)
{
  lane_of[j] = lane_of[i];
  sfirst[j] = sfirst[i];
  nslice[j] = nslice[i];
  visited[j] = visited[i];
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::set_arrays(int i)
{
  nslice[i] = 0;
}

/* ----------------------------------------------------------------------
   count, then per record: partner, id/aux, stamp, a[3], b[3] (each pair's records
   together, lsdem_pair_state_encode; pairs by partner tag, whatever order the step
   visited them in)
------------------------------------------------------------------------- */

int FixLsdemHistory::pack_state(int i, double *buf)
{
  int m = 0;
  buf[m++] = ubuf(count_records(i)).d;
  const Slice *slices = lanes[lane_of[i]].slice[cur].data() + sfirst[i];
  by_partner.resize(std::max(by_partner.size(), (size_t) nslice[i]));
  for (int k = 0; k < nslice[i]; k++) by_partner[k] = &slices[k];
  std::sort(by_partner.begin(), by_partner.begin() + nslice[i],
            [](const Slice *a, const Slice *b) { return a->partner < b->partner; });
  for (int k = 0; k < nslice[i]; k++) {
    const Slice &s = *by_partner[k];
    lsdem_pair_state st;
    slice_state(s, st);
    records.resize(std::max(records.size(), (size_t) lsdem_pair_state_records(&st)));
    const int n = lsdem_pair_state_encode(&st, records.data());
    for (int r = 0; r < n; r++) {
      const lsdem_state_record &rec = records[r];
      buf[m++] = ubuf(s.partner).d;
      buf[m++] = ubuf(pack_ids(rec)).d;
      buf[m++] = ubuf((int64_t) rec.stamp).d;
      for (int d = 0; d < 3; d++) buf[m++] = rec.a[d];
      for (int d = 0; d < 3; d++) buf[m++] = rec.b[d];
    }
  }
  return m;
}

/* ----------------------------------------------------------------------
   records come grouped by partner: each run of one partner is one pair's state
   (lsdem_pair_state_decode, against the nodes of atom i's shape). They are appended to
   the current pool (the next step rewrites it without the dropped ones).
------------------------------------------------------------------------- */

int FixLsdemHistory::unpack_state(int i, const double *buf)
{
  const int n = (int) ubuf(buf[0]).i;
  auto avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  if (!avec) error->one(FLERR, "Fix LSDEM_HISTORY requires atom_style lsdem");
  const int nnodes = avec->shape_of(i)->nnodes;
  Lane &l = lanes[0];  // exchange and restart are serial: the first lane
  lane_of[i] = 0;
  sfirst[i] = l.ns[cur];
  nslice[i] = 0;
  records.resize(std::max(records.size(), (size_t) n));
  int m = 1;
  for (int k = 0; k < n;) {
    const tagint ptag = (tagint) ubuf(buf[m]).i;
    int len = 0;  // this partner's run of records
    while (k + len < n && (tagint) ubuf(buf[m + RECORD_DOUBLES * len]).i == ptag) {
      lsdem_state_record &rec = records[len];
      const double *r = &buf[m + RECORD_DOUBLES * len];
      unpack_ids(ubuf(r[1]).i, rec);
      rec.stamp = (int64_t) ubuf(r[2]).i;
      for (int d = 0; d < 3; d++) {
        rec.a[d] = r[3 + d];
        rec.b[d] = r[6 + d];
      }
      len++;
    }
    lsdem_pair_state st = scratch_state(l, len, len);
    lsdem_pair_state_decode(records.data(), len, nnodes, &st);
    // the decoded shear entries go behind the list, in the run's own layout
    lsdem_pair_state kept = st;
    place_shear(kept);
    memmove(kept.shear, st.shear, sizeof(lsdem_shear_hist) * st.nshear);
    if (keep_pair(l, cur, ptag, kept, nullptr) > 0) nslice[i]++;
    k += len;
    m += RECORD_DOUBLES * len;
  }
  note_records(count_records(i));
  return m;
}

/* ---------------------------------------------------------------------- */

int FixLsdemHistory::pack_exchange(int i, double *buf)
{
  return pack_state(i, buf);
}

/* ---------------------------------------------------------------------- */

int FixLsdemHistory::unpack_exchange(int nlocal, double *buf)
{
  return unpack_state(nlocal, buf);
}

/* ----------------------------------------------------------------------
   restart: buf[0] = total size, as every per-atom restart fix packs it
------------------------------------------------------------------------- */

int FixLsdemHistory::pack_restart(int i, double *buf)
{
  int m = 1 + pack_state(i, buf + 1);
  buf[0] = m;
  return m;
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int k = 0; k < nth; k++) m += static_cast<int>(extra[nlocal][m]);
  unpack_state(nlocal, &extra[nlocal][m + 1]);
}

/* ---------------------------------------------------------------------- */

int FixLsdemHistory::size_restart(int nlocal)
{
  return 2 + RECORD_DOUBLES * count_records(nlocal);
}

/* ---------------------------------------------------------------------- */

int FixLsdemHistory::maxsize_restart()
{
  int nlocal = atom->nlocal, mine = 0, all = 0;
  for (int i = 0; i < nlocal; i++) mine = std::max(mine, count_records(i));
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MAX, world);
  return 2 + RECORD_DOUBLES * all;
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::held(double &pairs, double &entries, double &shears,
                           double &bytes_used) const
{
  pairs = entries = shears = bytes_used = 0.0;
  for (const Lane &l : lanes)
    for (int k = 0; k < l.ns[cur]; k++) {
      const Slice &s = l.slice[cur][k];
      pairs += 1.0;
      entries += s.nentry >= 0 ? s.nentry : 0;
      shears += s.nshear;
      bytes_used += (double) sizeof(Slot) * ((s.nentry >= 0 ? HEAD_SLOTS + s.nentry : 0) + s.nshear);
    }
}

double FixLsdemHistory::memory_usage()
{
  double bytes = (double) nmax_atom * 4 * sizeof(int);
  for (const Lane &l : lanes) {
    for (const auto &slices : l.slice) bytes += (double) slices.size() * sizeof(Slice);
    for (const Chunk &c : l.chunk) bytes += (double) c.cap * sizeof(Slot);
    bytes += (double) l.maxscratch * sizeof(Slot);
  }
  bytes += (double) records.size() * sizeof(lsdem_state_record);
  return bytes;
}
