// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: reading numbers from input scripts (lsdem_input.h).
------------------------------------------------------------------------- */

#include "lsdem_input.h"

#include "error.h"
#include "lammps.h"
#include "utils.h"

#include <cmath>
#include <cstdlib>

using namespace LAMMPS_NS;

double LsdemInput::number(const char *file, int line, const char *str, const char *who,
                          const char *what, LAMMPS *lmp)
{
  // LAMMPS 29 Sep 2021 reads a number too large for a double as inf, LAMMPS 4 Feb 2025
  // refuses it in utils::numeric without naming the argument: look first
  const bool finite = !str || !utils::is_double(str) || std::isfinite(std::strtod(str, nullptr));
  const double v = finite ? utils::numeric(file, line, str, false, lmp) : HUGE_VAL;
  if (!std::isfinite(v))
    lmp->error->all(file, line, "{}: {} = {} is not a finite number (too large for a double: "
                    "give a value below 1.8e308)", who, what, str);
  return v;
}
