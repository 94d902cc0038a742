/* lsdem-shape bands: the sheets and bands of a cut strain field's zones (the geometry of
 * tools/lsdem_bands.py's micro-band count, in the core: lsdem_point_sizes, lsdem_sheets_fit,
 * lsdem_sheets_join).
 *
 *   lsdem-shape bands POINTS --tol T --min-length L [--aspect A] [--angle DEG]
 *                     [--samples N] [--seed S]
 *
 * POINTS: a file of little-endian float64 records (zone, x, y, z), one per localised node,
 * each zone's records together (zone ids are labels, not indices). Per zone of at least 2
 * nodes its principal sizes; in a zone at least L/2 long, sheets at least L/2 long
 * (lsdem_sheets_fit: tol T, refit slab 3T, breadth >= A x thickness, default A 2, N
 * RANSAC planes per sheet, default 400, seed S, default 1); the sheets of all zones joined
 * (lsdem_sheets_join: normals within DEG degrees, default 10, centres within 2T of the
 * leading plane) into bands at least L long. Lengths in the points' units. Prints a line per
 * zone, in file order, then one per band, largest group first:
 *   zone ID nodes N length L breadth B thickness T dip D azimuth A centre X Y Z sheets S
 *   band nodes N pieces P length L breadth B thickness T dip D azimuth A centre X Y Z
 *        normal NX NY NZ
 * (a one-node zone: sizes 0, dip 0, its node as centre). */
#include "lsdem.h"
#include "lsdem_shape_cmds.h"
#include "shape_common.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { SHEETS_PER_ZONE = 64 };

static int bands_usage(void)
{
  fprintf(stderr, "usage: lsdem-shape bands POINTS --tol T --min-length L [--aspect A] "
                  "[--angle DEG] [--samples N] [--seed S]\n");
  return 2;
}

/* the records of path: 4 doubles each, into *rec (*n records). 0 ok, 1 after a message */
static int read_records(const char *path, double **rec, long *n)
{
  FILE *f = fopen(path, "rb");
  if (!f) {
    fprintf(stderr, "lsdem-shape: bands: cannot open %s\n", path);
    return 1;
  }
  long size = -1;
  if (fseek(f, 0, SEEK_END) == 0) size = ftell(f);
  rewind(f);
  const long per = 4 * (long) sizeof(double);
  if (size < 0 || size % per != 0 || size / per > 100000000) {
    fprintf(stderr, "lsdem-shape: bands: %s: %ld bytes, not a whole number of (zone, x, y, z) "
                    "float64 records\n", path, size);
    fclose(f);
    return 1;
  }
  *n = size / per;
  *rec = malloc((size_t) (size > 0 ? size : per));
  const int ok = *rec && fread(*rec, 1, (size_t) size, f) == (size_t) size;
  fclose(f);
  if (!ok) {
    fprintf(stderr, "lsdem-shape: bands: cannot read %s\n", path);
    free(*rec);
    return 1;
  }
  return 0;
}

static void print_plane(const char *head, const lsdem_shearband_plane *pl, double length,
                        double breadth)
{
  printf("%s length %.9g breadth %.9g thickness %.9g dip %.9g azimuth %.9g centre %.9g %.9g "
         "%.9g", head, length, breadth, pl->thickness, pl->dip, pl->azimuth, pl->centre[0],
         pl->centre[1], pl->centre[2]);
}

int cmd_bands(int argc, char **argv)
{
  lsdem_sheet_params p = {0.0, 0.0, 0.0, 2.0, 400, 1};
  double min_length = -1.0, angle = 10.0;
  if (argc < 1) return bands_usage();
  for (int a = 1; a < argc; a += 2) {
    if (a + 1 >= argc) return bands_usage();
    long v;
    const char *k = argv[a], *val = argv[a + 1];
    if (!strcmp(k, "--tol")) {
      if (!parse_number(val, 1, &p.tol)) return shape_bad_value("bands", "--tol", val);
    } else if (!strcmp(k, "--min-length")) {
      if (!parse_number(val, 1, &min_length)) return shape_bad_value("bands", "--min-length", val);
    } else if (!strcmp(k, "--aspect")) {
      if (!parse_number(val, 0, &p.aspect) || p.aspect < 0.0)
        return shape_bad_value("bands", "--aspect", val);
    } else if (!strcmp(k, "--angle")) {
      if (!parse_number(val, 0, &angle) || angle < 0.0 || angle > 90.0)
        return shape_bad_value("bands", "--angle", val);
    } else if (!strcmp(k, "--samples")) {
      if (!parse_count(val, 1, 1000000, &v)) return shape_bad_value("bands", "--samples", val);
      p.samples = (int) v;
    } else if (!strcmp(k, "--seed")) {
      if (!parse_count(val, 0, 2147483647, &v)) return shape_bad_value("bands", "--seed", val);
      p.seed = (uint64_t) v;
    } else {
      return bands_usage();
    }
  }
  if (!(p.tol > 0.0) || !(min_length > 0.0)) return bands_usage();
  p.slab = 3.0 * p.tol;
  p.min_length = 0.5 * min_length;
  double *rec = NULL;
  long n = 0;
  if (read_records(argv[0], &rec, &n)) return 1;
  double *x = malloc(sizeof(double) * 3 * (size_t) (n > 0 ? n : 1));
  int *label = malloc(sizeof(int) * (size_t) (n > 0 ? n : 1));
  int *zlabel = malloc(sizeof(int) * (size_t) (n > 0 ? n : 1));
  lsdem_sheet *sheet = NULL;
  int ns = 0, rc = 0;
  for (long i = 0; i < n && x; i++) memcpy(&x[3 * i], &rec[4 * i + 1], 3 * sizeof(double));
  for (long z0 = 0; z0 < n && x && label && zlabel && !rc;) {
    long z1 = z0 + 1;
    while (z1 < n && rec[4 * z1] == rec[4 * z0]) z1++;
    const int m = (int) (z1 - z0);
    lsdem_shearband_plane pl;
    double sizes[3] = {0.0, 0.0, 0.0};
    memset(&pl, 0, sizeof pl);
    memcpy(pl.centre, &x[3 * z0], sizeof pl.centre);
    if (m >= 2 && lsdem_point_sizes(m, &x[3 * z0], &pl, sizes) != LSDEM_OK) rc = 1;
    int found = 0;
    for (long i = z0; i < z1; i++) label[i] = -1;
    if (!rc && sizes[0] >= p.min_length) {
      lsdem_sheet *grown = realloc(sheet, sizeof *sheet * (size_t) (ns + SHEETS_PER_ZONE));
      if (!grown || lsdem_sheets_fit(m, &x[3 * z0], &p, SHEETS_PER_ZONE, grown + ns, &found,
                                     &zlabel[z0]) != LSDEM_OK)
        rc = 1;
      if (grown) sheet = grown;
      for (long i = z0; !rc && i < z1; i++) label[i] = zlabel[i] >= 0 ? ns + zlabel[i] : -1;
      ns += found;
    }
    char head[64];
    snprintf(head, sizeof head, "zone %.17g nodes %d", rec[4 * z0], m);
    print_plane(head, &pl, sizes[0], sizes[1]);
    printf(" sheets %d\n", found);
    z0 = z1;
  }
  int *group = malloc(sizeof(int) * (size_t) (ns > 0 ? ns : 1));
  lsdem_sheet *band = malloc(sizeof *band * (size_t) (ns > 0 ? ns : 1));
  int nbands = 0;
  if (!rc && (!x || !label || !zlabel || !group || !band ||
              lsdem_sheets_join((int) n, x, label, ns, sheet, angle, 2.0 * p.tol, min_length,
                                group, band, &nbands) != LSDEM_OK))
    rc = 1;
  for (int b = 0; !rc && b < nbands; b++) {
    int pieces = 0;
    for (int k = 0; k < ns; k++) pieces += group[k] == b;
    char head[64];
    snprintf(head, sizeof head, "band nodes %d pieces %d", band[b].plane.ninliers, pieces);
    print_plane(head, &band[b].plane, band[b].length, band[b].breadth);
    printf(" normal %.9g %.9g %.9g\n", band[b].plane.normal[0], band[b].plane.normal[1],
           band[b].plane.normal[2]);
  }
  if (rc) fprintf(stderr, "lsdem-shape: bands: out of memory for %ld points\n", n);
  free(rec);
  free(x);
  free(label);
  free(zlabel);
  free(sheet);
  free(group);
  free(band);
  return rc;
}
