// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   compute ID group shearband/lsdem c_ID[N] threshold d [k K] [planes 1|2] [seed S]
           [phi v_phi psi v_psi] [kernel W] [bin B]
   (doc/compute_shearband_lsdem.rst). The group's grains whose indicator (column N of a
   per-atom compute, e.g. D2min or the von Mises shear of compute strain/lsdem) exceeds
   mean + K sd; up to two planes fitted to them (core lsdem_shearband_fit: RANSAC, then least
   squares). Global vector, per plane: dip, azimuth (degrees), inlier fraction, thickness
   (length), unit normal x y z (NaN for a plane not found); then, with phi and psi, the
   Coulomb, Roscoe and Arthur inclinations (degrees); then the group's D50 and, per plane,
   the thickness in D50, the indicator profile's width across the plane (core
   lsdem_shearband_profile), that width with the kernel's taken out, and it in D50.
   Per-atom vector: 0, or the band 1 or 2 the grain lies in.

   Every rank gathers every group grain (tag, position, indicator) and sorts them by tag, so
   every rank fits the same input in the same order: the results do not depend on the number
   of ranks.
------------------------------------------------------------------------- */

#include "compute_shearband_lsdem.h"

#include "arg_info.h"
#include "atom.h"
#include "atom_vec_lsdem.h"
#include "comm.h"
#include "error.h"
#include "input.h"
#include "memory.h"
#include "modify.h"
#include "update.h"
#include "variable.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

using namespace LAMMPS_NS;

static constexpr int PLANE_VALUES = 7;   // dip, azimuth, inlier fraction, thickness, normal
static constexpr int PROFILE_VALUES = 4; // thickness / D50, profile width, corrected, / D50
static constexpr int ROW = 6;            // tag, x, y, z, indicator, volume
static constexpr int RANSAC_SAMPLES = 500;

/* ---------------------------------------------------------------------- */

ComputeShearbandLsdem::ComputeShearbandLsdem(LAMMPS *lmp, int narg, char **arg) :
  Compute(lmp, narg, arg), column(0), source(nullptr), ivar{-1, -1}, kernel(0.0), bin(0.0),
  nmax(0), flag(nullptr)
{
  if (narg < 4) error->all(FLERR, "Illegal compute shearband/lsdem command: "
                           "compute ID group shearband/lsdem c_ID[N] threshold d ...");
  ArgInfo argi(arg[3], ArgInfo::COMPUTE);
  if (argi.get_type() != ArgInfo::COMPUTE || argi.get_dim() > 1)
    error->all(FLERR, "Compute shearband/lsdem: {} is not c_ID or c_ID[N]", arg[3]);
  id_source = argi.get_name();
  column = argi.get_index1();
  params.k = 2.0;
  params.threshold = 0.0;
  params.planes = 1;
  params.samples = RANSAC_SAMPLES;
  params.seed = 1;
  for (int iarg = 4; iarg < narg; iarg += 2) {
    if (iarg + 1 >= narg)
      error->all(FLERR, "Compute shearband/lsdem: {} needs a value", arg[iarg]);
    const char *v = arg[iarg + 1];
    if (strcmp(arg[iarg], "threshold") == 0) {
      params.threshold = utils::numeric(FLERR, v, false, lmp);
    } else if (strcmp(arg[iarg], "k") == 0) {
      params.k = utils::numeric(FLERR, v, false, lmp);
    } else if (strcmp(arg[iarg], "planes") == 0) {
      params.planes = utils::inumeric(FLERR, v, false, lmp);
    } else if (strcmp(arg[iarg], "seed") == 0) {
      params.seed = (uint64_t) utils::bnumeric(FLERR, v, false, lmp);
    } else if (strcmp(arg[iarg], "kernel") == 0) {
      kernel = utils::numeric(FLERR, v, false, lmp);
      if (!(kernel >= 0.0))
        error->all(FLERR, "Compute shearband/lsdem: kernel {}: expected a width >= 0 (the FWHM "
                   "of the indicator's smoothing, length units)", v);
    } else if (strcmp(arg[iarg], "bin") == 0) {
      bin = utils::numeric(FLERR, v, false, lmp);
      if (!(bin > 0.0))
        error->all(FLERR, "Compute shearband/lsdem: bin {}: expected a length > 0", v);
    } else if (strcmp(arg[iarg], "phi") == 0 || strcmp(arg[iarg], "psi") == 0) {
      if (strncmp(v, "v_", 2) != 0)
        error->all(FLERR, "Compute shearband/lsdem: {} {}: expected v_name", arg[iarg], v);
      theory_var[strcmp(arg[iarg], "psi") == 0] = v + 2;
    } else {
      error->all(FLERR, "Compute shearband/lsdem: unknown keyword {}", arg[iarg]);
    }
  }
  if (!(params.threshold > 0.0))
    error->all(FLERR, "Compute shearband/lsdem needs threshold d > 0");
  if (params.planes != 1 && params.planes != 2)
    error->all(FLERR, "Compute shearband/lsdem: planes {}: expected 1 or 2", params.planes);
  if (theory_var[0].empty() != theory_var[1].empty())
    error->all(FLERR, "Compute shearband/lsdem: phi and psi go together");

  vector_flag = 1;
  size_vector = PLANE_VALUES * params.planes + (theory_var[0].empty() ? 0 : 3) + 1 +
      PROFILE_VALUES * params.planes;
  extvector = 0;
  vector = new double[size_vector];
  peratom_flag = 1;
  size_peratom_cols = 0;
}

/* ---------------------------------------------------------------------- */

ComputeShearbandLsdem::~ComputeShearbandLsdem()
{
  delete[] vector;
  memory->destroy(flag);
}

/* ---------------------------------------------------------------------- */

void ComputeShearbandLsdem::init()
{
  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  if (!avec) error->all(FLERR, "Compute shearband/lsdem requires atom_style lsdem");
  const int ic = modify->find_compute(id_source);
  if (ic < 0) error->all(FLERR, "Compute shearband/lsdem: no compute {}", id_source);
  source = modify->compute[ic];
  if (!source->peratom_flag || (column == 0) != (source->size_peratom_cols == 0) ||
      column > source->size_peratom_cols)
    error->all(FLERR, "Compute shearband/lsdem: compute {} has no per-atom {}", id_source,
               column ? "column " + std::to_string(column) : std::string("vector"));
  for (int k = 0; k < 2 && !theory_var[0].empty(); k++) {
    ivar[k] = input->variable->find(theory_var[k].c_str());
    if (ivar[k] < 0 || !input->variable->equalstyle(ivar[k]))
      error->all(FLERR, "Compute shearband/lsdem: {} is not an equal-style variable",
                 theory_var[k]);
  }
}

/* ----------------------------------------------------------------------
   every group grain's row (tag, position, indicator), rank by rank, into rows; the rows
   each rank gave in count
------------------------------------------------------------------------- */

int ComputeShearbandLsdem::gather_rows(std::vector<int> &count)
{
  if (!(source->invoked_flag & Compute::INVOKED_PERATOM)) {
    source->compute_peratom();
    source->invoked_flag |= Compute::INVOKED_PERATOM;
  }
  std::vector<double> mine;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) {
      const double value = column ? source->array_atom[i][column - 1] : source->vector_atom[i];
      const double row[ROW] = {(double) atom->tag[i], atom->x[i][0], atom->x[i][1],
                               atom->x[i][2], value, avec->shape_of(i)->volume};
      mine.insert(mine.end(), row, row + ROW);
    }
  const int nmine = (int) mine.size();
  count.assign(comm->nprocs, 0);
  MPI_Allgather(&nmine, 1, MPI_INT, count.data(), 1, MPI_INT, world);
  std::vector<int> displ(comm->nprocs, 0);
  std::partial_sum(count.begin(), count.end() - 1, displ.begin() + 1);
  rows.resize((size_t) displ.back() + count.back());
  MPI_Allgatherv(mine.data(), nmine, MPI_DOUBLE, rows.data(), count.data(), displ.data(),
                 MPI_DOUBLE, world);
  return (int) (rows.size() / ROW);
}

/* ----------------------------------------------------------------------
   per owned atom its band; band[s] belongs to gathered row order[s]
------------------------------------------------------------------------- */

void ComputeShearbandLsdem::store_flags(const std::vector<int> &band,
                                        const std::vector<int> &order,
                                        const std::vector<int> &count)
{
  std::vector<int> by_row(order.size());
  for (size_t s = 0; s < order.size(); s++) by_row[order[s]] = band[s];
  int row = std::accumulate(count.begin(), count.begin() + comm->me, 0) / ROW;
  for (int i = 0; i < atom->nlocal; i++)
    flag[i] = (atom->mask[i] & groupbit) ? by_row[row++] : 0.0;
}

/* ---------------------------------------------------------------------- */

void ComputeShearbandLsdem::measure()
{
  if (atom->nmax > nmax) {
    memory->destroy(flag);
    nmax = atom->nmax;
    memory->create(flag, nmax, "shearband/lsdem:flag");
    vector_atom = flag;
  }
  std::vector<int> count;
  const int n = gather_rows(count);
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [this](int a, int b) { return rows[(size_t) ROW * a] < rows[(size_t) ROW * b]; });
  std::vector<double> x(3 * (size_t) n), value(n), volume(n);
  for (int s = 0; s < n; s++) {
    const double *r = &rows[(size_t) ROW * order[s]];
    std::copy(r + 1, r + 4, &x[3 * (size_t) s]);
    value[s] = r[4];
    volume[s] = r[5];
  }
  std::vector<int> band(n);
  lsdem_shearband_plane plane[2];
  int nplanes = 0;
  if (lsdem_shearband_fit(n, x.data(), value.data(), &params, plane, &nplanes, band.data()) !=
      LSDEM_OK)
    error->all(FLERR, "Compute shearband/lsdem: out of memory for {} grains", n);
  std::fill(vector, vector + PLANE_VALUES * params.planes, NAN);
  for (int q = 0; q < nplanes; q++) {
    const lsdem_shearband_plane &p = plane[q];
    const double v[PLANE_VALUES] = {p.dip, p.azimuth, p.inlier_fraction, p.thickness,
                                    p.normal[0], p.normal[1], p.normal[2]};
    std::copy(v, v + PLANE_VALUES, vector + PLANE_VALUES * q);
  }
  double *out = vector + PLANE_VALUES * params.planes;
  if (!theory_var[0].empty()) {
    lsdem_shearband_theory(input->variable->compute_equal(ivar[0]),
                           input->variable->compute_equal(ivar[1]), out);
    out += 3;
  }
  measure_widths(n, x.data(), value.data(), volume.data(), plane, nplanes, out);
  store_flags(band, order, count);
}

/* ----------------------------------------------------------------------
   the group's D50 (core lsdem_median_diameter, volume-equivalent diameters by volume), then
   per plane: thickness / D50, the indicator profile's width (bins of `bin`, or D50 / 2; the
   peak within the inlier threshold), that width with the kernel's removed, and it / D50
------------------------------------------------------------------------- */

void ComputeShearbandLsdem::measure_widths(int n, const double *x, const double *value,
                                           const double *volume,
                                           const lsdem_shearband_plane *plane, int nplanes,
                                           double *out)
{
  const double d50 = lsdem_median_diameter(n, volume);
  out[0] = d50;
  std::fill(out + 1, out + 1 + PROFILE_VALUES * params.planes, NAN);
  const double b = bin > 0.0 ? bin : 0.5 * d50;
  for (int q = 0; q < nplanes && b > 0.0; q++) {
    double *o = out + 1 + PROFILE_VALUES * q, width, corrected;
    if (lsdem_shearband_profile(n, x, value, &plane[q], b, params.threshold, kernel, &width,
                                &corrected) != LSDEM_OK)
      error->all(FLERR, "Compute shearband/lsdem: out of memory for {} grains", n);
    o[0] = plane[q].thickness / d50;
    o[1] = width;
    o[2] = corrected;
    o[3] = corrected / d50;
  }
}

/* ---------------------------------------------------------------------- */

void ComputeShearbandLsdem::compute_vector()
{
  invoked_vector = update->ntimestep;
  if (!(invoked_flag & Compute::INVOKED_PERATOM)) measure();  // else measured already
}

/* ---------------------------------------------------------------------- */

void ComputeShearbandLsdem::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  if (!(invoked_flag & Compute::INVOKED_VECTOR)) measure();  // else measured already
}

/* ---------------------------------------------------------------------- */

double ComputeShearbandLsdem::memory_usage()
{
  return (double) nmax * sizeof(double) + (double) rows.capacity() * sizeof(double);
}
