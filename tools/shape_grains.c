/* shape_grains.c -- reading a grain data file (shape_grains.h). */
#define _POSIX_C_SOURCE 200809L /* strdup */
#include "shape_grains.h"

#include "lsdem.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void shape_free_grains(shape_grain_file *gf)
{
  for (int i = 0; i < gf->nvel; i++) free(gf->vel[i]);
  free(gf->vel);
  for (int i = 0; i < gf->nbonds; i++) free(gf->bond[i]);
  free(gf->bond);
  for (int i = 0; i < gf->nangles; i++) free(gf->angle[i]);
  free(gf->angle);
  for (int i = 0; gf->g && i < gf->n; i++) free(gf->g[i].line);
  free(gf->g);
}

/* The next non-blank line (comments stripped) into buf; 0 at end of file. */
static int next_line(FILE *f, char *buf, int size, int *lineno)
{
  while (fgets(buf, size, f)) {
    (*lineno)++;
    char *h = strchr(buf, '#');
    if (h) *h = '\0';
    char *s = buf;
    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n') s++;
    if (*s) return 1;
  }
  return 0;
}

/* A header line "N keyword" (keyword exactly, then only blanks): 1 and *n = N. */
static int header_count(const char *buf, const char *keyword, long *n)
{
  char *end;
  *n = strtol(buf, &end, 10);
  if (end == buf) return 0;
  end += strspn(end, " \t");
  size_t len = strlen(keyword);
  return !strncmp(end, keyword, len) && strspn(end + len, " \t\r\n") == strlen(end + len);
}

static int grains_error(const char *path, int line, const char *what)
{
  fprintf(stderr, "lsdem-shape: %s line %d: %s\n", path, line, what);
  return 1;
}

/* An Atoms line into g: atom_style lsdem (id type shape density x y z qw qx qy qz, and
 * perhaps 3 image flags) as the line of atom_style hybrid lsdem bond it becomes (molecule
 * 0); hybrid lsdem bond (id type x y z shape density qw qx qy qz molecule, perhaps image
 * flags) as it is. 0 if it is neither, or out of memory. */
static int read_atom(const char *buf, shape_grain *g)
{
  double v[16];
  int n = 0, used;
  for (const char *s = buf; n < 16 && sscanf(s, "%lf%n", v + n, &used) == 1; s += used) n++;
  if (n != 11 && n != 14 && n != 12 && n != 15) return 0;
  g->id = (long) v[0];
  g->type = (int) v[1];
  if (n == 11 || n == 14) {
    const char *fmt = "%ld %d %.12g %.12g %.12g %d %.12g %.15g %.15g %.15g %.15g 0";
    for (int k = 0; k < 3; k++) g->x[k] = v[4 + k];
    g->molecule = 0;
    int len = snprintf(NULL, 0, fmt, g->id, g->type, v[4], v[5], v[6], (int) v[2], v[3], v[7],
                       v[8], v[9], v[10]);
    if (!(g->line = malloc((size_t) len + 1))) return 0;
    snprintf(g->line, (size_t) len + 1, fmt, g->id, g->type, v[4], v[5], v[6], (int) v[2], v[3],
             v[7], v[8], v[9], v[10]);
    return 1;
  }
  for (int k = 0; k < 3; k++) g->x[k] = v[2 + k];
  g->molecule = (long) v[11];
  if (!(g->line = strdup(buf))) return 0;
  g->line[strcspn(g->line, "\r\n")] = '\0';
  return 1;
}

/* COUNT lines of a Bonds (ends 2: "id type atom1 atom2") or Angles (ends 3: "id type atom1
 * atom2 atom3") section, types 1 to ntypes, kept verbatim */
static int read_topology(FILE *f, const char *path, const char *section, int ends, long count,
                         int ntypes, char ***lines, int *n, int *line)
{
  char buf[1024], msg[160];
  if (!(*lines = calloc((size_t) (count ? count : 1), sizeof(char *))))
    return grains_error(path, *line, "out of memory");
  for (long i = 0; i < count; i++) {
    long id, at[3];
    int type;
    if (!next_line(f, buf, sizeof buf, line) ||
        sscanf(buf, "%ld %d %ld %ld %ld", &id, &type, at, at + 1, at + 2) < 2 + ends ||
        type < 1 || type > ntypes) {
      snprintf(msg, sizeof msg, "expected a %s line 'id type %s' with a type from 1 to the "
               "%s types", section, ends == 2 ? "atom1 atom2" : "atom1 atom2 atom3",
               ends == 2 ? "bond" : "angle");
      return grains_error(path, *line, msg);
    }
    if (!((*lines)[(*n)++] = strdup(buf))) return grains_error(path, *line, "out of memory");
  }
  return 0;
}

/* A data file for atom_style lsdem (as written by lsdem-shape pack / from-labels) or
 * hybrid lsdem bond (lsdem-shape net): header counts and box, Atoms, optional Velocities
 * and Bonds. */
int shape_read_grains(const char *path, shape_grain_file *gf)
{
  memset(gf, 0, sizeof(*gf));
  FILE *f = fopen(path, "r");
  if (!f) {
    fprintf(stderr, "lsdem-shape: cannot open %s\n", path);
    return 1;
  }
  char buf[1024];
  int line = 0, rc = 0;
  long natoms = -1, nbonds = 0, nangles = 0;
  gf->ntypes = 1;
  if (!fgets(buf, sizeof buf, f)) rc = grains_error(path, 1, "empty file");
  line = 1;
  while (!rc && next_line(f, buf, sizeof buf, &line)) {
    double a, b;
    long n;
    char w1[64], w2[64];
    if (header_count(buf, "atoms", &n)) {
      natoms = n;
      if (n < 0 || n > 100000000) rc = grains_error(path, line, "bad atom count");
      else if (!(gf->g = calloc((size_t) (n ? n : 1), sizeof(shape_grain))))
        rc = grains_error(path, line, "out of memory");
    } else if (header_count(buf, "atom types", &n)) {
      gf->ntypes = (int) n;
    } else if (header_count(buf, "bonds", &n)) {
      nbonds = n;
      if (n < 0 || n > 1000000000) rc = grains_error(path, line, "bad bond count");
    } else if (header_count(buf, "bond types", &n)) {
      gf->nbondtypes = (int) n;
    } else if (header_count(buf, "angles", &n)) {
      nangles = n;
      if (n < 0 || n > 1000000000) rc = grains_error(path, line, "bad angle count");
    } else if (header_count(buf, "angle types", &n)) {
      gf->nangletypes = (int) n;
    } else if (sscanf(buf, "%lf %lf %63s %63s", &a, &b, w1, w2) == 4 && w1[1] == 'l' &&
               w1[0] >= 'x' && w1[0] <= 'z') {
      gf->lo[w1[0] - 'x'] = a;
      gf->hi[w1[0] - 'x'] = b;
    } else if (sscanf(buf, "%63s", w1) == 1 && !strcmp(w1, "Atoms")) {
      if (natoms < 0) {
        rc = grains_error(path, line, "Atoms before the atom count");
        break;
      }
      gf->n = (int) natoms;
      for (long i = 0; i < natoms && !rc; i++) {
        shape_grain *g = gf->g + i;
        if (!next_line(f, buf, sizeof buf, &line) || !read_atom(buf, g))
          rc = grains_error(path, line, "expected 'id type shape density x y z qw qx qy qz' "
                                        "(atom_style lsdem) or 'id type x y z shape density qw "
                                        "qx qy qz molecule' (hybrid lsdem bond)");
        else if (g->molecule > gf->maxmol)
          gf->maxmol = g->molecule;
      }
    } else if (sscanf(buf, "%63s", w1) == 1 && !strcmp(w1, "Velocities")) {
      gf->vel = calloc((size_t) (natoms > 0 ? natoms : 1), sizeof(char *));
      for (long i = 0; i < natoms && !rc; i++) {
        if (!next_line(f, buf, sizeof buf, &line)) rc = grains_error(path, line, "short Velocities");
        else gf->vel[gf->nvel++] = strdup(buf);
      }
    } else if (sscanf(buf, "%63s", w1) == 1 && !strcmp(w1, "Bonds")) {
      rc = read_topology(f, path, "Bonds", 2, nbonds, gf->nbondtypes, &gf->bond, &gf->nbonds,
                         &line);
    } else if (sscanf(buf, "%63s", w1) == 1 && !strcmp(w1, "Angles")) {
      rc = read_topology(f, path, "Angles", 3, nangles, gf->nangletypes, &gf->angle,
                         &gf->nangles, &line);
    } else if (isalpha((unsigned char) buf[strspn(buf, " \t")])) {
      rc = grains_error(path, line, "unsupported section or header line (expected a data "
                                    "file of atom_style lsdem, or one lsdem-shape net wrote)");
    }
  }
  fclose(f);
  if (!rc && natoms < 0) rc = grains_error(path, line, "no atom count");
  if (!rc && gf->nbonds != nbonds) rc = grains_error(path, line, "the header's bond count "
                                                    "does not match the Bonds section");
  if (!rc && gf->nangles != nangles) rc = grains_error(path, line, "the header's angle count "
                                                      "does not match the Angles section");
  if (rc) shape_free_grains(gf);
  return rc;
}

int shape_ball_types(const shape_grain_file *gf, int type[2], int both_used)
{
  if (type[0] == 0) {
    type[0] = gf->n ? gf->ntypes + 1 : 1;
    type[1] = type[0] + 1;
  }
  int ntypes = gf->n ? gf->ntypes : 0;
  if (type[0] > ntypes) ntypes = type[0];
  if (both_used && type[1] > ntypes) ntypes = type[1];
  return ntypes;
}

long shape_next_id(const shape_grain_file *gf)
{
  long id0 = 1;
  for (int i = 0; i < gf->n; i++)
    if (gf->g[i].id >= id0) id0 = gf->g[i].id + 1;
  return id0;
}

int shape_check_sphere(const char *cmd, const char *library, int shape, double radius,
                       const char *what)
{
  lsdem_library *lib;
  lsdem_error err;
  if (lsdem_library_open(library, &lib, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape %s: %s\n", cmd, err.msg);
    return 1;
  }
  int rc = 0;
  if (shape < 1 || shape > lsdem_library_count(lib)) {
    fprintf(stderr, "lsdem-shape %s: shape-ID %d not in %s (%d shapes)\n", cmd, shape, library,
            lsdem_library_count(lib));
    rc = 1;
  } else {
    const lsdem_shape *s = lsdem_library_shape(lib, shape - 1);
    if (s->sdf.kind != LSDEM_SDF_SPHERE || fabs(s->sdf.a[0] - radius) > 1e-9 * radius) {
      fprintf(stderr, "lsdem-shape %s: shape-ID %d of %s must be an analytic sphere of "
              "radius %g for %s (make it with: lsdem-shape analytic OUT.lslib sphere %g "
              "--analytic)\n", cmd, shape, library, radius, what, radius);
      rc = 1;
    }
  }
  lsdem_library_close(lib);
  return rc;
}

FILE *shape_open_out(const char *cmd, const char *prefix, const char *ext, char *path,
                     size_t size)
{
  snprintf(path, size, "%s%s", prefix, ext);
  FILE *f = fopen(path, "w");
  if (!f) fprintf(stderr, "lsdem-shape %s: cannot write %s\n", cmd, path);
  return f;
}

int shape_close_out(const char *cmd, FILE *f, const char *path)
{
  if (fclose(f) != 0) {
    fprintf(stderr, "lsdem-shape %s: writing %s failed\n", cmd, path);
    return 1;
  }
  return 0;
}

void shape_write_grain_atoms(FILE *f, const shape_grain_file *gf)
{
  for (int i = 0; i < gf->n; i++) fprintf(f, "%s\n", gf->g[i].line);
}

void shape_write_bonds(FILE *f, const shape_grain_file *gf)
{
  for (int i = 0; i < gf->nbonds; i++) fputs(gf->bond[i], f);
}

void shape_write_angles(FILE *f, const shape_grain_file *gf)
{
  for (int i = 0; i < gf->nangles; i++) fputs(gf->angle[i], f);
}

typedef struct {
  long id;
  int index;
} id_index;

static int by_id(const void *a, const void *b)
{
  long x = ((const id_index *) a)->id, y = ((const id_index *) b)->id;
  return (x > y) - (x < y);
}

double shape_longest_bond(const shape_grain_file *gf)
{
  if (!gf->nbonds) return 0.0;
  id_index *map = malloc((size_t) gf->n * sizeof(id_index));
  if (!map) return -1.0;
  for (int i = 0; i < gf->n; i++) map[i] = (id_index){gf->g[i].id, i};
  qsort(map, (size_t) gf->n, sizeof(id_index), by_id);
  double longest = 0.0;
  for (int b = 0; b < gf->nbonds && longest >= 0.0; b++) {
    long id, at[2];
    int type;
    sscanf(gf->bond[b], "%ld %d %ld %ld", &id, &type, at, at + 1);
    const id_index *end[2];
    for (int k = 0; k < 2; k++) {
      id_index key = {at[k], 0};
      end[k] = bsearch(&key, map, (size_t) gf->n, sizeof(id_index), by_id);
    }
    if (!end[0] || !end[1]) {
      fprintf(stderr, "lsdem-shape: bond %ld joins atom %ld, which the data file does not "
              "have\n", id, end[0] ? at[1] : at[0]);
      longest = -1.0;
    } else {
      const double *x = gf->g[end[0]->index].x, *y = gf->g[end[1]->index].x;
      longest = fmax(longest, sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                                   (x[2] - y[2]) * (x[2] - y[2])));
    }
  }
  free(map);
  return longest;
}

void shape_write_velocities(FILE *f, const shape_grain_file *gf)
{
  if (!gf->nvel) return;
  fprintf(f, "\nVelocities\n\n");
  for (int i = 0; i < gf->nvel; i++) fputs(gf->vel[i], f);
}
