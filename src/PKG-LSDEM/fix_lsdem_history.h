/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package for LAMMPS: the contact state of each grain's pairs (internal fix).

   An internal fix (created by pair_style lsdem and by each fix wall/lsdem, never by
   the user). Each owned grain keeps, per partner it touched or was near on the last
   step, the state the core carries for a master from step to step (core/contact,
   lsdem_pair_state): the pair's node list (head and entries) and the shear history of
   ITS OWN nodes. Partners are held sorted by tag. The state travels with the grain
   (exchange) and is saved in restart files (as lsdem_state_record records, the layout of
   earlier versions, so that their restart files still load).

   Storage: all grains' states sit in a pool of 8-byte words, pair after pair in the
   order the styles visit the grains, each pair's state in one run: its list head, its
   list entries (four words each, eight with the cells' samples against a grid:
   lsdem_contact.h), its shear entries (eight words each), so that a step reads one stream
   and writes one. A step reads the current pool and writes the next one, so the kernel
   writes its output where it will be read next step (no copy). A pool is split into
   lanes, one per thread (pair_style lsdem/omp): each lane is written by one thread only
   and each grain's state lies in one lane, so that writing is race-free by construction
   (a pair's state has one owner, its master's lane); reading (find) is of the current
   pool only. Use per step:
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
#include "lsdem_lane_padding.h"

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
  // room for a pair's output: list_words words of list entries, shear_cap shear entries
  lsdem_pair_state reserve(int lane, int list_words, int shear_cap);  // out.shear: place_shear
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
  // what the current pool holds: pair states, node-list entries, shear entries, and the
  // bytes they take; memory_usage(): all the store reserves
  void held(double &pairs, double &entries, double &shears, double &bytes_used) const;

 private:
  typedef uint64_t Word;
  static constexpr int HEAD_WORDS = sizeof(lsdem_nodelist_head) / sizeof(Word);
  static constexpr int SHEAR_WORDS = sizeof(lsdem_shear_hist) / sizeof(Word);
  struct Slice {   // one pair's state in a pool: its run of words from `first`
    tagint partner;
    int first, list_valid, nentry, nlistword, nshear;
  };
  struct Pool {    // one lane: the states of its atoms, one after the other
    std::vector<Slice> slice;
    Word *word;
    int ns, nword, maxword;  // used; words allocated
    int atom_slice;          // where the atom being visited starts (while written)
    int atom_records;        // and the records its committed pairs take
    int maxrecords;          // the largest state written to this lane this step
    bool kept;               // some atom's state was written to this lane this step
    LsdemLanePadding apart;  // written by its thread at every pair: off the next lane's lines
  };
  std::vector<Pool> pool[2];  // the lanes of the two pools
  int cur;                    // pool[cur] holds the states; pool[1 - cur] is written
  int nmax_atom;              // length of the per-atom arrays
  int *lane_of, *sfirst, *nslice;  // per atom: its slices in pool[cur][lane_of]
  int *visited, generation;   // atoms visited since begin_step() carry its generation
  bool maybe_held;            // false: no atom holds a state in pool[cur]
  int maxrecords;             // largest state seen, in records (sizes exchange buffers)
  std::vector<lsdem_state_record> records;  // scratch for packing and unpacking

  void pool_room(Pool &p, int ns, int nword);
  void release(Pool &p);
  lsdem_pair_state pair_room(Pool &p, int list_words, int shear_cap);
  static int keep_pair(Pool &p, tagint partner, const lsdem_pair_state &st);
  static void slice_state(const Pool &p, const Slice &s, lsdem_pair_state &st);
  void note_records(int n);
  int count_records(int i) const;
  int pack_state(int i, double *buf);
  int unpack_state(int i, const double *buf);
};

}    // namespace LAMMPS_NS

#endif
#endif
