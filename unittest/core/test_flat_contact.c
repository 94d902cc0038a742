/* test_flat_contact.c -- lsdem_flat_contact_nodes, the most nodes one flat contact presses:
 *   - a box with a node lattice on its faces: the largest face's nodes (its n x m lattice,
 *     counted here), and under the traction law their summed areas, also when the box is
 *     given its nodes in any order;
 *   - nodes evenly spread on a sphere (a Fibonacci set of N): the cap within depth
 *     0.02 R of the pole holds N * 0.02 / 2 nodes (area fraction of a spherical cap);
 *   - an analytic sphere: one contact point (or its contact area). */
#include "lsdem_test.h"

#include <stdlib.h>

/* nodes on the surface of the box [-hx, hx] x [-hy, hy] x [-hz, hz], a lattice of spacing
 * h on each face (edges and corners once); returns the node count, fills area with a
 * per-node weight (1 + x^2: not uniform, to tell a sum of areas from a count) */
static int box_nodes(double hx, double hy, double hz, double h, double *nodes, double *area)
{
  const int nx = (int) lround(2 * hx / h), ny = (int) lround(2 * hy / h),
            nz = (int) lround(2 * hz / h);
  int n = 0;
  for (int i = 0; i <= nx; i++)
    for (int j = 0; j <= ny; j++)
      for (int k = 0; k <= nz; k++) {
        if (i > 0 && i < nx && j > 0 && j < ny && k > 0 && k < nz) continue; /* inside */
        double *p = nodes + 3 * n;
        p[0] = -hx + i * h;
        p[1] = -hy + j * h;
        p[2] = -hz + k * h;
        area[n++] = 1.0 + p[0] * p[0];
      }
  return n;
}

static void test_box(void)
{
  static double nodes[3 * 2000], area[2000];
  const double hx = 1.0, hy = 0.5, hz = 0.3, h = 0.1;
  lsdem_shape s = {0};
  s.sdf.kind = LSDEM_SDF_BOX;
  s.nnodes = box_nodes(hx, hy, hz, h, nodes, area);
  s.nodes = nodes;
  s.node_area = area;
  s.radius = sqrt(hx * hx + hy * hy + hz * hz);
  /* the largest face is z = +-hz: (2 hx / h + 1) x (2 hy / h + 1) nodes; the depth
   * 0.02 |h| = 0.023 is below the spacing, so no second layer joins */
  const int fx = 21, fy = 11;
  double face_area = 0.0;
  for (int i = 0; i < fx; i++) {
    const double x = -hx + i * h;
    face_area += fy * (1.0 + x * x);
  }
  CHECK_NEAR(lsdem_flat_contact_nodes(&s, LSDEM_NORMAL_PER_NODE), fx * fy, 0.0);
  CHECK_REL(lsdem_flat_contact_nodes(&s, LSDEM_NORMAL_TRACTION), face_area, 1e-12);
  /* the same nodes in reverse order */
  for (int a = 0, b = s.nnodes - 1; a < b; a++, b--) {
    for (int d = 0; d < 3; d++) {
      const double t = nodes[3 * a + d];
      nodes[3 * a + d] = nodes[3 * b + d];
      nodes[3 * b + d] = t;
    }
    const double t = area[a];
    area[a] = area[b];
    area[b] = t;
  }
  CHECK_NEAR(lsdem_flat_contact_nodes(&s, LSDEM_NORMAL_PER_NODE), fx * fy, 0.0);
}

static void test_round(void)
{
  enum { N = 20000 };
  static double nodes[3 * N], area[N];
  const double R = 2.0, golden = M_PI * (3.0 - sqrt(5.0));
  for (int k = 0; k < N; k++) { /* rotated away from the function's own directions */
    const double z = 1.0 - (2.0 * k + 1.0) / N, r = sqrt(1.0 - z * z);
    const double x = r * cos(golden * k + 0.3), y = r * sin(golden * k + 0.3);
    nodes[3 * k] = R * x;
    nodes[3 * k + 1] = R * (0.6 * y + 0.8 * z);
    nodes[3 * k + 2] = R * (-0.8 * y + 0.6 * z);
    area[k] = 4.0 * M_PI * R * R / N;
  }
  lsdem_shape s = {0};
  s.sdf.kind = LSDEM_SDF_GRID;
  s.nnodes = N;
  s.nodes = nodes;
  s.node_area = area;
  s.radius = R;
  /* a cap of height d on a sphere holds the fraction d / (2R) of its surface */
  const double cap = N * LSDEM_FLAT_CONTACT_DEPTH / 2.0;
  CHECK_REL(lsdem_flat_contact_nodes(&s, LSDEM_NORMAL_PER_NODE), cap, 0.1);
  CHECK_REL(lsdem_flat_contact_nodes(&s, LSDEM_NORMAL_TRACTION),
            2.0 * M_PI * R * (LSDEM_FLAT_CONTACT_DEPTH * R), 0.1);
}

static void test_analytic_sphere(void)
{
  lsdem_shape s = {0};
  s.sdf.kind = LSDEM_SDF_SPHERE;
  s.sdf.a[0] = 0.5;
  s.radius = 0.5;
  CHECK_NEAR(lsdem_flat_contact_nodes(&s, LSDEM_NORMAL_PER_NODE), 1.0, 0.0);
  CHECK_REL(lsdem_flat_contact_nodes(&s, LSDEM_NORMAL_TRACTION), M_PI * 0.25, 1e-15);
}

int main(void)
{
  test_box();
  test_round();
  test_analytic_sphere();
  return lsdem_test_summary();
}
