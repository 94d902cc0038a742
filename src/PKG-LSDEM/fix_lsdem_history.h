/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package for LAMMPS: per-node tangential contact history.

   An internal fix (created by pair_style lsdem and by each fix wall/lsdem, never by
   the user). Each owned grain keeps a variable-length list of the history entries of
   ITS OWN nodes that touched a partner on the last step: {partner tag, lsdem_node_hist}
   sorted by (partner, node), with a header per partner (tag, first entry, count). The
   list travels with the grain (exchange) and is saved in restart files (a partner tag
   per entry there).

   Use per step, for each owned grain i:
     begin_atom();
     for each partner j: find(i, tag_j, n) -> this pair's slice (the kernel's hist_in);
                         reserve(cap) -> room for the kernel's hist_out;
                         commit(tag_j, n_out);
     end_atom(i);   // i's list := the committed slices; untouched entries are dropped
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(LSDEM_HISTORY,FixLsdemHistory);
// clang-format on
#else

#ifndef LMP_FIX_LSDEM_HISTORY_H
#define LMP_FIX_LSDEM_HISTORY_H

#include "fix.h"
#include "lsdem.h"

namespace LAMMPS_NS {

class FixLsdemHistory : public Fix {
 public:
  FixLsdemHistory(class LAMMPS *, int, char **);
  ~FixLsdemHistory() override;
  int setmask() override;

  // per-step interface for the contact styles
  const lsdem_node_hist *find(int i, tagint partner, int &n) const;
  void prefetch(int i) const;  // start loading atom i's list (the next atom to process)
  bool holds(int i) const { return nhist[i] > 0; }  // atom i keeps entries
  void begin_atom();
  lsdem_node_hist *reserve(int cap);
  void commit(tagint partner, int n);
  void end_atom(int i);

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
    int start, n;
  };

  int nmax_atom;              // length of the per-atom pointer arrays
  int *nhist, *maxhist;       // entries and capacity of each atom's list
  lsdem_node_hist **hist;     // per atom: the entries, sorted by (partner, node)
  int *nslice, *maxslice;     // per atom: partners in the list, and capacity
  Slice **slice;              // per atom: each partner's run of entries, by partner
  int maxcount;               // largest list seen (sizes exchange/restart buffers)

  // scratch for the atom being processed (reused, grows only)
  lsdem_node_hist *scratch;
  int nscratch, maxscratch;
  Slice *slices;
  int nslices, maxslices;

  void ensure_capacity(int i, int n, int nslices);
  void note_count(int n);
  int pack_entries(int i, double *buf) const;
  int unpack_entries(int i, const double *buf);
};

}    // namespace LAMMPS_NS

#endif
#endif
