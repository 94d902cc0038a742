// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: contact islands of impulse mode across ranks
   (lsdem_impulse_islands.h). The physics is the core's (core/impulse: union-find,
   label merge, ETM); this file moves labels, records and velocities between ranks.
------------------------------------------------------------------------- */

#include "lsdem_impulse_islands.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "comm.h"
#include "error.h"
#include "fix.h"
#include "irregular.h"
#include "lsdem_lammps_compat.h"
#include "memory.h"

#include <algorithm>
#include <cstring>
#include <mpi.h>
#include <tuple>

using namespace LAMMPS_NS;

void LsdemIslandStats::clear()
{
  iterations = sweeps = resting = contacts = 0;
  islands = cross = largest = rounds = etm_islands = max_sweeps = largest_contacts = 0;
  rest_threads = 0;
  etm_rounds = 0;
  absorbed = dissipated = released = truncated = resting_work = etm_work = 0.0;
  t_islands = t_etm = t_comm = t_rest = 0.0;
}

/* ---------------------------------------------------------------------- */

LsdemImpulseIslands::LsdemImpulseIslands(LAMMPS *lmp, Fix *comm_fix, AtomVecLsdem *av) :
  Pointers(lmp), fix(comm_fix), avec(av), what(NONE), nvert(0), nmax(0), parent(nullptr),
  size(nullptr), id(nullptr), label(nullptr), xlabel(nullptr), involved(nullptr),
  crossed(nullptr)
{
  irregular = new Irregular(lmp);
}

LsdemImpulseIslands::~LsdemImpulseIslands()
{
  delete irregular;
  destroy_per_atom();
}

void LsdemImpulseIslands::destroy_per_atom()
{
  memory->destroy(parent);
  memory->destroy(size);
  memory->destroy(id);
  memory->destroy(label);
  memory->destroy(xlabel);
  memory->destroy(involved);
  memory->destroy(crossed);
}

void LsdemImpulseIslands::grow(int n)
{
  if (n <= nmax) return;
  nmax = std::max(n, atom->nmax);
  destroy_per_atom();
  memory->create(parent, nmax, "impulse/lsdem:parent");
  memory->create(size, nmax, "impulse/lsdem:size");
  memory->create(id, nmax, "impulse/lsdem:id");
  memory->create(label, nmax, "impulse/lsdem:label");
  memory->create(xlabel, nmax, "impulse/lsdem:xlabel");
  memory->create(involved, nmax, "impulse/lsdem:involved");
  memory->create(crossed, nmax, "impulse/lsdem:crossed");
}

double LsdemImpulseIslands::memory_usage() const
{
  double bytes = (double) nmax * (2 * sizeof(int32_t) + 3 * sizeof(int64_t) + 2);
  bytes += (double) (items.capacity() + sent.capacity() + got.capacity()) *
      sizeof(Item);
  bytes += (double) order.capacity() * sizeof(Order);
  bytes += (double) ws.capacity();
  return bytes;
}

/* ----------------------------------------------------------------------
   the solver's body of a grain record: the core's grain (world inverse inertia from q);
   a sphere (LOCKED) keeps 3 degrees of freedom as under fix nve/lsdem: no rotation
------------------------------------------------------------------------- */

lsdem_status LsdemImpulseIslands::grain_body(const Item &it, lsdem_impulse_body &b,
                                             lsdem_error *err)
{
  const double *d = it.d;
  const double zero[3] = {0.0, 0.0, 0.0};
  const bool locked = it.flags & LOCKED;
  lsdem_status st = lsdem_impulse_body_grain(&b, it.ta, d[0], d + 1, d + 4, d + 8, d + 11,
                                             locked ? zero : d + 14, err);
  if (st == LSDEM_OK && locked)
    for (int k = 0; k < 9; k++) b.inv_inertia[k] = 0.0;
  return st;
}

/* the record of grain i (local or ghost) from the atom arrays: its state at the step's
   start */

void LsdemImpulseIslands::body_item(int i, Item &it) const
{
  memset(&it, 0, sizeof(it));
  it.kind = BODY;
  it.ta = atom->tag[i];
  it.owner = i < atom->nlocal ? comm->me : -1;
  it.index = i;
  it.flags = avec->shape_of(i)->sdf.kind == LSDEM_SDF_SPHERE ? LOCKED : 0;
  double *d = it.d;
  d[0] = atom->rmass[i];
  for (int k = 0; k < 3; k++) {
    d[1 + k] = avec->inertia[i][k];
    d[8 + k] = atom->x[i][k];
    d[11 + k] = atom->v[i][k];
    d[14 + k] = atom->omega[i][k];
  }
  for (int k = 0; k < 4; k++) d[4 + k] = avec->quat[i][k];
}

/* the record of a collision: its geometry, and the state of a prescribed side (a wall, or
   a grain outside the group) so that the solving rank can make that body */

void LsdemImpulseIslands::contact_item(const LsdemImpulseContact &c, int k,
                                       const lsdem_impulse_body *body, const char *moving,
                                       Item &it) const
{
  memset(&it, 0, sizeof(it));
  it.kind = CONTACT;
  it.owner = comm->me;
  it.index = k;
  it.ta = c.ta;
  it.tb = c.tb;
  it.key = c.key;
  if (!moving[c.i]) it.flags |= A_FIXED;
  if (c.j < 0 || !moving[c.j]) it.flags |= B_FIXED;
  const int fixed = it.flags;
  if (c.approaching) it.flags |= APPROACHING;
  if (c.resting) it.flags |= RESTING;
  double *d = it.d;
  for (int k = 0; k < 3; k++) {
    d[k] = c.c.point[k];
    d[3 + k] = c.c.normal[k];
  }
  d[6] = c.c.depth;
  d[7] = c.c.mu;
  d[8] = c.c.restitution;
  if (fixed) {
    const lsdem_impulse_body &f = body[(fixed & A_FIXED) ? c.c.a : c.c.b];
    for (int k = 0; k < 3; k++) {
      d[9 + k] = f.x[k];
      d[12 + k] = f.v[k];
      d[15 + k] = f.omega[k];
    }
  }
  for (int k = 0; k < 3; k++) d[18 + k] = c.P[k];
}

/* ---------------------------------------------------------------------- */

std::string LsdemImpulseIslands::resolve(LsdemImpulseContact *coll, int n,
                                         lsdem_impulse_body *body, const char *moving,
                                         const lsdem_island_params &prm, int warm_start,
                                         LsdemIslandStats &st)
{
  double t0 = MPI_Wtime();
  const double c0 = st.t_comm;
  const int ncross = label_islands(coll, n, moving, st) ? flag_cross(st) : 0;
  make_items(coll, n, body, moving);
  st.t_islands += MPI_Wtime() - t0 - (st.t_comm - c0);
  if (ncross > 0) {
    find_hosts(st);
    gather_cross(st);
  }
  t0 = MPI_Wtime();
  step_bodies = body;
  std::string mesg = solve_items(prm, warm_start, st);
  st.t_etm += MPI_Wtime() - t0;
  scatter_results(ncross > 0, coll, body, st);
  return mesg;
}

/* ----------------------------------------------------------------------
   labels of the pass's islands on all atoms (local and ghost); false when every island
   lies on one rank (no label was exchanged)
------------------------------------------------------------------------- */

bool LsdemImpulseIslands::label_islands(const LsdemImpulseContact *coll, int n,
                                       const char *moving, LsdemIslandStats &st)
{
  const int nlocal = atom->nlocal;
  nvert = nlocal + atom->nghost;
  grow(nvert);
  for (int v = 0; v < nvert; v++) {
    id[v] = atom->tag[v];
    involved[v] = crossed[v] = 0;
  }
  pairs.resize(2 * (size_t) n);
  int ghost_ends = 0;
  for (int k = 0; k < n; k++) {
    const int a = moving[coll[k].i] ? coll[k].i : LSDEM_ISLAND_NONE;
    const int b = (coll[k].j >= 0 && moving[coll[k].j]) ? coll[k].j : LSDEM_ISLAND_NONE;
    pairs[2 * k] = a;
    pairs[2 * k + 1] = b;
    if (a >= 0) involved[a] = 1;
    if (b >= 0) involved[b] = 1;
    ghost_ends += (a >= nlocal) + (b >= nlocal);
  }
  lsdem_islands_build(nvert, id, n, pairs.data(), parent, size, label);

  double t0 = MPI_Wtime();
  int any = 0;
  MPI_Allreduce(&ghost_ends, &any, 1, MPI_INT, MPI_MAX, world);
  st.t_comm += MPI_Wtime() - t0;
  if (!any) return false;  // every island lies on one rank: nothing to exchange

  int rounds = 0, changed = 1;
  while (changed) {
    t0 = MPI_Wtime();
    for (int v = 0; v < nvert; v++) xlabel[v] = label[v];
    what = FWD_LABEL;
    LsdemCompat::forward_comm(comm, fix, 1);
    st.t_comm += MPI_Wtime() - t0;
    int mine = merge_received(nlocal, nvert);
    t0 = MPI_Wtime();
    for (int v = 0; v < nvert; v++) xlabel[v] = label[v];
    what = REV_LABEL;
    LsdemCompat::reverse_comm(comm, fix, 1);
    st.t_comm += MPI_Wtime() - t0;
    mine |= merge_received(0, nlocal);
    t0 = MPI_Wtime();
    MPI_Allreduce(&mine, &changed, 1, MPI_INT, MPI_MAX, world);
    st.t_comm += MPI_Wtime() - t0;
    rounds++;
  }
  what = NONE;
  st.rounds = std::max(st.rounds, rounds);
  return true;
}

/* ---------------------------------------------------------------------- */

const int64_t *LsdemImpulseIslands::island_labels(const LsdemImpulseContact *coll, int n,
                                          const char *moving, LsdemIslandStats &st)
{
  label_islands(coll, n, moving, st);
  return label;
}

/* atoms v in [lo, hi) take the smaller label they received (core: lsdem_islands_merge) */

int LsdemImpulseIslands::merge_received(int lo, int hi)
{
  mbody.clear();
  mlabel.clear();
  for (int v = lo; v < hi; v++)
    if (xlabel[v] < label[v]) {
      mbody.push_back(v);
      mlabel.push_back(xlabel[v]);
    }
  if (mbody.empty()) return 0;
  return lsdem_islands_merge(nvert, parent, label, (int) mbody.size(), mbody.data(),
                             mlabel.data());
}

/* ----------------------------------------------------------------------
   which local islands span ranks: those with a ghost in a collision here, or a grain that
   is a ghost in a collision on another rank (told to its owner by one reverse
   communication); such grains take part even without a collision here. Returns the number
   of such islands' pieces on all ranks.
------------------------------------------------------------------------- */

int LsdemImpulseIslands::flag_cross(LsdemIslandStats &st)
{
  const int nlocal = atom->nlocal;
  const double t0 = MPI_Wtime();
  for (int v = 0; v < nvert; v++) xlabel[v] = (v >= nlocal && involved[v]) ? 1 : 0;
  what = REV_FLAG;
  LsdemCompat::reverse_comm(comm, fix, 1);
  what = NONE;
  st.t_comm += MPI_Wtime() - t0;
  int pieces = 0;
  for (int v = 0; v < nvert; v++) {
    if (!xlabel[v]) continue;
    if (v < nlocal) involved[v] = 1;
    const int32_t r = lsdem_islands_find(parent, v);
    pieces += !crossed[r];
    crossed[r] = 1;
  }
  int all = 0;
  const double t1 = MPI_Wtime();
  MPI_Allreduce(&pieces, &all, 1, MPI_INT, MPI_SUM, world);
  st.t_comm += MPI_Wtime() - t1;
  return all;
}

/* ----------------------------------------------------------------------
   the records of every island this rank takes part in: owned grains in a collision and
   the collisions held here, each with its island's label; spans = 1 when the island
   spans ranks
------------------------------------------------------------------------- */

void LsdemImpulseIslands::make_items(const LsdemImpulseContact *coll, int n,
                                     const lsdem_impulse_body *body, const char *moving)
{
  items.clear();
  Item it;
  for (int v = 0; v < atom->nlocal; v++) {
    if (!involved[v]) continue;
    body_item(v, it);
    for (int k = 0; k < 3; k++) {  // its velocities now: the step's body
      it.d[11 + k] = body[v].v[k];
      it.d[14 + k] = body[v].omega[k];
    }
    it.label = label[v];
    it.spans = crossed[lsdem_islands_find(parent, v)];
    items.push_back(it);
  }
  for (int k = 0; k < n; k++) {
    const int e = moving[coll[k].i] ? coll[k].i : coll[k].j;
    contact_item(coll[k], k, body, moving, it);
    it.label = label[e];
    it.spans = crossed[lsdem_islands_find(parent, e)];
    items.push_back(it);
  }
}

/* ----------------------------------------------------------------------
   the host of every island spanning ranks that this rank takes part in: the rank holding
   most of its collisions, ties the lowest, decided by the island's directory rank
   (label mod ranks); on return queries holds (label, host in count) sorted by label
------------------------------------------------------------------------- */

void LsdemImpulseIslands::find_hosts(LsdemIslandStats &st)
{
  const double t0 = MPI_Wtime();
  queries.clear();
  for (const Item &it : items)
    if (it.spans) queries.push_back({it.label, it.kind == CONTACT ? 1 : 0, comm->me});
  std::sort(queries.begin(), queries.end(),
            [](const Query &a, const Query &b) { return a.label < b.label; });
  size_t m = 0;  // one query per label, with this rank's count of its collisions
  for (size_t k = 0; k < queries.size(); k++) {
    if (m > 0 && queries[m - 1].label == queries[k].label) queries[m - 1].count += queries[k].count;
    else queries[m++] = queries[k];
  }
  queries.resize(m);
  proclist.resize(m);
  for (size_t k = 0; k < m; k++) proclist[k] = (int) (queries[k].label % comm->nprocs);
  exchange(queries, answers);

  // the directory: per label the largest count, ties the lowest rank; one reply per query
  std::sort(answers.begin(), answers.end(), [](const Query &a, const Query &b) {
    return a.label < b.label || (a.label == b.label && a.rank < b.rank);
  });
  proclist.resize(answers.size());
  for (size_t k = 0; k < answers.size();) {
    size_t e = k, best = k;
    while (e < answers.size() && answers[e].label == answers[k].label) {
      if (answers[e].count > answers[best].count) best = e;
      e++;
    }
    st.cross++;
    const int host = answers[best].rank;
    for (size_t r = k; r < e; r++) {
      proclist[r] = answers[r].rank;
      answers[r].count = host;
    }
    k = e;
  }
  exchange(answers, queries);
  std::sort(queries.begin(), queries.end(),
            [](const Query &a, const Query &b) { return a.label < b.label; });
  st.t_comm += MPI_Wtime() - t0;
}

/* the records of islands spanning ranks go to their hosts; what this rank hosts joins its
   own islands' records */

void LsdemImpulseIslands::gather_cross(LsdemIslandStats &st)
{
  const double t0 = MPI_Wtime();
  sent.clear();
  proclist.clear();
  size_t keep = 0;
  for (size_t k = 0; k < items.size(); k++) {
    if (!items[k].spans) {
      items[keep++] = items[k];
      continue;
    }
    Query probe = {items[k].label, 0, 0};
    auto h = std::lower_bound(queries.begin(), queries.end(), probe,
                              [](const Query &a, const Query &b) { return a.label < b.label; });
    if (h == queries.end() || h->label != items[k].label)
      error->one(FLERR, "fix impulse/lsdem: island {} has no host rank (internal error)",
                 items[k].label);
    sent.push_back(items[k]);
    proclist.push_back(h->count);
  }
  items.resize(keep);
  exchange(sent, got);
  items.insert(items.end(), got.begin(), got.end());
  st.t_comm += MPI_Wtime() - t0;
}

/* ----------------------------------------------------------------------
   every island whose records are here, in label order; each assembled in the order of
   global ids (so that any rank count gives the same bits)
------------------------------------------------------------------------- */

std::string LsdemImpulseIslands::solve_items(const lsdem_island_params &prm, int warm,
                                             LsdemIslandStats &st)
{
  // sorted by (label, kind, ta, tb, key), unique to each record: the keys with the record's
  // place are sorted (a fifth of a record's bytes to move) and the islands read the records
  // through them
  order.resize(items.size());
  for (size_t k = 0; k < items.size(); k++) {
    const Item &it = items[k];
    order[k] = {it.label, it.ta, it.tb, it.kind, it.key, (int32_t) k};
  }
  std::sort(order.begin(), order.end(), [](const Order &a, const Order &b) {
    return std::tie(a.label, a.kind, a.ta, a.tb, a.key) <
        std::tie(b.label, b.kind, b.ta, b.tb, b.key);
  });
  results.clear();
  std::string first;
  for (size_t k = 0; k < order.size();) {
    size_t e = k;
    while (e < order.size() && order[e].label == order[k].label) e++;
    std::string mesg = solve_island(&order[k], (int) (e - k), prm, warm, st);
    if (first.empty()) first = mesg;
    k = e;
  }
  return first;
}

/* one island (its records' keys o[0..n), in solve order): its grains (tag order), then its
   contacts (id order) with their bodies found by tag, or a prescribed body made from the
   record; ETM; the grains' new velocities */

std::string LsdemImpulseIslands::solve_island(const Order *o, int n,
                                              const lsdem_island_params &prm, int warm,
                                              LsdemIslandStats &st)
{
  lsdem_error err;
  auto it = [&](int k) -> const Item & { return items[o[k].at]; };
  int nb = 0;
  while (nb < n && o[nb].kind == BODY) nb++;
  bool approaching = false;
  for (int k = nb; k < n; k++) approaching |= (it(k).flags & APPROACHING) != 0;
  if (!approaching) return std::string();  // nothing to resolve; velocities unchanged
  bodies.resize(nb);
  for (int k = 0; k < nb; k++) {
    const Item &g = it(k);
    if (g.owner == comm->me)  // an owned grain: the step's body, made from the same record
      bodies[k] = step_bodies[g.index];
    else if (grain_body(g, bodies[k], &err) != LSDEM_OK)
      return fmt::format("grain {}: {}", o[k].ta, err.msg);
  }
  auto grain_index = [&](int64_t tag) {
    const Order *p = std::lower_bound(o, o + nb, tag,
                                      [](const Order &a, int64_t t) { return a.ta < t; });
    return (p < o + nb && p->ta == tag) ? (int) (p - o) : -1;
  };
  int cursor = 0;  // the contacts come in increasing ta: side a's grain by a forward walk
  auto grain_a = [&](int64_t tag) {
    while (cursor < nb && o[cursor].ta < tag) cursor++;
    return (cursor < nb && o[cursor].ta == tag) ? cursor : -1;
  };
  auto prescribed = [&](const Item &c, int64_t tag) {
    lsdem_impulse_body w;
    lsdem_impulse_body_wall(&w, tag, c.d + 9, c.d + 12, c.d + 15, nullptr);
    bodies.push_back(w);
    return (int) bodies.size() - 1;
  };
  contacts.resize(n - nb);
  resting.resize(n - nb);
  impulse.resize(3 * (size_t) (n - nb));
  collision.resize(3 * (size_t) (n - nb));
  int nrest = 0;
  for (int k = nb; k < n; k++) {
    const Item &c = it(k);
    lsdem_impulse_contact &ct = contacts[k - nb];
    for (int d = 0; d < 3; d++) {
      ct.point[d] = c.d[d];
      ct.normal[d] = c.d[3 + d];
      impulse[3 * (k - nb) + d] = c.d[18 + d];
    }
    ct.depth = c.d[6];
    ct.mu = c.d[7];
    ct.restitution = c.d[8];
    ct.a = (c.flags & A_FIXED) ? prescribed(c, c.ta) : grain_a(c.ta);
    ct.b = (c.flags & B_FIXED) ? prescribed(c, c.tb) : grain_index(c.tb);
    resting[k - nb] = (c.flags & RESTING) ? 1 : 0;
    nrest += resting[k - nb];
    if (ct.a < 0 || ct.b < 0)
      return fmt::format("island {}: contact of grains {} and {} without its grain record "
                         "(internal error)", o[0].label, c.ta, c.tb);
  }
  const int nc = n - nb, nbodies = (int) bodies.size();
  const size_t need = lsdem_island_workspace_size(nbodies, nc);
  if (ws.size() < need) ws.resize(need);
  lsdem_island_result res;
  double(*P)[3] = reinterpret_cast<double(*)[3]>(impulse.data());
  double(*J)[3] = reinterpret_cast<double(*)[3]>(collision.data());
  const lsdem_status s = lsdem_island_solve(bodies.data(), nbodies, contacts.data(), nc,
                                            nrest ? resting.data() : nullptr, P, J, warm,
                                            &prm, ws.data(), ws.size(), &res, &err);
  st.islands++;
  st.largest = std::max(st.largest, nb);
  st.largest_contacts = std::max(st.largest_contacts, nc);
  st.contacts += nc;
  if (s != LSDEM_ERR_ARG) {
    st.iterations += res.etm.iterations;
    st.etm_islands += res.etm_ran;
    st.etm_rounds = std::max(st.etm_rounds, res.etm.rounds);
    st.absorbed += res.etm.absorbed;
    st.dissipated += res.etm.dissipated;
    st.released += res.etm.released;
    st.truncated += res.etm.truncated;
    st.resting += res.nresting;
    st.sweeps += (bigint) res.rest.sweeps * res.nresting;
    st.max_sweeps = std::max(st.max_sweeps, res.rest.sweeps);
    st.rest_threads = std::max(st.rest_threads, res.rest.threads);
    st.resting_work += res.rest.work;
    st.etm_work += res.etm.work;
    st.t_rest += res.rest_seconds;
  }
  for (int k = 0; k < nb; k++) {
    Result r;
    r.owner = it(k).owner;
    r.index = it(k).index;
    for (int d = 0; d < 3; d++) {
      r.v[d] = bodies[k].v[d];
      r.omega[d] = bodies[k].omega[d];
    }
    results.push_back(r);
  }
  for (int k = 0; k < nc; k++) {
    Result r;
    r.owner = it(nb + k).owner;
    r.index = -1 - it(nb + k).index;
    for (int d = 0; d < 3; d++) {
      r.v[d] = resting[k] ? P[k][d] : 0.0;
      r.omega[d] = J[k][d];
    }
    results.push_back(r);
  }
  return s == LSDEM_OK ? std::string() : std::string(err.msg);
}

/* ----------------------------------------------------------------------
   new velocities to the grains' owners
------------------------------------------------------------------------- */

void LsdemImpulseIslands::scatter_results(bool remote, LsdemImpulseContact *coll,
                                          lsdem_impulse_body *body, LsdemIslandStats &st)
{
  auto apply = [&](const Result &r) {
    if (r.index < 0) {
      LsdemImpulseContact &c = coll[-1 - r.index];
      for (int d = 0; d < 3; d++) {
        c.P[d] = r.v[d];
        c.J[d] += r.omega[d];
      }
      return;
    }
    for (int d = 0; d < 3; d++) {
      body[r.index].v[d] = r.v[d];
      body[r.index].omega[d] = r.omega[d];
    }
  };
  const double t0 = MPI_Wtime();
  back.clear();
  proclist.clear();
  for (const Result &r : results) {
    if (r.owner == comm->me) apply(r);
    else {
      back.push_back(r);
      proclist.push_back(r.owner);
    }
  }
  if (remote) {  // islands spanning ranks exist somewhere: every rank takes part
    exchange(back, results);
    for (const Result &r : results) apply(r);
  }
  st.t_comm += MPI_Wtime() - t0;
}

/* ----------------------------------------------------------------------
   send[k] to rank proclist[k] (LAMMPS Irregular); returns the count received
------------------------------------------------------------------------- */

template <class T> int LsdemImpulseIslands::exchange(const std::vector<T> &send, std::vector<T> &recv)
{
  const int nrecv = irregular->create_data((int) send.size(), const_cast<int *>(proclist.data()), 1);
  recv.resize(nrecv);
  irregular->exchange_data((char *) const_cast<T *>(send.data()), sizeof(T), (char *) recv.data());
  irregular->destroy_data();
  return nrecv;
}

/* ----------------------------------------------------------------------
   ghost communication: labels forward (owner -> ghosts, min), labels and flags reverse
   (ghosts -> owner, min / max); a ghost relays what it received (corner copies)
------------------------------------------------------------------------- */

int LsdemImpulseIslands::pack_forward(int n, int *list, double *buf)
{
  for (int k = 0; k < n; k++) buf[k] = ubuf(xlabel[list[k]]).d;
  return n;
}

void LsdemImpulseIslands::unpack_forward(int n, int first, double *buf)
{
  for (int k = 0; k < n; k++)
    xlabel[first + k] = std::min(xlabel[first + k], (int64_t) ubuf(buf[k]).i);
}

int LsdemImpulseIslands::pack_reverse(int n, int first, double *buf)
{
  for (int k = 0; k < n; k++) buf[k] = ubuf(xlabel[first + k]).d;
  return n;
}

void LsdemImpulseIslands::unpack_reverse(int n, int *list, double *buf)
{
  for (int k = 0; k < n; k++) {
    const int64_t got_k = ubuf(buf[k]).i;
    int64_t &mine = xlabel[list[k]];
    mine = what == REV_FLAG ? std::max(mine, got_k) : std::min(mine, got_k);
  }
}
