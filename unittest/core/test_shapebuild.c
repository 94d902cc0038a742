/* test_shapebuild.c -- lsdem_shape_build and the shared quality checks (lsdem_shape_check):
 * each warning raised by the defect it names and by nothing else. */
#include "lsdem.h"
#include "lsdem_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* A sphere of radius R sampled on a grid of spacing h (margin samples), built. */
static void build_sphere(double R, double h, int margin, int nnodes, double spacing,
                         lsdem_built_shape *b)
{
  const lsdem_sdf sphere = {LSDEM_SDF_SPHERE, 0, {R, 0, 0}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL};
  const double lo[3] = {-R, -R, -R}, hi[3] = {R, R, R};
  lsdem_sdf s = {LSDEM_SDF_GRID, 0, {0, 0, 0}, {{0, 0, 0}, 0, {0, 0, 0}, NULL, 0.0, 0.0}, NULL};
  lsdem_error err;
  CHECK(lsdem_grid_sample(&sphere, lo, hi, h, margin, &s.grid, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(lsdem_shape_build(&s, nnodes, spacing, 3, b, &err) == LSDEM_OK, "%s", err.msg);
}

static void test_good_sphere(void)
{
  lsdem_built_shape b;
  build_sphere(1.0, 0.08, 2, 0, 0.0, &b); /* automatic node count: spacing 0.09 d */
  const double V = 4.0 / 3.0 * PI;
  CHECK_REL(b.shape.volume, V, 1e-3);
  CHECK_REL(b.shape.inertia[0], 0.4 * V, 3e-3);
  CHECK(b.shape.nclusters > 1 && b.shape.radius >= 1.0, "clusters %d radius %g",
        b.shape.nclusters, b.shape.radius);
  /* 0.09 d = 0.18: area 4 pi / 0.18^2 = 388 nodes */
  CHECK(abs(b.shape.nnodes - 388) <= 12, "automatic node count %d", b.shape.nnodes);
  lsdem_shape_report r;
  lsdem_error err;
  CHECK(lsdem_shape_check(&b.shape, &r, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(r.warnings == 0, "warnings %d", r.warnings);
  CHECK_NEAR(r.radius_eq, 1.0, 1e-3);
  CHECK(fabs(r.volume_error) < 0.01 && r.inertia_error < 0.02, "node volume %g inertia %g",
        r.volume_error, r.inertia_error);
  char text[256];
  CHECK(lsdem_shape_report_text(&r, text, sizeof text) == 0 && text[0] == '\0', "text '%s'", text);
  lsdem_built_shape_free(&b);
}

static void test_each_warning(void)
{
  lsdem_shape_report r;
  lsdem_error err;
  char text[1024];
  lsdem_built_shape b;
  build_sphere(1.0, 0.15, 2, 40, 0.0, &b); /* h > R/10, 40 nodes: spacing ~ 0.56 > 0.2 */
  CHECK(lsdem_shape_check(&b.shape, &r, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(r.warnings == (LSDEM_CHECK_COARSE_GRID | LSDEM_CHECK_SPARSE_NODES), "warnings %d",
        r.warnings);
  lsdem_shape_report_text(&r, text, sizeof text);
  CHECK(strstr(text, "coarser than R/10") && strstr(text, "exceeds d/10"), "%s", text);
  /* a wrong volume and moments in the shape: node integrals disagree */
  b.shape.volume *= 1.1;
  b.shape.inertia[1] *= 0.8;
  CHECK(lsdem_shape_check(&b.shape, &r, &err) == LSDEM_OK, "%s", err.msg);
  CHECK((r.warnings & LSDEM_CHECK_VOLUME) && (r.warnings & LSDEM_CHECK_INERTIA), "warnings %d",
        r.warnings);
  /* the same shape within tolerances given (volume 10 % off, moments 20 %): no node warning,
   * and the text names the tolerance that was used */
  CHECK(lsdem_shape_check_tol(&b.shape, 0.15, 0.30, &r, &err) == LSDEM_OK, "%s", err.msg);
  CHECK(!(r.warnings & (LSDEM_CHECK_VOLUME | LSDEM_CHECK_INERTIA)) && r.volume_tol == 0.15,
        "warnings %d", r.warnings);
  CHECK(lsdem_shape_check_tol(&b.shape, 0.05, 0.30, &r, &err) == LSDEM_OK, "%s", err.msg);
  lsdem_shape_report_text(&r, text, sizeof text);
  CHECK((r.warnings & LSDEM_CHECK_VOLUME) && !(r.warnings & LSDEM_CHECK_INERTIA) &&
        strstr(text, "(tolerance 5%)"), "warnings %d: %s", r.warnings, text);
  CHECK(lsdem_shape_check(&b.shape, &r, &err) == LSDEM_OK, "%s", err.msg);
  const size_t need = lsdem_shape_report_text(&r, text, 20); /* truncation: size reported */
  CHECK(need > 100 && strlen(text) < 20, "need %zu", need);
  lsdem_built_shape_free(&b);
  /* a solid cut by the grid box: negative samples on the border */
  build_sphere(1.0, 0.08, 2, 100, 0.0, &b);
  float *phi = b.phi;
  phi[0] = -0.01f;
  CHECK(lsdem_shape_check(&b.shape, &r, &err) == LSDEM_OK, "%s", err.msg);
  CHECK((r.warnings & LSDEM_CHECK_OPEN_LEVEL_SET) && r.border_negative == 1, "border %ld",
        r.border_negative);
  lsdem_built_shape_free(&b);
  /* node spacing given: count = area / spacing^2 */
  build_sphere(1.0, 0.08, 2, 0, 0.25, &b);
  CHECK(abs(b.shape.nnodes - (int)ceil(4.0 * PI / 0.0625)) <= 6, "nodes %d", b.shape.nnodes);
  lsdem_built_shape_free(&b);
  lsdem_shape empty;
  memset(&empty, 0, sizeof empty);
  CHECK(lsdem_shape_check(&empty, &r, &err) == LSDEM_ERR_ARG, "no nodes");
}

int main(void)
{
  test_good_sphere();
  test_each_warning();
  return lsdem_test_summary();
}
