/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   angle_style lsdem/net: bending stiffness of a net's joints (three balls along a lattice
   line, lsdem-shape net --bending): E = Kb (1 + cos theta), zero when the line is straight
   (core lsdem_net_bend_force). Each force is rounded to the net bonds' power-of-two
   quantum before it is added, so a ball's force is the same sum on any rank count.
------------------------------------------------------------------------- */

#ifdef ANGLE_CLASS
// clang-format off
AngleStyle(lsdem/net,AngleLsdemNet);
// clang-format on
#else

#ifndef LMP_ANGLE_LSDEM_NET_H
#define LMP_ANGLE_LSDEM_NET_H

#include "angle.h"
#include "lsdem_kernel.h"

namespace LAMMPS_NS {

class AngleLsdemNet : public Angle {
 public:
  AngleLsdemNet(class LAMMPS *);
  ~AngleLsdemNet() override;
  void compute(int, int) override;
  void coeff(int, char **) override;
  void init_style() override;
  double equilibrium_angle(int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_data(FILE *) override;
  double single(int, int, int, int) override;

 protected:
  double *kb;               // per type: bending stiffness (energy per radian squared)
  lsdem_quantum quantum;    // bond_style lsdem/net's, for the order-free sums

  void allocate();
};

}    // namespace LAMMPS_NS

#endif
#endif
