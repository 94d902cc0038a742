/* shape_labels.c -- `lsdem-shape from-labels`: a labelled CT image (raw or multi-page
 * TIFF) to a shape library, one grid shape per label, and optionally the in-situ sample as
 * a LAMMPS data file (each grain at its scan position and orientation). */
#include "lsdem.h"
#include "lsdem_shape_cmds.h"
#include "shape_common.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { LABELS_MAX_WARNED = 10 }; /* grains whose warnings are printed in full */
/* The node checks' tolerances for grains from voxel labels, from what the discretisation
 * gives on good grains of tools/synthetic_sand.py scans at D50 8, 14 and 25 voxels (default
 * node spacing): the node volume differed from the grid's by -3.8 to +12.0 % on 751 truth
 * labels (median +5 %: the co-area node areas of a grid that is only nearly a distance
 * function) and by up to 16.6 % on 285 labels lsdem-segment found with IoU >= 0.8 (rougher
 * surfaces); the moments by up to 13.2 and 17.1 %. The defaults' 3 % and 5 % failed nearly
 * every grain; these bounds pass them all with a margin (doc/lsdem_shape.rst, from-labels).
 * They check the nodes against the grid, not the segmentation: the labels that held two
 * grains or missed one showed the same spread (up to 17.4 % and 23.8 %). */
#define LABELS_VOLUME_TOL 0.20
#define LABELS_INERTIA_TOL 0.25
/* warnings that only restate the scan's resolution: counted once for all grains */
#define LABELS_RESOLUTION (LSDEM_CHECK_COARSE_GRID | LSDEM_CHECK_SPARSE_NODES)

typedef struct {
  int raw, big_endian, dims[3];
  lsdem_voxel_type type;
  lsdem_voxel_options vox;
  long nodes, seed;
  double node_spacing, density;
  const char *data;
} labels_options;

static int parse_type(const char *s, lsdem_voxel_type *t)
{
  static const char *names[4] = {"u8", "u16", "u32", "i32"};
  for (int k = 0; k < 4; k++)
    if (!strcmp(s, names[k])) {
      *t = (lsdem_voxel_type)k;
      return 1;
    }
  return 0;
}

static int parse_labels_options(int argc, char **argv, labels_options *o)
{
  memset(o, 0, sizeof *o);
  o->vox = (lsdem_voxel_options){1.0, 27, 0, 2};
  o->nodes = 0, o->seed = 1, o->density = 0.0; /* nodes 0: spacing d/10 (auto) */
  int have_density = 0;
  for (int i = 0; i < argc; i++) {
    const int has = i + 1 < argc;
    long v = 0;
    int ok = 1;
    if (!strcmp(argv[i], "--raw")) {
      ok = i + 4 < argc && parse_type(argv[i + 4], &o->type);
      for (int a = 0; ok && a < 3; a++) {
        ok = parse_count(argv[i + 1 + a], 1, 1 << 20, &v);
        o->dims[a] = (int)v;
      }
      o->raw = 1;
      if (ok) i += 4;
    } else if (!strcmp(argv[i], "--big-endian")) o->big_endian = 1;
    else if (!strcmp(argv[i], "--voxel")) ok = has && parse_number(argv[++i], 1, &o->vox.voxel_size);
    else if (!strcmp(argv[i], "--min-voxels")) ok = has && parse_count(argv[++i], 1, 2147483647L, &o->vox.min_voxels);
    else if (!strcmp(argv[i], "--nodes")) ok = has && parse_count(argv[++i], 1, 1000000, &o->nodes);
    else if (!strcmp(argv[i], "--node-spacing")) {
      ok = has && parse_number(argv[++i], 1, &o->node_spacing);
      o->nodes = 0;
    } else if (!strcmp(argv[i], "--smooth")) {
      ok = has && parse_count(argv[++i], 0, 20, &v);
      o->vox.smooth = (int)v;
    } else if (!strcmp(argv[i], "--margin")) {
      ok = has && parse_count(argv[++i], 1, 100, &v);
      o->vox.margin = (int)v;
    } else if (!strcmp(argv[i], "--seed")) ok = has && parse_count(argv[++i], 0, 2147483647L, &o->seed);
    else if (!strcmp(argv[i], "--data") && has) o->data = argv[++i];
    else if (!strcmp(argv[i], "--density")) ok = have_density = has && parse_number(argv[++i], 1, &o->density);
    else ok = 0;
    if (!ok) {
      fprintf(stderr, "lsdem-shape: from-labels: bad option or value near '%s'\n", argv[i]);
      return 0;
    }
  }
  if (o->data && !have_density) {
    fprintf(stderr, "lsdem-shape: from-labels: --data needs --density RHO\n");
    return 0;
  }
  if (o->big_endian && !o->raw) {
    fprintf(stderr, "lsdem-shape: from-labels: --big-endian goes with --raw\n");
    return 0;
  }
  return 1;
}

static int read_image(const char *path, const labels_options *o, lsdem_label_image *img)
{
  lsdem_error err;
  lsdem_status st;
  FILE *f = fopen(path, "rb");
  if (!f) {
    fprintf(stderr, "lsdem-shape: from-labels: cannot open %s: %s\n", path, strerror(errno));
    return 1;
  }
  fclose(f);
  if (lsdem_image_is_tiff(path)) {
    if (o->raw)
      fprintf(stderr, "lsdem-shape: from-labels: %s is a TIFF file: --raw ignored\n", path);
    st = lsdem_image_read_tiff(path, img, &err);
  } else if (o->raw) {
    st = lsdem_image_read_raw(path, o->dims, o->type, o->big_endian, img, &err);
  } else {
    fprintf(stderr, "lsdem-shape: from-labels: %s is not a TIFF file: give its layout with "
            "--raw NX NY NZ u8|u16|u32|i32\n", path);
    return 1;
  }
  if (st != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: from-labels: %s\n", err.msg);
    return 1;
  }
  return 0;
}

/* Library shapes for the grains (their grids are handed over to the built shapes). */
static int build_shapes(lsdem_voxel_grain *gr, int n, const labels_options *o,
                        lsdem_built_shape *b, char (*names)[32])
{
  int warned = 0, with_warnings = 0, coarse = 0, sparse = 0;
  for (int i = 0; i < n; i++) {
    lsdem_sdf sdf;
    memset(&sdf, 0, sizeof sdf);
    sdf.kind = LSDEM_SDF_GRID;
    sdf.grid = gr[i].grid;
    gr[i].grid.phi = NULL; /* now owned by b[i] */
    lsdem_error err;
    snprintf(names[i], sizeof names[i], "label_%ld", (long)gr[i].label);
    if (lsdem_shape_build(&sdf, (int)o->nodes, o->node_spacing, (uint64_t)o->seed, &b[i], &err) !=
        LSDEM_OK) {
      fprintf(stderr, "lsdem-shape: from-labels: %s (%ld voxels): %s\n", names[i], gr[i].nvoxels,
              err.msg);
      return 1;
    }
    lsdem_shape_report r;
    if (lsdem_shape_check_tol(&b[i].shape, LABELS_VOLUME_TOL, LABELS_INERTIA_TOL, &r, &err) !=
        LSDEM_OK) {
      fprintf(stderr, "lsdem-shape: warning: %s: not checked: %s\n", names[i], err.msg);
      r.warnings = 0;
    }
    coarse += (r.warnings & LSDEM_CHECK_COARSE_GRID) != 0;
    sparse += (r.warnings & LSDEM_CHECK_SPARSE_NODES) != 0;
    r.warnings &= ~LABELS_RESOLUTION;
    if (r.warnings && warned < LABELS_MAX_WARNED) { /* the first few in full, count the rest */
      shape_print_report(&r, names[i]);
      warned++;
    }
    with_warnings += r.warnings != 0;
    shape_progress("from-labels: shapes built", i + 1, n);
  }
  if (with_warnings > warned)
    fprintf(stderr, "lsdem-shape: warning: %d grains have quality warnings (first %d shown)\n",
            with_warnings, warned);
  if (coarse)
    fprintf(stderr, "lsdem-shape: warning: %d of %d grains have a grid (the voxel) coarser than "
            "R/10, R the equivalent-sphere radius: contacts will be rough\n", coarse, n);
  if (sparse)
    fprintf(stderr, "lsdem-shape: warning: %d of %d grains have a mean node spacing above d/10 "
            "(--nodes, --node-spacing)\n", sparse, n);
  return 0;
}

/* The in-situ sample: grain i is shape i+1 at its scan position and orientation, in a box
 * bounded by the outer voxel faces. */
static int write_in_situ(const char *path, const lsdem_label_image *img,
                         const lsdem_voxel_grain *gr, int n, const labels_options *o)
{
  double *pos = malloc((3 * (size_t)n + 1) * sizeof(double));
  double *quat = malloc((4 * (size_t)n + 1) * sizeof(double));
  int *shape = malloc(((size_t)n + 1) * sizeof(int));
  int rc = !pos || !quat || !shape;
  if (rc) fprintf(stderr, "lsdem-shape: from-labels: out of memory\n");
  for (int i = 0; !rc && i < n; i++) {
    memcpy(pos + 3 * i, gr[i].position, 3 * sizeof(double));
    memcpy(quat + 4 * i, gr[i].quat, 4 * sizeof(double));
    shape[i] = i + 1;
  }
  const double s = o->vox.voxel_size;
  const double lo[3] = {-0.5 * s, -0.5 * s, -0.5 * s};
  const double hi[3] = {(img->n[0] - 0.5) * s, (img->n[1] - 0.5) * s, (img->n[2] - 0.5) * s};
  if (!rc)
    rc = shape_write_data(path, "LSDEM in-situ sample from a labelled image (lsdem-shape "
                          "from-labels)", n, shape, o->density, pos, quat, lo, hi);
  free(pos), free(quat), free(shape);
  return rc;
}

int cmd_from_labels(int argc, char **argv)
{
  if (argc < 2) {
    fprintf(stderr, "usage: lsdem-shape from-labels IMAGE OUT.lslib [--raw NX NY NZ TYPE "
            "[--big-endian]] [--voxel SIZE]\n                   [--min-voxels N] [--nodes N | "
            "--node-spacing S] [--smooth K] [--margin M] [--seed S]\n                   [--data "
            "OUT.data --density RHO]\n");
    return 2;
  }
  labels_options o;
  if (!parse_labels_options(argc - 2, argv + 2, &o)) return 2;
  lsdem_label_image img;
  if (read_image(argv[0], &o, &img)) return 1;
  lsdem_voxel_grain *gr = NULL;
  int n = 0, dropped = 0;
  lsdem_error err;
  if (lsdem_voxel_grains(&img, &o.vox, &gr, &n, &dropped, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: from-labels: %s: %s\n", argv[0], err.msg);
    lsdem_label_image_free(&img);
    return 1;
  }
  printf("%s: %d x %d x %d voxels, %d grains, %d label%s below %ld voxels dropped\n", argv[0],
         img.n[0], img.n[1], img.n[2], n, dropped, dropped == 1 ? "" : "s", o.vox.min_voxels);
  int rc = 0;
  if (n == 0) {
    fprintf(stderr, "lsdem-shape: from-labels: %s: no label with at least %ld voxels\n", argv[0],
            o.vox.min_voxels);
    rc = 1;
  }
  lsdem_built_shape *b = calloc((size_t)n + 1, sizeof *b);
  char(*names)[32] = calloc((size_t)n + 1, sizeof *names);
  lsdem_shape *shapes = calloc((size_t)n + 1, sizeof *shapes);
  const char **np = calloc((size_t)n + 1, sizeof *np);
  if (!rc && (!b || !names || !shapes || !np)) {
    fprintf(stderr, "lsdem-shape: from-labels: out of memory\n");
    rc = 1;
  }
  if (!rc) rc = build_shapes(gr, n, &o, b, names);
  for (int i = 0; !rc && i < n; i++) shapes[i] = b[i].shape, np[i] = names[i];
  if (!rc && lsdem_library_write(argv[1], shapes, np, n, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: from-labels: %s\n", err.msg);
    rc = 1;
  }
  if (!rc) printf("%s: %d grid shapes (label_<L>), voxel size %g\n", argv[1], n, o.vox.voxel_size);
  if (!rc && o.data) {
    rc = write_in_situ(o.data, &img, gr, n, &o);
    if (!rc) printf("%s: in-situ sample, %d grains at their scan poses\n", o.data, n);
  }
  for (int i = 0; b && i < n; i++) lsdem_built_shape_free(&b[i]);
  free(b), free(names), free(shapes), free(np);
  lsdem_voxel_grains_free(gr, n);
  lsdem_label_image_free(&img);
  return rc;
}
