/* shape_wall.c -- `lsdem-shape wall` and `lsdem-shape terrain`: the narrow band of a wall
 * (lsdem_band_from_mesh) from a closed triangle mesh or a terrain height map, or a terrain
 * kept as its heights (`--heights`, lsdem_band_from_heights), written as a band file
 * (lsdem_band_write) and checked by reading it back (lsdem_band_open). */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "lsdem.h"
#include "lsdem_shape_cmds.h"
#include "shape_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

typedef struct {
  double spacing, width, scale, cell, zscale; /* width 0: 2 spacing; cell 0: from the file */
  int heights; /* terrain: keep the heights (spacing = the raster's cell), not bricks */
  int closed;  /* wall: refuse a mesh with holes (else signed by its winding number) */
  int open;    /* wall: the mesh has holes */
} wall_options;

static int parse_wall_options(const char *cmd, int argc, char **argv, int terrain,
                              wall_options *o)
{
  *o = (wall_options){0.0, 0.0, 1.0, 0.0, 1.0, 0, 0, 0};
  for (int i = 0; i < argc; i++) {
    if (terrain && !strcmp(argv[i], "--heights")) {
      o->heights = 1;
      continue;
    }
    if (!terrain && !strcmp(argv[i], "--closed")) {
      o->closed = 1;
      continue;
    }
    const int has = i + 1 < argc;
    double *v = !strcmp(argv[i], "--spacing")              ? &o->spacing
                : !strcmp(argv[i], "--width")              ? &o->width
                : !terrain && !strcmp(argv[i], "--scale")  ? &o->scale
                : terrain && !strcmp(argv[i], "--cell")    ? &o->cell
                : terrain && !strcmp(argv[i], "--zscale")  ? &o->zscale
                                                           : NULL;
    const int ok = v && has && parse_number(argv[++i], 1, v);
    if (!ok) {
      fprintf(stderr, "lsdem-shape: %s: bad option or value near '%s' (options: --spacing H > 0, "
              "--width W > 0%s)\n", cmd, argv[i],
              terrain ? ", --cell C > 0, --zscale Z > 0, --heights" : ", --scale S > 0, --closed");
      return 0;
    }
  }
  if (o->heights && o->spacing > 0.0) {
    fprintf(stderr, "lsdem-shape: %s: --heights keeps the raster's own spacing (its cell): "
            "drop --spacing\n", cmd);
    return 0;
  }
  if (o->heights) return 1; /* width: 2 cells once the raster is read */
  if (!(o->spacing > 0.0)) {
    fprintf(stderr, "lsdem-shape: %s: --spacing H is required (the band's grid spacing)\n", cmd);
    return 0;
  }
  if (o->width == 0.0) o->width = 2.0 * o->spacing;
  return 1;
}

static double seconds_since(const struct timespec *t0)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)(t.tv_sec - t0->tv_sec) + 1e-9 * (double)(t.tv_nsec - t0->tv_nsec);
}

static int cmp_triple(const void *a, const void *b)
{
  const int *x = a, *y = b;
  for (int k = 0; k < 3; k++)
    if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
  return 0;
}

/* Triangles with the same three vertices as an earlier one (any order or orientation). */
static long count_duplicates(const lsdem_mesh *m)
{
  int *t = malloc(3 * (size_t)m->ntris * sizeof(int) + 1);
  if (!t) return -1;
  for (int i = 0; i < m->ntris; i++) {
    int *v = t + 3 * i;
    memcpy(v, m->tris + 3 * i, 3 * sizeof(int));
    for (int a = 0; a < 2; a++) /* sort the three */
      for (int b = 0; b < 2 - a; b++)
        if (v[b] > v[b + 1]) { const int x = v[b]; v[b] = v[b + 1], v[b + 1] = x; }
  }
  qsort(t, (size_t)m->ntris, 3 * sizeof(int), cmp_triple);
  long dup = 0;
  for (int i = 1; i < m->ntris; i++) dup += cmp_triple(t + 3 * (i - 1), t + 3 * i) == 0;
  free(t);
  return dup;
}

/* The surface's own report line: triangles, degenerate and duplicate ones, open edges. */
static void report_surface(const char *name, const lsdem_mesh *m, const lsdem_mesh_topology *t,
                           const char *open_what)
{
  printf("%s: %d triangles, %d degenerate (zero area), %ld duplicate, %d open edges%s",
         name, m->ntris, t->degenerate_tris, count_duplicates(m), t->boundary_edges, open_what);
  if (t->nonmanifold_edges || t->misoriented_edges)
    printf(", %d non-manifold edges, %d edges with inconsistent orientation",
           t->nonmanifold_edges, t->misoriented_edges);
  printf("\n");
}

/* Largest |phi| of a band kept as heights at its columns' vertices (0 up to rounding:
 * its lookups are exact). */
static double heights_misfit(const lsdem_band *b)
{
  double worst = 0.0, g[3];
  for (int j = 0; j < b->n[1]; j++)
    for (int i = 0; i < b->n[0]; i++) {
      const double p[3] = {b->origin[0] + b->h * i, b->origin[1] + b->h * j,
                           b->heights[(size_t)i + (size_t)b->n[0] * j]};
      worst = fmax(worst, fabs(lsdem_band_eval(b, p, g)));
    }
  return worst;
}

/* Every ridge and slot narrower than 2 spacings, which trilinear interpolation cannot
 * hold (the band then rounds or closes them): named with their thinnest width and place. */
static int report_thin_features(const char *cmd, const lsdem_band *b)
{
  enum { SHOWN = 40 };
  lsdem_thin_feature *f = NULL;
  int n = 0;
  lsdem_error err;
  if (lsdem_band_thin_features(b, 2.0 * b->h, &f, &n, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: %s: %s\n", cmd, err.msg);
    return 1;
  }
  printf("ridges and slots narrower than 2 h (%g): %d\n", 2.0 * b->h, n);
  for (int k = 0; k < n && k < SHOWN; k++)
    printf("  %s %d: %d triangles, %.3g h (%.3g) across at (%.6g, %.6g, %.6g), triangle %d\n",
           f[k].ridge ? "ridge" : "slot", k + 1, f[k].ntris, f[k].thinnest / b->h,
           f[k].thinnest, f[k].at[0], f[k].at[1], f[k].at[2], (int)f[k].tri);
  if (n > SHOWN) printf("  ... and %d more (make the band finer to hold them)\n", n - SHOWN);
  else if (n > 0)
    printf("  (the band rounds ridges and closes slots this narrow: a finer --spacing, or "
           "exact yes in fix wall/lsdem)\n");
  free(f);
  return 0;
}

/* Samples of the dense grid the band stands for: a brick band's box, or for heights the
 * columns' extent times the relief plus width + h above and below. */
static double dense_samples(const lsdem_band *b)
{
  if (!b->heights) return (double)b->n[0] * b->n[1] * b->n[2];
  float lo = INFINITY, hi = -INFINITY;
  for (size_t k = 0; k < (size_t)b->n[0] * b->n[1]; k++)
    lo = fminf(lo, b->heights[k]), hi = fmaxf(hi, b->heights[k]);
  return (double)b->n[0] * b->n[1] * (floor(((double)hi - lo + 2.0 * (b->width + b->h)) / b->h) + 1.0);
}

/* Print the band's report, write it and read it back (the file as lmp will read it);
 * surface check against m, or at the columns for heights. Frees b. 0, or 1 after a
 * message (the output then does not exist). */
static int write_and_check(const char *cmd, lsdem_band *b, lsdem_band_source src,
                           double build_s, const lsdem_mesh *m, const char *out)
{
  const double dense = 4.0 * dense_samples(b);
  if (b->heights) {
    printf("heights: %d x %d columns at spacing %g, width %g (%.3g h), exact distances at "
           "lookup\n", b->n[0], b->n[1], b->h, b->width, b->width / b->h);
    printf("memory %.3g MB (heights and tile ranges) against %.3g MB for the dense grid (%.2f "
           "%%)\n", lsdem_band_bytes(b) / 1048576.0, dense / 1048576.0,
           100.0 * lsdem_band_bytes(b) / dense);
  } else {
    const double slots = (double)b->nb[0] * b->nb[1] * b->nb[2];
    printf("band: spacing %g, width %g (%.3g h); grid %d x %d x %d samples, %d x %d x %d bricks "
           "of %d cells\n", b->h, b->width, b->width / b->h, b->n[0], b->n[1], b->n[2],
           b->nb[0], b->nb[1], b->nb[2], LSDEM_BAND_BRICK);
    printf("stored bricks: %lld of %.0f (%.2f %%); memory %.3g MB (index and bricks) against "
           "%.3g MB for the dense grid (%.2f %%)\n", (long long)b->nbricks, slots,
           100.0 * (double)b->nbricks / slots, lsdem_band_bytes(b) / 1048576.0,
           dense / 1048576.0, 100.0 * lsdem_band_bytes(b) / dense);
  }
  printf("build time: %.2f s\n", build_s);
  lsdem_error err;
  int rc = 0;
  if (lsdem_band_write(out, b, src, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: %s: %s\n", cmd, err.msg);
    rc = 1;
  }
  lsdem_band_free(b);
  lsdem_band_file *f = NULL;
  if (!rc && lsdem_band_open(out, &f, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: %s: reading the band file back failed: %s\n", cmd, err.msg);
    remove(out);
    rc = 1;
  }
  if (!rc) {
    const lsdem_band *r = lsdem_band_file_band(f);
    if (m) {
      lsdem_band_distance dist;
      lsdem_band_misfit(r, m, &dist);
      printf("surface check: max |phi| at the %d vertices and %d triangle centroids %.3g h "
             "(%.3g)\n", m->nverts, m->ntris, dist.mesh_to_zero / r->h, dist.mesh_to_zero);
      printf("Hausdorff distance between the band's zero level set and the mesh: %.3g h "
             "(%.3g; from the zero level set at %lld grid-edge crossings: %.3g h)\n",
             dist.hausdorff / r->h, dist.hausdorff, (long long)dist.crossings,
             dist.zero_to_mesh / r->h);
      rc = report_thin_features(cmd, r);
    } else {
      const double misfit = heights_misfit(r);
      printf("surface check: max |phi| at the %d columns' vertices %.3g h (%.3g)\n",
             r->n[0] * r->n[1], misfit / r->h, misfit);
    }
    struct stat sb;
    printf("%s: band file of a %s, %lld bytes\n", out,
           src == LSDEM_BAND_MESH ? "closed mesh"
                                  : (src == LSDEM_BAND_TERRAIN ? "terrain" : "terrain's heights"),
           stat(out, &sb) == 0 ? (long long)sb.st_size : -1LL);
    lsdem_band_close(f);
  }
  return rc;
}

/* Build the band of m, then write_and_check. */
static int build_and_write(const char *cmd, const lsdem_mesh *m, lsdem_band_source src,
                           const wall_options *o, const char *out)
{
  lsdem_band b;
  lsdem_error err;
  struct timespec t0;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  const lsdem_status st = o->open ? lsdem_band_from_open_mesh(m, o->spacing, o->width, &b, &err)
                                  : lsdem_band_from_mesh(m, o->spacing, o->width, src, &b, &err);
  if (st != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: %s: %s\n", cmd, err.msg);
    return 1;
  }
  return write_and_check(cmd, &b, src, seconds_since(&t0), m, out);
}

static int wall_usage(void)
{
  fprintf(stderr, "usage: lsdem-shape wall MESH.stl|MESH.obj OUT.band --spacing H [--width W] "
          "[--scale S] [--closed]\n");
  return 2;
}

int cmd_wall(int argc, char **argv)
{
  if (argc < 2) return wall_usage();
  wall_options o;
  if (!parse_wall_options("wall", argc - 2, argv + 2, 0, &o)) return 2;
  const char *path = argv[0];
  lsdem_mesh m;
  lsdem_error err;
  if (lsdem_mesh_read(path, &m, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: wall: %s\n", err.msg);
    return 1;
  }
  for (int i = 0; i < 3 * m.nverts; i++) m.verts[i] *= o.scale;
  lsdem_mesh_topology topo;
  const lsdem_status closed = lsdem_mesh_check_closed(&m, &topo, &err);
  report_surface(path, &m, &topo, "");
  int rc = 0;
  o.open = closed != LSDEM_OK && !o.closed && topo.nonmanifold_edges == 0 &&
           topo.misoriented_edges == 0 && topo.degenerate_tris == 0;
  if (closed != LSDEM_OK && !o.open) {
    fprintf(stderr, "lsdem-shape: wall: %s: %s: a wall from a mesh needs a closed surface%s "
            "(for a terrain, an open surface, use lsdem-shape terrain)\n", path, err.msg,
            o.closed ? " (--closed)" : ", or one with holes but otherwise manifold and "
            "consistently oriented");
    rc = 1;
  }
  if (o.open)
    printf("%s: a mesh with %d open edges: signed near its holes by the generalised winding "
           "number (holes narrower than about 2 W are closed; --closed refuses it)\n", path,
           topo.boundary_edges);
  if (!rc && lsdem_mesh_check_self_intersection(&m, NULL, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: wall: %s: %s\n", path, err.msg);
    rc = 1;
  }
  if (!rc) {
    const double v = lsdem_mesh_volume(&m);
    if (v < 0.0)
      fprintf(stderr, "lsdem-shape: warning: %s: the faces point inwards: the wall's solid is "
              "the mesh's outside (a container, volume %g); reverse the faces for a solid "
              "body\n", path, -v);
    rc = build_and_write("wall", &m, LSDEM_BAND_MESH, &o, argv[1]);
  }
  lsdem_mesh_free(&m);
  return rc;
}

static int terrain_usage(void)
{
  fprintf(stderr, "usage: lsdem-shape terrain HEIGHTMAP.asc|.tif|.tiff|.png OUT.band --spacing H "
          "[--width W]\n                   [--cell C] [--zscale Z]\n"
          "       lsdem-shape terrain HEIGHTMAP OUT.band --heights [--width W] [--cell C] "
          "[--zscale Z]\n");
  return 2;
}

int cmd_terrain(int argc, char **argv)
{
  if (argc < 2) return terrain_usage();
  wall_options o;
  if (!parse_wall_options("terrain", argc - 2, argv + 2, 1, &o)) return 2;
  const char *path = argv[0];
  lsdem_heightmap hm;
  lsdem_mesh m;
  lsdem_error err;
  if (lsdem_heightmap_read(path, o.cell, o.zscale, &hm, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: terrain: %s\n", err.msg);
    return 1;
  }
  long nodata = 0;
  float zmin = INFINITY, zmax = -INFINITY;
  for (size_t i = 0; i < (size_t)hm.nx * hm.ny; i++) {
    if (isnan(hm.z[i])) nodata++;
    else zmin = fminf(zmin, hm.z[i]), zmax = fmaxf(zmax, hm.z[i]);
  }
  printf("%s: %d x %d heights, cell %g, first at (%g, %g), heights %g .. %g, %ld nodata\n",
         path, hm.nx, hm.ny, hm.cell, hm.x0, hm.y0, zmin, zmax, nodata);
  /* beyond its border the terrain continues flat at the edge's heights, out past the
   * band's box (width + spacing beyond the surface), so no grain finds a cliff there */
  if (o.heights) o.spacing = hm.cell;
  if (o.heights && o.width == 0.0) o.width = 2.0 * hm.cell;
  const int pad = (int)ceil((o.width + o.spacing) / hm.cell) + 1;
  lsdem_status st = lsdem_heightmap_pad(&hm, pad, &err);
  if (st == LSDEM_OK)
    printf("padded by %d cells of edge heights on every side: the terrain continues flat "
           "beyond its border\n", pad);
  if (st == LSDEM_OK && o.heights) {
    lsdem_band b;
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    st = lsdem_band_from_heights(&hm, o.width, &b, &err);
    lsdem_heightmap_free(&hm);
    if (st != LSDEM_OK) {
      fprintf(stderr, "lsdem-shape: terrain: %s: %s\n", path, err.msg);
      return 1;
    }
    return write_and_check("terrain", &b, LSDEM_BAND_HEIGHTS, seconds_since(&t0), NULL, argv[1]);
  }
  if (st == LSDEM_OK) st = lsdem_heightmap_mesh(&hm, &m, &err);
  lsdem_heightmap_free(&hm);
  if (st != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: terrain: %s: %s\n", path, err.msg);
    return 1;
  }
  lsdem_mesh_topology topo;
  lsdem_mesh_check_closed(&m, &topo, NULL); /* open: its border and holes, counted */
  report_surface("surface", &m, &topo, " (the border and the holes' edges)");
  const int rc = build_and_write("terrain", &m, LSDEM_BAND_TERRAIN, &o, argv[1]);
  lsdem_mesh_free(&m);
  return rc;
}
