// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   atom_style lsdem library <file>: one atom per rigid grain (report §2.2: a grain is a
   level-set grid plus surface nodes in its principal frame). Per grain we keep only
   state: position, velocity, quaternion, angular velocity, shape index, mass and
   principal moments, and the integrator's previous corrector increment. Grids and
   nodes stay in the shape library, mapped read-only once per process.
------------------------------------------------------------------------- */

#include "atom_vec_lsdem.h"
#include "abort_flush.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "input.h"
#include "lsdem_data_file.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <utility>
#include <vector>

using namespace LAMMPS_NS;

namespace {

// One Storage per Atom object. It must outlive every AtomVecLsdem of that Atom: the
// base AtomVec destructor (and, for atom_style hybrid, the hybrid style's destructor,
// which runs after its sub-styles are deleted) frees the arrays through the addresses
// registered in atom->peratom and resets the pointers to null. Entries are never
// erased; a later Atom at the same address finds null pointers, as after a fresh start.
// A separate entry per Atom keeps replicate correct: it packs atoms from the old Atom
// into a new one while both exist.
AtomVecLsdem::Storage &storage_for(const Atom *a)
{
  static std::map<const Atom *, AtomVecLsdem::Storage> registry;
  return registry[a];  // value-initialised (all null) on first use
}

// Line-buffered from now on (glibc: setvbuf with no buffer only sets the mode, also on a
// stream already written to).
void line_buffered(FILE *f)
{
  if (!f) return;
  fflush(f);
  setvbuf(f, nullptr, _IOLBF, 0);
}

// Output kept when another rank aborts (at atom_style, and at each run for a new 'log'
// file): the log and screen line-buffered, since an error->one on another rank kills rank 0
// at once through MPI_Abort and rank 0's buffered lines were lost with it (this also lets a
// long run's progress be followed, tail -f); and a rank with neither (ranks > 0 under
// -screen none) sends its aborting errors to stderr; the ranks mpirun then terminates flush
// their streams (dumps with flush no).
void keep_output_on_abort(LAMMPS *lmp)
{
  line_buffered(lmp->logfile);
  line_buffered(lmp->screen);
  lsdem_note_error_output(lmp->screen || lmp->logfile);
  lsdem_flush_on_terminate();
}

#if LSDEM_CHECK_DATA_LINES
// What follows the values that LAMMPS's data reader gave a line, to the end of that line
// and without a '#' comment; nmore = how many it took after values[nvalues - 1] (image
// flags). The reader (Atom::data_atoms, data_vels) cuts a section into values at any white
// space, line ends included, ends each with a NUL written over the separator after it, and
// counts the values of the first line of each chunk only; the rest of its buffer is as read,
// each line ending in '\n' and the buffer in a NUL. So a line with a value too many leaves it
// here, and one with a value too few took the first of the next line, whose others are here
// (the line after that then crashes the reader). When the line end directly followed the
// last value, the NUL replaced it and the whole next line is here.
std::string text_after_values(char **values, int nvalues, int &nmore)
{
  const char *p = values[nvalues - 1] + strlen(values[nvalues - 1]) + 1;
  nmore = 0;
  for (;;) {  // values taken later end in a NUL, text not read yet in a separator
    const char *word = p + strspn(p, " \t\r\f");
    const size_t len = strcspn(word, " \t\n\r\f");
    if (len == 0 || word[len] != '\0') break;
    nmore++;
    p = word + len + 1;
  }
  const std::string rest(p, strcspn(p, "\n"));
  return rest.substr(0, rest.find('#'));
}
#endif

// Comm::rendezvous callback: the atom IDs sent to this rank (each ID goes to rank ID % nprocs);
// those present more than once go to *ptr with their counts.
int find_repeated_ids(int n, char *inbuf, int &flag, int *& /*proclist*/, char *& /*outbuf*/,
                      void *ptr)
{
  tagint *ids = (tagint *) inbuf;
  std::sort(ids, ids + n);
  auto *repeated = static_cast<std::vector<std::pair<tagint, int>> *>(ptr);
  for (int i = 0, j; i < n; i = j) {
    for (j = i + 1; j < n && ids[j] == ids[i]; j++) {}
    if (j - i > 1) repeated->emplace_back(ids[i], j - i);
  }
  flag = 0;  // nothing to send back
  return 0;
}

// names accepted by compute property/atom, in property index order
const char *const property_names[] = {"qw",       "qx",       "qy",       "qz",   "shape",
                                      "inertia1", "inertia2", "inertia3", "nodes"};
const int nproperty = sizeof(property_names) / sizeof(property_names[0]);

}    // namespace

/* ---------------------------------------------------------------------- */

AtomVecLsdem::AtomVecLsdem(LAMMPS *lmp) : AtomVec(lmp)
{
  mass_type = PER_ATOM;
  molecular = Atom::ATOMIC;

  atom->radius_flag = atom->rmass_flag = atom->omega_flag = atom->torque_flag = 1;

  shape = nullptr;
  quat = inertia = dwprev = nullptr;
  radius = rmass = nullptr;
  omega = nullptr;
  lib = nullptr;
  shape0 = nullptr;
  nshape_open = 0;
  maxradius = 0.0;
  min_grain_radius = HUGE_VAL;
  rmass_one = 0.0;

  store = &storage_for(atom);
  register_peratom("shape", &store->shape, Atom::INT, 0);
  register_peratom("quat", &store->quat, Atom::DOUBLE, 4);
  register_peratom("inertia", &store->inertia, Atom::DOUBLE, 3);
  register_peratom("dwprev", &store->dwprev, Atom::DOUBLE, 3);

  // radius = bounding radius of the shape; omega is world-frame; quat goes with every
  // forward communication (grains rotate every step) and with borders (ghosts created
  // at reneighbouring get no forward communication that step)

  fields_grow = LsdemCompat::fields("radius rmass omega torque shape quat inertia dwprev");
  fields_copy = LsdemCompat::fields("radius rmass omega shape quat inertia dwprev");
  fields_comm = LsdemCompat::fields("quat");
  fields_comm_vel = LsdemCompat::fields("omega quat");
  fields_reverse = LsdemCompat::fields("torque");
  fields_border = LsdemCompat::fields("radius rmass shape inertia quat");
  fields_border_vel = LsdemCompat::fields("radius rmass shape inertia quat omega");
  fields_exchange = LsdemCompat::fields("radius rmass omega shape quat inertia dwprev");
  fields_restart = LsdemCompat::fields("radius rmass omega shape quat inertia dwprev");
  fields_create = LsdemCompat::fields("radius rmass omega shape quat inertia dwprev");
  fields_data_atom = LsdemCompat::fields("id type shape rmass x quat");
  fields_data_vel = LsdemCompat::fields("id v omega");
}

/* ---------------------------------------------------------------------- */

AtomVecLsdem::~AtomVecLsdem()
{
  lsdem_library_close(lib);
}

/* ----------------------------------------------------------------------
   add a per-atom array to atom->peratom, or point an existing entry of the same name
   (a second atom_style command, read_restart) at our storage
------------------------------------------------------------------------- */

void AtomVecLsdem::register_peratom(const char *name, void *address, int datatype, int cols)
{
  for (int i = 0; i < LsdemCompat::peratom_count(atom); i++) {
    if (strcmp(LsdemCompat::cstr(atom->peratom[i].name), name) == 0) {
      if (atom->peratom[i].datatype != datatype || atom->peratom[i].cols != cols)
        error->all(FLERR, "atom_style lsdem: per-atom array '{}' already exists "
                   "with a different layout", name);
      atom->peratom[i].address = address;
      return;
    }
  }
  atom->add_peratom(name, address, datatype, cols);
}

/* ----------------------------------------------------------------------
   atom_style lsdem library <file>
------------------------------------------------------------------------- */

void AtomVecLsdem::process_args(int narg, char **arg)
{
  if (narg != 2 || strcmp(arg[0], "library") != 0)
    error->all(FLERR, "Illegal atom_style lsdem command: expected 'atom_style lsdem "
               "library <file.lslib>'");
  keep_output_on_abort(lmp);
  open_library(arg[1]);
  if (comm->me == 0) report_library();
  setup_fields();
}

/* ----------------------------------------------------------------------
   grains are 3d bodies (level sets, quaternions, Euler's equations)
------------------------------------------------------------------------- */

void AtomVecLsdem::init()
{
  AtomVec::init();
  if (domain->dimension != 3)
    error->all(FLERR, "atom_style lsdem needs a 3d simulation (remove 'dimension {}')",
               domain->dimension);
  keep_output_on_abort(lmp);
  stop_if_any_rank(lmp, FLERR, repeated_ids());
  std::string bad;
  for (int i = 0; i < atom->nlocal && bad.empty(); i++) bad = body_mismatch(i);
  stop_if_any_rank(lmp, FLERR, bad);
}

/* ----------------------------------------------------------------------
   atom IDs held by more than one atom (LAMMPS's read_data only notices some: a largest ID
   below the atom count), as a message naming those this rank found, or "": each ID is sorted
   with its copies on rank ID % nprocs (one rendezvous of the local IDs)
------------------------------------------------------------------------- */

std::string AtomVecLsdem::repeated_ids() const
{
  if (!atom->tag_enable) return std::string();
  const int nlocal = atom->nlocal;
  std::vector<tagint> ids(atom->tag, atom->tag + nlocal);
  std::vector<int> procs(nlocal);
  for (int i = 0; i < nlocal; i++) procs[i] = (int) (ids[i] % comm->nprocs);
  std::vector<std::pair<tagint, int>> repeated;
  char *unused = nullptr;
  comm->rendezvous(1, nlocal, (char *) ids.data(), sizeof(tagint), 0, procs.data(),
                   find_repeated_ids, 0, unused, 0, &repeated);
  bigint mine = repeated.size(), total;
  MPI_Allreduce(&mine, &total, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (repeated.empty()) return std::string();
  const size_t max_named = 10;
  std::string list;
  for (size_t k = 0; k < repeated.size() && k < max_named; k++)
    list += fmt::format("{}{} ({} atoms)", k ? ", " : "", repeated[k].first, repeated[k].second);
  if (total > (bigint) std::min(repeated.size(), max_named))
    list += fmt::format(" and {} more", total - (bigint) std::min(repeated.size(), max_named));
  return fmt::format("atom_style lsdem: {} atom ID{} given to more than one atom: {}; every "
                     "grain needs its own ID (check the Atoms sections read, and the IDs "
                     "that read_data add merge keeps)", total, total == 1 ? " is" : "s are",
                     list);
}

/* ----------------------------------------------------------------------
   what is wrong with atom i's radius, mass and moments, or "": they come from its shape
   (bounding radius; density times volume and times the unit moments), and LAMMPS's set
   diameter, set mass and set density (which uses a sphere's volume) would change them
   apart. The moments are compared as I/m with the shape's J/V (relative 1e-9: a density
   read back from a data file may differ from the written one in its last bit).
------------------------------------------------------------------------- */

std::string AtomVecLsdem::body_mismatch(int i) const
{
  const lsdem_shape *sh = shape_of(i);
  const tagint id = atom->tag[i];
  const char *fix = "the radius, mass and moments of a grain come from its shape and the "
                    "density given in the data file (set diameter, set mass and set density do "
                    "not apply to atom_style lsdem)";
  if (radius[i] != sh->radius)
    return fmt::format("atom_style lsdem: atom {} has radius {} but its shape {} has bounding "
                       "radius {}; {}", id, radius[i], shape[i] + 1, sh->radius, fix);
  const double *I = inertia[i];
  bool same = rmass[i] > 0.0 && std::isfinite(rmass[i]);
  for (int k = 0; k < 3 && same; k++)
    same = std::fabs(I[k] / rmass[i] - sh->inertia[k] / sh->volume) <=
           1e-9 * (sh->inertia[k] / sh->volume);
  if (!same)
    return fmt::format("atom_style lsdem: atom {} has mass {} but moments of inertia {} {} {} "
                       "(its shape {} gives mass/moments in the ratio {} : {} {} {}); {}", id,
                       rmass[i], I[0], I[1], I[2], shape[i] + 1, sh->volume, sh->inertia[0],
                       sh->inertia[1], sh->inertia[2], fix);
  return std::string();
}

/* ---------------------------------------------------------------------- */

void AtomVecLsdem::open_library(const char *path)
{
  lsdem_error err;
  err.msg[0] = '\0';
  lsdem_library_close(lib);
  lib = nullptr;
  shape0 = nullptr;
  nshape_open = 0;
  libpath = path;
  if (lsdem_library_open(path, &lib, &err) != LSDEM_OK)
    error->all(FLERR, "atom_style lsdem: cannot open shape library {}: {}", path, err.msg);
  if (lsdem_library_count(lib) <= 0)
    error->all(FLERR, "atom_style lsdem: shape library {} holds no shapes", path);
  shape0 = lsdem_library_shape(lib, 0);
  nshape_open = lsdem_library_count(lib);
  // open reads no section (grids, nodes): rank 0 checks their checksums and values once
  std::string damaged;
  if (comm->me == 0 && lsdem_library_verify(lib, -1, &err) != LSDEM_OK)
    damaged = fmt::format("atom_style lsdem: shape library {} is damaged or invalid: {} "
                          "(lsdem-shape verify lists every bad shape)", path, err.msg);
  stop_if_any_rank(lmp, FLERR, damaged);

  maxradius = 0.0;
  min_grain_radius = HUGE_VAL;
  for (int s = 0; s < lsdem_library_count(lib); s++) {
    const lsdem_shape *sh = lsdem_library_shape(lib, s);
    maxradius = std::max(maxradius, sh->radius);
    if (sh->sdf.kind != LSDEM_SDF_SPHERE) min_grain_radius = std::min(min_grain_radius, sh->radius);
  }
}

/* ---------------------------------------------------------------------- */

void AtomVecLsdem::stop_if_any_rank(LAMMPS *lmp, const char *file, int line,
                                    const std::string &mesg)
{
  const int me = lmp->comm->me, nprocs = lmp->comm->nprocs;
  const int mine = mesg.empty() ? nprocs : me;
  int first;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, lmp->world);
  if (first == nprocs) return;
  int len = me == first ? (int) mesg.size() : 0;
  MPI_Bcast(&len, 1, MPI_INT, first, lmp->world);
  std::string text = me == first ? mesg : std::string(len, ' ');
  MPI_Bcast(&text[0], len, MPI_CHAR, first, lmp->world);
  if (first > 0) text += fmt::format(" (found on rank {})", first);
  // Buffered output (dumps with flush no) reaches its files now: after error->all, main()
  // meets the other ranks at a barrier and exits, and a rank that exits first can have
  // mpirun kill rank 0 before exit() would have flushed it.
  fflush(nullptr);
  lmp->error->all(file, line, text);
}

/* ----------------------------------------------------------------------
   print the shapes (or a summary) and warn about coarse grids: an LS sphere needs a
   grid spacing finer than about R/10 to behave like a DEM sphere (Duriez & Bonelli 2021)
------------------------------------------------------------------------- */

void AtomVecLsdem::report_library()
{
  const int n = lsdem_library_count(lib);
  std::string mesg = fmt::format("LSDEM shape library: {} shape{}, max bounding radius {:.6g}\n",
                                 n, n == 1 ? "" : "s", maxradius);
  if (n <= 20) {
    mesg += fmt::format("  {:>5} {:<16} {:<9} {:>7} {:>13} {:>13}\n", "shape", "name", "kind",
                        "nodes", "radius", "volume");
    for (int s = 0; s < n; s++) {
      const lsdem_shape *sh = lsdem_library_shape(lib, s);
      const char *name = lsdem_library_name(lib, s);
      mesg += fmt::format("  {:>5} {:<16} {:<9} {:>7} {:>13.6g} {:>13.6g}\n", s + 1,
                          (name && name[0]) ? name : "-", lsdem_sdf_kind_name(sh->sdf.kind),
                          sh->nnodes, sh->radius, sh->volume);
    }
  } else {
    double rmin = maxradius, vmin = HUGE_VAL, vmax = 0.0;
    long nodes = 0;
    for (int s = 0; s < n; s++) {
      const lsdem_shape *sh = lsdem_library_shape(lib, s);
      rmin = std::min(rmin, sh->radius);
      vmin = std::min(vmin, sh->volume);
      vmax = std::max(vmax, sh->volume);
      nodes += sh->nnodes;
    }
    mesg += fmt::format("  bounding radius {:.6g} to {:.6g}, volume {:.6g} to {:.6g}, "
                        "{:.1f} nodes per shape on average\n", rmin, maxradius, vmin, vmax,
                        (double) nodes / n);
  }
  utils::logmesg(lmp, mesg);

  // name the first few coarse shapes, count the rest (CT libraries hold thousands)
  const int max_named = 10;
  int ncoarse = 0;
  for (int s = 0; s < n; s++) {
    const lsdem_shape *sh = lsdem_library_shape(lib, s);
    if (sh->sdf.kind != LSDEM_SDF_GRID || !lsdem_grid_is_coarse(sh->sdf.grid.h, sh->volume))
      continue;
    if (++ncoarse > max_named) continue;
    const char *name = lsdem_library_name(lib, s);
    const double limit = lsdem_grid_spacing_limit(sh->volume);
    error->warning(FLERR, "atom_style lsdem: shape {} ({}) has grid spacing {:.6g}, "
                   "coarser than R/10 = {:.6g} (R = equivalent-volume radius {:.6g}); "
                   "contacts will be rough", s + 1, (name && name[0]) ? name : "unnamed",
                   sh->sdf.grid.h, limit, 10.0 * limit);
  }
  if (ncoarse > max_named)
    error->warning(FLERR, "atom_style lsdem: {} more shapes have grid spacings coarser than "
                   "R/10", ncoarse - max_named);
}

/* ----------------------------------------------------------------------
   local copies of the per-atom arrays (also for replicate, where two styles coexist)
------------------------------------------------------------------------- */

void AtomVecLsdem::grow_pointers()
{
  radius = atom->radius;
  rmass = atom->rmass;
  omega = atom->omega;
  shape = store->shape;
  quat = store->quat;
  inertia = store->inertia;
  dwprev = store->dwprev;
}

/* ----------------------------------------------------------------------
   create_atoms: shape 1 of the library at density 1, identity orientation
------------------------------------------------------------------------- */

void AtomVecLsdem::create_atom_post(int ilocal)
{
  const lsdem_shape *sh = lsdem_library_shape(lib, 0);
  shape[ilocal] = 0;
  quat[ilocal][0] = 1.0;
  radius[ilocal] = sh->radius;
  rmass[ilocal] = sh->volume;
  for (int k = 0; k < 3; k++) inertia[ilocal][k] = sh->inertia[k];
}

#if LSDEM_CHECK_DATA_LINES
/* ----------------------------------------------------------------------
   the Atoms or Velocities line whose values LAMMPS has just cut (values[0..nvalues-1], after
   nbefore others) has exactly as many as the section's first line: after them only blanks or
   a comment, or (when its line end was overwritten) a whole next line of that many
------------------------------------------------------------------------- */

void AtomVecLsdem::check_data_line(char **values, int nvalues, int nbefore,
                                   const char *section, const char *layout,
                                   const std::string &id)
{
  int nmore;
  const std::string rest = text_after_values(values, nvalues, nmore);
  const int nwords = nbefore + nvalues + nmore;
  const size_t nrest = utils::count_words(rest);
  if (nrest == 0 || (int) nrest == nwords) return;
  error->one(FLERR, "read_data: each {} line needs {} values ({}{}), but after the {} read "
             "for atom {} comes '{}' ({} value{}) before a line end: the line of atom {}, or "
             "this next line, has more or fewer values than {}", section, nwords, layout,
             nmore ? " ix iy iz" : "", nwords, id, utils::trim(rest), nrest,
             nrest == 1 ? "" : "s", id, nwords);
}
#endif

/* ----------------------------------------------------------------------
   the data file read_data reads (input->arg[0]) holds as many Atoms lines as its header
   declares atoms: LAMMPS reads the declared count of lines and stops on a blank or keyword
   line with "Incorrect atom format in data file". Read once per file and atom count by each
   rank that gets an atom; a file the rank cannot open is left to read_data.
------------------------------------------------------------------------- */

void AtomVecLsdem::check_atoms_count()
{
  if (input->narg < 1) return;
  const std::string key = fmt::format("{}\n{}", input->arg[0], atom->natoms);
  if (key == data_file_checked) return;
  data_file_checked = key;
  const std::string problem = LsdemDataFile::atoms_count_problem(input->arg[0]);
  if (!problem.empty()) error->one(FLERR, problem);
}

/* ----------------------------------------------------------------------
   Atoms line: id type shape-ID density x y z qw qx qy qz [ix iy iz]; checked before
   AtomVec::data_atom reads it (its values' count: by LAMMPS itself since 2022)
------------------------------------------------------------------------- */

void AtomVecLsdem::data_atom(double *coord, imageint image, LSDEM_DATA_ATOM_VALUES)
{
  check_atoms_count();
#if LSDEM_CHECK_DATA_LINES
  check_data_line(values, size_data_atom, 0, "Atoms",
                  "atom-ID atom-type shape-ID density x y z qw qx qy qz", values[0]);
#endif
  AtomVec::data_atom(coord, image, LSDEM_DATA_ATOM_PASS);
}

#if LSDEM_CHECK_DATA_LINES
/* ----------------------------------------------------------------------
   Velocities line: id vx vy vz wx wy wz (values: from vx on)
------------------------------------------------------------------------- */

void AtomVecLsdem::data_vel(int ilocal, char **values)
{
  check_data_line(values, size_data_vel - 1, 1, "Velocities", "atom-ID vx vy vz wx wy wz",
                  std::to_string(atom->tag[ilocal]));
  AtomVec::data_vel(ilocal, values);
}
#endif

/* ----------------------------------------------------------------------
   Atoms line: id type shape-ID density x y z qw qx qy qz (shape-ID 1-based)
   AtomVec::data_atom() has stored shape-ID in shape[] and density in rmass[]
------------------------------------------------------------------------- */

void AtomVecLsdem::data_atom_post(int ilocal)
{
  const tagint id = atom->tag[ilocal];
  const int n = lsdem_library_count(lib);
  const int s = shape[ilocal] - 1;
  if (s < 0 || s >= n)
    error->one(FLERR, "Atom {} in Atoms section has shape-ID {}; the shape library has "
               "shapes 1 to {}", id, shape[ilocal], n);
  shape[ilocal] = s;

  const double density = rmass[ilocal];
  if (!(density > 0.0) || !std::isfinite(density))
    error->one(FLERR, "Atom {} in Atoms section has invalid density {}", id, density);

  double *q = quat[ilocal];
  const double qq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  if (!(qq > 0.0) || !std::isfinite(qq))
    error->one(FLERR, "Atom {} in Atoms section has invalid quaternion {} {} {} {}", id,
               q[0], q[1], q[2], q[3]);
  // a quaternion already unit to round-off is kept bit for bit, so that a data file
  // written by write_data reads back identically
  if (std::fabs(qq - 1.0) > 4.0 * DBL_EPSILON) lsdem_quat_normalize(q);

  const lsdem_shape *sh = lsdem_library_shape(lib, s);
  rmass[ilocal] = density * sh->volume;
  radius[ilocal] = sh->radius;
  for (int k = 0; k < 3; k++) {
    inertia[ilocal][k] = density * sh->inertia[k];
    omega[ilocal][k] = 0.0;
    dwprev[ilocal][k] = 0.0;
  }
}

/* ----------------------------------------------------------------------
   read_restart opens the library at the path the restart names, as it is now: each grain's
   shape must be there and be the shape it was written with (its bounding radius is copied
   from the shape, so a changed or reordered library shows in it)
------------------------------------------------------------------------- */

void AtomVecLsdem::unpack_restart_init(int ilocal)
{
  const int n = lsdem_library_count(lib);
  const int s = shape[ilocal];
  if (s < 0 || s >= n)
    error->one(FLERR, "read_restart: atom {} has shape-ID {}, but the shape library {} has "
               "shapes 1 to {}: the restart was written with another library",
               atom->tag[ilocal], s + 1, libpath, n);
  const double r = lsdem_library_shape(lib, s)->radius;
  if (radius[ilocal] != r)
    error->one(FLERR, "read_restart: atom {} has bounding radius {} but its shape {} in the "
               "shape library {} has radius {}: the restart was written with another library "
               "(or the library file changed since)", atom->tag[ilocal], radius[ilocal], s + 1,
               libpath, r);
}

/* ----------------------------------------------------------------------
   write_data: the same layout read_data reads (density, 1-based shape-ID)
------------------------------------------------------------------------- */

void AtomVecLsdem::pack_data_pre(int ilocal)
{
  rmass_one = rmass[ilocal];
  rmass[ilocal] = rmass_one / lsdem_library_shape(lib, shape[ilocal])->volume;
  shape[ilocal] += 1;
}

void AtomVecLsdem::pack_data_post(int ilocal)
{
  rmass[ilocal] = rmass_one;
  shape[ilocal] -= 1;
}

/* ----------------------------------------------------------------------
   compute property/atom names (quatw/quati.. are taken by the ellipsoid style there)
------------------------------------------------------------------------- */

int AtomVecLsdem::property_atom(LsdemCompat::PropertyName name)
{
  for (int k = 0; k < nproperty; k++)
    if (strcmp(LsdemCompat::cstr(name), property_names[k]) == 0) return k;
  return -1;
}

void AtomVecLsdem::pack_property_atom(int index, double *buf, int nvalues, int groupbit)
{
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  int n = 0;
  for (int i = 0; i < nlocal; i++, n += nvalues) {
    if (!(mask[i] & groupbit)) {
      buf[n] = 0.0;
    } else if (index < 4) {
      buf[n] = quat[i][index];
    } else if (index == 4) {
      buf[n] = shape[i] + 1;
    } else if (index < 8) {
      buf[n] = inertia[i][index - 5];
    } else {
      buf[n] = shape_of(i)->nnodes;  // the grain's share of contact work: a balance weight
    }
  }
}
