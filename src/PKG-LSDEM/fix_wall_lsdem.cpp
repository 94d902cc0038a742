// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix wall/lsdem (doc/fix_wall_lsdem.rst). The wall is a core wall record
   (core/boundary: plane, the half-space z <= 0 of its own frame; cylinder, an inverted
   infinite cylinder, solid outside radius R) whose signed distance is the slave shape B
   of the same contact kernels the pair style calls. With pivot a plane is a platen that
   tilts about the ram contact point (report §3.2.1). Its tests (may a grain touch it,
   has one crossed it) and its pose and motion are the core's; this file is LAMMPS glue.
------------------------------------------------------------------------- */

#include "fix_wall_lsdem.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_lsdem_history.h"
#include "fix_lsdem_sphere_shear.h"
#include "force.h"
#include "lsdem_vtk_series.h"
#include "input.h"
#include "lsdem_input.h"
#include "math_const.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"
#include "variable.h"

#include <algorithm>
#include <functional>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;
using MathConst::MY_PI;

// history partner tags of a wall (grain tags are >= 1): the grain's nodes in the wall's
// level set, and the wall's sharp points in the grain's (twoway)
static constexpr tagint WALL_PARTNER = -1;
static constexpr tagint WALL_POINTS_PARTNER = -2;

/* ---------------------------------------------------------------------- */

FixWallLsdem::FixWallLsdem(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), nlanes(1), ncand(0), fix_history(nullptr), sphere_shear(nullptr),
  avec(nullptr),
  band_file(nullptr), twoway(false), point_cap(0), map_every(0), map_restart_steps(0),
  map_booked(-1), fall_valid(0), moving(false), passive(false), contact_step(-1), cand(nullptr), maxcand(0),
  cand_nlocal(0), cand_built(-1), cand_margin(0.0), cand_step(-1), drift_step(-1),
  cand_drift(0.0)
{
  for (int d = 0; d < 6; d++) {
    vstr[d] = nullptr;
    vvar[d] = -1;
  }
  const char *usage = "fix wall/lsdem plane px py pz nx ny nz kn ks mu [keywords], "
                      "fix wall/lsdem cylinder c1 c2 R kn ks mu [keywords] or "
                      "fix wall/lsdem mesh|terrain FILE kn ks mu [keywords]";
  if (narg < 4) error->all(FLERR, "Illegal fix wall/lsdem command: {}", usage);

  vector_flag = 1;
  size_vector = 13;  // force on the wall (extensive), point, normal/axis, tilt, tilt rate
  global_freq = 1;
  extvector = -1;
  extlist = new int[size_vector];
  for (int k = 0; k < size_vector; k++) extlist[k] = k < 3 ? 1 : 0;
  for (int d = 0; d < 3; d++) tlocal[d] = 0.0;
  restart_global = 1;
  dynamic_group_allow = 1;
  memset(&prm, 0, sizeof(prm));
  memset(&points, 0, sizeof(points));
  memset(&thinnest, 0, sizeof(thinnest));
  thinnest.thinnest = HUGE_VAL;
  thin_searched = false;

  int iarg;
  double geom[6];
  const bool plane = strcmp(arg[3], "plane") == 0, cylinder = strcmp(arg[3], "cylinder") == 0;
  const bool band = strcmp(arg[3], "mesh") == 0 || strcmp(arg[3], "terrain") == 0;
  if (plane) iarg = 10;
  else if (cylinder) iarg = 7;
  else if (band) iarg = 5;
  else error->all(FLERR, "fix wall/lsdem: unknown wall {} ({})", arg[3], usage);
  if (narg < iarg + 3) error->all(FLERR, "Illegal fix wall/lsdem command: {}", usage);
  for (int k = 4; k < iarg && !band; k++)
    geom[k - 4] = LsdemInput::number(FLERR, arg[k], "fix wall/lsdem", "the wall geometry", lmp);
  opts.read_stiffness(lmp, "fix wall/lsdem", arg + iarg);
  iarg += 3;

  int axis = 2;             // cylinder axis 0,1,2 = x,y,z
  double vel[3] = {0.0, 0.0, 0.0};
  bool pivot = false, spin = false, exact = false;
  double pivot_prm[3];      // h, I, c
  double spin_prm[6];       // centre, angular velocity
  while (iarg < narg) {
    std::string key = arg[iarg];
    int nval = key == "velocity" ? 3 : (key == "pivot" || key == "map" ? 2 : (key == "spin" ? 6 : 1));
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
        else vel[d] = LsdemInput::number(FLERR, val_d, "fix wall/lsdem", "velocity", lmp);
        if (vstr[d] || vel[d] != 0.0) moving = true;
      }
    } else if (key == "axis") {
      if (val == "x" || val == "y" || val == "z") axis = val[0] - 'x';
      else error->all(FLERR, "fix wall/lsdem: axis must be x, y or z, not {}", val);
      if (!cylinder) error->all(FLERR, "fix wall/lsdem: axis is for cylinder walls");
    } else if (key == "pivot") {
      nval = parse_pivot(iarg, narg, arg, pivot_prm);
      pivot = true;
    } else if (key == "exact") {
      if (val != "yes" && val != "no") error->all(FLERR, "fix wall/lsdem: exact must be yes or no");
      if (!band) error->all(FLERR, "fix wall/lsdem: keyword exact is for mesh and terrain walls");
      exact = val == "yes";
    } else if (key == "twoway") {
      if (val != "yes" && val != "no")
        error->all(FLERR, "fix wall/lsdem: twoway must be yes or no");
      if (!band)
        error->all(FLERR, "fix wall/lsdem: keyword twoway is for mesh and terrain walls (a {} "
                   "wall has no sharp features to test)", arg[3]);
      twoway = val == "yes";
    } else if (key == "map") {
      map_every = utils::bnumeric(FLERR, arg[iarg + 1], false, lmp);
      map_prefix = arg[iarg + 2];
      if (map_every <= 0) error->all(FLERR, "fix wall/lsdem: map N must be > 0");
      if (!band) error->all(FLERR, "fix wall/lsdem: keyword map is for mesh and terrain walls");
    } else if (key == "spin") {
      for (int k = 0; k < 6; k++) {
        const char *val_k = arg[iarg + 1 + k];
        spin_prm[k] = 0.0;
        if (k >= 3 && utils::strmatch(val_k, "^v_")) vstr[k] = utils::strdup(val_k + 2);
        else spin_prm[k] = LsdemInput::number(FLERR, val_k, "fix wall/lsdem",
                                              k < 3 ? "spin centre" : "spin angular velocity", lmp);
      }
      if (!vstr[3] && !vstr[4] && !vstr[5] && spin_prm[3] == 0.0 && spin_prm[4] == 0.0 &&
          spin_prm[5] == 0.0)
        error->all(FLERR, "fix wall/lsdem: spin angular velocity must not be zero (give a "
                   "number or v_name for each component)");
      spin = true;
    } else error->all(FLERR, "fix wall/lsdem: unknown keyword {}", key);
    iarg += 1 + nval;
  }
  opts.check_law(lmp, "fix wall/lsdem");
  prm.law = opts.law;

  // plane: point, normal; cylinder: the axis' coordinates in the other two directions
  // (x,y,z order), radius
  lsdem_error err;
  lsdem_status st = LSDEM_OK;
  if (band) open_band(arg[3], arg[4]);
  else if (plane) st = lsdem_boundary_plane(&bnd, geom, geom + 3, &err);
  else st = lsdem_boundary_cylinder(&bnd, axis, geom, geom[2], &err);
  if (st == LSDEM_OK && pivot)
    st = lsdem_boundary_pivot(&bnd, pivot_prm[0], pivot_prm[1], pivot_prm[2], &err);
  if (st == LSDEM_OK && spin) st = lsdem_boundary_spin(&bnd, spin_prm, spin_prm + 3, &err);
  if (st != LSDEM_OK) error->all(FLERR, "fix wall/lsdem: {}", err.msg);
  for (int d = 0; d < 3; d++) bnd.pose.v[d] = vel[d];
  memset(&map, 0, sizeof(map));
  if (map_every > 0 && bnd.shape.sdf.band->heights)
    error->all(FLERR, "fix wall/lsdem {}: keyword map needs the terrain's triangles, which a "
               "terrain kept as heights does not store: make it with lsdem-shape terrain "
               "without --heights", arg[4]);
  if (map_every > 0 && bnd.shape.sdf.band->ntris == 0)
    error->all(FLERR, "fix wall/lsdem {}: keyword map needs the triangles in the band file; "
               "make it again with this version of lsdem-shape", arg[4]);
  if (map_every > 0) map_series.reset(new LsdemVtkSeries(map_prefix));
  memset(&exact_pn, 0, sizeof(exact_pn));
  if (exact) use_exact_band(arg[4]);
  if (twoway) make_points(arg[4]);
  flocal[0] = flocal[1] = flocal[2] = 0.0;
  fall[0] = fall[1] = fall[2] = 0.0;
}

/* ----------------------------------------------------------------------
   mesh or terrain FILE: the band file (lsdem-shape wall / terrain), mapped read-only
   (ranks on one machine share it through the page cache); the keyword must name what
   the file was made from
------------------------------------------------------------------------- */

void FixWallLsdem::open_band(const std::string &kind, const char *path)
{
  lsdem_error err;
  if (lsdem_band_open(path, &band_file, &err) != LSDEM_OK)
    error->all(FLERR, "fix wall/lsdem {}: {}", kind, err.msg);
  const bool terrain = lsdem_band_file_source(band_file) != LSDEM_BAND_MESH;
  if (terrain != (kind == "terrain"))
    error->all(FLERR, "fix wall/lsdem {} {}: the file was made from a {} (lsdem-shape {}): "
               "write fix wall/lsdem {} {}", kind, path, terrain ? "height map" : "mesh",
               terrain ? "terrain" : "wall", terrain ? "terrain" : "mesh", path);
  lsdem_boundary_band(&bnd, lsdem_band_file_band(band_file));
}

/* ----------------------------------------------------------------------
   exact yes: the wall's level set is the band with the surface's pseudonormals, so that
   inside the band values and normals come from the closest triangle (sharp edges)
------------------------------------------------------------------------- */

void FixWallLsdem::use_exact_band(const char *path)
{
  const lsdem_band *b = lsdem_band_file_band(band_file);
  if (b->heights) return; /* a terrain kept as heights is exact already */
  if (b->ntris == 0)
    error->all(FLERR, "fix wall/lsdem: exact needs the triangles in {}; make it again with "
               "this version of lsdem-shape", path);
  lsdem_error err;
  if (lsdem_pseudonormals_make(b->verts, b->nverts, b->tris, b->ntris, b->nbr, &exact_pn,
                               &err) != LSDEM_OK)
    error->all(FLERR, "fix wall/lsdem {}: {}", path, err.msg);
  exact_band = *b;
  exact_band.exact = &exact_pn;
  bnd.shape.sdf.band = &exact_band;
}

/* ----------------------------------------------------------------------
   twoway yes: the band's sharp convex edges as points at about the band's spacing (core:
   lsdem_band_points), from the triangles the band file keeps
------------------------------------------------------------------------- */

void FixWallLsdem::make_points(const char *path)
{
  const lsdem_band *b = bnd.shape.sdf.band;
  if (b->heights)
    error->all(FLERR, "fix wall/lsdem {}: twoway needs the terrain's triangles, which a terrain "
               "kept as heights does not store: make it with lsdem-shape terrain without "
               "--heights", path);
  if (b->ntris == 0)
    error->all(FLERR, "fix wall/lsdem {}: twoway needs the triangles in the band file; make it "
               "again with this version of lsdem-shape", path);
  if (opts.law.normal == LSDEM_NORMAL_TRACTION)
    error->all(FLERR, "fix wall/lsdem: twoway tests the wall's points with a spring per point; "
               "it does not take normal traction (a point has no area)");
  lsdem_error err;
  if (lsdem_band_points_make(b, b->h, &points, &err) != LSDEM_OK)
    error->all(FLERR, "fix wall/lsdem {}: {}", path, err.msg);
  if (comm->me == 0)
    utils::logmesg(lmp, "fix wall/lsdem {}: twoway: {} points on {} sharp edges\n", id,
                   points.n, points.nedges);
}

/* ----------------------------------------------------------------------
   pivot h I [c] into p = (h, I, c), c optional (default 0), checked by the core when
   the platen is made; returns the number of values read
------------------------------------------------------------------------- */

int FixWallLsdem::parse_pivot(int iarg, int narg, char **arg, double p[3])
{
  p[0] = LsdemInput::number(FLERR, arg[iarg + 1], "fix wall/lsdem", "pivot h", lmp);
  p[1] = LsdemInput::number(FLERR, arg[iarg + 2], "fix wall/lsdem", "pivot I", lmp);
  p[2] = 0.0;
  if (iarg + 3 < narg && utils::is_double(arg[iarg + 3])) {
    p[2] = LsdemInput::number(FLERR, arg[iarg + 3], "fix wall/lsdem", "pivot c", lmp);
    return 3;
  }
  return 2;
}

/* ---------------------------------------------------------------------- */

FixWallLsdem::~FixWallLsdem()
{
  for (int d = 0; d < 6; d++) delete[] vstr[d];
  delete[] extlist;
  memory->destroy(cand);
  lsdem_wall_map_free(&map);
  lsdem_pseudonormals_free(&exact_pn);
  lsdem_band_points_free(&points);
  lsdem_band_close(band_file);
  if (modify)
    for (const std::string &fid : {history_id, sphere_shear_id}) {
      if (fid.empty()) continue;
      int ifix = modify->find_fix(fid);
      if (ifix >= 0) modify->delete_fix(ifix);
    }
}

/* ---------------------------------------------------------------------- */

int FixWallLsdem::setmask()
{
  int mask = POST_FORCE;
  if (moving || lsdem_boundary_turns(&bnd)) mask |= INITIAL_INTEGRATE;
  return mask;
}

/* ----------------------------------------------------------------------
   the history stores are created here (not in init) so that a restart file's
   per-atom history reaches them when the fix is re-specified after read_restart:
   the general one (node lists, level-set grains' springs) and, with friction, the
   analytic spheres' springs, one slot per sphere (fix_lsdem_sphere_shear.h; not with
   twoway, whose points keep their springs in the general store)
------------------------------------------------------------------------- */

void FixWallLsdem::post_constructor()
{
  if (opts.law.mu <= 0.0 && opts.nodelist == 0.0) return;
  history_id = std::string("LSDEM_WALL_HISTORY_") + id;
  fix_history = dynamic_cast<FixLsdemHistory *>(
      modify->add_fix(fmt::format("{} all LSDEM_HISTORY", history_id)));
  if (opts.law.mu <= 0.0 || twoway) return;
  sphere_shear_id = std::string("LSDEM_WALL_SPHERE_SHEAR_") + id;
  sphere_shear = dynamic_cast<FixLsdemSphereShear *>(
      modify->add_fix(fmt::format("{} all LSDEM_SPHERE_SHEAR", sphere_shear_id)));
}

/* ---------------------------------------------------------------------- */

void FixWallLsdem::init()
{
  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  if (!avec) error->all(FLERR, "Fix wall/lsdem requires atom_style lsdem");
  prm.dt = update->dt;
  prm.detect = opts.detect(avec);
  if (!fix_history) prm.detect.node_skin = 0.0;
  if (twoway) {
    const int64_t cap = lsdem_band_points_within(bnd.shape.sdf.band, &points,
                                                 avec->max_shape_radius());
    point_cap = (int) std::min<int64_t>(cap, INT_MAX);
  }
  set_lanes(1);
  LsdemContactOptions::sum_quanta(
      LsdemContactOptions::node_spring(opts.law.kn, opts.law.normal, opts.stride, avec), avec,
      force_q, torque_q);
  for (int d = 0; d < 6; d++) {
    if (!vstr[d]) continue;
    const char *what = d < 3 ? "velocity" : "spin";
    vvar[d] = input->variable->find(vstr[d]);
    if (vvar[d] < 0) error->all(FLERR, "fix wall/lsdem: {} variable {} does not exist", what, vstr[d]);
    if (!input->variable->equalstyle(vvar[d]))
      error->all(FLERR, "fix wall/lsdem: {} variable {} is not equal-style", what, vstr[d]);
  }
  if (bnd.shape.sdf.kind == LSDEM_SDF_PLANE) check_plane_in_box();
  if (bnd.shape.sdf.kind == LSDEM_SDF_BAND) {
    check_band_width();
    find_thinnest();
  }
  if (map_every > 0 && !map.sum) {
    // forces in the wall's own quanta; work for sliding up to the band's width per step
    lsdem_error err;
    const lsdem_band *b = bnd.shape.sdf.band;
    if (lsdem_wall_map_init(&map, b->ntris, force_q, b->width, &err) != LSDEM_OK)
      error->all(FLERR, "fix wall/lsdem {}: {}", id, err.msg);
    if (!map_restart.empty()) {  // rank 0 holds the restarted sums, the others none
      std::copy(map_restart.begin(), map_restart.end(), map.sum);
      map_restart.clear();
    }
    map.steps = map_restart_steps;
  }
}

/* ----------------------------------------------------------------------
   a plane that leaves the whole box on its solid side would put every grain inside
   the wall: stop and give the range of n.p that cuts the box
------------------------------------------------------------------------- */

void FixWallLsdem::check_plane_in_box() const
{
  const double *lo = domain->triclinic ? domain->boxlo_bound : domain->boxlo;
  const double *hi = domain->triclinic ? domain->boxhi_bound : domain->boxhi;
  const double *R = bnd.pose.R, *p = bnd.pose.x;
  const double n[3] = {R[2], R[5], R[8]};
  double smin = HUGE_VAL, smax = -HUGE_VAL;  // n.x over the box corners
  for (int c = 0; c < 8; c++) {
    const double s = n[0] * (c & 1 ? hi[0] : lo[0]) + n[1] * (c & 2 ? hi[1] : lo[1]) +
        n[2] * (c & 4 ? hi[2] : lo[2]);
    smin = std::min(smin, s);
    smax = std::max(smax, s);
  }
  const double sp = n[0] * p[0] + n[1] * p[1] + n[2] * p[2];
  if (sp > smax)
    error->all(FLERR, "fix wall/lsdem {}: plane point ({} {} {}) is outside the box with the "
               "whole box on the wall's solid side (n.p = {:.6g}); the plane must cut the box: "
               "n.p in [{:.6g}, {:.6g}] for normal ({:.6g} {:.6g} {:.6g})", id, p[0], p[1],
               p[2], sp, smin, smax, n[0], n[1], n[2]);
}

/* ----------------------------------------------------------------------
   an analytic sphere touches a band wall through one lookup of its centre (depth =
   radius - phi), which needs phi to be a distance out to the radius: the band must be
   wider than the largest sphere of the library
------------------------------------------------------------------------- */

void FixWallLsdem::check_band_width() const
{
  const double width = bnd.shape.sdf.band->width;
  const double overlap = LsdemContactOptions::OVERLAP_WARN * avec->max_shape_radius();
  if (!(prm.detect.node_skin + overlap < width))
    error->all(FLERR, "fix wall/lsdem {}: the band is {:.6g} wide, no wider than the node skin "
               "{:.6g} plus the largest expected overlap {:.6g} ({:.0f} % of the largest grain "
               "radius {:.6g}): a node that deep would read the band's clamped value; make the "
               "band again with lsdem-shape ... --width above {:.6g} (or a smaller nodelist "
               "skin)", id, width, prm.detect.node_skin, overlap,
               100.0 * LsdemContactOptions::OVERLAP_WARN, avec->max_shape_radius(),
               prm.detect.node_skin + overlap);
  for (int k = 0; k < avec->nshapes(); k++) {
    const lsdem_shape *s = lsdem_library_shape(avec->library(), k);
    if (s->sdf.kind == LSDEM_SDF_SPHERE && !(s->sdf.a[0] < width))
      error->all(FLERR, "fix wall/lsdem {}: the band is {:.6g} wide, no wider than the library's "
                 "sphere {} of radius {:.6g}: a sphere touches the wall by one lookup at its "
                 "centre, which needs the distance out to its radius; make the band again with "
                 "lsdem-shape ... --width above {:.6g}", id, width, k + 1, s->sdf.a[0],
                 s->sdf.a[0]);
  }
}

/* ----------------------------------------------------------------------
   the time-step bound for thin walls: a grain touching the wall may move its nodes (by at
   most (|v| + |omega| R) dt) less than the wall's thinnest ridge in a step, else a node
   could step over it without ever being inside; ridges up to half the largest grain's
   radius count (a faster grain stops fix nve/lsdem anyway), found once from the band's
   triangles (core lsdem_band_thin_features)
------------------------------------------------------------------------- */

void FixWallLsdem::find_thinnest()
{
  const lsdem_band *b = bnd.shape.sdf.band;
  if (thin_searched || b->ntris == 0) return;  // done already, or no triangles kept
  thin_searched = true;
  lsdem_thin_feature *f = nullptr;
  int n = 0;
  lsdem_error err;
  const double limit = std::max(2.0 * b->h, 0.5 * avec->max_shape_radius());
  if (lsdem_band_thin_features(b, limit, &f, &n, &err) != LSDEM_OK)
    error->all(FLERR, "fix wall/lsdem {}: {}", id, err.msg);
  for (int k = 0; k < n; k++)
    if (f[k].ridge && f[k].thinnest < thinnest.thinnest) thinnest = f[k];
  free(f);
  if (thinnest.thinnest < HUGE_VAL && comm->me == 0)
    utils::logmesg(lmp, "fix wall/lsdem {}: thinnest ridge {:.6g} across at ({:.6g}, {:.6g}, "
                   "{:.6g}): a grain touching the wall may move its nodes less than that in "
                   "a step\n", id, thinnest.thinnest, thinnest.at[0], thinnest.at[1],
                   thinnest.at[2]);
}

std::string FixWallLsdem::too_fast_for_thin(int i) const
{
  const double *v = atom->v[i], *om = atom->omega[i], dt = update->dt, R = atom->radius[i];
  const double step = (std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) +
                       std::sqrt(om[0] * om[0] + om[1] * om[1] + om[2] * om[2]) * R) * dt;
  if (!(step > thinnest.thinnest)) return std::string();
  return fmt::format(
      "fix wall/lsdem {}: grain {} touches the wall at step {} moving its nodes up to {:.6g} "
      "a step, more than the wall's thinnest ridge, {:.6g} across at ({:.6g}, {:.6g}, {:.6g}): "
      "a node could step over it; a time step below {:.6g} would hold it ((|v| + |omega| R) "
      "dt below the ridge), or a thicker wall", id, atom->tag[i], update->ntimestep, step,
      thinnest.thinnest, thinnest.at[0], thinnest.at[1], thinnest.at[2],
      dt * thinnest.thinnest / step);
}

/* ----------------------------------------------------------------------
   velocity and spin components given as equal-style variables, evaluated once per step
------------------------------------------------------------------------- */

void FixWallLsdem::update_velocity()
{
  for (int d = 0; d < 3; d++)
    if (vstr[d]) bnd.pose.v[d] = input->variable->compute_equal(vvar[d]);
  if (!vstr[3] && !vstr[4] && !vstr[5]) return;
  double omega[3];
  for (int d = 0; d < 3; d++)
    omega[d] = vstr[3 + d] ? input->variable->compute_equal(vvar[3 + d]) : bnd.spin.omega[d];
  lsdem_error err;
  if (lsdem_boundary_spin_omega(&bnd, omega, &err) != LSDEM_OK)
    error->all(FLERR, "fix wall/lsdem {} at step {}: {}", id, update->ntimestep, err.msg);
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
   a moving wall advances to where it is when this step's forces are computed (a
   platen tilts under the last force call's torque about P, P moves with the wall
   velocity)
------------------------------------------------------------------------- */

void FixWallLsdem::initial_integrate(int /*vflag*/)
{
  update_velocity();
  lsdem_boundary_advance(&bnd, update->dt);
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
  lsdem_boundary_platen_load(&bnd, fall, all + 3);
}

/* ----------------------------------------------------------------------
   cheap rejection: the grain's bounding sphere, widened by margin, does not reach the
   wall at pose w
------------------------------------------------------------------------- */

bool FixWallLsdem::may_touch(int i, const lsdem_pose &w, double margin) const
{
  return lsdem_boundary_may_touch(&bnd, &w, atom->x[i], atom->radius[i] + margin);
}

bool FixWallLsdem::reaches(int i, const lsdem_pose &w) const
{
  return reaches_at(i, lsdem_boundary_distance(&bnd, &w, atom->x[i], nullptr));
}

// the same from the centre's distance phi to the wall
bool FixWallLsdem::reaches_at(int i, double phi) const
{
  return (atom->mask[i] & groupbit) && lsdem_boundary_reaches(&bnd, phi, atom->radius[i]);
}

lsdem_pose FixWallLsdem::pose_at(double s) const
{
  lsdem_pose w;
  lsdem_boundary_pose_at(&bnd, s, &w);
  return w;
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
      !neighbor->build_once && neighbor->skin > 0.0 && !lsdem_boundary_turns(&bnd);
}

/* ----------------------------------------------------------------------
   how far beyond its reach a grain must be kept to stay covered until the next
   reneighbouring: until then a grain stays within half the skin of where the lists were
   built and the wall within half the skin of where the candidates were found
   (candidates_hold). Found at a reneighbouring, a grain and the wall close in by at most
   one skin; found between two (the wall had moved), a grain may already be half a skin
   from where the lists were built and go half a skin the other way: 1.5 skins (a grain
   moving away and back while a platen came down was missed with one)
------------------------------------------------------------------------- */

double FixWallLsdem::candidate_margin() const
{
  return (neighbor->lastcall == update->ntimestep ? 1.0 : 1.5) * neighbor->skin;
}

/* ----------------------------------------------------------------------
   the candidates found at the last reneighbouring still cover every grain that can
   touch the wall at pose w: since then no grain moved more than half the neighbour skin
   and the wall translated by at most as much
------------------------------------------------------------------------- */

bool FixWallLsdem::candidates_hold(const lsdem_pose &w) const
{
  if (cand_built < 0 || cand_built != neighbor->lastcall || cand_nlocal != atom->nlocal)
    return false;
  const double *x = w.x;
  double moved2 = 0.0;
  for (int d = 0; d < 3; d++) moved2 += (x[d] - cand_wall_x[d]) * (x[d] - cand_wall_x[d]);
  const double half = 0.5 * neighbor->skin;
  return moved2 <= half * half;
}

/* ----------------------------------------------------------------------
   grains to visit: within reach of the wall at pose w, or keeping history with it (group
   membership is tested at the visit: groups may be dynamic); the reach is widened by
   the neighbour skin when the list can last until the next reneighbouring, else the
   list is for this step
------------------------------------------------------------------------- */

void FixWallLsdem::find_candidates(const lsdem_pose &w)
{
  const int nlocal = atom->nlocal;
  if (nlocal > maxcand) {
    maxcand = atom->nmax;
    memory->destroy(cand);
    memory->create(cand, maxcand, "wall/lsdem:cand");
  }
  const bool keep = candidates_can_last();
  const double margin = keep ? candidate_margin() : 0.0;
  ncand = 0;
  for (int i = 0; i < nlocal; i++)
    if (may_touch(i, w, margin) || lanes[0]->path.keeps_state(i))
      cand[ncand++] = i;
  cand_built = keep ? neighbor->lastcall : -1;
  cand_nlocal = nlocal;
  if (sphere_shear) assign_sphere_slots();
  for (int d = 0; d < 3; d++) cand_wall_x[d] = w.x[d];
  // the wall guard's record (guard_gap): only when fix impulse/lsdem runs the wall and the
  // margin leaves a gap to use
  cand_margin = margin;
  cand_step = update->ntimestep;
  drift_step = -1;
  cand_near.clear();
  if (!passive || !(margin > 0.0)) return;
  cand_near.assign(nlocal, 0);
  for (int c = 0; c < ncand; c++) cand_near[cand[c]] = 1;
  cand_x.resize(3 * (size_t) nlocal);
  for (int i = 0; i < nlocal; i++)
    for (int d = 0; d < 3; d++) cand_x[3 * i + d] = atom->x[i][d];
}

/* ----------------------------------------------------------------------
   fix impulse/lsdem takes the wall over (on) or gives it back: the candidates are
   searched again, and the springs the wall's own contacts kept end
------------------------------------------------------------------------- */

void FixWallLsdem::set_passive(bool on)
{
  passive = on;
  cand_built = -1;
  if (on && sphere_shear) sphere_shear->drop_all();
}

/* grain i keeps its spring on this wall in a slot of sphere_shear: an analytic sphere, with
   friction (and not twoway), while the wall makes its own contacts (not passive: fix
   impulse/lsdem's detection keeps its pair states in the general store) */
bool FixWallLsdem::keeps_sphere_slot(int i) const
{
  return sphere_shear && !passive && avec->shape_of(i)->sdf.kind == LSDEM_SDF_SPHERE;
}

/* ----------------------------------------------------------------------
   each owned sphere's slot for its spring on this wall, at each search for candidates:
   kept by the candidates (and taken over from the general store where a restart file of
   an earlier version left it there), emptied for the others, which cannot reach the wall
   before the next search; all emptied while fix impulse/lsdem runs the wall
------------------------------------------------------------------------- */

void FixWallLsdem::assign_sphere_slots()
{
  int c = 0;  // cand is in atom order
  for (int i = 0; i < atom->nlocal; i++) {
    if (avec->shape_of(i)->sdf.kind != LSDEM_SDF_SPHERE) continue;
    sphere_shear->assign(i, &WALL_PARTNER, 1);
    while (c < ncand && cand[c] < i) c++;
    if (!passive && c < ncand && cand[c] == i) sphere_shear->take_over(i, fix_history);
    else FixLsdemSphereShear::drop(sphere_shear->slots(i)[0]);
  }
}

/* ----------------------------------------------------------------------
   the wall guard's cheap rejection (lsdem_impulse_guard_wall's near and far_gap): a grain
   outside the candidates had phi(x_b) >= L (r + margin) when they were found (grain at
   x_b, wall at cand_wall_x); phi being L-Lipschitz and the wall not turning, its
   predicted centre x + v dt reaches the wall at pose w (phi < L r) only if
   dt |v| > margin - |x - x_b| - |w.x - cand_wall_x|: that gap, less a round-off margin,
   or 0 when the candidates do not tell (then the guard tests every grain)
------------------------------------------------------------------------- */

double FixWallLsdem::guard_gap(const lsdem_pose &w)
{
  const int nlocal = atom->nlocal;
  const bool current = cand_step == update->ntimestep ||
      (cand_built >= 0 && cand_built == neighbor->lastcall);
  if (cand_near.empty() || (int) cand_near.size() != nlocal || cand_nlocal != nlocal ||
      !current || lsdem_boundary_turns(&bnd))
    return 0.0;
  if (drift_step != update->ntimestep) {  // the grains stay put through the step's passes
    double most = 0.0;
    for (int i = 0; i < nlocal; i++) {
      if (cand_near[i]) continue;
      double d2 = 0.0;
      for (int d = 0; d < 3; d++) {
        const double dx = atom->x[i][d] - cand_x[3 * i + d];
        d2 += dx * dx;
      }
      most = std::max(most, d2);
    }
    cand_drift = std::sqrt(most);
    drift_step = update->ntimestep;
  }
  double shift = 0.0, scale = cand_margin;
  for (int d = 0; d < 3; d++) {
    shift += (w.x[d] - cand_wall_x[d]) * (w.x[d] - cand_wall_x[d]);
    scale += std::fabs(w.x[d]) + std::max(std::fabs(domain->boxlo[d]), std::fabs(domain->boxhi[d]));
  }
  const double gap = cand_margin - cand_drift - std::sqrt(shift) - 1e-9 * scale;
  return gap > 0.0 ? gap : 0.0;
}

/* ----------------------------------------------------------------------
   n lanes with their contact paths set up for this run (one per thread)
------------------------------------------------------------------------- */

void FixWallLsdem::set_lanes(int n)
{
  while ((int) lanes.size() < n) lanes.emplace_back(new Lane);
  for (int l = 0; l < (int) lanes.size(); l++)
    lanes[l]->path.setup(fix_history, avec, l, point_cap);
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
  lsdem_pose w;
  begin_force_call(lanes_for_call(), w);
  visit_all(w);
  end_force_call();
  if (map_every > 0 && update->ntimestep > map_booked) {
    book_map();
    if (update->ntimestep % map_every == 0) write_map();
  }
}

/* ----------------------------------------------------------------------
   this step's contacts into the map, once per step (setup repeats a step's force call)
------------------------------------------------------------------------- */

void FixWallLsdem::book_map()
{
  map_booked = update->ntimestep;
  map.steps++;
  each_contact([&](const Contact &c) {
    lsdem_wall_map_add(&map, c.tri, c.force, c.normal, c.slide, c.began);
  });
}

/* ----------------------------------------------------------------------
   the map's sums over all ranks (exact integers: the same on any rank count) to rank 0,
   which writes PREFIX_<step>.vtp and PREFIX.pvd; then a new interval everywhere
------------------------------------------------------------------------- */

void FixWallLsdem::write_map()
{
  const size_t n = (size_t) map.ntris * LSDEM_MAP_FIELDS;
  std::vector<int64_t> sum(comm->me == 0 ? n : 0);
  MPI_Reduce(map.sum, comm->me == 0 ? sum.data() : nullptr, (int) n, MPI_INT64_T, MPI_SUM, 0,
             world);
  if (comm->me == 0) {
    const std::string path = map_series->step_file(update->ntimestep);
    write_map_vtp(path, sum);
    const double time = update->atime + (update->ntimestep - update->atimestep) * update->dt;
    if (!map_series->add(update->ntimestep, time))
      error->one(FLERR, "fix wall/lsdem {}: writing {} failed: {}", id, map_series->index_file(),
                 utils::getsyserror());
  }
  lsdem_wall_map_new_interval(&map);
}

/* ----------------------------------------------------------------------
   the wall's surface where it is now, with per triangle (cell data): mean normal force
   and pressure over the interval, mean tangential force, fraction of the interval's steps
   in contact, impacts and friction work since the start
------------------------------------------------------------------------- */

void FixWallLsdem::write_map_vtp(const std::string &path, const std::vector<int64_t> &sum) const
{
  const lsdem_band *b = bnd.shape.sdf.band;
  FILE *fp = fopen(path.c_str(), "w");
  if (!fp) error->one(FLERR, "fix wall/lsdem {}: cannot open {}: {}", id, path, utils::getsyserror());
  lsdem_wall_map total = map;  // the reduced sums, read through the core's units
  total.sum = const_cast<int64_t *>(sum.data());
  const double steps = total.steps > 0 ? (double) total.steps : 1.0;
  fmt::print(fp, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
             "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<PolyData>\n<Piece "
             "NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
             "NumberOfPolys=\"{}\">\n<Points>\n<DataArray type=\"Float64\" "
             "NumberOfComponents=\"3\" format=\"ascii\">\n", b->nverts, b->ntris);
  for (int64_t v = 0; v < b->nverts; v++) {
    double p[3];
    lsdem_affine3(bnd.pose.R, bnd.pose.x, &b->verts[3 * v], p);
    fmt::print(fp, "{:.9g} {:.9g} {:.9g}\n", p[0], p[1], p[2]);
  }
  fputs("</DataArray>\n</Points>\n<Polys>\n<DataArray type=\"Int64\" Name=\"connectivity\" "
        "format=\"ascii\">\n", fp);
  for (int64_t t = 0; t < b->ntris; t++)
    fmt::print(fp, "{} {} {}\n", b->tris[3 * t], b->tris[3 * t + 1], b->tris[3 * t + 2]);
  fputs("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n", fp);
  for (int64_t t = 1; t <= b->ntris; t++) fmt::print(fp, "{}\n", 3 * t);
  fputs("</DataArray>\n</Polys>\n<CellData Scalars=\"pressure\">\n", fp);
  auto array = [&](const char *name, const std::function<double(int64_t)> &value) {
    fmt::print(fp, "<DataArray type=\"Float64\" Name=\"{}\" format=\"ascii\">\n", name);
    for (int64_t t = 0; t < b->ntris; t++) fmt::print(fp, "{:.9g}\n", value(t));
    fputs("</DataArray>\n", fp);
  };
  auto area = [&](int64_t t) {
    const double *p0 = &b->verts[3 * b->tris[3 * t]], *p1 = &b->verts[3 * b->tris[3 * t + 1]];
    const double *p2 = &b->verts[3 * b->tris[3 * t + 2]];
    double e1[3], e2[3], n[3];
    lsdem_sub3(p1, p0, e1);
    lsdem_sub3(p2, p0, e2);
    lsdem_cross3(e1, e2, n);
    return 0.5 * sqrt(lsdem_dot3(n, n));
  };
  array("pressure", [&](int64_t t) {
    return lsdem_wall_map_value(&total, LSDEM_MAP_FN, t) / steps / area(t);
  });
  array("normal_force", [&](int64_t t) { return lsdem_wall_map_value(&total, LSDEM_MAP_FN, t) / steps; });
  array("shear_force", [&](int64_t t) { return lsdem_wall_map_value(&total, LSDEM_MAP_FT, t) / steps; });
  array("contact_fraction", [&](int64_t t) {
    return lsdem_wall_map_value(&total, LSDEM_MAP_CONTACTS, t) / steps;
  });
  array("impacts", [&](int64_t t) { return lsdem_wall_map_value(&total, LSDEM_MAP_IMPACTS, t); });
  array("friction_work", [&](int64_t t) { return lsdem_wall_map_value(&total, LSDEM_MAP_WORK, t); });
  array("area", area);
  fputs("</CellData>\n</Piece>\n</PolyData>\n</VTKFile>\n", fp);
  const bool bad = ferror(fp) != 0;
  if (fclose(fp) != 0 || bad) error->one(FLERR, "fix wall/lsdem {}: writing {} failed", id, path);
}

void FixWallLsdem::visit_all(const lsdem_pose &w)
{
  visit_candidates(*lanes[0], 0, ncand, w);
}

/* ----------------------------------------------------------------------
   a force call's start: the candidates, the lanes emptied, the pair states' pool opened
   for them; w: the wall as the contact kernel sees it now (a tilting platen's point
   moves with P plus its rotation about P)
------------------------------------------------------------------------- */

void FixWallLsdem::begin_force_call(int n, lsdem_pose &w)
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
  w = pose_at(0.0);
  if (!candidates_hold(w)) find_candidates(w);
  lanes[0]->path.begin_step(n);
}

/* ----------------------------------------------------------------------
   candidates [from, to) by the lane's path against the wall at pose w, each grain's
   centre distance phi and the wall's normal n there found once: a grain the wall reaches
   (and take[i] != 0 when take is given) is tested, visit(i, true, phi, n, slot); one that
   keeps a state from the last step (a pair state, or a sphere's spring in its slot) but is
   not tested is visited too, visit(i, false, phi, n, slot), and loses it; slot: the
   sphere's slot (keeps_sphere_slot), else nullptr and the visit between the path's
   begin_atom and end_atom
------------------------------------------------------------------------- */

template <class Visit>
void FixWallLsdem::each_candidate(Lane &lane, int from, int to, const lsdem_pose &w,
                                  const char *take, Visit visit)
{
  for (int c = from; c < to; c++) {
    const int i = cand[c];
    double n[3];
    const double phi = lsdem_boundary_distance(&bnd, &w, atom->x[i], n);
    const bool test = (!take || take[i]) && reaches_at(i, phi);
    lsdem_shear_hist *slot = keeps_sphere_slot(i) ? sphere_shear->slots(i) : nullptr;
    const bool kept = slot ? FixLsdemSphereShear::held(*slot) : lane.path.keeps_state(i);
    if (!test && !kept) continue;  // far, nothing kept
    if (!slot) lane.path.begin_atom();
    visit(i, test, phi, n, slot);
    if (!slot) lane.path.end_atom(i);
  }
}

/* ----------------------------------------------------------------------
   candidates [from, to) against wall pose w, by the lane's thread: each grain's contact
   through the shared path (a sphere's with its spring in its slot), its force and torque
   added to the grain (owned: one thread writes it) and, rounded to the quanta, to the
   lane's total on the wall, so that the wall's totals over lanes and ranks are the same
   in any order (lsdem_quantum_for); the centre's distance also rejects crossing() cheaply
------------------------------------------------------------------------- */

void FixWallLsdem::visit_candidates(Lane &lane, int from, int to, const lsdem_pose &w)
{
  const int *mask = atom->mask;
  const bigint step = update->ntimestep;
  each_candidate(lane, from, to, w, nullptr,
                 [&](int i, bool test, double phi, const double *n, lsdem_shear_hist *slot) {
    if (slot) {
      if (test) test_sphere(lane, i, w, *slot, phi, n);
      else FixLsdemSphereShear::drop(*slot);
    } else if (test) {
      test_grain(lane, i, w, step);
    }
    if ((mask[i] & groupbit) && lane.crossing.empty()) {
      double v[3];
      velocity_after_force(i, v);
      if (!lsdem_boundary_clear_of_crossing(&bnd, &w, atom->x[i], phi, v, update->dt))
        lane.crossing = crossing(i, w);
    }
  });
}

/* grain i, which the wall reaches, through the shared contact path (pair states in the
   general store) */
void FixWallLsdem::test_grain(Lane &lane, int i, const lsdem_pose &w, bigint step)
{
  const bool began = map_every > 0 && !lane.path.touched(i, WALL_PARTNER);  // maps only
  lsdem_pose p;
  LsdemContactPath::pose_of(atom, avec, i, p);
  lsdem_contact_result res;
  lane.path.test(i, WALL_PARTNER, avec->shape_of(i), p, &bnd.shape, w, prm, step, res);
  if (res.npen > 0) apply_contact(lane, i, res, w, began, true);
  if (twoway) test_points(lane, i, p, w);
}

/* sphere i, which the wall reaches, its centre at phi with the wall's normal n there,
   with its spring in its slot, in place: the sphere's overlap is the centre's (the one
   lookup lsdem_sphere_overlap would make again; a wall has no grid, whose outside it
   would handle) */
void FixWallLsdem::test_sphere(Lane &lane, int i, const lsdem_pose &w, lsdem_shear_hist &slot,
                               double phi, const double n[3])
{
  const double ra = avec->shape_of(i)->sdf.a[0];
  const double d = lsdem_sphere_depth(&bnd.shape.sdf, phi, ra);
  if (!(d > 0.0)) {
    FixLsdemSphereShear::drop(slot);
    return;
  }
  const bool began = map_every > 0 && !FixLsdemSphereShear::held(slot);  // maps only
  lsdem_pose p;
  LsdemContactPath::pose_of(atom, avec, i, p);
  lsdem_contact_result res;
  LsdemContactPath::overlapping_sphere_in_place(ra, p, w, n, d, prm, update->ntimestep, slot,
                                                res);
  apply_contact(lane, i, res, w, began, true);
}

/* ----------------------------------------------------------------------
   fix impulse/lsdem's call in place of the force call: the force path's visit with
   detection alone (LsdemContactPath::detect, the pair's node list kept), the wall at its
   pose s after now
------------------------------------------------------------------------- */

void FixWallLsdem::each_manifold(double s, const char *take, const ManifoldVisit &visit)
{
  const lsdem_pose w = pose_at(s);
  if (!candidates_hold(w)) find_candidates(w);
  const int n = lanes_for_call();
  lanes[0]->path.begin_step(n);
  if (n == 1) {
    detect_candidates(*lanes[0], 0, ncand, w, take, &visit);
  } else {
    // the lanes hold consecutive runs of the candidates: read in lane order, the serial
    // order, so the visits are the serial run's
    for (int l = 0; l < n; l++) {
      lanes[l]->found_i.clear();
      lanes[l]->found.clear();
      lanes[l]->found_points.clear();
    }
    detect_all(w, take, n);
    for (int l = 0; l < n; l++) {
      Lane &lane = *lanes[l];
      for (size_t k = 0; k < lane.found.size(); k++) {
        lsdem_manifold m = lane.found[k];
        m.point = lane.found_points.data() + (size_t) m.cap;
        m.cap = m.n;
        visit(lane.found_i[k], m);
      }
    }
  }
  lanes[0]->path.end_step();
}

void FixWallLsdem::detect_candidates(Lane &lane, int from, int to, const lsdem_pose &w,
                                     const char *take, const ManifoldVisit *visit)
{
  const bigint step = update->ntimestep;
  lane.found_i.clear();
  lane.found.clear();
  lane.found_points.clear();
  each_candidate(lane, from, to, w, take,
                 [&](int i, bool test, double, const double *, lsdem_shear_hist *) {
    if (!test) return;
    lsdem_pose p;
    LsdemContactPath::pose_of(atom, avec, i, p);
    if (lane.path.detect(i, WALL_PARTNER, avec->shape_of(i), p, &bnd.shape, w, prm.detect,
                         step) <= 0)
      return;
    const lsdem_manifold &m = lane.path.manifold();
    if (visit) {
      (*visit)(i, m);
      return;
    }
    lsdem_manifold kept = m;
    kept.point = nullptr;
    kept.cap = (int) lane.found_points.size();  // where its points start
    lane.found_i.push_back(i);
    lane.found.push_back(kept);
    lane.found_points.insert(lane.found_points.end(), m.point, m.point + m.n);
  });
}

void FixWallLsdem::detect_all(const lsdem_pose &w, const char *take, int n)
{
  for (int l = 0; l < n; l++) {  // one thread: lane 0 takes them all, the others none
    const int from = l == 0 ? 0 : ncand;
    detect_candidates(*lanes[l], from, ncand, w, take, nullptr);
  }
}

/* ---------------------------------------------------------------------- */

lsdem_impulse_guard_wall FixWallLsdem::guard_wall(double s, const lsdem_wall_params &step)
{
  lsdem_impulse_guard_wall g;
  g.boundary = &bnd;
  g.groups = groupbit;
  g.pose = pose_at(s);
  g.detect = prm.detect;
  const int nlocal = atom->nlocal;
  guard_lists.assign(nlocal, lsdem_nodelist());
  if (fix_history && prm.detect.node_skin > 0.0)
    for (int i = 0; i < nlocal; i++) {
      lsdem_pair_state st;
      if (fix_history->find(i, WALL_PARTNER, st)) guard_lists[i] = st.list;
    }
  g.lists = guard_lists.data();
  g.prm = step;
  g.prm.mu = opts.law.mu;
  g.far_gap = guard_gap(g.pose);
  g.near = g.far_gap > 0.0 ? cand_near.data() : nullptr;
  return g;
}

/* ----------------------------------------------------------------------
   a contact of grain i (res: force and torque on the grain, torque_b on the wall about
   its point) applied: rounded to the quanta, added to the grain and to the lane's totals
   on the wall; kept for output; a contact through the band checked for tunnelling
------------------------------------------------------------------------- */

void FixWallLsdem::apply_contact(Lane &lane, int i, const lsdem_contact_result &res,
                                 const lsdem_pose &w, bool began, bool through_band)
{
  lsdem_contact_terms t;
  lsdem_contact_terms_of(&res, 1.0, force_q, torque_q, &t);
  double *fi = atom->f[i], *ti = atom->torque[i];
  for (int d = 0; d < 3; d++) fi[d] += t.force[d];  // row by row: short loops the compiler pairs up
  for (int d = 0; d < 3; d++) ti[d] += t.torque_a[d];
  for (int d = 0; d < 3; d++) lane.f[d] -= t.force[d];
  for (int d = 0; d < 3; d++) lane.t[d] += t.torque_b[d];
  add_contact(lane, i, res, w, began);
  if (through_band && lane.crossing.empty() && lsdem_boundary_tunnelled(&bnd, res.max_depth))
    lane.crossing = tunnelled(i, res.max_depth);
  if (lane.crossing.empty() && thinnest.thinnest < HUGE_VAL) lane.crossing = too_fast_for_thin(i);
}

/* ----------------------------------------------------------------------
   twoway: the wall's sharp points in grain i's level set (the wall is the master there),
   turned into the grain's view (force and torque on the grain, the torque on the wall)
   and applied with the same weight as the grain's nodes: the points lie only on sharp
   convex edges, where the grain's nodes find (almost) nothing, so a contact is counted
   once (doc/fix_wall_lsdem.rst)
------------------------------------------------------------------------- */

void FixWallLsdem::test_points(Lane &lane, int i, const lsdem_pose &p, const lsdem_pose &w)
{
  const bool began = map_every > 0 && !lane.path.touched(i, WALL_POINTS_PARTNER);
  lsdem_contact_result res;
  if (lane.path.test_points(i, WALL_POINTS_PARTNER, bnd.shape.sdf.band, points, w,
                            avec->shape_of(i), p, prm, update->ntimestep, res) == 0)
    return;
  for (int d = 0; d < 3; d++) {
    const double t_wall = res.torque_a[d];
    res.force[d] = -res.force[d];
    res.torque_a[d] = res.torque_b[d];
    res.torque_b[d] = t_wall;
  }
  apply_contact(lane, i, res, w, began, false);
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
  if (bnd.pivots) reduce_pivot_load();
}

/* grain i's velocity after this step's force: fix nve/lsdem's next v */
void FixWallLsdem::velocity_after_force(int i, double v[3]) const
{
  const double kick = update->dt * force->ftm2v / atom->rmass[i];
  for (int k = 0; k < 3; k++) v[k] = atom->v[i][k] + kick * atom->f[i][k];
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
  // d: the centre's distance in front of the wall's surface; vn: its velocity relative to
  // the wall along the wall's normal there (< 0: towards the wall)
  const double dt = update->dt;
  double v[3], d, vn;
  velocity_after_force(i, v);
  if (!lsdem_boundary_crossing(&bnd, &w, atom->x[i], v, dt, &d, &vn)) return std::string();
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

/* ----------------------------------------------------------------------
   a node of grain i read the solid-side background of a band wall: it is deeper in the
   wall than the band is wide, the band no longer knows where the surface is
------------------------------------------------------------------------- */

std::string FixWallLsdem::tunnelled(int i, double depth) const
{
  const double width = bnd.shape.sdf.band->width;
  return fmt::format(
      "fix wall/lsdem {}: grain {} tunnelled into the wall at step {}: a node is at least "
      "{:.6g} deep, the band's whole width (lsdem-shape --width {:.6g}); a smaller time step, "
      "a stiffer wall or a wider band (made again with a larger --width) would hold it",
      id, atom->tag[i], update->ntimestep, depth, width);
}

/* ---------------------------------------------------------------------- */

void FixWallLsdem::add_contact(Lane &lane, int i, const lsdem_contact_result &res,
                               const lsdem_pose &w, bool began)
{
  lane.contact.emplace_back();
  Contact &c = lane.contact.back();
  c.i = i;
  c.npen = res.npen;
  for (int d = 0; d < 3; d++) {
    c.force[d] = res.force[d];
    c.point[d] = res.point[d];
  }
  c.tri = -1;
  if (map_every <= 0) return;
  // the map's inputs: the triangle nearest the contact point (wall frame), the wall's
  // normal there, the grain's tangential slip at the point relative to the wall over dt
  double rel[3], local[3], d2, vg[3], vw[3], arm[3], spin[3], vt[3];
  lsdem_sub3(c.point, w.x, rel);
  lsdem_matT_vec(w.R, rel, local);
  c.tri = lsdem_band_closest_triangle(bnd.shape.sdf.band, local, &d2);
  lsdem_boundary_distance(&bnd, &w, c.point, c.normal);
  lsdem_sub3(c.point, atom->x[i], arm);
  lsdem_cross3(atom->omega[i], arm, spin);
  lsdem_cross3(w.omega, rel, vw);
  for (int d = 0; d < 3; d++) {
    vg[d] = atom->v[i][d] + spin[d];
    vw[d] += w.v[d];
  }
  double vr[3];
  lsdem_sub3(vg, vw, vr);
  const double vn = lsdem_dot3(vr, c.normal);
  for (int d = 0; d < 3; d++) vt[d] = vr[d] - vn * c.normal[d];
  c.slide = sqrt(lsdem_dot3(vt, vt)) * update->dt;
  c.began = began;
}

/* ----------------------------------------------------------------------
   n = 0,1,2: total force the grains exert on the wall (x,y,z);
   n = 3,4,5: the wall's reference point (plane point or cylinder axis point) now;
   n = 6,7,8: the wall's body z axis in the world (plane normal or cylinder axis) now;
   n = 9: tilt of a pivoting platen, the angle (degrees) between its normal and the ram axis;
   n = 10,11,12: its angular velocity, or a spinning wall's (world, radians/time; else 0)
------------------------------------------------------------------------- */

double FixWallLsdem::compute_vector(int n)
{
  if (n >= 10) return bnd.pivots ? bnd.platen.omega[n - 10] : bnd.pose.omega[n - 10];
  if (n == 9) {
    if (!bnd.pivots) return 0.0;
    const double normal[3] = {bnd.pose.R[2], bnd.pose.R[5], bnd.pose.R[8]};
    return lsdem_tilt_angle(normal, bnd.platen.axis) * 180.0 / MY_PI;
  }
  if (n >= 6) return bnd.pose.R[3 * (n - 6) + 2];
  if (n >= 3) return bnd.pose.x[n - 3];
  if (!fall_valid) {
    MPI_Allreduce(flocal, fall, 3, MPI_DOUBLE, MPI_SUM, world);
    fall_valid = 1;
  }
  return fall[n];
}

/* ----------------------------------------------------------------------
   restart: the wall's current position, so that a moving wall resumes where it was (3
   doubles); with pivot, PIVOT_TAG first and then the wall point,
   pivot point, orientation and angular velocity (14 doubles); with spin, SPIN_TAG first
   and then the wall point, the spin's centre, its point at angle 0, the angle turned and
   the axis (14 doubles). With a force map the above is preceded by MAP_TAG and its count and
   followed by the map (see write_restart). The tags let any kind of fix read any kind of
   file without reading past its end.
------------------------------------------------------------------------- */

static const double PIVOT_TAG = -DBL_MAX, SPIN_TAG = -0.5 * DBL_MAX, MAP_TAG = -0.25 * DBL_MAX;

void FixWallLsdem::write_restart(FILE *fp)
{
  // the map's sums over all ranks (every rank calls this; rank 0 writes)
  const size_t nmap = map_every > 0 && map.sum ? (size_t) map.ntris * LSDEM_MAP_FIELDS : 0;
  std::vector<int64_t> sum(comm->me == 0 ? nmap : 0);
  if (nmap)
    MPI_Reduce(map.sum, comm->me == 0 ? sum.data() : nullptr, (int) nmap, MPI_INT64_T, MPI_SUM,
               0, world);
  if (comm->me == 0) {
    double list[14];
    int n = 0;
    const lsdem_platen &p = bnd.platen;
    if (bnd.pivots) list[n++] = PIVOT_TAG;
    for (int d = 0; d < 3; d++) list[n++] = bnd.pose.x[d];
    if (bnd.pivots) {
      for (int d = 0; d < 3; d++) list[n++] = p.x[d];
      for (int k = 0; k < 4; k++) list[n++] = p.q[k];
      for (int d = 0; d < 3; d++) list[n++] = p.omega[d];
    }
    if (bnd.spin.on) {
      n = 0;
      list[n++] = SPIN_TAG;
      for (int d = 0; d < 3; d++) list[n++] = bnd.pose.x[d];
      for (int d = 0; d < 3; d++) list[n++] = bnd.spin.centre[d];
      for (int d = 0; d < 3; d++) list[n++] = bnd.spin.x0[d];
      list[n++] = bnd.spin.angle;
      for (int d = 0; d < 3; d++) list[n++] = bnd.spin.axis[d];
    }
    // with a map: MAP_TAG, the count of the doubles above, them, then the map's
    // triangles and steps (doubles) and its sums (int64)
    const double head[2] = {MAP_TAG, (double) n}, tail[2] = {(double) map.ntris, (double) map.steps};
    int size = n * sizeof(double);
    if (nmap) size += (int) (sizeof head + sizeof tail + nmap * sizeof(int64_t));
    fwrite(&size, sizeof(int), 1, fp);
    if (nmap) fwrite(head, sizeof(double), 2, fp);
    fwrite(list, sizeof(double), n, fp);
    if (nmap) {
      fwrite(tail, sizeof(double), 2, fp);
      fwrite(sum.data(), sizeof(int64_t), nmap, fp);
    }
  }
}

void FixWallLsdem::restart(char *buf)
{
  const double *list = (const double *) buf;
  if (list[0] == MAP_TAG) {  // a map's sums after the wall's state
    const int n = (int) list[1];
    const double *tail = list + 2 + n;
    if (map_every > 0 && (int64_t) tail[0] == bnd.shape.sdf.band->ntris && comm->me == 0) {
      const size_t nmap = (size_t) tail[0] * LSDEM_MAP_FIELDS;
      map_restart.resize(nmap);
      memcpy(map_restart.data(), tail + 2, nmap * sizeof(int64_t));
    }
    map_restart_steps = (bigint) tail[1];
    map_booked = update->ntimestep;  // the file's step is in the sums already
    list += 2;
  }
  const bool tagged = list[0] == PIVOT_TAG, spun = list[0] == SPIN_TAG;
  const double *x = tagged || spun ? list + 1 : list;
  for (int d = 0; d < 3; d++) bnd.pose.x[d] = x[d];
  if (bnd.spin.on) {
    lsdem_spin &sp = bnd.spin;
    for (int d = 0; d < 3; d++) {
      sp.centre[d] = spun ? list[4 + d] : sp.centre[d];
      sp.x0[d] = spun ? list[7 + d] : bnd.pose.x[d];
    }
    sp.angle = spun ? list[10] : 0.0;  // a file without spin: from where the wall was
    for (int d = 0; spun && d < 3; d++) sp.axis[d] = list[11 + d];
    if (!spun) memcpy(sp.R0, bnd.pose.R, sizeof sp.R0);
    lsdem_boundary_place_spun(&bnd);
  }
  if (!bnd.pivots) return;
  lsdem_platen &p = bnd.platen;
  if (tagged) {
    for (int d = 0; d < 3; d++) {
      p.x[d] = list[4 + d];
      p.omega[d] = list[11 + d];
    }
    for (int k = 0; k < 4; k++) p.q[k] = list[7 + k];
  } else { // a file without pivot: the level platen where it was, at rest
    lsdem_boundary_pivot(&bnd, p.h, p.inertia, p.damping, nullptr);
  }
  lsdem_boundary_place_platen(&bnd);
}
