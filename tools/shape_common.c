/* shape_common.c -- command-line plumbing shared by the lsdem-shape subcommands. */
#define _POSIX_C_SOURCE 200809L /* fileno, isatty, clock_gettime */
#include "shape_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

void shape_progress(const char *what, int done, int total)
{
  static struct timespec start;
  if (done == 1) clock_gettime(CLOCK_MONOTONIC, &start);
  const char *env = getenv("LSDEM_PROGRESS");
  const int on = env ? strcmp(env, "0") != 0 : isatty(fileno(stderr));
  if (!on || total < 20 || (done != total && (10L * done / total) == (10L * (done - 1) / total)))
    return;
  struct timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now);
  const double t = (double)(now.tv_sec - start.tv_sec) + 1e-9 * (now.tv_nsec - start.tv_nsec);
  fprintf(stderr, "lsdem-shape: %s: %d of %d (%ld %%), %.1f s", what, done, total,
          100L * done / total, t);
  if (done < total) fprintf(stderr, ", about %.0f s left", t * (total - done) / done);
  fputc('\n', stderr);
}

int shape_bad_value(const char *cmd, const char *what, const char *value)
{
  fprintf(stderr, "lsdem-shape %s: bad %s '%s'\n", cmd, what, value);
  return 2;
}

int parse_number(const char *s, int positive, double *v)
{
  char *end;
  *v = strtod(s, &end);
  return end != s && *end == '\0' && isfinite(*v) && (!positive || *v > 0.0);
}

int parse_count(const char *s, long lo, long hi, long *v)
{
  char *end;
  *v = strtol(s, &end, 10);
  return end != s && *end == '\0' && *v >= lo && *v <= hi;
}

int shape_warn_quality(const lsdem_shape *s, const char *name)
{
  lsdem_shape_report r;
  lsdem_error err;
  if (lsdem_shape_check(s, &r, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: warning: %s: not checked: %s\n", name, err.msg);
    return 0;
  }
  return shape_print_report(&r, name);
}

int shape_print_report(const lsdem_shape_report *r, const char *name)
{
  char text[1536];
  lsdem_shape_report_text(r, text, sizeof text);
  for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n"))
    fprintf(stderr, "lsdem-shape: warning: %s: %s\n", name, line);
  return r->warnings;
}

void shape_write_box(FILE *f, const double lo[3], const double hi[3], const char *style)
{
  for (int k = 0; k < 3; k++)
    fprintf(f, "%.12g %.12g %clo %chi\n", lo[k], hi[k], 'x' + k, 'x' + k);
  fprintf(f, "\nAtoms # %s\n\n", style);
}

int shape_write_data(const char *path, const char *title, int n, const int *shape,
                     double density, const double *pos, const double *quat, const double lo[3],
                     const double hi[3])
{
  FILE *f = fopen(path, "w");
  if (!f) {
    fprintf(stderr, "lsdem-shape: cannot write the data file %s\n", path);
    return 1;
  }
  fprintf(f, "%s\n\n%d atoms\n1 atom types\n\n", title, n);
  shape_write_box(f, lo, hi, "lsdem");
  for (int i = 0; i < n; i++) {
    const double *x = pos + 3 * i, *q = quat + 4 * i;
    fprintf(f, "%d 1 %d %.12g %.12g %.12g %.12g %.15g %.15g %.15g %.15g\n", i + 1, shape[i],
            density, x[0], x[1], x[2], q[0], q[1], q[2], q[3]);
  }
  if (fclose(f) != 0) {
    fprintf(stderr, "lsdem-shape: writing the data file %s failed\n", path);
    return 1;
  }
  return 0;
}
