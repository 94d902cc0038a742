/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix network/lsdem: the contact network every N steps as VTK lines (prefix_<step>.vtp,
   ParaView index prefix.pvd), one line per touching pair or grain-wall contact with its
   normal force, and the strong-chain statistics as a global vector.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(network/lsdem,FixNetworkLsdem);
// clang-format on
#else

#ifndef LMP_FIX_NETWORK_LSDEM_H
#define LMP_FIX_NETWORK_LSDEM_H

#include "fix.h"
#include "lsdem_contact_sources.h"
#include "lsdem_kernel.h"
#include "lsdem_output_steps.h"
#include "lsdem_vtk_series.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixNetworkLsdem : public Fix {
 public:
  FixNetworkLsdem(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  double compute_vector(int) override;

 private:
  std::vector<std::string> wall_ids;  // keyword wall: whose contacts are lines
  LsdemContactSources sources;
  class AtomVecLsdem *avec;
  LsdemVtkSeries series;
  LsdemOutputSteps steps;             // N: every N steps or v_name
  // keyword band v_name: an atom-style variable flagging grains in a shear band (non-zero)
  std::string band_var;
  int band_ivar;
  // contacts, mean normal force, strong fraction, share; the grain contacts' normal fabric
  // (deviator Dxx Dyy Dzz Dxy Dxz Dyz, anisotropy); with band: inside's count and fabric,
  // outside's count and fabric
  double stats[27];
  int nstats;

  double pair_normal_force(int j, const double *force_on_i, const double *point,
                           double normal[3]) const;
  static int normal_fabric(const std::vector<double> &lines, const std::vector<char> &keep,
                           double *out);
  std::vector<char> lines_in_band(const std::vector<double> &lines);
  std::vector<double> contact_rows() const;
  void write_network();
  void write_vtp(const std::vector<double> &lines, const std::vector<double> &fn);
};

}    // namespace LAMMPS_NS

#endif
#endif
