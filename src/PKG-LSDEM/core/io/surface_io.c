/* surface_io.c -- writing triangle meshes (lsdem_mesh) as legacy VTK and PLY files, for
 * ParaView and other viewers. */
#include "lsdem_io.h"

#include <stdio.h>

/* --------------------------------------------------------------- writers ---- */

static lsdem_status finish_file(FILE *f, const char *path, lsdem_error *err)
{
  const int bad = ferror(f);
  if (fclose(f) != 0 || bad)
    return lsdem_fail(err, LSDEM_ERR_IO, "%s: write failed", path);
  return LSDEM_OK;
}

lsdem_status lsdem_mesh_write_vtk(const char *path, const lsdem_mesh *m, lsdem_error *err)
{
  FILE *f = fopen(path, "w");
  if (!f) return lsdem_fail(err, LSDEM_ERR_IO, "%s: cannot open for writing", path);
  fprintf(f, "# vtk DataFile Version 3.0\nLSDEM level-set surface\nASCII\nDATASET POLYDATA\n");
  fprintf(f, "POINTS %d double\n", m->nverts);
  for (int v = 0; v < m->nverts; v++)
    fprintf(f, "%.9g %.9g %.9g\n", m->verts[3 * v], m->verts[3 * v + 1], m->verts[3 * v + 2]);
  fprintf(f, "POLYGONS %d %d\n", m->ntris, 4 * m->ntris);
  for (int t = 0; t < m->ntris; t++)
    fprintf(f, "3 %d %d %d\n", m->tris[3 * t], m->tris[3 * t + 1], m->tris[3 * t + 2]);
  return finish_file(f, path, err);
}

lsdem_status lsdem_mesh_write_ply(const char *path, const lsdem_mesh *m, lsdem_error *err)
{
  FILE *f = fopen(path, "w");
  if (!f) return lsdem_fail(err, LSDEM_ERR_IO, "%s: cannot open for writing", path);
  fprintf(f, "ply\nformat ascii 1.0\ncomment LSDEM level-set surface\n"
          "element vertex %d\nproperty double x\nproperty double y\nproperty double z\n"
          "element face %d\nproperty list uchar int vertex_indices\nend_header\n",
          m->nverts, m->ntris);
  for (int v = 0; v < m->nverts; v++)
    fprintf(f, "%.9g %.9g %.9g\n", m->verts[3 * v], m->verts[3 * v + 1], m->verts[3 * v + 2]);
  for (int t = 0; t < m->ntris; t++)
    fprintf(f, "3 %d %d %d\n", m->tris[3 * t], m->tris[3 * t + 1], m->tris[3 * t + 2]);
  return finish_file(f, path, err);
}

