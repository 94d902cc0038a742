// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix ID group field/lsdem N prefix kernel W spacing H [regular V S]
       [mask cylinder cx cy R zlo zhi | mask membrane fixID] [wall fixID ...]
   (doc/fix_field_lsdem.rst). Every N steps (and at a run's setup when the step is a
   multiple of N), or on the steps an equal-style variable names (N = v_name): each
   grain of the group (mass, solid volume, centre, displacement since
   the reference) and each contact branch of pair_style lsdem and the listed wall/lsdem
   fixes (force on a grain of the group, contact point, grain centre: what compute
   stress/lsdem sums) travel to rank 0, sorted (grains by tag, branches by their values),
   so the fields are the same bits on any number of ranks; rank 0 calls the core
   (lsdem_fields_compute) and writes prefix_<step>.vti and prefix.pvd.

   The reference is the configuration at the first setup: each grain's unwrapped centre in
   a fix STORE row (it migrates with the grain and survives a restart), and the box's
   period vectors (global restart info). In a periodic dimension the core's grid spans the
   period (along the period vector: a triclinic box's grid is skewed with it); grains go at
   their unwrapped centres with their unwrapped displacements, and the box's change of
   period vectors is the displacement jump across a period (lsdem_field_box).
------------------------------------------------------------------------- */

#include "fix_field_lsdem.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_membrane_lsdem.h"
#include "fix_wall_lsdem.h"
#include "group.h"
#include "lsdem_input.h"
#include "modify.h"
#include "pair_lsdem.h"
#include "update.h"

#include <algorithm>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

// gathered rows: a grain is tag mass volume x[3] u[3]; a branch is tag_grain tag_other
// (a wall: -(its index among the listed walls + 1)) force[3] point[3] centre[3]
static constexpr int GRAIN_ROW = 9, BRANCH_ROW = 11;

static const char *USAGE = "fix ID group field/lsdem N|v_name prefix kernel W spacing H "
                           "[regular V S] [mask cylinder cx cy R zlo zhi | mask membrane "
                           "fixID] [wall fixID ...]";

// the keywords after which a list of wall IDs ends
static bool is_keyword(const char *word)
{
  for (const char *k : {"kernel", "spacing", "regular", "mask", "wall"})
    if (strcmp(word, k) == 0) return true;
  return false;
}

/* ---------------------------------------------------------------------- */

FixFieldLsdem::FixFieldLsdem(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), mask_kind(MASK_NONE), mask_centre{0.0, 0.0}, mask_radius(0.0),
  mask_zlo(0.0), mask_zhi(0.0), membrane(nullptr), have_ref_box(false), avec(nullptr),
  store(nullptr), have_reference(false), series(narg > 4 ? arg[4] : "", "vti")
{
  memset(&params, 0, sizeof params);
  memset(ref_period, 0, sizeof ref_period);
  memset(last_period, 0, sizeof last_period);
  restart_global = 1;
  if (narg < 9) error->all(FLERR, "Illegal fix field/lsdem command: {}", USAGE);
  steps.parse(lmp, arg[3], "Fix field/lsdem");
  nevery = 1;  // end_of_step follows the box's flips every step (steps decides the writes)
  if (std::string(arg[4]).find_first_of("*%") != std::string::npos)
    error->all(FLERR, "Fix field/lsdem takes a file prefix without * or %: it writes "
               "prefix_<step>.vti and prefix.pvd");
  params.width = params.h = 0.0;
  params.min_variance = LSDEM_FIELD_MIN_VARIANCE;
  params.min_weight = LSDEM_FIELD_MIN_WEIGHT;
  int iarg = 5;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if ((key == "kernel" || key == "spacing") && iarg + 1 < narg) {
      double &v = key == "kernel" ? params.width : params.h;
      v = LsdemInput::number(FLERR, arg[iarg + 1], "fix field/lsdem", key.c_str(), lmp);
      if (!(v > 0.0)) error->all(FLERR, "Fix field/lsdem: {} must be > 0, got {}", key, v);
      iarg += 2;
    } else if (key == "regular" && iarg + 2 < narg) {
      params.min_variance = LsdemInput::number(FLERR, arg[iarg + 1], "fix field/lsdem",
                                               "regular", lmp);
      params.min_weight = LsdemInput::number(FLERR, arg[iarg + 2], "fix field/lsdem",
                                             "regular", lmp);
      if (!(params.min_variance >= 0.0) || !(params.min_weight >= 0.0))
        error->all(FLERR, "Fix field/lsdem: regular values must be >= 0");
      iarg += 3;
    } else if (key == "mask" && iarg + 6 < narg && strcmp(arg[iarg + 1], "cylinder") == 0) {
      double *v[5] = {&mask_centre[0], &mask_centre[1], &mask_radius, &mask_zlo, &mask_zhi};
      for (int k = 0; k < 5; k++)
        *v[k] = LsdemInput::number(FLERR, arg[iarg + 2 + k], "fix field/lsdem", "mask", lmp);
      if (!(mask_radius > 0.0) || !(mask_zhi > mask_zlo))
        error->all(FLERR, "Fix field/lsdem: mask cylinder needs R > 0 and zhi > zlo");
      mask_kind = MASK_CYLINDER;
      iarg += 7;
    } else if (key == "mask" && iarg + 2 < narg && strcmp(arg[iarg + 1], "membrane") == 0) {
      membrane_id = arg[iarg + 2];
      mask_kind = MASK_MEMBRANE;
      iarg += 3;
    } else if (key == "wall" && iarg + 1 < narg) {
      iarg++;
      while (iarg < narg && !is_keyword(arg[iarg])) wall_ids.emplace_back(arg[iarg++]);
    } else {
      error->all(FLERR, "Illegal fix field/lsdem keyword {}: {}", key, USAGE);
    }
  }
  if (!(params.width > 0.0) || !(params.h > 0.0))
    error->all(FLERR, "Fix field/lsdem needs kernel W and spacing H: {}", USAGE);
  if (!dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem")))
    error->all(FLERR, "Fix field/lsdem requires atom_style lsdem");
}

/* ---------------------------------------------------------------------- */

FixFieldLsdem::~FixFieldLsdem()
{
  if (modify->nfix && !id_store.empty()) modify->delete_fix(id_store);
}

/* ----------------------------------------------------------------------
   the reference store is a fix of its own, added once this fix exists
------------------------------------------------------------------------- */

void FixFieldLsdem::post_constructor()
{
  id_store = std::string(id) + "_FIELD_STORE";
  store = LsdemCompat::add_peratom_store(modify, id_store, group->names[igroup], 3);
  have_reference = store->restart_reset;
  store->restart_reset = 0;
}

/* ---------------------------------------------------------------------- */

int FixFieldLsdem::setmask()
{
  return END_OF_STEP;
}

/* ---------------------------------------------------------------------- */

void FixFieldLsdem::init()
{
  store = LsdemCompat::find_peratom_store(modify, id_store.c_str());
  if (!store) error->all(FLERR, "Could not find fix field/lsdem's store {}", id_store);
  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  sources.find(lmp, wall_ids, "Fix field/lsdem");
  steps.init(lmp, "Fix field/lsdem");
  if (mask_kind == MASK_MEMBRANE) {
    const int ifix = modify->find_fix(membrane_id.c_str());
    membrane = ifix < 0 ? nullptr : dynamic_cast<FixMembraneLsdem *>(modify->fix[ifix]);
    if (!membrane)
      error->all(FLERR, "Fix field/lsdem: mask membrane {} is not a fix membrane/lsdem",
                 membrane_id);
    if (domain->zperiodic)
      error->all(FLERR, "Fix field/lsdem: mask membrane needs a box not periodic in z");
    // the inner layer's triangles (the surface through its sphere centres) and their vertices
    membrane_tri.clear();
    const std::vector<tagint> &tri = membrane->triangle_tags();
    const std::vector<int> &layer = membrane->triangle_layers();
    for (size_t t = 0; t < layer.size(); t++)
      if (layer[t] == 0) membrane_tri.insert(membrane_tri.end(), &tri[3 * t], &tri[3 * t] + 3);
    membrane_tags = membrane_tri;
    std::sort(membrane_tags.begin(), membrane_tags.end());
    membrane_tags.erase(std::unique(membrane_tags.begin(), membrane_tags.end()),
                        membrane_tags.end());
  }
}

/* ---------------------------------------------------------------------- */

void FixFieldLsdem::setup(int /*vflag*/)
{
  if (!have_reference) store_reference();
  if (!have_ref_box) {  // a restart file written before the reference box was kept
    if (comm->me == 0)
      error->warning(FLERR, "Fix field/lsdem: the restart file has no reference box; the box "
                     "now taken as the reference (wrong jumps if a periodic box deformed)");
    store_reference_box();
  }
  period_vectors(last_period);  // a change of the box between runs is a deformation
  if (steps.due_at_setup(update->ntimestep)) write_and_schedule();
}

/* ----------------------------------------------------------------------
   a flip of the box in the step (fix deform's: a tilt beyond half a length reset by a
   period vector) changes the basis of the reference's period vectors with it
------------------------------------------------------------------------- */

void FixFieldLsdem::end_of_step()
{
  if (domain->triclinic) {
    double now[3][3];
    period_vectors(now);
    lsdem_field_box_rebase(last_period, now, ref_period);
    memcpy(last_period, now, sizeof now);
  }
  if (steps.due(update->ntimestep)) write_and_schedule();
}

/* ----------------------------------------------------------------------
   every rank: the files (rank 0), then the next step to write
------------------------------------------------------------------------- */

void FixFieldLsdem::write_and_schedule()
{
  write_fields();
  steps.written(lmp, update->ntimestep, "Fix field/lsdem");
}

/* ---------------------------------------------------------------------- */

void FixFieldLsdem::period_vectors(double p[3][3]) const
{
  // a = (xprd 0 0), b = (xy yprd 0), c = (xz yz zprd)
  const double *h = domain->h;
  const double period[3][3] = {{h[0], 0.0, 0.0}, {h[5], h[1], 0.0}, {h[4], h[3], h[2]}};
  memcpy(p, period, sizeof period);
}

void FixFieldLsdem::store_reference_box()
{
  period_vectors(ref_period);
  have_ref_box = true;
}

void FixFieldLsdem::store_reference()
{
  store_reference_box();
  double **x = atom->x;
  const imageint *image = atom->image;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) domain->unmap(x[i], image[i], store->astore[i]);
  have_reference = true;
}

/* ---------------------------------------------------------------------- */

std::vector<double> FixFieldLsdem::grain_rows() const
{
  std::vector<double> rows;
  double **x = atom->x;
  const imageint *image = atom->image;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const lsdem_shape *shape = lsdem_library_shape(avec->library(), avec->shape[i]);
    double xu[3];
    domain->unmap(x[i], image[i], xu);
    // the unwrapped centre: the image whose displacement u is (lsdem_field_grain)
    const double row[GRAIN_ROW] = {(double) atom->tag[i], atom->rmass[i], shape->volume,
                                   xu[0], xu[1], xu[2],
                                   xu[0] - store->astore[i][0], xu[1] - store->astore[i][1],
                                   xu[2] - store->astore[i][2]};
    rows.insert(rows.end(), row, row + GRAIN_ROW);
  }
  return rows;
}

/* ----------------------------------------------------------------------
   the branches compute stress/lsdem sums: each pair test (listed once, on the rank owning
   its master) gives the master's side and the slave's side, a wall contact its grain's
------------------------------------------------------------------------- */

std::vector<double> FixFieldLsdem::branch_rows() const
{
  std::vector<double> rows;
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  double **x = atom->x;
  auto add = [&](int i, double other, const double *f, const double *point, double sign) {
    if (!(mask[i] & groupbit)) return;
    const double row[BRANCH_ROW] = {(double) tag[i], other, sign * f[0], sign * f[1],
                                    sign * f[2], point[0], point[1], point[2],
                                    x[i][0], x[i][1], x[i][2]};
    rows.insert(rows.end(), row, row + BRANCH_ROW);
  };
  sources.check_current(lmp, "Fix field/lsdem");
  if (sources.pair) {
    sources.pair->each_contact([&](const PairLsdem::Contact &c) {
      const double f[3] = {c.scale * c.res.force[0], c.scale * c.res.force[1],
                           c.scale * c.res.force[2]};
      add(c.i, (double) tag[c.j], f, c.res.point, 1.0);
      add(c.j, (double) tag[c.i], f, c.res.point, -1.0);
    });
  }
  for (int k = 0; k < (int) sources.walls.size(); k++)
    sources.walls[k]->each_contact([&](const FixWallLsdem::Contact &c) {
      add(c.i, -(double) (k + 1), c.force, c.point, 1.0);
    });
  return rows;
}

/* ---------------------------------------------------------------------- */

void FixFieldLsdem::write_fields()
{
  const double t0 = MPI_Wtime();
  const std::vector<double> grains = lsdem_gather_sorted(world, grain_rows(), GRAIN_ROW);
  const std::vector<double> branches = lsdem_gather_sorted(world, branch_rows(), BRANCH_ROW);
  const std::vector<double> nodes = lsdem_gather_sorted(world, membrane_rows(), 4);
  if (comm->me != 0) return;
  const int n = (int) (grains.size() / GRAIN_ROW), nb = (int) (branches.size() / BRANCH_ROW);
  if (n == 0) error->one(FLERR, "Fix field/lsdem: no grains in group {}", group->names[igroup]);
  std::vector<lsdem_field_grain> g(n);
  for (int i = 0; i < n; i++) {
    const double *r = &grains[(size_t) i * GRAIN_ROW];
    g[i].mass = r[1];
    g[i].volume = r[2];
    std::copy(r + 3, r + 6, g[i].x);
    std::copy(r + 6, r + 9, g[i].u);
  }
  std::vector<lsdem_field_branch> b(nb);
  for (int i = 0; i < nb; i++) {
    const double *r = &branches[(size_t) i * BRANCH_ROW];
    std::copy(r + 2, r + 5, b[i].force);
    std::copy(r + 5, r + 8, b[i].point);
    std::copy(r + 8, r + 11, b[i].centre);
  }
  lsdem_fields f;
  lsdem_error err;
  set_box();
  if (lsdem_fields_compute(&params, n, g.data(), nb, b.data(), &f, &err) != LSDEM_OK)
    error->one(FLERR, "Fix field/lsdem: {}", err.msg);
  if (mask_kind == MASK_CYLINDER)
    lsdem_fields_mask_cylinder(&f, mask_centre, mask_radius, mask_zlo, mask_zhi);
  if (mask_kind == MASK_MEMBRANE) mask_membrane(&f, nodes);
  const double t1 = MPI_Wtime();
  const std::string file = series.step_file(update->ntimestep);
  const lsdem_status s = lsdem_fields_write_vti(file.c_str(), &f, &err);
  const int nn[3] = {f.grid.n[0], f.grid.n[1], f.grid.n[2]};
  lsdem_fields_free(&f);
  if (s != LSDEM_OK) error->one(FLERR, "Fix field/lsdem: {}", err.msg);
  // the snapshot's cost, for progress and for bench/analysis_cost.sh (rank 0's wall time;
  // the other ranks wait for it at their next collective)
  utils::logmesg(lmp, "fix field/lsdem {}: step {}: {} grains on {}x{}x{} nodes: gathered and "
                 "computed in {:.3f} s, written in {:.3f} s: {}\n", id, update->ntimestep, n,
                 nn[0], nn[1], nn[2], t1 - t0, MPI_Wtime() - t1, file);
  const double time = update->atime + (update->ntimestep - update->atimestep) * update->dt;
  if (!series.add(update->ntimestep, time))
    error->one(FLERR, "Fix field/lsdem: writing {} failed: {}", series.index_file(),
               utils::getsyserror());
}

/* ----------------------------------------------------------------------
   the core's box: periodic dimensions, bounds and tilt factors now, and the displacement
   jump across each period (period vector now minus at the reference)
------------------------------------------------------------------------- */

void FixFieldLsdem::set_box()
{
  const int periodic[3] = {domain->xperiodic, domain->yperiodic, domain->zperiodic};
  double now[3][3];
  period_vectors(now);
  // the tilt factors xy, xz, yz: the off-diagonal of the period vectors (0: orthogonal)
  params.box.tilt[0] = now[1][0];
  params.box.tilt[1] = now[2][0];
  params.box.tilt[2] = now[2][1];
  for (int k = 0; k < 3; k++) {
    params.box.periodic[k] = periodic[k];
    params.box.lo[k] = domain->boxlo[k];
    params.box.hi[k] = domain->boxhi[k];
    for (int i = 0; i < 3; i++)
      params.box.jump[k][i] = periodic[k] ? now[k][i] - ref_period[k][i] : 0.0;
  }
}

/* ----------------------------------------------------------------------
   the membrane's inner-layer vertices here: tag x y z
------------------------------------------------------------------------- */

std::vector<double> FixFieldLsdem::membrane_rows() const
{
  std::vector<double> rows;
  if (mask_kind != MASK_MEMBRANE) return rows;
  for (int i = 0; i < atom->nlocal; i++)
    if (std::binary_search(membrane_tags.begin(), membrane_tags.end(), atom->tag[i])) {
      const double row[4] = {(double) atom->tag[i], atom->x[i][0], atom->x[i][1], atom->x[i][2]};
      rows.insert(rows.end(), row, row + 4);
    }
  return rows;
}

/* ----------------------------------------------------------------------
   rank 0: the nodes outside the membrane's inner layer, closed at its end rings (core
   lsdem_fields_mask_surface)
------------------------------------------------------------------------- */

void FixFieldLsdem::mask_membrane(lsdem_fields *f, const std::vector<double> &nodes)
{
  const int nv = (int) (nodes.size() / 4);
  if (nv != (int) membrane_tags.size())
    error->one(FLERR, "Fix field/lsdem: {} of the {} vertices of membrane {} exist", nv,
               membrane_tags.size(), membrane_id);
  std::vector<double> v(3 * (size_t) nv);
  for (int k = 0; k < nv; k++) std::copy(&nodes[4 * k + 1], &nodes[4 * k + 4], &v[3 * k]);
  std::vector<int> tri(membrane_tri.size());
  for (size_t k = 0; k < tri.size(); k++)  // rows sorted by tag, as membrane_tags
    tri[k] = (int) (std::lower_bound(membrane_tags.begin(), membrane_tags.end(),
                                     membrane_tri[k]) - membrane_tags.begin());
  lsdem_error err;
  if (lsdem_fields_mask_surface(f, nv, v.data(), (int) tri.size() / 3, tri.data(), &err) !=
      LSDEM_OK)
    error->one(FLERR, "Fix field/lsdem: mask membrane: {}", err.msg);
}

/* ----------------------------------------------------------------------
   global restart info: the reference box's period vectors
------------------------------------------------------------------------- */

void FixFieldLsdem::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  const int size = 9 * sizeof(double);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(&ref_period[0][0], sizeof(double), 9, fp);
}

void FixFieldLsdem::restart(char *buf)
{
  memcpy(&ref_period[0][0], buf, 9 * sizeof(double));
  have_ref_box = true;
}
