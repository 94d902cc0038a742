/* test_surface.c -- marching-tetrahedra meshes of level sets (surface.c) against analytic
 * geometry: vertex positions, closedness and Euler characteristic, orientation, enclosed
 * volume and area; and the VTK/PLY writers. Topology and volume are recomputed here from
 * the triangles, independently of the mesh code. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static lsdem_sdf analytic(lsdem_sdf_kind kind, int inverted, double a0, double a1, double a2)
{
  lsdem_sdf s;
  memset(&s, 0, sizeof s);
  s.kind = kind, s.inverted = inverted;
  s.a[0] = a0, s.a[1] = a1, s.a[2] = a2;
  return s;
}

typedef struct {
  int a, b;
} edge;

static int edge_cmp(const void *x, const void *y)
{
  const edge *p = x, *q = y;
  const int pa = p->a < p->b ? p->a : p->b, pb = p->a < p->b ? p->b : p->a;
  const int qa = q->a < q->b ? q->a : q->b, qb = q->a < q->b ? q->b : q->a;
  return pa != qa ? (pa > qa) - (pa < qa) : (pb > qb) - (pb < qb);
}

/* Every undirected edge used by exactly two triangles, once in each direction (closed and
 * consistently oriented). Returns the number of distinct edges, or -1 when not closed. */
static int closed_edges(const lsdem_mesh *m)
{
  edge *e = malloc(3 * (size_t)m->ntris * sizeof *e);
  for (int t = 0; t < m->ntris; t++)
    for (int c = 0; c < 3; c++) {
      e[3 * t + c].a = m->tris[3 * t + c];
      e[3 * t + c].b = m->tris[3 * t + (c + 1) % 3];
    }
  const int n = 3 * m->ntris;
  qsort(e, (size_t)n, sizeof *e, edge_cmp);
  int distinct = 0, ok = n % 2 == 0;
  for (int i = 0; ok && i < n; i += 2) {
    ok = edge_cmp(&e[i], &e[i + 1]) == 0 && e[i].a == e[i + 1].b && e[i].b == e[i + 1].a &&
         (i + 2 >= n || edge_cmp(&e[i], &e[i + 2]) != 0);
    distinct++;
  }
  free(e);
  return ok ? distinct : -1;
}

/* Enclosed volume by the divergence theorem, sum det(p0, p1, p2) / 6. */
static double signed_volume(const lsdem_mesh *m)
{
  double v = 0.0;
  for (int t = 0; t < m->ntris; t++) {
    const double *a = m->verts + 3 * m->tris[3 * t], *b = m->verts + 3 * m->tris[3 * t + 1],
                 *c = m->verts + 3 * m->tris[3 * t + 2];
    v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
          a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
  }
  return v;
}

/* Triangles whose normal points towards the origin (for star-shaped solids about it). */
static int inward_triangles(const lsdem_mesh *m)
{
  int bad = 0;
  for (int t = 0; t < m->ntris; t++) {
    const double *a = m->verts + 3 * m->tris[3 * t], *b = m->verts + 3 * m->tris[3 * t + 1],
                 *c = m->verts + 3 * m->tris[3 * t + 2];
    double u[3], v[3], n[3], mid[3];
    for (int k = 0; k < 3; k++) u[k] = b[k] - a[k], v[k] = c[k] - a[k];
    for (int k = 0; k < 3; k++) mid[k] = (a[k] + b[k] + c[k]) / 3.0;
    n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    if (n[0] * mid[0] + n[1] * mid[1] + n[2] * mid[2] < 0.0) bad++;
  }
  return bad;
}

static void check_closed_sphere_topology(const lsdem_mesh *m, const char *what)
{
  const int ne = closed_edges(m);
  CHECK(ne > 0, "%s: mesh is not closed and consistently oriented", what);
  CHECK(m->nverts - ne + m->ntris == 2, "%s: Euler characteristic V - E + F = %d - %d + %d",
        what, m->nverts, ne, m->ntris);
}

/* Sphere of radius R sampled at h = R/10. A vertex is the root of the linear interpolant
 * of phi = |p| - R along a lattice edge of length L <= sqrt(3) h; phi'' <= 1/|p| along a
 * line, so |phi(vertex)| <= L^2 / (8 r_min), r_min >= R - sqrt(3) h (both ends of the
 * edge lie within L of the surface): | |v| - R | <= 3 h^2 / (8 (R - sqrt(3) h)) = 0.045 h. */
static void test_sphere(const lsdem_sdf *s, double R, double h, const char *what)
{
  lsdem_mesh m;
  lsdem_error err;
  CHECK(lsdem_mesh_extract(s, s->kind == LSDEM_SDF_GRID ? 0.0 : h, &m, &err) == LSDEM_OK,
        "%s: %s", what, err.msg);
  const double bound = 3.0 * h * h / (8.0 * (R - sqrt(3.0) * h)) + 1e-6 * R;
  double worst = 0.0;
  for (int v = 0; v < m.nverts; v++) {
    const double *p = m.verts + 3 * v;
    worst = fmax(worst, fabs(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - R));
  }
  printf("%s: %d vertices, %d triangles, max | |v| - R | = %.4f h (bound %.4f h)\n", what,
         m.nverts, m.ntris, worst / h, bound / h);
  CHECK(worst <= bound, "%s: vertex off the sphere by %g > %g", what, worst, bound);
  check_closed_sphere_topology(&m, what);
  CHECK(inward_triangles(&m) == 0, "%s: %d triangles face inward", what, inward_triangles(&m));
  const double vol = signed_volume(&m), area = lsdem_mesh_area(&m);
  printf("%s: volume %+.3f%%, area %+.3f%%\n", what, 100 * (vol / (4.0 / 3.0 * PI * R * R * R) - 1),
         100 * (area / (4.0 * PI * R * R) - 1));
  CHECK(vol > 0.0, "%s: signed volume %g not positive (inward orientation)", what, vol);
  CHECK_REL(vol, 4.0 / 3.0 * PI * R * R * R, 0.01);
  CHECK_REL(area, 4.0 * PI * R * R, 0.02);
  lsdem_mesh_free(&m);
}

static void test_box(void)
{
  const double half[3] = {1.0, 0.7, 0.5}, lo[3] = {-1.0, -0.7, -0.5}, h = 0.05;
  lsdem_sdf box = analytic(LSDEM_SDF_BOX, 0, 1.0, 0.7, 0.5);
  lsdem_sdf s;
  memset(&s, 0, sizeof s);
  lsdem_error err;
  CHECK(lsdem_grid_sample(&box, lo, half, h, 3, &s.grid, &err) == LSDEM_OK, "%s", err.msg);
  s.kind = LSDEM_SDF_GRID;
  lsdem_mesh m;
  CHECK(lsdem_mesh_extract(&s, 0.0, &m, &err) == LSDEM_OK, "%s", err.msg);
  check_closed_sphere_topology(&m, "box grid");
  const double vol = 8.0 * half[0] * half[1] * half[2],
               area = 8.0 * (half[0] * half[1] + half[1] * half[2] + half[0] * half[2]);
  printf("box grid h=%g: %d triangles, volume %+.3f%%, area %+.3f%%\n", h, m.ntris,
         100 * (signed_volume(&m) / vol - 1), 100 * (lsdem_mesh_area(&m) / area - 1));
  CHECK_REL(signed_volume(&m), vol, 0.02);
  CHECK_REL(lsdem_mesh_area(&m), area, 0.03);
  CHECK(inward_triangles(&m) == 0, "box: %d triangles face inward", inward_triangles(&m));
  /* every vertex within the box grown by a little (corners are cut, never bulge) */
  int outside = 0;
  for (int v = 0; v < m.nverts; v++)
    for (int k = 0; k < 3; k++) outside += fabs(m.verts[3 * v + k]) > half[k] + 1e-6;
  CHECK(outside == 0, "box: %d vertex coordinates beyond the faces", outside);
  lsdem_mesh_free(&m);
  lsdem_grid_free(&s.grid);
}

/* An analytic ellipsoid on a lattice of its own: closed, with the right volume. */
static void test_ellipsoid_analytic(void)
{
  lsdem_sdf e = analytic(LSDEM_SDF_ELLIPSOID, 0, 1.0, 0.6, 0.4);
  lsdem_mesh m;
  lsdem_error err;
  CHECK(lsdem_mesh_extract(&e, 0.04, &m, &err) == LSDEM_OK, "%s", err.msg);
  check_closed_sphere_topology(&m, "ellipsoid");
  const double vol = 4.0 / 3.0 * PI * 1.0 * 0.6 * 0.4;
  printf("ellipsoid h=0.04: volume %+.3f%%\n", 100 * (signed_volume(&m) / vol - 1));
  CHECK_REL(signed_volume(&m), vol, 0.01);
  lsdem_mesh_free(&m);
}

/* A grid whose zero level passes exactly through samples: phi = max(|i-5|, |j-5|, |k-5|) - 3
 * (h = 1) is zero on every sample of the cube [2, 8]^3's surface, and every lattice edge
 * that crosses the surface ends on such a sample. So every vertex must be one of these
 * samples, each at most once (no coincident copies), the triangles they collapse dropped,
 * and the rest closed; the solid lies between the inner cube [3, 7]^3 and the cube. */
static void test_exact_zero_samples(void)
{
  enum { N = 11 };
  float phi[N * N * N];
  for (int k = 0; k < N; k++)
    for (int j = 0; j < N; j++)
      for (int i = 0; i < N; i++)
        phi[i + N * (j + N * k)] = (float)(fmax(abs(i - 5), fmax(abs(j - 5), abs(k - 5))) - 3);
  lsdem_sdf s;
  memset(&s, 0, sizeof s);
  s.kind = LSDEM_SDF_GRID;
  s.grid.n[0] = s.grid.n[1] = s.grid.n[2] = N;
  s.grid.h = 1.0;
  s.grid.phi = phi;
  lsdem_mesh m;
  lsdem_error err;
  CHECK(lsdem_mesh_extract(&s, 0.0, &m, &err) == LSDEM_OK, "%s", err.msg);
  char seen[N * N * N];
  memset(seen, 0, sizeof seen);
  int off_sample = 0, repeated = 0;
  for (int v = 0; v < m.nverts; v++) {
    const double *p = m.verts + 3 * v;
    int c[3], dev = 0;
    for (int a = 0; a < 3; a++) {
      c[a] = (int)lround(p[a]);
      off_sample += fabs(p[a] - c[a]) > 1e-12 || c[a] < 0 || c[a] >= N;
      dev = abs(c[a] - 5) > dev ? abs(c[a] - 5) : dev;
    }
    off_sample += dev != 3;
    if (!off_sample) repeated += seen[c[0] + N * (c[1] + N * c[2])]++ > 0;
  }
  CHECK(off_sample == 0 && repeated == 0, "L-inf cube: %d vertices off the zero samples, "
        "%d repeated", off_sample, repeated);
  check_closed_sphere_topology(&m, "L-inf cube");
  const double vol = signed_volume(&m);
  CHECK(vol > 125.0 && vol <= 216.0 + 1e-9, "L-inf cube: volume %g not in (125, 216]", vol);
  lsdem_mesh_free(&m);
}

static void test_errors(void)
{
  lsdem_sdf plane = analytic(LSDEM_SDF_PLANE, 0, 0, 0, 0);
  lsdem_sdf inv = analytic(LSDEM_SDF_SPHERE, 1, 1, 0, 0);
  lsdem_mesh m;
  lsdem_error err;
  CHECK(lsdem_mesh_extract(&plane, 0.1, &m, &err) == LSDEM_ERR_ARG, "plane accepted");
  CHECK(strstr(err.msg, "unbounded") != NULL, "message: %s", err.msg);
  CHECK(lsdem_mesh_extract(&inv, 0.1, &m, &err) == LSDEM_ERR_ARG, "inverted sphere accepted");
  CHECK(lsdem_mesh_write_vtk("/nonexistent-dir/x.vtk", &m, &err) == LSDEM_ERR_IO, "no error");
}

/* The files carry the mesh: headers give the counts, the first vertex and last face. */
static void test_writers(void)
{
  lsdem_sdf s = analytic(LSDEM_SDF_SPHERE, 0, 1, 0, 0);
  lsdem_mesh m;
  lsdem_error err;
  CHECK(lsdem_mesh_extract(&s, 0.25, &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_mesh_write_vtk("surface_test.vtk", &m, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_mesh_write_ply("surface_test.ply", &m, &err) == LSDEM_OK, "%s", err.msg);
  char line[256];
  int np = -1, npoly = -1, nsize = -1, nv = -1, nf = -1;
  double x[3] = {0, 0, 0};
  FILE *f = fopen("surface_test.vtk", "r");
  while (f && fgets(line, sizeof line, f)) {
    if (sscanf(line, "POINTS %d double", &np) == 1)
      CHECK(fscanf(f, "%lf %lf %lf", &x[0], &x[1], &x[2]) == 3, "vtk point");
    sscanf(line, "POLYGONS %d %d", &npoly, &nsize);
  }
  if (f) fclose(f);
  CHECK(np == m.nverts && npoly == m.ntris && nsize == 4 * m.ntris, "vtk counts %d %d %d", np,
        npoly, nsize);
  CHECK_NEAR(x[0], m.verts[0], 1e-8);
  f = fopen("surface_test.ply", "r");
  int in_header = 1, last[4] = {0, 0, 0, 0}, rows = 0, bad_faces = 0;
  while (f && fgets(line, sizeof line, f)) {
    if (in_header) {
      sscanf(line, "element vertex %d", &nv);
      sscanf(line, "element face %d", &nf);
      in_header = strncmp(line, "end_header", 10) != 0;
    } else if (++rows > nv) {
      bad_faces += sscanf(line, "%d %d %d %d", &last[0], &last[1], &last[2], &last[3]) != 4;
    }
  }
  if (f) fclose(f);
  CHECK(nv == m.nverts && nf == m.ntris && rows == nv + nf && bad_faces == 0,
        "ply counts %d %d rows %d, %d bad faces", nv, nf, rows, bad_faces);
  CHECK(last[0] == 3 && last[3] == m.tris[3 * m.ntris - 1], "ply last face %d ... %d", last[0],
        last[3]);
  lsdem_mesh_free(&m);
}

int main(void)
{
  const double R = 1.0, h = R / 10.0;
  lsdem_sdf sphere = analytic(LSDEM_SDF_SPHERE, 0, R, 0, 0);
  test_sphere(&sphere, R, h, "analytic sphere");
  lsdem_sdf grid;
  memset(&grid, 0, sizeof grid);
  const double lo[3] = {-R, -R, -R}, hi[3] = {R, R, R};
  lsdem_error err;
  CHECK(lsdem_grid_sample(&sphere, lo, hi, h, 3, &grid.grid, &err) == LSDEM_OK, "%s", err.msg);
  grid.kind = LSDEM_SDF_GRID;
  test_sphere(&grid, R, h, "sphere grid R/10");
  lsdem_grid_free(&grid.grid);
  test_box();
  test_ellipsoid_analytic();
  test_exact_zero_samples();
  test_errors();
  test_writers();
  return lsdem_test_summary();
}
