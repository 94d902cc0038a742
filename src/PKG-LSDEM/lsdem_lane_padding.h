/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: the padding that keeps one thread's lane off the cache lines of the
   next. A lane (pair_style lsdem/omp's and fix wall/lsdem/omp's contact lanes, the lanes
   of fix LSDEM_HISTORY's pools) is written by its thread at every contact; two lanes on
   one 64-byte line make each write fetch the line back from the other core ("false
   sharing": it made 2 threads spend 46 % more CPU than one, bench/README.md, issue 36).
   As a lane's last member, it puts at least a line between the lane's fields and whatever
   lies behind it, in an array of lanes or in the next allocation. (alignas would not do:
   C++11 allocators do not honour it.)
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_LANE_PADDING_H
#define LMP_LSDEM_LANE_PADDING_H

namespace LAMMPS_NS {

struct LsdemLanePadding {
  char line[64];
};

}    // namespace LAMMPS_NS

#endif
