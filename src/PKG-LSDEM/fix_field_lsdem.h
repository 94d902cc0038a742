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
  void write_restart(FILE *) override;
  void restart(char *) override;

 private:
  lsdem_field_params params;
  enum { MASK_NONE, MASK_CYLINDER, MASK_MEMBRANE } mask_kind;  // keyword mask
  double mask_centre[2], mask_radius, mask_zlo, mask_zhi;     // mask cylinder cx cy R zlo zhi
  std::string membrane_id;                                    // mask membrane fixID
  class FixMembraneLsdem *membrane;
  std::vector<tagint> membrane_tri;   // its inner layer's triangles (3 tags each)
  std::vector<tagint> membrane_tags;  // their vertices, sorted
  double ref_period[3][3];            // the box's period vectors at the reference (rows),
                                      // in the basis of the box now (after flips)
  double last_period[3][3];           // the box's period vectors at the last step's end
  void period_vectors(double p[3][3]) const;  // the box's now (rows)
  bool have_ref_box;
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
  std::vector<double> membrane_rows() const;
  void set_box();
  void mask_membrane(lsdem_fields *f, const std::vector<double> &nodes);
  void store_reference_box();
  void write_fields();
  void write_and_schedule();
};

}    // namespace LAMMPS_NS

#endif
#endif
