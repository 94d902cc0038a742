/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package for LAMMPS: reading numbers from input scripts.

   utils::numeric reads "1e400" as inf (a number too large for a double; LAMMPS 2025 refuses
   it without naming the argument): every numeric
   keyword and argument of the LSDEM styles goes through LsdemInput::number, which stops
   naming the style, the keyword and the text given when the value is not finite.
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_INPUT_H
#define LMP_LSDEM_INPUT_H

namespace LAMMPS_NS {
class LAMMPS;
namespace LsdemInput {
  // the floating-point value of str (utils::numeric), which must be finite
  double number(const char *file, int line, const char *str, const char *who,
                const char *what, LAMMPS *lmp);
}    // namespace LsdemInput
}    // namespace LAMMPS_NS

#endif
