// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix ID group membrane/lsdem pressure P triangles FILE [weights wi wo] [knb K]

   Each triangle is handled once, by the rank owning its lowest-ID vertex; the other
   vertices are owned or ghost atoms (atom->map); forces on ghosts are summed back to
   their owners by reverse communication of a private buffer. Formulas in the core
   (membrane.c): lsdem_triangle_area_vector, lsdem_pressure_vertex_force,
   lsdem_triangle_volume_term, lsdem_cap_edge_accumulate / lsdem_cap_volume_term.
------------------------------------------------------------------------- */

#include "fix_membrane_lsdem.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "bond_lsdem_membrane.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "input.h"
#include "lsdem_input.h"
#include "lsdem_lammps_compat.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "pair_lsdem.h"
#include "update.h"
#include "variable.h"

#include "lsdem_kernel.h"

#include <cmath>
#include <cstdio>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {
enum { ROLE_MEMBRANE = 1, ROLE_INNER = 2, ROLE_MIDDLE = 4 };
constexpr int MIDDLE = ROLE_MEMBRANE | ROLE_MIDDLE;
constexpr int INNER_MIDDLE = MIDDLE | ROLE_INNER;
bool has_role(int role, int bits) { return (role & bits) == bits; }
// triangle_vertices: the rank owns the triangle, does not, or lacks one of its vertices
enum { TRI_OWNED = 0, TRI_NOT_OWNED = -1, TRI_MISSING = -2 };
constexpr double MAX_RB_FRACTION = 0.2;       // r_b <= Rs / 5
constexpr double MAX_SINK_FRACTION = 0.2;     // p A_s / knb <= 0.2 r_b
}    // namespace

/* ---------------------------------------------------------------------- */

FixMembraneLsdem::FixMembraneLsdem(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), specimen_radius(0.0), nlayers(0), ninner(0), pressure_value(0.0), knb(-1.0),
    tributary_area(0.0), checked_pressure(-1.0), on_specimen(false), specimen_share(1.0), pvar(-1), nmax(0), fpress(nullptr),
    role(nullptr), contact_radial(0.0), middle_area(0.0), vec_step(-1), radial_step(-1), bond(nullptr)
{
  const char *usage = "fix ID group membrane/lsdem pressure P triangles FILE "
                      "[weights w_inner w_outer] [knb K] [surface centres|specimen]";
  if (narg < 7 || strcmp(arg[3], "pressure") != 0 || strcmp(arg[5], "triangles") != 0)
    error->all(FLERR, "Illegal fix membrane/lsdem command: {}", usage);

  axis[0] = axis[1] = 0.0;
  sphere_radius[0] = sphere_radius[1] = 0.0;
  area0[0] = area0[1] = 0.0;
  vector_flag = 1;
  size_vector = 6;
  global_freq = 1;
  extvector = 0;
  comm_reverse = 4;

  if (utils::strmatch(arg[4], "^v_")) pstr = arg[4] + 2;
  else pressure_value = LsdemInput::number(FLERR, arg[4], "fix membrane/lsdem", "pressure", lmp);
  file = arg[6];
  weight[0] = weight[1] = -1.0;
  for (int iarg = 7; iarg < narg;) {
    if (strcmp(arg[iarg], "weights") == 0 && iarg + 2 < narg) {
      weight[0] = LsdemInput::number(FLERR, arg[iarg + 1], "fix membrane/lsdem", "weights", lmp);
      weight[1] = LsdemInput::number(FLERR, arg[iarg + 2], "fix membrane/lsdem", "weights", lmp);
      if (weight[0] < 0.0 || weight[1] < 0.0)
        error->all(FLERR, "fix membrane/lsdem: weights must be >= 0");
      iarg += 3;
    } else if (strcmp(arg[iarg], "surface") == 0 && iarg + 1 < narg) {
      if (strcmp(arg[iarg + 1], "centres") == 0) on_specimen = false;
      else if (strcmp(arg[iarg + 1], "specimen") == 0) on_specimen = true;
      else error->all(FLERR, "fix membrane/lsdem: surface must be centres or specimen");
      iarg += 2;
    } else if (strcmp(arg[iarg], "knb") == 0 && iarg + 1 < narg) {
      knb = LsdemInput::number(FLERR, arg[iarg + 1], "fix membrane/lsdem", "knb", lmp);
      if (knb <= 0.0) error->all(FLERR, "fix membrane/lsdem: knb ({}) must be > 0", knb);
      iarg += 2;
    } else error->all(FLERR, "Illegal fix membrane/lsdem keyword {}: {}", arg[iarg], usage);
  }

  // rank 0 reads; a failure stops all ranks
  std::string failure;
  if (comm->me == 0 && !(failure = read_file()).empty())
    failure = "fix membrane/lsdem: " + failure;
  AtomVecLsdem::stop_if_any_rank(lmp, FLERR, failure);
  bcast_file();
  if (weight[0] < 0.0) {
    weight[0] = nlayers == 2 ? 0.8 : 1.0;  // report §3.3.2: 80% inner, 20% outer
    weight[1] = nlayers == 2 ? 0.2 : 0.0;
  }
  ninner = 0;
  for (auto &kv : role_of)
    if (kv.second & ROLE_INNER) ninner++;
  for (int k = 0; k < 6; k++) vec[k] = 0.0;
  // the layers share the force P A_inner: the outer layer's pressure is scaled by
  // A_inner / A_outer of the membrane as generated (file), so restarts do not change it
  layer_scale[0] = 1.0;
  layer_scale[1] = nlayers == 2 ? area0[0] / area0[1] : 0.0;
  // specimen surface (radius Rs) per unit area of the inner centres' surface (Rs + r_b)
  specimen_share = specimen_radius / (specimen_radius + sphere_radius[0]);
  if (on_specimen) {
    layer_scale[0] *= specimen_share;
    layer_scale[1] *= specimen_share;
  }
}

/* ---------------------------------------------------------------------- */

FixMembraneLsdem::~FixMembraneLsdem()
{
  memory->destroy(fpress);
  memory->destroy(role);
}

/* ---------------------------------------------------------------------- */

int FixMembraneLsdem::setmask()
{
  return POST_FORCE;
}

/* ----------------------------------------------------------------------
   triangles file (doc/fix_membrane_lsdem.rst), read on rank 0 by the core's codec of the
   bonded-ball structures' files (lsdem_membrane_file_read, the net file's line reader)
------------------------------------------------------------------------- */

std::string FixMembraneLsdem::read_file()
{
  lsdem_membrane_file mf;
  lsdem_error err;
  if (lsdem_membrane_file_read(file.c_str(), &mf, &err) != LSDEM_OK) return err.msg;
  for (int k = 0; k < 2; k++) {
    axis[k] = mf.axis[k];
    sphere_radius[k] = mf.sphere_radius[k];
    area0[k] = mf.lateral_areas[k];
  }
  specimen_radius = mf.specimen_radius;
  nlayers = mf.layers;
  for (int v = 0; v < mf.nvertices; v++) {
    const tagint a = (tagint) mf.vertex[v];
    vtag.push_back(a);
    role_of[a] = ROLE_MEMBRANE | (mf.vertex_layer[v] == 0 ? ROLE_INNER : 0) |
        (mf.vertex_end[v] == 0 ? ROLE_MIDDLE : 0);
  }
  for (int t = 0; t < mf.ntriangles; t++) {
    for (int c = 0; c < 3; c++) tri.push_back((tagint) mf.triangle[3 * t + c]);
    tri_layer.push_back(mf.triangle_layer[t]);
  }
  for (int e = 0; e < mf.ncap_edges; e++) {
    cap.push_back((tagint) mf.cap_edge[2 * e]);
    cap.push_back((tagint) mf.cap_edge[2 * e + 1]);
    cap_layer.push_back(mf.cap_layer[e]);
    cap_end.push_back(mf.cap_end[e] - 1);
  }
  lsdem_membrane_file_free(&mf);
  return "";
}

/* ---------------------------------------------------------------------- */

void FixMembraneLsdem::bcast_file()
{
  double d[7] = {axis[0], axis[1], specimen_radius, sphere_radius[0], sphere_radius[1],
                 area0[0], area0[1]};
  MPI_Bcast(d, 7, MPI_DOUBLE, 0, world);
  axis[0] = d[0];
  axis[1] = d[1];
  specimen_radius = d[2];
  sphere_radius[0] = d[3];
  sphere_radius[1] = d[4];
  area0[0] = d[5];
  area0[1] = d[6];
  int n[4] = {nlayers, (int) vtag.size(), (int) tri_layer.size(), (int) cap_layer.size()};
  MPI_Bcast(n, 4, MPI_INT, 0, world);
  nlayers = n[0];
  std::vector<int> roles(n[1]);
  if (comm->me == 0)
    for (int v = 0; v < n[1]; v++) roles[v] = role_of[vtag[v]];
  vtag.resize(n[1]);
  tri.resize(3 * (size_t) n[2]);
  tri_layer.resize(n[2]);
  cap.resize(2 * (size_t) n[3]);
  cap_layer.resize(n[3]);
  cap_end.resize(n[3]);
  MPI_Bcast(vtag.data(), n[1], MPI_LMP_TAGINT, 0, world);
  MPI_Bcast(roles.data(), n[1], MPI_INT, 0, world);
  MPI_Bcast(tri.data(), 3 * n[2], MPI_LMP_TAGINT, 0, world);
  MPI_Bcast(tri_layer.data(), n[2], MPI_INT, 0, world);
  MPI_Bcast(cap.data(), 2 * n[3], MPI_LMP_TAGINT, 0, world);
  MPI_Bcast(cap_layer.data(), n[3], MPI_INT, 0, world);
  MPI_Bcast(cap_end.data(), n[3], MPI_INT, 0, world);
  role_of.clear();
  for (int v = 0; v < n[1]; v++) role_of[vtag[v]] = roles[v];
}

/* ---------------------------------------------------------------------- */

void FixMembraneLsdem::init()
{
  if (!atom->tag_enable || atom->map_style == Atom::MAP_NONE)
    error->all(FLERR, "fix membrane/lsdem needs atom IDs and an atom map");
  if (!force->newton_bond) error->all(FLERR, "fix membrane/lsdem needs newton_bond on");
  if (domain->xperiodic || domain->yperiodic)
    error->all(FLERR, "fix membrane/lsdem: the membrane must not cross a periodic boundary "
               "in x or y (use a non-periodic box: boundary f f f or m m m)");
  bond = dynamic_cast<BondLsdemMembrane *>(force->bond_match("lsdem/membrane"));
  if (!bond) bond = dynamic_cast<BondLsdemMembrane *>(force->bond_match("lsdem/membrane/omp"));
  if (!bond) error->all(FLERR, "fix membrane/lsdem needs bond_style lsdem/membrane");
  tvert.resize(3 * tri_layer.size());
  tterm.resize(4 * tri_layer.size());
  if (!pstr.empty()) {
    pvar = input->variable->find(pstr.c_str());
    if (pvar < 0) error->all(FLERR, "fix membrane/lsdem: variable {} does not exist", pstr);
    if (!input->variable->equalstyle(pvar))
      error->all(FLERR, "fix membrane/lsdem: variable {} must be equal-style", pstr);
  }
  if (knb <= 0.0) {
    Pair *pair = PairLsdem::of(force);
    int dim;
    double *kmax = pair ? (double *) pair->extract("kn_max", dim) : nullptr;
    if (!kmax || *kmax <= 0.0)
      error->all(FLERR, "fix membrane/lsdem: give the grain-membrane stiffness with keyword "
                 "knb (no pair_style lsdem stiffness found)");
    knb = *kmax;
  }
  double rb = sphere_radius[0];
  if (rb > MAX_RB_FRACTION * specimen_radius)
    error->all(FLERR, "fix membrane/lsdem: membrane sphere radius r_b = {} is too large for the "
               "specimen radius {} in {}: use r_b <= {} (a fifth of the specimen radius)",
               rb, specimen_radius, file, MAX_RB_FRACTION * specimen_radius);
  checked_pressure = -1.0;
}

/* ---------------------------------------------------------------------- */

void FixMembraneLsdem::setup(int vflag)
{
  grow();
  refresh_roles();
  // every vertex exists once and is in the group
  bigint mine = 0, outside = 0;
  for (int i = 0; i < atom->nlocal; i++)
    if (role[i]) {
      mine++;
      if (!(atom->mask[i] & groupbit)) outside++;
    }
  bigint all[2], loc[2] = {mine, outside};
  MPI_Allreduce(loc, all, 2, MPI_LMP_BIGINT, MPI_SUM, world);
  if (all[0] != (bigint) vtag.size())
    error->all(FLERR, "fix membrane/lsdem: {} of the {} membrane spheres of {} exist (read the "
               "data file written with it)", all[0], vtag.size(), file);
  if (all[1])
    error->all(FLERR, "fix membrane/lsdem: {} membrane spheres are not in fix group {}", all[1],
               group->names[igroup]);
  // tributary area of one inner sphere, for the pressure check
  vec_step = -1;
  compute_geometry();
  tributary_area = ninner ? vec[2] / ninner : 0.0;
  post_force(vflag);
}

/* ---------------------------------------------------------------------- */

void FixMembraneLsdem::grow()
{
  if (atom->nmax <= nmax) return;
  nmax = atom->nmax;
  memory->grow(fpress, nmax, 4, "membrane/lsdem:fpress");
  memory->grow(role, nmax, "membrane/lsdem:role");
}

/* per local and ghost atom, from the tag (after reneighbouring: atoms moved or changed) */
void FixMembraneLsdem::refresh_roles()
{
  int nall = atom->nlocal + atom->nghost;
  for (int i = 0; i < nall; i++) {
    auto it = role_of.find(atom->tag[i]);
    role[i] = it == role_of.end() ? 0 : it->second;
  }
}

/* ---------------------------------------------------------------------- */

void FixMembraneLsdem::current_pressure()
{
  if (pvar >= 0) {
    modify->clearstep_compute();
    pressure_value = input->variable->compute_equal(pvar);
    modify->addstep_compute(update->ntimestep + 1);
  }
  if (pressure_value != checked_pressure) check_apparatus(pressure_value);
}

/* The pressure on one inner sphere's tributary area must not push it deeper than
 * MAX_SINK_FRACTION r_b into a grain of contact stiffness knb. */
void FixMembraneLsdem::check_apparatus(double p)
{
  double rb = sphere_radius[0];
  double sink = std::fabs(p) * tributary_area / knb;
  if (sink > MAX_SINK_FRACTION * rb)
    error->all(FLERR, "fix membrane/lsdem: pressure {} is too high for the grain-membrane "
               "stiffness knb = {}: one inner sphere (tributary area {:.4g}) would sink {:.4g} "
               "= {:.0f}% of r_b = {} into a grain; use pressure <= {:.4g} or knb >= {:.4g}",
               p, knb, tributary_area, sink, 100.0 * sink / rb, rb,
               MAX_SINK_FRACTION * rb * knb / tributary_area,
               std::fabs(p) * tributary_area / (MAX_SINK_FRACTION * rb));
  checked_pressure = p;
}

/* ----------------------------------------------------------------------
   local index of a triangle's vertex (closest image to the owner vertex), -1 when it is
   neither owned nor a ghost here
------------------------------------------------------------------------- */

int FixMembraneLsdem::vertex(tagint tag, int owner) const
{
  int j = atom->map(tag);
  return j >= 0 ? domain->closest_image(owner, j) : -1;
}

/* Triangle t is computed by the rank owning its lowest-ID vertex: TRI_OWNED on that rank,
   with the local indices of its vertices (owned or ghost, closest images) in v;
   TRI_NOT_OWNED elsewhere; TRI_MISSING when a vertex is not here (note_missing_vertex). */
int FixMembraneLsdem::triangle_vertices(int t, int v[3]) const
{
  const tagint *tg = &tri[3 * t];
  int low = tg[0] < tg[1] ? (tg[0] < tg[2] ? 0 : 2) : (tg[1] < tg[2] ? 1 : 2);
  int owner = atom->map(tg[low]);
  if (owner < 0 || owner >= atom->nlocal) return TRI_NOT_OWNED;
  for (int k = 0; k < 3; k++) {
    v[k] = k == low ? owner : vertex(tg[k], owner);
    if (v[k] < 0) return TRI_MISSING;
  }
  return TRI_OWNED;
}

/* triangle_vertices into v; false (v[0] = TRI_NOT_OWNED or TRI_MISSING) when the triangle
   is not this rank's to compute */
bool FixMembraneLsdem::owned_vertices(int t, int *v) const
{
  int status = triangle_vertices(t, v);
  if (status != TRI_OWNED) v[0] = status;
  return status == TRI_OWNED;
}

/* the first missing vertex of this rank, kept in `missing`, which the caller reports on all
   ranks (stop_if_any_rank) */
void FixMembraneLsdem::note_missing_vertex(int t)
{
  if (!missing.empty()) return;
  const tagint *tg = &tri[3 * t];
  tagint gone = tg[0];
  for (int k = 0; k < 3; k++)
    if (atom->map(tg[k]) < 0) gone = tg[k];
  missing = fmt::format("fix membrane/lsdem: vertex {} of triangle {} ({} {} {}) is neither "
                        "owned nor a ghost on rank {}: the ghost cutoff is shorter than a "
                        "triangle edge (comm_modify cutoff) or the membrane tore apart", gone,
                        t + 1, tg[0], tg[1], tg[2], comm->me);
}

/* ---------------------------------------------------------------------- */

double FixMembraneLsdem::radial_projection(int i, const double *f) const
{
  double dx = atom->x[i][0] - axis[0], dy = atom->x[i][1] - axis[1];
  double r = sqrt(dx * dx + dy * dy);
  return r > 0.0 ? (f[0] * dx + f[1] * dy) / r : 0.0;
}

/* ----------------------------------------------------------------------
   A third of the specimen-surface area behind an inner triangle, for the radial stress:
   the radial projection S_T . r_hat of its area vector (r_hat at the centroid, radius r_T)
   is the area r dtheta dz it covers on a cylinder, unchanged when the membrane wrinkles
   between the grains (|S_T| is not); the specimen surface lies r_b further in, so that area
   is scaled by (r_T - r_b) / r_T.
------------------------------------------------------------------------- */

double FixMembraneLsdem::specimen_area_share(const double *a, const double *b, const double *c,
                                             const double *S) const
{
  double cx = (a[0] + b[0] + c[0]) / 3.0 - axis[0], cy = (a[1] + b[1] + c[1]) / 3.0 - axis[1];
  double r = sqrt(cx * cx + cy * cy);
  if (r <= sphere_radius[0]) return 0.0;
  return (S[0] * cx + S[1] * cy) / r * (r - sphere_radius[0]) / r / 3.0;
}

/* ----------------------------------------------------------------------
   phase one, triangles [from, to): report §2.3.5, each vertex of triangle T gets
   -w p S_T / 3 (p = pressure_value); the inner layer's specimen-surface share
------------------------------------------------------------------------- */

void FixMembraneLsdem::pressure_terms(int from, int to)
{
  double **x = atom->x;
  for (int t = from; t < to; t++) {
    int *v = &tvert[3 * t];
    if (!owned_vertices(t, v)) continue;
    double S[3], *term = &tterm[4 * t];
    lsdem_triangle_area_vector(x[v[0]], x[v[1]], x[v[2]], S);
    int layer = tri_layer[t];
    lsdem_pressure_vertex_force(S, weight[layer] * layer_scale[layer] * pressure_value, term);
    term[3] = layer == 0 ? specimen_area_share(x[v[0]], x[v[1]], x[v[2]], S) : 0.0;
  }
}

/* phase two: the terms onto the vertices in triangle order (shares in column 3, for the
   radial stress), summed over ranks, onto the owned spheres' forces */
void FixMembraneLsdem::apply_pressure()
{
  missing.clear();
  int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  for (int i = 0; i < nall; i++) fpress[i][0] = fpress[i][1] = fpress[i][2] = fpress[i][3] = 0.0;
  for_triangles(&FixMembraneLsdem::pressure_terms);
  int ntri = ntriangles();
  for (int t = 0; t < ntri; t++) {
    const int *v = &tvert[3 * t];
    if (v[0] == TRI_MISSING) note_missing_vertex(t);
    if (v[0] < 0) continue;
    const double *term = &tterm[4 * t];
    for (int k = 0; k < 3; k++) {
      double *fp = fpress[v[k]];
      fp[0] += term[0];
      fp[1] += term[1];
      fp[2] += term[2];
      fp[3] += term[3];
    }
  }
  AtomVecLsdem::stop_if_any_rank(lmp, FLERR, missing);
  LsdemCompat::reverse_comm(comm, this);
  double **fa = atom->f;
  for (int i = 0; i < nlocal; i++) {
    if (!role[i]) continue;
    fa[i][0] += fpress[i][0];
    fa[i][1] += fpress[i][1];
    fa[i][2] += fpress[i][2];
  }
}

/* ----------------------------------------------------------------------
   radial stress: contact force = force so far - bond forces, on the middle-ring spheres of
   both layers (grains that reach an outer sphere through the inner layer's gaps push on the
   membrane too; contacts between membrane spheres cancel in the sum). The grains push the
   membrane outward: positive = compressive on the specimen. Bond forces from this step's
   bond call (bond_style lsdem/membrane keeps them), else computed here.
------------------------------------------------------------------------- */

double FixMembraneLsdem::contact_radial_sum() const
{
  int nlocal = atom->nlocal;
  double **f = atom->f, **x = atom->x;
  double radial = 0.0;
  for (int i = 0; i < nlocal; i++)
    if (has_role(role[i], MIDDLE)) radial += radial_projection(i, f[i]);
  int **bondlist = neighbor->bondlist;
  for (int n = 0; n < neighbor->nbondlist; n++) {
    int i1 = bondlist[n][0], i2 = bondlist[n][1];
    bool r1 = has_role(role[i1], MIDDLE), r2 = has_role(role[i2], MIDDLE);
    if (!r1 && !r2) continue;
    double f2[3], f1[3];
    const double *kept = bond->force_on_atom2(n);
    if (kept) {
      f2[0] = kept[0];
      f2[1] = kept[1];
      f2[2] = kept[2];
    } else {
      bond->bond_force(x[i1], x[i2], bondlist[n][2], f2);
    }
    f1[0] = -f2[0];
    f1[1] = -f2[1];
    f1[2] = -f2[2];
    if (r1) radial -= radial_projection(i1, f1);
    if (r2) radial -= radial_projection(i2, f2);
  }
  return radial;
}

/* ---------------------------------------------------------------------- */

void FixMembraneLsdem::post_force(int /*vflag*/)
{
  grow();
  if (neighbor->ago == 0) refresh_roles();
  current_pressure();
  contact_radial = contact_radial_sum();
  apply_pressure();
  double area = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (has_role(role[i], INNER_MIDDLE)) area += fpress[i][3];
  middle_area = area;
  vec_step = radial_step = -1;
}

/* ----------------------------------------------------------------------
   output 2, the radial stress alone (fix ave/time samples it every step): the ranks'
   partial sums of the last post_force, per unit area of the specimen surface, compressive
   positive
------------------------------------------------------------------------- */

void FixMembraneLsdem::reduce_radial_stress()
{
  double loc[2] = {contact_radial, middle_area}, all[2];
  MPI_Allreduce(loc, all, 2, MPI_DOUBLE, MPI_SUM, world);
  vec[1] = all[1] > 0.0 ? all[0] / all[1] : 0.0;
  radial_step = update->ntimestep;
}

/* ---------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   volumes (eq 2.30 closed by the end-ring caps) and areas, reduced over ranks;
   positions relative to a common origin on the axis
------------------------------------------------------------------------- */

/* phase one, triangles [from, to): the volume term of eq 2.30 and the area, positions
   relative to a common origin on the axis */
void FixMembraneLsdem::geometry_terms(int from, int to)
{
  double **x = atom->x;
  for (int t = from; t < to; t++) {
    int *v = &tvert[3 * t];
    if (!owned_vertices(t, v)) continue;
    double p[3][3], S[3];
    for (int k = 0; k < 3; k++) {
      p[k][0] = x[v[k]][0] - axis[0];
      p[k][1] = x[v[k]][1] - axis[1];
      p[k][2] = x[v[k]][2];
    }
    lsdem_triangle_area_vector(p[0], p[1], p[2], S);
    tterm[4 * t] = lsdem_triangle_volume_term(p[0], p[1], p[2]);
    tterm[4 * t + 1] = sqrt(S[0] * S[0] + S[1] * S[1] + S[2] * S[2]);
  }
}

void FixMembraneLsdem::compute_geometry()
{
  missing.clear();
  int nlocal = atom->nlocal;
  double **x = atom->x;
  const double origin[3] = {axis[0], axis[1], 0.0};
  // local: volume[2], area[2], caps[layer][end] = sum_v(3), sum_s(3), n, radial sums(2)
  double loc[2 + 2 + 2 * 2 * 7 + 2] = {0.0};
  double *caps = loc + 4;
  auto rel = [&](int i, double *out) {
    for (int k = 0; k < 3; k++) out[k] = x[i][k] - origin[k];
  };
  for_triangles(&FixMembraneLsdem::geometry_terms);
  int ntri = ntriangles();
  for (int t = 0; t < ntri; t++) {
    if (tvert[3 * t] == TRI_MISSING) note_missing_vertex(t);
    if (tvert[3 * t] < 0) continue;
    loc[tri_layer[t]] += tterm[4 * t];
    loc[2 + tri_layer[t]] += tterm[4 * t + 1];
  }
  int ncap = (int) cap_layer.size();
  for (int e = 0; e < ncap; e++) {
    tagint a = cap[2 * e], b = cap[2 * e + 1];
    int owner = atom->map(a < b ? a : b);
    if (owner < 0 || owner >= nlocal) continue;
    int ja = atom->map(a), jb = atom->map(b);
    if (ja < 0 || jb < 0) {
      if (missing.empty())
        missing = fmt::format("fix membrane/lsdem: cap edge {} {} has a missing vertex on "
                              "rank {}", a, b, comm->me);
      continue;
    }
    int ia = a < b ? owner : domain->closest_image(owner, ja);
    int ib = a < b ? domain->closest_image(owner, jb) : owner;
    double pa[3], pb[3];
    rel(ia, pa);
    rel(ib, pb);
    double *c = caps + 7 * (2 * cap_layer[e] + cap_end[e]);
    lsdem_cap_edge_accumulate(pa, pb, c, c + 3);
    c[6] += 1.0;
  }
  loc[4 + 28] = contact_radial;
  loc[4 + 29] = middle_area;
  AtomVecLsdem::stop_if_any_rank(lmp, FLERR, missing);
  double all[34];
  MPI_Allreduce(loc, all, 34, MPI_DOUBLE, MPI_SUM, world);
  double vol[2] = {all[0], all[1]}, zc[2][2] = {{0, 0}, {0, 0}};
  for (int layer = 0; layer < 2; layer++)
    for (int end = 0; end < 2; end++) {
      const double *c = all + 4 + 7 * (2 * layer + end);
      int n = (int) lround(c[6]);
      vol[layer] += lsdem_cap_volume_term(c, n, c + 3);
      zc[layer][end] = n ? c[2] / n : 0.0;
    }
  double rb = sphere_radius[0], A = all[2], H = zc[0][1] - zc[0][0];
  vec[0] = vol[0];
  // per unit area of the specimen surface, compressive positive
  vec[1] = all[33] > 0.0 ? all[32] / all[33] : 0.0;
  vec[2] = A;
  vec[3] = lsdem_membrane_inset_volume(vol[0], A, H, rb);
  vec[4] = pressure_value;
  vec[5] = nlayers == 2 ? vol[1] : 0.0;
  vec_step = radial_step = update->ntimestep;
}

/* ---------------------------------------------------------------------- */

double FixMembraneLsdem::compute_vector(int n)
{
  if (n == 1) {
    if (radial_step != update->ntimestep) reduce_radial_stress();
  } else if (vec_step != update->ntimestep) {
    compute_geometry();
  }
  return vec[n];
}

/* ---------------------------------------------------------------------- */

int FixMembraneLsdem::pack_reverse_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++)
    for (int k = 0; k < 4; k++) buf[m++] = fpress[i][k];
  return m;
}

void FixMembraneLsdem::unpack_reverse_comm(int n, int *list, double *buf)
{
  int m = 0;
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 4; k++) fpress[list[i]][k] += buf[m++];
}

/* ---------------------------------------------------------------------- */

double FixMembraneLsdem::memory_usage()
{
  return (double) nmax * (4 * sizeof(double) + sizeof(int)) +
         (double) (tri.size() + cap.size() + vtag.size()) * sizeof(tagint);
}
