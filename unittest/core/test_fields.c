/* test_fields.c -- continuum fields (core/fields): affine fields recovered exactly on a
 * random packing, rigid rotations strain-free, FFT against direct summation, totals kept,
 * the cylinder mask and the .vti file; periodic boxes (affine maps of the box recovered at
 * every node, the fit against a brute-force minimum-image sum, the open grid as the
 * control); tilted (triclinic) boxes (their skewed grid: affine maps recovered at every
 * node, FFT against direct, kernel weights at Cartesian distances, the surface mask); the
 * surface mask (point in closed surface). */
#include "lsdem_test.h"

#include "fields/lsdem_fields.h"

#include <stdlib.h>
#include <string.h>

#define NGRAINS 400
#define BOX 10.0

static const lsdem_field_params PARAMS = {1.0, 0.5, LSDEM_FIELD_MIN_VARIANCE,
                                         LSDEM_FIELD_MIN_WEIGHT, {{0}, {0}, {0}, {0}, {{0}}}};

/* a random loose packing: centres uniform in the box, masses and volumes in (0.5, 1.5] */
static void random_grains(lsdem_field_grain *g, int n)
{
  for (int i = 0; i < n; i++) {
    g[i].mass = 0.5 + urand();
    g[i].volume = 0.4 * (0.5 + urand());
    for (int k = 0; k < 3; k++) g[i].x[k] = BOX * urand();
  }
}

/* grains moved by the map x -> F x about the box centre: u = (F - I)(X - c) */
static void deform(lsdem_field_grain *g, int n, const double F[9])
{
  const double c = 0.5 * BOX;
  for (int i = 0; i < n; i++) {
    double X[3], y[3];
    for (int k = 0; k < 3; k++) X[k] = g[i].x[k] - c;
    lsdem_mat_vec(F, X, y);
    for (int k = 0; k < 3; k++) {
      g[i].u[k] = y[k] - X[k];
      g[i].x[k] = y[k] + c;
    }
  }
}

static double max_abs(const double *a, int n)
{
  double m = 0.0;
  for (int k = 0; k < n; k++) m = fabs(a[k]) > m ? fabs(a[k]) : m;
  return m;
}

/* H = F - I recovered at every regular node; both strains as the formulas say */
static void check_affine(const char *name, const double F[9])
{
  static lsdem_field_grain g[NGRAINS];
  random_grains(g, NGRAINS);
  deform(g, NGRAINS, F);
  lsdem_fields f;
  lsdem_error err;
  CHECK(lsdem_fields_compute(&PARAMS, NGRAINS, g, 0, NULL, &f, &err) == LSDEM_OK, "%s", err.msg);
  double H[9], small[9], green[9], C[9];
  for (int k = 0; k < 9; k++) H[k] = F[k] - (k % 4 == 0 ? 1.0 : 0.0);
  lsdem_matT_mul(F, F, C);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      small[3 * i + j] = 0.5 * (H[3 * i + j] + H[3 * j + i]);
      green[3 * i + j] = 0.5 * (C[3 * i + j] - (i == j));
    }
  const size_t nodes = lsdem_field_grid_nodes(&f.grid);
  size_t regular = 0;
  double err_grad = 0.0, err_small = 0.0, err_green = 0.0;
  for (size_t node = 0; node < nodes; node++) {
    if (!f.regular[node]) continue;
    regular++;
    for (int k = 0; k < 9; k++) {
      err_grad = fmax(err_grad, fabs(f.grad[9 * node + k] - H[k]));
      err_small = fmax(err_small, fabs(f.strain_small[9 * node + k] - small[k]));
      err_green = fmax(err_green, fabs(f.strain_green[9 * node + k] - green[k]));
    }
  }
  /* the specimen's interior at least: the box is about a third of the padded grid */
  CHECK(regular > nodes / 8, "%s: %zu regular nodes of %zu", name, regular, nodes);
  CHECK(err_grad <= 1e-10 * max_abs(H, 9), "%s: gradient off by %.3g", name, err_grad);
  CHECK(err_small <= 1e-10 * max_abs(small, 9), "%s: small strain off by %.3g", name, err_small);
  CHECK(err_green <= 1e-10 * max_abs(green, 9), "%s: Green strain off by %.3g", name, err_green);
  lsdem_fields_free(&f);
}

/* The control: the plain mass-weighted average of the displacements, ubar = (m u * phi) /
 * (m * phi) on the same grid and kernel, differentiated by central differences, is NOT the
 * imposed gradient on a random packing (the weighted centre of the grains under a node is
 * not the node): it is off by more than 1 % of H somewhere in the interior, where the
 * local-linear fit above is exact to 1e-10. */
static void check_plain_average_fails(void)
{
  static lsdem_field_grain g[NGRAINS];
  const double F[9] = {1, 0.01, 0, 0, 1, 0, 0, 0, 1};
  random_grains(g, NGRAINS);
  deform(g, NGRAINS, F);
  const double lo[3] = {0, 0, 0}, hi[3] = {BOX + 0.1, BOX, BOX};
  lsdem_field_grid grid;
  CHECK(lsdem_field_grid_cover(lo, hi, PARAMS.h, PARAMS.width, &grid, NULL) == LSDEM_OK, "grid");
  const size_t nodes = lsdem_field_grid_nodes(&grid);
  double *ch = calloc(2 * nodes, sizeof(double));
  for (int i = 0; i < NGRAINS; i++) {
    const double v[2] = {g[i].mass, g[i].mass * g[i].u[0]};
    lsdem_field_deposit(&grid, g[i].x, 2, v, ch);
  }
  CHECK(lsdem_field_smooth_fft(&grid, PARAMS.width, 2, ch, NULL) == LSDEM_OK, "smooth");
  /* d ubar_x / dy at nodes 2 kernel widths inside the box */
  const int *n = grid.n, inset = (int)ceil(2.0 * PARAMS.width / PARAMS.h);
  double worst = 0.0;
  for (int i2 = 0; i2 < n[2]; i2++)
    for (int i1 = 1; i1 < n[1] - 1; i1++)
      for (int i0 = 0; i0 < n[0]; i0++) {
        const double x[3] = {grid.origin[0] + grid.h[0] * i0, grid.origin[1] + grid.h[1] * i1,
                             grid.origin[2] + grid.h[2] * i2};
        int interior = 1;
        for (int k = 0; k < 3; k++)
          interior &= x[k] > lo[k] + inset * grid.h[k] && x[k] < hi[k] - inset * grid.h[k];
        if (!interior) continue;
        const size_t node = (size_t)i0 + (size_t)n[0] * ((size_t)i1 + (size_t)n[1] * i2);
        const size_t up = node + (size_t)n[0], down = node - (size_t)n[0];
        const double dudy =
            (ch[nodes + up] / ch[up] - ch[nodes + down] / ch[down]) / (2 * grid.h[1]);
        worst = fmax(worst, fabs(dudy - 0.01));
      }
  CHECK(worst > 0.01 * 0.01, "the plain average came out affine too (off by %.3g)", worst);
  free(ch);
}

/* a rigid rotation by 30 degrees: no Green strain, the rotation vector everywhere */
static void check_rotation(void)
{
  static lsdem_field_grain g[NGRAINS];
  const double angle = 30.0 * M_PI / 180.0;
  const double axis[3] = {1.0 / sqrt(3.0), 1.0 / sqrt(3.0), 1.0 / sqrt(3.0)};
  double q[4] = {cos(angle / 2), sin(angle / 2) * axis[0], sin(angle / 2) * axis[1],
                 sin(angle / 2) * axis[2]}, R[9];
  lsdem_quat_to_matrix(q, R);
  random_grains(g, NGRAINS);
  deform(g, NGRAINS, R);
  lsdem_fields f;
  lsdem_error err;
  CHECK(lsdem_fields_compute(&PARAMS, NGRAINS, g, 0, NULL, &f, &err) == LSDEM_OK, "%s", err.msg);
  const size_t nodes = lsdem_field_grid_nodes(&f.grid);
  double e = 0.0, erot = 0.0;
  size_t regular = 0;
  for (size_t node = 0; node < nodes; node++) {
    if (!f.regular[node]) continue;
    regular++;
    e = fmax(e, max_abs(f.strain_green + 9 * node, 9));
    for (int k = 0; k < 3; k++) erot = fmax(erot, fabs(f.rotation[3 * node + k] - angle * axis[k]));
  }
  CHECK(regular > nodes / 8, "rotation: %zu regular nodes of %zu", regular, nodes);
  CHECK(e <= 1e-12, "30 degree rotation: Green strain %.3g", e);
  CHECK(erot <= 1e-10, "30 degree rotation: rotation vector off by %.3g", erot);
  lsdem_fields_free(&f);
}

/* FFT and direct summation agree on random deposits */
static void check_fft_direct(void)
{
  const double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {3.0, 2.0, 2.5};
  const double width = 0.6, h = 0.25;
  lsdem_field_grid g;
  CHECK(lsdem_field_grid_cover(lo, hi, h, width, &g, NULL) == LSDEM_OK, "grid");
  const size_t nodes = lsdem_field_grid_nodes(&g);
  double *a = calloc(2 * nodes, sizeof(double)), *b = calloc(2 * nodes, sizeof(double));
  for (int i = 0; i < 50; i++) {
    const double x[3] = {hi[0] * urand(), hi[1] * urand(), hi[2] * urand()};
    const double v[2] = {urand(), srand1()};
    lsdem_field_deposit(&g, x, 2, v, a);
  }
  memcpy(b, a, 2 * nodes * sizeof(double));
  const double deposited = max_abs(a, (int)(2 * nodes));
  CHECK(lsdem_field_smooth_fft(&g, width, 2, a, NULL) == LSDEM_OK, "fft");
  CHECK(lsdem_field_smooth_direct(&g, width, 2, b, NULL) == LSDEM_OK, "direct");
  double diff = 0.0, scale = max_abs(b, (int)(2 * nodes));
  for (size_t k = 0; k < 2 * nodes; k++) diff = fmax(diff, fabs(a[k] - b[k]));
  CHECK(diff <= 1e-12 * scale, "FFT against direct: %.3g of %.3g", diff, scale);
  /* the smoothing spread the deposits: its peak is well below theirs */
  CHECK(scale < 0.2 * deposited, "smoothed peak %g, deposited %g", scale, deposited);
  free(a);
  free(b);
}

/* sum density h^3 = total mass, sum solid fraction h^3 = total volume, sum stress h^3 =
 * minus the Love-Weber moment of the branches */
static void check_totals(void)
{
  static lsdem_field_grain g[NGRAINS];
  enum { NB = 300 };
  static lsdem_field_branch b[NB];
  random_grains(g, NGRAINS);
  double mass = 0.0, volume = 0.0, M[9] = {0.0}, sigma[9];
  for (int i = 0; i < NGRAINS; i++) {
    mass += g[i].mass;
    volume += g[i].volume;
    for (int k = 0; k < 3; k++) g[i].u[k] = 0.0;
  }
  for (int i = 0; i < NB; i++) {
    const lsdem_field_grain *gr = g + (i * 7) % NGRAINS;
    for (int k = 0; k < 3; k++) {
      b[i].force[k] = srand1();
      b[i].centre[k] = gr->x[k];
      b[i].point[k] = gr->x[k] + 0.5 * srand1();
    }
    lsdem_love_weber_add(M, b[i].force, b[i].point, b[i].centre);
  }
  lsdem_love_weber_stress(M, 1.0, sigma);
  lsdem_fields f;
  CHECK(lsdem_fields_compute(&PARAMS, NGRAINS, g, NB, b, &f, NULL) == LSDEM_OK, "compute");
  const size_t nodes = lsdem_field_grid_nodes(&f.grid);
  const double dv = f.grid.h[0] * f.grid.h[1] * f.grid.h[2];
  double m = 0.0, v = 0.0, s[9] = {0.0};
  for (size_t node = 0; node < nodes; node++) {
    m += f.density[node] * dv;
    v += f.solid_fraction[node] * dv;
    for (int k = 0; k < 9; k++) s[k] += f.stress[9 * node + k] * dv;
  }
  CHECK_REL(m, mass, 1e-12);
  CHECK_REL(v, volume, 1e-12);
  for (int k = 0; k < 9; k++) CHECK_NEAR(s[k], sigma[k], 1e-10 * max_abs(sigma, 9));
  /* the fields are smooth, not the deposits: the peak density is far below a grain's mass
   * in one voxel */
  CHECK(max_abs(f.density, (int)nodes) < 0.5 / dv, "peak density %g", max_abs(f.density, (int)nodes));

  /* cylinder mask: outside NaN, inside untouched */
  const double centre[2] = {5.0, 5.0};
  const double before = f.density[nodes / 2];
  lsdem_fields_mask_cylinder(&f, centre, 3.0, 1.0, 9.0);
  size_t inside = 0;
  for (size_t node = 0; node < nodes; node++) {
    const int i0 = (int)(node % (size_t)f.grid.n[0]);
    const int i1 = (int)(node / (size_t)f.grid.n[0] % (size_t)f.grid.n[1]);
    const int i2 = (int)(node / ((size_t)f.grid.n[0] * f.grid.n[1]));
    const double x = f.grid.origin[0] + f.grid.h[0] * i0 - 5.0;
    const double y = f.grid.origin[1] + f.grid.h[1] * i1 - 5.0;
    const double z = f.grid.origin[2] + f.grid.h[2] * i2;
    const int in = x * x + y * y <= 9.0 && z >= 1.0 && z <= 9.0;
    inside += in;
    if (in != f.inside[node] || in != !isnan(f.stress[9 * node]) || in != !isnan(f.density[node])) {
      CHECK(0, "mask wrong at node %zu", node);
      break;
    }
  }
  CHECK(inside > 0 && inside < nodes, "%zu nodes inside of %zu", inside, nodes);
  CHECK(isnan(f.density[nodes / 2]) || f.density[nodes / 2] == before, "masked a node inside");
  lsdem_fields_free(&f);
}

/* the .vti holds the arrays' bits: the first (density) read back after its byte count */
static void check_vti(void)
{
  static lsdem_field_grain g[50];
  random_grains(g, 50);
  lsdem_fields f;
  lsdem_error err;
  CHECK(lsdem_fields_compute(&PARAMS, 50, g, 0, NULL, &f, NULL) == LSDEM_OK, "compute");
  CHECK(lsdem_fields_write_vti("test_fields.vti", &f, &err) == LSDEM_OK, "%s", err.msg);
  FILE *fp = fopen("test_fields.vti", "rb");
  static char text[1 << 16];
  const size_t got = fread(text, 1, sizeof text - 1, fp);
  text[got] = 0;
  const char *start = strstr(text, "<AppendedData encoding=\"raw\">\n_");
  CHECK(start != NULL && strstr(text, "Name=\"strain_green\" NumberOfComponents=\"9\""),
        "header");
  if (start) {
    const size_t nodes = lsdem_field_grid_nodes(&f.grid);
    uint64_t size = 0;
    fseek(fp, (long)(start - text) + (long)strlen("<AppendedData encoding=\"raw\">\n_"), SEEK_SET);
    CHECK(fread(&size, sizeof size, 1, fp) == 1 && size == nodes * sizeof(double),
          "byte count %llu", (unsigned long long)size);
    double *d = malloc(nodes * sizeof(double));
    CHECK(fread(d, sizeof(double), nodes, fp) == nodes &&
              memcmp(d, f.density, nodes * sizeof(double)) == 0, "density bits");
    free(d);
  }
  fclose(fp);
  lsdem_error e2;
  CHECK(lsdem_fields_write_vti("no/such/folder/x.vti", &f, &e2) == LSDEM_ERR_IO, "bad path");
  lsdem_fields_free(&f);
}


/* ------------------------------------------------------------ periodic boxes ---- */

#define PGRAINS 1500
#define PBOX 10.0

static void invert3(const double M[9], double inv[9])
{
  double c[9];
  lsdem_cross3(M + 3, M + 6, c);
  lsdem_cross3(M + 6, M, c + 3);
  lsdem_cross3(M, M + 3, c + 6);
  const double det = lsdem_dot3(M, c);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) inv[3 * i + j] = c[3 * j + i] / det;
}

/* The box [0, PBOX)^3 now, the image of the reference box under x = F X + t (its period
 * vectors P_k = F^-1 PBOX e_k, a sheared box for simple shear): grains uniform in the
 * reference box, mapped, given at their unwrapped centres (the drift t takes some out of
 * the box: the core wraps them), or with wrapped != 0 wrapped into the box as LAMMPS keeps
 * them (then u is not the affine field of the positions: what an open grid sees).
 * jump_k = PBOX e_k - P_k. */
static void periodic_scene(const double F[9], lsdem_field_grain *g, int n, lsdem_field_box *box,
                           int wrapped)
{
  double Finv[9];
  invert3(F, Finv);
  const double t[3] = {3.3, -2.1, 0.7}; /* a drift: some grains wrap */
  memset(box, 0, sizeof *box);
  for (int k = 0; k < 3; k++) {
    box->periodic[k] = 1;
    box->hi[k] = PBOX;
    for (int i = 0; i < 3; i++) box->jump[k][i] = (i == k) * PBOX - Finv[3 * i + k] * PBOX;
  }
  for (int i = 0; i < n; i++) {
    double f[3], X[3] = {0, 0, 0}, x[3];
    for (int k = 0; k < 3; k++) f[k] = urand();
    for (int k = 0; k < 3; k++)
      for (int j = 0; j < 3; j++) X[j] += f[k] * Finv[3 * j + k] * PBOX;
    lsdem_mat_vec(F, X, x);
    g[i].mass = 0.5 + urand();
    g[i].volume = 0.4 * (0.5 + urand());
    for (int k = 0; k < 3; k++) {
      x[k] += t[k];
      g[i].u[k] = x[k] - X[k];
      g[i].x[k] = wrapped ? x[k] - PBOX * floor(x[k] / PBOX) : x[k];
    }
  }
}

/* The fields of PGRAINS grains g under p (into f); H = F - I; returns the largest
 * |grad - H| over the nodes, with how many are regular and the integrated density's
 * relative difference from the total mass */
static double fit_affine(const lsdem_field_params *p, const lsdem_field_grain *g,
                         const double F[9], lsdem_fields *f, double H[9], size_t *regular,
                         double *mass_error)
{
  lsdem_error err;
  CHECK(lsdem_fields_compute(p, PGRAINS, g, 0, NULL, f, &err) == LSDEM_OK, "%s", err.msg);
  for (int k = 0; k < 9; k++) H[k] = F[k] - (k % 4 == 0 ? 1.0 : 0.0);
  double e = 0.0, m = 0.0, mass = 0.0;
  *regular = 0;
  for (size_t node = 0; node < lsdem_field_grid_nodes(&f->grid); node++) {
    *regular += f->regular[node];
    for (int k = 0; k < 9; k++) e = fmax(e, fabs(f->grad[9 * node + k] - H[k]));
    m += f->density[node] * f->grid.h[0] * f->grid.h[1] * f->grid.h[2];
  }
  for (int i = 0; i < PGRAINS; i++) mass += g[i].mass;
  *mass_error = fabs(m - mass) / mass;
  return e;
}

/* every node of the periodic grid regular and H = F - I to 1e-10; the open grid on the same
 * grains misses it (the wrapped grains' displacements jump by jump_k there) */
static void check_periodic_affine(const char *name, const double F[9])
{
  static lsdem_field_grain g[PGRAINS];
  lsdem_field_params p = PARAMS;
  periodic_scene(F, g, PGRAINS, &p.box, 0);
  lsdem_fields f;
  double H[9], dm;
  size_t regular;
  const double e = fit_affine(&p, g, F, &f, H, &regular, &dm);
  const size_t nodes = lsdem_field_grid_nodes(&f.grid);
  CHECK(f.grid.n[0] * f.grid.h[0] == PBOX && f.grid.origin[0] == 0.0, "%s: grid %d x %g from %g",
        name, f.grid.n[0], f.grid.h[0], f.grid.origin[0]);
  CHECK(regular == nodes, "%s: %zu regular nodes of %zu", name, regular, nodes);
  CHECK(e <= 1e-10 * max_abs(H, 9), "%s: periodic gradient off by %.3g (%.3g relative)", name, e,
        e / max_abs(H, 9));
  CHECK(dm <= 1e-12, "%s: integrated density off the mass by %.3g", name, dm);
  printf("periodic %s: %zu nodes, all regular, gradient error %.2e relative, mass %.2e\n",
         name, nodes, e / max_abs(H, 9), dm);
  lsdem_fields_free(&f);
  /* the control: the open, padded grid over the same grains as LAMMPS keeps them (wrapped
   * into the box, unwrapped displacements) */
  for (int i = 0; i < PGRAINS; i++)
    for (int k = 0; k < 3; k++) g[i].x[k] -= PBOX * floor(g[i].x[k] / PBOX);
  p.box = PARAMS.box;
  lsdem_error err;
  CHECK(lsdem_fields_compute(&p, PGRAINS, g, 0, NULL, &f, &err) == LSDEM_OK, "%s", err.msg);
  double eo = 0.0;
  size_t bad = 0, in_box = 0, node = 0;
  for (int i2 = 0; i2 < f.grid.n[2]; i2++)
    for (int i1 = 0; i1 < f.grid.n[1]; i1++)
      for (int i0 = 0; i0 < f.grid.n[0]; i0++, node++) {
        const int i[3] = {i0, i1, i2};
        int inside = 1;
        for (int k = 0; k < 3; k++) {
          const double x = f.grid.origin[k] + f.grid.h[k] * i[k];
          inside &= x >= 0.0 && x <= PBOX;
        }
        if (!inside) continue;
        in_box++;
        double en = f.regular[node] ? 0.0 : INFINITY;
        for (int k = 0; k < 9 && f.regular[node]; k++)
          en = fmax(en, fabs(f.grad[9 * node + k] - H[k]));
        bad += !(en <= 1e-10 * max_abs(H, 9));
        if (isfinite(en)) eo = fmax(eo, en);
      }
  CHECK(bad > in_box / 20, "%s: the open grid got %zu of %zu nodes in the box wrong", name, bad,
        in_box);
  printf("  open grid: %zu of %zu nodes in the box irregular or off by more than 1e-10 "
         "(worst regular %.2e relative)\n", bad, in_box, eo / max_abs(H, 9));
  lsdem_fields_free(&f);
}

/* The periodic fit of a non-affine displacement (the box's affine map plus a periodic
 * wave) against the same weighted least-squares fit summed directly: every grain's image
 * nearest each node through each of its 8 deposit nodes, its displacement that of the
 * image (u + the jumps of the periods crossed). Checked on every node of the six faces. */
static void check_periodic_bruteforce(void)
{
  enum { NG = 600 };
  static lsdem_field_grain g[NG];
  const double F[9] = {1.01, 0.01, 0, 0, 0.99, 0, 0, 0, 1};
  lsdem_field_params p = PARAMS;
  p.width = 1.2;
  periodic_scene(F, g, NG, &p.box, 0);
  for (int i = 0; i < NG; i++) g[i].u[0] += 0.02 * sin(2.0 * M_PI * g[i].x[1] / PBOX);
  lsdem_fields f;
  CHECK(lsdem_fields_compute(&p, NG, g, 0, NULL, &f, NULL) == LSDEM_OK, "compute");
  const lsdem_field_grid *gr = &f.grid;
  const size_t nodes = lsdem_field_grid_nodes(gr);
  double *G = malloc(nodes * sizeof(double));
  lsdem_field_kernel(gr, p.width, G);
  double worst = 0.0;
  size_t checked = 0, node = 0;
  for (int i2 = 0; i2 < gr->n[2]; i2++)
    for (int i1 = 0; i1 < gr->n[1]; i1++)
      for (int i0 = 0; i0 < gr->n[0]; i0++, node++) {
        const int in[3] = {i0, i1, i2};
        int face = 0;
        for (int k = 0; k < 3; k++) face |= in[k] == 0 || in[k] == gr->n[k] - 1;
        if (!face || !f.regular[node]) continue;
        double S = 0, Sy[3] = {0}, Su[3] = {0}, Syy[9] = {0}, Suy[9] = {0};
        for (int i = 0; i < NG; i++) {
          size_t cn[8];
          double w[8], d[8][3];
          lsdem_field_cell(gr, g[i].x, cn, w, d);
          for (int c = 0; c < 8; c++) {
            const int ci[3] = {(int)(cn[c] % gr->n[0]), (int)(cn[c] / gr->n[0] % gr->n[1]),
                               (int)(cn[c] / ((size_t)gr->n[0] * gr->n[1]))};
            int o[3];
            double y[3], u[3];
            for (int k = 0; k < 3; k++) {
              o[k] = ci[k] - in[k];
              o[k] -= gr->n[k] * (int)lround((double)o[k] / gr->n[k]); /* minimum image */
            }
            size_t ko = 0; /* the kernel's node of offset o */
            for (int k = 2; k >= 0; k--)
              ko = ko * (size_t)gr->n[k] + (size_t)(o[k] < 0 ? o[k] + gr->n[k] : o[k]);
            const double W = g[i].mass * w[c] * G[ko];
            if (W == 0.0) continue;
            for (int k = 0; k < 3; k++) y[k] = d[c][k] + o[k] * gr->h[k];
            /* the image's shift: node + y - x, a whole number of periods per axis */
            for (int k = 0; k < 3; k++) u[k] = g[i].u[k];
            for (int a = 0; a < 3; a++) {
              const double x = gr->origin[a] + gr->h[a] * in[a] + y[a];
              const double s = round((x - g[i].x[a]) / PBOX);
              for (int k = 0; k < 3; k++) u[k] += s * p.box.jump[a][k];
            }
            S += W;
            for (int k = 0; k < 3; k++) {
              Sy[k] += W * y[k];
              Su[k] += W * u[k];
              for (int l = 0; l < 3; l++) {
                Syy[3 * k + l] += W * y[k] * y[l];
                Suy[3 * k + l] += W * u[k] * y[l];
              }
            }
          }
        }
        double C[9], B[9], Ci[9], L[9], Finv[9], Fn[9];
        for (int k = 0; k < 3; k++)
          for (int l = 0; l < 3; l++) {
            C[3 * k + l] = Syy[3 * k + l] / S - Sy[k] * Sy[l] / (S * S);
            B[3 * k + l] = Suy[3 * k + l] / S - Su[k] * Sy[l] / (S * S);
          }
        invert3(C, Ci);
        lsdem_mat_mul(B, Ci, L);
        for (int k = 0; k < 9; k++) Finv[k] = (k % 4 == 0) - L[k];
        invert3(Finv, Fn);
        for (int k = 0; k < 9; k++)
          worst = fmax(worst, fabs(f.grad[9 * node + k] - (Fn[k] - (k % 4 == 0))));
        checked++;
      }
  CHECK(checked > 1000, "%zu face nodes checked", checked);
  CHECK(worst <= 1e-10 * 0.01, "periodic fit against the direct sum: off by %.3g", worst);
  printf("periodic fit = direct minimum-image sum on %zu face nodes to %.2e\n", checked, worst);
  free(G);
  lsdem_fields_free(&f);
}

/* 60 values deposited at lattice coordinates uniform in [0, span) (half at the z = 0 face)
 * of grid g, smoothed by FFT and by direct summation: their largest difference over the
 * largest value */
static double fft_direct_difference(const lsdem_field_grid *g, double width,
                                    const double span[3])
{
  const size_t nodes = lsdem_field_grid_nodes(g);
  double *a = calloc(nodes, sizeof(double)), *b = calloc(nodes, sizeof(double));
  for (int i = 0; i < 60; i++) {
    const double xi[3] = {span[0] * urand(), span[1] * urand(),
                          i % 2 ? 0.05 * urand() : span[2] * urand()};
    double x[3];
    lsdem_field_from_lattice(g->skew, xi, x);
    const double v = urand();
    lsdem_field_deposit(g, x, 1, &v, a);
  }
  memcpy(b, a, nodes * sizeof(double));
  CHECK(lsdem_field_smooth_fft(g, width, 1, a, NULL) == LSDEM_OK, "fft");
  CHECK(lsdem_field_smooth_direct(g, width, 1, b, NULL) == LSDEM_OK, "direct");
  double diff = 0.0;
  const double scale = max_abs(b, (int)nodes);
  for (size_t k = 0; k < nodes; k++) diff = fmax(diff, fabs(a[k] - b[k]));
  free(a);
  free(b);
  return diff / scale;
}

/* Grains uniform in box (periodic in x and z; a third at its x = 0 face) with contact
 * branches, half of them given with the far image of their point (the period vector a
 * further, a third c back: minimum image takes them back): the fields' integrals are the
 * total mass and the Love-Weber sum of the branches. */
static void check_branch_integrals(const lsdem_field_box *box)
{
  enum { NG = 200, NB = 300 };
  static lsdem_field_grain gr[NG];
  static lsdem_field_branch br[NB];
  double M[9] = {0}, sigma[9], skew[3];
  lsdem_field_box_skew(box, skew);
  const double l[3] = {box->hi[0] - box->lo[0], box->hi[1] - box->lo[1], box->hi[2] - box->lo[2]};
  const double pa[3] = {l[0], 0.0, 0.0}, pc[3] = {box->tilt[1], box->tilt[2], l[2]};
  for (int i = 0; i < NG; i++) {
    gr[i].mass = 1.0;
    gr[i].volume = 0.5;
    double xi[3];
    for (int k = 0; k < 3; k++) xi[k] = box->lo[k] + l[k] * urand();
    xi[0] = i % 3 ? xi[0] : box->lo[0] + 0.1 * urand();
    lsdem_field_from_lattice(skew, xi, gr[i].x);
  }
  for (int i = 0; i < NB; i++) {
    const lsdem_field_grain *c = gr + i % NG;
    for (int k = 0; k < 3; k++) {
      br[i].force[k] = srand1();
      br[i].centre[k] = c->x[k];
      br[i].point[k] = c->x[k] + 0.3 * srand1();
    }
    lsdem_love_weber_add(M, br[i].force, br[i].point, br[i].centre);
    for (int k = 0; k < 3; k++) {
      if (i % 2) br[i].point[k] += pa[k];
      if (i % 3 == 0) br[i].point[k] -= pc[k];
    }
  }
  lsdem_love_weber_stress(M, 1.0, sigma);
  lsdem_field_params p = PARAMS;
  p.width = 0.4;
  p.h = 0.25;
  p.box = *box;
  lsdem_fields f;
  lsdem_error err;
  CHECK(lsdem_fields_compute(&p, NG, gr, NB, br, &f, &err) == LSDEM_OK, "%s", err.msg);
  const double dv = f.grid.h[0] * f.grid.h[1] * f.grid.h[2];
  double s[9] = {0}, m = 0;
  for (size_t node = 0; node < lsdem_field_grid_nodes(&f.grid); node++) {
    m += f.density[node] * dv;
    for (int k = 0; k < 9; k++) s[k] += f.stress[9 * node + k] * dv;
  }
  CHECK_REL(m, (double)NG, 1e-12);
  for (int k = 0; k < 9; k++) CHECK_NEAR(s[k], sigma[k], 1e-10 * max_abs(sigma, 9));
  lsdem_fields_free(&f);
}

/* ------------------------------------------------------------- tilted boxes ---- */

/* A tilted periodic box (LAMMPS's triclinic form) that is the image under x = F X + t of
 * a reference box of tilt ref_tilt (F upper triangular keeps that form): the period vectors
 * a_k = F A_k, the box now from 0 with lengths a0, b1, c2 and tilt (b0, c0, c1); grains
 * uniform in the reference box, at their unwrapped centres (the drift takes some out of the
 * box). Every node regular, H = F - I to 1e-10 relative, the mass integral, the grid spanning
 * the period vectors. */
static void check_tilted_affine(const char *name, const double F[9], const double ref_tilt[3])
{
  static lsdem_field_grain g[PGRAINS];
  const double A[3][3] = {{PBOX, 0, 0}, {ref_tilt[0], PBOX, 0}, {ref_tilt[1], ref_tilt[2], PBOX}};
  double a[3][3];
  for (int k = 0; k < 3; k++) lsdem_mat_vec(F, A[k], a[k]);
  lsdem_field_params p = PARAMS;
  memset(&p.box, 0, sizeof p.box);
  for (int k = 0; k < 3; k++) {
    p.box.periodic[k] = 1;
    p.box.hi[k] = a[k][k];
    for (int i = 0; i < 3; i++) p.box.jump[k][i] = a[k][i] - A[k][i];
  }
  p.box.tilt[0] = a[1][0];
  p.box.tilt[1] = a[2][0];
  p.box.tilt[2] = a[2][1];
  CHECK(a[0][1] == 0.0 && a[0][2] == 0.0 && a[1][2] == 0.0, "%s: F keeps the box's form", name);
  const double t[3] = {3.3, -2.1, 0.7};
  for (int i = 0; i < PGRAINS; i++) {
    double X[3] = {0, 0, 0}, x[3];
    for (int k = 0; k < 3; k++) {
      const double f = urand();
      for (int j = 0; j < 3; j++) X[j] += f * A[k][j];
    }
    lsdem_mat_vec(F, X, x);
    g[i].mass = 0.5 + urand();
    g[i].volume = 0.4 * (0.5 + urand());
    for (int k = 0; k < 3; k++) {
      g[i].x[k] = x[k] + t[k];
      g[i].u[k] = g[i].x[k] - X[k];
    }
  }
  lsdem_fields f;
  double H[9], dm;
  size_t regular;
  const double e = fit_affine(&p, g, F, &f, H, &regular, &dm);
  const size_t nodes = lsdem_field_grid_nodes(&f.grid);
  for (int k = 0; k < 3; k++) {
    int end[3] = {0, 0, 0};
    end[k] = f.grid.n[k];
    double x[3];
    lsdem_field_node_position(&f.grid, end, x);
    CHECK(fabs(x[0] - a[k][0]) + fabs(x[1] - a[k][1]) + fabs(x[2] - a[k][2]) <= 1e-12 * PBOX,
          "%s: node n_%d at (%g %g %g), not the period vector (%g %g %g)", name, k, x[0], x[1],
          x[2], a[k][0], a[k][1], a[k][2]);
  }
  CHECK(regular == nodes, "%s: %zu regular nodes of %zu", name, regular, nodes);
  CHECK(e <= 1e-10 * max_abs(H, 9), "%s: tilted gradient off by %.3g (%.3g relative)", name, e,
        e / max_abs(H, 9));
  CHECK(dm <= 1e-12, "%s: integrated density off the mass by %.3g", name, dm);
  printf("tilted %s: skew %.3f %.3f %.3f, %zu nodes, all regular, gradient error %.2e "
         "relative, mass %.2e\n", name, f.grid.skew[0], f.grid.skew[1], f.grid.skew[2], nodes,
         e / max_abs(H, 9), dm);
  lsdem_fields_free(&f);
}

/* A grid periodic in x and z, open in y, of a box with tilt factors tilt (zeros:
 * orthogonal): the periodic axes span their periods, the FFT equals the direct sum, a
 * node's kernel weight follows the Cartesian distance (the node of offset (1, -1, 0)
 * against its world distance), a kernel reaching half the period is refused; contact
 * branches across the faces (check_branch_integrals) */
static void check_smooth_and_stress(const char *name, const double tilt[3])
{
  lsdem_field_box box;
  memset(&box, 0, sizeof box);
  box.periodic[0] = box.periodic[2] = 1;
  const double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {4.0, 2.0, 3.0}; /* y open: the grains' */
  for (int k = 0; k < 3; k++) {
    box.hi[k] = hi[k];
    box.tilt[k] = tilt[k];
  }
  lsdem_field_grid g;
  CHECK(lsdem_field_grid_cover_box(&box, lo, hi, 0.25, 0.4, &g, NULL) == LSDEM_OK, "grid");
  CHECK(g.origin[0] == 0.0 && g.n[0] * g.h[0] == 4.0 && g.n[2] * g.h[2] == 3.0 && g.h[1] == 0.25,
        "%s: periodic axes span the period", name);
  CHECK(g.skew[0] == tilt[0] / 2.0 && g.skew[1] == tilt[1] / 3.0 && g.skew[2] == tilt[2] / 3.0,
        "%s: skew", name);
  const double diff = fft_direct_difference(&g, 0.4, hi);
  CHECK(diff <= 1e-12, "%s: FFT against direct: %.3g relative", name, diff);
  const size_t nodes = lsdem_field_grid_nodes(&g);
  double *K = malloc(nodes * sizeof(double));
  lsdem_field_kernel(&g, 0.4, K);
  /* lattice offset (h0, -h1, 0): world (h0 - xy/ly h1, -h1, 0) */
  const double d[3] = {g.h[0] - tilt[0] / hi[1] * g.h[1], -g.h[1], 0.0};
  const size_t k1 = (size_t)(g.n[0] - 1) + (size_t)g.n[0] * 1; /* offset -(1, -1, 0) */
  CHECK_REL(K[k1] / K[0], exp(-lsdem_dot3(d, d) / (2.0 * 0.4 * 0.4)), 1e-14);
  free(K);
  lsdem_error err;
  CHECK(lsdem_field_grid_cover_box(&box, lo, hi, 0.25, 0.6, &g, &err) == LSDEM_ERR_ARG,
        "%s: reach", name);
  check_branch_integrals(&box);
  printf("%s grid: FFT = direct to %.2e, mass and contact stress integrals hold\n", name, diff);
}

/* The reference's period vectors follow a flip of the box into the new basis: an xy flip
 * (b' = b - a), then a yz flip (c' = c - b, LAMMPS's xz' = xz - xy), each with a step's
 * deformation on top; a step without a flip leaves them alone */
static void check_box_rebase(void)
{
  double ref[3][3] = {{9, 0, 0}, {0.3, 9, 0}, {-0.2, 0.4, 9}}, ref0[3][3];
  memcpy(ref0, ref, sizeof ref);
  const double last[3][3] = {{9.1, 0, 0}, {4.54, 8.9, 0}, {0.5, 4.4, 9.05}};
  double now[3][3];
  memcpy(now, last, sizeof now);
  now[1][0] += 1e-3; /* a step's shear */
  CHECK(lsdem_field_box_rebase(last, now, ref) == 0 && !memcmp(ref, ref0, sizeof ref),
        "a step without a flip changed the reference");
  double flipped[3][3];
  memcpy(flipped, now, sizeof now);
  flipped[1][0] -= flipped[0][0]; /* xy flip: b - a */
  flipped[1][0] += 1e-3;
  CHECK(lsdem_field_box_rebase(now, flipped, ref) == 1, "xy flip not seen");
  for (int i = 0; i < 3; i++) {
    CHECK(ref[1][i] == ref0[1][i] - ref0[0][i], "xy flip: b_ref[%d] = %g", i, ref[1][i]);
    CHECK(ref[0][i] == ref0[0][i] && ref[2][i] == ref0[2][i], "xy flip moved a or c");
  }
  double again[3][3];
  memcpy(again, flipped, sizeof again);
  for (int i = 0; i < 3; i++) again[2][i] -= flipped[1][i]; /* yz flip: c - b */
  double ref1[3][3];
  memcpy(ref1, ref, sizeof ref);
  CHECK(lsdem_field_box_rebase(flipped, again, ref) == 1, "yz flip not seen");
  for (int i = 0; i < 3; i++)
    CHECK(ref[2][i] == ref1[2][i] - ref1[1][i], "yz flip: c_ref[%d] = %g", i, ref[2][i]);
  printf("box flips: the reference's period vectors follow the xy and yz flips\n");
}

/* The surface mask on a skewed grid: the nodes inside the cube [2, 6]^3 are those whose
 * world positions are (nodes within 1e-9 of a face not counted) */
static void check_tilted_mask(void)
{
  const double cube[8][3] = {{2, 2, 2}, {6, 2, 2}, {2, 6, 2}, {6, 6, 2},
                             {2, 2, 6}, {6, 2, 6}, {2, 6, 6}, {6, 6, 6}};
  const int ct[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                         {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  lsdem_field_grid cg = {{45, 41, 41}, {-1.5, 0, 0}, {0.2, 0.2, 0.2}, {0, 0, 0},
                         {0.13, -0.11, 0.07}};
  const size_t nodes = lsdem_field_grid_nodes(&cg);
  unsigned char *in = malloc(nodes);
  lsdem_error err;
  CHECK(lsdem_field_inside_surface(&cg, 8, &cube[0][0], 12, &ct[0][0], in, &err) == LSDEM_OK,
        "tilted cube");
  size_t node = 0, wrong = 0, inside = 0;
  for (int i2 = 0; i2 < cg.n[2]; i2++)
    for (int i1 = 0; i1 < cg.n[1]; i1++)
      for (int i0 = 0; i0 < cg.n[0]; i0++, node++) {
        const int i[3] = {i0, i1, i2};
        double x[3], face = HUGE_VAL;
        int want = 1;
        lsdem_field_node_position(&cg, i, x);
        for (int k = 0; k < 3; k++) {
          want &= x[k] > 2.0 && x[k] < 6.0;
          face = fmin(face, fmin(fabs(x[k] - 2.0), fabs(x[k] - 6.0)));
        }
        if (face < 1e-9) continue;
        inside += want;
        wrong += in[node] != want;
      }
  CHECK(wrong == 0 && inside > 1000, "tilted mask: %zu nodes wrong, %zu inside", wrong, inside);
  printf("tilted mask: %zu nodes inside the cube, none wrong\n", inside);
  free(in);
}

/* ------------------------------------------------------------- surface mask ---- */

/* a closed-ended tube: nz + 1 rings of na vertices on radius R(z), z from z0 to z1, the
 * lateral triangles only (the core closes the end rings) */
static int tube(int na, int nz, double R0, double bulge, double z0, double z1, double *v, int *t)
{
  int nt = 0;
  for (int j = 0; j <= nz; j++)
    for (int i = 0; i < na; i++) {
      const double s = (double)j / nz, a = 2.0 * M_PI * (i + 0.5 * (j % 2)) / na;
      const double R = R0 + bulge * sin(M_PI * s);
      double *p = v + 3 * (j * na + i);
      p[0] = 5.0 + R * cos(a);
      p[1] = 5.0 + R * sin(a);
      p[2] = z0 + (z1 - z0) * s;
    }
  for (int j = 0; j < nz; j++)
    for (int i = 0; i < na; i++) {
      const int a = j * na + i, b = j * na + (i + 1) % na, c = (j + 1) * na + i,
                d = (j + 1) * na + (i + 1) % na;
      /* ring j + 1 turned by half a step from ring j (even j) or back (odd j) */
      const int q[2][6] = {{a, b, c, b, d, c}, {a, b, d, a, d, c}};
      memcpy(t + 3 * nt, q[j % 2], sizeof q[0]);
      nt += 2;
    }
  return nt;
}

/* nodes inside the undeformed tube = inside the cylinder of its radius but within one
 * node of the surface (the facets cut the circle: the polygon's inner radius is
 * R cos(pi / na)); a bulged tube: inside its per-height radius profile likewise; the
 * open-ended tube closed at its ends by the core (nodes beyond the end rings outside) */
static void check_surface_mask(void)
{
  enum { NA = 96, NZ = 40 };
  static double v[3 * NA * (NZ + 1)];
  static int t[3 * 2 * NA * NZ];
  lsdem_field_grid g;
  const double lo[3] = {1, 1, 0}, hi[3] = {9, 9, 10};
  CHECK(lsdem_field_grid_cover(lo, hi, 0.2, 0.3, &g, NULL) == LSDEM_OK, "grid");
  const size_t nodes = lsdem_field_grid_nodes(&g);
  unsigned char *in = malloc(nodes);
  lsdem_error err;
  for (int bulged = 0; bulged < 2; bulged++) {
    const double R0 = 3.0, bulge = bulged ? 0.6 : 0.0, z0 = 1.0, z1 = 9.0;
    const int nt = tube(NA, NZ, R0, bulge, z0, z1, v, t);
    CHECK(lsdem_field_inside_surface(&g, NA * (NZ + 1), v, nt, t, in, &err) == LSDEM_OK, "%s",
          err.msg);
    size_t differ = 0, far = 0, inside = 0, node = 0;
    const double h = g.h[0];
    for (int i2 = 0; i2 < g.n[2]; i2++)
      for (int i1 = 0; i1 < g.n[1]; i1++)
        for (int i0 = 0; i0 < g.n[0]; i0++, node++) {
          const double x = g.origin[0] + h * i0 - 5.0, y = g.origin[1] + h * i1 - 5.0;
          const double z = g.origin[2] + h * i2;
          const double R = R0 + bulge * sin(M_PI * fmin(fmax((z - z0) / (z1 - z0), 0.0), 1.0));
          const double r = sqrt(x * x + y * y);
          const int expect = r <= R && z >= z0 && z <= z1;
          inside += in[node];
          if (in[node] == expect) continue;
          differ++;
          /* distance to the surface, the ends included */
          const double dist = fmin(fabs(r - R), fmin(fabs(z - z0), fabs(z - z1)));
          far += dist > h;
        }
    CHECK(inside > nodes / 20, "%zu nodes inside", inside);
    CHECK(far == 0, "%s tube: %zu nodes differ from the profile farther than a node from the "
          "surface (%zu differ)", bulged ? "bulged" : "straight", far, differ);
    printf("surface mask, %s tube: %zu nodes inside, %zu differ from the %s, all within one "
           "node of the surface\n", bulged ? "bulged" : "straight", inside, differ,
           bulged ? "radius profile" : "cylinder");
  }
  /* a ray through vertices and edges: a cube of 12 triangles whose faces and edges lie on
   * node rows and columns counts every crossing once */
  const double cube[8][3] = {{2, 2, 2}, {6, 2, 2}, {2, 6, 2}, {6, 6, 2},
                             {2, 2, 6}, {6, 2, 6}, {2, 6, 6}, {6, 6, 6}};
  const int ct[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                         {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  lsdem_field_grid cg = {{41, 41, 41}, {0, 0, 0}, {0.2, 0.2, 0.2}, {0, 0, 0}, {0, 0, 0}};
  unsigned char *cin = malloc(41 * 41 * 41);
  CHECK(lsdem_field_inside_surface(&cg, 8, &cube[0][0], 12, &ct[0][0], cin, &err) == LSDEM_OK,
        "cube");
  size_t wrong = 0, node = 0;
  for (int i2 = 0; i2 < 41; i2++)
    for (int i1 = 0; i1 < 41; i1++)
      for (int i0 = 0; i0 < 41; i0++, node++) {
        const int i[3] = {i0, i1, i2};
        int strictly = 1, outside = 0;
        for (int k = 0; k < 3; k++) {
          strictly &= i[k] > 10 && i[k] < 30;
          outside |= i[k] < 10 || i[k] > 30;
        }
        wrong += (strictly && !cin[node]) || (outside && cin[node]);
      }
  CHECK(wrong == 0, "cube: %zu nodes off the surface on the wrong side", wrong);
  const int bad[3] = {0, 1, 8};
  CHECK(lsdem_field_inside_surface(&cg, 8, &cube[0][0], 1, bad, cin, &err) == LSDEM_ERR_ARG,
        "bad index");
  free(cin);
  free(in);
}

int main(void)
{
  const double pure_shear[9] = {1.01, 0, 0, 0, 0.99, 0, 0, 0, 1};
  const double simple_shear[9] = {1, 0.01, 0, 0, 1, 0, 0, 0, 1};
  const double dilation[9] = {1.01, 0, 0, 0, 1.01, 0, 0, 0, 1.01};
  check_affine("pure shear", pure_shear);
  check_affine("simple shear", simple_shear);
  check_affine("dilation", dilation);
  check_plain_average_fails();
  check_rotation();
  check_fft_direct();
  check_totals();
  check_vti();
  check_periodic_affine("pure shear", pure_shear);
  check_periodic_affine("simple shear", simple_shear);
  check_periodic_affine("dilation", dilation);
  check_periodic_bruteforce();
  const double no_tilt[3] = {0, 0, 0}, ref_tilt[3] = {-1.0, 2.0, 1.5};
  const double tilt[3] = {0.8, -0.6, 0.9};
  check_smooth_and_stress("periodic", no_tilt);
  check_smooth_and_stress("tilted", tilt);
  const double upper[9] = {1.02, 0.03, -0.04, 0, 0.99, 0.05, 0, 0, 1.01};
  check_tilted_affine("simple shear of a cube", simple_shear, no_tilt);
  check_tilted_affine("upper-triangular F of a tilted box", upper, ref_tilt);
  check_tilted_mask();
  check_box_rebase();
  check_surface_mask();
  return lsdem_test_summary();
}
