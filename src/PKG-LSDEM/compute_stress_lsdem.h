/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute stress/lsdem: Love-Weber average stress of a group of grains from their
   contacts (report eq 3.6), with p, q and the mobilised friction angle (eqs 3.7-3.9).
   Compression positive.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(stress/lsdem,ComputeStressLsdem);
// clang-format on
#else

#ifndef LMP_COMPUTE_STRESS_LSDEM_H
#define LMP_COMPUTE_STRESS_LSDEM_H

#include "compute.h"
#include "lsdem_contact_sources.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class ComputeStressLsdem : public Compute {
 public:
  ComputeStressLsdem(class LAMMPS *, int, char **);
  ~ComputeStressLsdem() override;
  void init() override;
  void compute_vector() override;

 private:
  double volume_value;     // fixed specimen volume, or
  std::string volume_var;  // an equal-style variable giving it
  int ivar;
  std::vector<std::string> wall_ids;
  LsdemContactSources sources;  // pair_style lsdem (if any) and the named walls

  double specimen_volume();
  void add_pair_contacts(double M[9]) const;
  void add_wall_contacts(double M[9]) const;
};

}    // namespace LAMMPS_NS

#endif
#endif
