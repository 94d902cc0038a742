/* lsdem-shape -- make, inspect and convert LSDEM shape libraries (doc/lsdem_shape.rst).
 *
 *   lsdem-shape list LIB
 *   lsdem-shape verify LIB
 *   lsdem-shape from-morph OUT.lslib MORPH...
 *   lsdem-shape to-morph LIB INDEX OUT.dat
 *   lsdem-shape analytic OUT.lslib KIND PARAMS... [--spacing H] [--nodes N] [--name NAME]
 *                        [--margin M] [--seed S] [--analytic]
 *   lsdem-shape merge OUT.lslib IN.lslib...
 *   lsdem-shape pick OUT.lslib IN.lslib INDICES.txt
 *   lsdem-shape render LIB SAMPLE OUT.png [--size W H] [--view x|y|z|iso] [--dump FRAME]
 *                      [--colour id|shape]                          (shape_render.c)
 *   lsdem-shape surface LIB INDEX OUT.vtk|OUT.ply [--spacing H]       (shape_render.c)
 *   lsdem-shape random OUT.lslib --count K --size D [options]         (shape_random.c)
 *   lsdem-shape pack LIB OUT.data --count N (--box X Y Z | --cylinder R H) [options]
 *                                                                     (shape_pack.c)
 *   lsdem-shape membrane PREFIX --radius RS --height H --rb RB ...     (shape_membrane.c)
 *   lsdem-shape net PREFIX --library LIB --shape ID --rb RB --spacing A ... (shape_net.c)
 *   lsdem-shape to-raw IMAGE.tif OUT.raw                              (shape_image.c)
 *   lsdem-shape voids LIB DATA (--cylinder R Z0 Z1 | --box ...) [options] (shape_voids.c)
 *   lsdem-shape bands POINTS --tol T --min-length L [options]           (shape_bands.c)
 *   lsdem-shape wall MESH.stl|.obj OUT.band --spacing H [--width W] [--scale S]
 *                                                                     (shape_wall.c)
 *   lsdem-shape terrain HEIGHTMAP OUT.band --spacing H [--width W] [--cell C] [--zscale Z]
 *                                                                     (shape_wall.c)
 *
 * Exit status 0 on success, 1 on any error (with a message on stderr), 2 on bad usage. */
#include "lsdem.h"
#include "lsdem_shape_cmds.h"
#include "shape_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static int usage(void)
{
  fprintf(stderr,
          "usage: lsdem-shape list LIB\n"
          "       lsdem-shape verify LIB\n"
          "       lsdem-shape from-morph OUT.lslib MORPH...\n"
          "       lsdem-shape to-morph LIB INDEX OUT.dat\n"
          "       lsdem-shape analytic OUT.lslib KIND PARAMS... [--spacing H] [--nodes N]\n"
          "                   [--name NAME] [--margin M] [--seed S] [--analytic]\n"
          "         KIND PARAMS: sphere R | ellipsoid A B C | box HX HY HZ | cylinder R HALFLEN\n"
          "                      | superellipsoid A B C E1 E2\n"
          "       lsdem-shape merge OUT.lslib IN.lslib...\n"
          "       lsdem-shape pick OUT.lslib IN.lslib INDICES.txt\n"
          "       lsdem-shape render LIB SAMPLE OUT.png [--size W H] [--view x|y|z|iso]\n"
          "                   [--dump FRAME] [--colour id|shape]\n"
          "       lsdem-shape surface LIB INDEX OUT.vtk|OUT.ply [--spacing H]\n"
          "       lsdem-shape from-labels IMAGE OUT.lslib [--raw NX NY NZ u8|u16|u32|i32 [--big-endian]]\n"
          "                   [--voxel S] [--min-voxels N] [--nodes N | --node-spacing S] [--smooth K]\n"
          "                   [--margin M] [--seed S] [--data OUT.data --density RHO]\n"
          "       lsdem-shape to-raw IMAGE.tif OUT.raw\n"
          "       lsdem-shape from-mesh MESH.stl|MESH.obj OUT.lslib [--spacing H] [--nodes N |\n"
          "                   --node-spacing S] [--scale S] [--name NAME] [--margin M] [--seed S] [--allow-open]\n"
          "       lsdem-shape random OUT.lslib --count K --size D [--size-spread S] [--elongation EL]\n"
          "                   [--flatness FL] [--angularity A] [--roughness R] [--seed S] [--nodes N]\n"
          "                   [--spacing H] [--margin M] [--name PREFIX]\n"
          "       lsdem-shape pack LIB OUT.data --count N (--box X Y Z | --cylinder R H) [--density RHO]\n"
          "                   [--seed S] [--max-tries T] [--gap G] [--weights W1,W2,... |\n"
          "                   --size-bins D0:W0,D1:W1,...,Dk] [--strict]\n"
          "       lsdem-shape membrane PREFIX --radius RS --height H --rb RB --library LIB\n"
          "                   --shapes SHAPE_IN SHAPE_OUT [--grains GRAINS.data] [--centre X Y]\n"
          "                   [--z0 Z] [--outer F] [--density RHO] [--types T_IN T_OUT]\n"
          "                   [--knbb K] [--ksbb K] [--kinter KN KS]\n"
          "       lsdem-shape net PREFIX --library LIB --shape ID --rb RB --spacing A --size L1 L2\n"
          "                   [--lattice hex|square] [--origin X Y Z] [--e1 X Y Z] [--e2 X Y Z]\n"
          "                   [--rest R0] [--clamp all|none|u0,u1,v0,v1] [--density RHO | --mass M]\n"
          "                   [--k K] [--damp C] [--break strain S | --break force F]\n"
          "                   [--types TFREE TCLAMP] [--grains DATA] [--name NAME] [--margin D]\n"
          "       lsdem-shape voids LIB DATA (--cylinder R Z0 Z1 | --box X0 X1 Y0 Y1 Z0 Z1)\n"
          "                   [--centre X Y] [--inset D] [--spacing H]\n"
          "       lsdem-shape bands POINTS --tol T --min-length L [--aspect A] [--angle DEG]\n"
          "                   [--samples N] [--seed S]\n"
          "       lsdem-shape wall MESH.stl|MESH.obj OUT.band --spacing H [--width W] [--scale S]\n"
          "       lsdem-shape terrain HEIGHTMAP.asc|.tif|.png OUT.band --spacing H [--width W]\n"
          "                   [--cell C] [--zscale Z]\n");
  return 2;
}

static int fail(const char *what, const lsdem_error *err)
{
  fprintf(stderr, "lsdem-shape: %s%s%s\n", what, err ? ": " : "", err ? err->msg : "");
  return 1;
}

/* ------------------------------------------------------------ list, verify ---- */

/* Every shape of lib checked as the atom style checks it (lsdem_library_verify: section
 * checksum, then the content), each bad one reported on stderr; returns how many. */
static int report_bad_shapes(const lsdem_library *lib, const char *cmd)
{
  lsdem_error err;
  int bad = 0;
  for (int i = 0; i < lsdem_library_count(lib); i++)
    if (lsdem_library_verify(lib, i, &err) != LSDEM_OK) {
      fprintf(stderr, "lsdem-shape: %s: %s\n", cmd, err.msg);
      bad++;
    }
  return bad;
}

static int cmd_list(int argc, char **argv)
{
  if (argc != 1) return usage();
  lsdem_library *lib = NULL;
  lsdem_error err;
  if (lsdem_library_open(argv[0], &lib, &err) != LSDEM_OK) return fail("list", &err);
  const int n = lsdem_library_count(lib);
  printf("%s: %d shape%s\n", argv[0], n, n == 1 ? "" : "s");
  printf("%5s  %-20s %-9s %-13s %6s %5s %10s %12s  %s\n", "index", "name", "kind",
         "grid/params", "nodes", "clus", "radius", "volume", "inertia I1 I2 I3");
  for (int i = 0; i < n; i++) {
    const lsdem_shape *s = lsdem_library_shape(lib, i);
    char dims[64];
    if (s->sdf.kind == LSDEM_SDF_GRID)
      snprintf(dims, sizeof dims, "%dx%dx%d h=%g", s->sdf.grid.n[0], s->sdf.grid.n[1],
               s->sdf.grid.n[2], s->sdf.grid.h);
    else
      snprintf(dims, sizeof dims, "%g %g %g", s->sdf.a[0], s->sdf.a[1], s->sdf.a[2]);
    printf("%5d  %-20s %-9s %-13s %6d %5d %10.6g %12.6g  %.6g %.6g %.6g\n", i,
           lsdem_library_name(lib, i), lsdem_sdf_kind_name(s->sdf.kind), dims, s->nnodes, s->nclusters,
           s->radius, s->volume, s->inertia[0], s->inertia[1], s->inertia[2]);
  }
  fflush(stdout); /* the table before the bad shapes on stderr */
  const int bad = report_bad_shapes(lib, "list");
  if (bad)
    fprintf(stderr, "lsdem-shape: list: %s: %d of %d shapes bad (above): atom_style lsdem "
            "refuses this library; make it again from the shapes' sources (lsdem-shape "
            "from-morph, analytic, from-labels, ...)\n", argv[0], bad, n);
  lsdem_library_close(lib);
  return bad ? 1 : 0;
}

static int cmd_verify(int argc, char **argv)
{
  if (argc != 1) return usage();
  lsdem_library *lib = NULL;
  lsdem_error err;
  if (lsdem_library_open(argv[0], &lib, &err) != LSDEM_OK) return fail("verify", &err);
  const int bad = report_bad_shapes(lib, "verify");
  printf("%s: %d shape%s, %d bad\n", argv[0], lsdem_library_count(lib),
         lsdem_library_count(lib) == 1 ? "" : "s", bad);
  lsdem_library_close(lib);
  return bad ? 1 : 0;
}

/* ------------------------------------------------------------- from-morph ---- */

/* Shape name of a morphology file: its base name without the extension. */
static void name_from_path(const char *path, char *name)
{
  const char *base = strrchr(path, '/');
  base = base ? base + 1 : path;
  snprintf(name, LSDEM_LIBRARY_NAME_MAX, "%s", base);
  char *dot = strrchr(name, '.');
  if (dot && dot != name) *dot = '\0';
}

typedef struct {
  lsdem_morph morph;
  double *nodes, *area, *sphere;
  int *start;
  char name[LSDEM_LIBRARY_NAME_MAX];
} imported;

static lsdem_status import_morph(const char *path, imported *im, lsdem_shape *s,
                                 lsdem_error *err)
{
  lsdem_status st = lsdem_morph_read(path, &im->morph, err);
  if (st != LSDEM_OK) return st;
  const size_t nn = im->morph.nnodes > 0 ? (size_t)im->morph.nnodes : 1;
  im->nodes = malloc(3 * nn * sizeof(double));
  im->area = malloc(nn * sizeof(double));
  im->sphere = malloc(4 * nn * sizeof(double));
  im->start = malloc((nn + 1) * sizeof(int));
  if (!im->nodes || !im->area || !im->sphere || !im->start)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: out of memory", path);
  name_from_path(path, im->name);
  st = lsdem_morph_to_shape(&im->morph, im->nodes, im->area, im->start, im->sphere, s, err);
  if (st != LSDEM_OK) {
    char msg[sizeof err->msg];
    snprintf(msg, sizeof msg, "%s", err->msg);
    return lsdem_fail(err, st, "%s: %s", path, msg);
  }
  return LSDEM_OK;
}

static int cmd_from_morph(int argc, char **argv)
{
  if (argc < 2) return usage();
  const int n = argc - 1;
  imported *im = calloc((size_t)n, sizeof *im);
  lsdem_shape *shapes = calloc((size_t)n, sizeof *shapes);
  const char **names = calloc((size_t)n, sizeof *names);
  lsdem_error err;
  int rc = !im || !shapes || !names ? fail("from-morph: out of memory", NULL) : 0;
  for (int i = 0; !rc && i < n; i++) {
    if (import_morph(argv[1 + i], &im[i], &shapes[i], &err) != LSDEM_OK) {
      fprintf(stderr, "lsdem-shape: from-morph: shape %d: %s\n", i, err.msg);
      rc = 1;
    } else {
      shape_warn_quality(&shapes[i], argv[1 + i]);
    }
    names[i] = im[i].name;
  }
  if (!rc && lsdem_library_write(argv[0], shapes, names, n, &err) != LSDEM_OK)
    rc = fail("from-morph", &err);
  if (!rc) printf("%s: %d shape%s from morphology files\n", argv[0], n, n == 1 ? "" : "s");
  for (int i = 0; im && i < n; i++) {
    lsdem_morph_free(&im[i].morph);
    free(im[i].nodes);
    free(im[i].area);
    free(im[i].sphere);
    free(im[i].start);
  }
  free(im);
  free(shapes);
  free(names);
  return rc;
}

/* --------------------------------------------------------------- to-morph ---- */

/* A grid shape as a morphology in voxel units (lengths divided by the spacing h):
 * volume / h^3, inertia / h^5, centroid at -origin / h in grid coordinates. */
static int cmd_to_morph(int argc, char **argv)
{
  if (argc != 3) return usage();
  lsdem_library *lib = NULL;
  lsdem_error err;
  long index;
  if (lsdem_library_open(argv[0], &lib, &err) != LSDEM_OK) return fail("to-morph", &err);
  if (!parse_count(argv[1], 0, lsdem_library_count(lib) - 1L, &index)) {
    fprintf(stderr, "lsdem-shape: to-morph: index '%s' is not in 0..%d\n", argv[1],
            lsdem_library_count(lib) - 1);
    lsdem_library_close(lib);
    return 1;
  }
  const lsdem_shape *s = lsdem_library_shape(lib, (int)index);
  if (s->sdf.kind != LSDEM_SDF_GRID) {
    fprintf(stderr, "lsdem-shape: to-morph: shape %ld is an analytic %s: a morphology file "
            "needs a grid\n", index, lsdem_sdf_kind_name(s->sdf.kind));
    lsdem_library_close(lib);
    return 1;
  }
  const double h = s->sdf.grid.h;
  const size_t ns = (size_t)s->sdf.grid.n[0] * s->sdf.grid.n[1] * s->sdf.grid.n[2];
  lsdem_morph m = {0};
  m.nodes = malloc((3 * (size_t)s->nnodes + 1) * sizeof(double));
  float *phi = malloc(ns * sizeof(float));
  int rc = 0;
  if (!m.nodes || !phi) rc = fail("to-morph: out of memory", NULL);
  if (!rc && lsdem_library_verify(lib, (int)index, &err) != LSDEM_OK) rc = fail("to-morph", &err);
  if (!rc) {
    m.mass = s->volume / (h * h * h);
    for (int k = 0; k < 3; k++) {
      m.inertia[k] = s->inertia[k] / pow(h, 5.0);
      m.cm_grid[k] = -s->sdf.grid.origin[k] / h;
      m.n[k] = s->sdf.grid.n[k];
    }
    m.nnodes = s->nnodes;
    for (int i = 0; i < 3 * s->nnodes; i++) m.nodes[i] = s->nodes[i] / h;
    m.radius = s->radius / h;
    for (size_t i = 0; i < ns; i++) phi[i] = (float)(s->sdf.grid.phi[i] / h);
    m.phi = phi;
    if (lsdem_morph_write(argv[2], &m, &err) != LSDEM_OK) rc = fail("to-morph", &err);
  }
  if (!rc && h != 1.0)
    printf("%s: lengths in voxels of the shape's spacing %g\n", argv[2], h);
  free(m.nodes);
  free(phi);
  lsdem_library_close(lib);
  return rc;
}

/* ---------------------------------------------------------------- analytic ---- */

typedef struct {
  lsdem_sdf sdf;       /* the exact shape */
  double half[3];      /* half-extents of its bounding box */
  double volume, inertia[3];
} analytic_shape;

/* Closed-form volume and principal moments (density 1) of the solids, about the centroid:
 * sphere I = 2/5 V R^2; ellipsoid I_x = V (b^2 + c^2) / 5; box (half-extents) I_x =
 * V (hy^2 + hz^2) / 3; cylinder along z (half-length L) I_x = V (3 R^2 + 4 L^2) / 12,
 * I_z = V R^2 / 2. The superellipsoid has none: quadrature of its exact surface
 * (lsdem_star_massprops, ~1e-5 relative); its axes are principal by symmetry. */
static void closed_form_massprops(analytic_shape *a)
{
  const double *p = a->sdf.a;
  double s2[3] = {0, 0, 0}; /* I_k = V * (sum of the other two s2) */
  if (a->sdf.kind == LSDEM_SDF_SUPERELLIPSOID) {
    lsdem_massprops mp;
    lsdem_star_massprops(lsdem_superellipsoid_radius, &a->sdf, 256, &mp, NULL);
    a->volume = mp.volume;
    for (int k = 0; k < 3; k++) a->inertia[k] = mp.inertia[4 * k];
    return;
  }
  switch (a->sdf.kind) {
  case LSDEM_SDF_SPHERE:
    a->volume = 4.0 / 3.0 * PI * p[0] * p[0] * p[0];
    s2[0] = s2[1] = s2[2] = p[0] * p[0] / 5.0;
    break;
  case LSDEM_SDF_ELLIPSOID:
    a->volume = 4.0 / 3.0 * PI * p[0] * p[1] * p[2];
    for (int k = 0; k < 3; k++) s2[k] = p[k] * p[k] / 5.0;
    break;
  case LSDEM_SDF_BOX:
    a->volume = 8.0 * p[0] * p[1] * p[2];
    for (int k = 0; k < 3; k++) s2[k] = p[k] * p[k] / 3.0;
    break;
  default: /* cylinder */
    a->volume = 2.0 * PI * p[0] * p[0] * p[1];
    s2[0] = s2[1] = p[0] * p[0] / 4.0;
    s2[2] = p[1] * p[1] / 3.0;
  }
  for (int k = 0; k < 3; k++) a->inertia[k] = a->volume * (s2[(k + 1) % 3] + s2[(k + 2) % 3]);
}

/* Surface area, exact for sphere, box and cylinder; Thomsen's approximation (p = 1.6075,
 * within 1.1%) for the ellipsoid. Only sizes the default node count. */
static double surface_area(const analytic_shape *a)
{
  const double *p = a->sdf.a;
  switch (a->sdf.kind) {
  case LSDEM_SDF_SPHERE: return 4.0 * PI * p[0] * p[0];
  case LSDEM_SDF_BOX:
  case LSDEM_SDF_SUPERELLIPSOID: /* the box of its semi-axes: an upper bound */
    return 8.0 * (p[0] * p[1] + p[1] * p[2] + p[2] * p[0]);
  case LSDEM_SDF_CYLINDER: return 2.0 * PI * p[0] * p[0] + 4.0 * PI * p[0] * p[1];
  default: {
    const double q = 1.6075;
    return 4.0 * PI * pow((pow(p[0] * p[1], q) + pow(p[0] * p[2], q) + pow(p[1] * p[2], q)) / 3.0,
                          1.0 / q);
  }
  }
}

/* Default node count: a mean node spacing sqrt(area / N) of 0.09 d, d the diameter of
 * the sphere of equal volume, inside the d/10 limit of lsdem_shape_check. */
static long default_node_count(const analytic_shape *a)
{
  const double d = 2.0 * cbrt(3.0 * a->volume / (4.0 * PI)), spacing = 0.09 * d;
  return (long)ceil(surface_area(a) / (spacing * spacing));
}

/* KIND PARAMS... at argv; returns how many arguments were used, 0 on error. */
static int parse_analytic(int argc, char **argv, analytic_shape *a)
{
  static const struct {
    const char *name;
    lsdem_sdf_kind kind;
    int nparams;
  } kinds[] = {{"sphere", LSDEM_SDF_SPHERE, 1}, {"ellipsoid", LSDEM_SDF_ELLIPSOID, 3},
               {"box", LSDEM_SDF_BOX, 3}, {"cylinder", LSDEM_SDF_CYLINDER, 2},
               {"superellipsoid", LSDEM_SDF_SUPERELLIPSOID, 5}};
  memset(a, 0, sizeof *a);
  for (size_t k = 0; argc > 0 && k < sizeof kinds / sizeof kinds[0]; k++) {
    if (strcmp(argv[0], kinds[k].name) != 0) continue;
    if (argc < 1 + kinds[k].nparams) break;
    a->sdf.kind = kinds[k].kind;
    for (int i = 0; i < kinds[k].nparams; i++)
      if (!parse_number(argv[1 + i], 1, &a->sdf.a[i])) {
        fprintf(stderr, "lsdem-shape: analytic: %s parameter %d '%s' must be a positive "
                "number\n", kinds[k].name, i + 1, argv[1 + i]);
        return 0;
      }
    const double *p = a->sdf.a;
    if (a->sdf.kind == LSDEM_SDF_SUPERELLIPSOID && !(p[3] >= 0.1 && p[3] <= 2.0 && p[4] >= 0.1 &&
                                                     p[4] <= 2.0)) {
      fprintf(stderr, "lsdem-shape: analytic: superellipsoid exponents E1 E2 must be in "
              "[0.1, 2] (1: ellipsoid, 0.1: nearly a box, 2: a double cone / octahedron)\n");
      return 0;
    }
    switch (a->sdf.kind) {
    case LSDEM_SDF_SPHERE: a->half[0] = a->half[1] = a->half[2] = p[0]; break;
    case LSDEM_SDF_CYLINDER: a->half[0] = a->half[1] = p[0], a->half[2] = p[1]; break;
    default: memcpy(a->half, p, sizeof a->half);
    }
    closed_form_massprops(a);
    return 1 + kinds[k].nparams;
  }
  fprintf(stderr, "lsdem-shape: analytic: expected sphere R | ellipsoid A B C | box HX HY HZ | "
          "cylinder R HALFLEN | superellipsoid A B C E1 E2, got '%s'\n", argc > 0 ? argv[0] : "");
  return 0;
}

typedef struct {
  double spacing; /* 0: smallest half-extent / 10 */
  long nodes;     /* 0: default_node_count */
  long margin, seed;
  int keep_analytic;
  const char *name;
} analytic_options;

static int parse_options(int argc, char **argv, analytic_options *o)
{
  o->spacing = 0.0, o->nodes = 0, o->margin = 3, o->seed = 1, o->keep_analytic = 0;
  o->name = NULL;
  for (int i = 0; i < argc; i++) {
    const int has = i + 1 < argc;
    int ok = 1;
    if (!strcmp(argv[i], "--analytic")) o->keep_analytic = 1;
    else if (!strcmp(argv[i], "--spacing")) ok = has && parse_number(argv[++i], 1, &o->spacing);
    else if (!strcmp(argv[i], "--nodes")) ok = has && parse_count(argv[++i], 1, 1000000, &o->nodes);
    else if (!strcmp(argv[i], "--margin")) ok = has && parse_count(argv[++i], 1, 100, &o->margin);
    else if (!strcmp(argv[i], "--seed")) ok = has && parse_count(argv[++i], 0, 2147483647L, &o->seed);
    else if (!strcmp(argv[i], "--name") && has) o->name = argv[++i];
    else ok = 0;
    if (!ok) {
      fprintf(stderr, "lsdem-shape: analytic: bad option or value near '%s' (options: "
              "--spacing H > 0, --nodes 1..1000000, --margin 1..100, --seed >= 0, --name S, "
              "--analytic)\n", argv[i]);
      return 0;
    }
  }
  return 1;
}

/* Grid sampling of an analytic shape: the grid's own volume next to the exact one. */
static void report_sampling(const lsdem_grid *g, double exact_volume)
{
  lsdem_massprops mp;
  lsdem_error err;
  if (lsdem_massprops_grid(g, 2, &mp, &err) == LSDEM_OK)
    printf("grid %dx%dx%d, spacing %g: grid volume %.6g vs exact %.6g (%+.2f%%)\n", g->n[0],
           g->n[1], g->n[2], g->h, mp.volume, exact_volume,
           100.0 * (mp.volume / exact_volume - 1.0));
}

/* The analytic shape: nodes on the exact surface (lsdem_shape_build), closed-form mass
 * properties, and unless --analytic the exact SDF sampled onto a grid that the built
 * shape takes over. */
static lsdem_status build_analytic(const analytic_shape *a, const analytic_options *o,
                                   lsdem_built_shape *b, lsdem_error *err)
{
  lsdem_status st = lsdem_shape_build(&a->sdf, (int)o->nodes, 0.0, (uint64_t)o->seed, b, err);
  if (st != LSDEM_OK) return st;
  b->shape.volume = a->volume;
  memcpy(b->shape.inertia, a->inertia, sizeof b->shape.inertia);
  if (o->keep_analytic) return LSDEM_OK;
  const double hmin = fmin(a->half[0], fmin(a->half[1], a->half[2]));
  const double h = o->spacing > 0.0 ? o->spacing : hmin / 10.0;
  const double lo[3] = {-a->half[0], -a->half[1], -a->half[2]};
  lsdem_grid g;
  memset(&g, 0, sizeof g);
  st = lsdem_grid_sample(&a->sdf, lo, a->half, h, (int)o->margin, &g, err);
  if (st != LSDEM_OK) return st;
  memset(&b->shape.sdf, 0, sizeof b->shape.sdf);
  b->shape.sdf.kind = LSDEM_SDF_GRID;
  b->shape.sdf.grid = g;
  b->phi = (float *)g.phi;
  b->shape.radius = fmax(b->shape.radius, lsdem_sdf_bound_radius(&b->shape.sdf));
  report_sampling(&g, a->volume);
  return LSDEM_OK;
}

/* More default nodes than this is a flat or thin shape (a sphere gets 388): asked for. */
enum { DEFAULT_NODES_MAX = 10000 };

static int cmd_analytic(int argc, char **argv)
{
  if (argc < 3) return usage();
  analytic_shape a;
  const int used = parse_analytic(argc - 1, argv + 1, &a);
  analytic_options o;
  if (!used || !parse_options(argc - 1 - used, argv + 1 + used, &o)) return 1;
  if (o.nodes == 0 && (o.nodes = default_node_count(&a)) > DEFAULT_NODES_MAX) {
    fprintf(stderr, "lsdem-shape: analytic: this shape is so flat or thin that the default "
            "node spacing (0.09 x its equivalent diameter) gives %ld nodes; give --nodes N "
            "(placing N nodes takes time growing as N^2: about a minute for 20000)\n", o.nodes);
    return 1;
  }
  if (o.keep_analytic && a.sdf.kind != LSDEM_SDF_SPHERE) {
    fprintf(stderr, "lsdem-shape: analytic: --analytic is only for spheres\n");
    return 1;
  }
  lsdem_built_shape b;
  lsdem_error err;
  const char *name = o.name ? o.name : argv[1];
  int rc = 0;
  if (build_analytic(&a, &o, &b, &err) != LSDEM_OK) rc = fail("analytic", &err);
  if (!rc) shape_warn_quality(&b.shape, name);
  if (!rc && lsdem_library_write(argv[0], &b.shape, &name, 1, &err) != LSDEM_OK)
    rc = fail("analytic", &err);
  if (!rc)
    printf("%s: %s '%s', %d nodes in %d clusters, radius %.6g, volume %.6g\n", argv[0],
           o.keep_analytic ? "analytic sphere" : "grid shape", name, b.shape.nnodes,
           b.shape.nclusters, b.shape.radius, b.shape.volume);
  lsdem_built_shape_free(&b);
  return rc;
}

/* ------------------------------------------------------------------- merge ---- */

static int cmd_merge(int argc, char **argv)
{
  if (argc < 2) return usage();
  const int nin = argc - 1;
  lsdem_library **libs = calloc((size_t)nin, sizeof *libs);
  lsdem_error err;
  int rc = libs ? 0 : fail("merge: out of memory", NULL), total = 0;
  for (int i = 0; !rc && i < nin; i++) {
    if (lsdem_library_open(argv[1 + i], &libs[i], &err) != LSDEM_OK) rc = fail("merge", &err);
    else total += lsdem_library_count(libs[i]);
  }
  lsdem_shape *shapes = calloc((size_t)total + 1, sizeof *shapes);
  const char **names = calloc((size_t)total + 1, sizeof *names);
  if (!rc && (!shapes || !names)) rc = fail("merge: out of memory", NULL);
  for (int i = 0, k = 0; !rc && i < nin; i++)
    for (int j = 0; !rc && j < lsdem_library_count(libs[i]); j++, k++) {
      if (lsdem_library_verify(libs[i], j, &err) != LSDEM_OK) rc = fail(argv[1 + i], &err);
      shapes[k] = *lsdem_library_shape(libs[i], j);
      names[k] = lsdem_library_name(libs[i], j);
    }
  /* The writer replaces OUT by rename, so OUT may also be one of the (mapped) inputs. */
  if (!rc && lsdem_library_write(argv[0], shapes, names, total, &err) != LSDEM_OK)
    rc = fail("merge", &err);
  if (!rc) printf("%s: %d shapes from %d libraries\n", argv[0], total, nin);
  for (int i = 0; libs && i < nin; i++) lsdem_library_close(libs[i]);
  free(libs);
  free(shapes);
  free(names);
  return rc;
}

/* -------------------------------------------------------------------- pick ---- */

/* pick OUT.lslib IN.lslib INDICES: entry j of OUT is a copy of entry INDICES[j] of IN
 * (0-based, whitespace-separated in the file INDICES, repeats allowed): a library with one
 * shape per grain (the CT case's memory and cache traffic) from a few templates. */
static int cmd_pick(int argc, char **argv)
{
  if (argc != 3) return usage();
  lsdem_library *lib = NULL;
  lsdem_error err;
  if (lsdem_library_open(argv[1], &lib, &err) != LSDEM_OK) return fail("pick", &err);
  const int nin = lsdem_library_count(lib);
  FILE *f = fopen(argv[2], "r");
  int rc = f ? 0 : fail("pick: cannot open the index file", NULL), n = 0, cap = 0;
  int *idx = NULL;
  long v;
  while (!rc && fscanf(f, "%ld", &v) == 1) {
    if (v < 0 || v >= nin) {
      fprintf(stderr, "lsdem-shape: pick: index %ld (entry %d) outside 0..%d of %s\n", v, n + 1,
              nin - 1, argv[1]);
      rc = 1;
      break;
    }
    if (n == cap) {
      cap = cap ? 2 * cap : 1024;
      int *t = realloc(idx, (size_t)cap * sizeof *idx);
      if (!t) {
        rc = fail("pick: out of memory", NULL);
        break;
      }
      idx = t;
    }
    idx[n++] = (int)v;
  }
  if (!rc && f && !feof(f)) rc = fail("pick: the index file holds something else than integers", NULL);
  if (!rc && n == 0) rc = fail("pick: no indices", NULL);
  if (f) fclose(f);
  lsdem_shape *shapes = rc ? NULL : calloc((size_t)n, sizeof *shapes);
  const char **names = rc ? NULL : calloc((size_t)n, sizeof *names);
  if (!rc && (!shapes || !names)) rc = fail("pick: out of memory", NULL);
  for (int k = 0; !rc && k < nin; k++)
    if (lsdem_library_verify(lib, k, &err) != LSDEM_OK) rc = fail(argv[1], &err);
  for (int j = 0; !rc && j < n; j++) {
    shapes[j] = *lsdem_library_shape(lib, idx[j]);
    names[j] = lsdem_library_name(lib, idx[j]);
  }
  if (!rc && lsdem_library_write(argv[0], shapes, names, n, &err) != LSDEM_OK)
    rc = fail("pick", &err);
  if (!rc) printf("%s: %d shapes picked from the %d of %s\n", argv[0], n, nin, argv[1]);
  free(idx);
  free(shapes);
  free(names);
  lsdem_library_close(lib);
  return rc;
}

int main(int argc, char **argv)
{
  static const struct {
    const char *name;
    int (*run)(int, char **);
  } cmds[] = {{"list", cmd_list},         {"verify", cmd_verify},   {"from-morph", cmd_from_morph},
              {"to-morph", cmd_to_morph}, {"analytic", cmd_analytic}, {"merge", cmd_merge},
              {"render", cmd_render}, {"surface", cmd_surface},
              {"from-labels", cmd_from_labels}, {"from-mesh", cmd_from_mesh},
              {"random", cmd_random}, {"pack", cmd_pack}, {"membrane", cmd_membrane},
              {"net", cmd_net},
              {"to-raw", cmd_to_raw}, {"voids", cmd_voids}, {"pick", cmd_pick},
              {"wall", cmd_wall}, {"terrain", cmd_terrain}, {"bands", cmd_bands}};
  if (argc < 2) return usage();
  for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; i++)
    if (!strcmp(argv[1], cmds[i].name)) return cmds[i].run(argc - 2, argv + 2);
  fprintf(stderr, "lsdem-shape: unknown command '%s'\n", argv[1]);
  return usage();
}
