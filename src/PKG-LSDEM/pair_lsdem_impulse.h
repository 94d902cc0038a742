/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   pair_style lsdem/impulse: the contact detection of pair_style lsdem (the same full
   neighbor list, poses of local and ghost grains, master of each pair, node lists) that
   applies no force: it keeps the contact manifold of every touching master-on-slave pair
   of the step (core/contact, lsdem_detect) for fix impulse/lsdem, which resolves them by
   impulses (report chapter 4).
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(lsdem/impulse,PairLsdemImpulse);
// clang-format on
#else

#ifndef LMP_PAIR_LSDEM_IMPULSE_H
#define LMP_PAIR_LSDEM_IMPULSE_H

#include "pair_lsdem.h"

#include <vector>

namespace LAMMPS_NS {

class PairLsdemImpulse : public PairLsdem {
 public:
  // one master-on-slave test that found penetrating nodes on the last force call
  struct Touch {
    int i, j;         // master (owned) and slave (owned or ghost) local indices
    int first, n;     // its points: points()[first .. first + n)
    int stride;
    double xa[3], dab[3];
  };

  PairLsdemImpulse(class LAMMPS *);
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  double memory_usage() override;

  int ntouches() const { return (int) touch.size(); }
  const Touch &touch_at(int k) const { return touch[k]; }
  // the manifold of touch k (a view into this style's storage, valid until the next call)
  lsdem_manifold manifold(int k);
  bigint touches_step() const { return touch_step; }
  double detect_seconds() const { return seconds; }  // wall time in compute, cumulative
  // per atom (local and ghost; nonzero: asleep, fix impulse/lsdem keyword sleep): a pair
  // of two sleeping grains is not tested. nullptr: every pair is tested
  void set_sleeping(const double *flag) { sleeping = flag; }

 protected:
  // a lane's (thread's) finds during a force call, joined in lane order at its end
  struct Found {
    std::vector<Touch> touch;
    std::vector<lsdem_contact_point> points;
  };
  void begin_detection(int eflag, int vflag, int nlanes);
  void detect_range(int lane, int iifrom, int iito);
  void end_detection();

 private:
  std::vector<Touch> touch;
  std::vector<lsdem_contact_point> points;
  std::vector<Found> found;
  bigint touch_step;
  double seconds, t_start;
  const double *sleeping;

  void keep(Found &, int i, int j, const lsdem_manifold &m);
};

}    // namespace LAMMPS_NS

#endif
#endif
