/* test_net.c -- nets of bonded balls (core/specimen/net.c, net_file.c): the lattices
 * against their construction rules (counts by closed form, every bond one spacing long,
 * clamp flags on the chosen edges, an orthonormal frame for a tilted plane), the side of a
 * sagged net a point is on (worked by hand), the bond force
 * against a central difference of its energy and the damping against its definition, the
 * rupture criteria on either side of the limit, and the codec of the net file (round trip; a
 * bond to a missing ball, a repeated ball and a bad header refused with the line named) and
 * of the membrane's triangles file (round trip; bad files refused, named). */
#include "lsdem.h"
#include "lsdem_test.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double dist(const double *a, const double *b)
{
  double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

static double dot(const double *a, const double *b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Bonds counted per ball against the lattice's coordination: square 2 n1 n2 - n1 - n2;
 * hexagonal: n2 (n1 - 1) in rows + (n2 - 1)(2 n1 - 1) between rows. */
static void test_counts(int lattice, int n1, int n2)
{
  double a = 0.5;
  lsdem_net_params p = {lattice, {1, 2, 3}, {1, 0, 0}, {0, 1, 0},
                        {(n1 - 1) * a, (n2 - 1) * a * (lattice ? sqrt(3.0) / 2 : 1.0)},
                        a, 0.9 * a, LSDEM_NET_EDGE_U0 | LSDEM_NET_EDGE_V1};
  lsdem_net net;
  lsdem_error err;
  CHECK(lsdem_net_build(&p, &net, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(net.n1 == n1 && net.n2 == n2, "%d x %d, expected %d x %d", net.n1, net.n2, n1, n2);
  int expect = lattice == LSDEM_NET_SQUARE ? 2 * n1 * n2 - n1 - n2
                                           : n2 * (n1 - 1) + (n2 - 1) * (2 * n1 - 1);
  CHECK(net.nbonds == expect, "lattice %d: %d bonds, expected %d", lattice, net.nbonds, expect);
  for (int b = 0; b < net.nbonds; b++)
    CHECK_NEAR(dist(net.x + 3 * net.bond[2 * b], net.x + 3 * net.bond[2 * b + 1]), a, 1e-12);
  for (int j = 0; j < n2; j++)
    for (int i = 0; i < n1; i++) {
      int b = j * n1 + i;
      CHECK(net.clamp[b] == (i == 0 || j == n2 - 1), "ball (%d, %d) clamp %d", i, j,
            net.clamp[b]);
    }
  lsdem_net_free(&net);
}

static void test_frame(void)
{
  lsdem_net_params p = {LSDEM_NET_HEX, {0, 0, 5}, {2, 0, 2}, {1, 3, 0}, {4, 3}, 1.0, 1.0, 15};
  lsdem_net net;
  lsdem_error err;
  CHECK(lsdem_net_build(&p, &net, &err) == LSDEM_OK, "%s", err.msg);
  CHECK_NEAR(dot(net.e1, net.e1), 1.0, 1e-14);
  CHECK_NEAR(dot(net.e2, net.e2), 1.0, 1e-14);
  CHECK_NEAR(dot(net.e1, net.e2), 0.0, 1e-14);
  CHECK_NEAR(dot(net.normal, net.e1), 0.0, 1e-14);
  CHECK_NEAR(dot(net.normal, net.e2), 0.0, 1e-14);
  for (int b = 0; b < net.nballs; b++) {
    double uv[2];
    CHECK_NEAR(lsdem_net_height(&net, net.x + 3 * b, uv), 0.0, 1e-12);
    CHECK(uv[0] > -1e-12 && uv[0] < net.size[0] + 1e-12 && uv[1] > -1e-12 &&
              uv[1] < net.size[1] + 1e-12,
          "ball %d at (%g, %g) outside the footprint %g x %g", b, uv[0], uv[1], net.size[0],
          net.size[1]);
  }
  double above[3] = {net.origin[0] + 2 * net.normal[0], net.origin[1] + 2 * net.normal[1],
                     net.origin[2] + 2 * net.normal[2]}, uv[2];
  CHECK_NEAR(lsdem_net_height(&net, above, uv), 2.0, 1e-12);
  lsdem_net_free(&net);
  p.e2[0] = 4, p.e2[1] = 0, p.e2[2] = 4; /* parallel to e1 */
  CHECK(lsdem_net_build(&p, &net, &err) == LSDEM_ERR_ARG, "parallel directions accepted");
  p.e2[0] = 0, p.e2[1] = 1, p.e2[2] = 0;
  p.rest = 0.0;
  CHECK(lsdem_net_build(&p, &net, &err) == LSDEM_ERR_ARG, "zero rest length accepted");
}

/* lsdem_net_side on a 3 x 3 square net in z = 0 (n = +z) whose middle ball sagged to
 * z = -0.5: the side each point must be on, worked out by hand from the rule (nearest ball
 * in (u, v) over the footprint, the initial plane beside it). */
static void test_side(void)
{
  lsdem_net_params p = {LSDEM_NET_SQUARE, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 2}, 1.0, 1.0, 15};
  lsdem_net net;
  lsdem_error err;
  CHECK(lsdem_net_build(&p, &net, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(net.nballs == 9 && net.x[3 * 4] == 1.0 && net.x[3 * 4 + 1] == 1.0, "middle ball");
  net.x[3 * 4 + 2] = -0.5;
  static const struct {
    double x[3];
    int side;
  } cases[] = {
      {{1.1, 0.9, -0.3}, LSDEM_NET_BEFORE},  /* in the bulge, above the sagged ball */
      {{1.1, 0.9, -0.7}, LSDEM_NET_THROUGH}, /* below it */
      {{0.2, 0.1, -0.1}, LSDEM_NET_THROUGH}, /* nearest ball (0, 0) at z = 0 */
      {{0.2, 0.1, 0.1}, LSDEM_NET_BEFORE},
      {{3.0, 1.0, 0.5}, LSDEM_NET_BEFORE},   /* beside the footprint, on the normal's side */
      {{3.0, 1.0, -0.5}, LSDEM_NET_BESIDE},  /* beside it and past the plane */
      {{1.0, -0.1, -0.5}, LSDEM_NET_BESIDE},
  };
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    int side = lsdem_net_side(&net, net.x, cases[c].x);
    CHECK(side == cases[c].side, "point (%g, %g, %g): side %d, expected %d", cases[c].x[0],
          cases[c].x[1], cases[c].x[2], side, cases[c].side);
  }
  lsdem_net_free(&net);
}

/* f_j = -dE/dx_j (central difference of the returned energy); damping along the bond */
static void test_force(void)
{
  double xi[3] = {0.1, -0.2, 0.3}, xj[3] = {1.2, 0.4, -0.1}, v0[3] = {0, 0, 0}, fj[3], s;
  double k = 3.0, r0 = 0.8, h = 1e-6;
  lsdem_net_bond_force(xi, xj, v0, v0, k, r0, 0.0, fj, &s);
  CHECK_NEAR(s, dist(xi, xj) - r0, 1e-15);
  for (int d = 0; d < 3; d++) {
    double xp[3] = {xj[0], xj[1], xj[2]}, xm[3] = {xj[0], xj[1], xj[2]}, f[3];
    xp[d] += h;
    xm[d] -= h;
    double ep = lsdem_net_bond_force(xi, xp, v0, v0, k, r0, 0.0, f, &s);
    double em = lsdem_net_bond_force(xi, xm, v0, v0, k, r0, 0.0, f, &s);
    CHECK_NEAR(fj[d], -(ep - em) / (2 * h), 1e-8);
  }
  /* damping: the force changes by -c (v.u) u; a transverse velocity changes nothing */
  double u[3], vj[3], fd[3], c = 0.7;
  for (int d = 0; d < 3; d++) u[d] = (xj[d] - xi[d]) / dist(xi, xj);
  for (int d = 0; d < 3; d++) vj[d] = 2.0 * u[d];
  lsdem_net_bond_force(xi, xj, v0, vj, k, r0, c, fd, &s);
  for (int d = 0; d < 3; d++) CHECK_NEAR(fd[d] - fj[d], -c * 2.0 * u[d], 1e-14);
  double t[3] = {u[1], -u[0], 0.0};
  lsdem_net_bond_force(xi, xj, v0, t, k, r0, c, fd, &s);
  for (int d = 0; d < 3; d++) CHECK_NEAR(fd[d], fj[d], 1e-14);
  /* the damping power is minus the damping force's power on the relative motion,
   * -(fd - fj) . (vj - vi) = c (v.u)^2; a transverse velocity withdraws nothing */
  double vi[3] = {0.3, -0.1, 0.2}, vk[3] = {2.0 * u[0] + t[0], 2.0 * u[1] + t[1],
                                            2.0 * u[2] + t[2]};
  lsdem_net_bond_force(xi, xj, vi, vk, k, r0, c, fd, &s);
  double pw = 0.0;
  for (int d = 0; d < 3; d++) pw -= (fd[d] - fj[d]) * (vk[d] - vi[d]);
  CHECK_NEAR(lsdem_net_bond_damping_power(xi, xj, vi, vk, c), pw, 1e-14);
  CHECK(pw > 0.0, "damping power %g not positive", pw);
  CHECK_NEAR(lsdem_net_bond_damping_power(xi, xj, v0, t, c), 0.0, 1e-15);
  CHECK(lsdem_net_bond_damping_power(xi, xi, v0, vj, c) == 0.0, "zero length");
}

/* Joints: square n1 x n2 has n2 (n1 - 2) along rows and n1 (n2 - 2) along columns; the
 * hexagonal 3 x 3 net 3 in its rows and 4 across them (counted by hand: the middle row's
 * first two balls have both diagonals, the third none); each joint's ends are bonded to its
 * middle ball, at the spacing, on opposite sides */
static void test_joints(int lattice, int n1, int n2, int expect)
{
  double a = 0.5;
  lsdem_net_params p = {lattice, {0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                        {(n1 - 1) * a, (n2 - 1) * a * (lattice ? sqrt(3.0) / 2 : 1.0)},
                        a, a, 15};
  lsdem_net net;
  lsdem_error err;
  CHECK(lsdem_net_build(&p, &net, &err) == LSDEM_OK, "%s", err.msg);
  int *joint, nj;
  CHECK(lsdem_net_joints(&net, &joint, &nj, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(nj == expect, "lattice %d %d x %d: %d joints, expected %d", lattice, n1, n2, nj, expect);
  for (int k = 0; k < nj; k++) {
    const double *xp = net.x + 3 * joint[3 * k], *xb = net.x + 3 * joint[3 * k + 1],
                 *xq = net.x + 3 * joint[3 * k + 2];
    const double u[3] = {xp[0] - xb[0], xp[1] - xb[1], xp[2] - xb[2]};
    const double w[3] = {xq[0] - xb[0], xq[1] - xb[1], xq[2] - xb[2]};
    CHECK_NEAR(dist(xp, xb), a, 1e-12);
    CHECK_NEAR(dist(xq, xb), a, 1e-12);
    CHECK_NEAR(dot(u, w), -a * a, 1e-12);
    CHECK(joint[3 * k] < joint[3 * k + 2], "joint %d listed twice", k);
  }
  free(joint);
  lsdem_net_free(&net);
}

/* bending: forces are -dE/dx (central differences) and sum to zero with the middle ball's;
 * E = 0 on a straight line and kb d^2 / 2 + O(d^4) at a small bend d; no torque about the
 * middle ball (the forces only bend, they do not turn the joint) */
static void test_bend(void)
{
  const double kb = 2.5, h = 1e-6;
  double x1[3] = {-1.1, 0.2, 0.1}, x2[3] = {0.05, -0.1, 0.2}, x3[3] = {0.9, 0.3, -0.4};
  double f1[3], f3[3], g1[3], g3[3];
  lsdem_net_bend_force(x1, x2, x3, kb, f1, f3);
  double *ends[2] = {x1, x3}, *fend[2] = {f1, f3};
  for (int e = 0; e < 2; e++)
    for (int d = 0; d < 3; d++) {
      const double keep = ends[e][d];
      ends[e][d] = keep + h;
      const double ep = lsdem_net_bend_force(x1, x2, x3, kb, g1, g3);
      ends[e][d] = keep - h;
      const double em = lsdem_net_bend_force(x1, x2, x3, kb, g1, g3);
      ends[e][d] = keep;
      CHECK_NEAR(fend[e][d], -(ep - em) / (2 * h), 1e-8);
    }
  double f2[3], torque[3] = {0, 0, 0};
  for (int d = 0; d < 3; d++) f2[d] = -(f1[d] + f3[d]);
  for (int d = 0; d < 3; d++) { /* -dE/dx2 by central differences */
    const double keep = x2[d];
    x2[d] = keep + h;
    const double ep = lsdem_net_bend_force(x1, x2, x3, kb, g1, g3);
    x2[d] = keep - h;
    const double em = lsdem_net_bend_force(x1, x2, x3, kb, g1, g3);
    x2[d] = keep;
    CHECK_NEAR(f2[d], -(ep - em) / (2 * h), 1e-8);
  }
  for (int e = 0; e < 2; e++) {
    const double r[3] = {ends[e][0] - x2[0], ends[e][1] - x2[1], ends[e][2] - x2[2]};
    torque[0] += r[1] * fend[e][2] - r[2] * fend[e][1];
    torque[1] += r[2] * fend[e][0] - r[0] * fend[e][2];
    torque[2] += r[0] * fend[e][1] - r[1] * fend[e][0];
  }
  for (int d = 0; d < 3; d++) CHECK_NEAR(torque[d], 0.0, 1e-14);
  const double s1[3] = {-1.0, 0.0, 0.0}, s2[3] = {0.0, 0.0, 0.0}, s3[3] = {2.0, 0.0, 0.0};
  CHECK_NEAR(lsdem_net_bend_force(s1, s2, s3, kb, f1, f3), 0.0, 1e-15);
  for (int d = 0; d < 3; d++) CHECK(f1[d] == 0.0 && f3[d] == 0.0, "straight: no force");
  const double dth = 1e-3, b3[3] = {2.0 * cos(dth), 2.0 * sin(dth), 0.0};
  CHECK_REL(lsdem_net_bend_force(s1, s2, b3, kb, f1, f3), 0.5 * kb * dth * dth, 1e-6);
  CHECK_NEAR(lsdem_net_bend_force(s2, s2, s3, kb, f1, f3), kb, 0.0);
  CHECK(f1[0] == 0.0 && f3[0] == 0.0, "zero arm: no force");
}

static void test_breaks(void)
{
  CHECK(!lsdem_net_bond_breaks(LSDEM_NET_BREAK_STRAIN, 0.2, 5.0, 1.0, 0.19), "strain below");
  CHECK(lsdem_net_bond_breaks(LSDEM_NET_BREAK_STRAIN, 0.2, 5.0, 1.0, 0.21), "strain above");
  CHECK(!lsdem_net_bond_breaks(LSDEM_NET_BREAK_FORCE, 1.0, 5.0, 1.0, 0.19), "force below");
  CHECK(lsdem_net_bond_breaks(LSDEM_NET_BREAK_FORCE, 1.0, 5.0, 1.0, 0.21), "force above");
  CHECK(!lsdem_net_bond_breaks(LSDEM_NET_BREAK_NONE, 0.0, 5.0, 1.0, 100.0), "none");
}

static void write_text(const char *path, const char *text)
{
  FILE *f = fopen(path, "w");
  fputs(text, f);
  fclose(f);
}

static void test_file(void)
{
  lsdem_net_params p = {LSDEM_NET_SQUARE, {0, 0, 1}, {1, 0, 0}, {0, 0, 1}, {2, 1}, 1.0, 0.9,
                        LSDEM_NET_EDGE_U0 | LSDEM_NET_EDGE_U1};
  lsdem_net net, back;
  lsdem_error err;
  CHECK(lsdem_net_build(&p, &net, &err) == LSDEM_OK, "%s", err.msg);
  for (int b = 0; b < net.nballs; b++) net.id[b] = 100 + 7 * b;
  CHECK(lsdem_net_write("net_rt.net", &net, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_net_read("net_rt.net", &back, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(back.nballs == net.nballs && back.nbonds == net.nbonds && back.lattice == net.lattice,
        "counts after the round trip");
  for (int b = 0; b < net.nballs; b++)
    CHECK(back.id[b] == net.id[b] && back.clamp[b] == net.clamp[b], "ball %d", b);
  for (int b = 0; b < 2 * net.nbonds; b++) CHECK(back.bond[b] == net.bond[b], "bond end %d", b);
  for (int d = 0; d < 3; d++) CHECK(back.normal[d] == net.normal[d], "normal %d", d);
  CHECK(back.size[0] == net.size[0] && back.size[1] == net.size[1], "size");
  lsdem_net_free(&back);
  lsdem_net_free(&net);

  const char *head = "lsdem-net 1\nlattice square\ncounts 2 1\norigin 0 0 0\ne1 1 0 0\n"
                     "e2 0 1 0\nsize 1 0\nspacing 1\nrest 1\nballs 2\n5 1\n6 0\n";
  char text[1024];
  snprintf(text, sizeof text, "%sbonds 1\n5 7\n", head);
  write_text("net_missing.net", text);
  CHECK(lsdem_net_read("net_missing.net", &back, &err) == LSDEM_ERR_FORMAT, "missing ball");
  CHECK(strstr(err.msg, "line 14") && strstr(err.msg, "atom ID 7"), "message: %s", err.msg);
  snprintf(text, sizeof text, "%s", head);
  strcpy(strstr(text, "6 0\n"), "5 0\nbonds 0\n");
  write_text("net_twice.net", text);
  CHECK(lsdem_net_read("net_twice.net", &back, &err) == LSDEM_ERR_FORMAT, "repeated ball");
  CHECK(strstr(err.msg, "ball ID 5 is listed twice") != NULL, "message: %s", err.msg);
  write_text("net_header.net", "lsdem-membrane-triangles 1\n");
  CHECK(lsdem_net_read("net_header.net", &back, &err) == LSDEM_ERR_FORMAT, "bad header");
  CHECK(strstr(err.msg, "line 1") != NULL, "message: %s", err.msg);
}

/* The membrane's triangles file through the same codec: a file printed and read back gives
 * every value and ID (doubles to the printed 15 digits: the values here have fewer); a
 * triangle naming a vertex the file does not list, an unknown keyword, a missing section, a
 * bad row and a missing file are refused with the file (and line) named. */
static void test_membrane_file(void)
{
  long vertex[4] = {11, 12, 13, 14}, triangle[6] = {11, 12, 13, 12, 13, 14}, cap[2] = {11, 14};
  int vlayer[4] = {0, 0, 1, 1}, vend[4] = {1, 0, 0, 2}, tlayer[2] = {0, 1}, clayer[1] = {1},
      cend[1] = {2};
  lsdem_membrane_file mf = {{0.5, -0.25}, 3.5, {0.125, 0.25}, {12.5, 14.75}, 2, 4, 2, 1,
                            vertex, vlayer, vend, triangle, tlayer, cap, clayer, cend};
  FILE *f = fopen("mem_rt.tri", "w");
  lsdem_membrane_file_print(f, &mf, "a test file");
  fclose(f);
  lsdem_membrane_file back;
  lsdem_error err;
  CHECK(lsdem_membrane_file_read("mem_rt.tri", &back, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(back.axis[0] == 0.5 && back.axis[1] == -0.25 && back.specimen_radius == 3.5 &&
            back.sphere_radius[0] == 0.125 && back.sphere_radius[1] == 0.25 &&
            back.lateral_areas[0] == 12.5 && back.lateral_areas[1] == 14.75 && back.layers == 2,
        "scalars after the round trip");
  CHECK(back.nvertices == 4 && back.ntriangles == 2 && back.ncap_edges == 1, "counts");
  for (int v = 0; v < 4; v++)
    CHECK(back.vertex[v] == vertex[v] && back.vertex_layer[v] == vlayer[v] &&
              back.vertex_end[v] == vend[v], "vertex %d", v);
  for (int k = 0; k < 6; k++) CHECK(back.triangle[k] == triangle[k], "triangle corner %d", k);
  CHECK(back.triangle_layer[1] == 1 && back.cap_edge[0] == 11 && back.cap_edge[1] == 14 &&
            back.cap_layer[0] == 1 && back.cap_end[0] == 2, "triangle layer, cap edge");
  lsdem_membrane_file_free(&back);

  const char *head = "lsdem-membrane-triangles 1\naxis 0 0\nspecimen_radius 1\n"
                     "sphere_radius 0.1 0\nlayers 1\nlateral_areas 6 0\n"
                     "vertices 3\n1 0 1\n2 0 0\n3 0 2\n";
  char text[1024];
  snprintf(text, sizeof text, "%striangles 1\n1 2 9 0\ncap_edges 0\n", head);
  write_text("mem_missing.tri", text);
  CHECK(lsdem_membrane_file_read("mem_missing.tri", &back, &err) == LSDEM_ERR_FORMAT,
        "a missing vertex");
  CHECK(strstr(err.msg, "mem_missing.tri") && strstr(err.msg, "vertex 9"), "message: %s",
        err.msg);
  snprintf(text, sizeof text, "%sbogus 1\n", head);
  write_text("mem_key.tri", text);
  CHECK(lsdem_membrane_file_read("mem_key.tri", &back, &err) == LSDEM_ERR_FORMAT, "keyword");
  CHECK(strstr(err.msg, "line 11: unknown keyword") != NULL, "message: %s", err.msg);
  write_text("mem_short.tri", head);
  CHECK(lsdem_membrane_file_read("mem_short.tri", &back, &err) == LSDEM_ERR_FORMAT, "sections");
  CHECK(strstr(err.msg, "is incomplete") != NULL, "message: %s", err.msg);
  snprintf(text, sizeof text, "%s", head);
  strcpy(strstr(text, "3 0 2\n"), "3 0 3\n");
  write_text("mem_row.tri", text);
  CHECK(lsdem_membrane_file_read("mem_row.tri", &back, &err) == LSDEM_ERR_FORMAT, "bad end");
  CHECK(strstr(err.msg, "line 10: expected 'atom-ID layer end'") != NULL, "message: %s",
        err.msg);
  CHECK(lsdem_membrane_file_read("mem_none.tri", &back, &err) == LSDEM_ERR_IO, "no file");
  CHECK(strstr(err.msg, "cannot open triangles file mem_none.tri") != NULL, "message: %s",
        err.msg);
}

int main(void)
{
  test_counts(LSDEM_NET_SQUARE, 5, 4);
  test_counts(LSDEM_NET_HEX, 6, 5);
  test_counts(LSDEM_NET_HEX, 7, 1);
  test_frame();
  test_side();
  test_force();
  test_joints(LSDEM_NET_SQUARE, 5, 4, 4 * 3 + 5 * 2);
  test_joints(LSDEM_NET_HEX, 3, 3, 3 + 4);
  test_joints(LSDEM_NET_HEX, 7, 1, 5);
  test_bend();
  test_breaks();
  test_file();
  test_membrane_file();
  return lsdem_test_summary();
}
