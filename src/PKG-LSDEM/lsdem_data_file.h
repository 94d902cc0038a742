/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package for LAMMPS: a read_data file's Atoms count against its Atoms lines.

   LAMMPS's read_data reads as many Atoms lines as the header's "N atoms" declares; when the
   section holds fewer, it stops with "Incorrect atom format in data file" (29 Sep 2021),
   which names neither the count nor the line. atom_style lsdem checks the file itself.
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_DATA_FILE_H
#define LMP_LSDEM_DATA_FILE_H

#include <string>

namespace LAMMPS_NS {
namespace LsdemDataFile {
  // "" when the data file at path holds as many Atoms lines as its header declares atoms
  // (or cannot be read as a data file: read_data then says why); else what is wrong, with
  // the lines and the fix. An Atoms line is any line that is neither blank nor starts with
  // a letter (a section keyword).
  std::string atoms_count_problem(const std::string &path);
}    // namespace LsdemDataFile
}    // namespace LAMMPS_NS

#endif
