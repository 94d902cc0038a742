/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   bond_style lsdem/net: the permanent springs between the balls of a net (report §4.4.2,
   Figure 4.6): an axial spring K (|d| - r0) with optional axial viscous damping and
   optional rupture by strain or by force (core lsdem_net_bond_force,
   lsdem_net_bond_breaks). A broken bond is switched off the LAMMPS way (its type set to 0
   in the bond list and in the atoms' bond_type, as bond_style quartic does) and never
   acts again. Each bond's force is rounded to a power-of-two quantum before it is added
   (lsdem_quantum_for), so a ball's bond force is the same sum on any rank count.
   The general bonded-ball structure: bond_style lsdem/membrane is a net whose bonds carry a
   tangential spring as well (bond_lsdem_membrane.h). A force call runs in two phases:
   every bond's force, energy and stretch into a buffer (the part a threaded style shares
   among threads: lsdem/membrane/omp), then, in bond-list order, rupture, damping work,
   rounding and the scatter onto the atoms (the same sums, bit for bit, on any thread
   count).
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
  double memory_usage() override;

  // force on atom 2 of entry n of neighbor->bondlist from this step's force call, or
  // nullptr when there was none this step (a fix after the force computation)
  const double *force_on_atom2(int n) const;

 protected:
  double *k, *r0, *damp, *limit;    // per type; limit of the rupture criterion
  int *mode;                        // per type: LSDEM_NET_BREAK_NONE / _STRAIN / _FORCE
  lsdem_quantum quantum;            // for the order-free sums of the bond forces (0: none)
  double *damping_work;             // per type: this rank's damping work since creation
  double *terms;                    // per bondlist entry: force on atom 2 (3), energy, stretch
  int maxterms;
  bigint terms_step;                // the step the terms are from (-1: none)

  virtual void allocate();
  void set_types(int ilo, int ihi, double k_one, double r0_one, double damp_one,
                 double limit_one, int mode_one);
  void restart_doubles(FILE *fp, double *a, int n);
  void break_bond(int n);           // entry n of neighbor->bondlist
  void bond_terms(int from, int to);  // entries [from, to) of the bond list into terms
  virtual void all_bond_terms();      // every entry (lsdem/membrane/omp: by threads)
  // force on atom 2 of bond (i1, i2) of this type (atom 1 gets the opposite) and its
  // stretch L - r0; returns the energy
  virtual double bond_term(int i1, int i2, int type, double *f2, double *stretch) const;
  double spring_fbond(int type, double rsq) const;    // the axial spring's fbond
  // f on atom 1 = fbond * del in the virial: the axial part of the force f2 on atom 2
  virtual double virial_fbond(int type, const double *del, double rsq, const double *f2) const;

 private:
  void apply_term(int n);    // phase two for entry n
};

}    // namespace LAMMPS_NS

#endif
#endif
