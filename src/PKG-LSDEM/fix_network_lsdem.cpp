// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix ID group network/lsdem N prefix [wall fixID ...]   (doc/fix_network_lsdem.rst)
   Every N steps (and at a run's setup when the step is a multiple of N), or on the steps
   an equal-style variable names (N = v_name): each contact
   between two grains of the group (pair_style lsdem's tests, two-way halves merged) and
   each contact of a grain of the group with a listed fix wall/lsdem travels to rank 0,
   sorted, with its normal force: the force on the grain along the partner's outward
   normal at the contact point (the slave's level-set gradient, the wall's normal).
   Rank 0 writes prefix_<step>.vtp (a polyline centre - contact point - centre, or centre -
   point for a wall) and prefix.pvd, and the strong-chain statistics (core
   lsdem_strong_chains) reach every rank as the fix's global vector.
------------------------------------------------------------------------- */

#include "fix_network_lsdem.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "comm.h"
#include "error.h"
#include "input.h"
#include "variable.h"
#include "fix_wall_lsdem.h"
#include "lsdem_input.h"
#include "pair_lsdem.h"
#include "update.h"

#include <cmath>
#include <cstdio>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

// a gathered contact: tag_a tag_b (a wall: -(its index among the listed walls + 1), tag_a
// < tag_b for grains) force_on_a[3] point[3] x_a[3] x_b[3] (a wall: the point) fn
// normal[3] (unit, the partner's outward normal at the point, towards a)
static constexpr int ROW = 18, FORCE = 2, POINT = 5, XA = 8, XB = 11, FN = 14, NORMAL = 15;

/* ---------------------------------------------------------------------- */

FixNetworkLsdem::FixNetworkLsdem(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), avec(nullptr), series(narg > 4 ? arg[4] : "", "vtp"), band_ivar(-1),
  stats{}, nstats(11)
{
  const char *usage = "fix ID group network/lsdem N|v_name prefix [band v_name] [wall fixID ...]";
  if (narg < 5) error->all(FLERR, "Illegal fix network/lsdem command: {}", usage);
  nevery = steps.parse(lmp, arg[3], "Fix network/lsdem");
  if (std::string(arg[4]).find_first_of("*%") != std::string::npos)
    error->all(FLERR, "Fix network/lsdem takes a file prefix without * or %: it writes "
               "prefix_<step>.vtp and prefix.pvd");
  int iarg = 5;
  if (iarg + 1 < narg && strcmp(arg[iarg], "band") == 0) {
    if (strncmp(arg[iarg + 1], "v_", 2) != 0)
      error->all(FLERR, "Fix network/lsdem: band takes an atom-style variable v_name (e.g. "
                 "of compute shearband/lsdem's flag), not {}", arg[iarg + 1]);
    band_var = arg[iarg + 1] + 2;
    nstats = 27;
    iarg += 2;
  }
  if (iarg < narg && (strcmp(arg[iarg], "wall") != 0 || iarg + 1 == narg))
    error->all(FLERR, "Illegal fix network/lsdem command: {}", usage);
  for (iarg++; iarg < narg; iarg++) wall_ids.emplace_back(arg[iarg]);
  if (!dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem")))
    error->all(FLERR, "Fix network/lsdem requires atom_style lsdem");
  vector_flag = 1;
  size_vector = nstats;
  global_freq = nevery;
  extvector = 0;
}

/* ---------------------------------------------------------------------- */

int FixNetworkLsdem::setmask()
{
  return END_OF_STEP;
}

/* ---------------------------------------------------------------------- */

void FixNetworkLsdem::init()
{
  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  sources.find(lmp, wall_ids, "Fix network/lsdem");
  if (!sources.pair && sources.walls.empty())
    error->all(FLERR, "Fix network/lsdem needs pair_style lsdem or a wall");
  steps.init(lmp, "Fix network/lsdem");
  if (!band_var.empty()) {
    band_ivar = input->variable->find(band_var.c_str());
    if (band_ivar < 0 || !input->variable->atomstyle(band_ivar))
      error->all(FLERR, "Fix network/lsdem: band variable {} is not an atom-style variable",
                 band_var);
  }
}

/* ---------------------------------------------------------------------- */

void FixNetworkLsdem::setup(int /*vflag*/)
{
  if (steps.due_at_setup(update->ntimestep)) write_network();
}

/* ---------------------------------------------------------------------- */

void FixNetworkLsdem::end_of_step()
{
  if (steps.due(update->ntimestep)) write_network();
}

/* ---------------------------------------------------------------------- */

double FixNetworkLsdem::compute_vector(int n)
{
  return stats[n];
}

/* ----------------------------------------------------------------------
   f . n, n the unit outward normal of grain j's level set at the point (world frame, into
   normal): positive when f pushes the grain away from j
------------------------------------------------------------------------- */

double FixNetworkLsdem::pair_normal_force(int j, const double *force_on_i,
                                          const double *point, double normal[3]) const
{
  const lsdem_shape *shape = lsdem_library_shape(avec->library(), avec->shape[j]);
  double rel[3], body[3], grad[3], n[3];
  lsdem_sub3(point, atom->x[j], rel);
  lsdem_quat_rotate_inv(avec->quat[j], rel, body);
  lsdem_sdf_eval(&shape->sdf, body, grad);
  lsdem_quat_rotate(avec->quat[j], grad, n);
  const double len = std::sqrt(lsdem_dot3(n, n));
  for (int d = 0; d < 3; d++) normal[d] = len > 0.0 ? n[d] / len : 0.0;
  return lsdem_dot3(force_on_i, normal);
}

/* ---------------------------------------------------------------------- */

std::vector<double> FixNetworkLsdem::contact_rows() const
{
  std::vector<double> rows;
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  double **x = atom->x;
  auto add = [&](double ta, double tb, const double *f, double sign, const double *point,
                 const double *xa, const double *xb, double fn, const double *n) {
    const double row[ROW] = {ta, tb, sign * f[0], sign * f[1], sign * f[2],
                             point[0], point[1], point[2], xa[0], xa[1], xa[2],
                             xb[0], xb[1], xb[2], fn, sign * n[0], sign * n[1], sign * n[2]};
    rows.insert(rows.end(), row, row + ROW);
  };
  sources.check_current(lmp, "Fix network/lsdem");
  if (sources.pair)
    sources.pair->each_contact([&](const PairLsdem::Contact &c) {
      if (!(mask[c.i] & groupbit) || !(mask[c.j] & groupbit)) return;
      const double f[3] = {c.scale * c.res.force[0], c.scale * c.res.force[1],
                           c.scale * c.res.force[2]};
      double n[3];
      const double fn = pair_normal_force(c.j, f, c.res.point, n);
      if (tag[c.i] < tag[c.j])
        add((double) tag[c.i], (double) tag[c.j], f, 1.0, c.res.point, x[c.i], x[c.j], fn, n);
      else
        add((double) tag[c.j], (double) tag[c.i], f, -1.0, c.res.point, x[c.j], x[c.i], fn, n);
    });
  for (int k = 0; k < (int) sources.walls.size(); k++) {
    const lsdem_boundary &wall = sources.walls[k]->boundary();
    sources.walls[k]->each_contact([&](const FixWallLsdem::Contact &c) {
      if (!(mask[c.i] & groupbit)) return;
      double n[3];
      lsdem_boundary_distance(&wall, &wall.pose, c.point, n);
      const double len = std::sqrt(lsdem_dot3(n, n));
      for (int d = 0; d < 3; d++) n[d] = len > 0.0 ? n[d] / len : 0.0;
      const double fn = lsdem_dot3(c.force, n);
      add((double) tag[c.i], -(double) (k + 1), c.force, 1.0, c.point, x[c.i], c.point, fn, n);
    });
  }
  return rows;
}

/* ----------------------------------------------------------------------
   the sorted rows with the tests of one pair (two-way mode: one per side) merged: forces
   and normal forces summed, contact points averaged
------------------------------------------------------------------------- */

static std::vector<double> merge_pairs(const std::vector<double> &rows)
{
  std::vector<double> out;
  const size_t n = rows.size() / ROW;
  for (size_t r = 0; r < n;) {
    const double *first = &rows[r * ROW];
    size_t s = r + 1;
    while (s < n && rows[s * ROW] == first[0] && rows[s * ROW + 1] == first[1]) s++;
    std::vector<double> line(first, first + ROW);
    for (size_t t = r + 1; t < s; t++) {
      for (int d = 0; d < 3; d++) {
        line[FORCE + d] += rows[t * ROW + FORCE + d];
        line[POINT + d] += rows[t * ROW + POINT + d];
      }
      line[FN] += rows[t * ROW + FN];
    }
    for (int d = 0; d < 3; d++) line[POINT + d] /= (double) (s - r);
    out.insert(out.end(), line.begin(), line.end());
    r = s;
  }
  return out;
}

/* ---------------------------------------------------------------------- */

void FixNetworkLsdem::write_network()
{
  const std::vector<double> rows = lsdem_gather_sorted(world, contact_rows(), ROW);
  if (comm->me == 0) {
    const std::vector<double> lines = merge_pairs(rows);
    const int n = (int) (lines.size() / ROW);
    std::vector<double> fn(n);
    for (int l = 0; l < n; l++) fn[l] = lines[(size_t) l * ROW + FN];
    lsdem_chain_stats cs;
    lsdem_strong_chains(n, fn.data(), &cs);
    stats[0] = cs.contacts;
    stats[1] = cs.mean;
    stats[2] = cs.strong_fraction;
    stats[3] = cs.strong_share;
    std::vector<char> keep(lines.size() / ROW);
    for (size_t l = 0; l < keep.size(); l++) keep[l] = lines[l * ROW + 1] > 0.0;  // grains
    normal_fabric(lines, keep, stats + 4);
    if (band_ivar >= 0) {  // inside: both grains in the band; outside: the other grain lines
      const std::vector<char> in = lines_in_band(lines);
      for (size_t l = 0; l < keep.size(); l++) keep[l] = keep[l] && in[l];
      stats[11] = normal_fabric(lines, keep, stats + 12);
      for (size_t l = 0; l < keep.size(); l++) keep[l] = lines[l * ROW + 1] > 0.0 && !in[l];
      stats[19] = normal_fabric(lines, keep, stats + 20);
    }
    write_vtp(lines, fn);
  } else if (band_ivar >= 0) {
    lines_in_band(std::vector<double>());  // the gather is collective
  }
  MPI_Bcast(stats, nstats, MPI_DOUBLE, 0, world);
  steps.written(lmp, update->ntimestep, "Fix network/lsdem");
}

/* ----------------------------------------------------------------------
   the contact-normal fabric of the lines kept (report §3.5.4's measure, as compute
   fabric/lsdem's of long axes): the deviator D (xx yy zz xy xz yz) of F = <n n> and the
   anisotropy a (0 for no line); a merged two-way line keeps its first test's normal.
   Returns the lines counted.
------------------------------------------------------------------------- */

int FixNetworkLsdem::normal_fabric(const std::vector<double> &lines,
                                   const std::vector<char> &keep, double *out)
{
  double F[9] = {0.0}, D[9];
  int count = 0;
  for (size_t l = 0; l < keep.size(); l++) {
    if (!keep[l]) continue;
    lsdem_fabric_add(F, &lines[l * ROW + NORMAL]);
    count++;
  }
  if (count == 0) {
    for (int k = 0; k < 7; k++) out[k] = 0.0;
    return 0;
  }
  lsdem_fabric_deviator(F, (double) count, D);
  const int ij[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
  for (int k = 0; k < 6; k++) out[k] = D[3 * ij[k][0] + ij[k][1]];
  out[6] = lsdem_fabric_anisotropy(D);
  return count;
}

/* ----------------------------------------------------------------------
   which lines join two grains both flagged by the band variable (collective: every rank
   gathers its grains' tag and flag to rank 0, which classifies the lines)
------------------------------------------------------------------------- */

std::vector<char> FixNetworkLsdem::lines_in_band(const std::vector<double> &lines)
{
  const int nlocal = atom->nlocal;
  std::vector<double> flag(nlocal > 0 ? nlocal : 1), mine;
  input->variable->compute_atom(band_ivar, 0, flag.data(), 1, 0);
  for (int i = 0; i < nlocal; i++) {
    mine.push_back((double) atom->tag[i]);
    mine.push_back(flag[i] != 0.0 ? 1.0 : 0.0);
  }
  const std::vector<double> all = lsdem_gather_sorted(world, mine, 2);
  std::vector<char> in(lines.size() / ROW, 0);
  auto flagged = [&](double tag) {  // all is sorted by tag
    size_t lo = 0, hi = all.size() / 2;
    while (lo < hi) {
      const size_t mid = (lo + hi) / 2;
      if (all[2 * mid] < tag) lo = mid + 1;
      else hi = mid;
    }
    return lo < all.size() / 2 && all[2 * lo] == tag && all[2 * lo + 1] != 0.0;
  };
  for (size_t l = 0; l < in.size(); l++)
    in[l] = flagged(lines[l * ROW]) && flagged(lines[l * ROW + 1]);
  return in;
}

/* ----------------------------------------------------------------------
   one polyline per contact: x_a, point, x_b (a wall contact: x_a, point); cell data
   id_a, id_b (a wall: -(index + 1)), normal_force, force (on grain a), normal (the
   partner's outward unit normal), strong (1/0)
------------------------------------------------------------------------- */

void FixNetworkLsdem::write_vtp(const std::vector<double> &lines, const std::vector<double> &fn)
{
  const int n = (int) fn.size();
  const double mean = stats[1];
  auto is_wall = [&](int l) { return lines[(size_t) l * ROW + 1] < 0.0; };
  int npoints = 0;
  for (int l = 0; l < n; l++) npoints += is_wall(l) ? 2 : 3;
  const std::string file = series.step_file(update->ntimestep);
  FILE *fp = fopen(file.c_str(), "w");
  if (!fp)
    error->one(FLERR, "Fix network/lsdem cannot open {}: {}", file, utils::getsyserror());
  fmt::print(fp, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
             "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<PolyData>\n"
             "<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" "
             "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n<Points>\n"
             "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n",
             npoints, n);
  for (int l = 0; l < n; l++) {
    const double *r = &lines[(size_t) l * ROW];
    const int ends[3] = {XA, POINT, XB};
    for (int e = 0; e < (is_wall(l) ? 2 : 3); e++)
      fmt::print(fp, "{:.17g} {:.17g} {:.17g}\n", r[ends[e]], r[ends[e] + 1], r[ends[e] + 2]);
  }
  fputs("</DataArray>\n</Points>\n<Lines>\n"
        "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n", fp);
  int point = 0;
  std::string offsets;
  for (int l = 0; l < n; l++) {
    const int m = is_wall(l) ? 2 : 3;
    for (int e = 0; e < m; e++) fmt::print(fp, "{}\n", point + e);
    point += m;
    offsets += fmt::format("{}\n", point);
  }
  fmt::print(fp, "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n"
             "{}</DataArray>\n</Lines>\n<CellData Scalars=\"normal_force\">\n", offsets);
  const char *idname[2] = {"id_a", "id_b"};
  for (int k = 0; k < 2; k++) {
    fmt::print(fp, "<DataArray type=\"Int64\" Name=\"{}\" format=\"ascii\">\n", idname[k]);
    for (int l = 0; l < n; l++) fmt::print(fp, "{}\n", (long long) lines[(size_t) l * ROW + k]);
    fputs("</DataArray>\n", fp);
  }
  fputs("<DataArray type=\"Float64\" Name=\"normal_force\" format=\"ascii\">\n", fp);
  for (int l = 0; l < n; l++) fmt::print(fp, "{:.17g}\n", fn[l]);
  fputs("</DataArray>\n", fp);
  const char *vecname[2] = {"force", "normal"};
  const int vecat[2] = {FORCE, NORMAL};
  for (int k = 0; k < 2; k++) {
    fmt::print(fp, "<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"3\" "
               "format=\"ascii\">\n", vecname[k]);
    for (int l = 0; l < n; l++) {
      const double *v = &lines[(size_t) l * ROW + vecat[k]];
      fmt::print(fp, "{:.17g} {:.17g} {:.17g}\n", v[0], v[1], v[2]);
    }
    fputs("</DataArray>\n", fp);
  }
  fputs("<DataArray type=\"UInt8\" Name=\"strong\" format=\"ascii\">\n", fp);
  for (int l = 0; l < n; l++) fmt::print(fp, "{}\n", fn[l] > mean ? 1 : 0);
  fputs("</DataArray>\n</CellData>\n</Piece>\n</PolyData>\n</VTKFile>\n", fp);
  const bool bad = ferror(fp) != 0;
  if (fclose(fp) != 0 || bad) error->one(FLERR, "Fix network/lsdem: writing {} failed", file);
  const double time = update->atime + (update->ntimestep - update->atimestep) * update->dt;
  if (!series.add(update->ntimestep, time))
    error->one(FLERR, "Fix network/lsdem: writing {} failed: {}", series.index_file(),
               utils::getsyserror());
}
