/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package for LAMMPS: per-node tangential contact history.

   An internal fix (created by pair_style lsdem and by each fix wall/lsdem, never by
   the user). Each owned grain keeps a variable-length list of the history entries of
   ITS OWN nodes that touched a partner on the last step: {partner tag, lsdem_node_hist},
   one run of entries per partner (sorted by node) with a header per partner (tag, first
   entry, count), headers sorted by partner. The list travels with the grain (exchange)
   and is saved in restart files (a partner tag per entry there).

   Storage: all grains' lists sit in one pool, in the order the styles visit the grains;
   a step reads the current pool and writes the next one, so the kernel writes its
   output where it will be read next step (no copy) and both pools are walked in order
   (the hardware prefetcher follows). Use per step:
     begin_step();
     for each owned grain i:
       begin_atom();
       for each partner j: find(i, tag_j, n) -> this pair's slice (the kernel's hist_in);
                           reserve(cap) -> room for the kernel's hist_out;
                           commit(tag_j, n_out);
       end_atom(i);  // i's list := the committed slices; untouched entries are dropped
     end_step();     // grains not visited lose their lists
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

namespace LAMMPS_NS {

class FixLsdemHistory : public Fix {
 public:
  FixLsdemHistory(class LAMMPS *, int, char **);
  ~FixLsdemHistory() override;
  int setmask() override;

  // per-step interface for the contact styles
  void begin_step();
  const lsdem_node_hist *find(int i, tagint partner, int &n) const;
  bool holds(int i) const { return nhist[i] > 0; }  // atom i keeps entries
  void begin_atom();
  lsdem_node_hist *reserve(int cap);
  void commit(tagint partner, int n);
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
  struct Slice {
    tagint partner;
    int start, n;  // entries from the atom's first one
  };
  struct Pool {    // the lists of all atoms, one after the other
    lsdem_node_hist *entry;
    int n, max;
    Slice *slice;
    int ns, maxs;
  };
  Pool pool[2];
  int cur;                    // pool[cur] holds the lists; pool[1 - cur] is written
  int nmax_atom;              // length of the per-atom arrays
  int *first, *nhist;         // per atom: its entries in pool[cur]
  int *sfirst, *nslice;       // per atom: its slice headers in pool[cur]
  int *visited, generation;   // atoms visited since begin_step() carry its generation
  int atom_entry, atom_slice; // where the atom being visited starts in the next pool
  int maxcount;               // largest list seen (sizes exchange/restart buffers)

  void pool_room(Pool &p, int n, int ns);
  void note_count(int n);
  int pack_entries(int i, double *buf) const;
  int unpack_entries(int i, const double *buf);
};

}    // namespace LAMMPS_NS

#endif
#endif
