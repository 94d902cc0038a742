/* shape_net.c -- `lsdem-shape net`: a net of bonded balls (core lsdem_net_build) in any
 * plane, alone or added to a data file (grains, or grains and the nets this command put
 * there before), as LAMMPS input:
 *   PREFIX.data  atom_style hybrid lsdem bond: the given file's atoms and bonds + the net's
 *                balls (molecule: one past the file's largest) + its bonds (bond type: one
 *                past the file's bond types); with --bending (or angles in the given
 *                file) atom_style hybrid lsdem angle: + its joints as Angles (angle type:
 *                one past the file's)
 *   PREFIX.net   the net file fix net/lsdem reads (core lsdem_net_write)
 *   PREFIX.in    bond_style lsdem/net (the first net only), bond_coeff of the net's bond
 *                type, angle_style lsdem/net and angle_coeff with --bending, groups NAME, NAME_free, NAME_clamp (and grains when the file had
 *                grains): include after read_data, every net's in the order they were made
 * Free balls get type TFREE, clamped balls TCLAMP, both the one sphere shape. */
#include "lsdem_shape_cmds.h"
#include "shape_common.h"
#include "shape_grains.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  const char *prefix, *grains, *library, *brk, *name;
  lsdem_net_params np;
  int shape, type[2];
  double rb, density, mass, k, damp, limit, margin, bending; /* bending < 0: none */
} net_opts;

static int net_usage(void)
{
  fprintf(stderr,
          "usage: lsdem-shape net PREFIX --library LIB --shape ID --rb RB --spacing A\n"
          "         --size L1 L2 [--lattice hex|square] [--origin X Y Z] [--e1 X Y Z]\n"
          "         [--e2 X Y Z] [--rest R0] [--clamp all|none|EDGE[,EDGE...]]\n"
          "         [--density RHO | --mass M] [--k K] [--damp C]\n"
          "         [--break strain S | --break force F] [--types TFREE TCLAMP]\n"
          "         [--grains DATA] [--name NAME] [--margin D] [--bending KB]\n"
          "  EDGE: u0 u1 v0 v1 (the net's sides at e1 = 0, e1 = L1, e2 = 0, e2 = L2)\n"
          "  DATA: grains (atom_style lsdem), or a PREFIX.data of this command: the net is\n"
          "  added to it with the next atom IDs, types, molecule and bond type; NAME: its\n"
          "  groups NAME, NAME_free, NAME_clamp (default net); KB: bending stiffness of the\n"
          "  joints (angle_style lsdem/net; then atom_style hybrid lsdem angle)\n"
          "  writes PREFIX.data, PREFIX.net, PREFIX.in (doc/fix_net_lsdem.rst)\n");
  return 2;
}

static int bad(const char *what, const char *value)
{
  return shape_bad_value("net", what, value);
}

static int parse_vec(char **argv, int i, double v[3])
{
  return parse_number(argv[i], 0, v) && parse_number(argv[i + 1], 0, v + 1) &&
         parse_number(argv[i + 2], 0, v + 2);
}

/* all | none | comma list of u0 u1 v0 v1 into an LSDEM_NET_EDGE_* mask; -1 if bad */
static int parse_edges(const char *s)
{
  static const char *names[] = {"u0", "u1", "v0", "v1"};
  if (!strcmp(s, "all")) return 15;
  if (!strcmp(s, "none")) return 0;
  int mask = 0;
  for (const char *p = s; *p;) {
    size_t len = strcspn(p, ",");
    int bit = -1;
    for (int k = 0; k < 4; k++)
      if (len == 2 && !strncmp(p, names[k], 2)) bit = k;
    if (bit < 0) return -1;
    mask |= 1 << bit;
    p += len + (p[len] == ',');
  }
  return mask;
}

static int parse_break(char **argv, int i, net_opts *o)
{
  o->brk = argv[i];
  return (!strcmp(argv[i], "strain") || !strcmp(argv[i], "force")) &&
         parse_number(argv[i + 1], 1, &o->limit);
}

static void defaults(net_opts *o)
{
  memset(o, 0, sizeof(*o));
  o->np.lattice = LSDEM_NET_HEX;
  o->np.e1[0] = o->np.e2[1] = 1.0;
  o->np.clamp = 15;
  o->density = 1.0;
  o->k = 0.1;
  o->margin = -1.0;
  o->bending = -1.0;
  o->name = "net";
}

static int parse_opt(int argc, char **argv, int *i, net_opts *o)
{
  const char *a = argv[*i];
  int left = argc - *i - 1;
  long k, l;
  if (!strcmp(a, "--library") && left >= 1) o->library = argv[++*i];
  else if (!strcmp(a, "--grains") && left >= 1) o->grains = argv[++*i];
  else if (!strcmp(a, "--name") && left >= 1) {
    o->name = argv[++*i];
    if (!*o->name || strspn(o->name, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                      "0123456789_") != strlen(o->name))
      return bad("name (letters, digits, underscores)", o->name);
  }
  else if (!strcmp(a, "--shape") && left >= 1) {
    if (!parse_count(argv[++*i], 1, 16777216, &k)) return bad("shape", argv[*i]);
    o->shape = (int) k;
  } else if (!strcmp(a, "--rb") && left >= 1) {
    if (!parse_number(argv[++*i], 1, &o->rb)) return bad("rb", argv[*i]);
  } else if (!strcmp(a, "--spacing") && left >= 1) {
    if (!parse_number(argv[++*i], 1, &o->np.spacing)) return bad("spacing", argv[*i]);
  } else if (!strcmp(a, "--rest") && left >= 1) {
    if (!parse_number(argv[++*i], 1, &o->np.rest)) return bad("rest length", argv[*i]);
  } else if (!strcmp(a, "--size") && left >= 2) {
    if (!parse_number(argv[*i + 1], 0, &o->np.extent[0]) ||
        !parse_number(argv[*i + 2], 0, &o->np.extent[1]) || o->np.extent[0] < 0 ||
        o->np.extent[1] < 0)
      return bad("size", argv[*i + 1]);
    *i += 2;
  } else if (!strcmp(a, "--lattice") && left >= 1) {
    ++*i;
    if (strcmp(argv[*i], "hex") && strcmp(argv[*i], "square")) return bad("lattice", argv[*i]);
    o->np.lattice = strcmp(argv[*i], "hex") ? LSDEM_NET_SQUARE : LSDEM_NET_HEX;
  } else if ((!strcmp(a, "--origin") || !strcmp(a, "--e1") || !strcmp(a, "--e2")) && left >= 3) {
    double *v = a[2] == 'o' ? o->np.origin : a[3] == '1' ? o->np.e1 : o->np.e2;
    if (!parse_vec(argv, *i + 1, v)) return bad(a + 2, argv[*i + 1]);
    *i += 3;
  } else if (!strcmp(a, "--clamp") && left >= 1) {
    if ((o->np.clamp = parse_edges(argv[++*i])) < 0) return bad("clamp edges", argv[*i]);
  } else if (!strcmp(a, "--density") && left >= 1) {
    if (!parse_number(argv[++*i], 1, &o->density)) return bad("density", argv[*i]);
  } else if (!strcmp(a, "--mass") && left >= 1) {
    if (!parse_number(argv[++*i], 1, &o->mass)) return bad("mass", argv[*i]);
  } else if (!strcmp(a, "--k") && left >= 1) {
    if (!parse_number(argv[++*i], 1, &o->k)) return bad("k", argv[*i]);
  } else if (!strcmp(a, "--damp") && left >= 1) {
    if (!parse_number(argv[++*i], 0, &o->damp) || o->damp < 0) return bad("damp", argv[*i]);
  } else if (!strcmp(a, "--bending") && left >= 1) {
    if (!parse_number(argv[++*i], 0, &o->bending) || o->bending < 0)
      return bad("bending stiffness (>= 0)", argv[*i]);
  } else if (!strcmp(a, "--margin") && left >= 1) {
    if (!parse_number(argv[++*i], 0, &o->margin) || o->margin < 0) return bad("margin", argv[*i]);
  } else if (!strcmp(a, "--break") && left >= 2) {
    if (!parse_break(argv, *i + 1, o)) return bad("break (strain S or force F, > 0)", argv[*i + 1]);
    *i += 2;
  } else if (!strcmp(a, "--types") && left >= 2) {
    if (!parse_count(argv[*i + 1], 1, 1000000, &k) || !parse_count(argv[*i + 2], 1, 1000000, &l) ||
        k == l)
      return bad("types (two different types)", argv[*i + 1]);
    o->type[0] = (int) k;
    o->type[1] = (int) l;
    *i += 2;
  } else {
    fprintf(stderr, "lsdem-shape net: unknown or incomplete option '%s'\n", a);
    return net_usage();
  }
  return 0;
}

static int parse_opts(int argc, char **argv, net_opts *o)
{
  defaults(o);
  if (argc < 1 || argv[0][0] == '-') return net_usage();
  o->prefix = argv[0];
  for (int i = 1; i < argc; i++) {
    int rc = parse_opt(argc, argv, &i, o);
    if (rc) return rc;
  }
  if (!o->library || o->shape < 1 || o->rb <= 0 || o->np.spacing <= 0) {
    fprintf(stderr, "lsdem-shape net: --library, --shape, --rb and --spacing are required\n");
    return net_usage();
  }
  if (o->np.rest <= 0) o->np.rest = o->np.spacing;
  if (o->mass > 0) o->density = o->mass / (4.0 / 3.0 * M_PI * o->rb * o->rb * o->rb);
  return 0;
}

/* ----------------------------------------------------------------- output ---- */

/* Box: the grains' box and the balls' bounding box grown by the margin (room to sag). */
static void net_box(const net_opts *o, const shape_grain_file *gf, const lsdem_net *net,
                    double lo[3], double hi[3])
{
  double margin = o->margin >= 0 ? o->margin
                                 : 0.5 * fmax(net->size[0], net->size[1]) + 2.0 * o->rb;
  for (int k = 0; k < 3; k++) {
    lo[k] = hi[k] = net->x[k];
    for (int b = 1; b < net->nballs; b++) {
      lo[k] = fmin(lo[k], net->x[3 * b + k]);
      hi[k] = fmax(hi[k], net->x[3 * b + k]);
    }
    lo[k] -= margin + o->rb;
    hi[k] += margin + o->rb;
    if (gf->n) {
      lo[k] = fmin(lo[k], gf->lo[k]);
      hi[k] = fmax(hi[k], gf->hi[k]);
    }
  }
}

/* The data file; joints (nj of them, or none without --bending) become Angles of the next
 * angle type. */
static int write_data(const net_opts *o, const shape_grain_file *gf, const lsdem_net *net,
                      int ntypes, const int *joint, int nj)
{
  const int btype = gf->nbondtypes + 1, atype = gf->nangletypes + (o->bending >= 0);
  char path[4096];
  FILE *f = shape_open_out("net", o->prefix, ".data", path, sizeof path);
  if (!f) return 1;
  double lo[3], hi[3];
  net_box(o, gf, net, lo, hi);
  fprintf(f, "LSDEM grains + net (lsdem-shape net; atom_style hybrid lsdem %s)\n\n",
          atype ? "angle" : "bond");
  fprintf(f, "%ld atoms\n%d atom types\n%d bonds\n%d bond types\n",
          (long) gf->n + net->nballs, ntypes, gf->nbonds + net->nbonds, btype);
  if (atype) fprintf(f, "%d angles\n%d angle types\n", gf->nangles + nj, atype);
  fprintf(f, "\n");
  shape_write_box(f, lo, hi, "hybrid");
  shape_write_grain_atoms(f, gf);
  for (int b = 0; b < net->nballs; b++)
    fprintf(f, "%ld %d %.17g %.17g %.17g %d %.17g 1 0 0 0 %ld\n", net->id[b],
            o->type[net->clamp[b]], net->x[3 * b], net->x[3 * b + 1], net->x[3 * b + 2],
            o->shape, o->density, gf->maxmol + 1);
  shape_write_velocities(f, gf);
  fprintf(f, "\nBonds\n\n");
  shape_write_bonds(f, gf);
  for (int b = 0; b < net->nbonds; b++)
    fprintf(f, "%d %d %ld %ld\n", gf->nbonds + b + 1, btype, net->id[net->bond[2 * b]],
            net->id[net->bond[2 * b + 1]]);
  if (atype) {
    fprintf(f, "\nAngles\n\n");
    shape_write_angles(f, gf);
    for (int k = 0; k < nj; k++)
      fprintf(f, "%d %d %ld %ld %ld\n", gf->nangles + k + 1, atype, net->id[joint[3 * k]],
              net->id[joint[3 * k + 1]], net->id[joint[3 * k + 2]]);
  }
  return shape_close_out("net", f, path);
}

static int write_include(const net_opts *o, const shape_grain_file *gf, const lsdem_net *net,
                         double carried)
{
  const int btype = gf->nbondtypes + 1;
  char path[4096];
  FILE *f = shape_open_out("net", o->prefix, ".in", path, sizeof path);
  if (!f) return 1;
  fprintf(f, "# net of %s.data (lsdem-shape net): include after read_data\n", o->prefix);
  fprintf(f, "# %s lattice, %d x %d balls of radius %.6g, spacing %.6g, rest length %.6g\n",
          net->lattice == LSDEM_NET_HEX ? "hexagonal" : "square", net->n1, net->n2, o->rb,
          net->spacing, net->rest);
  /* ghosts out to two spacings: a bond's far ball stays a ghost up to 100 % strain; with
     nets before this one in the file, out to two of their longest bonds too */
  fprintf(f, "comm_modify vel yes cutoff %.15g\n",
          2.0 * fmax(net->spacing, carried) + 2.0 * o->rb);
  if (btype == 1) fprintf(f, "bond_style lsdem/net\n");
  else fprintf(f, "# bond_style lsdem/net: in the .in of the file's first net (include it first)\n");
  fprintf(f, "bond_coeff %d %.15g %.15g", btype, o->k, net->rest);
  if (o->damp > 0) fprintf(f, " damp %.15g", o->damp);
  if (o->brk) fprintf(f, " break %s %.15g", o->brk, o->limit);
  fprintf(f, "\n");
  if (o->bending >= 0) {
    const int atype = gf->nangletypes + 1;
    fprintf(f, "# joints bend (needs atom_style hybrid lsdem angle)\n");
    if (atype == 1) fprintf(f, "angle_style lsdem/net\n");
    fprintf(f, "angle_coeff %d %.15g\n", atype, o->bending);
  }
  fprintf(f, "group %s type %d %d\ngroup %s_free type %d\ngroup %s_clamp type %d\n",
          o->name, o->type[0], o->type[1], o->name, o->type[0], o->name, o->type[1]);
  if (gf->n) fprintf(f, "group grains molecule 0\n");
  return shape_close_out("net", f, path);
}

static int write_net(const net_opts *o, lsdem_net *net)
{
  char path[4096];
  snprintf(path, sizeof path, "%s.net", o->prefix);
  lsdem_error err;
  if (lsdem_net_write(path, net, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape net: %s\n", err.msg);
    return 1;
  }
  return 0;
}

static int count_clamped(const lsdem_net *net)
{
  int n = 0;
  for (int b = 0; b < net->nballs; b++) n += net->clamp[b];
  return n;
}

int cmd_net(int argc, char **argv)
{
  net_opts o;
  int rc = parse_opts(argc, argv, &o);
  if (rc) return rc;
  if (shape_check_sphere("net", o.library, o.shape, o.rb, "the net's balls")) return 1;
  shape_grain_file gf;
  memset(&gf, 0, sizeof gf);
  if (o.grains && shape_read_grains(o.grains, &gf)) return 1;
  const double carried = shape_longest_bond(&gf);
  if (carried < 0.0) {
    shape_free_grains(&gf);
    return 1;
  }
  const int ntypes = shape_ball_types(&gf, o.type, 1);

  lsdem_net net;
  lsdem_error err;
  if (lsdem_net_build(&o.np, &net, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape net: %s\n", err.msg);
    shape_free_grains(&gf);
    return 1;
  }
  long id0 = shape_next_id(&gf);
  for (int b = 0; b < net.nballs; b++) net.id[b] = id0 + b;
  int *joint = NULL, nj = 0;
  if (o.bending >= 0 && lsdem_net_joints(&net, &joint, &nj, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape net: %s\n", err.msg);
    rc = 1;
  }
  if (!rc) rc = write_data(&o, &gf, &net, ntypes, joint, nj);
  free(joint);
  if (!rc) rc = write_net(&o, &net);
  if (!rc) rc = write_include(&o, &gf, &net, carried);
  if (!rc)
    printf("net: %d x %d balls (%d clamped), %d bonds, footprint %.12g x %.12g, normal "
           "%.12g %.12g %.12g; atom IDs %ld-%ld, types %d (free) %d (clamped), molecule %ld, "
           "bond type %d; %d joints as angles\n",
           net.n1, net.n2, count_clamped(&net), net.nbonds, net.size[0], net.size[1],
           net.normal[0], net.normal[1], net.normal[2], id0, id0 + net.nballs - 1, o.type[0],
           o.type[1], gf.maxmol + 1, gf.nbondtypes + 1, nj);
  lsdem_net_free(&net);
  shape_free_grains(&gf);
  return rc;
}
