/* shape_render.c -- lsdem-shape render and surface: look at grains without ParaView
 * (doc/lsdem_shape.rst).
 *
 *   lsdem-shape render LIB SAMPLE OUT.png [--size W H] [--view x|y|z|iso] [--dump FRAME]
 *                      [--colour id|shape]
 *   lsdem-shape surface LIB INDEX OUT.vtk|OUT.ply [--spacing H]
 *
 * SAMPLE is a LAMMPS data file of atom_style lsdem (its Atoms section: id type shape-ID
 * density x y z qw qx qy qz, shape-ID 1-based) or a LAMMPS dump file (text, `dump custom`)
 * whose ATOMS header names the columns `id`, `x y z` (or `xu yu zu`) and five columns
 * c_NAME[1] .. c_NAME[5] of `compute NAME all property/atom qw qx qy qz shape`. */
#include "lsdem.h"
#include "lsdem_shape_cmds.h"
#include "shape_common.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { LINE_MAX_CHARS = 4096, MAX_TOKENS = 64 };

typedef struct {
  lsdem_render_grain *g;
  int n, cap;
} grain_list;

static int render_usage(void)
{
  fprintf(stderr, "usage: lsdem-shape render LIB SAMPLE OUT.png [--size W H] "
          "[--view x|y|z|iso] [--dump FRAME] [--colour id|shape]\n"
          "       lsdem-shape surface LIB INDEX OUT.vtk|OUT.ply [--spacing H]\n");
  return 2;
}

/* Split a line at blanks (in place); returns the token count (at most MAX_TOKENS). */
static int split(char *line, char *tok[MAX_TOKENS])
{
  int n = 0;
  for (char *t = strtok(line, " \t\r\n"); t && n < MAX_TOKENS; t = strtok(NULL, " \t\r\n"))
    tok[n++] = t;
  return n;
}

/* A line into buf; 0 at the end of the file, -1 for a line longer than the buffer. */
static int read_line(FILE *f, char *buf)
{
  if (!fgets(buf, LINE_MAX_CHARS, f)) return 0;
  return strchr(buf, '\n') || feof(f) ? 1 : -1;
}

static int add_grain(grain_list *L, const lsdem_render_grain *g)
{
  if (L->n == L->cap) {
    const int cap = L->cap ? 2 * L->cap : 256;
    lsdem_render_grain *p = realloc(L->g, (size_t)cap * sizeof *p);
    if (!p) return 0;
    L->g = p, L->cap = cap;
  }
  L->g[L->n++] = *g;
  return 1;
}

/* One grain from its text fields: id, 1-based shape, position, quaternion (normalised). */
static int make_grain(const char *id, const char *shape, char *const x[3], char *const q[4],
                      int nshapes, lsdem_render_grain *g)
{
  double s;
  long i;
  if (!parse_count(id, 1, LONG_MAX, &i) || !parse_number(shape, 0, &s) || s < 1 ||
      s > nshapes || s != floor(s))
    return 0;
  g->id = i, g->shape = (int)s - 1;
  for (int k = 0; k < 3; k++)
    if (!parse_number(x[k], 0, &g->x[k])) return 0;
  for (int k = 0; k < 4; k++)
    if (!parse_number(q[k], 0, &g->q[k])) return 0;
  const double n2 = g->q[0] * g->q[0] + g->q[1] * g->q[1] + g->q[2] * g->q[2] + g->q[3] * g->q[3];
  if (!(n2 > 0.0) || !isfinite(n2)) return 0; /* normalised below, as read_data does */
  lsdem_quat_normalize(g->q);
  return 1;
}

/* The Atoms section of a data file: id type shape density x y z qw qx qy qz [images]. */
static int read_data_file(FILE *f, const char *path, int nshapes, grain_list *L)
{
  char line[LINE_MAX_CHARS], *tok[MAX_TOKENS];
  int lineno = 0, in_atoms = 0, r;
  while ((r = read_line(f, line)) != 0) {
    lineno++;
    if (r < 0) break;
    char *hash = strchr(line, '#');
    if (hash) *hash = '\0';
    const int n = split(line, tok);
    if (!in_atoms) {
      in_atoms = n >= 1 && !strcmp(tok[0], "Atoms");
      continue;
    }
    if (n == 0) {
      if (L->n > 0) break; /* the blank line after the section */
      continue;
    }
    if (n != 11 && n != 14) {
      fprintf(stderr, "lsdem-shape: render: %s:%d: an Atoms line of atom_style lsdem has 11 "
              "(or 14 with image flags) fields: id type shape density x y z qw qx qy qz, "
              "got %d\n", path, lineno, n);
      return 0;
    }
    lsdem_render_grain g;
    if (!make_grain(tok[0], tok[2], tok + 4, tok + 7, nshapes, &g) || !add_grain(L, &g)) {
      fprintf(stderr, "lsdem-shape: render: %s:%d: bad grain (id, shape-ID in 1..%d, "
              "numbers, a non-zero quaternion expected)\n", path, lineno, nshapes);
      return 0;
    }
  }
  if (r < 0 || L->n == 0) {
    fprintf(stderr, "lsdem-shape: render: %s: %s\n", path,
            r < 0 ? "line too long" : "no Atoms section with grains");
    return 0;
  }
  return 1;
}

/* Column positions in an ITEM: ATOMS header (after "ITEM:" "ATOMS"): id, x y z, and the
 * five c_NAME[1..5] columns qw qx qy qz shape. */
static int dump_columns(char **tok, int n, int col[9])
{
  for (int k = 0; k < 9; k++) col[k] = -1;
  static const char *const pos[2][3] = {{"x", "y", "z"}, {"xu", "yu", "zu"}};
  for (int i = 0; i < n; i++) {
    if (!strcmp(tok[i], "id")) col[0] = i;
    for (int a = 0; a < 2; a++)
      for (int k = 0; k < 3; k++)
        if (!strcmp(tok[i], pos[a][k]) && col[1 + k] < 0) col[1 + k] = i;
    const size_t len = strlen(tok[i]);
    if (col[4] < 0 && !strncmp(tok[i], "c_", 2) && len > 5 && !strcmp(tok[i] + len - 3, "[1]") &&
        i + 4 < n) {
      int ok = 1;
      for (int k = 2; k <= 5; k++) { /* c_NAME[k] follows */
        char want[256];
        snprintf(want, sizeof want, "%.*s[%d]", (int)(len - 3), tok[i], k);
        ok = ok && !strcmp(tok[i + k - 1], want);
      }
      if (ok) col[4] = i;
    }
  }
  for (int k = 0; k < 5; k++)
    if (col[k] < 0) return 0;
  return 1;
}

/* Frame `frame` (0-based; negative counts from the end) of a text dump file. */
static int read_dump_file(FILE *f, const char *path, int nshapes, long frame, grain_list *L)
{
  char line[LINE_MAX_CHARS], *tok[MAX_TOKENS];
  long nframes = 0;
  int r;
  while ((r = read_line(f, line)) > 0) nframes += !strncmp(line, "ITEM: TIMESTEP", 14);
  const long want = frame < 0 ? nframes + frame : frame;
  if (want < 0 || want >= nframes) {
    fprintf(stderr, "lsdem-shape: render: %s: frame %ld not in the file's %ld frames\n", path,
            frame, nframes);
    return 0;
  }
  rewind(f);
  long seen = -1, natoms = -1, lineno = 0;
  int col[9], have_cols = 0;
  while ((r = read_line(f, line)) > 0) {
    lineno++;
    if (!strncmp(line, "ITEM: TIMESTEP", 14) && ++seen > want) break;
    if (seen != want) continue;
    if (!strncmp(line, "ITEM: NUMBER OF ATOMS", 21)) {
      if (read_line(f, line) <= 0 || sscanf(line, "%ld", &natoms) != 1 || natoms < 0) break;
      lineno++;
    } else if (!strncmp(line, "ITEM: ATOMS", 11)) {
      const int n = split(line, tok);
      if (!(have_cols = dump_columns(tok + 2, n - 2, col))) {
        fprintf(stderr, "lsdem-shape: render: %s:%ld: the ATOMS columns need id, x y z (or xu "
                "yu zu) and c_NAME[1..5] of compute property/atom qw qx qy qz shape\n", path,
                lineno);
        return 0;
      }
      for (long a = 0; a < natoms; a++) {
        lineno++;
        const int nt = read_line(f, line) > 0 ? split(line, tok) : 0;
        int maxcol = col[4] + 4; /* the last column read */
        for (int k = 0; k < 4; k++) maxcol = col[k] > maxcol ? col[k] : maxcol;
        lsdem_render_grain g;
        char *x[3] = {NULL, NULL, NULL}, *q[4] = {NULL, NULL, NULL, NULL};
        if (nt > maxcol) {
          for (int k = 0; k < 3; k++) x[k] = tok[col[1 + k]];
          for (int k = 0; k < 4; k++) q[k] = tok[col[4] + k];
        }
        if (nt <= maxcol || !make_grain(tok[col[0]], tok[col[4] + 4], x, q, nshapes, &g) ||
            !add_grain(L, &g)) {
          fprintf(stderr, "lsdem-shape: render: %s:%ld: bad or missing atom line (shape in "
                  "1..%d, a non-zero quaternion expected)\n", path, lineno, nshapes);
          return 0;
        }
      }
      break;
    }
  }
  if (!have_cols || r < 0) {
    fprintf(stderr, "lsdem-shape: render: %s: frame %ld has no complete ITEM: ATOMS section\n",
            path, want);
    return 0;
  }
  return 1;
}

static int read_sample(const char *path, int nshapes, long frame, grain_list *L)
{
  FILE *f = fopen(path, "r");
  if (!f) {
    fprintf(stderr, "lsdem-shape: render: cannot open %s\n", path);
    return 0;
  }
  char first[LINE_MAX_CHARS] = "";
  const int is_dump = read_line(f, first) > 0 && !strncmp(first, "ITEM:", 5);
  rewind(f);
  const int ok = is_dump ? read_dump_file(f, path, nshapes, frame, L)
                         : read_data_file(f, path, nshapes, L);
  fclose(f);
  return ok;
}

/* The named views: camera direction and image up (see doc/lsdem_shape.rst). */
static int set_view(const char *name, lsdem_render_view *v)
{
  static const struct {
    const char *name;
    double view[3], up[3];
  } views[] = {{"x", {-1, 0, 0}, {0, 0, 1}},
               {"y", {0, 1, 0}, {0, 0, 1}},
               {"z", {0, 0, -1}, {0, 1, 0}},
               {"iso", {-1, 1, -0.8}, {0, 0, 1}}};
  for (size_t i = 0; i < sizeof views / sizeof views[0]; i++)
    if (!strcmp(name, views[i].name)) {
      memcpy(v->view, views[i].view, sizeof v->view);
      memcpy(v->up, views[i].up, sizeof v->up);
      return 1;
    }
  return 0;
}

static int parse_render_options(int argc, char **argv, lsdem_render_view *v, long *frame)
{
  long w = 800, h = 600;
  for (int i = 0; i < argc; i++) {
    int ok = 1;
    if (!strcmp(argv[i], "--size"))
      ok = i + 2 < argc && parse_count(argv[i + 1], 1, 16384, &w) &&
           parse_count(argv[i + 2], 1, 16384, &h), i += 2;
    else if (!strcmp(argv[i], "--view")) ok = i + 1 < argc && set_view(argv[++i], v);
    else if (!strcmp(argv[i], "--dump"))
      ok = i + 1 < argc && parse_count(argv[++i], -1000000000L, 1000000000L, frame);
    else if (!strcmp(argv[i], "--colour") && i + 1 < argc) {
      v->colour_by_shape = !strcmp(argv[++i], "shape");
      ok = v->colour_by_shape || !strcmp(argv[i], "id");
    } else ok = 0;
    if (!ok) {
      fprintf(stderr, "lsdem-shape: render: bad option or value near '%s'\n",
              argv[i < argc ? i : argc - 1]);
      return 0;
    }
  }
  v->width = (int)w, v->height = (int)h;
  return 1;
}

int cmd_render(int argc, char **argv)
{
  if (argc < 3) return render_usage();
  lsdem_render_view v;
  memset(&v, 0, sizeof v);
  set_view("iso", &v);
  long frame = -1;
  if (!parse_render_options(argc - 3, argv + 3, &v, &frame)) return 2;
  lsdem_library *lib = NULL;
  lsdem_error err;
  if (lsdem_library_open(argv[0], &lib, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: render: %s\n", err.msg);
    return 1;
  }
  const int ns = lsdem_library_count(lib);
  const lsdem_shape **shapes = malloc(((size_t)ns + 1) * sizeof *shapes);
  unsigned char *rgb = malloc(3 * (size_t)v.width * v.height);
  grain_list L = {NULL, 0, 0};
  int rc = shapes && rgb ? 0 : 1;
  for (int i = 0; !rc && i < ns; i++) shapes[i] = lsdem_library_shape(lib, i);
  if (!rc && !read_sample(argv[1], ns, frame, &L)) rc = 1;
  if (!rc && (lsdem_render(shapes, ns, L.g, L.n, &v, rgb, &err) != LSDEM_OK ||
              lsdem_png_write(argv[2], v.width, v.height, rgb, &err) != LSDEM_OK)) {
    fprintf(stderr, "lsdem-shape: render: %s\n", err.msg);
    rc = 1;
  }
  if (!rc) printf("%s: %d grains, %dx%d pixels\n", argv[2], L.n, v.width, v.height);
  free(L.g);
  free(rgb);
  free(shapes);
  lsdem_library_close(lib);
  return rc;
}

/* ----------------------------------------------------------------- surface ---- */

static int ends_with(const char *s, const char *suffix)
{
  const size_t n = strlen(s), m = strlen(suffix);
  return n >= m && !strcmp(s + n - m, suffix);
}

int cmd_surface(int argc, char **argv)
{
  if (argc != 3 && argc != 5) return render_usage();
  double h = 0.0;
  if (argc == 5 && (strcmp(argv[3], "--spacing") || !parse_number(argv[4], 1, &h))) {
    fprintf(stderr, "lsdem-shape: surface: bad option or value near '%s'\n", argv[3]);
    return 2;
  }
  const int ply = ends_with(argv[2], ".ply");
  if (!ply && !ends_with(argv[2], ".vtk")) {
    fprintf(stderr, "lsdem-shape: surface: output '%s' must end in .vtk or .ply\n", argv[2]);
    return 2;
  }
  lsdem_library *lib = NULL;
  lsdem_error err;
  if (lsdem_library_open(argv[0], &lib, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: surface: %s\n", err.msg);
    return 1;
  }
  long index;
  int rc = 0;
  if (!parse_count(argv[1], 0, lsdem_library_count(lib) - 1L, &index)) {
    fprintf(stderr, "lsdem-shape: surface: index '%s' is not in 0..%d\n", argv[1],
            lsdem_library_count(lib) - 1);
    rc = 1;
  }
  lsdem_mesh m = {0, 0, NULL, NULL};
  if (!rc && (lsdem_library_verify(lib, (int)index, &err) != LSDEM_OK ||
              lsdem_mesh_extract(&lsdem_library_shape(lib, (int)index)->sdf, h, &m, &err) !=
                  LSDEM_OK ||
              (ply ? lsdem_mesh_write_ply(argv[2], &m, &err)
                   : lsdem_mesh_write_vtk(argv[2], &m, &err)) != LSDEM_OK)) {
    fprintf(stderr, "lsdem-shape: surface: %s\n", err.msg);
    rc = 1;
  }
  if (!rc)
    printf("%s: %d vertices, %d triangles, area %.6g, enclosed volume %.6g (shape %.6g)\n",
           argv[2], m.nverts, m.ntris, lsdem_mesh_area(&m), lsdem_mesh_volume(&m),
           lsdem_library_shape(lib, (int)index)->volume);
  lsdem_mesh_free(&m);
  lsdem_library_close(lib);
  return rc;
}
