/* shapebuild.c -- a library shape from an SDF in its principal frame (nodes, clusters,
 * bounding radius, mass properties), and the quality checks every shape source runs
 * (issue 4: grid spacing vs size, node spacing, closed level set, volume and inertia
 * consistency between grid and nodes). */
#include "lsdem_prep.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

void lsdem_built_shape_free(lsdem_built_shape *b)
{
  if (!b) return;
  free(b->nodes);
  free(b->area);
  free(b->cluster_sphere);
  free(b->cluster_start);
  free(b->phi);
  memset(b, 0, sizeof *b);
}

static double max_node_radius(const double *nodes, int n)
{
  double r2 = 0.0;
  for (int i = 0; i < n; i++) {
    const double *p = nodes + 3 * i;
    r2 = fmax(r2, p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  }
  return sqrt(r2);
}

/* Node count giving a mean spacing sqrt(area / N) of `spacing` on a grid's surface;
 * spacing <= 0: LSDEM_AUTO_NODE_SPACING times the equivalent-sphere diameter. */
static lsdem_status count_from_spacing(const lsdem_sdf *sdf, double spacing, int *n,
                                       lsdem_error *err)
{
  if (sdf->kind != LSDEM_SDF_GRID)
    return lsdem_fail(err, LSDEM_ERR_ARG, "a node spacing needs a grid shape");
  if (!(spacing > 0.0)) {
    lsdem_massprops mp;
    const lsdem_status st = lsdem_massprops_grid(&sdf->grid, 1, &mp, err);
    if (st != LSDEM_OK) return st;
    spacing = LSDEM_AUTO_NODE_SPACING * 2.0 * cbrt(3.0 * mp.volume / (4.0 * PI));
  }
  const double area = lsdem_surface_area_grid(&sdf->grid);
  const double want = ceil(area / (spacing * spacing));
  if (!(want >= 1.0) || want > (double)LSDEM_LIBRARY_MAX_NODES)
    return lsdem_fail(err, LSDEM_ERR_ARG, "node spacing %g on a surface of area %g gives "
                      "%.0f nodes (allowed 1..%d)", spacing, area, want, LSDEM_LIBRARY_MAX_NODES);
  *n = (int)want;
  return LSDEM_OK;
}

static lsdem_status alloc_nodes(lsdem_built_shape *b, int n, lsdem_error *err)
{
  const size_t nn = (size_t)n;
  b->nodes = malloc(3 * nn * sizeof(double));
  b->area = malloc(nn * sizeof(double));
  b->cluster_sphere = malloc(4 * nn * sizeof(double));
  b->cluster_start = malloc((nn + 1) * sizeof(int));
  if (!b->nodes || !b->area || !b->cluster_sphere || !b->cluster_start)
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "cannot allocate %d nodes", n);
  return LSDEM_OK;
}

lsdem_status lsdem_shape_build(const lsdem_sdf *sdf, int nnodes, double node_spacing,
                               uint64_t seed, lsdem_built_shape *out, lsdem_error *err)
{
  if (!out) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  memset(out, 0, sizeof *out);
  if (!sdf) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL SDF");
  lsdem_shape *s = &out->shape;
  s->sdf = *sdf;
  if (sdf->kind == LSDEM_SDF_GRID) out->phi = (float *)sdf->grid.phi;
  lsdem_status st = LSDEM_OK;
  if (nnodes <= 0) {
    st = count_from_spacing(sdf, node_spacing, &nnodes, err);
    if (st != LSDEM_OK) return st;
  }
  if ((st = alloc_nodes(out, nnodes, err)) != LSDEM_OK) return st;
  int count = 0;
  st = lsdem_nodes_seed(sdf, nnodes, seed, out->nodes, out->area, &count, err);
  if (st != LSDEM_OK) return st;
  s->nnodes = count;
  s->nclusters = lsdem_nodes_cluster(count, out->nodes, out->area, LSDEM_CLUSTER_TARGET,
                                     out->cluster_start, out->cluster_sphere);
  s->nodes = out->nodes;
  s->node_area = out->area;
  s->cluster_start = out->cluster_start;
  s->cluster_sphere = out->cluster_sphere;
  s->radius = fmax(max_node_radius(out->nodes, count), lsdem_sdf_bound_radius(sdf));
  if (sdf->kind == LSDEM_SDF_GRID) {
    lsdem_massprops mp;
    if ((st = lsdem_massprops_grid(&sdf->grid, 2, &mp, err)) != LSDEM_OK) return st;
    s->volume = mp.volume;
    memcpy(s->inertia, mp.principal, sizeof s->inertia);
  }
  return LSDEM_OK;
}

/* ----------------------------------------------------------------- checks ---- */

/* Negative samples on the six border faces of a grid: the zero level set is not closed
 * inside the grid (the solid is cut by the grid box). */
static long border_negative(const lsdem_grid *g)
{
  long count = 0;
  size_t m = 0;
  for (int k = 0; k < g->n[2]; k++)
    for (int j = 0; j < g->n[1]; j++)
      for (int i = 0; i < g->n[0]; i++, m++) {
        const int on_border = i == 0 || j == 0 || k == 0 || i == g->n[0] - 1 ||
                              j == g->n[1] - 1 || k == g->n[2] - 1;
        if (on_border && g->phi[m] < 0.0f) count++;
      }
  return count;
}

/* Volume and second moments of the solid from its surface nodes by the divergence
 * theorem: V = (1/3) oint x.n dA, and since div(x_i x_j x) = 5 x_i x_j,
 * int x_i x_j dV = (1/5) oint x_i x_j (x.n) dA; each node stands for its area. */
static void node_moments(const lsdem_shape *s, double *volume, double inertia[3])
{
  double v = 0.0, m2[3] = {0.0, 0.0, 0.0};
  for (int k = 0; k < s->nnodes; k++) {
    const double *x = s->nodes + 3 * k;
    double n[3];
    lsdem_sdf_eval(&s->sdf, x, n);
    const double xn = (x[0] * n[0] + x[1] * n[1] + x[2] * n[2]) * s->node_area[k];
    v += xn / 3.0;
    for (int a = 0; a < 3; a++) m2[a] += x[a] * x[a] * xn / 5.0;
  }
  *volume = v;
  for (int a = 0; a < 3; a++) inertia[a] = m2[(a + 1) % 3] + m2[(a + 2) % 3];
}

lsdem_status lsdem_shape_check(const lsdem_shape *s, lsdem_shape_report *r, lsdem_error *err)
{
  return lsdem_shape_check_tol(s, LSDEM_CHECK_VOLUME_TOL, LSDEM_CHECK_INERTIA_TOL, r, err);
}

lsdem_status lsdem_shape_check_tol(const lsdem_shape *s, double volume_tol, double inertia_tol,
                                   lsdem_shape_report *r, lsdem_error *err)
{
  if (!s || !r) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  memset(r, 0, sizeof *r);
  r->volume_tol = volume_tol;
  r->inertia_tol = inertia_tol;
  if (s->nnodes < 1 || !s->nodes || !s->node_area)
    return lsdem_fail(err, LSDEM_ERR_ARG, "the shape has no nodes");
  if (!(s->volume > 0.0))
    return lsdem_fail(err, LSDEM_ERR_ARG, "the shape's volume %g is not positive", s->volume);
  r->radius_eq = cbrt(3.0 * s->volume / (4.0 * PI));
  double area = 0.0;
  for (int k = 0; k < s->nnodes; k++) area += s->node_area[k];
  r->node_spacing = sqrt(area / s->nnodes);
  if (r->node_spacing > 2.0 * r->radius_eq / 10.0) r->warnings |= LSDEM_CHECK_SPARSE_NODES;
  if (s->sdf.kind == LSDEM_SDF_GRID) {
    r->h = s->sdf.grid.h;
    if (lsdem_grid_is_coarse(r->h, s->volume)) r->warnings |= LSDEM_CHECK_COARSE_GRID;
    r->border_negative = border_negative(&s->sdf.grid);
    if (r->border_negative) r->warnings |= LSDEM_CHECK_OPEN_LEVEL_SET;
  }
  node_moments(s, &r->volume_nodes, r->inertia_nodes);
  r->volume_error = r->volume_nodes / s->volume - 1.0;
  if (!(fabs(r->volume_error) <= volume_tol)) r->warnings |= LSDEM_CHECK_VOLUME;
  for (int a = 0; a < 3; a++)
    r->inertia_error = fmax(r->inertia_error, s->inertia[a] > 0.0
                                                  ? fabs(r->inertia_nodes[a] / s->inertia[a] - 1.0)
                                                  : HUGE_VAL);
  if (!(r->inertia_error <= inertia_tol)) r->warnings |= LSDEM_CHECK_INERTIA;
  return LSDEM_OK;
}

size_t lsdem_shape_report_text(const lsdem_shape_report *r, char *buf, size_t size)
{
  char line[5][256];
  int nl = 0;
  if (r->warnings & LSDEM_CHECK_COARSE_GRID)
    snprintf(line[nl++], sizeof line[0], "grid spacing %g is coarser than R/10 = %g "
             "(R = %g, equivalent-sphere radius)\n", r->h, r->radius_eq / 10.0, r->radius_eq);
  if (r->warnings & LSDEM_CHECK_SPARSE_NODES)
    snprintf(line[nl++], sizeof line[0], "mean node spacing %g exceeds d/10 = %g "
             "(d = %g, equivalent-sphere diameter)\n", r->node_spacing, r->radius_eq / 5.0,
             2.0 * r->radius_eq);
  if (r->warnings & LSDEM_CHECK_OPEN_LEVEL_SET)
    snprintf(line[nl++], sizeof line[0], "zero level set not closed: %ld negative samples "
             "on the grid border\n", r->border_negative);
  if (r->warnings & LSDEM_CHECK_VOLUME)
    snprintf(line[nl++], sizeof line[0], "node volume %g differs from the shape volume by "
             "%+.2f%% (tolerance %.0f%%)\n", r->volume_nodes, 100.0 * r->volume_error,
             100.0 * r->volume_tol);
  if (r->warnings & LSDEM_CHECK_INERTIA)
    snprintf(line[nl++], sizeof line[0], "node moments of inertia differ from the shape's "
             "by up to %.2f%% (tolerance %.0f%%)\n", 100.0 * r->inertia_error,
             100.0 * r->inertia_tol);
  size_t need = 0;
  if (size) buf[0] = '\0';
  for (int i = 0; i < nl; i++) {
    const size_t len = strlen(line[i]);
    if (need + len < size) memcpy(buf + need, line[i], len + 1);
    need += len;
  }
  return need;
}
