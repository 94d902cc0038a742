// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: reading numbers from input scripts (lsdem_input.h).
------------------------------------------------------------------------- */

#include "lsdem_input.h"

#include "error.h"
#include "lammps.h"
#include "utils.h"

#include <cmath>

using namespace LAMMPS_NS;

double LsdemInput::number(const char *file, int line, const char *str, const char *who,
                          const char *what, LAMMPS *lmp)
{
  const double v = utils::numeric(file, line, str, false, lmp);
  if (!std::isfinite(v))
    lmp->error->all(file, line, "{}: {} = {} is not a finite number (too large for a double: "
                    "give a value below 1.8e308)", who, what, str);
  return v;
}
