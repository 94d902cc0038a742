/* packing.c -- a packed sample from a shape library: random sequential addition of grains
 * at random positions and orientations in a box or a cylinder, without overlap by the
 * contact kernel's node test (see lsdem.h). World frame; lengths of the shapes. */
#include "lsdem_prep.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

double lsdem_container_volume(const lsdem_container *c)
{
  return c->kind == LSDEM_CONTAINER_BOX ? c->size[0] * c->size[1] * c->size[2]
                                        : PI * c->size[0] * c->size[0] * c->size[1];
}

void lsdem_container_bounds(const lsdem_container *c, double lo[3], double hi[3])
{
  if (c->kind == LSDEM_CONTAINER_BOX) {
    for (int a = 0; a < 3; a++) lo[a] = 0.0, hi[a] = c->size[a];
  } else {
    lo[0] = lo[1] = -c->size[0], hi[0] = hi[1] = c->size[0];
    lo[2] = 0.0, hi[2] = c->size[1];
  }
}

/* ------------------------------------------------------------------ probes ---- */

/* A shape whose nodes are pushed out by gap along the outward normal of its own level
 * set (cluster spheres and radius grown by gap), so that the kernel's "node inside the
 * other level set" test enforces a clearance. gap = 0: the shape itself. */
typedef struct {
  lsdem_shape s;
  double *nodes, *sphere;
  double rin; /* smallest |node| of the original: no surface point is nearer the centroid */
  lsdem_contact_point *found; /* the probe's manifold storage (its node count) */
} probe;

static lsdem_status probe_make(const lsdem_shape *s, double gap, probe *p, lsdem_error *err)
{
  memset(p, 0, sizeof *p);
  p->s = *s;
  p->rin = HUGE_VAL;
  p->found = malloc((size_t)lsdem_manifold_capacity(s) * sizeof *p->found + 1);
  if (!p->found) return lsdem_fail(err, LSDEM_ERR_NOMEM, "probe manifold");
  for (int k = 0; k < s->nnodes; k++) {
    const double *x = s->nodes + 3 * k;
    p->rin = fmin(p->rin, sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]));
  }
  if (!(gap > 0.0)) return LSDEM_OK;
  p->nodes = malloc(3 * (size_t)s->nnodes * sizeof(double) + 1);
  p->sphere = malloc(4 * (size_t)s->nclusters * sizeof(double) + 1);
  if (!p->nodes || !p->sphere) return lsdem_fail(err, LSDEM_ERR_NOMEM, "probe nodes");
  for (int k = 0; k < s->nnodes; k++) {
    double n[3];
    lsdem_sdf_eval(&s->sdf, s->nodes + 3 * k, n);
    for (int a = 0; a < 3; a++) p->nodes[3 * k + a] = s->nodes[3 * k + a] + gap * n[a];
  }
  for (int c = 0; c < s->nclusters; c++) {
    memcpy(p->sphere + 4 * c, s->cluster_sphere + 4 * c, 4 * sizeof(double));
    p->sphere[4 * c + 3] += gap;
  }
  p->s.nodes = p->nodes;
  p->s.cluster_sphere = p->sphere;
  p->s.radius = s->radius + gap;
  return LSDEM_OK;
}

static void probe_free(probe *p)
{
  free(p->nodes);
  free(p->sphere);
  free(p->found);
  p->nodes = p->sphere = NULL;
  p->found = NULL;
}

static void pose_of(const lsdem_placed *g, lsdem_pose *p)
{
  memset(p, 0, sizeof *p);
  memcpy(p->x, g->x, sizeof p->x);
  lsdem_quat_to_matrix(g->q, p->R);
}

/* Any node of probe A inside B's level set (the kernel's detection, every node). */
static int nodes_penetrate(const probe *A, const lsdem_pose *pa, const lsdem_shape *B,
                           const lsdem_pose *pb)
{
  const lsdem_detect_params every_node = {1, 0.0};
  lsdem_manifold m = lsdem_manifold_over(A->found, lsdem_manifold_capacity(&A->s));
  return lsdem_detect(&A->s, pa, B, pb, &every_node, 0, NULL, NULL, &m) > 0;
}

/* Overlap of two placed grains: bounding spheres, then nodes both ways. */
static int probes_overlap(const probe *pa, const lsdem_placed *a, const probe *pb,
                          const lsdem_placed *b)
{
  double d2 = 0.0;
  for (int k = 0; k < 3; k++) d2 += (a->x[k] - b->x[k]) * (a->x[k] - b->x[k]);
  const double reach = pa->s.radius + pb->s.radius; /* each grown by the gap */
  if (d2 > reach * reach) return 0;
  lsdem_pose A, B;
  pose_of(a, &A);
  pose_of(b, &B);
  /* probe nodes against the other's true level set (the probes share the level sets) */
  return nodes_penetrate(pa, &A, &pb->s, &B) || nodes_penetrate(pb, &B, &pa->s, &A);
}

/* ------------------------------------------------------------------- walls ---- */

enum { MAX_WALLS = 6 };

typedef struct {
  int n;
  lsdem_shape s[MAX_WALLS];
  lsdem_pose p[MAX_WALLS];
} walls;

/* A plane wall through x0 whose solid lies behind the inward normal n (unit): the plane
 * SDF's body +z maps to n, R = (t1, t2, n) as columns with t2 = n x t1. */
static void add_plane(walls *w, const double x0[3], const double n[3])
{
  lsdem_shape *s = &w->s[w->n];
  lsdem_pose *p = &w->p[w->n++];
  memset(s, 0, sizeof *s);
  memset(p, 0, sizeof *p);
  s->sdf.kind = LSDEM_SDF_PLANE;
  s->radius = HUGE_VAL;
  const double a[3] = {fabs(n[0]) < 0.9 ? 1.0 : 0.0, fabs(n[0]) < 0.9 ? 0.0 : 1.0, 0.0};
  double t1[3] = {a[1] * n[2] - a[2] * n[1], a[2] * n[0] - a[0] * n[2], a[0] * n[1] - a[1] * n[0]};
  const double l = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
  for (int k = 0; k < 3; k++) t1[k] /= l;
  const double t2[3] = {n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2],
                        n[0] * t1[1] - n[1] * t1[0]};
  for (int r = 0; r < 3; r++) {
    p->R[3 * r] = t1[r];
    p->R[3 * r + 1] = t2[r];
    p->R[3 * r + 2] = n[r];
    p->x[r] = x0[r];
  }
}

static void container_walls(const lsdem_container *c, walls *w)
{
  w->n = 0;
  const double height = c->kind == LSDEM_CONTAINER_BOX ? c->size[2] : c->size[1];
  const double o[3] = {0, 0, 0}, top[3] = {0, 0, height};
  const double up[3] = {0, 0, 1}, down[3] = {0, 0, -1};
  add_plane(w, o, up);
  add_plane(w, top, down);
  if (c->kind == LSDEM_CONTAINER_BOX) {
    const double ex[3] = {1, 0, 0}, mx[3] = {-1, 0, 0}, ey[3] = {0, 1, 0}, my[3] = {0, -1, 0};
    const double px[3] = {c->size[0], 0, 0}, py[3] = {0, c->size[1], 0};
    add_plane(w, o, ex);
    add_plane(w, px, mx);
    add_plane(w, o, ey);
    add_plane(w, py, my);
    return;
  }
  lsdem_shape *s = &w->s[w->n];
  lsdem_pose *p = &w->p[w->n++];
  memset(s, 0, sizeof *s);
  memset(p, 0, sizeof *p);
  s->sdf.kind = LSDEM_SDF_CYLINDER; /* infinite, inverted: the solid is outside radius R */
  s->sdf.inverted = 1;
  s->sdf.a[0] = c->size[0];
  s->radius = HUGE_VAL;
  p->R[0] = p->R[4] = p->R[8] = 1.0;
}

/* Distance from x to the nearest wall (negative outside the container). */
static double wall_clearance(const lsdem_container *c, const double x[3])
{
  if (c->kind == LSDEM_CONTAINER_BOX) {
    double d = HUGE_VAL;
    for (int a = 0; a < 3; a++) d = fmin(d, fmin(x[a], c->size[a] - x[a]));
    return d;
  }
  const double rho = sqrt(x[0] * x[0] + x[1] * x[1]);
  return fmin(c->size[0] - rho, fmin(x[2], c->size[1] - x[2]));
}

static int probe_outside(const probe *pr, const lsdem_placed *g, const lsdem_container *c,
                         const walls *w)
{
  if (wall_clearance(c, g->x) >= pr->s.radius) return 0;
  lsdem_pose A;
  pose_of(g, &A);
  for (int k = 0; k < w->n; k++)
    if (nodes_penetrate(pr, &A, &w->s[k], &w->p[k])) return 1;
  return 0;
}

/* ---------------------------------------------------------- public re-checks ---- */

int lsdem_pack_overlap(const lsdem_shape *sa, const lsdem_placed *a, const lsdem_shape *sb,
                       const lsdem_placed *b, double gap)
{
  probe pa, pb;
  memset(&pb, 0, sizeof pb);
  int r = -1;
  if (probe_make(sa, gap, &pa, NULL) == LSDEM_OK && probe_make(sb, gap, &pb, NULL) == LSDEM_OK)
    r = probes_overlap(&pa, a, &pb, b);
  probe_free(&pa);
  probe_free(&pb);
  return r != 0;
}

int lsdem_pack_outside(const lsdem_shape *s, const lsdem_placed *a, const lsdem_container *c,
                       double gap)
{
  probe p;
  walls w;
  container_walls(c, &w);
  int r = 1;
  if (probe_make(s, gap, &p, NULL) == LSDEM_OK) r = probe_outside(&p, a, c, &w);
  probe_free(&p);
  return r;
}

/* --------------------------------------------------------------- cell list ---- */

/* Placed grains binned by centre in cubes of side >= the largest pair reach, so every
 * possible overlap partner is in the 27 cells around a grain's cell. */
typedef struct {
  double lo[3], cs;
  int n[3];
  int *head, *next;
} cell_list;

static int cell_coord(const cell_list *L, const double x[3], int a)
{
  int i = (int)floor((x[a] - L->lo[a]) / L->cs);
  return i < 0 ? 0 : (i >= L->n[a] ? L->n[a] - 1 : i);
}

static lsdem_status cells_init(cell_list *L, const lsdem_container *c, double reach, int count,
                               lsdem_error *err)
{
  double hi[3];
  lsdem_container_bounds(c, L->lo, hi);
  L->cs = reach;
  for (;;) { /* at most ~4M cells */
    double total = 1.0;
    for (int a = 0; a < 3; a++) total *= floor((hi[a] - L->lo[a]) / L->cs) + 1.0;
    if (total <= 4194304.0) break;
    L->cs *= 2.0;
  }
  size_t nc = 1;
  for (int a = 0; a < 3; a++) {
    L->n[a] = (int)floor((hi[a] - L->lo[a]) / L->cs) + 1;
    nc *= (size_t)L->n[a];
  }
  L->head = malloc(nc * sizeof(int));
  L->next = malloc(((size_t)count + 1) * sizeof(int));
  if (!L->head || !L->next) return lsdem_fail(err, LSDEM_ERR_NOMEM, "cell list of %zu cells", nc);
  for (size_t i = 0; i < nc; i++) L->head[i] = -1;
  return LSDEM_OK;
}

static size_t cell_index(const cell_list *L, int i, int j, int k)
{
  return (size_t)i + (size_t)L->n[0] * ((size_t)j + (size_t)L->n[1] * k);
}

static void cells_add(cell_list *L, const double x[3], int id)
{
  const size_t c = cell_index(L, cell_coord(L, x, 0), cell_coord(L, x, 1), cell_coord(L, x, 2));
  L->next[id] = L->head[c];
  L->head[c] = id;
}

/* ------------------------------------------------------------------ packing ---- */

typedef struct {
  const lsdem_container *c;
  const walls *w;
  const probe *probes; /* per shape */
  const lsdem_placed *out;
  cell_list *cells;
} packer;

static int fits(const packer *P, const lsdem_placed *g)
{
  const probe *pg = &P->probes[g->shape];
  if (probe_outside(pg, g, P->c, P->w)) return 0;
  int c[3];
  for (int a = 0; a < 3; a++) c[a] = cell_coord(P->cells, g->x, a);
  for (int k = c[2] - 1; k <= c[2] + 1; k++)
    for (int j = c[1] - 1; j <= c[1] + 1; j++)
      for (int i = c[0] - 1; i <= c[0] + 1; i++) {
        if (i < 0 || j < 0 || k < 0 || i >= P->cells->n[0] || j >= P->cells->n[1] ||
            k >= P->cells->n[2])
          continue;
        for (int o = P->cells->head[cell_index(P->cells, i, j, k)]; o >= 0; o = P->cells->next[o])
          if (probes_overlap(pg, g, &P->probes[P->out[o].shape], &P->out[o])) return 0;
      }
  return 1;
}

/* Uniform random point of the container shrunk by `inset` (0 if it leaves nothing). */
static int random_position(const lsdem_container *c, double inset, uint64_t *rng, double x[3])
{
  if (c->kind == LSDEM_CONTAINER_BOX) {
    for (int a = 0; a < 3; a++) {
      const double span = c->size[a] - 2.0 * inset;
      if (!(span > 0.0)) return 0;
      x[a] = inset + span * lsdem_uniform01(rng);
    }
    return 1;
  }
  const double R = c->size[0] - inset, H = c->size[1] - 2.0 * inset;
  if (!(R > 0.0) || !(H > 0.0)) return 0;
  const double r = R * sqrt(lsdem_uniform01(rng)), t = 2.0 * PI * lsdem_uniform01(rng);
  x[0] = r * cos(t), x[1] = r * sin(t), x[2] = inset + H * lsdem_uniform01(rng);
  return 1;
}

void lsdem_random_quat(uint64_t *rng, double q[4])
{
  const double u1 = lsdem_uniform01(rng), u2 = lsdem_uniform01(rng), u3 = lsdem_uniform01(rng);
  const double a = sqrt(1.0 - u1), b = sqrt(u1);
  q[0] = b * cos(2.0 * PI * u3);
  q[1] = a * sin(2.0 * PI * u2);
  q[2] = a * cos(2.0 * PI * u2);
  q[3] = b * sin(2.0 * PI * u3);
}

static int pick_shape(int nshapes, const double *weights, double total, uint64_t *rng)
{
  if (!weights) return (int)(lsdem_splitmix64(rng) % (uint64_t)nshapes);
  double u = lsdem_uniform01(rng) * total;
  for (int k = 0; k < nshapes; k++) {
    if (u <= weights[k] && weights[k] > 0.0) return k;
    u -= weights[k];
  }
  return nshapes - 1;
}

typedef struct {
  double radius;
  int index, shape;
} order_item;

static int by_radius_desc(const void *pa, const void *pb)
{
  const order_item *a = pa, *b = pb;
  if (a->radius != b->radius) return a->radius < b->radius ? 1 : -1;
  return a->index - b->index;
}

static lsdem_status check_inputs(const lsdem_shape *shapes, int nshapes, const lsdem_container *c,
                                 const lsdem_pack_params *p, double *wtotal, lsdem_error *err)
{
  if (!shapes || !c || !p || nshapes < 1) return lsdem_fail(err, LSDEM_ERR_ARG, "no shapes");
  if (p->count < 0 || p->max_tries < 1 || !(p->gap >= 0.0))
    return lsdem_fail(err, LSDEM_ERR_ARG, "count %d, max tries %ld, gap %g: need >= 0, >= 1, >= 0",
                      p->count, p->max_tries, p->gap);
  for (int a = 0; a < (c->kind == LSDEM_CONTAINER_BOX ? 3 : 2); a++)
    if (!(c->size[a] > 0.0) || !isfinite(c->size[a]))
      return lsdem_fail(err, LSDEM_ERR_ARG, "container size %g: must be positive", c->size[a]);
  for (int k = 0; k < nshapes; k++)
    if (shapes[k].nnodes < 1 || !(shapes[k].radius > 0.0) || !isfinite(shapes[k].radius))
      return lsdem_fail(err, LSDEM_ERR_ARG, "shape %d has no nodes or no finite radius", k);
  *wtotal = 0.0;
  for (int k = 0; p->weights && k < nshapes; k++) {
    if (!(p->weights[k] >= 0.0) || !isfinite(p->weights[k]))
      return lsdem_fail(err, LSDEM_ERR_ARG, "weight %d (%g) must be >= 0", k, p->weights[k]);
    *wtotal += p->weights[k];
  }
  if (p->weights && !(*wtotal > 0.0))
    return lsdem_fail(err, LSDEM_ERR_ARG, "all shape weights are zero");
  return LSDEM_OK;
}

lsdem_status lsdem_pack(const lsdem_shape *shapes, int nshapes, const lsdem_container *c,
                        const lsdem_pack_params *p, lsdem_placed *out, int *placed,
                        lsdem_error *err)
{
  double wtotal = 0.0;
  if (placed) *placed = 0;
  if (!out || !placed) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL output");
  lsdem_status st = check_inputs(shapes, nshapes, c, p, &wtotal, err);
  if (st != LSDEM_OK) return st;
  uint64_t rng = p->seed;
  probe *probes = calloc((size_t)nshapes, sizeof *probes);
  order_item *order = malloc(((size_t)p->count + 1) * sizeof *order);
  cell_list cells = {{0, 0, 0}, 0, {0, 0, 0}, NULL, NULL};
  if (!probes || !order) st = lsdem_fail(err, LSDEM_ERR_NOMEM, "packing %d grains", p->count);
  double rmax = 0.0;
  for (int k = 0; st == LSDEM_OK && k < nshapes; k++) {
    st = probe_make(&shapes[k], p->gap, &probes[k], err);
    rmax = fmax(rmax, probes[k].s.radius);
  }
  for (int i = 0; st == LSDEM_OK && i < p->count; i++) {
    order[i].index = i;
    order[i].shape = pick_shape(nshapes, p->weights, wtotal, &rng);
    order[i].radius = shapes[order[i].shape].radius;
  }
  if (st == LSDEM_OK) {
    qsort(order, (size_t)p->count, sizeof *order, by_radius_desc);
    st = cells_init(&cells, c, 2.0 * rmax, p->count, err);
  }
  walls w;
  container_walls(c, &w);
  const packer P = {c, &w, probes, out, &cells};
  int n = 0;
  for (int i = 0; st == LSDEM_OK && i < p->count; i++) {
    lsdem_placed *g = &out[n];
    g->shape = order[i].shape;
    const double inset = probes[g->shape].rin + p->gap;
    for (long t = 0; t < p->max_tries; t++) {
      if (!random_position(c, inset, &rng, g->x)) break;
      lsdem_random_quat(&rng, g->q);
      if (fits(&P, g)) {
        cells_add(&cells, g->x, n++);
        break;
      }
    }
  }
  *placed = n;
  for (int k = 0; probes && k < nshapes; k++) probe_free(&probes[k]);
  free(probes);
  free(order);
  free(cells.head);
  free(cells.next);
  return st;
}
