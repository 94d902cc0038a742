/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   LsdemContactSources: the contact lists an analysis style reads (pair_style lsdem's of its
   last force call, and those of the named fix wall/lsdem), with the check that they are of
   the current step; lsdem_gather_sorted: rows of doubles from every rank on rank 0 in
   lexicographic order, so that what rank 0 sums from them is the same bits on any number
   of ranks (fix field/lsdem, fix network/lsdem).
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_CONTACT_SOURCES_H
#define LMP_LSDEM_CONTACT_SOURCES_H

#include "pointers.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class LsdemContactSources {
 public:
  class PairLsdem *pair = nullptr;          // nullptr without pair_style lsdem
  std::vector<class FixWallLsdem *> walls;  // in the order named

  // look the sources up (in a style's init()): errors quote `who`
  void find(class LAMMPS *lmp, const std::vector<std::string> &wall_ids, const char *who);
  // stop with an error unless every source holds the contacts of the current step
  void check_current(class LAMMPS *lmp, const char *who) const;
};

// every rank's rows (width doubles each) on rank 0 of comm, sorted lexicographically;
// the other ranks get an empty vector
std::vector<double> lsdem_gather_sorted(MPI_Comm comm, const std::vector<double> &mine,
                                        int width);

}    // namespace LAMMPS_NS

#endif
