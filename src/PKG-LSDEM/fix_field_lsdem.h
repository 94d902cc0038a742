/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix field/lsdem: continuum fields of the grains on a regular grid (core lsdem_fields:
   local-linear Gaussian fit by FFT, Goldhirsch contact stress), every N steps one VTK
   ImageData file prefix_<step>.vti plus the ParaView index prefix.pvd.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(field/lsdem,FixFieldLsdem);
// clang-format on
#else

#ifndef LMP_FIX_FIELD_LSDEM_H
#define LMP_FIX_FIELD_LSDEM_H

#include "fix.h"
#include "fields/lsdem_fields.h"
#include "lsdem_contact_sources.h"
#include "lsdem_lammps_compat.h"
#include "lsdem_output_steps.h"
#include "lsdem_vtk_series.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixFieldLsdem : public Fix {
 public:
  FixFieldLsdem(class LAMMPS *, int, char **);
  ~FixFieldLsdem() override;
  void post_constructor() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;

 private:
  lsdem_field_params params;
  bool masked;                        // keyword mask cylinder cx cy R zlo zhi
  double mask_centre[2], mask_radius, mask_zlo, mask_zhi;
  std::vector<std::string> wall_ids;  // keyword wall: whose contacts enter the stress
  LsdemContactSources sources;
  class AtomVecLsdem *avec;
  std::string id_store;               // fix STORE: each grain's unwrapped reference x
  LsdemCompat::FixStorePeratom *store;
  bool have_reference;
  LsdemVtkSeries series;
  LsdemOutputSteps steps;             // N: every N steps or v_name

  void store_reference();
  std::vector<double> grain_rows() const;
  std::vector<double> branch_rows() const;
  void write_fields();
  void write_and_schedule();
};

}    // namespace LAMMPS_NS

#endif
#endif
