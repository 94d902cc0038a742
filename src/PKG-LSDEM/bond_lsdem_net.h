/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   bond_style lsdem/net: the permanent springs between the balls of a net (report §4.4.2,
   Figure 4.6): an axial spring K (|d| - r0) with optional axial viscous damping and
   optional rupture by strain or by force (core lsdem_net_bond_force,
   lsdem_net_bond_breaks). A broken bond is switched off the LAMMPS way (its type set to 0
   in the bond list and in the atoms' bond_type, as bond_style quartic does) and never
   acts again. Each bond's force is rounded to a power-of-two quantum before it is added
   (lsdem_quantum_for), so a ball's bond force is the same sum on any rank count.
------------------------------------------------------------------------- */

#ifdef BOND_CLASS
// clang-format off
BondStyle(lsdem/net,BondLsdemNet);
// clang-format on
#else

#ifndef LMP_BOND_LSDEM_NET_H
#define LMP_BOND_LSDEM_NET_H

#include "bond.h"
#include "lsdem_kernel.h"

namespace LAMMPS_NS {

class BondLsdemNet : public Bond {
 public:
  BondLsdemNet(class LAMMPS *);
  ~BondLsdemNet() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double equilibrium_distance(int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_data(FILE *) override;
  double single(int, double, int, int, double &) override;
  void *extract(const char *, int &) override;

 protected:
  double *k, *r0, *damp, *limit;    // per type; limit of the rupture criterion
  int *mode;                        // per type: LSDEM_NET_BREAK_NONE / _STRAIN / _FORCE
  lsdem_quantum quantum;            // for the order-free sums of the bond forces
  double *damping_work;             // per type: this rank's damping work since creation

  void allocate();
  void break_bond(int n);           // entry n of neighbor->bondlist
};

}    // namespace LAMMPS_NS

#endif
#endif
