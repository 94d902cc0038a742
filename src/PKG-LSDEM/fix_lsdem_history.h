/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package for LAMMPS: the contact state of each grain's pairs (internal fix).

   An internal fix (created by pair_style lsdem and by each fix wall/lsdem, never by
   the user). Each owned grain keeps, per partner it touched or was near on the last
   step, the state the core carries for a master from step to step (core/contact,
   lsdem_pair_state): the pair's node list (head and entries) and the shear history of
   ITS OWN nodes. Partners are held sorted by tag. The state travels with the grain
   (exchange) and is saved in restart files (as lsdem_state_record records, the layout of
   earlier versions, so that their restart files still load).

   Storage: all grains' states sit in pools (slices with their list heads, list entries,
   shear entries), in the order the styles visit the grains; a step reads the current
   pools and writes the next ones, so the kernel writes its output where it will be read
   next step (no copy) and the pools are walked in order (the hardware prefetcher
   follows). Use per step:
     begin_step();
     for each owned grain i:
       begin_atom();
       for each partner j: find(i, tag_j, in) -> this pair's state (the kernel's input);
                           reserve(list_cap, shear_cap) -> room for the kernel's output;
                           commit(tag_j, out);
       end_atom(i);  // i's state := the committed pairs; untouched pairs are dropped
     end_step();     // grains not visited lose their state
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
  void begin_step();
  bool find(int i, tagint partner, lsdem_pair_state &in) const;
  bool holds(int i) const { return nslice[i] > 0; }  // atom i keeps state
  void begin_atom();
  lsdem_pair_state reserve(int list_cap, int shear_cap);
  void commit(tagint partner, const lsdem_pair_state &out);
  void end_atom(int i);
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

 private:
  struct Slice {   // one pair's state in a pool
    tagint partner;
    lsdem_nodelist_head head;
    int list_valid;
    int entry_start, nshear, shear_start;  // entries: head.count from entry_start
  };
  struct Pool {    // the states of all atoms, one after the other
    std::vector<Slice> slice;
    std::vector<lsdem_nodelist_entry> entry;
    std::vector<lsdem_shear_hist> shear;
    int ns, nentry, nshear;  // used
  };
  Pool pool[2];
  int cur;                    // pool[cur] holds the states; pool[1 - cur] is written
  int nmax_atom;              // length of the per-atom arrays
  int *sfirst, *nslice;       // per atom: its slices in pool[cur]
  int *visited, generation;   // atoms visited since begin_step() carry its generation
  int atom_slice;             // where the atom being visited starts in the next pool
  int atom_records;           // and the records its committed pairs take
  int maxrecords;             // largest state seen, in records (sizes exchange buffers)
  std::vector<lsdem_state_record> records;  // scratch for packing and unpacking

  static void pool_room(Pool &p, int ns, int nentry, int nshear);
  static lsdem_pair_state pair_room(Pool &p, int list_cap, int shear_cap);
  static int keep_pair(Pool &p, tagint partner, const lsdem_pair_state &st);
  void note_records(int n);
  int count_records(int i) const;
  int pack_state(int i, double *buf);
  int unpack_state(int i, const double *buf);
};

}    // namespace LAMMPS_NS

#endif
#endif
