/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package for LAMMPS: the warm-start store of impulse mode's resting contacts
   (fix impulse/lsdem, method split). Each owned grain keeps, for every contact it held
   (as the master of a grain pair, or against a wall) at the end of the last step, the
   partner's tag (a wall: -(w + 1)), the contact point in the grain's BODY frame and the
   contact's accumulated impulse (WORLD frame; 0 for a collision). A new contact takes
   the impulse of the nearest unused entry of the same partner within a radius (Jolt's
   and Bullet's contact matching by position: node indices change as a patch slides). The
   entries travel with the grain (the fix's pack/unpack_exchange) and go into restart
   files, so a run continued from a restart, or on another rank count, is the same run.
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_IMPULSE_WARM_H
#define LMP_LSDEM_IMPULSE_WARM_H

#include "lmptype.h"

#include <vector>

namespace LAMMPS_NS {

class LsdemImpulseWarm {
 public:
  static constexpr int DOUBLES = 7;  // per entry in buffers: partner, point[3], P[3]

  void grow(int nmax);
  void copy(int i, int j) { entries[j] = entries[i]; }
  void clear(int i) { entries[i].clear(); }
  int count(int i) const { return (int) entries[i].size(); }
  int largest() const { return most; }  // most entries of one grain since the start

  // Contact matching for grain i, one contact after another, partner by partner:
  // take(i, partner, xb, radius, P): the impulse of the nearest entry not yet taken
  // this step within radius of the body-frame point xb (P = 0 and false when none).
  bool take(int i, tagint partner, const double xb[3], double radius, double P[3]);
  // The step's contacts of grain i replace its entries: clear(i), then add(...) per contact.
  void add(int i, tagint partner, const double xb[3], const double P[3]);

  // f(partner, P) for each of grain i's entries
  template <class F> void each(int i, F f) const
  {
    for (const Entry &e : entries[i]) f(e.partner, e.P);
  }

  int pack(int i, double *buf) const;    // returns the doubles written: 1 + DOUBLES n
  int unpack(int i, const double *buf);  // returns the doubles read
  double memory_usage() const;

 private:
  struct Entry {
    tagint partner;
    double xb[3], P[3];
    bool taken;
  };
  std::vector<std::vector<Entry>> entries;  // per atom (owned grains hold entries)
  int most = 0;
};

}    // namespace LAMMPS_NS

#endif
