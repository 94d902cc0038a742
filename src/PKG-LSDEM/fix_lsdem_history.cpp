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
  Fix(lmp, narg, arg), cur(0), nmax_atom(0), lane_of(nullptr), sfirst(nullptr),
  nslice(nullptr), visited(nullptr), generation(0), maybe_held(false), maxrecords(0)
{
  if (narg != 3) error->all(FLERR, "Illegal fix LSDEM_HISTORY command (internal fix)");

  restart_peratom = 1;
  create_attribute = 1;
  maxexchange_dynamic = 1;
  maxexchange = 1;
  for (auto &lanes : pool) lanes.resize(1);
  for (auto &lanes : pool)
    for (Pool &p : lanes) {
      p.word = nullptr;
      p.ns = p.nword = p.maxword = p.atom_slice = p.atom_records = p.maxrecords = 0;
    }
  static_assert(sizeof(lsdem_nodelist_head) % sizeof(Word) == 0 &&
                    sizeof(lsdem_shear_hist) % sizeof(Word) == 0 &&
                    sizeof(lsdem_nodelist_entry) == sizeof(Word),
                "a pair's state is whole words");

  FixLsdemHistory::grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
}

/* ---------------------------------------------------------------------- */

FixLsdemHistory::~FixLsdemHistory()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  for (auto &lanes : pool)
    for (Pool &p : lanes) release(p);
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

void FixLsdemHistory::release(Pool &p)
{
  memory->sfree(p.word);
  p.word = nullptr;
  p.maxword = 0;
}

/* room for ns more slices and nword more words; grows by a quarter (not doubling: the
   pools are most of a grain's memory, and they reach their size in the first steps; the
   step's pointers into p are taken after this) */
void FixLsdemHistory::pool_room(Pool &p, int ns, int nword)
{
  const size_t need = (size_t) p.ns + (size_t) ns;
  if (need > p.slice.size())
    p.slice.resize(std::max({need, p.slice.size() + p.slice.size() / 4, (size_t) 16}));
  if (p.nword + nword > p.maxword) {
    p.maxword = std::max(p.maxword + p.maxword / 4, p.nword + nword);
    p.word = (Word *) memory->srealloc(p.word, sizeof(Word) * p.maxword, "lsdem/history:words");
  }
}

/* ----------------------------------------------------------------------
   a stored pair's state as the kernel reads it: head and entries when it has a list,
   the shear entries behind them
------------------------------------------------------------------------- */

void FixLsdemHistory::slice_state(const Pool &p, const Slice &s, lsdem_pair_state &st)
{
  Word *run = p.word + s.first;
  st.list.valid = s.list_valid;
  st.list.head = reinterpret_cast<lsdem_nodelist_head *>(run);
  st.list.entry = reinterpret_cast<lsdem_nodelist_entry *>(run + HEAD_WORDS);
  st.shear = reinterpret_cast<lsdem_shear_hist *>(
      run + (s.list_valid ? HEAD_WORDS + s.nlistword : 0));
  st.nshear = s.nshear;
}

/* ----------------------------------------------------------------------
   the state of atom i against one partner; false when it keeps none
------------------------------------------------------------------------- */

bool FixLsdemHistory::find(int i, tagint ptag, lsdem_pair_state &in) const
{
  const Pool &p = pool[cur][lane_of[i]];
  const Slice *s = p.slice.data() + sfirst[i];
  for (int k = 0; k < nslice[i]; k++)  // a few partners: a scan beats a binary search
    if (s[k].partner == ptag) {
      slice_state(p, s[k], in);
      return true;
    }
  return false;
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::begin_step(int nlanes)
{
  auto &next = pool[1 - cur];
  for (int l = nlanes; l < (int) next.size(); l++) release(next[l]);
  const int had = (int) next.size();
  next.resize(nlanes);
  for (int l = had; l < nlanes; l++) {
    next[l].word = nullptr;
    next[l].maxword = 0;
  }
  for (Pool &p : next) {
    p.ns = p.nword = p.maxrecords = 0;
    p.kept = false;
  }
  generation = generation < INT_MAX ? generation + 1 : 1;  // wraps, never to 0 (new atoms)
}

/* ---------------------------------------------------------------------- */

void FixLsdemHistory::begin_atom(int lane)
{
  Pool &next = pool[1 - cur][lane];
  next.atom_slice = next.ns;
  next.atom_records = 0;
}

/* ----------------------------------------------------------------------
   room in pool p for one more pair's state, a run of words after the used ones (head,
   list_words words of entries, then the shear entries wherever place_shear puts them),
   and keeping what was written there: a pair with a list or shear entries becomes the
   pool's next slice; returns the records it takes (0: nothing kept)
------------------------------------------------------------------------- */

lsdem_pair_state FixLsdemHistory::pair_room(Pool &p, int list_words, int shear_cap)
{
  pool_room(p, 1, HEAD_WORDS + list_words + SHEAR_WORDS * shear_cap);
  Word *run = p.word + p.nword;
  lsdem_pair_state st;
  st.list.valid = 0;
  st.list.head = reinterpret_cast<lsdem_nodelist_head *>(run);
  st.list.entry = reinterpret_cast<lsdem_nodelist_entry *>(run + HEAD_WORDS);
  // the shear entries until place_shear knows the list
  st.shear = reinterpret_cast<lsdem_shear_hist *>(run + HEAD_WORDS + list_words);
  st.nshear = 0;
  return st;
}

void FixLsdemHistory::place_shear(lsdem_pair_state &out)
{
  Word *run = reinterpret_cast<Word *>(out.list.head);
  out.shear = reinterpret_cast<lsdem_shear_hist *>(
      run + (out.list.valid ? HEAD_WORDS + out.list.head->words : 0));
}

int FixLsdemHistory::keep_pair(Pool &p, tagint ptag, const lsdem_pair_state &st)
{
  if (!st.list.valid && st.nshear <= 0) return 0;
  Slice &s = p.slice[p.ns++];
  s.partner = ptag;
  s.first = p.nword;
  s.list_valid = st.list.valid;
  s.nentry = st.list.valid ? st.list.head->count : 0;
  s.nlistword = st.list.valid ? st.list.head->words : 0;
  s.nshear = st.nshear;
  p.nword += (st.list.valid ? HEAD_WORDS + s.nlistword : 0) + SHEAR_WORDS * st.nshear;
  return (st.list.valid ? 2 + s.nentry : 0) + st.nshear;
}

/* ----------------------------------------------------------------------
   room for a pair's new state after the committed ones, and keeping the state the
   kernel wrote there
------------------------------------------------------------------------- */

lsdem_pair_state FixLsdemHistory::reserve(int lane, int list_words, int shear_cap)
{
  return pair_room(pool[1 - cur][lane], list_words, shear_cap);
}

void FixLsdemHistory::commit(int lane, tagint ptag, const lsdem_pair_state &out)
{
  Pool &next = pool[1 - cur][lane];
  next.atom_records += keep_pair(next, ptag, out);
}

/* ----------------------------------------------------------------------
   atom i's state := the committed pairs, ordered by partner tag
------------------------------------------------------------------------- */

void FixLsdemHistory::end_atom(int lane, int i)
{
  Pool &next = pool[1 - cur][lane];
  Slice *s = next.slice.data() + next.atom_slice;
  const int ns = next.ns - next.atom_slice;
  for (int a = 1; a < ns; a++) {  // few partners per grain: insertion sort
    Slice t = s[a];
    int b = a - 1;
    while (b >= 0 && s[b].partner > t.partner) {
      s[b + 1] = s[b];
      b--;
    }
    s[b + 1] = t;
  }
  lane_of[i] = lane;
  sfirst[i] = next.atom_slice;
  nslice[i] = ns;
  visited[i] = generation;
  if (ns > 0) next.kept = true;
  next.maxrecords = std::max(next.maxrecords, next.atom_records);
}

/* ----------------------------------------------------------------------
   the written pool becomes the current one; owned atoms the step did not visit have
   nothing in it (none to clear when no atom held a state: a store that spheres' slots
   leave empty costs nothing per atom)
------------------------------------------------------------------------- */

void FixLsdemHistory::end_step()
{
  const int nlocal = atom->nlocal;
  if (maybe_held)
    for (int i = 0; i < nlocal; i++)
      if (visited[i] != generation) nslice[i] = 0;
  maybe_held = false;
  for (const Pool &p : pool[1 - cur]) {
    note_records(p.maxrecords);
    maybe_held = maybe_held || p.kept;
  }
  cur = 1 - cur;
}

/* ----------------------------------------------------------------------
   records of atom i's state in the current pool; the exchange buffer must hold the
   largest, and it only ever grows
------------------------------------------------------------------------- */

int FixLsdemHistory::count_records(int i) const
{
  const Pool &p = pool[cur][lane_of[i]];
  int n = 0;
  for (int k = sfirst[i]; k < sfirst[i] + nslice[i]; k++)
    n += (p.slice[k].list_valid ? 2 + p.slice[k].nentry : 0) + p.slice[k].nshear;
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
   atom j takes over atom i's state (its place in the pool: states are never written in
   place, so two atoms may share one until the next step rewrites the pool)
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
   together, lsdem_pair_state_encode)
------------------------------------------------------------------------- */

int FixLsdemHistory::pack_state(int i, double *buf)
{
  int m = 0;
  buf[m++] = ubuf(count_records(i)).d;
  const Pool &p = pool[cur][lane_of[i]];
  for (int k = 0; k < nslice[i]; k++) {
    const Slice &s = p.slice[sfirst[i] + k];
    lsdem_pair_state st;
    slice_state(p, s, st);
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
  Pool &p = pool[cur][0];  // exchange and restart are serial: the first lane
  lane_of[i] = 0;
  sfirst[i] = p.ns;
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
    lsdem_pair_state st = pair_room(p, len * LSDEM_NODELIST_MAX_WORDS, len);
    lsdem_pair_state_decode(records.data(), len, nnodes, &st);
    // the decoded shear entries go behind the list, in the run's own layout
    lsdem_pair_state kept = st;
    place_shear(kept);
    memmove(kept.shear, st.shear, sizeof(lsdem_shear_hist) * st.nshear);
    if (keep_pair(p, ptag, kept) > 0) nslice[i]++;
    maybe_held = maybe_held || nslice[i] > 0;
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
  pairs = entries = shears = 0.0;
  double words = 0.0;
  for (const Pool &p : pool[cur])
    for (int k = 0; k < p.ns; k++) {
      const Slice &s = p.slice[k];
      pairs += 1.0;
      entries += s.list_valid ? s.nentry : 0;
      shears += s.nshear;
      words += (s.list_valid ? HEAD_WORDS + s.nlistword : 0) + SHEAR_WORDS * s.nshear;
    }
  bytes_used = words * sizeof(Word);
}

double FixLsdemHistory::memory_usage()
{
  double bytes = (double) nmax_atom * 4 * sizeof(int);
  for (const auto &lanes : pool)
    for (const Pool &p : lanes)
      bytes += (double) p.slice.size() * sizeof(Slice) + (double) p.maxword * sizeof(Word);
  bytes += (double) records.size() * sizeof(lsdem_state_record);
  return bytes;
}
