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

/* A data file for atom_style lsdem (as written by lsdem-shape pack / from-labels):
 * header counts and box, Atoms (id type shape density x y z qw qx qy qz), optional
 * Velocities. */
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
  long natoms = -1;
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
    } else if (sscanf(buf, "%lf %lf %63s %63s", &a, &b, w1, w2) == 4 && w1[1] == 'l' &&
               w1[0] >= 'x' && w1[0] <= 'z') {
      gf->lo[w1[0] - 'x'] = a;
      gf->hi[w1[0] - 'x'] = b;
    } else if (sscanf(buf, "%63s", w1) == 1 && !strcmp(w1, "Atoms")) {
      if (natoms < 0) {
        rc = grains_error(path, line, "Atoms before the atom count");
        break;
      }
      for (long i = 0; i < natoms && !rc; i++) {
        shape_grain *g = gf->g + i;
        if (!next_line(f, buf, sizeof buf, &line) ||
            sscanf(buf, "%ld %d %d %lf %lf %lf %lf %lf %lf %lf %lf", &g->id, &g->type, &g->shape,
                   &g->density, g->x, g->x + 1, g->x + 2, g->q, g->q + 1, g->q + 2, g->q + 3) != 11)
          rc = grains_error(path, line, "expected 'id type shape density x y z qw qx qy qz' "
                                        "(atom_style lsdem)");
      }
      gf->n = (int) natoms;
    } else if (sscanf(buf, "%63s", w1) == 1 && !strcmp(w1, "Velocities")) {
      gf->vel = calloc((size_t) (natoms > 0 ? natoms : 1), sizeof(char *));
      for (long i = 0; i < natoms && !rc; i++) {
        if (!next_line(f, buf, sizeof buf, &line)) rc = grains_error(path, line, "short Velocities");
        else gf->vel[gf->nvel++] = strdup(buf);
      }
    } else if (isalpha((unsigned char) buf[strspn(buf, " \t")])) {
      rc = grains_error(path, line, "unsupported section or header line (expected a data "
                                    "file of atom_style lsdem)");
    }
  }
  fclose(f);
  if (!rc && natoms < 0) rc = grains_error(path, line, "no atom count");
  if (rc) shape_free_grains(gf);
  return rc;
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
  for (int i = 0; i < gf->n; i++) {
    const shape_grain *g = gf->g + i;
    fprintf(f, "%ld %d %.12g %.12g %.12g %d %.12g %.15g %.15g %.15g %.15g 0\n", g->id, g->type,
            g->x[0], g->x[1], g->x[2], g->shape, g->density, g->q[0], g->q[1], g->q[2], g->q[3]);
  }
}

void shape_write_velocities(FILE *f, const shape_grain_file *gf)
{
  if (!gf->nvel) return;
  fprintf(f, "\nVelocities\n\n");
  for (int i = 0; i < gf->nvel; i++) fputs(gf->vel[i], f);
}
