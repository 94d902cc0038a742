/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   dump lsdem/vtk: the posed grain surfaces, one VTK XML PolyData file per dump step
   (prefix_<step>.vtp) plus a ParaView time-series index (prefix.pvd).
------------------------------------------------------------------------- */

#ifdef DUMP_CLASS
// clang-format off
DumpStyle(lsdem/vtk,DumpLsdemVtk);
// clang-format on
#else

#ifndef LMP_DUMP_LSDEM_VTK_H
#define LMP_DUMP_LSDEM_VTK_H

#include "dump.h"
#include "lsdem_kernel.h"
#include "lsdem_vtk_series.h"

#include <string>
#include <utility>
#include <vector>

namespace LAMMPS_NS {

class DumpLsdemVtk : public Dump {
 public:
  DumpLsdemVtk(class LAMMPS *, int, char **);
  ~DumpLsdemVtk() override;

 protected:
  void init_style() override;
  void openfile() override;
  void write_header(bigint) override;
  void pack(tagint *) override;
  void write_data(int, double *) override;

 private:
  // one dumped grain as packed: id, shape (0-based), x[3], quat[4]
  enum { SIZE_ONE = 9 };

  class AtomVecLsdem *avec;
  std::string prefix;       // file names: prefix_<step>.vtp, prefix.pvd
  double spacing_factor;    // mesh lattice spacing relative to the default
  std::vector<double> records;    // filewriter: this step's grains from all ranks
  bool step_written;
  double step_time;
  LsdemVtkSeries series;    // prefix_<step>.vtp files and their index prefix.pvd

  // shape meshes in their principal frames, extracted on first use (filewriter only)
  const lsdem_library *mesh_library;
  std::vector<lsdem_mesh> meshes;
  std::vector<char> mesh_ready;

  std::string step_file(bigint) const;
  const lsdem_mesh &shape_mesh(int);
  void free_meshes();
  void write_vtp();
  void write_pvd();
};

}    // namespace LAMMPS_NS

#endif
#endif
