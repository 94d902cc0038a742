/* vti.c -- the fields as VTK XML ImageData (lsdem_fields.h): point data, raw appended
 * binary (each array a UInt64 byte count, then its values, little-endian as written). */
#include "lsdem_fields.h"

#include "../base/lsdem_vec3.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

typedef struct {
  const char *name;
  const void *data;
  int components;
  int bytes; /* per component: 8 Float64, 1 UInt8 */
} vti_array;

/* The grid's ImageData attributes: extent, origin (world) and spacing, and for a skewed
 * grid (lsdem_field_grid) the Direction matrix (VTK 9, ParaView 5.10 on: row-major, its
 * columns the unit lattice directions T e_k) with the spacing along them, h_k |T e_k|. */
static void write_geometry(FILE *fp, const lsdem_field_grid *g)
{
  const int zero[3] = {0, 0, 0};
  double origin[3], col[3][3], spacing[3];
  lsdem_field_node_position(g, zero, origin);
  for (int k = 0; k < 3; k++) {
    double e[3] = {0.0, 0.0, 0.0};
    e[k] = 1.0;
    lsdem_field_from_lattice(g->skew, e, col[k]);
    const double len = sqrt(lsdem_dot3(col[k], col[k]));
    for (int i = 0; i < 3; i++) col[k][i] /= len;
    spacing[k] = g->h[k] * len;
  }
  fprintf(fp, "<ImageData WholeExtent=\"0 %d 0 %d 0 %d\" Origin=\"%.17g %.17g %.17g\" "
              "Spacing=\"%.17g %.17g %.17g\"",
          g->n[0] - 1, g->n[1] - 1, g->n[2] - 1, origin[0], origin[1], origin[2], spacing[0],
          spacing[1], spacing[2]);
  if (g->skew[0] != 0.0 || g->skew[1] != 0.0 || g->skew[2] != 0.0)
    fprintf(fp, " Direction=\"%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"",
            col[0][0], col[1][0], col[2][0], col[0][1], col[1][1], col[2][1], col[0][2],
            col[1][2], col[2][2]);
  fputs(">\n", fp);
}

static void write_arrays(FILE *fp, const lsdem_field_grid *g, const vti_array *a, int na)
{
  const uint64_t nodes = lsdem_field_grid_nodes(g);
  fputs("<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" "
        "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n", fp);
  write_geometry(fp, g);
  fprintf(fp, "<Piece Extent=\"0 %d 0 %d 0 %d\">\n<PointData Scalars=\"density\">\n",
          g->n[0] - 1, g->n[1] - 1, g->n[2] - 1);
  uint64_t offset = 0;
  for (int k = 0; k < na; k++) {
    fprintf(fp, "<DataArray type=\"%s\" Name=\"%s\" NumberOfComponents=\"%d\" "
                "format=\"appended\" offset=\"%llu\"/>\n",
            a[k].bytes == 8 ? "Float64" : "UInt8", a[k].name, a[k].components,
            (unsigned long long)offset);
    offset += sizeof(uint64_t) + nodes * a[k].components * a[k].bytes;
  }
  fputs("</PointData>\n</Piece>\n</ImageData>\n<AppendedData encoding=\"raw\">\n_", fp);
  for (int k = 0; k < na; k++) {
    const uint64_t size = nodes * a[k].components * a[k].bytes;
    fwrite(&size, sizeof size, 1, fp);
    fwrite(a[k].data, (size_t)a[k].bytes, (size_t)(nodes * a[k].components), fp);
  }
  fputs("\n</AppendedData>\n</VTKFile>\n", fp);
}

lsdem_status lsdem_fields_write_vti(const char *path, const lsdem_fields *f,
                                    lsdem_error *err)
{
  const vti_array arrays[] = {
      {"density", f->density, 1, 8},
      {"solid_fraction", f->solid_fraction, 1, 8},
      {"displacement_gradient", f->grad, 9, 8},
      {"strain_small", f->strain_small, 9, 8},
      {"strain_green", f->strain_green, 9, 8},
      {"rotation", f->rotation, 3, 8},
      {"volumetric_strain", f->volumetric, 1, 8},
      {"shear_strain", f->shear, 1, 8},
      {"stress", f->stress, 9, 8},
      {"regular", f->regular, 1, 1},
      {"inside", f->inside, 1, 1},
  };
  FILE *fp = fopen(path, "wb");
  if (!fp) return lsdem_fail(err, LSDEM_ERR_IO, "%s: %s", path, strerror(errno));
  write_arrays(fp, &f->grid, arrays, (int)(sizeof arrays / sizeof arrays[0]));
  const int bad = ferror(fp) != 0;
  if (fclose(fp) != 0 || bad)
    return lsdem_fail(err, LSDEM_ERR_IO, "%s: write failed: %s", path, strerror(errno));
  return LSDEM_OK;
}
