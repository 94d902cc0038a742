/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   LsdemVtkSeries (lsdem_vtk_series.h).
------------------------------------------------------------------------- */

#include "lsdem_vtk_series.h"

#include "fmt/format.h"

#include <cstdio>

using namespace LAMMPS_NS;

std::string LsdemVtkSeries::step_file(long long step) const
{
  return fmt::format("{}_{}.{}", prefix, step, extension);
}

bool LsdemVtkSeries::add(long long step, double time)
{
  const std::string file = step_file(step);
  const size_t slash = file.find_last_of('/');
  const std::string rel = slash == std::string::npos ? file : file.substr(slash + 1);
  bool replaced = false;
  for (auto &entry : entries)
    if (entry.second == rel) entry.first = time, replaced = true;
  if (!replaced) entries.emplace_back(time, rel);

  pvd = prefix + ".pvd";
  const std::string tmp = pvd + ".tmp";
  FILE *f = fopen(tmp.c_str(), "w");
  if (!f) return false;
  fputs("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" "
        "byte_order=\"LittleEndian\">\n<Collection>\n", f);
  for (const auto &entry : entries)
    fmt::print(f, "<DataSet timestep=\"{:.17g}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
               entry.first, entry.second);
  fputs("</Collection>\n</VTKFile>\n", f);
  const bool bad = ferror(f) != 0;
  return fclose(f) == 0 && !bad && rename(tmp.c_str(), pvd.c_str()) == 0;
}
