/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package for LAMMPS: one grain's contacts, the way pair_style lsdem and
   fix wall/lsdem both run them: pose -> pair state -> manifold -> law -> commit.
     the pose        of a grain from the atom arrays (pose_of);
     the pair state  of the master (node list, shear history) from fix LSDEM_HISTORY;
     the manifold    from the core's detection (lsdem_detect);
     the law         the core's penalty law (lsdem_penalty_apply), whose result the style
                     applies to the grains;
     the commit      of the pair's new state to the store.
   No physics here: the core does it (core/contact).
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_CONTACT_PATH_H
#define LMP_LSDEM_CONTACT_PATH_H

#include "fix_lsdem_sphere_shear.h"
#include "lmptype.h"
#include "lsdem_kernel.h"

namespace LAMMPS_NS {

class LsdemContactPath {
 public:
  LsdemContactPath();
  ~LsdemContactPath();
  LsdemContactPath(const LsdemContactPath &) = delete;
  LsdemContactPath &operator=(const LsdemContactPath &) = delete;

  // where pair states are kept (nullptr: nowhere) and in which of its lanes this path
  // writes (one per thread), and manifold storage for the largest shape of the atom
  // style's library and at least min_points points; at each init
  void setup(class FixLsdemHistory *, const class AtomVecLsdem *, int lane = 0,
             int min_points = 1);
  // the world-frame pose of atom i (local or ghost); an analytic sphere's R is the identity
  // (its level set does not turn with it)
  static void pose_of(const class Atom *, const class AtomVecLsdem *, int i, lsdem_pose &);

  // the visit of the grains' pairs: per step (once, for all lanes), and per owned grain
  // around its test() calls (by the lane's thread)
  void begin_step(int nlanes = 1);
  void begin_atom();
  void end_atom(int i);
  void end_step();
  bool keeps_state(int i) const;  // grain i holds a pair state from the last step
  // grain i touched `partner` on the last step: its pair state holds shear history
  // (kept when the law has friction, mu > 0; without, always false)
  bool touched(int i, tagint partner) const;

  // one pair: grain i's nodes (shape A at pa) against partner `partner` (B at pb); its
  // state is read and written when the store is set and the pair needs one (friction or
  // node lists). An analytic sphere A takes the core's one-point path (lsdem_contact_sphere:
  // the same result, without a manifold). Returns the penetrating nodes.
  int test(int i, tagint partner, const lsdem_shape *A, const lsdem_pose &pa,
           const lsdem_shape *B, const lsdem_pose &pb, const lsdem_contact_params &prm,
           bigint step, lsdem_contact_result &res);
  // the other way round for a band wall (fix wall/lsdem twoway): the wall's sharp points
  // (pts, at pw; the master) against grain i's level set (B at pb), the law with the
  // points' shear history kept under `partner` in i's store. Returns the penetrating points.
  int test_points(int i, tagint partner, const lsdem_band *band, const lsdem_band_points &pts,
                  const lsdem_pose &pw, const lsdem_shape *B, const lsdem_pose &pb,
                  const lsdem_contact_params &prm, bigint step, lsdem_contact_result &res);
  // detection alone (no law, no shear history): grain i's manifold against its partner,
  // with the pair's node list kept when the store is set and det.node_skin > 0 (impulse
  // mode, pair_style lsdem/impulse). Returns the manifold's points.
  int detect(int i, tagint partner, const lsdem_shape *A, const lsdem_pose &pa,
             const lsdem_shape *B, const lsdem_pose &pb, const lsdem_detect_params &det,
             bigint step);
  // test() for an analytic sphere A of radius ra whose pair keeps its one spring in `slot`
  // (not in the store; FixLsdemSphereShear), read and written in place. Returns the
  // penetrating nodes (0 or 1). Inline: every sphere pair, every step.
  static int test_sphere_in_place(double ra, const lsdem_pose &pa, const lsdem_shape *B,
                                  const lsdem_pose &pb, const lsdem_contact_params &prm,
                                  bigint step, lsdem_shear_hist &slot, lsdem_contact_result &res)
  {
    with_slot(slot, [&](const lsdem_shear_hist *in, int n_in, int *kept) {
      lsdem_contact_sphere(ra, &pa, B, &pb, &prm.law, prm.dt, step, in, n_in, &slot, kept,
                           &res);
    });
    return res.npen;
  }
  // the same for a sphere whose overlap the caller found: B's outward normal n and the
  // depth d > 0 (lsdem_contact_sphere_overlapping; fix wall/lsdem). Returns 1.
  static int overlapping_sphere_in_place(double ra, const lsdem_pose &pa, const lsdem_pose &pb,
                                         const double n[3], double d,
                                         const lsdem_contact_params &prm, bigint step,
                                         lsdem_shear_hist &slot, lsdem_contact_result &res)
  {
    with_slot(slot, [&](const lsdem_shear_hist *in, int n_in, int *kept) {
      lsdem_contact_sphere_overlapping(ra, &pa, &pb, n, d, &prm.law, prm.dt, step, in, n_in,
                                       &slot, kept, &res);
    });
    return res.npen;
  }
  // the manifold of the last test or detect
  const lsdem_manifold &manifold() const { return m; }

 private:
  // kernel(in, n_in, kept) with the spring the slot holds (in: nullptr when none), which
  // it reads and then writes back in place (*kept: 1 when it keeps one); dropped otherwise
  template <class Kernel> static void with_slot(lsdem_shear_hist &slot, Kernel kernel)
  {
    const bool held = FixLsdemSphereShear::held(slot);
    int kept = 0;
    kernel(held ? &slot : nullptr, held ? 1 : 0, &kept);
    if (!kept) FixLsdemSphereShear::drop(slot);
  }
  // test() for an analytic sphere A of radius ra
  int test_sphere(int i, tagint partner, double ra, const lsdem_pose &pa, const lsdem_shape *B,
                  const lsdem_pose &pb, const lsdem_contact_params &prm, bigint step,
                  lsdem_contact_result &res);

  class FixLsdemHistory *store;
  int lane;
  lsdem_contact_point *points;
  int cap;
  lsdem_manifold m;
};

}    // namespace LAMMPS_NS

#endif
