/* -*- c++ -*- ----------------------------------------------------------
   LSDEM package for LAMMPS: the contact options that pair_style/pair_coeff lsdem and
   fix wall/lsdem share, parsed and checked in one place (doc/pair_lsdem.rst,
   doc/fix_wall_lsdem.rst):
     the penalty law   kn ks mu, cn value, ct value, normal node|traction
     the detection     stride N, nodelist auto|off|skin
   Each style takes the keywords it documents (pair_style: normal, stride, nodelist;
   pair_coeff: cn, ct; fix wall/lsdem: all of them).
------------------------------------------------------------------------- */

#ifndef LMP_LSDEM_CONTACT_OPTIONS_H
#define LMP_LSDEM_CONTACT_OPTIONS_H

#include "lsdem_kernel.h"

#include <string>

namespace LAMMPS_NS {

class LsdemContactOptions {
 public:
  // keyword groups, for read_keyword's `accept`
  enum { DAMPING = 1, NORMAL = 2, DETECT = 4 };
  // node lists' auto skin: this fraction of the smallest bounding radius of a grain shape
  // that has nodes (spheres have none)
  static constexpr double NODE_SKIN_AUTO = 0.02;
  // the deepest a node is expected to penetrate, as a fraction of a grain's bounding
  // radius: pair lsdem warns beyond it at setup, band walls must be wider than it plus
  // the node skin
  static constexpr double OVERLAP_WARN = 0.05;

  lsdem_penalty_law law;
  int stride;       // test every stride-th node (report §3.4.1)
  double nodelist;  // node-list setting: -1 auto, 0 off, > 0 skin length

  LsdemContactOptions();  // kn = 0 (to be read), per-node law, stride 1, nodelist auto
  // kn ks mu from three arguments (finite numbers; `who` names the command in errors)
  void read_stiffness(class LAMMPS *, const char *who, char **arg);
  // key and its value when key is one of the groups in accept (cn, ct: DAMPING; normal:
  // NORMAL; stride, nodelist: DETECT); false when it is not
  bool read_keyword(class LAMMPS *, const char *who, const std::string &key, const char *value,
                    int accept);
  // kn > 0; ks, mu, cn, ct >= 0; all finite: otherwise an error naming `who` and the values
  void check_law(class LAMMPS *, const char *who) const;
  // the detection parameters for grains of this atom style (the auto skin from its library)
  lsdem_detect_params detect(const class AtomVecLsdem *) const;
  // the skin a nodelist setting gives for this atom style's shapes
  static double node_skin(double setting, const class AtomVecLsdem *);
  // the stiffest per-node normal spring (force/length) a law of normal stiffness kn can
  // form with this atom style's shapes: kn * stride, times the largest node area (a
  // sphere's: lsdem_sphere_contact_area) under the traction law
  static double node_spring(double kn, lsdem_normal_law, int stride, const class AtomVecLsdem *);
  // quanta of order-free force and torque sums (lsdem_quantum_for) for contacts whose
  // stiffest node spring is `spring`: force scale spring x the largest grain radius,
  // torque scale that times the radius again
  static void sum_quanta(double spring, const class AtomVecLsdem *, lsdem_quantum &force,
                         lsdem_quantum &torque);
};

}    // namespace LAMMPS_NS

#endif
