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
  nslice(nullptr), room(nullptr), nroom(nullptr), visited(nullptr), generation(0),
  maxrecords(0)
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
  memory->sfree(room);
  memory->destroy(nroom);
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
  l.maxscratch = l.atom_used = l.atom_slice = l.atom_records = l.maxrecords = 0;
}

void FixLsdemHistory::release_chunks(std::vector<Chunk> &chunks)
{
  for (Chunk &c : chunks) memory->sfree(c.slot);
  chunks.clear();
}

/* ----------------------------------------------------------------------
   n slots of new room from lane l's chunks; a new chunk (at least a quarter of what the
   lane holds, so that they stay few) when the last one is full. Chunks never move:
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

/* the slots a pair's state takes: head and entries when it has a list, its shear entries
   (as the kernel wrote it, and as stored) */
int FixLsdemHistory::slots_of(const lsdem_pair_state &st)
{
  return (st.list.valid ? HEAD_SLOTS + st.list.head->count : 0) + st.nshear;
}

int FixLsdemHistory::slice_slots(const Slice &s)
{
  return (s.nentry >= 0 ? HEAD_SLOTS + s.nentry : 0) + s.nshear;
}

/* new room for an atom's state of `used` slots: an eighth more, so that an atom whose
   contacts gain a node or two is rewritten in place */
int FixLsdemHistory::room_for(int used)
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
  // the slices lie in the order of the last step's visit: the next atom's first run is
  // most likely the next one read after this atom's; its head on the way into the cache
  const Lane &l = lanes[lane_of[i]];
  const int next = sfirst[i] + nslice[i];
  if (s == l.slice[cur].data() + sfirst[i] && next < l.ns[cur])
    for (int k = 0; k < HEAD_SLOTS; k++) __builtin_prefetch(l.slice[cur][next].run + k);
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
  l.atom_used = l.atom_records = 0;
}

/* ----------------------------------------------------------------------
   the lane's scratch holds at least `need` slots, the atom's pairs kept so far included
------------------------------------------------------------------------- */

void FixLsdemHistory::scratch_room(Lane &l, int need)
{
  if (need <= l.maxscratch) return;
  l.maxscratch = need + need / 4;
  l.scratch = (Slot *) memory->srealloc(l.scratch, sizeof(Slot) * l.maxscratch,
                                        "lsdem/history:scratch");
}

/* ----------------------------------------------------------------------
   room for the kernel's output of one pair behind the atom's pairs kept so far: head,
   list_cap entries, then the shear entries wherever place_shear puts them
------------------------------------------------------------------------- */

lsdem_pair_state FixLsdemHistory::reserve(int lane, int list_cap, int shear_cap)
{
  Lane &l = lanes[lane];
  scratch_room(l, l.atom_used + HEAD_SLOTS + list_cap + shear_cap);
  Slot *run = l.scratch + l.atom_used;
  lsdem_pair_state st;
  st.list.valid = 0;
  st.list.head = reinterpret_cast<lsdem_nodelist_head *>(run);
  st.list.entry = &run[HEAD_SLOTS].entry;
  st.shear = &run[HEAD_SLOTS + list_cap].shear;  // until place_shear knows the list
  st.nshear = 0;
  return st;
}

void FixLsdemHistory::place_shear(lsdem_pair_state &out)
{
  Slot *run = reinterpret_cast<Slot *>(out.list.head);
  out.shear = &run[out.list.valid ? HEAD_SLOTS + out.list.head->count : 0].shear;
}

/* ----------------------------------------------------------------------
   keeping the pair's state st written at the end of lane l's scratch: a pair with a list
   or shear entries becomes the next slice of the lane's slice list `which` (its run
   stays in the scratch until the atom ends); returns the records it takes
------------------------------------------------------------------------- */

int FixLsdemHistory::keep_pair(Lane &l, int which, tagint ptag, const lsdem_pair_state &st)
{
  const int used = slots_of(st);
  if (used <= 0) return 0;
  std::vector<Slice> &list = l.slice[which];
  if ((int) list.size() <= l.ns[which])
    list.resize(std::max(list.size() + list.size() / 4, (size_t) 16));
  Slice &s = list[l.ns[which]++];
  s.partner = ptag;
  s.run = nullptr;  // in the scratch until the atom ends, behind the atom's earlier pairs
  s.nentry = st.list.valid ? st.list.head->count : -1;
  s.nshear = st.nshear;
  l.atom_used += used;
  return (st.list.valid ? 2 + st.list.head->count : 0) + st.nshear;
}

void FixLsdemHistory::commit(int lane, tagint ptag, const lsdem_pair_state &out)
{
  Lane &l = lanes[lane];
  l.atom_records += keep_pair(l, 1 - cur, ptag, out);
}

/* ----------------------------------------------------------------------
   atom i's state := the pairs committed since begin_atom (slice list `which`), copied
   from the scratch over the atom's old room when it fits there, else into new room
------------------------------------------------------------------------- */

void FixLsdemHistory::keep_atom(Lane &l, int which, int i)
{
  if (l.atom_used > nroom[i]) {
    nroom[i] = room_for(l.atom_used);
    room[i] = take_slots(l, nroom[i]);
  }
  if (l.atom_used > 0) memcpy(room[i], l.scratch, sizeof(Slot) * l.atom_used);
  Slice *s = l.slice[which].data() + l.atom_slice;
  const int ns = l.ns[which] - l.atom_slice;
  Slot *run = room[i];
  for (int k = 0; k < ns; k++) {  // back to back, in the order they were kept
    s[k].run = run;
    run += slice_slots(s[k]);
  }
  lane_of[i] = (int) (&l - lanes.data());
  sfirst[i] = l.atom_slice;
  nslice[i] = ns;
}

void FixLsdemHistory::end_atom(int lane, int i)
{
  Lane &l = lanes[lane];
  keep_atom(l, 1 - cur, i);
  visited[i] = generation;
  l.maxrecords = std::max(l.maxrecords, l.atom_records);
}

/* ----------------------------------------------------------------------
   the written slices become the current ones; owned atoms the step did not visit have
   nothing in them (and their room is given up)
------------------------------------------------------------------------- */

void FixLsdemHistory::end_step()
{
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++)
    if (visited[i] != generation) nslice[i] = lane_of[i] = nroom[i] = 0;
  for (const Lane &l : lanes) note_records(l.maxrecords);
  cur = 1 - cur;
  compact_if_wasteful();
}

/* ----------------------------------------------------------------------
   when an eighth of the chunks' used slots are no atom's (rooms left behind by states
   that outgrew them, atoms gone or without pairs) or lanes have gone: the owned atoms'
   rooms copied, atom by atom, into one new chunk per lane (the lane that visited the
   atom) with room for an eighth more, the old chunks freed
------------------------------------------------------------------------- */

void FixLsdemHistory::compact_if_wasteful()
{
  const int nlocal = atom->nlocal;
  size_t used = 0, live = 0;
  for (const Lane &l : lanes)
    for (const Chunk &c : l.chunk) used += c.used;
  for (int i = 0; i < nlocal; i++) live += nroom[i];
  if ((int) lanes.size() <= nlanes && 8 * (used - live) <= used) return;
  std::vector<size_t> need(lanes.size(), 0);
  for (int i = 0; i < nlocal; i++) need[lane_of[i]] += nroom[i];
  std::vector<std::vector<Chunk>> old(lanes.size());
  for (size_t l = 0; l < lanes.size(); l++) {
    old[l].swap(lanes[l].chunk);
    if (need[l] == 0) continue;
    Chunk c;
    c.cap = (int) std::max(need[l] + need[l] / 8, (size_t) MIN_CHUNK_SLOTS);
    c.used = 0;
    c.slot = (Slot *) memory->smalloc(sizeof(Slot) * c.cap, "lsdem/history:chunk");
    lanes[l].chunk.push_back(c);
  }
  for (int i = 0; i < nlocal; i++) {
    if (nroom[i] == 0) continue;
    Lane &l = lanes[lane_of[i]];
    Slot *to = take_slots(l, nroom[i]);
    memcpy(to, room[i], sizeof(Slot) * nroom[i]);
    Slice *s = l.slice[cur].data() + sfirst[i];
    for (int k = 0; k < nslice[i]; k++) s[k].run = to + (s[k].run - room[i]);
    room[i] = to;
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
  room = (Slot **) memory->srealloc(room, sizeof(Slot *) * nmax, "lsdem/history:room");
  memory->grow(nroom, nmax, "lsdem/history:nroom");
  for (int i = nmax_atom; i < nmax; i++) {
    lane_of[i] = sfirst[i] = nslice[i] = visited[i] = nroom[i] = 0;
    room[i] = nullptr;
  }
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
  room[j] = room[i];
  nroom[j] = nroom[i];
  visited[j] = visited[i];
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::set_arrays(int i)
{
  nslice[i] = nroom[i] = 0;
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
   (lsdem_pair_state_decode, against the nodes of atom i's shape), kept as the atom's
   state of the last step, in new room of the first lane.
------------------------------------------------------------------------- */

int FixLsdemHistory::unpack_state(int i, const double *buf)
{
  const int n = (int) ubuf(buf[0]).i;
  auto avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  if (!avec) error->one(FLERR, "Fix LSDEM_HISTORY requires atom_style lsdem");
  const int nnodes = avec->shape_of(i)->nnodes;
  Lane &l = lanes[0];  // exchange and restart are serial: the first lane
  l.atom_slice = l.ns[cur];
  l.atom_used = 0;
  nroom[i] = 0;  // new room: what index i held before is another atom's or garbage
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
    lsdem_pair_state st = reserve(0, len, len);
    lsdem_pair_state_decode(records.data(), len, nnodes, &st);
    // the decoded shear entries go behind the list, in the run's own layout
    lsdem_pair_state kept = st;
    place_shear(kept);
    memmove(kept.shear, st.shear, sizeof(lsdem_shear_hist) * st.nshear);
    keep_pair(l, cur, ptag, kept);
    k += len;
    m += RECORD_DOUBLES * len;
  }
  keep_atom(l, cur, i);
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
      bytes_used += (double) sizeof(Slot) * slice_slots(s);
    }
}

double FixLsdemHistory::memory_usage()
{
  double bytes = (double) nmax_atom * (5 * sizeof(int) + sizeof(Slot *));
  for (const Lane &l : lanes) {
    for (const auto &slices : l.slice) bytes += (double) slices.size() * sizeof(Slice);
    for (const Chunk &c : l.chunk) bytes += (double) c.cap * sizeof(Slot);
    bytes += (double) l.maxscratch * sizeof(Slot);
  }
  bytes += (double) records.size() * sizeof(lsdem_state_record);
  return bytes;
}
