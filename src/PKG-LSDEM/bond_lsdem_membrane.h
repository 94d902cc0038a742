/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   bond_style lsdem/membrane: the permanent springs between neighbouring spheres of the
   triaxial test's flexible membrane (report §2.3.5): a normal spring Knbb (|d| - r0) and a
   tangential spring Ksbb that keeps the hexagonal pattern (core lsdem_membrane_bond_force:
   in-surface offset from its rest value, measured in the cylinder frame of the membrane
   axis; no per-bond history).
------------------------------------------------------------------------- */

#ifdef BOND_CLASS
// clang-format off
BondStyle(lsdem/membrane,BondLsdemMembrane);
// clang-format on
#else

#ifndef LMP_BOND_LSDEM_MEMBRANE_H
#define LMP_BOND_LSDEM_MEMBRANE_H

#include "bond.h"

namespace LAMMPS_NS {

class BondLsdemMembrane : public Bond {
 public:
  BondLsdemMembrane(class LAMMPS *);
  ~BondLsdemMembrane() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  double equilibrium_distance(int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  void write_data(FILE *) override;
  double single(int, double, int, int, double &) override;
  void *extract(const char *, int &) override;

  // force on atom 2 of a bond of this type (atom 1 gets the opposite); returns the energy
  double bond_force(const double *x1, const double *x2, int type, double *f2) const;

 protected:
  double axis[2];                 // membrane axis (x, y), parallel to z
  double *kn, *ks, *r0, *rest;    // per type; rest = 2 values (hoop, axial) per type

  void allocate();
};

}    // namespace LAMMPS_NS

#endif
#endif
