/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   LsdemOutputSteps: the steps a file-writing fix writes on (lsdem_output_steps.h).
------------------------------------------------------------------------- */

#include "lsdem_output_steps.h"

#include "error.h"
#include "input.h"
#include "lammps.h"
#include "update.h"
#include "utils.h"
#include "variable.h"

#include <cstring>

using namespace LAMMPS_NS;

int LsdemOutputSteps::parse(LAMMPS *lmp, const char *arg, const char *style)
{
  if (strncmp(arg, "v_", 2) == 0 && arg[2] != '\0') {
    var = arg + 2;
    return 1;
  }
  interval = utils::inumeric(FLERR, arg, false, lmp);
  if (interval <= 0)
    lmp->error->all(FLERR, "{}: N must be > 0 or v_name, got {}", style, arg);
  return interval;
}

void LsdemOutputSteps::init(LAMMPS *lmp, const char *style)
{
  if (var.empty()) return;
  ivar = lmp->input->variable->find(var.c_str());
  if (ivar < 0 || !lmp->input->variable->equalstyle(ivar))
    lmp->error->all(FLERR, "{}: N's variable {} is not an equal-style variable", style, var);
  next = (bigint) lmp->input->variable->compute_equal(ivar);
  if (next < lmp->update->ntimestep)
    lmp->error->all(FLERR, "{}: N's variable {} gives step {}, already past", style, var,
                    next);
}

bool LsdemOutputSteps::due_at_setup(bigint step) const
{
  return var.empty() ? step % interval == 0 : step == next;
}

bool LsdemOutputSteps::due(bigint step) const
{
  return var.empty() ? step % interval == 0 : step == next;
}

void LsdemOutputSteps::written(LAMMPS *lmp, bigint step, const char *style)
{
  if (var.empty()) return;
  next = (bigint) lmp->input->variable->compute_equal(ivar);
  if (next <= step)
    lmp->error->all(FLERR, "{}: N's variable {} gives step {} after writing on step {}",
                    style, var, next, step);
}
