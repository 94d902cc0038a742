/* lsdem-shape voids: solid fraction and void ratio of a sample's grains inside a region, by
 * sampling a regular lattice with each grain's own level set (an independent measure of a
 * packing's density: it uses the grains' shapes and poses, not their masses).
 *
 *   lsdem-shape voids LIB DATA (--cylinder R Z0 Z1 | --box X0 X1 Y0 Y1 Z0 Z1)
 *               [--centre X Y] [--inset D] [--spacing H]
 *
 * The region is a cylinder about the z axis (through --centre, default 0 0) of radius R
 * between heights Z0 and Z1, or a box; --inset D shrinks it by D on every side (the core of
 * a specimen, away from the walls' looser layer). Lattice points at spacing H (default 1.0)
 * on cell centres; a point is solid when it is inside (phi < 0) at least one grain, so
 * overlaps count once. Prints one line:
 *   voids: points N solid S solid_fraction F void_ratio E volume V
 * DATA is a data file of atom_style lsdem (Atoms: id type shape density x y z qw qx qy qz,
 * as written by lsdem-shape pack or LAMMPS write_data); other sections are skipped. */
#include "lsdem.h"
#include "lsdem_shape_cmds.h"
#include "shape_common.h"

#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  int shape; /* 1-based shape-ID */
  double x[3], q[4];
} voids_grain;

static int voids_usage(void)
{
  fprintf(stderr, "usage: lsdem-shape voids LIB DATA (--cylinder R Z0 Z1 | --box X0 X1 Y0 Y1 Z0 "
                  "Z1) [--centre X Y] [--inset D] [--spacing H]\n");
  return 2;
}

/* The Atoms section of an atom_style lsdem data file. 0 ok, 1 after a message. */
static int read_atoms(const char *path, voids_grain **out, long *count)
{
  FILE *f = fopen(path, "r");
  if (!f) {
    fprintf(stderr, "lsdem-shape: voids: cannot open %s\n", path);
    return 1;
  }
  char buf[1024];
  long natoms = -1, line = 0;
  int rc = 0, done = 0;
  voids_grain *g = NULL;
  while (!rc && !done && fgets(buf, sizeof buf, f)) {
    line++;
    char *h = strchr(buf, '#');
    if (h) *h = '\0';
    char *s = buf + strspn(buf, " \t\r\n");
    long n;
    char word[32];
    if (line == 1 || !*s) continue; /* the title line, blank lines */
    if (sscanf(s, "%ld %31s", &n, word) == 2 && !strcmp(word, "atoms") && natoms < 0) {
      natoms = n;
      if (n < 0 || n > 100000000 || !(g = calloc((size_t)(n ? n : 1), sizeof *g))) {
        fprintf(stderr, "lsdem-shape: voids: %s line %ld: bad atom count %ld\n", path, line, n);
        rc = 1;
      }
    } else if (!strncmp(s, "Atoms", 5) && (s[5] == '\0' || isspace((unsigned char)s[5]))) {
      if (natoms < 0) {
        fprintf(stderr, "lsdem-shape: voids: %s: Atoms before the atom count\n", path);
        rc = 1;
        break;
      }
      for (long i = 0; i < natoms && !rc;) {
        if (!fgets(buf, sizeof buf, f)) {
          fprintf(stderr, "lsdem-shape: voids: %s: %ld of %ld Atoms lines\n", path, i, natoms);
          rc = 1;
          break;
        }
        line++;
        if (!*(buf + strspn(buf, " \t\r\n"))) continue;
        long id;
        int type;
        double dens;
        voids_grain *p = g + i;
        if (sscanf(buf, "%ld %d %d %lf %lf %lf %lf %lf %lf %lf %lf", &id, &type, &p->shape,
                   &dens, p->x, p->x + 1, p->x + 2, p->q, p->q + 1, p->q + 2, p->q + 3) != 11) {
          fprintf(stderr, "lsdem-shape: voids: %s line %ld: expected 'id type shape density x y "
                  "z qw qx qy qz' (atom_style lsdem)\n", path, line);
          rc = 1;
        }
        i++;
      }
      done = 1;
    }
  }
  fclose(f);
  if (!rc && !done) {
    fprintf(stderr, "lsdem-shape: voids: %s: no Atoms section\n", path);
    rc = 1;
  }
  if (rc) free(g);
  else *out = g, *count = natoms;
  return rc;
}

int cmd_voids(int argc, char **argv)
{
  if (argc < 2) return voids_usage();
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, centre[2] = {0, 0}, inset = 0.0, h = 1.0;
  double radius = 0.0;
  int cyl = -1;
  for (int i = 2; i < argc; i++) {
    const char *a = argv[i];
    int ok = 1;
    if (!strcmp(a, "--cylinder") && i + 3 < argc && cyl < 0) {
      cyl = 1;
      ok = parse_number(argv[++i], 1, &radius) && parse_number(argv[++i], 0, &lo[2]) &&
           parse_number(argv[++i], 0, &hi[2]);
    } else if (!strcmp(a, "--box") && i + 6 < argc && cyl < 0) {
      cyl = 0;
      for (int k = 0; k < 3 && ok; k++)
        ok = parse_number(argv[++i], 0, &lo[k]) && parse_number(argv[++i], 0, &hi[k]);
    } else if (!strcmp(a, "--centre") && i + 2 < argc) {
      ok = parse_number(argv[++i], 0, &centre[0]) && parse_number(argv[++i], 0, &centre[1]);
    } else if (!strcmp(a, "--inset") && i + 1 < argc) {
      ok = parse_number(argv[++i], 0, &inset) && inset >= 0.0;
    } else if (!strcmp(a, "--spacing") && i + 1 < argc) {
      ok = parse_number(argv[++i], 1, &h);
    } else
      ok = 0;
    if (!ok) {
      fprintf(stderr, "lsdem-shape: voids: bad option or value near '%s'\n", a);
      return voids_usage();
    }
  }
  if (cyl < 0) {
    fprintf(stderr, "lsdem-shape: voids: give --cylinder R Z0 Z1 or --box X0 X1 Y0 Y1 Z0 Z1\n");
    return voids_usage();
  }
  if (cyl) {
    radius -= inset;
    lo[0] = centre[0] - radius, hi[0] = centre[0] + radius;
    lo[1] = centre[1] - radius, hi[1] = centre[1] + radius;
    lo[2] += inset, hi[2] -= inset;
  } else
    for (int k = 0; k < 3; k++) lo[k] += inset, hi[k] -= inset;
  int n[3];
  for (int k = 0; k < 3; k++) {
    const double cells = floor((hi[k] - lo[k]) / h);
    if (!(cells >= 1.0) || (cyl && !(radius > 0.0))) {
      fprintf(stderr, "lsdem-shape: voids: the region (after --inset %g) is empty\n", inset);
      return 1;
    }
    if (cells > 100000.0) {
      fprintf(stderr, "lsdem-shape: voids: more than 1e5 lattice points along an axis; use a "
              "larger --spacing\n");
      return 1;
    }
    n[k] = (int)cells;
    lo[k] = 0.5 * (lo[k] + hi[k]) - 0.5 * n[k] * h; /* centre the lattice in the region */
  }
  const size_t total = (size_t)n[0] * n[1] * n[2];
  if (total > (size_t)8e9) {
    fprintf(stderr, "lsdem-shape: voids: %zu lattice points: use a larger --spacing\n", total);
    return 1;
  }
  lsdem_library *lib = NULL;
  lsdem_error err;
  if (lsdem_library_open(argv[0], &lib, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: voids: %s\n", err.msg);
    return 1;
  }
  voids_grain *g = NULL;
  long ng = 0;
  if (read_atoms(argv[1], &g, &ng)) {
    lsdem_library_close(lib);
    return 1;
  }
  const int ns = lsdem_library_count(lib);
  uint8_t *solid = calloc(total / 8 + 1, 1);
  int rc = 0;
  if (!solid) {
    fprintf(stderr, "lsdem-shape: voids: out of memory (%zu lattice points)\n", total);
    rc = 1;
  }
  for (long i = 0; !rc && i < ng; i++) {
    if (g[i].shape < 1 || g[i].shape > ns) {
      fprintf(stderr, "lsdem-shape: voids: atom %ld has shape %d; the library has 1..%d\n",
              i + 1, g[i].shape, ns);
      rc = 1;
      break;
    }
    const lsdem_shape *s = lsdem_library_shape(lib, g[i].shape - 1);
    double q[4], qn = 0.0;
    for (int k = 0; k < 4; k++) qn += g[i].q[k] * g[i].q[k];
    for (int k = 0; k < 4; k++) q[k] = g[i].q[k] / sqrt(qn);
    int a[3], b[3];
    for (int k = 0; k < 3; k++) {
      a[k] = (int)ceil((g[i].x[k] - s->radius - lo[k]) / h - 0.5);
      b[k] = (int)floor((g[i].x[k] + s->radius - lo[k]) / h - 0.5);
      a[k] = a[k] < 0 ? 0 : a[k];
      b[k] = b[k] >= n[k] ? n[k] - 1 : b[k];
    }
    for (int kz = a[2]; kz <= b[2]; kz++)
      for (int ky = a[1]; ky <= b[1]; ky++)
        for (int kx = a[0]; kx <= b[0]; kx++) {
          const double p[3] = {lo[0] + (kx + 0.5) * h, lo[1] + (ky + 0.5) * h,
                               lo[2] + (kz + 0.5) * h};
          const double d[3] = {p[0] - g[i].x[0], p[1] - g[i].x[1], p[2] - g[i].x[2]};
          if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > s->radius * s->radius) continue;
          const size_t m = (size_t)kx + (size_t)n[0] * ((size_t)ky + (size_t)n[1] * kz);
          if (solid[m >> 3] & (1u << (m & 7))) continue;
          double body[3], grad[3];
          lsdem_quat_rotate_inv(q, d, body);
          if (lsdem_sdf_eval(&s->sdf, body, grad) < 0.0) solid[m >> 3] |= (uint8_t)(1u << (m & 7));
        }
  }
  if (!rc) {
    size_t inside = 0, nsolid = 0, m = 0;
    for (int kz = 0; kz < n[2]; kz++)
      for (int ky = 0; ky < n[1]; ky++)
        for (int kx = 0; kx < n[0]; kx++, m++) {
          if (cyl) {
            const double x = lo[0] + (kx + 0.5) * h - centre[0], y = lo[1] + (ky + 0.5) * h - centre[1];
            if (x * x + y * y > radius * radius) continue;
          }
          inside++;
          if (solid[m >> 3] & (1u << (m & 7))) nsolid++;
        }
    if (!inside || !nsolid) {
      fprintf(stderr, "lsdem-shape: voids: %zu lattice points in the region, %zu solid: "
              "nothing to measure\n", inside, nsolid);
      rc = 1;
    } else {
      const double fs = (double)nsolid / (double)inside;
      printf("voids: points %zu solid %zu solid_fraction %.5f void_ratio %.5f volume %.6g\n",
             inside, nsolid, fs, 1.0 / fs - 1.0, (double)inside * h * h * h);
    }
  }
  free(solid);
  free(g);
  lsdem_library_close(lib);
  return rc;
}
