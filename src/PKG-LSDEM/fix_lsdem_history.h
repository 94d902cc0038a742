/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package for LAMMPS: the contact state of each grain's pairs (internal fix).

   An internal fix (created by pair_style lsdem and by each fix wall/lsdem, never by
   the user). Each owned grain keeps, per partner it touched or was near on the last
   step, the state the core carries for a master from step to step (core/contact,
   lsdem_pair_state): the pair's node list (head and entries) and the shear history of
   ITS OWN nodes, partners in the order they were visited. The state travels with the grain
   (exchange) and is saved in restart files (as lsdem_state_record records, the layout of
   earlier versions, so that their restart files still load).

   Storage: one pool of 64-byte slots, updated in place. Each pair's state is a run of
   slots: its list head (two slots), its list entries, its shear entries (the layout of
   earlier versions); an atom's pairs' runs lie back to back, in the order they were
   visited (so that a step reads them in the order they lie). The kernel reads an atom's
   runs and writes each pair's new state into its lane's scratch; at the end of the atom
   the scratch is copied over the atom's old runs when it fits there (an atom's room is
   reserved with an eighth more than it used), else into new room, the old becoming
   garbage, reclaimed by compacting the pool at the end of a step once an eighth of it is
   garbage. The slots are held in chunks that never move during a step: each lane (one
   per thread, pair_style lsdem/omp) takes new room from its own chunks, and an atom's
   room is only written by the lane visiting the atom, so that writing is race-free by
   construction; reading (find) is of the last step's states. Use per step:
     begin_step(nlanes);
     for each owned grain i, by the thread of lane L:
       begin_atom(L);
       for each partner j: find(i, tag_j, in) -> this pair's state (the kernel's input);
                           reserve(L, list_cap, shear_cap) -> room for the kernel's output;
                           commit(L, tag_j, out);
       end_atom(L, i);  // i's state := the committed pairs; untouched pairs are dropped
     end_step();        // grains not visited lose their state
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(LSDEM_HISTORY,FixLsdemHistory);
// clang-format on
#else

#ifndef LMP_FIX_LSDEM_HISTORY_H
#define LMP_FIX_LSDEM_HISTORY_H

#include "fix.h"
#include "lsdem_kernel.h"

#include <vector>

namespace LAMMPS_NS {

class FixLsdemHistory : public Fix {
 public:
  FixLsdemHistory(class LAMMPS *, int, char **);
  ~FixLsdemHistory() override;
  int setmask() override;

  // per-step interface for the contact styles
  void begin_step(int nlanes = 1);
  bool find(int i, tagint partner, lsdem_pair_state &in) const;
  bool holds(int i) const { return nslice[i] > 0; }  // atom i keeps state
  void begin_atom(int lane);
  lsdem_pair_state reserve(int lane, int list_cap, int shear_cap);  // out.shear: place_shear
  static void place_shear(lsdem_pair_state &out);  // after detection: behind the list
  void commit(int lane, tagint partner, const lsdem_pair_state &out);
  void end_atom(int lane, int i);
  void end_step();
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  double memory_usage() override;
  // what the pool holds: pair states, node-list entries, shear entries, and the bytes of
  // the states (runs of 64-byte slots) in use and reserved (memory_usage: all the store's)
  void held(double &pairs, double &entries, double &shears, double &bytes_used) const;

 private:
  // a slot holds a shear entry or a list entry; a list head takes two
  union Slot {
    lsdem_shear_hist shear;
    lsdem_nodelist_entry entry;
    unsigned char bytes[64];
  };
  static constexpr int HEAD_SLOTS = 2;
  static constexpr int MIN_CHUNK_SLOTS = 1024;  // 64 KB
  struct Slice {   // one pair's state: its run of slots
    tagint partner;
    Slot *run;     // (set when its atom ends)
    int nentry;    // list entries; -1: no list
    int nshear;
  };
  struct Chunk {   // slots that stay put until the pool is compacted
    Slot *slot;
    int used, cap;
  };
  struct Lane {    // one thread's part
    std::vector<Slice> slice[2];  // slice[cur]: the last step's; slice[1 - cur] written
    int ns[2];                    // slices used in each
    std::vector<Chunk> chunk;     // where the lane's new room is taken from
    Slot *scratch;                // the new state of the atom being visited
    int maxscratch;
    int atom_used;                // its slots in the scratch
    int atom_slice;               // where its slices start
    int atom_records;             // and the records its committed pairs take
    int maxrecords;               // the largest state written to this lane this step
  };
  std::vector<Lane> lanes;    // at least the lanes of the last step (their chunks hold runs)
  int nlanes;                 // lanes of the current step
  int cur;                    // which slice lists hold the states
  int nmax_atom;              // length of the per-atom arrays
  int *lane_of, *sfirst, *nslice;  // per atom: its slices in lanes[lane_of].slice[cur]
  Slot **room;                // per atom: where its runs lie
  int *nroom;                 // and the slots reserved there
  int *visited, generation;   // atoms visited since begin_step() carry its generation
  int maxrecords;             // largest state seen, in records (sizes exchange buffers)
  std::vector<lsdem_state_record> records;  // scratch for packing and unpacking
  std::vector<const Slice *> by_partner;     // scratch: an atom's pairs in packing order

  void init_lane(Lane &l);
  void release_chunks(std::vector<Chunk> &chunks);
  Slot *take_slots(Lane &l, int n);
  static int slots_of(const lsdem_pair_state &st);
  static int slice_slots(const Slice &s);
  static int room_for(int used);
  void scratch_room(Lane &l, int need);
  const Slice *slice_of(int i, tagint partner) const;
  static void slice_state(const Slice &s, lsdem_pair_state &st);
  int keep_pair(Lane &l, int which, tagint partner, const lsdem_pair_state &st);
  void keep_atom(Lane &l, int which, int i);
  void compact_if_wasteful();
  void note_records(int n);
  int count_records(int i) const;
  int pack_state(int i, double *buf);
  int unpack_state(int i, const double *buf);
};

}    // namespace LAMMPS_NS

#endif
#endif
