/* net_file.c -- the codec of the bonded-ball structures' files, one line reader for both
 * formats: the net file lsdem-shape net writes and fix net/lsdem reads, and the triaxial
 * membrane's triangles file lsdem-shape membrane writes and fix membrane/lsdem reads
 * (formats in lsdem_specimen.h, "Net files" and "The triaxial membrane's file"). */
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

/* The first word of the current line into word (cap 32); returns where the rest starts, or
 * NULL for none. */
static const char *line_key(const reader *r, char word[32])
{
  int used = 0;
  return sscanf(r->buf, "%31s%n", word, &used) == 1 ? r->buf + used : NULL;
}

/* n numbers from s into v; 1 if there are that many. */
static int numbers(const char *s, int n, double *v)
{
  for (int k = 0; k < n; k++) {
    char *end;
    v[k] = strtod(s, &end);
    if (end == s) return 0;
    s = end;
  }
  return 1;
}

/* "KEY a b c" with n numbers into v; 1 if the next line is that. */
static int keyed(reader *r, const char *key, int n, double *v)
{
  char word[32];
  const char *rest = next_line(r) ? line_key(r, word) : NULL;
  return rest && !strcmp(word, key) && numbers(rest, n, v);
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

/* IDs sorted with their indices: pairs (id, index) by id */
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

/* ------------------------------------------------- the membrane's file ---- */

void lsdem_membrane_file_print(FILE *f, const lsdem_membrane_file *mf, const char *about)
{
  fprintf(f, "lsdem-membrane-triangles 1\n");
  if (about) fprintf(f, "# %s\n", about);
  fprintf(f, "axis %.15g %.15g\nspecimen_radius %.15g\nsphere_radius %.15g %.15g\nlayers %d\n",
          mf->axis[0], mf->axis[1], mf->specimen_radius, mf->sphere_radius[0],
          mf->sphere_radius[1], mf->layers);
  fprintf(f, "lateral_areas %.15g %.15g\n", mf->lateral_areas[0], mf->lateral_areas[1]);
  fprintf(f, "vertices %d\n", mf->nvertices);
  for (int i = 0; i < mf->nvertices; i++)
    fprintf(f, "%ld %d %d\n", mf->vertex[i], mf->vertex_layer[i], mf->vertex_end[i]);
  fprintf(f, "triangles %d\n", mf->ntriangles);
  for (int t = 0; t < mf->ntriangles; t++)
    fprintf(f, "%ld %ld %ld %d\n", mf->triangle[3 * t], mf->triangle[3 * t + 1],
            mf->triangle[3 * t + 2], mf->triangle_layer[t]);
  fprintf(f, "cap_edges %d\n", mf->ncap_edges);
  for (int e = 0; e < mf->ncap_edges; e++)
    fprintf(f, "%ld %ld %d %d\n", mf->cap_edge[2 * e], mf->cap_edge[2 * e + 1], mf->cap_layer[e],
            mf->cap_end[e]);
}

void lsdem_membrane_file_free(lsdem_membrane_file *mf)
{
  free(mf->vertex);
  free(mf->vertex_layer);
  free(mf->vertex_end);
  free(mf->triangle);
  free(mf->triangle_layer);
  free(mf->cap_edge);
  free(mf->cap_layer);
  free(mf->cap_end);
  memset(mf, 0, sizeof(*mf));
}

static lsdem_status bad_line(const reader *r, const char *what, lsdem_error *err)
{
  return lsdem_fail(err, LSDEM_ERR_FORMAT, "triangles file %s line %d: %s", r->path, r->line,
                    what);
}

/* the count after a section's keyword (rest of the line), >= least and < 10^9 */
static int section_count(const char *rest, int least, int *n)
{
  double v;
  if (!numbers(rest, 1, &v) || !(v >= least && v < 1e9) || v != (int) v) return 0;
  *n = (int) v;
  return 1;
}

/* n rows of `cols` atom IDs and `nints` small integers each in [lo[k], hi[k]] */
static lsdem_status read_rows(reader *r, int n, int cols, long *ids, int nints, int **ints,
                              const int *lo, const int *hi, const char *what, lsdem_error *err)
{
  for (int row = 0; row < n; row++) {
    if (!next_line(r)) return bad_line(r, what, err);
    const char *s = r->buf;
    for (int c = 0; c < cols + nints; c++) {
      char *end;
      const long v = strtol(s, &end, 10);
      if (end == s) return bad_line(r, what, err);
      s = end;
      if (c < cols) ids[(size_t) cols * row + c] = v;
      else if (v < lo[c - cols] || v > hi[c - cols]) return bad_line(r, what, err);
      else ints[c - cols][row] = (int) v;
    }
  }
  return LSDEM_OK;
}

static void *alloc_array(int n, size_t size)
{
  return malloc((size_t) (n > 0 ? n : 1) * size);
}

/* the sections of vertices, triangles and cap edges */
static lsdem_status read_vertices(reader *r, const char *rest, lsdem_membrane_file *mf,
                                  lsdem_error *err)
{
  static const int lo[2] = {0, 0}, hi[2] = {1, 2};
  if (mf->vertex || !section_count(rest, 3, &mf->nvertices))
    return bad_line(r, "vertices N (N >= 3, once)", err);
  mf->vertex = alloc_array(mf->nvertices, sizeof(long));
  mf->vertex_layer = alloc_array(mf->nvertices, sizeof(int));
  mf->vertex_end = alloc_array(mf->nvertices, sizeof(int));
  if (!mf->vertex || !mf->vertex_layer || !mf->vertex_end)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "triangles file %s: out of memory", r->path);
  int *ints[2] = {mf->vertex_layer, mf->vertex_end};
  return read_rows(r, mf->nvertices, 1, mf->vertex, 2, ints, lo, hi,
                   "expected 'atom-ID layer end'", err);
}

static lsdem_status read_triangles(reader *r, const char *rest, lsdem_membrane_file *mf,
                                   lsdem_error *err)
{
  static const int lo[1] = {0}, hi[1] = {1};
  if (mf->triangle || !section_count(rest, 1, &mf->ntriangles))
    return bad_line(r, "triangles N (N >= 1, once)", err);
  mf->triangle = alloc_array(mf->ntriangles, 3 * sizeof(long));
  mf->triangle_layer = alloc_array(mf->ntriangles, sizeof(int));
  if (!mf->triangle || !mf->triangle_layer)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "triangles file %s: out of memory", r->path);
  int *ints[1] = {mf->triangle_layer};
  return read_rows(r, mf->ntriangles, 3, mf->triangle, 1, ints, lo, hi,
                   "expected 'id1 id2 id3 layer'", err);
}

static lsdem_status read_cap_edges(reader *r, const char *rest, lsdem_membrane_file *mf,
                                   lsdem_error *err)
{
  static const int lo[2] = {0, 1}, hi[2] = {1, 2};
  if (mf->cap_edge || !section_count(rest, 0, &mf->ncap_edges))
    return bad_line(r, "cap_edges N (N >= 0, once)", err);
  mf->cap_edge = alloc_array(mf->ncap_edges, 2 * sizeof(long));
  mf->cap_layer = alloc_array(mf->ncap_edges, sizeof(int));
  mf->cap_end = alloc_array(mf->ncap_edges, sizeof(int));
  if (!mf->cap_edge || !mf->cap_layer || !mf->cap_end)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "triangles file %s: out of memory", r->path);
  int *ints[2] = {mf->cap_layer, mf->cap_end};
  return read_rows(r, mf->ncap_edges, 2, mf->cap_edge, 2, ints, lo, hi,
                   "expected 'id1 id2 layer end(1 bottom, 2 top)'", err);
}

/* a keyword line of scalars: axis, specimen_radius, sphere_radius, lateral_areas, layers;
 * seen: bit per keyword; 0 when the word is none of them */
static int read_scalars(const char *word, const char *rest, lsdem_membrane_file *mf,
                        int *seen, int *ok)
{
  static const char *keys[] = {"axis", "specimen_radius", "sphere_radius", "lateral_areas",
                               "layers"};
  static const int counts[] = {2, 1, 2, 2, 1};
  double layers = 0.0;
  double *dest[] = {mf->axis, &mf->specimen_radius, mf->sphere_radius, mf->lateral_areas,
                    &layers};
  for (int k = 0; k < 5; k++) {
    if (strcmp(word, keys[k])) continue;
    *ok = numbers(rest, counts[k], dest[k]);
    if (k == 3) *ok &= mf->lateral_areas[0] > 0.0 && mf->lateral_areas[1] >= 0.0;
    if (k == 4) {
      *ok &= (layers == 1.0 || layers == 2.0);
      mf->layers = (int) layers;
    }
    *seen |= 1 << k;
    return 1;
  }
  return 0;
}

/* every triangle and cap edge names a vertex of the file */
static lsdem_status check_vertices(const reader *r, const lsdem_membrane_file *mf,
                                   lsdem_error *err)
{
  long *sorted = alloc_array(mf->nvertices, 2 * sizeof(long));
  if (!sorted) return lsdem_fail(err, LSDEM_ERR_NOMEM, "triangles file %s: out of memory", r->path);
  for (int v = 0; v < mf->nvertices; v++) {
    sorted[2 * v] = mf->vertex[v];
    sorted[2 * v + 1] = v;
  }
  qsort(sorted, (size_t) mf->nvertices, 2 * sizeof(long), by_id);
  lsdem_status st = LSDEM_OK;
  for (int k = 0; k < 3 * mf->ntriangles && st == LSDEM_OK; k++)
    if (ball_index(sorted, mf->nvertices, mf->triangle[k]) < 0)
      st = lsdem_fail(err, LSDEM_ERR_FORMAT, "triangles file %s: triangle vertex %ld is not in "
                      "the vertices list", r->path, mf->triangle[k]);
  for (int k = 0; k < 2 * mf->ncap_edges && st == LSDEM_OK; k++)
    if (ball_index(sorted, mf->nvertices, mf->cap_edge[k]) < 0)
      st = lsdem_fail(err, LSDEM_ERR_FORMAT, "triangles file %s: cap edge vertex %ld is not in "
                      "the vertices list", r->path, mf->cap_edge[k]);
  free(sorted);
  return st;
}

static lsdem_status read_membrane_body(reader *r, lsdem_membrane_file *mf, lsdem_error *err)
{
  double version;
  if (!next_line(r) || sscanf(r->buf, "lsdem-membrane-triangles %lf", &version) != 1 ||
      version != 1.0)
    return bad_line(r, "expected 'lsdem-membrane-triangles 1' (a file from lsdem-shape "
                    "membrane)", err);
  int seen = 0;
  while (next_line(r)) {
    char word[32];
    const char *rest = line_key(r, word);
    if (!rest) continue;
    int ok = 1;
    lsdem_status st = LSDEM_OK;
    if (read_scalars(word, rest, mf, &seen, &ok)) {
      if (!ok) return bad_line(r, "expected axis CX CY, specimen_radius RS, sphere_radius RB "
                               "RB_OUTER, lateral_areas A_INNER (> 0) A_OUTER (>= 0) or "
                               "layers 1|2", err);
    } else if (!strcmp(word, "vertices")) st = read_vertices(r, rest, mf, err);
    else if (!strcmp(word, "triangles")) st = read_triangles(r, rest, mf, err);
    else if (!strcmp(word, "cap_edges")) st = read_cap_edges(r, rest, mf, err);
    else return bad_line(r, "unknown keyword", err);
    if (st != LSDEM_OK) return st;
  }
  if (seen != 31 || !mf->vertex || !mf->triangle || !mf->cap_edge ||
      !(mf->specimen_radius > 0.0) || !(mf->sphere_radius[0] > 0.0) ||
      (mf->layers == 2 && !(mf->lateral_areas[1] > 0.0)))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "triangles file %s is incomplete (needs axis, "
                      "specimen_radius > 0, sphere_radius > 0, lateral_areas, layers, vertices, "
                      "triangles, cap_edges)", r->path);
  return check_vertices(r, mf, err);
}

lsdem_status lsdem_membrane_file_read(const char *path, lsdem_membrane_file *mf,
                                      lsdem_error *err)
{
  memset(mf, 0, sizeof(*mf));
  reader r = {fopen(path, "r"), path, 0, {0}};
  if (!r.f) return lsdem_fail(err, LSDEM_ERR_IO, "cannot open triangles file %s", path);
  const lsdem_status st = read_membrane_body(&r, mf, err);
  fclose(r.f);
  if (st != LSDEM_OK) lsdem_membrane_file_free(mf);
  return st;
}
