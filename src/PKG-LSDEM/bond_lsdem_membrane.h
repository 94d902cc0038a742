/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   bond_style lsdem/membrane: the permanent springs between neighbouring spheres of the
   triaxial test's flexible membrane (report §2.3.5): a normal spring Knbb (|d| - r0) and a
   tangential spring Ksbb that keeps the hexagonal pattern (core lsdem_membrane_bond_force:
   in-surface offset from its rest value, measured in the cylinder frame of the membrane
   axis; no per-bond history).
   A force call runs in two phases: every bond's force and energy into a buffer (the part
   bond_style lsdem/membrane/omp shares among threads), then the scatter onto the atoms in
   bond-list order (serial: the same sums, bit for bit, on any thread count). fix
   membrane/lsdem reads the buffer back for the radial stress instead of recomputing it.
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
  // force on atom 2 of entry n of neighbor->bondlist from this step's force call, or
  // nullptr when there was none this step (a fix after the force computation)
  const double *force_on_atom2(int n) const;
  double memory_usage() override;

 protected:
  double axis[2];                 // membrane axis (x, y), parallel to z
  double *kn, *ks, *r0, *rest;    // per type; rest = 2 values (hoop, axial) per type
  double *terms;                  // per bondlist entry: force on atom 2 (3), energy (1)
  int maxterms;
  bigint terms_step;              // the step the terms are from (-1: none)

  void allocate();
  void bond_terms(int from, int to);  // entries [from, to) of the bond list into terms
  virtual void all_bond_terms();      // every entry (lsdem/membrane/omp: by threads)
};

}    // namespace LAMMPS_NS

#endif
#endif
