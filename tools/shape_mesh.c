/* shape_mesh.c -- `lsdem-shape from-mesh`: a closed triangle mesh (STL or OBJ) to one grid
 * shape. Open meshes are refused unless --allow-open; self-intersecting meshes always. */
#include "lsdem.h"
#include "lsdem_shape_cmds.h"
#include "shape_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

typedef struct {
  double spacing, scale, node_spacing; /* spacing 0: R_eq / 12 */
  long nodes, margin, seed;
  int allow_open;
  const char *name;
} mesh_options;

static int parse_mesh_options(int argc, char **argv, mesh_options *o)
{
  *o = (mesh_options){0.0, 1.0, 0.0, 0, 3, 1, 0, NULL}; /* nodes 0: spacing d/10 (auto) */
  for (int i = 0; i < argc; i++) {
    const int has = i + 1 < argc;
    int ok = 1;
    if (!strcmp(argv[i], "--allow-open")) o->allow_open = 1;
    else if (!strcmp(argv[i], "--spacing")) ok = has && parse_number(argv[++i], 1, &o->spacing);
    else if (!strcmp(argv[i], "--scale")) ok = has && parse_number(argv[++i], 1, &o->scale);
    else if (!strcmp(argv[i], "--nodes")) ok = has && parse_count(argv[++i], 1, 1000000, &o->nodes);
    else if (!strcmp(argv[i], "--node-spacing")) {
      ok = has && parse_number(argv[++i], 1, &o->node_spacing);
      o->nodes = 0;
    } else if (!strcmp(argv[i], "--margin")) ok = has && parse_count(argv[++i], 1, 100, &o->margin);
    else if (!strcmp(argv[i], "--seed")) ok = has && parse_count(argv[++i], 0, 2147483647L, &o->seed);
    else if (!strcmp(argv[i], "--name") && has) o->name = argv[++i];
    else ok = 0;
    if (!ok) {
      fprintf(stderr, "lsdem-shape: from-mesh: bad option or value near '%s'\n", argv[i]);
      return 0;
    }
  }
  return 1;
}

/* Read, scale and check the mesh; faces turned inside out are reversed. On failure the
 * caller frees *m (empty when reading failed). */
static int load_mesh(const char *path, const mesh_options *o, lsdem_mesh *m)
{
  lsdem_error err;
  if (lsdem_mesh_read(path, m, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: from-mesh: %s\n", err.msg);
    return 1;
  }
  for (int i = 0; i < 3 * m->nverts; i++) m->verts[i] *= o->scale;
  if (lsdem_mesh_check_closed(m, NULL, &err) != LSDEM_OK) {
    if (!o->allow_open) {
      fprintf(stderr, "lsdem-shape: from-mesh: %s: %s (--allow-open samples it anyway)\n", path,
              err.msg);
      return 1;
    }
    fprintf(stderr, "lsdem-shape: warning: %s: %s; the sign of the distance is unreliable "
            "near these edges\n", path, err.msg);
  }
  if (lsdem_mesh_check_self_intersection(m, NULL, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: from-mesh: %s: %s\n", path, err.msg);
    return 1;
  }
  const double v = lsdem_mesh_volume(m);
  if (!(fabs(v) > 0.0) || !isfinite(v)) {
    fprintf(stderr, "lsdem-shape: from-mesh: %s: the mesh encloses no volume (%g)\n", path, v);
    return 1;
  }
  if (v < 0.0) {
    for (int t = 0; t < m->ntris; t++) {
      const int tmp = m->tris[3 * t + 1];
      m->tris[3 * t + 1] = m->tris[3 * t + 2], m->tris[3 * t + 2] = tmp;
    }
    fprintf(stderr, "lsdem-shape: warning: %s: the faces point inwards; reversed\n", path);
  }
  return 0;
}

/* The mesh's SDF in the mesh frame, then re-expressed in its principal frame. */
static lsdem_status principal_grid(const lsdem_mesh *m, double h, int margin, lsdem_grid *out,
                                   lsdem_massprops *mp, double q[4], lsdem_error *err)
{
  lsdem_grid g;
  lsdem_status st = lsdem_mesh_sdf_grid(m, h, margin + 1, &g, err);
  if (st != LSDEM_OK) return st;
  st = lsdem_massprops_grid(&g, 2, mp, err);
  if (st == LSDEM_OK) st = lsdem_grid_to_principal(&g, mp, margin, out, q, err);
  lsdem_grid_free(&g);
  return st;
}

static void name_from_path(const char *path, char *name, size_t size)
{
  const char *base = strrchr(path, '/');
  snprintf(name, size, "%s", base ? base + 1 : path);
  char *dot = strrchr(name, '.');
  if (dot && dot != name) *dot = '\0';
}

int cmd_from_mesh(int argc, char **argv)
{
  if (argc < 2) {
    fprintf(stderr, "usage: lsdem-shape from-mesh MESH OUT.lslib [--spacing H] [--nodes N | "
            "--node-spacing S]\n                   [--scale S] [--name NAME] [--margin M] "
            "[--seed S] [--allow-open]\n");
    return 2;
  }
  mesh_options o;
  if (!parse_mesh_options(argc - 2, argv + 2, &o)) return 2;
  lsdem_mesh m;
  if (load_mesh(argv[0], &o, &m)) {
    lsdem_mesh_free(&m);
    return 1;
  }
  const double volume = fabs(lsdem_mesh_volume(&m));
  const double h = o.spacing > 0.0 ? o.spacing : cbrt(3.0 * volume / (4.0 * PI)) / 12.0;
  lsdem_sdf sdf;
  memset(&sdf, 0, sizeof sdf);
  sdf.kind = LSDEM_SDF_GRID;
  lsdem_massprops mp;
  double q[4];
  lsdem_error err;
  lsdem_built_shape b;
  memset(&b, 0, sizeof b);
  char name[LSDEM_LIBRARY_NAME_MAX];
  name_from_path(argv[0], name, sizeof name);
  const char *shape_name = o.name ? o.name : name;
  int rc = 0, built = 0; /* built: the grid belongs to b */
  lsdem_status st = principal_grid(&m, h, (int)o.margin, &sdf.grid, &mp, q, &err);
  if (st == LSDEM_OK) {
    built = 1;
    st = lsdem_shape_build(&sdf, (int)o.nodes, o.node_spacing, (uint64_t)o.seed, &b, &err);
  }
  if (st != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: from-mesh: %s: %s\n", argv[0], err.msg);
    rc = 1;
  }
  if (!rc) {
    printf("%s: %d triangles, mesh volume %.6g, grid %dx%dx%d spacing %g: grid volume %.6g "
           "(%+.2f%%)\n", argv[0], m.ntris, volume, sdf.grid.n[0], sdf.grid.n[1], sdf.grid.n[2], h,
           b.shape.volume, 100.0 * (b.shape.volume / volume - 1.0));
    printf("pose in the mesh frame: centroid %.9g %.9g %.9g, principal -> mesh quaternion "
           "%.9g %.9g %.9g %.9g\n", mp.centroid[0], mp.centroid[1], mp.centroid[2], q[0], q[1],
           q[2], q[3]);
    shape_warn_quality(&b.shape, shape_name);
  }
  if (!rc && lsdem_library_write(argv[1], &b.shape, &shape_name, 1, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: from-mesh: %s\n", err.msg);
    rc = 1;
  }
  if (!rc)
    printf("%s: grid shape '%s', %d nodes in %d clusters, radius %.6g, volume %.6g\n", argv[1],
           shape_name, b.shape.nnodes, b.shape.nclusters, b.shape.radius, b.shape.volume);
  if (built) lsdem_built_shape_free(&b);
  else lsdem_grid_free(&sdf.grid);
  lsdem_mesh_free(&m);
  return rc;
}
