/* shape_membrane.c -- `lsdem-shape membrane`: the triaxial test's flexible membrane
 * (core lsdem_membrane_build) around a grain data file, as LAMMPS input:
 *   PREFIX.data  atom_style hybrid lsdem bond: grains (molecule 0) + membrane spheres + Bonds
 *   PREFIX.tri   triangles file for fix membrane/lsdem (doc/fix_membrane_lsdem.rst)
 *   PREFIX.in    bond_style lsdem/membrane, bond_coeff lines, groups (include after read_data)
 * Hybrid Atoms lines (AtomVecHybrid: common "id type x y z", then each sub-style's own
 * fields): id type x y z shape-ID density qw qx qy qz molecule-ID. */
#include "lsdem_shape_cmds.h"
#include "shape_common.h"
#include "shape_grains.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  const char *prefix, *grains, *library;
  lsdem_membrane_params mp;
  int shape[2], type[2];
  double density, knbb, ksbb, kn_outer, ks_outer, kn_inter, ks_inter;
} membrane_opts;

static int membrane_usage(void)
{
  fprintf(stderr,
          "usage: lsdem-shape membrane PREFIX --radius RS --height H --rb RB --library LIB\n"
          "         --shapes SHAPE_IN SHAPE_OUT [--grains GRAINS.data] [--centre X Y] [--z0 Z]\n"
          "         [--outer F] [--density RHO] [--types T_IN T_OUT] [--knbb K] [--ksbb K]\n"
          "         [--kouter KN KS] [--kinter KN KS]\n"
          "  writes PREFIX.data, PREFIX.tri, PREFIX.in (doc/fix_membrane_lsdem.rst)\n");
  return 2;
}

static int bad(const char *what, const char *value)
{
  return shape_bad_value("membrane", what, value);
}

/* Two non-negative stiffnesses after an option (--kouter, --kinter). */
static int parse_stiffness_pair(char **argv, int i, double *kn, double *ks)
{
  return parse_number(argv[i + 1], 0, kn) && parse_number(argv[i + 2], 0, ks) && *kn >= 0 &&
         *ks >= 0;
}

static int parse_opts(int argc, char **argv, membrane_opts *o)
{
  memset(o, 0, sizeof(*o));
  o->mp.outer_factor = 1.1;
  o->density = 1.0;
  o->knbb = o->ksbb = 50.0;
  o->kn_outer = o->ks_outer = o->kn_inter = o->ks_inter = -1.0;
  o->shape[0] = o->shape[1] = -1;
  if (argc < 1 || argv[0][0] == '-') return membrane_usage();
  o->prefix = argv[0];
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    int left = argc - i - 1;
    double v, w;
    long k, l;
    if (!strcmp(a, "--radius") && left >= 1) {
      if (!parse_number(argv[++i], 1, &o->mp.specimen_radius)) return bad("radius", argv[i]);
    } else if (!strcmp(a, "--height") && left >= 1) {
      if (!parse_number(argv[++i], 1, &o->mp.height)) return bad("height", argv[i]);
    } else if (!strcmp(a, "--rb") && left >= 1) {
      if (!parse_number(argv[++i], 1, &o->mp.rb)) return bad("rb", argv[i]);
    } else if (!strcmp(a, "--outer") && left >= 1) {
      if (!parse_number(argv[++i], 0, &v) || (v != 0 && v < 1.0)) return bad("outer factor (0 or >= 1)", argv[i]);
      o->mp.outer_factor = v;
    } else if (!strcmp(a, "--z0") && left >= 1) {
      if (!parse_number(argv[++i], 0, &o->mp.z0)) return bad("z0", argv[i]);
    } else if (!strcmp(a, "--centre") && left >= 2) {
      if (!parse_number(argv[i + 1], 0, &v) || !parse_number(argv[i + 2], 0, &w))
        return bad("centre", argv[i + 1]);
      o->mp.centre[0] = v;
      o->mp.centre[1] = w;
      i += 2;
    } else if (!strcmp(a, "--density") && left >= 1) {
      if (!parse_number(argv[++i], 1, &o->density)) return bad("density", argv[i]);
    } else if (!strcmp(a, "--knbb") && left >= 1) {
      if (!parse_number(argv[++i], 0, &o->knbb) || o->knbb < 0) return bad("knbb", argv[i]);
    } else if (!strcmp(a, "--ksbb") && left >= 1) {
      if (!parse_number(argv[++i], 0, &o->ksbb) || o->ksbb < 0) return bad("ksbb", argv[i]);
    } else if (!strcmp(a, "--kouter") && left >= 2) {
      if (!parse_stiffness_pair(argv, i, &o->kn_outer, &o->ks_outer)) return bad("kouter", argv[i + 1]);
      i += 2;
    } else if (!strcmp(a, "--kinter") && left >= 2) {
      if (!parse_stiffness_pair(argv, i, &o->kn_inter, &o->ks_inter)) return bad("kinter", argv[i + 1]);
      i += 2;
    } else if (!strcmp(a, "--shapes") && left >= 2) {
      if (!parse_count(argv[i + 1], 1, 16777216, &k) || !parse_count(argv[i + 2], 1, 16777216, &l))
        return bad("shapes", argv[i + 1]);
      o->shape[0] = (int) k;
      o->shape[1] = (int) l;
      i += 2;
    } else if (!strcmp(a, "--types") && left >= 2) {
      if (!parse_count(argv[i + 1], 1, 1000000, &k) || !parse_count(argv[i + 2], 1, 1000000, &l))
        return bad("types", argv[i + 1]);
      o->type[0] = (int) k;
      o->type[1] = (int) l;
      i += 2;
    } else if (!strcmp(a, "--grains") && left >= 1) {
      o->grains = argv[++i];
    } else if (!strcmp(a, "--library") && left >= 1) {
      o->library = argv[++i];
    } else {
      fprintf(stderr, "lsdem-shape membrane: unknown or incomplete option '%s'\n", a);
      return membrane_usage();
    }
  }
  if (o->mp.specimen_radius <= 0 || o->mp.height <= 0 || o->mp.rb <= 0 || !o->library ||
      o->shape[0] < 1) {
    fprintf(stderr, "lsdem-shape membrane: --radius, --height, --rb, --library and --shapes "
                    "are required\n");
    return membrane_usage();
  }
  if (o->kn_outer < 0) o->kn_outer = o->knbb;
  if (o->ks_outer < 0) o->ks_outer = o->ksbb;
  if (o->kn_inter < 0) o->kn_inter = o->knbb;
  if (o->ks_inter < 0) o->ks_inter = o->ksbb;
  return 0;
}

/* ----------------------------------------------------------------- output ---- */

/* The two membrane shapes must be analytic spheres of radius rb and outer_factor rb. */
static int check_shapes(const membrane_opts *o, const lsdem_membrane *m)
{
  int rc = 0;
  for (int layer = 0; layer < (m->nrings[1] ? 2 : 1) && !rc; layer++)
    rc = shape_check_sphere("membrane", o->library, o->shape[layer], m->sphere_radius[layer],
                            layer ? "the outer layer" : "the inner layer");
  return rc;
}

/* bond types written: the kinds up to the last one used (3 for a single layer, else 9) */
static int bond_types(const lsdem_membrane *m)
{
  int n = 0;
  for (int k = 0; k < LSDEM_MEMBRANE_BOND_KINDS; k++)
    if (m->kind_used[k]) n = k + 1;
  return n;
}

/* molecule ID of a membrane sphere: 1 bottom end ring, 2 top end ring, 3 otherwise */
static int sphere_molecule(const lsdem_membrane *m, int i)
{
  if (m->ring[i] == 0) return 1;
  return m->ring[i] == m->nrings[m->layer[i]] - 1 ? 2 : 3;
}

static int write_data(const membrane_opts *o, const shape_grain_file *gf, const lsdem_membrane *m,
                      long id0, int ntypes)
{
  char path[4096];
  FILE *f = shape_open_out("membrane", o->prefix, ".data", path, sizeof path);
  if (!f) return 1;
  double lo[3], hi[3], reach = m->ring_radius[m->nrings[1] ? 1 : 0] + 2.0 * o->mp.rb * 1.1;
  for (int k = 0; k < 2; k++) {
    lo[k] = o->mp.centre[k] - reach;
    hi[k] = o->mp.centre[k] + reach;
  }
  lo[2] = o->mp.z0 - 2.0 * o->mp.rb;
  hi[2] = o->mp.z0 + o->mp.height + 2.0 * o->mp.rb;
  for (int k = 0; k < 3 && gf->n; k++) {
    lo[k] = fmin(lo[k], gf->lo[k]);
    hi[k] = fmax(hi[k], gf->hi[k]);
  }
  fprintf(f, "LSDEM grains + membrane (lsdem-shape membrane; atom_style hybrid lsdem bond)\n\n");
  fprintf(f, "%ld atoms\n%d atom types\n%d bonds\n%d bond types\n\n", (long) gf->n + m->nspheres,
          ntypes, m->nbonds, bond_types(m));
  shape_write_box(f, lo, hi, "hybrid");
  shape_write_grain_atoms(f, gf);
  for (int i = 0; i < m->nspheres; i++) {
    int layer = m->layer[i];
    fprintf(f, "%ld %d %.15g %.15g %.15g %d %.12g 1 0 0 0 %d\n", id0 + i, o->type[layer],
            m->x[3 * i], m->x[3 * i + 1], m->x[3 * i + 2], o->shape[layer], o->density,
            sphere_molecule(m, i));
  }
  shape_write_velocities(f, gf);
  fprintf(f, "\nBonds\n\n");
  for (int b = 0; b < m->nbonds; b++)
    fprintf(f, "%d %d %ld %ld\n", b + 1, m->bond_kind[b] + 1, id0 + m->bond[2 * b],
            id0 + m->bond[2 * b + 1]);
  return shape_close_out("membrane", f, path);
}

/* The triangles file through the core's codec (lsdem_membrane_file_print): vertices, lateral
 * triangles and cap edges by atom ID, with the lateral areas as generated (the pressure
 * split's reference). */
static int write_triangles(const membrane_opts *o, const lsdem_membrane *m, long id0)
{
  char path[4096], about[4200];
  lsdem_membrane_file mf;
  memset(&mf, 0, sizeof mf);
  mf.axis[0] = o->mp.centre[0];
  mf.axis[1] = o->mp.centre[1];
  mf.specimen_radius = o->mp.specimen_radius;
  mf.sphere_radius[0] = m->sphere_radius[0];
  mf.sphere_radius[1] = m->sphere_radius[1];
  mf.layers = m->nrings[1] ? 2 : 1;
  for (int t = 0; t < m->ntris; t++) {
    double S[3];
    lsdem_triangle_area_vector(m->x + 3 * m->tri[3 * t], m->x + 3 * m->tri[3 * t + 1],
                               m->x + 3 * m->tri[3 * t + 2], S);
    mf.lateral_areas[m->tri_layer[t]] += sqrt(S[0] * S[0] + S[1] * S[1] + S[2] * S[2]);
  }
  mf.nvertices = m->nspheres;
  mf.ntriangles = m->ntris;
  mf.ncap_edges = m->ncap_edges;
  mf.vertex = malloc((size_t) (m->nspheres + 1) * sizeof(long));
  mf.vertex_layer = malloc((size_t) (m->nspheres + 1) * sizeof(int));
  mf.vertex_end = malloc((size_t) (m->nspheres + 1) * sizeof(int));
  mf.triangle = malloc((size_t) (3 * m->ntris + 1) * sizeof(long));
  mf.triangle_layer = m->tri_layer;
  mf.cap_edge = malloc((size_t) (2 * m->ncap_edges + 1) * sizeof(long));
  mf.cap_layer = m->cap_layer;
  mf.cap_end = malloc((size_t) (m->ncap_edges + 1) * sizeof(int));
  int failed = !mf.vertex || !mf.vertex_layer || !mf.vertex_end || !mf.triangle ||
               !mf.cap_edge || !mf.cap_end;
  if (failed) fprintf(stderr, "lsdem-shape membrane: out of memory\n");
  FILE *f = failed ? NULL : shape_open_out("membrane", o->prefix, ".tri", path, sizeof path);
  if (f) {
    for (int i = 0; i < m->nspheres; i++) {
      const int mol = sphere_molecule(m, i);
      mf.vertex[i] = id0 + i;
      mf.vertex_layer[i] = m->layer[i];
      mf.vertex_end[i] = mol == 3 ? 0 : mol;
    }
    for (int k = 0; k < 3 * m->ntris; k++) mf.triangle[k] = id0 + m->tri[k];
    for (int e = 0; e < m->ncap_edges; e++) {
      mf.cap_edge[2 * e] = id0 + m->cap_edge[2 * e];
      mf.cap_edge[2 * e + 1] = id0 + m->cap_edge[2 * e + 1];
      mf.cap_end[e] = m->cap_end[e] + 1;
    }
    snprintf(about, sizeof about, "written by lsdem-shape membrane; atom IDs of %s.data",
             o->prefix);
    lsdem_membrane_file_print(f, &mf, about);
    failed = shape_close_out("membrane", f, path);
  } else {
    failed = 1;
  }
  free(mf.vertex);
  free(mf.vertex_layer);
  free(mf.vertex_end);
  free(mf.triangle);
  free(mf.cap_edge);
  free(mf.cap_end);
  return failed;
}

static int write_include(const membrane_opts *o, const lsdem_membrane *m)
{
  static const char *kind_names[LSDEM_MEMBRANE_BOND_KINDS] = {
      "inner, in ring",        "inner, to upper ring +half step", "inner, to upper ring -half step",
      "outer, in ring",        "outer, to upper ring +half step", "outer, to upper ring -half step",
      "outer -> inner, -half", "outer -> inner, +half",            "outer -> inner, apex above"};
  char path[4096];
  FILE *f = shape_open_out("membrane", o->prefix, ".in", path, sizeof path);
  if (!f) return 1;
  fprintf(f, "# membrane of %s.data (lsdem-shape membrane): include after read_data\n", o->prefix);
  fprintf(f, "# %d spheres per ring, %d + %d rings, ring spacing %.6g, centre radii %.6g %.6g\n",
          m->nper, m->nrings[0], m->nrings[1], m->dz, m->ring_radius[0], m->ring_radius[1]);
  fprintf(f, "bond_style lsdem/membrane axis %.15g %.15g\n", o->mp.centre[0], o->mp.centre[1]);
  fprintf(f, "# bond_coeff type Knbb Ksbb r0 rest_hoop rest_axial\n");
  for (int k = 0; k < bond_types(m); k++) {
    /* bond kinds: 0-2 inner layer, 3-5 outer layer, 6-8 outer -> inner */
    const double kn = k < 3 ? o->knbb : k < 6 ? o->kn_outer : o->kn_inter;
    const double ks = k < 3 ? o->ksbb : k < 6 ? o->ks_outer : o->ks_inter;
    fprintf(f, "bond_coeff %d %.12g %.12g %.15g %.15g %.15g  # %s (%d bonds)\n", k + 1, kn, ks,
            m->kind_r0[k], m->kind_rest[2 * k], m->kind_rest[2 * k + 1], kind_names[k],
            m->kind_used[k]);
  }
  if (m->nrings[1])
    fprintf(f, "group membrane type %d %d\ngroup membrane_inner type %d\n"
               "group membrane_outer type %d\n", o->type[0], o->type[1], o->type[0], o->type[1]);
  else
    fprintf(f, "group membrane type %d\ngroup membrane_inner type %d\n", o->type[0], o->type[0]);
  fprintf(f, "group membrane_bottom molecule 1\ngroup membrane_top molecule 2\n");
  return shape_close_out("membrane", f, path);
}

int cmd_membrane(int argc, char **argv)
{
  membrane_opts o;
  int rc = parse_opts(argc, argv, &o);
  if (rc) return rc;
  shape_grain_file gf;
  memset(&gf, 0, sizeof gf);
  if (o.grains && shape_read_grains(o.grains, &gf)) return 1;
  if (gf.nbonds) {
    fprintf(stderr, "lsdem-shape membrane: %s has bonds; the membrane's bond style takes a "
            "grain file without them\n", o.grains);
    shape_free_grains(&gf);
    return 1;
  }
  long id0 = shape_next_id(&gf);
  const int ntypes = shape_ball_types(&gf, o.type, o.mp.outer_factor > 0);

  lsdem_membrane m;
  lsdem_error err;
  if (lsdem_membrane_build(&o.mp, &m, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape membrane: %s\n", err.msg);
    shape_free_grains(&gf);
    return 1;
  }
  rc = check_shapes(&o, &m);
  if (!rc) rc = write_data(&o, &gf, &m, id0, ntypes);
  if (!rc) rc = write_triangles(&o, &m, id0);
  if (!rc) rc = write_include(&o, &m);
  if (!rc)
    printf("membrane: %d spheres (%d per ring, %d inner + %d outer rings, ring spacing %.12g), "
           "%d bonds, %d triangles; inner centres on radius %.12g, outer %.12g; atom IDs %ld-%ld\n",
           m.nspheres, m.nper, m.nrings[0], m.nrings[1], m.dz, m.nbonds, m.ntris,
           m.ring_radius[0], m.ring_radius[1], id0, id0 + m.nspheres - 1);
  lsdem_membrane_free(&m);
  shape_free_grains(&gf);
  return rc;
}
