/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix net/lsdem: what a net of bonded balls (lsdem-shape net, bond_style lsdem/net) does,
   as a global vector for thermo: the anchors' reaction force and its peak, the largest
   bond strain, the residual height, the bonds broken, the grains through the net and
   before it. It reads the net file (core lsdem_net_read) and changes no atom; every
   output but the peak (kept from the end of every step, not in restart files) is
   recomputed from the atoms when asked.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(net/lsdem,FixNetLsdem);
// clang-format on
#else

#ifndef LMP_FIX_NET_LSDEM_H
#define LMP_FIX_NET_LSDEM_H

#include "fix.h"
#include "lsdem_kernel.h"

#include <string>
#include <unordered_map>
#include <vector>

namespace LAMMPS_NS {

class FixNetLsdem : public Fix {
 public:
  FixNetLsdem(class LAMMPS *, int, char **);
  ~FixNetLsdem() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  double compute_vector(int) override;

 private:
  std::string file;
  lsdem_net net;                          // frame, footprint, ball IDs (core codec)
  std::unordered_map<tagint, int> index;  // atom ID -> ball index of the file
  int clamp_group, clamp_bit, grain_group, grain_bit;
  std::vector<double> xball;              // every ball's position (gathered)
  std::vector<int> net_types;             // per bond type: 1 if the net's bonds have it
  double peak;                            // largest |anchor reaction| so far
  double out[10];
  bigint out_step;

  void check_balls();
  void find_bond_types();
  void compute_outputs();
  void anchor_reaction(double *r);
  double largest_strain();
  double lowest_height();
  double bonds_broken();
  void grain_sides(double *through, double *before);
  double damping_work();
};

}    // namespace LAMMPS_NS

#endif
#endif
