/* shape_common.h -- command-line plumbing shared by the lsdem-shape subcommands
 * (lsdem_shape.c and tools/shape_<name>.c). */
#ifndef LSDEM_SHAPE_COMMON_H
#define LSDEM_SHAPE_COMMON_H

#include "lsdem.h"

#include <stdio.h>

/* A whole-string finite number into *v; positive when `positive` is set. 1 if valid. */
int parse_number(const char *s, int positive, double *v);
/* "lsdem-shape CMD: bad WHAT 'VALUE'" on stderr; returns 2 (a usage error). */
int shape_bad_value(const char *cmd, const char *what, const char *value);
/* A whole-string integer in [lo, hi] into *v. 1 if valid. */
int parse_count(const char *s, long lo, long hi, long *v);

/* Print the warnings of the shared quality checks (lsdem_shape_check) for one shape as
 * "lsdem-shape: warning: NAME: ..." lines on stderr; returns the LSDEM_CHECK_* bits. */
int shape_warn_quality(const lsdem_shape *s, const char *name);
/* The same lines for a report already made; returns its bits. */
int shape_print_report(const lsdem_shape_report *r, const char *name);

/* A LAMMPS data file for atom_style lsdem: n grains, shape[i] the 1-based shape-ID,
 * positions 3n, quaternions 4n (scalar-first, body -> world), one density, box lo/hi.
 * Returns 0, or 1 after a message on stderr. */
int shape_write_data(const char *path, const char *title, int n, const int *shape,
                     double density, const double *pos, const double *quat, const double lo[3],
                     const double hi[3]);

/* A data file's box lines (xlo xhi, ...) and the header of its Atoms section of atom
 * style STYLE ("Atoms # STYLE"). */
void shape_write_box(FILE *f, const double lo[3], const double hi[3], const char *style);

/* Progress of a long loop on stderr, at every tenth of `total` (and the last), when
 * stderr is a terminal or LSDEM_PROGRESS=1 is set, for loops of at least 20 items:
 * "lsdem-shape: WHAT: DONE of TOTAL (P %), T s". Call with done = 1..total. */
void shape_progress(const char *what, int done, int total);

#endif
