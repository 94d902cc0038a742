/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   bond_style lsdem/membrane: the permanent springs between neighbouring spheres of the
   triaxial test's flexible membrane (report §2.3.5), a kind of net (bond_style lsdem/net):
   the net's axial spring Knbb (|d| - r0), undamped and unbreakable, plus a tangential
   spring Ksbb that keeps the hexagonal pattern (core lsdem_membrane_bond_force: in-surface
   offset from its rest value, measured in the cylinder frame of the membrane axis; no
   per-bond history). The force call, its per-bond buffer (bond_style lsdem/membrane/omp
   fills it by threads) and the scatter in bond-list order are the net's; the membrane's
   forces are not rounded to a quantum (its sums are in bond-list order, as they always
   were). fix membrane/lsdem reads the buffer back for the radial stress instead of
   recomputing it.
------------------------------------------------------------------------- */

#ifdef BOND_CLASS
// clang-format off
BondStyle(lsdem/membrane,BondLsdemMembrane);
// clang-format on
#else

#ifndef LMP_BOND_LSDEM_MEMBRANE_H
#define LMP_BOND_LSDEM_MEMBRANE_H

#include "bond_lsdem_net.h"

namespace LAMMPS_NS {

class BondLsdemMembrane : public BondLsdemNet {
 public:
  BondLsdemMembrane(class LAMMPS *);
  ~BondLsdemMembrane() override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
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
  double axis[2];          // membrane axis (x, y), parallel to z
  double *ks, *rest;       // per type; rest = 2 values (hoop, axial) per type (kn: the net's k)

  void allocate() override;
  double bond_term(int i1, int i2, int type, double *f2, double *stretch) const override;
  double virial_fbond(int type, const double *del, double rsq, const double *f2) const override;
};

}    // namespace LAMMPS_NS

#endif
#endif
