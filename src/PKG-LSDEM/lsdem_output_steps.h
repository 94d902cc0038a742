/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   LsdemOutputSteps: when a file-writing fix (field/lsdem, network/lsdem) writes. Its N is
   either a step interval (every N steps, and at a run's setup when the step is a multiple
   of N) or v_name, an equal-style variable that gives the next step to write (as fix
   print's N): evaluated at init and after each write, it must not name a step already
   past; a run's setup writes when the step is the one it names.
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_OUTPUT_STEPS_H
#define LMP_LSDEM_OUTPUT_STEPS_H

#include "lmptype.h"

#include <string>

namespace LAMMPS_NS {
class LAMMPS;

class LsdemOutputSteps {
 public:
  // N or v_name of a fix's arguments; returns the fix's nevery (N, or 1 for a variable)
  int parse(LAMMPS *lmp, const char *arg, const char *style);
  // the variable's next step (a run's init)
  void init(LAMMPS *lmp, const char *style);
  bool due_at_setup(bigint step) const;
  bool due(bigint step) const;  // whether to write on `step` (called at any step)
  // after a write on `step`: the variable's next step, which must lie beyond it
  void written(LAMMPS *lmp, bigint step, const char *style);

 private:
  int interval = 0;
  std::string var;  // the variable's name without v_ (empty: an interval)
  int ivar = -1;
  bigint next = 0;
};

}    // namespace LAMMPS_NS

#endif
