// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix wall/lsdem (doc/fix_wall_lsdem.rst). The wall is an analytic signed distance
   from the core (plane: the half-space z <= 0 of its own frame; cylinder: an inverted
   infinite cylinder, solid outside radius R) used as the slave shape B of the same
   contact kernels the pair style calls. With pivot a plane is a platen that tilts about
   the ram contact point (report §3.2.1; core/pivot.c).
------------------------------------------------------------------------- */

#include "fix_wall_lsdem.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_lsdem_history.h"
#include "force.h"
#include "input.h"
#include "lsdem_input.h"
#include "math_const.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"
#include "variable.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;
using MathConst::MY_PI;

// history partner tag of a wall (grain tags are >= 1)
static constexpr tagint WALL_PARTNER = -1;

/* ---------------------------------------------------------------------- */

FixWallLsdem::FixWallLsdem(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), nlanes(1), ncand(0), axis(2), fix_history(nullptr), avec(nullptr),
  fall_valid(0), moving(false), passive(false), contact_step(-1), pivot(false), pivot_h(0.0),
  pivot_inertia(0.0), pivot_damping(0.0), cand(nullptr), maxcand(0), cand_nlocal(0),
  cand_built(-1)
{
  for (int d = 0; d < 3; d++) {
    vstr[d] = nullptr;
    vvar[d] = -1;
  }
  const char *usage = "fix wall/lsdem plane px py pz nx ny nz kn ks mu [keywords] or "
                      "fix wall/lsdem cylinder c1 c2 R kn ks mu [keywords]";
  if (narg < 4) error->all(FLERR, "Illegal fix wall/lsdem command: {}", usage);

  vector_flag = 1;
  size_vector = 13;  // force on the wall (extensive), point, normal/axis, tilt, tilt rate
  global_freq = 1;
  extvector = -1;
  extlist = new int[size_vector];
  for (int k = 0; k < size_vector; k++) extlist[k] = k < 3 ? 1 : 0;
  for (int d = 0; d < 3; d++) tlocal[d] = pivot_torque[d] = pivot_omega[d] = 0.0;
  restart_global = 1;
  dynamic_group_allow = 1;

  memset(&wall, 0, sizeof(wall));
  memset(&wpose, 0, sizeof(wpose));
  memset(&prm, 0, sizeof(prm));
  wall.radius = HUGE_VAL;  // unbounded: the kernel must not reject by B's bounding sphere

  int iarg;
  double geom[6];
  if (strcmp(arg[3], "plane") == 0) {
    wallstyle = PLANE;
    iarg = 10;
  } else if (strcmp(arg[3], "cylinder") == 0) {
    wallstyle = CYLINDER;
    iarg = 7;
  } else error->all(FLERR, "fix wall/lsdem: unknown wall {} ({})", arg[3], usage);
  if (narg < iarg + 3) error->all(FLERR, "Illegal fix wall/lsdem command: {}", usage);
  for (int k = 4; k < iarg; k++)
    geom[k - 4] = LsdemInput::number(FLERR, arg[k], "fix wall/lsdem", "the wall geometry", lmp);
  opts.read_stiffness(lmp, "fix wall/lsdem", arg + iarg);
  iarg += 3;

  while (iarg < narg) {
    std::string key = arg[iarg];
    int nval = key == "velocity" ? 3 : (key == "pivot" ? 2 : 1);
    if (iarg + nval >= narg) error->all(FLERR, "fix wall/lsdem: keyword {} needs a value", key);
    std::string val = arg[iarg + 1];
    if (opts.read_keyword(lmp, "fix wall/lsdem", key, arg[iarg + 1],
                          LsdemContactOptions::DAMPING | LsdemContactOptions::NORMAL |
                              LsdemContactOptions::DETECT)) {
      // the contact law or detection
    } else if (key == "velocity") {
      for (int d = 0; d < 3; d++) {
        const char *val_d = arg[iarg + 1 + d];
        if (utils::strmatch(val_d, "^v_")) vstr[d] = utils::strdup(val_d + 2);
        else wpose.v[d] = LsdemInput::number(FLERR, val_d, "fix wall/lsdem", "velocity", lmp);
        if (vstr[d] || wpose.v[d] != 0.0) moving = true;
      }
    } else if (key == "axis") {
      if (val == "x" || val == "y" || val == "z") axis = val[0] - 'x';
      else error->all(FLERR, "fix wall/lsdem: axis must be x, y or z, not {}", val);
      if (wallstyle != CYLINDER) error->all(FLERR, "fix wall/lsdem: axis is for cylinder walls");
    } else if (key == "pivot") {
      nval = parse_pivot(iarg, narg, arg);
    } else error->all(FLERR, "fix wall/lsdem: unknown keyword {}", key);
    iarg += 1 + nval;
  }
  opts.check_law(lmp, "fix wall/lsdem");
  prm.law = opts.law;

  if (wallstyle == PLANE) {
    // scaled by its largest component first, so that no square overflows or underflows
    const double big = std::max({fabs(geom[3]), fabs(geom[4]), fabs(geom[5])});
    if (!(big > 0.0) || !std::isfinite(big))
      error->all(FLERR, "fix wall/lsdem: plane normal must be finite and not zero");
    double n[3] = {geom[3] / big, geom[4] / big, geom[5] / big};
    const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int d = 0; d < 3; d++) n[d] /= len;
    for (int d = 0; d < 3; d++) wpose.x[d] = geom[d];
    wall.sdf.kind = LSDEM_SDF_PLANE;
    set_plane_frame(n);
    if (pivot) start_pivot();
  } else {
    if (geom[2] <= 0.0) error->all(FLERR, "fix wall/lsdem: cylinder radius must be > 0");
    // c1 c2 are the axis' coordinates in the other two directions, in x,y,z order
    int other[2] = {axis == 0 ? 1 : 0, axis == 2 ? 1 : 2};
    wpose.x[other[0]] = geom[0];
    wpose.x[other[1]] = geom[1];
    wall.sdf.kind = LSDEM_SDF_CYLINDER;
    wall.sdf.inverted = 1;  // solid outside: a container
    wall.sdf.a[0] = geom[2];
    wall.sdf.a[1] = 0.0;    // infinite
    set_axis_frame();
  }
  flocal[0] = flocal[1] = flocal[2] = 0.0;
  fall[0] = fall[1] = fall[2] = 0.0;
}

/* ----------------------------------------------------------------------
   pivot h I [c]: returns the number of values read (c is optional, default 0)
------------------------------------------------------------------------- */

int FixWallLsdem::parse_pivot(int iarg, int narg, char **arg)
{
  if (wallstyle != PLANE)
    error->all(FLERR, "fix wall/lsdem: keyword pivot is for plane walls only, not {}", arg[3]);
  pivot = true;
  pivot_h = LsdemInput::number(FLERR, arg[iarg + 1], "fix wall/lsdem", "pivot h", lmp);
  pivot_inertia = LsdemInput::number(FLERR, arg[iarg + 2], "fix wall/lsdem", "pivot I", lmp);
  int nval = 2;
  if (iarg + 3 < narg && utils::is_double(arg[iarg + 3])) {
    pivot_damping = LsdemInput::number(FLERR, arg[iarg + 3], "fix wall/lsdem", "pivot c", lmp);
    nval = 3;
  }
  if (pivot_h < 0.0)
    error->all(FLERR, "fix wall/lsdem: pivot h = {} must be >= 0 (distance of the pivot "
               "behind the plane)", pivot_h);
  if (pivot_inertia <= 0.0)
    error->all(FLERR, "fix wall/lsdem: pivot I = {} must be > 0 (moment of inertia about "
               "the pivot, mass*distance^2)", pivot_inertia);
  if (pivot_damping < 0.0)
    error->all(FLERR, "fix wall/lsdem: pivot c = {} must be >= 0 (damping torque per "
               "angular velocity)", pivot_damping);
  return nval;
}

/* ----------------------------------------------------------------------
   the pivot P sits h behind the plane's point, along -n; the ram axis is n, the plate
   starts untilted and at rest
------------------------------------------------------------------------- */

void FixWallLsdem::start_pivot()
{
  for (int d = 0; d < 3; d++) {
    ram_axis[d] = wpose.R[3 * d + 2];
    pivot_x[d] = wpose.x[d] - pivot_h * ram_axis[d];
  }
  lsdem_matrix_to_quat(wpose.R, pivot_q);
}

/* ---------------------------------------------------------------------- */

FixWallLsdem::~FixWallLsdem()
{
  for (int d = 0; d < 3; d++) delete[] vstr[d];
  delete[] extlist;
  memory->destroy(cand);
  if (fix_history && modify) {
    int ifix = modify->find_fix(history_id);
    if (ifix >= 0) modify->delete_fix(ifix);
  }
}

/* ---------------------------------------------------------------------- */

int FixWallLsdem::setmask()
{
  int mask = POST_FORCE;
  if (moving || pivot) mask |= INITIAL_INTEGRATE;
  return mask;
}

/* ----------------------------------------------------------------------
   the history store is created here (not in init) so that a restart file's
   per-atom history reaches it when the fix is re-specified after read_restart
------------------------------------------------------------------------- */

void FixWallLsdem::post_constructor()
{
  if (opts.law.mu <= 0.0 && opts.nodelist == 0.0) return;
  history_id = std::string("LSDEM_WALL_HISTORY_") + id;
  fix_history = dynamic_cast<FixLsdemHistory *>(
      modify->add_fix(fmt::format("{} all LSDEM_HISTORY", history_id)));
}

/* ---------------------------------------------------------------------- */

void FixWallLsdem::init()
{
  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  if (!avec) error->all(FLERR, "Fix wall/lsdem requires atom_style lsdem");
  prm.dt = update->dt;
  prm.detect = opts.detect(avec);
  if (!fix_history) prm.detect.node_skin = 0.0;
  set_lanes(1);
  LsdemContactOptions::sum_quanta(
      LsdemContactOptions::node_spring(opts.law.kn, opts.law.normal, opts.stride, avec), avec,
      force_q, torque_q);
  for (int d = 0; d < 3; d++) {
    if (!vstr[d]) continue;
    vvar[d] = input->variable->find(vstr[d]);
    if (vvar[d] < 0) error->all(FLERR, "fix wall/lsdem: velocity variable {} does not exist", vstr[d]);
    if (!input->variable->equalstyle(vvar[d]))
      error->all(FLERR, "fix wall/lsdem: velocity variable {} is not equal-style", vstr[d]);
  }
  if (wallstyle == PLANE) check_plane_in_box();
}

/* ----------------------------------------------------------------------
   a plane that leaves the whole box on its solid side would put every grain inside
   the wall: stop and give the range of n.p that cuts the box
------------------------------------------------------------------------- */

void FixWallLsdem::check_plane_in_box() const
{
  const double *lo = domain->triclinic ? domain->boxlo_bound : domain->boxlo;
  const double *hi = domain->triclinic ? domain->boxhi_bound : domain->boxhi;
  const double n[3] = {wpose.R[2], wpose.R[5], wpose.R[8]};
  double smin = HUGE_VAL, smax = -HUGE_VAL;  // n.x over the box corners
  for (int c = 0; c < 8; c++) {
    const double s = n[0] * (c & 1 ? hi[0] : lo[0]) + n[1] * (c & 2 ? hi[1] : lo[1]) +
        n[2] * (c & 4 ? hi[2] : lo[2]);
    smin = std::min(smin, s);
    smax = std::max(smax, s);
  }
  const double sp = n[0] * wpose.x[0] + n[1] * wpose.x[1] + n[2] * wpose.x[2];
  if (sp > smax)
    error->all(FLERR, "fix wall/lsdem {}: plane point ({} {} {}) is outside the box with the "
               "whole box on the wall's solid side (n.p = {:.6g}); the plane must cut the box: "
               "n.p in [{:.6g}, {:.6g}] for normal ({:.6g} {:.6g} {:.6g})", id, wpose.x[0],
               wpose.x[1], wpose.x[2], sp, smin, smax, n[0], n[1], n[2]);
}

/* ----------------------------------------------------------------------
   velocity components given as equal-style variables, evaluated once per step
------------------------------------------------------------------------- */

void FixWallLsdem::update_velocity()
{
  for (int d = 0; d < 3; d++)
    if (vstr[d]) wpose.v[d] = input->variable->compute_equal(vvar[d]);
}

/* ---------------------------------------------------------------------- */

void FixWallLsdem::reset_dt()
{
  prm.dt = update->dt;
}

/* ---------------------------------------------------------------------- */

void FixWallLsdem::setup(int vflag)
{
  cand_built = -1;  // atoms may have been added, removed or reordered between runs
  update_velocity();
  post_force(vflag);
}

/* ----------------------------------------------------------------------
   a moving wall advances to where it is when this step's forces are computed
------------------------------------------------------------------------- */

void FixWallLsdem::initial_integrate(int /*vflag*/)
{
  update_velocity();
  if (pivot) step_pivot();
  else
    for (int d = 0; d < 3; d++) wpose.x[d] += update->dt * wpose.v[d];
}

/* ----------------------------------------------------------------------
   the platen tilts under the last force call's torque about P (n -> n+1), P moves
   with the wall velocity, and the plane's point and frame follow
------------------------------------------------------------------------- */

void FixWallLsdem::step_pivot()
{
  lsdem_step_pivot(pivot_q, pivot_omega, pivot_torque, ram_axis, pivot_inertia, pivot_damping,
                   update->dt);
  for (int d = 0; d < 3; d++) pivot_x[d] += update->dt * wpose.v[d];
  place_platen();
}

/* ----------------------------------------------------------------------
   the plane's point, frame and angular velocity from the pivot state (wpose.v stays the
   ram's velocity, the velocity P moves with)
------------------------------------------------------------------------- */

void FixWallLsdem::place_platen()
{
  lsdem_pose now;
  lsdem_pivot_pose(pivot_x, wpose.v, pivot_q, pivot_omega, pivot_h, &now);
  for (int d = 0; d < 3; d++) {
    wpose.x[d] = now.x[d];
    wpose.omega[d] = now.omega[d];
  }
  for (int k = 0; k < 9; k++) wpose.R[k] = now.R[k];
}

/* ----------------------------------------------------------------------
   the grains' force and torque on the platen summed over ranks (every rank then moves
   the platen identically); the torque is taken from the plane's point to P
------------------------------------------------------------------------- */

void FixWallLsdem::reduce_pivot_load()
{
  double local[6], all[6];
  for (int d = 0; d < 3; d++) {
    local[d] = flocal[d];
    local[3 + d] = tlocal[d];
  }
  MPI_Allreduce(local, all, 6, MPI_DOUBLE, MPI_SUM, world);
  for (int d = 0; d < 3; d++) fall[d] = all[d];
  fall_valid = 1;
  lsdem_torque_about(all + 3, wpose.x, fall, pivot_x, pivot_torque);
}

/* ----------------------------------------------------------------------
   cheap rejection: the grain's bounding sphere, widened by margin, does not reach the
   wall
------------------------------------------------------------------------- */

bool FixWallLsdem::may_touch(int i, double margin) const
{
  const double *x = atom->x[i];
  const double r = atom->radius[i] + margin;
  const double rel[3] = {x[0] - wpose.x[0], x[1] - wpose.x[1], x[2] - wpose.x[2]};
  // rel . column k of R: its component along the wall frame's axis k
  auto along = [&](int k) {
    return rel[0] * wpose.R[k] + rel[1] * wpose.R[3 + k] + rel[2] * wpose.R[6 + k];
  };
  if (wallstyle == PLANE) return along(2) < r;
  const double a0 = along(0), a1 = along(1);
  return wall.sdf.a[0] - sqrt(a0 * a0 + a1 * a1) < r;
}

/* ----------------------------------------------------------------------
   whether candidates found with the neighbour skin as margin cover every grain that can
   touch until the next reneighbouring: LAMMPS rebuilds the lists as soon as a grain has
   moved half the skin only with distance checks at every step (neigh_modify delay 0
   every 1 check yes, not once yes); a tilting platen's far points move more than its
   point, so it is not covered
------------------------------------------------------------------------- */

bool FixWallLsdem::candidates_can_last() const
{
  return neighbor->dist_check && neighbor->every == 1 && neighbor->delay == 0 &&
      !neighbor->build_once && neighbor->skin > 0.0 && !pivot;
}

/* ----------------------------------------------------------------------
   the candidates found at the last reneighbouring still cover every grain that can
   touch: since then no grain moved more than half the neighbour skin and the wall
   translated by at most as much
------------------------------------------------------------------------- */

bool FixWallLsdem::candidates_hold() const
{
  if (cand_built < 0 || cand_built != neighbor->lastcall || cand_nlocal != atom->nlocal)
    return false;
  double moved2 = 0.0;
  for (int d = 0; d < 3; d++) moved2 += (wpose.x[d] - cand_wall_x[d]) * (wpose.x[d] - cand_wall_x[d]);
  const double half = 0.5 * neighbor->skin;
  return moved2 <= half * half;
}

/* ----------------------------------------------------------------------
   grains to visit: within reach of the wall, or keeping history with it (group
   membership is tested at the visit: groups may be dynamic); the reach is widened by
   the neighbour skin when the list can last until the next reneighbouring, else the
   list is for this step
------------------------------------------------------------------------- */

void FixWallLsdem::find_candidates()
{
  const int nlocal = atom->nlocal;
  if (nlocal > maxcand) {
    maxcand = atom->nmax;
    memory->destroy(cand);
    memory->create(cand, maxcand, "wall/lsdem:cand");
  }
  const bool keep = candidates_can_last();
  const double margin = keep ? neighbor->skin : 0.0;
  ncand = 0;
  for (int i = 0; i < nlocal; i++)
    if (may_touch(i, margin) || lanes[0]->path.keeps_state(i))
      cand[ncand++] = i;
  cand_built = keep ? neighbor->lastcall : -1;
  cand_nlocal = nlocal;
  for (int d = 0; d < 3; d++) cand_wall_x[d] = wpose.x[d];
}

/* ----------------------------------------------------------------------
   n lanes with their contact paths set up for this run (one per thread)
------------------------------------------------------------------------- */

void FixWallLsdem::set_lanes(int n)
{
  while ((int) lanes.size() < n) lanes.emplace_back(new Lane);
  for (int l = 0; l < (int) lanes.size(); l++) lanes[l]->path.setup(fix_history, avec, l);
}

/* ---------------------------------------------------------------------- */

void FixWallLsdem::post_force(int /*vflag*/)
{
  if (passive) {  // fix impulse/lsdem resolves this wall's contacts: none of its own
    fall_valid = 0;
    contact_step = update->ntimestep;
    nlanes = 0;
    for (int d = 0; d < 3; d++) flocal[d] = tlocal[d] = 0.0;
    return;
  }
  lsdem_pose tilting;
  const lsdem_pose *w = begin_force_call(lanes_for_call(), tilting);
  visit_all(*w);
  end_force_call();
}

void FixWallLsdem::visit_all(const lsdem_pose &w)
{
  visit_candidates(*lanes[0], 0, ncand, w);
}

/* ----------------------------------------------------------------------
   a force call's start: the candidates, the lanes emptied, the pair states' pool opened
   for them; returns the wall as the contact kernel sees it (a tilting platen's point
   moves with P plus its rotation about P, into `tilting`)
------------------------------------------------------------------------- */

const lsdem_pose *FixWallLsdem::begin_force_call(int n, lsdem_pose &tilting)
{
  fall_valid = 0;
  contact_step = update->ntimestep;
  nlanes = n;
  for (int l = 0; l < n; l++) {
    Lane &lane = *lanes[l];
    for (int d = 0; d < 3; d++) lane.f[d] = lane.t[d] = 0.0;
    lane.contact.clear();
    lane.crossing.clear();
  }
  if (!candidates_hold()) find_candidates();
  lanes[0]->path.begin_step(n);
  if (!pivot) return &wpose;
  lsdem_pivot_pose(pivot_x, wpose.v, pivot_q, pivot_omega, pivot_h, &tilting);
  return &tilting;
}

/* ----------------------------------------------------------------------
   candidates [from, to) against wall pose w, by the lane's thread: each grain's contact
   through the shared path, its force and torque added to the grain (owned: one thread
   writes it) and, rounded to the quanta, to the lane's total on the wall, so that the
   wall's totals over lanes and ranks are the same in any order (lsdem_quantum_for)
------------------------------------------------------------------------- */

void FixWallLsdem::visit_candidates(Lane &lane, int from, int to, const lsdem_pose &w)
{
  double **f = atom->f, **torque = atom->torque;
  const int *mask = atom->mask;
  const bigint step = update->ntimestep;
  for (int c = from; c < to; c++) {
    const int i = cand[c];
    const bool test = (mask[i] & groupbit) && may_touch(i, 0.0);
    if (!test && !lane.path.keeps_state(i)) continue;  // far, nothing kept
    lane.path.begin_atom();
    if (test) {
      lsdem_pose p;
      LsdemContactPath::pose_of(atom, avec, i, p);
      lsdem_contact_result res;
      lane.path.test(i, WALL_PARTNER, avec->shape_of(i), p, &wall, w, prm, step, res);
      if (res.npen > 0) {
        double fk[3], ta[3], tb[3];
        lsdem_quantize3(res.force, force_q, fk);
        lsdem_quantize3(res.torque_a, torque_q, ta);
        lsdem_quantize3(res.torque_b, torque_q, tb);
        for (int d = 0; d < 3; d++) {
          f[i][d] += fk[d];
          torque[i][d] += ta[d];
          lane.f[d] -= fk[d];
          lane.t[d] += tb[d];
        }
        add_contact(lane, i, res);
      }
    }
    if ((mask[i] & groupbit) && lane.crossing.empty()) lane.crossing = crossing(i, w);
    lane.path.end_atom(i);
  }
}

/* ----------------------------------------------------------------------
   a force call's end: the lanes' totals (exact sums, any order), the first grain through
   the wall in candidate order (stopped at fix nve/lsdem's next check), the pivot's load
------------------------------------------------------------------------- */

void FixWallLsdem::end_force_call()
{
  lanes[0]->path.end_step();
  for (int d = 0; d < 3; d++) flocal[d] = tlocal[d] = 0.0;
  for (int l = 0; l < nlanes; l++)
    for (int d = 0; d < 3; d++) {
      flocal[d] += lanes[l]->f[d];
      tlocal[d] += lanes[l]->t[d];
    }
  for (int l = 0; l < nlanes; l++)
    if (!lanes[l]->crossing.empty()) {
      avec->defer_stop(lanes[l]->crossing);
      break;
    }
  if (pivot) reduce_pivot_load();
}

/* ----------------------------------------------------------------------
   a grain whose centre is behind the wall's surface, or will be at the next step (moved
   by its velocity after this step's force, this wall's included: v + dt f / m), goes
   through the wall: the contact cannot hold it, and where the wall is the box's face
   LAMMPS deletes it at the next reneighbouring and reports it only as lost. Found here
   (no communication) for every candidate (every grain that can reach the wall before the
   next reneighbouring, see candidates_can_last), stopped at the next check of
   fix nve/lsdem, naming the grain, the wall, the step and the time step that would hold
   it (|v_n| dt <= 0.1 R)
------------------------------------------------------------------------- */

std::string FixWallLsdem::crossing(int i, const lsdem_pose &w) const
{
  // d: the centre's distance in front of the wall's surface; n: the direction in which d
  // grows at the centre (plane: its normal; container: towards its axis)
  const double *x = atom->x[i];
  const double dt = update->dt, kick = dt * force->ftm2v / atom->rmass[i];
  double v[3], rel[3], n[3], d;
  for (int k = 0; k < 3; k++) v[k] = atom->v[i][k] + kick * atom->f[i][k];
  for (int k = 0; k < 3; k++) rel[k] = x[k] - w.x[k];
  if (wallstyle == PLANE) {
    for (int k = 0; k < 3; k++) n[k] = w.R[3 * k + 2];
    d = lsdem_dot3(rel, n);
  } else {
    const double ax[3] = {w.R[2], w.R[5], w.R[8]}, along = lsdem_dot3(rel, ax);
    double radial[3];
    for (int k = 0; k < 3; k++) radial[k] = rel[k] - along * ax[k];
    const double rho = sqrt(lsdem_dot3(radial, radial));
    d = wall.sdf.a[0] - rho;
    for (int k = 0; k < 3; k++) n[k] = rho > 0.0 ? -radial[k] / rho : 0.0;
  }
  double wv[3], vr[3];  // the wall's velocity at the grain's centre, and the grain's relative
  lsdem_cross3(w.omega, rel, wv);
  for (int k = 0; k < 3; k++) vr[k] = v[k] - w.v[k] - wv[k];
  const double vn = lsdem_dot3(vr, n);  // < 0: towards the wall
  if (d >= 0.0 && d + vn * dt >= 0.0) return std::string();
  const double R = atom->radius[i], dt_hold = vn < 0.0 ? 0.1 * R / -vn : 0.0;
  return fmt::format(
      "fix wall/lsdem {}: grain {} {} at step {}: its centre is {:.6g} {} the wall's surface "
      "and it moves at {:.6g} {} the wall (after this step's force); the contact cannot hold "
      "a grain that moves a large part of its radius {:.6g} through the wall in one step: a "
      "time step below {:.6g} would (|v_n| dt <= 0.1 R; now {:.6g}), or a stiffer wall, or "
      "slow the grain down",
      id, atom->tag[i], d < 0.0 ? "went through the wall" : "would go through the wall",
      update->ntimestep, fabs(d), d < 0.0 ? "behind" : "in front of", fabs(vn),
      vn < 0.0 ? "towards" : "away from", R, dt_hold, dt);
}

/* ---------------------------------------------------------------------- */

void FixWallLsdem::add_contact(Lane &lane, int i, const lsdem_contact_result &res)
{
  lane.contact.emplace_back();
  Contact &c = lane.contact.back();
  c.i = i;
  for (int d = 0; d < 3; d++) {
    c.force[d] = res.force[d];
    c.point[d] = res.point[d];
  }
}

/* ----------------------------------------------------------------------
   n = 0,1,2: total force the grains exert on the wall (x,y,z);
   n = 3,4,5: the wall's reference point (plane point or cylinder axis point) now;
   n = 6,7,8: the wall's body z axis in the world (plane normal or cylinder axis) now;
   n = 9: tilt of a pivoting platen, the angle (degrees) between its normal and the ram axis;
   n = 10,11,12: its angular velocity (world, radians/time; 0 without pivot)
------------------------------------------------------------------------- */

double FixWallLsdem::compute_vector(int n)
{
  if (n >= 10) return pivot ? pivot_omega[n - 10] : 0.0;
  if (n == 9) {
    if (!pivot) return 0.0;
    const double normal[3] = {wpose.R[2], wpose.R[5], wpose.R[8]};
    return lsdem_tilt_angle(normal, ram_axis) * 180.0 / MY_PI;
  }
  if (n >= 6) return wpose.R[3 * (n - 6) + 2];
  if (n >= 3) return wpose.x[n - 3];
  if (!fall_valid) {
    MPI_Allreduce(flocal, fall, 3, MPI_DOUBLE, MPI_SUM, world);
    fall_valid = 1;
  }
  return fall[n];
}

/* ----------------------------------------------------------------------
   wall frame: body z = plane normal n (outward from the wall's solid side)
------------------------------------------------------------------------- */

void FixWallLsdem::set_plane_frame(const double n[3])
{
  // t1 = a unit vector perpendicular to n, t2 = n x t1: columns (t1, t2, n)
  double a[3] = {0.0, 0.0, 0.0};
  int k = fabs(n[0]) < fabs(n[1]) ? (fabs(n[0]) < fabs(n[2]) ? 0 : 2) : (fabs(n[1]) < fabs(n[2]) ? 1 : 2);
  a[k] = 1.0;
  double t1[3] = {a[1] * n[2] - a[2] * n[1], a[2] * n[0] - a[0] * n[2], a[0] * n[1] - a[1] * n[0]};
  double len = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
  for (int d = 0; d < 3; d++) t1[d] /= len;
  double t2[3] = {n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2],
                  n[0] * t1[1] - n[1] * t1[0]};
  for (int r = 0; r < 3; r++) {
    wpose.R[3 * r + 0] = t1[r];
    wpose.R[3 * r + 1] = t2[r];
    wpose.R[3 * r + 2] = n[r];
  }
}

/* ----------------------------------------------------------------------
   cylinder frame: body z = the axis; a cyclic permutation of x,y,z (proper)
------------------------------------------------------------------------- */

void FixWallLsdem::set_axis_frame()
{
  for (int k = 0; k < 9; k++) wpose.R[k] = 0.0;
  for (int c = 0; c < 3; c++) {
    int world_dim = (axis + 1 + c) % 3;  // body x,y,z -> world axis+1, axis+2, axis
    wpose.R[3 * world_dim + c] = 1.0;
  }
}

/* ----------------------------------------------------------------------
   restart: the wall's current position, so that a moving wall resumes where it was (3
   doubles); with pivot, PIVOT_TAG first and then the wall point,
   pivot point, orientation and angular velocity (14 doubles). The tag lets either kind of
   fix read either kind of file without reading past its end.
------------------------------------------------------------------------- */

static const double PIVOT_TAG = -DBL_MAX;

void FixWallLsdem::write_restart(FILE *fp)
{
  if (comm->me == 0) {
    double list[14];
    int n = 0;
    if (pivot) list[n++] = PIVOT_TAG;
    for (int d = 0; d < 3; d++) list[n++] = wpose.x[d];
    if (pivot) {
      for (int d = 0; d < 3; d++) list[n++] = pivot_x[d];
      for (int k = 0; k < 4; k++) list[n++] = pivot_q[k];
      for (int d = 0; d < 3; d++) list[n++] = pivot_omega[d];
    }
    int size = n * sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), n, fp);
  }
}

void FixWallLsdem::restart(char *buf)
{
  const double *list = (const double *) buf;
  const bool tagged = list[0] == PIVOT_TAG;
  const double *x = tagged ? list + 1 : list;
  for (int d = 0; d < 3; d++) wpose.x[d] = x[d];
  if (!pivot) return;
  if (tagged) {
    for (int d = 0; d < 3; d++) {
      pivot_x[d] = list[4 + d];
      pivot_omega[d] = list[11 + d];
    }
    for (int k = 0; k < 4; k++) pivot_q[k] = list[7 + k];
  } else { // a file without pivot: the level platen where it was, at rest
    for (int d = 0; d < 3; d++) pivot_x[d] = wpose.x[d] - pivot_h * ram_axis[d];
  }
  place_platen();
}
