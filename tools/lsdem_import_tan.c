/* lsdem-import-tan -- turn a scene in the Kawamoto/Tan input layout into LSDEM inputs.
 *
 *   lsdem-import-tan SCENE_DIR OUT_PREFIX [--density RHO] [--box X Y Z]
 *
 * SCENE_DIR holds Morphologies/morph_<i>.dat (i = 1..N), InitState/positions_*.dat and
 * InitState/rotations_*.dat (the report code's layout). Writes OUT_PREFIX.lslib (one shape
 * per distinct morphology file: symlinks to one file share one shape) and OUT_PREFIX.data
 * (a LAMMPS data file for atom_style lsdem, lengths in voxels, Tan's quaternions converted to
 * LSDEM's scalar-first convention). The box is taken from SCENE_DIR/geometry.txt (box_x ..)
 * when present, else from --box, else from the grains' extent. */
#include "lsdem.h"
#include "shape_common.h"

#include <dirent.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  char real[PATH_MAX]; /* resolved morphology path: equal paths share a shape */
  int grain;           /* 0-based grain index */
} morph_ref;

static int compare_refs(const void *a, const void *b)
{
  const morph_ref *x = a, *y = b;
  int c = strcmp(x->real, y->real);
  return c ? c : (x->grain - y->grain);
}

static int die(const char *what, const lsdem_error *err)
{
  fprintf(stderr, "lsdem-import-tan: %s%s%s\n", what, err ? ": " : "", err ? err->msg : "");
  return 1;
}

/* A morphology that does not make shape `shape`, named by the first grain that uses it. */
static int bad_grain(const char *scene, int grain, int shape, const lsdem_error *err)
{
  fprintf(stderr, "lsdem-import-tan: grain %d (%s/Morphologies/morph_%d.dat, shape %d): %s\n",
          grain + 1, scene, grain + 1, shape, err->msg);
  return 1;
}

/* The single file in dir whose name starts with prefix (positions_, rotations_). */
static int find_init_file(const char *scene, const char *prefix, char *out, size_t n)
{
  char dir[PATH_MAX];
  snprintf(dir, sizeof dir, "%s/InitState", scene);
  DIR *d = opendir(dir);
  if (!d) return 0;
  int found = 0;
  struct dirent *e;
  while ((e = readdir(d))) {
    if (strncmp(e->d_name, prefix, strlen(prefix)) == 0 &&
        snprintf(out, n, "%.*s/%s", PATH_MAX / 2, dir, e->d_name) < (int)n)
      found++;
  }
  closedir(d);
  return found == 1;
}

/* box_x/box_y/box_z from geometry.txt (written by the reference scene generator). */
static int read_geometry_box(const char *scene, double box[3])
{
  char path[PATH_MAX], key[64];
  snprintf(path, sizeof path, "%s/geometry.txt", scene);
  FILE *f = fopen(path, "r");
  if (!f) return 0;
  int got = 0;
  double v;
  char line[512];
  while (fgets(line, sizeof line, f)) {
    if (sscanf(line, "%63s %lf", key, &v) != 2) continue;
    for (int k = 0; k < 3; k++) {
      char want[8];
      snprintf(want, sizeof want, "box_%c", 'x' + k);
      if (strcmp(key, want) == 0) box[k] = v, got |= 1 << k;
    }
  }
  fclose(f);
  return got == 7;
}

/* One shape per distinct morphology file; shape_of[grain] = its shape index. */
static int import_shapes(const char *scene, int ngrains, const char *lib_path, int *shape_of)
{
  morph_ref *refs = calloc((size_t)ngrains, sizeof *refs);
  if (!refs) return die("out of memory", NULL);
  for (int i = 0; i < ngrains; i++) {
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/Morphologies/morph_%d.dat", scene, i + 1);
    if (!realpath(path, refs[i].real)) {
      fprintf(stderr, "lsdem-import-tan: grain %d: cannot open %s\n", i + 1, path);
      free(refs);
      return 1;
    }
    refs[i].grain = i;
  }
  qsort(refs, (size_t)ngrains, sizeof *refs, compare_refs);

  int nshapes = 0;
  for (int i = 0; i < ngrains; i++)
    if (i == 0 || strcmp(refs[i].real, refs[i - 1].real) != 0) nshapes++;
  lsdem_morph *morphs = calloc((size_t)nshapes, sizeof *morphs);
  lsdem_shape *shapes = calloc((size_t)nshapes, sizeof *shapes);
  char **names = calloc((size_t)nshapes, sizeof *names);
  double **bufs = calloc((size_t)nshapes, sizeof *bufs);
  int **ibufs = calloc((size_t)nshapes, sizeof *ibufs);
  int rc = 0;
  lsdem_error err;
  if (!morphs || !shapes || !names || !bufs || !ibufs) rc = die("out of memory", NULL);

  for (int i = 0, s = -1; !rc && i < ngrains; i++) {
    if (i == 0 || strcmp(refs[i].real, refs[i - 1].real) != 0) {
      s++;
      if (lsdem_morph_read(refs[i].real, &morphs[s], &err) != LSDEM_OK) {
        rc = bad_grain(scene, refs[i].grain, s, &err);
        break;
      }
      const int nn = morphs[s].nnodes;
      /* nodes (3n) + areas (n) + cluster spheres (4n) in one block, starts in another */
      bufs[s] = malloc(sizeof(double) * 8 * (size_t)(nn > 0 ? nn : 1));
      ibufs[s] = malloc(sizeof(int) * (size_t)(nn + 1));
      if (!bufs[s] || !ibufs[s]) {
        rc = die("out of memory", NULL);
        break;
      }
      if (lsdem_morph_to_shape(&morphs[s], bufs[s], bufs[s] + 3 * nn, ibufs[s], bufs[s] + 4 * nn,
                               &shapes[s], &err) != LSDEM_OK) {
        rc = bad_grain(scene, refs[i].grain, s, &err);
        break;
      }
      const char *base = strrchr(refs[i].real, '/');
      names[s] = strdup(base ? base + 1 : refs[i].real);
    }
    shape_of[refs[i].grain] = s;
  }
  if (!rc && lsdem_library_write(lib_path, shapes, (const char *const *)names, nshapes, &err) != LSDEM_OK)
    rc = die("writing the shape library", &err);
  if (!rc) printf("lsdem-import-tan: %d grains, %d distinct shapes -> %s\n", ngrains, nshapes, lib_path);

  for (int s = 0; s < nshapes; s++) {
    lsdem_morph_free(&morphs[s]);
    free(names ? names[s] : NULL);
    free(bufs ? bufs[s] : NULL);
    free(ibufs ? ibufs[s] : NULL);
  }
  free(morphs), free(shapes), free(names), free(bufs), free(ibufs), free(refs);
  return rc;
}

/* The data file: shape IDs 1-based, Tan's quaternions converted to scalar-first. */
static int write_data(const char *path, int n, const double *pos, const double *rot,
                      const int *shape_of, double density, const double lo[3], const double hi[3])
{
  double *quat = malloc(sizeof(double) * 4 * (size_t)(n > 0 ? n : 1));
  int *shape = malloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
  if (!quat || !shape) {
    free(quat), free(shape);
    return die("out of memory", NULL);
  }
  for (int i = 0; i < n; i++) {
    lsdem_quat_from_tan(rot + 4 * i, quat + 4 * i);
    lsdem_quat_normalize(quat + 4 * i);
    shape[i] = shape_of[i] + 1;
  }
  const int rc = shape_write_data(path, "LSDEM data file from a Kawamoto/Tan scene (lengths in voxels)",
                                  n, shape, density, pos, quat, lo, hi);
  free(quat), free(shape);
  return rc;
}

int main(int argc, char **argv)
{
  if (argc < 3) {
    fprintf(stderr, "usage: lsdem-import-tan SCENE_DIR OUT_PREFIX [--density RHO] [--box X Y Z]\n");
    return 2;
  }
  const char *scene = argv[1], *prefix = argv[2];
  double density = 1.0, box[3] = {0, 0, 0};
  int have_box = read_geometry_box(scene, box);
  for (int a = 3; a < argc; a++) {
    if (!strcmp(argv[a], "--density") && a + 1 < argc) density = atof(argv[++a]);
    else if (!strcmp(argv[a], "--box") && a + 3 < argc) {
      for (int k = 0; k < 3; k++) box[k] = atof(argv[++a]);
      have_box = 1;
    } else {
      fprintf(stderr, "lsdem-import-tan: unknown option '%s'\n", argv[a]);
      return 2;
    }
  }

  char ppath[PATH_MAX], rpath[PATH_MAX];
  if (!find_init_file(scene, "positions_", ppath, sizeof ppath) ||
      !find_init_file(scene, "rotations_", rpath, sizeof rpath))
    return die("SCENE_DIR/InitState must hold exactly one positions_*.dat and one rotations_*.dat", NULL);
  lsdem_error err;
  double *pos = NULL, *rot = NULL;
  int np = 0, nr = 0;
  if (lsdem_read_positions(ppath, &pos, &np, &err) != LSDEM_OK) return die(ppath, &err);
  if (lsdem_read_rotations(rpath, &rot, &nr, &err) != LSDEM_OK) return die(rpath, &err);
  if (np != nr) {
    fprintf(stderr, "lsdem-import-tan: %d positions but %d rotations\n", np, nr);
    return 1;
  }

  char lib_path[PATH_MAX], data_path[PATH_MAX];
  snprintf(lib_path, sizeof lib_path, "%s.lslib", prefix);
  snprintf(data_path, sizeof data_path, "%s.data", prefix);
  int *shape_of = calloc((size_t)np, sizeof *shape_of);
  int rc = shape_of ? import_shapes(scene, np, lib_path, shape_of) : die("out of memory", NULL);

  double lo[3] = {0, 0, 0}, hi[3];
  if (!rc) {
    if (have_box) {
      for (int k = 0; k < 3; k++) hi[k] = box[k];
    } else { /* the grains' centre extent padded by the largest bounding radius */
      lsdem_library *lib = NULL;
      if (lsdem_library_open(lib_path, &lib, &err) != LSDEM_OK) return die(lib_path, &err);
      double rmax = 0;
      for (int s = 0; s < lsdem_library_count(lib); s++)
        if (lsdem_library_shape(lib, s)->radius > rmax) rmax = lsdem_library_shape(lib, s)->radius;
      lsdem_library_close(lib);
      for (int k = 0; k < 3; k++) lo[k] = hi[k] = pos[k];
      for (int i = 0; i < np; i++)
        for (int k = 0; k < 3; k++) {
          if (pos[3 * i + k] < lo[k]) lo[k] = pos[3 * i + k];
          if (pos[3 * i + k] > hi[k]) hi[k] = pos[3 * i + k];
        }
      for (int k = 0; k < 3; k++) lo[k] -= rmax, hi[k] += rmax;
    }
    rc = write_data(data_path, np, pos, rot, shape_of, density, lo, hi);
    if (!rc) printf("lsdem-import-tan: data file -> %s\n", data_path);
  }
  free(shape_of), free(pos), free(rot);
  return rc;
}
