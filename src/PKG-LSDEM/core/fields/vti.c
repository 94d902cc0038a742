/* vti.c -- the fields as VTK XML ImageData (lsdem_fields.h): point data, raw appended
 * binary (each array a UInt64 byte count, then its values, little-endian as written). */
#include "lsdem_fields.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

typedef struct {
  const char *name;
  const void *data;
  int components;
  int bytes; /* per component: 8 Float64, 1 UInt8 */
} vti_array;

static void write_arrays(FILE *fp, const lsdem_field_grid *g, const vti_array *a, int na)
{
  const uint64_t nodes = lsdem_field_grid_nodes(g);
  fprintf(fp, "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" "
              "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
              "<ImageData WholeExtent=\"0 %d 0 %d 0 %d\" Origin=\"%.17g %.17g %.17g\" "
              "Spacing=\"%.17g %.17g %.17g\">\n<Piece Extent=\"0 %d 0 %d 0 %d\">\n"
              "<PointData Scalars=\"density\">\n",
          g->n[0] - 1, g->n[1] - 1, g->n[2] - 1, g->origin[0], g->origin[1], g->origin[2],
          g->h[0], g->h[1], g->h[2], g->n[0] - 1, g->n[1] - 1, g->n[2] - 1);
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
