/* net.c -- nets of bonded balls (report §4.4.2, Figure 4.6): the plane lattice generator
 * and the bond law. Conventions in lsdem_specimen.h ("nets"). Lengths, forces and times in
 * the caller's units. */
#include "lsdem_specimen.h"
#include "../base/lsdem_vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------- lattice ---- */

/* Unit e1, e2 (e2 made orthogonal to e1: Gram-Schmidt) and n = e1 x e2; 0 when either
 * direction is zero or they are parallel. */
static int plane_frame(const double a[3], const double b[3], double e1[3], double e2[3],
                       double n[3])
{
  double la = sqrt(lsdem_dot3(a, a));
  if (!(la > 0.0)) return 0;
  for (int k = 0; k < 3; k++) e1[k] = a[k] / la;
  double along = lsdem_dot3(b, e1);
  for (int k = 0; k < 3; k++) e2[k] = b[k] - along * e1[k];
  double lb = sqrt(lsdem_dot3(e2, e2));
  if (!(lb > 1e-12 * sqrt(lsdem_dot3(b, b)))) return 0;
  for (int k = 0; k < 3; k++) e2[k] /= lb;
  lsdem_cross3(e1, e2, n);
  return 1;
}

static double row_spacing(int lattice, double a)
{
  return lattice == LSDEM_NET_HEX ? a * sqrt(3.0) / 2.0 : a;
}

/* Offset of row j along e1, in spacings: odd rows of the hexagonal lattice by half. */
static double row_shift(int lattice, int j)
{
  return lattice == LSDEM_NET_HEX && j % 2 ? 0.5 : 0.0;
}

static int edge_bits(const lsdem_net *net, int i, int j)
{
  return (i == 0 ? LSDEM_NET_EDGE_U0 : 0) | (i == net->n1 - 1 ? LSDEM_NET_EDGE_U1 : 0) |
         (j == 0 ? LSDEM_NET_EDGE_V0 : 0) | (j == net->n2 - 1 ? LSDEM_NET_EDGE_V1 : 0);
}

static void place_balls(lsdem_net *net, int clamp_mask)
{
  double a = net->spacing, h = row_spacing(net->lattice, a);
  for (int j = 0, b = 0; j < net->n2; j++)
    for (int i = 0; i < net->n1; i++, b++) {
      double u = (i + row_shift(net->lattice, j)) * a, v = j * h;
      for (int k = 0; k < 3; k++)
        net->x[3 * b + k] = net->origin[k] + u * net->e1[k] + v * net->e2[k];
      net->clamp[b] = (edge_bits(net, i, j) & clamp_mask) != 0;
    }
}

static void add_bond(lsdem_net *net, int a, int b)
{
  net->bond[2 * net->nbonds] = a;
  net->bond[2 * net->nbonds + 1] = b;
  net->nbonds++;
}

/* In-row bonds; then to the next row: square straight up, hexagonal the two balls half a
 * spacing to either side (even row j: indices i - 1 and i of row j + 1; odd row: i, i + 1). */
static void connect(lsdem_net *net)
{
  int n1 = net->n1;
  for (int j = 0; j < net->n2; j++)
    for (int i = 0; i < n1; i++) {
      int b = j * n1 + i;
      if (i + 1 < n1) add_bond(net, b, b + 1);
      if (j + 1 == net->n2) continue;
      if (net->lattice == LSDEM_NET_SQUARE) {
        add_bond(net, b, b + n1);
        continue;
      }
      int lo = j % 2 ? i : i - 1;
      for (int ip = lo; ip <= lo + 1; ip++)
        if (ip >= 0 && ip < n1) add_bond(net, b, (j + 1) * n1 + ip);
    }
}

static lsdem_status check_params(const lsdem_net_params *p, lsdem_error *err)
{
  if (p->lattice != LSDEM_NET_SQUARE && p->lattice != LSDEM_NET_HEX)
    return lsdem_fail(err, LSDEM_ERR_ARG, "net: unknown lattice %d (square or hex)",
                      p->lattice);
  if (!(p->spacing > 0.0 && isfinite(p->spacing)) || !(p->rest > 0.0 && isfinite(p->rest)))
    return lsdem_fail(err, LSDEM_ERR_ARG, "net: spacing (%g) and rest length (%g) must be "
                      "positive", p->spacing, p->rest);
  if (!(p->extent[0] >= 0.0 && p->extent[1] >= 0.0 && isfinite(p->extent[0]) &&
        isfinite(p->extent[1])))
    return lsdem_fail(err, LSDEM_ERR_ARG, "net: extents (%g, %g) must be >= 0", p->extent[0],
                      p->extent[1]);
  return LSDEM_OK;
}

lsdem_status lsdem_net_build(const lsdem_net_params *p, lsdem_net *net, lsdem_error *err)
{
  memset(net, 0, sizeof(*net));
  lsdem_status st = check_params(p, err);
  if (st != LSDEM_OK) return st;
  if (!plane_frame(p->e1, p->e2, net->e1, net->e2, net->normal))
    return lsdem_fail(err, LSDEM_ERR_ARG, "net: the in-plane directions e1 and e2 must be "
                      "non-zero and not parallel");
  double n1 = floor(p->extent[0] / p->spacing + 0.5) + 1;
  double n2 = floor(p->extent[1] / row_spacing(p->lattice, p->spacing) + 0.5) + 1;
  if (n1 * n2 > 1e8)
    return lsdem_fail(err, LSDEM_ERR_ARG, "net: %g x %g balls is too many (spacing %g too "
                      "small for the extents?)", n1, n2, p->spacing);
  net->lattice = p->lattice;
  net->n1 = (int) n1;
  net->n2 = (int) n2;
  net->nballs = net->n1 * net->n2;
  net->spacing = p->spacing;
  net->rest = p->rest;
  memcpy(net->origin, p->origin, sizeof(net->origin));
  net->size[0] = (net->n1 - 1 + (net->lattice == LSDEM_NET_HEX && net->n2 > 1 ? 0.5 : 0.0)) *
                 p->spacing;
  net->size[1] = (net->n2 - 1) * row_spacing(p->lattice, p->spacing);
  size_t n = (size_t) net->nballs, nb = 3 * n;
  net->x = malloc(3 * n * sizeof(double));
  net->id = calloc(n, sizeof(long));
  net->clamp = malloc(n * sizeof(int));
  net->bond = malloc(2 * nb * sizeof(int));
  if (!net->x || !net->id || !net->clamp || !net->bond) {
    lsdem_net_free(net);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "net: out of memory for %zu balls", n);
  }
  place_balls(net, p->clamp);
  connect(net);
  return LSDEM_OK;
}

void lsdem_net_free(lsdem_net *net)
{
  free(net->x);
  free(net->id);
  free(net->clamp);
  free(net->bond);
  net->x = NULL;
  net->id = NULL;
  net->clamp = net->bond = NULL;
}

/* the bonded neighbours of every ball: nbr[6 b .. 6 b + count[b]) (at most 6 on these
 * lattices) */
static int neighbour_table(const lsdem_net *net, int *nbr, int *count)
{
  memset(count, 0, (size_t) net->nballs * sizeof(int));
  for (int e = 0; e < net->nbonds; e++)
    for (int s = 0; s < 2; s++) {
      const int b = net->bond[2 * e + s], other = net->bond[2 * e + 1 - s];
      if (count[b] == 6) return 0;
      nbr[6 * b + count[b]++] = other;
    }
  return 1;
}

/* p and q on opposite sides of b along one line: x_p + x_q = 2 x_b (to rounding) */
static int opposite(const lsdem_net *net, int p, int b, int q)
{
  double off = 0.0;
  for (int k = 0; k < 3; k++) {
    const double d = net->x[3 * p + k] + net->x[3 * q + k] - 2.0 * net->x[3 * b + k];
    off += d * d;
  }
  return off <= 1e-18 * net->spacing * net->spacing;
}

lsdem_status lsdem_net_joints(const lsdem_net *net, int **joint, int *njoints,
                              lsdem_error *err)
{
  *joint = NULL;
  *njoints = 0;
  if (!net->x) return lsdem_fail(err, LSDEM_ERR_ARG, "net joints: the positions as built "
                                 "are needed (a net read from a file has none)");
  const size_t n = (size_t) net->nballs;
  int *nbr = malloc(6 * n * sizeof(int)), *count = malloc(n * sizeof(int));
  int *out = malloc(3 * 3 * n * sizeof(int) + sizeof(int)); /* <= 3 lines through a ball */
  if (!nbr || !count || !out) {
    free(nbr), free(count), free(out);
    return lsdem_fail(err, LSDEM_ERR_NOMEM, "net joints: out of memory for %zu balls", n);
  }
  int nj = 0;
  if (neighbour_table(net, nbr, count))
    for (int b = 0; b < net->nballs; b++)
      for (int i = 0; i < count[b]; i++)
        for (int j = 0; j < count[b]; j++) {
          const int p = nbr[6 * b + i], q = nbr[6 * b + j];
          if (p < q && opposite(net, p, b, q)) {
            out[3 * nj] = p, out[3 * nj + 1] = b, out[3 * nj + 2] = q;
            nj++;
          }
        }
  else
    nj = -1;
  free(nbr);
  free(count);
  if (nj < 0) {
    free(out);
    return lsdem_fail(err, LSDEM_ERR_ARG, "net joints: a ball with more than 6 bonds");
  }
  *joint = out;
  *njoints = nj;
  return LSDEM_OK;
}

double lsdem_net_height(const lsdem_net *net, const double x[3], double uv[2])
{
  double d[3] = {x[0] - net->origin[0], x[1] - net->origin[1], x[2] - net->origin[2]};
  uv[0] = lsdem_dot3(d, net->e1);
  uv[1] = lsdem_dot3(d, net->e2);
  return lsdem_dot3(d, net->normal);
}

int lsdem_net_side(const lsdem_net *net, const double *xball, const double x[3])
{
  double uv[2];
  const double h = lsdem_net_height(net, x, uv);
  if (uv[0] < 0.0 || uv[0] > net->size[0] || uv[1] < 0.0 || uv[1] > net->size[1])
    return h >= 0.0 ? LSDEM_NET_BEFORE : LSDEM_NET_BESIDE;
  double best = INFINITY, hball = 0.0;
  for (int b = 0; b < net->nballs; b++) {
    double buv[2];
    const double hb = lsdem_net_height(net, xball + 3 * (size_t) b, buv);
    const double d2 = (buv[0] - uv[0]) * (buv[0] - uv[0]) + (buv[1] - uv[1]) * (buv[1] - uv[1]);
    if (d2 < best) {
      best = d2;
      hball = hb;
    }
  }
  return h < hball ? LSDEM_NET_THROUGH : LSDEM_NET_BEFORE;
}

/* --------------------------------------------------------------- bonds ---- */

double lsdem_bond_axis(const double xi[3], const double xj[3], double u[3])
{
  const double d[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
  const double len = sqrt(lsdem_dot3(d, d));
  for (int m = 0; m < 3; m++) u[m] = len > 0.0 ? d[m] / len : 0.0;
  return len;
}

/* report §4.4.2 ("K = 0.1") and §2.3.5 (Knbb): the axial spring of every ball bond, with
 * the axial damping term w = c (v . u) (0: none) */
double lsdem_bond_axial_force(const double u[3], double stretch, double k, double w,
                              double fj[3])
{
  const double fmag = k * stretch + w;
  for (int m = 0; m < 3; m++) fj[m] = -fmag * u[m];
  return 0.5 * k * stretch * stretch;
}

double lsdem_net_bond_force(const double xi[3], const double xj[3], const double vi[3],
                            const double vj[3], double k, double r0, double c, double fj[3],
                            double *stretch)
{
  double u[3];
  const double len = lsdem_bond_axis(xi, xj, u);
  *stretch = len - r0;
  fj[0] = fj[1] = fj[2] = 0.0;
  if (!(len > 0.0)) return 0.5 * k * r0 * r0;
  double v[3] = {vj[0] - vi[0], vj[1] - vi[1], vj[2] - vi[2]};
  return lsdem_bond_axial_force(u, *stretch, k, c * lsdem_dot3(v, u), fj);
}

double lsdem_net_bond_damping_power(const double xi[3], const double xj[3], const double vi[3],
                                    const double vj[3], double c)
{
  double d[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
  double len = sqrt(lsdem_dot3(d, d));
  if (!(len > 0.0) || c == 0.0) return 0.0;
  double v[3] = {vj[0] - vi[0], vj[1] - vi[1], vj[2] - vi[2]};
  double w = lsdem_dot3(v, d) / len;
  return c * w * w;
}

/* bending stiffness of the joints (lsdem_specimen.h): E = kb (1 + cos theta), the form of
 * LAMMPS's angle_style cosine, smooth through the straight line where the harmonic form in
 * theta has a 1 / sin(theta) */
double lsdem_net_bend_force(const double x1[3], const double x2[3], const double x3[3],
                            double kb, double f1[3], double f3[3])
{
  const double a[3] = {x1[0] - x2[0], x1[1] - x2[1], x1[2] - x2[2]};
  const double b[3] = {x3[0] - x2[0], x3[1] - x2[1], x3[2] - x2[2]};
  const double la = sqrt(lsdem_dot3(a, a)), lb = sqrt(lsdem_dot3(b, b));
  f1[0] = f1[1] = f1[2] = f3[0] = f3[1] = f3[2] = 0.0;
  if (!(la > 0.0 && lb > 0.0)) return kb;
  const double c = lsdem_dot3(a, b) / (la * lb);
  for (int m = 0; m < 3; m++) { /* -kb dc/dx1 and -kb dc/dx3 */
    f1[m] = -kb * (b[m] / lb - c * a[m] / la) / la;
    f3[m] = -kb * (a[m] / la - c * b[m] / lb) / lb;
  }
  return kb * (1.0 + c);
}

int lsdem_net_bond_breaks(int mode, double limit, double k, double r0, double stretch)
{
  if (mode == LSDEM_NET_BREAK_STRAIN) return stretch / r0 > limit;
  if (mode == LSDEM_NET_BREAK_FORCE) return k * stretch > limit;
  return 0;
}
