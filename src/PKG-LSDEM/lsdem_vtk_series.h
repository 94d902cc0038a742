/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   LsdemVtkSeries: a ParaView time-series index (prefix.pvd) of the VTK files written so
   far (.vtp for dump lsdem/vtk and fix wall/lsdem's force maps, .vti for fix field/lsdem). A step written again replaces
   its entry; the index is written to a temporary file and renamed, so a reader never
   sees half of it.
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_VTK_SERIES_H
#define LMP_LSDEM_VTK_SERIES_H

#include <string>
#include <utility>
#include <vector>

namespace LAMMPS_NS {

class LsdemVtkSeries {
 public:
  explicit LsdemVtkSeries(const std::string &prefix, const std::string &extension = "vtp") :
    prefix(prefix), extension(extension) {}
  // prefix_<step>.<extension>
  std::string step_file(long long step) const;
  // add (or replace) the entry of step's file at simulation time `time` and rewrite
  // prefix.pvd; returns false (errno set) when it cannot be written
  bool add(long long step, double time);
  const std::string &index_file() const { return pvd; }

 private:
  std::string prefix, extension, pvd;
  std::vector<std::pair<double, std::string>> entries;  // (time, file name relative to .pvd)
};

}    // namespace LAMMPS_NS

#endif
