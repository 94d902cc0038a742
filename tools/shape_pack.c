/* lsdem-shape pack: a packed sample from a shape library (core packing.c) as a LAMMPS
 * data file for atom_style lsdem.
 *
 *   lsdem-shape pack LIB OUT.data --count N (--box X Y Z | --cylinder R H) [--density RHO]
 *               [--seed S] [--max-tries T] [--gap G] [--weights W1,W2,...]
 *               [--size-bins D0:W0,D1:W1,...,Dk] [--strict]
 *
 * Reports the achieved count, solid fraction and void ratio e = V_container / V_solids - 1. */
#include "lsdem.h"
#include "lsdem_shape_cmds.h"
#include "shape_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

typedef struct {
  long count, seed, tries;
  double density, gap;
  lsdem_container box;
  int have_box, strict;
  const char *weights, *bins;
} pack_options;

static int parse_pack(int argc, char **argv, pack_options *o)
{
  memset(o, 0, sizeof *o);
  o->seed = 1, o->tries = 1000, o->density = 2650.0;
  for (int i = 0; i < argc; i++) {
    const char *a = argv[i];
    int ok = 1;
    if (!strcmp(a, "--strict")) o->strict = 1;
    else if (!strcmp(a, "--count") && i + 1 < argc)
      ok = parse_count(argv[++i], 1, 100000000, &o->count);
    else if ((!strcmp(a, "--box") || !strcmp(a, "--cylinder")) && o->have_box) {
      fprintf(stderr, "lsdem-shape: pack: give --box or --cylinder once, not both\n");
      return 0;
    } else if (!strcmp(a, "--box") && i + 3 < argc) {
      o->box.kind = LSDEM_CONTAINER_BOX, o->have_box = 1;
      for (int k = 0; k < 3; k++) ok = ok && parse_number(argv[++i], 1, &o->box.size[k]);
    } else if (!strcmp(a, "--cylinder") && i + 2 < argc) {
      o->box.kind = LSDEM_CONTAINER_CYLINDER, o->have_box = 1;
      for (int k = 0; k < 2; k++) ok = ok && parse_number(argv[++i], 1, &o->box.size[k]);
    } else if (!strcmp(a, "--density") && i + 1 < argc)
      ok = parse_number(argv[++i], 1, &o->density);
    else if (!strcmp(a, "--seed") && i + 1 < argc)
      ok = parse_count(argv[++i], 0, 2147483647L, &o->seed);
    else if (!strcmp(a, "--max-tries") && i + 1 < argc)
      ok = parse_count(argv[++i], 1, 100000000, &o->tries);
    else if (!strcmp(a, "--gap") && i + 1 < argc)
      ok = parse_number(argv[++i], 0, &o->gap) && o->gap >= 0.0;
    else if (!strcmp(a, "--weights") && i + 1 < argc) o->weights = argv[++i];
    else if (!strcmp(a, "--size-bins") && i + 1 < argc) o->bins = argv[++i];
    else ok = 0;
    if (!ok) {
      fprintf(stderr, "lsdem-shape: pack: bad option or value near '%s'\n", a);
      return 0;
    }
  }
  if (o->count < 1 || !o->have_box) {
    fprintf(stderr, "lsdem-shape: pack: --count N and --box X Y Z or --cylinder R H are "
            "required\n");
    return 0;
  }
  if (o->weights && o->bins) {
    fprintf(stderr, "lsdem-shape: pack: give --weights or --size-bins, not both\n");
    return 0;
  }
  return 1;
}

/* --weights W1,W2,...: one non-negative weight per library shape. */
static int parse_weights(const char *s, int n, double *w)
{
  for (int k = 0; k < n; k++) {
    char *end;
    w[k] = strtod(s, &end);
    if (end == s || !(w[k] >= 0.0) || !isfinite(w[k])) return 0;
    if (k + 1 < n && *end != ',') return 0;
    s = end + 1;
    if (k + 1 == n && *end != '\0') return 0;
  }
  return 1;
}

/* --size-bins D0:W0,D1:W1,...,Dk: bin j = [Dj, Dj+1) of equivalent-sphere diameter gets
 * number fraction Wj, shared equally by the library shapes in it; shapes outside every bin
 * get weight 0. */
static int size_bin_weights(const char *s, const lsdem_library *lib, double *w)
{
  double d[65], f[65];
  int nb = 0;
  for (;;) {
    char *end;
    if (nb >= 64) return 0;
    d[nb] = strtod(s, &end);
    if (end == s || !(d[nb] > 0.0) || (nb > 0 && !(d[nb] > d[nb - 1]))) return 0;
    if (*end == '\0') break;
    if (*end != ':') return 0;
    s = end + 1;
    f[nb] = strtod(s, &end);
    if (end == s || !(f[nb] >= 0.0) || *end != ',') return 0;
    s = end + 1;
    nb++;
  }
  if (nb < 1) return 0;
  const int n = lsdem_library_count(lib);
  int *bin = malloc((size_t)n * sizeof(int)), members[64] = {0};
  if (!bin) return 0;
  for (int k = 0; k < n; k++) {
    const double deq = cbrt(6.0 * lsdem_library_shape(lib, k)->volume / PI);
    bin[k] = -1;
    for (int j = 0; j < nb; j++)
      if (deq >= d[j] && deq < d[j + 1]) bin[k] = j;
    if (bin[k] >= 0) members[bin[k]]++;
  }
  for (int j = 0; j < nb; j++)
    if (f[j] > 0.0 && members[j] == 0)
      fprintf(stderr, "lsdem-shape: pack: warning: no library shape in size bin [%g, %g)\n",
              d[j], d[j + 1]);
  for (int k = 0; k < n; k++) w[k] = bin[k] >= 0 ? f[bin[k]] / members[bin[k]] : 0.0;
  free(bin);
  return 1;
}

static int write_sample(const char *path, const pack_options *o, const lsdem_placed *g, int n)
{
  int *shape = malloc(((size_t)n + 1) * sizeof(int));
  double *pos = malloc((3 * (size_t)n + 1) * sizeof(double));
  double *quat = malloc((4 * (size_t)n + 1) * sizeof(double));
  int rc = !shape || !pos || !quat;
  if (rc) fprintf(stderr, "lsdem-shape: pack: out of memory\n");
  for (int i = 0; !rc && i < n; i++) {
    shape[i] = g[i].shape + 1;
    memcpy(pos + 3 * i, g[i].x, 3 * sizeof(double));
    memcpy(quat + 4 * i, g[i].q, 4 * sizeof(double));
  }
  double lo[3], hi[3];
  lsdem_container_bounds(&o->box, lo, hi);
  if (!rc)
    rc = shape_write_data(path, "LSDEM packed sample (lsdem-shape pack)", n, shape, o->density,
                          pos, quat, lo, hi);
  free(shape);
  free(pos);
  free(quat);
  return rc;
}

int cmd_pack(int argc, char **argv)
{
  if (argc < 2) {
    fprintf(stderr, "usage: lsdem-shape pack LIB OUT.data --count N (--box X Y Z | "
            "--cylinder R H) [options]\n");
    return 2;
  }
  pack_options o;
  if (!parse_pack(argc - 2, argv + 2, &o)) return 2;
  lsdem_library *lib = NULL;
  lsdem_error err;
  if (lsdem_library_open(argv[0], &lib, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: pack: %s\n", err.msg);
    return 1;
  }
  const int ns = lsdem_library_count(lib);
  lsdem_shape *shapes = calloc((size_t)ns, sizeof *shapes);
  double *w = calloc((size_t)ns, sizeof *w);
  lsdem_placed *g = calloc((size_t)o.count, sizeof *g);
  int rc = !shapes || !w || !g;
  if (rc) fprintf(stderr, "lsdem-shape: pack: out of memory\n");
  if (!rc && lsdem_library_verify(lib, -1, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: pack: %s\n", err.msg);
    rc = 1;
  }
  for (int k = 0; !rc && k < ns; k++) shapes[k] = *lsdem_library_shape(lib, k);
  if (!rc && o.weights && !parse_weights(o.weights, ns, w)) {
    fprintf(stderr, "lsdem-shape: pack: --weights needs %d comma-separated numbers >= 0\n", ns);
    rc = 1;
  }
  if (!rc && o.bins && !size_bin_weights(o.bins, lib, w)) {
    fprintf(stderr, "lsdem-shape: pack: --size-bins wants D0:W0,D1:W1,...,Dk with increasing "
            "diameters > 0 and weights >= 0\n");
    rc = 1;
  }
  const lsdem_pack_params prm = {(int)o.count, o.gap, o.tries, (uint64_t)o.seed,
                                 o.weights || o.bins ? w : NULL};
  int placed = 0;
  if (!rc && lsdem_pack(shapes, ns, &o.box, &prm, g, &placed, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: pack: %s\n", err.msg);
    rc = 1;
  }
  if (!rc) rc = write_sample(argv[1], &o, g, placed);
  if (!rc) {
    double vs = 0.0;
    for (int i = 0; i < placed; i++) vs += shapes[g[i].shape].volume;
    const double vc = lsdem_container_volume(&o.box);
    printf("%s: %d of %ld grains placed; solids %.6g of container %.6g: solid fraction %.4f, "
           "void ratio e = %.4f\n", argv[1], placed, o.count, vs, vc, vs / vc,
           vs > 0.0 ? vc / vs - 1.0 : HUGE_VAL);
    if (placed < o.count) {
      fprintf(stderr, "lsdem-shape: pack: only %d of %ld grains fit (%ld tries each); the "
              "data file holds the %d placed\n", placed, o.count, o.tries, placed);
      if (o.strict) rc = 1;
    }
  }
  free(shapes);
  free(w);
  free(g);
  lsdem_library_close(lib);
  return rc;
}
