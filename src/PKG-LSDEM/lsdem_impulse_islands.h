/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package for LAMMPS: contact islands of impulse mode across ranks (report §4.5),
   for fix impulse/lsdem. One call resolves one pass's collisions:

   1. islands: union-find over this rank's local and ghost grains (core: lsdem_islands_build),
      then the smallest tag of each island spread between ranks through ghost communication
      (forward: owner -> ghost copies, reverse: ghost copies -> owner, min), rounds repeated
      until no label changes anywhere (MPI_Allreduce of a flag per round; the way LAMMPS's
      compute cluster/atom labels clusters). A round carries a label across every rank
      boundary once, so the rounds grow with the ranks an island spans, not its grains; no
      rank ever holds more of the graph than its own contacts. When no collision touches a
      ghost on any rank, there is nothing to exchange (no round);
   2. an island is cross-rank when one of its grains is a ghost in a collision somewhere (one
      reverse communication of that flag tells the owners). An island wholly on one rank is
      solved there with no communication;
   3. a cross-rank island is solved on the rank that holds most of its collisions (ties: the
      lowest rank), found by a directory rank per island label (label mod ranks): ranks send
      it their counts, it answers with the host (LAMMPS Irregular, twice); owners send the
      island's grains, holders its contacts (Irregular), the host solves it and sends each
      grain's new velocities back to its owner (Irregular);
   4. every island, local or gathered, is assembled from the same records sorted by global
      ids (bodies by tag, contacts by (tag a, tag b, order in the pair)) and solved by the
      core's ETM (lsdem_etm_solve): the result does not depend on the rank count.
   Periodic boundaries are not handled (an island that wraps around the box has no single
   position per grain); fix impulse/lsdem refuses them.
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_IMPULSE_ISLANDS_H
#define LMP_LSDEM_IMPULSE_ISLANDS_H

#include "pointers.h"
#include "lsdem_kernel.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

// one glued contact held by this rank (the rank of its master), at the step's poses: the
// core's step contact (i, j: atom indices, local or ghost; b a wall: j = -1 - w)
typedef lsdem_impulse_step_contact LsdemImpulseContact;

// what one pass did, summed (or the largest) over the islands this rank solved
struct LsdemIslandStats {
  bigint iterations, sweeps;   // ETM group iterations; resting sweeps x contacts
  int islands, cross, largest, rounds, etm_islands, max_sweeps, largest_contacts, etm_rounds;
  int rest_threads;            // the most threads that shared an island's resting sweeps
  bigint resting, contacts;    // resting contacts solved; contacts of the islands solved
  double absorbed, dissipated, released, truncated, resting_work;
  double etm_work;             // the collision impulses' exact work (lsdem_etm_result.work)
  double t_islands, t_etm, t_comm;  // seconds
  double t_rest;                    // of t_etm: the resting stage
  void clear();
};

class LsdemImpulseIslands : protected Pointers {
 public:
  LsdemImpulseIslands(class LAMMPS *, class Fix *comm_fix, class AtomVecLsdem *);
  ~LsdemImpulseIslands() override;

  // Resolve the islands of contacts coll[0..n) (held here) that have one needing it
  // (approaching) by lsdem_island_solve (warm_start: apply the resting contacts' P first).
  // body: the step's bodies (atoms local and ghost, then walls), with current velocities;
  // moving[i]: atom i is integrated (in the group), else it acts as a wall of prescribed
  // velocity. New velocities are written to the bodies of owned grains (the fix sends them
  // to the ghosts' bodies), the resting contacts' new impulses to coll[k].P, the collision
  // impulses added to coll[k].J. Collective. Returns this rank's first island report (""
  // when all converged).
  std::string resolve(LsdemImpulseContact *coll, int n, lsdem_impulse_body *body,
                      const char *moving, const lsdem_island_params &prm, int warm_start,
                      LsdemIslandStats &st);

  // The island label (the smallest tag of its grains) of every atom, local and ghost, for
  // the contacts coll[0..n) between grains with moving[i] set (the same on every rank;
  // valid until the next call). Collective.
  const int64_t *island_labels(const LsdemImpulseContact *coll, int n, const char *moving,
                               LsdemIslandStats &st);

  // ghost communication of labels and flags, through the fix's pack/unpack methods
  bool exchanging() const { return what != NONE; }
  int pack_forward(int n, int *list, double *buf);
  void unpack_forward(int n, int first, double *buf);
  int pack_reverse(int n, int first, double *buf);
  void unpack_reverse(int n, int *list, double *buf);
  double memory_usage() const;

  // one island's grain or contact as the solver takes it (and ranks send it)
  struct Item {
    int64_t label;
    int64_t ta, tb;  // body: ta = its tag; contact: the tags of a and b (wall: -(w + 1))
    int32_t kind;    // BODY or CONTACT
    int32_t owner;   // body: owning rank; contact: the rank holding it
    int32_t index;   // body: local index there; contact: its place in that rank's list
    int32_t key;     // contact: its place among its pair's contacts
    int32_t flags;   // body: LOCKED; contact: A_FIXED, B_FIXED (that side a prescribed
                     // body), APPROACHING, RESTING
    int32_t spans;   // 1: the island spans ranks
    double d[21];    // body: mass, I0[3], q[4], x[3], v[3], omega[3];
                     // contact: point[3], normal[3], depth, mu, e, then the prescribed
                     // side's x[3], v[3], omega[3], then the resting impulse P[3]
  };
  enum { BODY = 0, CONTACT = 1 };
  enum { LOCKED = 1, A_FIXED = 1, B_FIXED = 2, APPROACHING = 4, RESTING = 8 };
  // a grain's body in the solver (also the fix's step bodies): spheres keep no rotation
  static lsdem_status grain_body(const Item &, lsdem_impulse_body &, lsdem_error *);
  // the record of owned or ghost grain i from the atom arrays (its state at the step's start)
  void body_item(int i, Item &) const;

 private:
  enum Exchange { NONE, FWD_LABEL, REV_LABEL, REV_FLAG };
  struct Result {  // a grain's new velocities (index >= 0: its local index), or a contact's
                   // resting impulse (in v) and collision impulse (in omega), index = -1 -
                   // its place in the holder's list
    int32_t owner, index;
    double v[3], omega[3];
  };
  struct Query {
    int64_t label;
    int32_t count, rank;
  };
  struct Order {  // an Item's sort key and its place in items
    int64_t label, ta, tb;
    int32_t kind, key, at;
  };

  class Fix *fix;
  class AtomVecLsdem *avec;
  class Irregular *irregular;
  Exchange what;
  int nvert;  // atoms (local + ghost) of the pass
  // per atom, grown with atom->nmax
  int nmax;
  int32_t *parent, *size;
  int64_t *id, *label, *xlabel;  // tags; island labels; labels in exchange
  char *involved, *crossed;      // in a collision; (root:) its island spans ranks
  std::vector<int32_t> pairs, mbody;
  std::vector<int64_t> mlabel;
  std::vector<Item> items, sent, got;
  std::vector<Order> order;  // items' keys in solve order: by island, then global ids
  std::vector<Result> results, back;
  std::vector<Query> queries, answers;
  std::vector<int> proclist;
  std::vector<char> ws;                  // ETM workspace
  std::vector<lsdem_impulse_body> bodies;
  const lsdem_impulse_body *step_bodies = nullptr;  // resolve's body: owned grains' bodies
  std::vector<lsdem_impulse_contact> contacts;
  std::vector<uint8_t> resting;
  std::vector<double> impulse, collision;  // 3 per contact

  void grow(int);
  void destroy_per_atom();
  bool label_islands(const LsdemImpulseContact *, int, const char *, LsdemIslandStats &);
  int merge_received(int lo, int hi);
  int flag_cross(LsdemIslandStats &);
  void make_items(const LsdemImpulseContact *, int, const lsdem_impulse_body *, const char *);
  void contact_item(const LsdemImpulseContact &, int k, const lsdem_impulse_body *,
                    const char *, Item &) const;
  void find_hosts(LsdemIslandStats &);
  void gather_cross(LsdemIslandStats &);
  std::string solve_items(const lsdem_island_params &, int warm, LsdemIslandStats &);
  std::string solve_island(const Order *, int, const lsdem_island_params &, int warm,
                           LsdemIslandStats &);
  void scatter_results(bool remote, LsdemImpulseContact *, lsdem_impulse_body *,
                       LsdemIslandStats &);
  template <class T> int exchange(const std::vector<T> &, std::vector<T> &);
};

}    // namespace LAMMPS_NS

#endif
