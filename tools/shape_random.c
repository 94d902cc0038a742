/* lsdem-shape random: a library of random sand-like grains (core randgrain.c).
 *
 *   lsdem-shape random OUT.lslib --count K --size D [--size-spread S] [--elongation EL]
 *               [--flatness FL] [--angularity A] [--roughness R] [--seed S] [--nodes N]
 *               [--spacing H] [--margin M] [--name PREFIX]
 *
 * Prints the measured statistics of every grain (equivalent diameter, Zingg elongation and
 * flatness of the inertia-equivalent ellipsoid, Wadell sphericity) next to the request. */
#include "lsdem.h"
#include "lsdem_shape_cmds.h"
#include "shape_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  long count, nodes, margin, seed;
  double size, spread, spacing; /* spacing 0: D_i / 20 */
  lsdem_randgrain_params p;
  const char *prefix;
} random_options;

/* A number in (0, hi] (positive) or [0, hi]. */
static int parse_fraction(const char *s, int positive, double hi, double *v)
{
  return parse_number(s, positive, v) && *v >= 0.0 && *v <= hi;
}

static int parse_random(int argc, char **argv, random_options *o)
{
  memset(o, 0, sizeof *o);
  o->margin = 3, o->seed = 1, o->prefix = "grain";
  o->p.elongation = 0.8, o->p.flatness = 0.8, o->p.angularity = 0.1, o->p.roughness = 0.02;
  for (int i = 0; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[++i] : ""; /* every option has a value */
    int ok = 1;
    if (!strcmp(a, "--count")) ok = parse_count(v, 1, 1000000, &o->count);
    else if (!strcmp(a, "--size")) ok = parse_number(v, 1, &o->size);
    else if (!strcmp(a, "--size-spread")) ok = parse_fraction(v, 0, HUGE_VAL, &o->spread);
    else if (!strcmp(a, "--elongation")) ok = parse_fraction(v, 1, 1.0, &o->p.elongation);
    else if (!strcmp(a, "--flatness")) ok = parse_fraction(v, 1, 1.0, &o->p.flatness);
    else if (!strcmp(a, "--angularity")) ok = parse_fraction(v, 0, 1.0, &o->p.angularity);
    else if (!strcmp(a, "--roughness")) ok = parse_fraction(v, 0, 1.0, &o->p.roughness);
    else if (!strcmp(a, "--seed")) ok = parse_count(v, 0, 2147483647L, &o->seed);
    else if (!strcmp(a, "--nodes")) ok = parse_count(v, 1, 1000000, &o->nodes);
    else if (!strcmp(a, "--spacing")) ok = parse_number(v, 1, &o->spacing);
    else if (!strcmp(a, "--margin")) ok = parse_count(v, 1, 100, &o->margin);
    else if (!strcmp(a, "--name")) ok = *v != '\0';
    else ok = 0;
    if (ok && !strcmp(a, "--name")) o->prefix = v;
    if (!ok) {
      fprintf(stderr, "lsdem-shape: random: bad option or value near '%s' (elongation and "
              "flatness in (0, 1], angularity and roughness in [0, 1])\n", a);
      return 0;
    }
  }
  if (o->count < 1 || !(o->size > 0.0)) {
    fprintf(stderr, "lsdem-shape: random: --count K and --size D are required\n");
    return 0;
  }
  return 1;
}

/* One grain: random radius -> distance grid in the principal frame -> nodes, clusters
 * and mass properties (lsdem_shape_build, which takes the grid over). The node count
 * defaults to a mean node spacing of 0.09 d (inside the d/10 check). */
static lsdem_status make_grain(const random_options *o, double size, uint64_t seed,
                               lsdem_built_shape *b, lsdem_error *err)
{
  lsdem_randgrain_params p = o->p;
  p.size = size;
  p.seed = seed;
  lsdem_randgrain g;
  lsdem_grid grid;
  memset(b, 0, sizeof *b);
  lsdem_status st = lsdem_randgrain_make(&p, &g, err);
  if (st != LSDEM_OK) return st;
  const double h = o->spacing > 0.0 ? o->spacing : size / 20.0;
  st = lsdem_randgrain_grid(&g, h, (int)o->margin, &grid, NULL, err);
  if (st != LSDEM_OK) return st;
  lsdem_sdf sdf;
  memset(&sdf, 0, sizeof sdf);
  sdf.kind = LSDEM_SDF_GRID;
  sdf.grid = grid;
  return lsdem_shape_build(&sdf, (int)o->nodes, 0.09 * size, seed, b, err);
}

int cmd_random(int argc, char **argv)
{
  if (argc < 1) {
    fprintf(stderr, "usage: lsdem-shape random OUT.lslib --count K --size D [options]\n");
    return 2;
  }
  random_options o;
  if (!parse_random(argc - 1, argv + 1, &o)) return 2;
  const int n = (int)o.count;
  lsdem_built_shape *b = calloc((size_t)n, sizeof *b);
  lsdem_shape *shapes = calloc((size_t)n, sizeof *shapes);
  char (*names)[LSDEM_LIBRARY_NAME_MAX] = calloc((size_t)n, sizeof *names);
  const char **np = calloc((size_t)n, sizeof *np);
  int rc = !b || !shapes || !names || !np;
  if (rc) fprintf(stderr, "lsdem-shape: random: out of memory\n");
  uint64_t seeds = (uint64_t)o.seed, sizes = (uint64_t)o.seed ^ 0x5DEECE66Dull;
  double sum_el = 0.0, sum_fl = 0.0, sum_sph = 0.0;
  if (!rc)
    printf("%5s  %-14s %10s %7s %7s %7s %6s\n", "index", "name", "d_eq", "elong", "flat",
           "spher", "nodes");
  for (int i = 0; !rc && i < n; i++) {
    /* lognormal sizes: D exp(spread z), z standard normal (Box-Muller) */
    const double u1 = lsdem_uniform01(&sizes), u2 = lsdem_uniform01(&sizes);
    const double z = sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
    const double size = o.size * exp(o.spread * z);
    lsdem_error err;
    if (make_grain(&o, size, lsdem_splitmix64(&seeds), &b[i], &err) != LSDEM_OK) {
      fprintf(stderr, "lsdem-shape: random: grain %d: %s\n", i, err.msg);
      rc = 1;
      break;
    }
    shapes[i] = b[i].shape;
    snprintf(names[i], sizeof names[i], "%s_%04d", o.prefix, i);
    np[i] = names[i];
    lsdem_shape_stats st;
    lsdem_shape_stats_compute(b[i].shape.volume, b[i].shape.inertia,
                              lsdem_surface_area_grid(&b[i].shape.sdf.grid), &st);
    printf("%5d  %-14s %10.5g %7.3f %7.3f %7.3f %6d\n", i, names[i], st.d_eq, st.elongation,
           st.flatness, st.sphericity, b[i].shape.nnodes);
    sum_el += st.elongation, sum_fl += st.flatness, sum_sph += st.sphericity;
    shape_warn_quality(&b[i].shape, names[i]);
  }
  lsdem_error err;
  if (!rc && lsdem_library_write(argv[0], shapes, np, n, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: random: %s\n", err.msg);
    rc = 1;
  }
  if (!rc)
    printf("%s: %d random grains; mean elongation %.3f (asked %.3f), flatness %.3f (asked "
           "%.3f), sphericity %.3f\n", argv[0], n, sum_el / n, o.p.elongation, sum_fl / n,
           o.p.flatness, sum_sph / n);
  for (int i = 0; b && i < n; i++) lsdem_built_shape_free(&b[i]);
  free(b);
  free(shapes);
  free(names);
  free(np);
  return rc;
}
