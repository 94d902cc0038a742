// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: contact options shared by pair lsdem and fix wall/lsdem
   (lsdem_contact_options.h).
------------------------------------------------------------------------- */

#include "lsdem_contact_options.h"

#include "atom_vec_lsdem.h"
#include "error.h"
#include "lammps.h"
#include "lsdem_input.h"
#include "utils.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

LsdemContactOptions::LsdemContactOptions() : stride(1), nodelist(-1.0)
{
  memset(&law, 0, sizeof(law));
  law.normal = LSDEM_NORMAL_PER_NODE;
}

/* ---------------------------------------------------------------------- */

void LsdemContactOptions::read_stiffness(LAMMPS *lmp, const char *who, char **arg)
{
  law.kn = LsdemInput::number(FLERR, arg[0], who, "kn", lmp);
  law.ks = LsdemInput::number(FLERR, arg[1], who, "ks", lmp);
  law.mu = LsdemInput::number(FLERR, arg[2], who, "mu", lmp);
}

/* ---------------------------------------------------------------------- */

bool LsdemContactOptions::read_keyword(LAMMPS *lmp, const char *who, const std::string &key,
                                       const char *value, int accept)
{
  const std::string val = value;
  if ((accept & DAMPING) && key == "cn") {
    law.cn = LsdemInput::number(FLERR, value, who, "cn", lmp);
  } else if ((accept & DAMPING) && key == "ct") {
    law.ct = LsdemInput::number(FLERR, value, who, "ct", lmp);
  } else if ((accept & NORMAL) && key == "normal") {
    if (val == "node") law.normal = LSDEM_NORMAL_PER_NODE;
    else if (val == "traction") law.normal = LSDEM_NORMAL_TRACTION;
    else lmp->error->all(FLERR, "{}: normal must be node or traction, not {}", who, val);
  } else if ((accept & DETECT) && key == "stride") {
    stride = utils::inumeric(FLERR, value, false, lmp);
    if (stride < 1) lmp->error->all(FLERR, "{}: stride must be >= 1", who);
  } else if ((accept & DETECT) && key == "nodelist") {
    if (val == "auto") nodelist = -1.0;
    else if (val == "off") nodelist = 0.0;
    else {
      nodelist = utils::is_double(value) ? LsdemInput::number(FLERR, value, who, "nodelist", lmp)
                                         : 0.0;
      if (!(nodelist > 0.0))
        lmp->error->all(FLERR, "nodelist must be auto, off or a skin length > 0, not {}", val);
    }
  } else {
    return false;
  }
  return true;
}

/* ---------------------------------------------------------------------- */

void LsdemContactOptions::check_law(LAMMPS *lmp, const char *who) const
{
  const lsdem_penalty_law &p = law;
  if (!(p.kn > 0.0) || !(p.ks >= 0.0) || !(p.mu >= 0.0) || !(p.cn >= 0.0) || !(p.ct >= 0.0))
    lmp->error->all(FLERR, "{}: need kn > 0 and ks, mu, cn, ct >= 0; got kn = {}, ks = {}, "
                    "mu = {}, cn = {}, ct = {}", who, p.kn, p.ks, p.mu, p.cn, p.ct);
}

/* ---------------------------------------------------------------------- */

double LsdemContactOptions::node_skin(double setting, const AtomVecLsdem *avec)
{
  if (setting >= 0.0) return setting;
  const double r = avec->smallest_grain_radius();
  return std::isfinite(r) ? NODE_SKIN_AUTO * r : 0.0;
}

lsdem_detect_params LsdemContactOptions::detect(const AtomVecLsdem *avec) const
{
  lsdem_detect_params d;
  d.node_stride = stride;
  d.node_skin = node_skin(nodelist, avec);
  return d;
}

/* ---------------------------------------------------------------------- */

double LsdemContactOptions::node_spring(double kn, lsdem_normal_law normal, int stride,
                                        const AtomVecLsdem *avec)
{
  double area = 1.0;
  if (normal == LSDEM_NORMAL_TRACTION) {
    area = 0.0;
    for (int s = 0; s < avec->nshapes(); s++) {
      const lsdem_shape *sh = lsdem_library_shape(avec->library(), s);
      if (sh->sdf.kind == LSDEM_SDF_SPHERE)
        area = std::max(area, lsdem_sphere_contact_area(sh->sdf.a[0]));
      for (int k = 0; k < sh->nnodes; k++) area = std::max(area, sh->node_area[k]);
    }
  }
  return kn * stride * area;
}

void LsdemContactOptions::sum_quanta(double spring, const AtomVecLsdem *avec,
                                     lsdem_quantum &force, lsdem_quantum &torque)
{
  const double r = avec->max_shape_radius();
  force = lsdem_quantum_for(spring * r);
  torque = lsdem_quantum_for(spring * r * r);
}
