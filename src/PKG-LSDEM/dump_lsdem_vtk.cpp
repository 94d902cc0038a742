// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   dump ID group lsdem/vtk N prefix [spacing S]

   Every N steps: prefix_<step>.vtp, a VTK XML PolyData file (ASCII) holding the surface
   of every grain of the group -- its shape's zero level set as a triangle mesh (core
   lsdem_mesh_extract, once per shape) moved to the grain's pose, x_world = x + R(q) v --
   with cell data `id` (grain atom ID) and `shape` (1-based shape-ID, as in data files);
   then prefix.pvd, the ParaView index of every step written so far, rewritten whole.
   The grains' (id, shape, x, q) travel to rank 0 through the Dump base class; rank 0
   writes. Every file is complete and closed when write() returns, so a later failure of
   the run loses nothing already written.
------------------------------------------------------------------------- */

#include "dump_lsdem_vtk.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "error.h"
#include "lsdem_input.h"
#include "update.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

DumpLsdemVtk::DumpLsdemVtk(LAMMPS *lmp, int narg, char **arg) :
  Dump(lmp, narg, arg), avec(nullptr), spacing_factor(1.0), step_written(true),
  step_time(0.0), series(narg > 4 ? arg[4] : ""), mesh_library(nullptr)
{
  if (narg < 5) error->all(FLERR, "Illegal dump lsdem/vtk command: dump ID group lsdem/vtk N "
                           "prefix [spacing S]");
  prefix = arg[4];
  if (prefix.find_first_of("*%") != std::string::npos)
    error->all(FLERR, "Dump lsdem/vtk takes a file prefix without * or %: it writes "
               "prefix_<step>.vtp and prefix.pvd");
  for (int iarg = 5; iarg < narg; iarg += 2) {
    if (strcmp(arg[iarg], "spacing") != 0 || iarg + 1 >= narg)
      error->all(FLERR, "Illegal dump lsdem/vtk keyword {}: expected spacing S", arg[iarg]);
    spacing_factor = LsdemInput::number(FLERR, arg[iarg + 1], "dump lsdem/vtk", "spacing", lmp);
    if (!(spacing_factor > 0.0))
      error->all(FLERR, "Dump lsdem/vtk spacing must be positive, got {}", arg[iarg + 1]);
  }
  if (!dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem")))
    error->all(FLERR, "Dump lsdem/vtk requires atom_style lsdem");

  size_one = SIZE_ONE;
  multifile = 1;    // a new .vtp per dump step (opened by openfile, closed by Dump::write)
  binary = compressed = 0;
}

/* ---------------------------------------------------------------------- */

DumpLsdemVtk::~DumpLsdemVtk()
{
  free_meshes();
}

/* ---------------------------------------------------------------------- */

void DumpLsdemVtk::init_style()
{
  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  if (!avec) error->all(FLERR, "Dump lsdem/vtk requires atom_style lsdem");
  if (sort_flag && sortcol != 0)
    error->all(FLERR, "Dump lsdem/vtk can only sort by atom ID");
}

/* ---------------------------------------------------------------------- */

std::string DumpLsdemVtk::step_file(bigint step) const
{
  return series.step_file(step);
}

/* ----------------------------------------------------------------------
   called by Dump::write on every rank at each dump step: start a new step
------------------------------------------------------------------------- */

void DumpLsdemVtk::openfile()
{
  records.clear();
  step_written = false;
  step_time = update->atime + (update->ntimestep - update->atimestep) * update->dt;
  fp = nullptr;
  if (!filewriter) return;
  const std::string name = step_file(update->ntimestep);
  fp = fopen(name.c_str(), "w");
  if (!fp) {
    // like every LAMMPS dump, this one makes no folders: say so when one is missing
    const bool missing = errno == ENOENT;  // read before anything else can set it
    const std::string folder = name.substr(0, name.rfind('/'));
    const bool nofolder = missing && folder != name;
    const std::string hint =
        nofolder ? fmt::format(" (create its folder first, e.g. 'shell mkdir {}')", folder) : "";
    error->one(FLERR, "Dump lsdem/vtk cannot open {}: {}{}", name, utils::getsyserror(), hint);
  }
}

/* ----------------------------------------------------------------------
   the VTP header needs the point and triangle counts, so the whole file is written
   by write_vtp() once every grain has arrived
------------------------------------------------------------------------- */

void DumpLsdemVtk::write_header(bigint /*ndump*/) {}

/* ---------------------------------------------------------------------- */

void DumpLsdemVtk::pack(tagint *ids)
{
  const tagint *tag = atom->tag;
  const int *mask = atom->mask;
  double **x = atom->x;
  int m = 0, n = 0;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    buf[m++] = ubuf(tag[i]).d;
    buf[m++] = avec->shape[i];
    for (int k = 0; k < 3; k++) buf[m++] = x[i][k];
    for (int k = 0; k < 4; k++) buf[m++] = avec->quat[i][k];
    if (ids) ids[n++] = tag[i];
  }
}

/* ----------------------------------------------------------------------
   filewriter: collect each rank's grains; the last chunk completes the step
------------------------------------------------------------------------- */

void DumpLsdemVtk::write_data(int n, double *mybuf)
{
  records.insert(records.end(), mybuf, mybuf + (size_t)n * SIZE_ONE);
  if (step_written || (bigint)(records.size() / SIZE_ONE) < ntotal) return;
  step_written = true;
  write_vtp();
  write_pvd();
}

/* ---------------------------------------------------------------------- */

const lsdem_mesh &DumpLsdemVtk::shape_mesh(int s)
{
  if (mesh_library != avec->library()) {    // a new atom_style: new shapes
    free_meshes();
    mesh_library = avec->library();
    meshes.assign(avec->nshapes(), lsdem_mesh());
    mesh_ready.assign(avec->nshapes(), 0);
  }
  if (!mesh_ready[s]) {
    const lsdem_shape *shape = lsdem_library_shape(mesh_library, s);
    double h = shape->sdf.kind == LSDEM_SDF_GRID ? shape->sdf.grid.h
                                                  : lsdem_sdf_bound_radius(&shape->sdf) / 20.0;
    lsdem_error err;
    if (lsdem_mesh_extract(&shape->sdf, spacing_factor == 1.0 ? 0.0 : spacing_factor * h,
                           &meshes[s], &err) != LSDEM_OK)
      error->one(FLERR, "Dump lsdem/vtk: surface of shape {}: {}", s + 1, err.msg);
    if (meshes[s].ntris == 0)
      error->warning(FLERR, "Dump lsdem/vtk: shape {} has no surface triangles at spacing {} "
                     "(its grains are left out of the files): lower the spacing keyword", s + 1,
                     spacing_factor);
    mesh_ready[s] = 1;
  }
  return meshes[s];
}

/* ---------------------------------------------------------------------- */

void DumpLsdemVtk::free_meshes()
{
  for (size_t s = 0; s < meshes.size(); s++)
    if (mesh_ready[s]) lsdem_mesh_free(&meshes[s]);
  meshes.clear();
  mesh_ready.clear();
}

/* ----------------------------------------------------------------------
   this step's grains as one PolyData piece: points of grain g are x_g + R(q_g) v for the
   vertices v of its shape's mesh; triangles keep their outward orientation
------------------------------------------------------------------------- */

void DumpLsdemVtk::write_vtp()
{
  const int ngrains = (int)(records.size() / SIZE_ONE);
  bigint npoints = 0, ntris = 0;
  for (int g = 0; g < ngrains; g++) {
    const lsdem_mesh &m = shape_mesh((int)records[g * SIZE_ONE + 1]);
    npoints += m.nverts;
    ntris += m.ntris;
  }

  fmt::print(fp, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
             "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<PolyData>\n"
             "<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
             "NumberOfStrips=\"0\" NumberOfPolys=\"{}\">\n", npoints, ntris);

  fputs("<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n",
        fp);
  for (int g = 0; g < ngrains; g++) {
    const double *r = &records[(size_t)g * SIZE_ONE];
    const lsdem_mesh &m = shape_mesh((int)r[1]);
    for (int v = 0; v < m.nverts; v++) {
      double p[3];
      lsdem_quat_rotate(r + 5, m.verts + 3 * v, p);
      fprintf(fp, "%.9g %.9g %.9g\n", r[2] + p[0], r[3] + p[1], r[4] + p[2]);
    }
  }
  fputs("</DataArray>\n</Points>\n<Polys>\n"
        "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n", fp);
  bigint base = 0;
  for (int g = 0; g < ngrains; g++) {
    const lsdem_mesh &m = shape_mesh((int)records[g * SIZE_ONE + 1]);
    for (int t = 0; t < m.ntris; t++)
      fmt::print(fp, "{} {} {}\n", base + m.tris[3 * t], base + m.tris[3 * t + 1],
                 base + m.tris[3 * t + 2]);
    base += m.nverts;
  }
  fputs("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n", fp);
  for (bigint t = 1; t <= ntris; t++) fmt::print(fp, "{}\n", 3 * t);
  fputs("</DataArray>\n</Polys>\n<CellData Scalars=\"id\">\n"
        "<DataArray type=\"Int64\" Name=\"id\" format=\"ascii\">\n", fp);
  for (int g = 0; g < ngrains; g++) {
    const tagint id = (tagint)ubuf(records[g * SIZE_ONE]).i;
    const int nt = shape_mesh((int)records[g * SIZE_ONE + 1]).ntris;
    for (int t = 0; t < nt; t++) fmt::print(fp, "{}\n", id);
  }
  fputs("</DataArray>\n<DataArray type=\"Int32\" Name=\"shape\" format=\"ascii\">\n", fp);
  for (int g = 0; g < ngrains; g++) {
    const int s = (int)records[g * SIZE_ONE + 1];
    for (int t = 0; t < shape_mesh(s).ntris; t++) fmt::print(fp, "{}\n", s + 1);
  }
  fputs("</DataArray>\n</CellData>\n</Piece>\n</PolyData>\n</VTKFile>\n", fp);
  if (fflush(fp) != 0 || ferror(fp))
    error->one(FLERR, "Dump lsdem/vtk: writing {} failed", step_file(update->ntimestep));
}

/* ----------------------------------------------------------------------
   prefix.pvd lists every step written so far (LsdemVtkSeries)
------------------------------------------------------------------------- */

void DumpLsdemVtk::write_pvd()
{
  if (!series.add(update->ntimestep, step_time))
    error->one(FLERR, "Dump lsdem/vtk: writing {} failed: {}", series.index_file(),
               utils::getsyserror());
}
