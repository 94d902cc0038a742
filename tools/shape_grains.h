/* shape_grains.h -- a grain data file (atom_style lsdem, as lsdem-shape pack and
 * from-labels write it), or a data file of atom_style hybrid lsdem bond that lsdem-shape
 * net wrote (grains and nets), read by the subcommands that add bonded balls around or
 * under the grains (membrane, net) and write everything into one data file. */
#ifndef LSDEM_SHAPE_GRAINS_H
#define LSDEM_SHAPE_GRAINS_H

#include <stddef.h>
#include <stdio.h>

typedef struct {
  long id, molecule;
  int type;
  double x[3];
  char *line; /* the Atoms line of atom_style hybrid lsdem bond, as it will be written */
} shape_grain;

typedef struct {
  int n, ntypes;
  double lo[3], hi[3];
  shape_grain *g;
  char **vel; /* Velocities lines (copied verbatim), n or NULL */
  int nvel;
  char **bond; /* Bonds lines (copied verbatim) */
  int nbonds, nbondtypes;
  char **angle; /* Angles lines (copied verbatim; lsdem-shape net --bending) */
  int nangles, nangletypes;
  long maxmol; /* the largest molecule ID (0: grains only) */
} shape_grain_file;

/* Read PATH: header counts and box, Atoms (atom_style lsdem: id type shape density x y z
 * qw qx qy qz; or hybrid lsdem bond: id type x y z shape density qw qx qy qz molecule),
 * optional Velocities, Bonds and Angles (kept verbatim). 0, or 1 after a message naming the line. */
int shape_read_grains(const char *path, shape_grain_file *gf);
void shape_free_grains(shape_grain_file *gf);
/* The first atom ID after the file's largest (1 for an empty file). */
long shape_next_id(const shape_grain_file *gf);

/* The atom types of a structure's two kinds of balls (membrane: inner and outer layer;
 * net: free and clamped): type[0] == 0 (not given) becomes the two types after the
 * file's. Returns the data file's atom type count: the file's, and at least type[0], and
 * type[1] when both kinds are used. */
int shape_ball_types(const shape_grain_file *gf, int type[2], int both_used);

/* Check that shape-ID `shape` (1-based) of LIBRARY is an analytic sphere of `radius`, the
 * ball shape of `what`; 0, or 1 after a message saying how to make it ("lsdem-shape CMD:"). */
int shape_check_sphere(const char *cmd, const char *library, int shape, double radius,
                       const char *what);
/* PREFIX + EXT opened for writing (its name in path), or NULL after a message. */
FILE *shape_open_out(const char *cmd, const char *prefix, const char *ext, char *path,
                     size_t size);
/* fclose; 0, or 1 after a message. */
int shape_close_out(const char *cmd, FILE *f, const char *path);
/* The file's atoms as Atoms lines of atom_style hybrid lsdem bond (grains of an lsdem file
 * as molecule 0): id type x y z shape-ID density qw qx qy qz molecule-ID. */
void shape_write_grain_atoms(FILE *f, const shape_grain_file *gf);
/* The file's Bonds lines (numbered 1 to nbonds, as read). */
void shape_write_bonds(FILE *f, const shape_grain_file *gf);
/* The file's Angles lines (numbered 1 to nangles, as read). */
void shape_write_angles(FILE *f, const shape_grain_file *gf);
/* The length of the file's longest bond (0 without bonds); -1 after a message when a bond
 * joins an atom the file does not have. */
double shape_longest_bond(const shape_grain_file *gf);
/* The grains' Velocities section, when the file had one. */
void shape_write_velocities(FILE *f, const shape_grain_file *gf);

#endif
