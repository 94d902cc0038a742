/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package for LAMMPS: the shear springs of analytic spheres' contacts (internal fix).

   Created by pair_style lsdem and by each fix wall/lsdem when their law has friction,
   never by the user. A sphere keeps one shear entry per partner (lsdem_contact_sphere:
   node 0), so its contacts need none of fix LSDEM_HISTORY's node lists, pools or per-step
   turnover: each owned sphere holds one slot per partner (the pair style: each partner it
   is master of in the neighbour list, in the order of its master pairs; a wall: the wall),
   updated in place by the kernel every step.
     assign(i, partners, n)  at each neighbour-list build: the slots of sphere i become one
                             per partner (in that order), each keeping its spring when i
                             held one for that partner; held() says whether it does
     take_over(i, history)   slots of i without a spring take the one fix LSDEM_HISTORY
                             holds for their partner (a restart file of an earlier version)
     drop_all()              every spring dropped (a wall that fix impulse/lsdem takes over)
     slots(i)                the slots, slot k the k-th partner's: node 0 = a spring
                             held (the pair touched on the last step), node -1 = none
   The held springs travel with the sphere (exchange) and are saved in restart files.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(LSDEM_SPHERE_SHEAR,FixLsdemSphereShear);
// clang-format on
#else

#ifndef LMP_FIX_LSDEM_SPHERE_SHEAR_H
#define LMP_FIX_LSDEM_SPHERE_SHEAR_H

#include "fix.h"
#include "lsdem_kernel.h"

#include <vector>

namespace LAMMPS_NS {

class FixLsdemSphereShear : public Fix {
 public:
  FixLsdemSphereShear(class LAMMPS *, int, char **);
  ~FixLsdemSphereShear() override;
  int setmask() override { return 0; }

  void assign(int i, const tagint *partners, int n);
  void take_over(int i, const class FixLsdemHistory *history);
  void drop_all();  // every owned sphere's springs
  lsdem_shear_hist *slots(int i) { return slot + (bigint) i * cap; }
  static bool held(const lsdem_shear_hist &h) { return h.node == 0; }
  static void drop(lsdem_shear_hist &h) { h.node = -1; }
  // springs held by the owned spheres (pair states, shear entries alike)
  double springs_held() const;

  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  double memory_usage() override;

 private:
  int nmax_atom;      // atoms nslot holds
  int rows, cap;      // atoms the slots are allocated for (owned spheres), slots per atom
  int *nslot;         // per atom: slots in use (0 for ghosts and atoms without a row)
  tagint *partner;    // per row, cap each: the partner of each slot
  lsdem_shear_hist *slot;  // per row, cap each
  std::vector<tagint> old_partner;         // scratch of assign()
  std::vector<lsdem_shear_hist> old_slot;

  void realloc_slots(int new_rows, int new_cap);
  void ensure_rows(int);
  void grow_cap(int);
  void note_exchange_size();
  int count_held(int i) const;
  int pack_held(int i, double *buf) const;
  int unpack_held(int i, const double *buf);
};

}    // namespace LAMMPS_NS

#endif
#endif
