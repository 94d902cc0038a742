/* test_fields.c -- continuum fields (core/fields): affine fields recovered exactly on a
 * random packing, rigid rotations strain-free, FFT against direct summation, totals kept,
 * the cylinder mask and the .vti file. */
#include "lsdem_test.h"

#include "fields/lsdem_fields.h"

#include <stdlib.h>
#include <string.h>

#define NGRAINS 400
#define BOX 10.0

static const lsdem_field_params PARAMS = {1.0, 0.5, LSDEM_FIELD_MIN_VARIANCE, LSDEM_FIELD_MIN_WEIGHT};

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
        const double x[3] = {grid.origin[0] + grid.h * i0, grid.origin[1] + grid.h * i1,
                             grid.origin[2] + grid.h * i2};
        int interior = 1;
        for (int k = 0; k < 3; k++)
          interior &= x[k] > lo[k] + inset * grid.h && x[k] < hi[k] - inset * grid.h;
        if (!interior) continue;
        const size_t node = (size_t)i0 + (size_t)n[0] * ((size_t)i1 + (size_t)n[1] * i2);
        const size_t up = node + (size_t)n[0], down = node - (size_t)n[0];
        const double dudy = (ch[nodes + up] / ch[up] - ch[nodes + down] / ch[down]) / (2 * grid.h);
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
  const double dv = f.grid.h * f.grid.h * f.grid.h;
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
    const double x = f.grid.origin[0] + f.grid.h * i0 - 5.0;
    const double y = f.grid.origin[1] + f.grid.h * i1 - 5.0;
    const double z = f.grid.origin[2] + f.grid.h * i2;
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
  return lsdem_test_summary();
}
