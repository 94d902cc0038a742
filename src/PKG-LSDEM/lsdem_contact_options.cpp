// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package for LAMMPS: contact options shared by pair lsdem and fix wall/lsdem
   (lsdem_contact_options.h).
------------------------------------------------------------------------- */

#include "lsdem_contact_options.h"

#include "atom_vec_lsdem.h"
#include "error.h"
#include "lammps.h"
#include "utils.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

LsdemContactOptions::LsdemContactOptions() : stride(1), nodelist(-1.0)
{
  memset(&law, 0, sizeof(law));
  law.normal = LSDEM_NORMAL_PER_NODE;
}

/* ---------------------------------------------------------------------- */

void LsdemContactOptions::read_stiffness(LAMMPS *lmp, char **arg)
{
  law.kn = utils::numeric(FLERR, arg[0], false, lmp);
  law.ks = utils::numeric(FLERR, arg[1], false, lmp);
  law.mu = utils::numeric(FLERR, arg[2], false, lmp);
}

/* ---------------------------------------------------------------------- */

bool LsdemContactOptions::read_keyword(LAMMPS *lmp, const char *who, const std::string &key,
                                       const char *value, int accept)
{
  const std::string val = value;
  if ((accept & DAMPING) && key == "cn") {
    law.cn = utils::numeric(FLERR, value, false, lmp);
  } else if ((accept & DAMPING) && key == "ct") {
    law.ct = utils::numeric(FLERR, value, false, lmp);
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
      nodelist = utils::is_double(value) ? utils::numeric(FLERR, value, false, lmp) : 0.0;
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
