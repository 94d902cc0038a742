/* net_file.c -- the net file codec: the one text format lsdem-shape net writes and fix
 * net/lsdem reads (format in lsdem_specimen.h, "Net files"). */
#include "lsdem_specimen.h"
#include "../base/lsdem_vec3.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------- writing ---- */

static void write_vec(FILE *f, const char *key, const double v[3])
{
  fprintf(f, "%s %.17g %.17g %.17g\n", key, v[0], v[1], v[2]);
}

lsdem_status lsdem_net_write(const char *path, const lsdem_net *net, lsdem_error *err)
{
  FILE *f = fopen(path, "w");
  if (!f) return lsdem_fail(err, LSDEM_ERR_IO, "net file %s: cannot write", path);
  fprintf(f, "lsdem-net 1\n# a net of bonded balls (doc/fix_net_lsdem.rst); atom IDs of the "
             "data file written with it\n");
  fprintf(f, "lattice %s\ncounts %d %d\n", net->lattice == LSDEM_NET_HEX ? "hex" : "square",
          net->n1, net->n2);
  write_vec(f, "origin", net->origin);
  write_vec(f, "e1", net->e1);
  write_vec(f, "e2", net->e2);
  fprintf(f, "size %.17g %.17g\nspacing %.17g\nrest %.17g\n", net->size[0], net->size[1],
          net->spacing, net->rest);
  fprintf(f, "balls %d\n", net->nballs);
  for (int b = 0; b < net->nballs; b++) fprintf(f, "%ld %d\n", net->id[b], net->clamp[b]);
  fprintf(f, "bonds %d\n", net->nbonds);
  for (int b = 0; b < net->nbonds; b++)
    fprintf(f, "%ld %ld\n", net->id[net->bond[2 * b]], net->id[net->bond[2 * b + 1]]);
  if (fclose(f) != 0) return lsdem_fail(err, LSDEM_ERR_IO, "net file %s: writing failed", path);
  return LSDEM_OK;
}

/* ------------------------------------------------------------- reading ---- */

typedef struct {
  FILE *f;
  const char *path;
  int line;
  char buf[1024];
} reader;

/* The next line with content (comments stripped) into r->buf; 0 at end of file. */
static int next_line(reader *r)
{
  while (fgets(r->buf, sizeof r->buf, r->f)) {
    r->line++;
    char *h = strchr(r->buf, '#');
    if (h) *h = '\0';
    if (r->buf[strspn(r->buf, " \t\r\n")]) return 1;
  }
  return 0;
}

/* "KEY a b c" with n numbers into v; 1 if the line is that. */
static int keyed(reader *r, const char *key, int n, double *v)
{
  char word[32];
  int used = 0;
  if (!next_line(r) || sscanf(r->buf, "%31s%n", word, &used) != 1 || strcmp(word, key)) return 0;
  const char *s = r->buf + used;
  for (int k = 0; k < n; k++) {
    char *end;
    v[k] = strtod(s, &end);
    if (end == s) return 0;
    s = end;
  }
  return 1;
}

static lsdem_status header(reader *r, lsdem_net *net, lsdem_error *err)
{
  char kind[32];
  double c[2], tmp[3];
  if (!next_line(r) || sscanf(r->buf, "lsdem-net %lf", tmp) != 1 || tmp[0] != 1.0)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "net file %s line %d: expected 'lsdem-net 1' "
                      "(a file written by lsdem-shape net)", r->path, r->line);
  if (!next_line(r) || sscanf(r->buf, "lattice %31s", kind) != 1 ||
      (strcmp(kind, "hex") && strcmp(kind, "square")))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "net file %s line %d: expected 'lattice hex' or "
                      "'lattice square'", r->path, r->line);
  net->lattice = strcmp(kind, "hex") ? LSDEM_NET_SQUARE : LSDEM_NET_HEX;
  static const char *keys[] = {"counts", "origin", "e1", "e2", "size", "spacing", "rest"};
  static const int counts[] = {2, 3, 3, 3, 2, 1, 1};
  double *dest[] = {c, net->origin, net->e1, net->e2, net->size, &net->spacing, &net->rest};
  for (int k = 0; k < 7; k++)
    if (!keyed(r, keys[k], counts[k], dest[k]))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "net file %s line %d: expected '%s' and %d "
                        "numbers", r->path, r->line, keys[k], counts[k]);
  int finite = 1;
  for (int k = 0; k < 7; k++)
    for (int j = 0; j < counts[k]; j++) finite &= isfinite(dest[k][j]);
  if (!finite || !(c[0] >= 1 && c[0] < 1e9 && c[1] >= 1 && c[1] < 1e9) || !(net->spacing > 0) ||
      !(net->rest > 0))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "net file %s line %d: header values must be "
                      "finite, counts >= 1, spacing and rest > 0", r->path, r->line);
  net->n1 = (int) c[0];
  net->n2 = (int) c[1];
  lsdem_cross3(net->e1, net->e2, net->normal);
  return LSDEM_OK;
}

/* "KEY N" then allocate; N in [0, 10^9). */
static lsdem_status section(reader *r, const char *key, int *n, lsdem_error *err)
{
  double v;
  if (!keyed(r, key, 1, &v) || !(v >= 0 && v < 1e9) || v != (int) v)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "net file %s line %d: expected '%s N'", r->path,
                      r->line, key);
  *n = (int) v;
  return LSDEM_OK;
}

static int by_id(const void *a, const void *b)
{
  long x = *(const long *) a, y = *(const long *) b;
  return (x > y) - (x < y);
}

/* Index of atom ID `id` among the balls (sorted copy `sorted` holds pairs id, index). */
static int ball_index(const long *sorted, int n, long id)
{
  int lo = 0, hi = n - 1;
  while (lo <= hi) {
    int mid = (lo + hi) / 2;
    if (sorted[2 * mid] == id) return (int) sorted[2 * mid + 1];
    if (sorted[2 * mid] < id) lo = mid + 1;
    else hi = mid - 1;
  }
  return -1;
}

static lsdem_status read_balls(reader *r, lsdem_net *net, long *sorted, lsdem_error *err)
{
  for (int b = 0; b < net->nballs; b++) {
    if (!next_line(r) || sscanf(r->buf, "%ld %d", &net->id[b], &net->clamp[b]) != 2 ||
        net->id[b] <= 0 || (net->clamp[b] != 0 && net->clamp[b] != 1))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "net file %s line %d: expected a ball line "
                        "'atom-ID clamp' (ID > 0, clamp 0 or 1)", r->path, r->line);
    sorted[2 * b] = net->id[b];
    sorted[2 * b + 1] = b;
  }
  qsort(sorted, (size_t) net->nballs, 2 * sizeof(long), by_id);
  for (int b = 1; b < net->nballs; b++)
    if (sorted[2 * b] == sorted[2 * b - 2])
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "net file %s: ball ID %ld is listed twice",
                        r->path, sorted[2 * b]);
  return LSDEM_OK;
}

static lsdem_status read_bonds(reader *r, lsdem_net *net, const long *sorted, lsdem_error *err)
{
  for (int b = 0; b < net->nbonds; b++) {
    long id[2];
    if (!next_line(r) || sscanf(r->buf, "%ld %ld", id, id + 1) != 2)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "net file %s line %d: expected a bond line "
                        "'atom-ID atom-ID'", r->path, r->line);
    for (int k = 0; k < 2; k++) {
      net->bond[2 * b + k] = ball_index(sorted, net->nballs, id[k]);
      if (net->bond[2 * b + k] < 0)
        return lsdem_fail(err, LSDEM_ERR_FORMAT, "net file %s line %d: bond %d joins atom ID "
                          "%ld, which is not a ball of the file's 'balls' list (write the net "
                          "again with lsdem-shape net, or add the ball)", r->path, r->line,
                          b + 1, id[k]);
    }
    if (id[0] == id[1])
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "net file %s line %d: bond %d joins ball %ld "
                        "to itself", r->path, r->line, b + 1, id[0]);
  }
  return LSDEM_OK;
}

static lsdem_status read_body(reader *r, lsdem_net *net, lsdem_error *err)
{
  lsdem_status st = header(r, net, err);
  if (st == LSDEM_OK) st = section(r, "balls", &net->nballs, err);
  if (st != LSDEM_OK) return st;
  net->id = malloc((size_t) (net->nballs ? net->nballs : 1) * sizeof(long));
  net->clamp = malloc((size_t) (net->nballs ? net->nballs : 1) * sizeof(int));
  long *sorted = malloc((size_t) (net->nballs ? net->nballs : 1) * 2 * sizeof(long));
  if (!net->id || !net->clamp || !sorted) {
    free(sorted);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "net file %s: out of memory", r->path);
  }
  st = read_balls(r, net, sorted, err);
  if (st == LSDEM_OK) st = section(r, "bonds", &net->nbonds, err);
  if (st == LSDEM_OK && !(net->bond = malloc((size_t) (net->nbonds ? net->nbonds : 1) * 2 *
                                             sizeof(int))))
    st = lsdem_fail(err, LSDEM_ERR_NOMEM, "net file %s: out of memory", r->path);
  if (st == LSDEM_OK) st = read_bonds(r, net, sorted, err);
  free(sorted);
  return st;
}

lsdem_status lsdem_net_read(const char *path, lsdem_net *net, lsdem_error *err)
{
  memset(net, 0, sizeof(*net));
  reader r = {fopen(path, "r"), path, 0, {0}};
  if (!r.f) return lsdem_fail(err, LSDEM_ERR_IO, "net file %s: cannot open", path);
  lsdem_status st = read_body(&r, net, err);
  fclose(r.f);
  if (st != LSDEM_OK) lsdem_net_free(net);
  return st;
}
