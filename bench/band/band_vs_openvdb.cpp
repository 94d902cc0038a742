// band_vs_openvdb.cpp -- wall storage: our narrow band (lsdem_band) against OpenVDB.
//
// One synthetic terrain (N x N cells, cell 1: a few sines, relief ~50, plus a little
// noise), triangulated as lsdem_heightmap_mesh does (two triangles per cell, counter-
// clockwise from above), is turned into a narrow band of half-width 2 at spacing 1 by
//   (a) OpenVDB 10: tools::meshToVolume<FloatGrid> with UNSIGNED_DISTANCE_FIELD, band 2
//       voxels, then every voxel and tile signed by the height field (solid below). (meshToLevelSet itself
//       needs a closed surface: its inside/outside classification floods from outside the
//       band, and around an open sheet both sides are "outside"; --signed-test measures
//       it.) The grid's transform puts its voxels on our band's samples, so both store
//       exact distances at the same points.
//   (b) ours: lsdem_band_from_mesh(h = 1, width = 2, LSDEM_BAND_TERRAIN) + lsdem_band_far.
// Then both are looked up at M random points within the band (|exact distance| < 2) with
// trilinear value + unit gradient, and compared with each other and with the exact signed
// distance to the triangles (brute force over the cells around the point).
//
// Benchmark only: prints figures, never pass/fail. bench/band/run.sh builds and runs it.
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/math/Operators.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "prep/lsdem_prep.h" // C headers with their own extern "C"
#include "geom/trilinear.h"   // the core's trilinear cell (static inline C)

#ifndef BENCH_HAVE_BAND_BUILDER
#define BENCH_HAVE_BAND_BUILDER 1
#endif

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// ------------------------------------------------------------------ terrain ----

struct Terrain {
  int N = 0;          // cells per side; (N+1)^2 heights at integer x, y
  std::vector<float> z;
  double zmin = 0, zmax = 0;
  float at(int i, int j) const { return z[(size_t)j * (N + 1) + i]; }
  // The triangulated surface's height (cell (i,j) split along (i,j)-(i+1,j+1): triangle
  // ((i,j),(i+1,j),(i+1,j+1)) where fx >= fy, ((i,j),(i+1,j+1),(i,j+1)) where fy > fx);
  // outside the footprint, its edge (the band's outside rule).
  double height(double x, double y) const
  {
    x = std::min(std::max(x, 0.0), (double)N);
    y = std::min(std::max(y, 0.0), (double)N);
    int i = std::min((int)x, N - 1), j = std::min((int)y, N - 1);
    const double fx = x - i, fy = y - j;
    const double z00 = at(i, j), z10 = at(i + 1, j), z01 = at(i, j + 1), z11 = at(i + 1, j + 1);
    if (fx >= fy) return z00 + fx * (z10 - z00) + fy * (z11 - z10);
    return z00 + fy * (z01 - z00) + fx * (z11 - z01);
  }
};

Terrain make_terrain(int N, uint64_t seed)
{
  Terrain t;
  t.N = N;
  t.z.resize((size_t)(N + 1) * (N + 1));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> noise(-0.15, 0.15);
  const double tau = 2.0 * M_PI;
  t.zmin = HUGE_VAL, t.zmax = -HUGE_VAL;
  for (int j = 0; j <= N; j++)
    for (int i = 0; i <= N; i++) {
      const double x = i, y = j;
      double h = 25.0 + 11.0 * std::sin(tau * x / 370.0 + 0.3) * std::sin(tau * y / 290.0) +
                 8.0 * std::sin(tau * (x + y) / 510.0 + 1.0) +
                 5.0 * std::sin(tau * (x - 0.6 * y) / 160.0) +
                 2.5 * std::sin(tau * y / 75.0 + 2.0) * std::cos(tau * x / 95.0) + noise(rng);
      const float f = (float)h;
      t.z[(size_t)j * (N + 1) + i] = f;
      t.zmin = std::min(t.zmin, (double)f), t.zmax = std::max(t.zmax, (double)f);
    }
  return t;
}

struct Mesh {
  std::vector<double> verts;
  std::vector<int> tris;
};

Mesh make_mesh(const Terrain &t)
{
  Mesh m;
  const int N = t.N, W = N + 1;
  m.verts.resize(3 * (size_t)W * W);
  for (int j = 0; j <= N; j++)
    for (int i = 0; i <= N; i++) {
      double *v = &m.verts[3 * ((size_t)j * W + i)];
      v[0] = i, v[1] = j, v[2] = t.at(i, j);
    }
  m.tris.reserve(6 * (size_t)N * N);
  for (int j = 0; j < N; j++)
    for (int i = 0; i < N; i++) {
      const int a = j * W + i, b = a + 1, c = a + W + 1, d = a + W;
      m.tris.insert(m.tris.end(), {a, b, c, a, c, d});
    }
  return m;
}

// --------------------------------------------------------- exact distance ----

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5).
inline void closest_on_triangle(const double p[3], const double a[3], const double b[3],
                                const double c[3], double out[3])
{
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int k = 0; k < 3; k++) ab[k] = b[k] - a[k], ac[k] = c[k] - a[k], ap[k] = p[k] - a[k];
  auto dot = [](const double *u, const double *v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) { std::memcpy(out, a, 24); return; }
  for (int k = 0; k < 3; k++) bp[k] = p[k] - b[k];
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) { std::memcpy(out, b, 24); return; }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    for (int k = 0; k < 3; k++) out[k] = a[k] + v * ab[k];
    return;
  }
  for (int k = 0; k < 3; k++) cp[k] = p[k] - c[k];
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) { std::memcpy(out, c, 24); return; }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    for (int k = 0; k < 3; k++) out[k] = a[k] + w * ac[k];
    return;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    for (int k = 0; k < 3; k++) out[k] = b[k] + w * (c[k] - b[k]);
    return;
  }
  const double den = 1.0 / (va + vb + vc), v = vb * den, w = vc * den;
  for (int k = 0; k < 3; k++) out[k] = a[k] + ab[k] * v + ac[k] * w;
}

// Signed distance from p to the triangulated terrain (negative below: the solid) and the
// unit direction from the closest point (the distance's gradient), by brute force over
// the triangles of the cells within `reach` of p horizontally. Exact when |d| < reach.
double exact_distance(const Terrain &t, const Mesh &m, const double p[3], double reach,
                      double grad[3])
{
  const int N = t.N;
  const int i0 = std::max(0, (int)std::floor(p[0] - reach)), i1 = std::min(N - 1, (int)std::floor(p[0] + reach));
  const int j0 = std::max(0, (int)std::floor(p[1] - reach)), j1 = std::min(N - 1, (int)std::floor(p[1] + reach));
  double best = HUGE_VAL, q[3], bq[3] = {p[0], p[1], p[2]};
  for (int j = j0; j <= j1; j++)
    for (int i = i0; i <= i1; i++)
      for (int s = 0; s < 2; s++) {
        const int *tri = &m.tris[6 * ((size_t)j * N + i) + 3 * s];
        closest_on_triangle(p, &m.verts[3 * (size_t)tri[0]], &m.verts[3 * (size_t)tri[1]],
                            &m.verts[3 * (size_t)tri[2]], q);
        const double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                          (p[2] - q[2]) * (p[2] - q[2]);
        if (d2 < best) best = d2, std::memcpy(bq, q, 24);
      }
  const double d = std::sqrt(best);
  const double sgn = p[2] >= t.height(p[0], p[1]) ? 1.0 : -1.0;
  for (int k = 0; k < 3; k++) grad[k] = d > 0 ? sgn * (p[k] - bq[k]) / d : (k == 2);
  return sgn * d;
}

// ------------------------------------------------------------------ OpenVDB ----

// The mesh for meshToVolume in index space, in double (QuadAndTriangleDataAdapter takes
// float points: 6e-5 of rounding at x = 1000).
struct VdbMeshAdapter {
  const Mesh *m;
  double origin[3], inv_h;
  size_t polygonCount() const { return m->tris.size() / 3; }
  size_t pointCount() const { return m->verts.size() / 3; }
  size_t vertexCount(size_t) const { return 3; }
  void getIndexSpacePoint(size_t n, size_t v, openvdb::Vec3d &pos) const
  {
    const double *p = &m->verts[3 * (size_t)m->tris[3 * n + v]];
    pos = openvdb::Vec3d((p[0] - origin[0]) * inv_h, (p[1] - origin[1]) * inv_h,
                         (p[2] - origin[2]) * inv_h);
  }
};

struct VdbBand {
  openvdb::FloatGrid::Ptr grid;
  double origin[3], h;
  double t_mesh = 0, t_sign = 0;
};

VdbBand build_vdb(const Terrain &t, const Mesh &m, const double origin[3], double h,
                  double width, bool signed_direct)
{
  VdbBand vb;
  std::memcpy(vb.origin, origin, sizeof vb.origin);
  vb.h = h;
  auto xform = openvdb::math::Transform::createLinearTransform(h);
  xform->postTranslate(openvdb::Vec3d(origin[0], origin[1], origin[2]));
  VdbMeshAdapter ad{&m, {origin[0], origin[1], origin[2]}, 1.0 / h};
  const float bw = (float)(width / h);
  auto t0 = Clock::now();
  if (signed_direct) { // what meshToLevelSet does (a closed surface assumed)
    vb.grid = openvdb::tools::meshToVolume<openvdb::FloatGrid>(ad, *xform, bw, bw, 0);
    vb.t_mesh = seconds_since(t0);
    return vb;
  }
  vb.grid = openvdb::tools::meshToVolume<openvdb::FloatGrid>(
      ad, *xform, bw, bw, openvdb::tools::UNSIGNED_DISTANCE_FIELD);
  vb.t_mesh = seconds_since(t0);
  t0 = Clock::now();
  // Sign every value, active or not, voxel or tile, by the height field: below the
  // triangulated surface is the solid. (tools::signedFloodFill, the usual step after an
  // unsigned conversion, guesses the inactive values' signs by scanlines within each leaf
  // and mis-signs some where the open sheet ends, at the footprint's edges.) A tile holds
  // no active voxel, so the surface does not cross it: its centre gives its side.
  auto &tree = vb.grid->tree();
  for (auto it = tree.beginValueAll(); it; ++it) {
    openvdb::Vec3d c;
    if (it.isVoxelValue()) c = it.getCoord().asVec3d();
    else c = it.getBoundingBox().getCenter();
    const double x = origin[0] + h * c.x(), y = origin[1] + h * c.y(), z = origin[2] + h * c.z();
    const float v = std::fabs(*it);
    it.setValue(z < t.height(x, y) ? -v : v);
  }
  vb.t_sign = seconds_since(t0);
  vb.grid->setGridClass(openvdb::GRID_LEVEL_SET);
  return vb;
}

// Trilinear value and unit gradient from the 8 samples: the core's own (geom/trilinear.h),
// so that both structures differ only in how they find the samples.
inline double trilinear(const float v[8], const double f[3], double grad[3])
{
  double du[3];
  const double phi = trilinear_cell(v, f, du);
  unit_gradient(du, grad);
  return phi;
}

// (1) the 8 samples by BoxSampler::probeValues through a ConstAccessor, then the core's
// trilinear value + gradient.
inline double vdb_eval_probe(const VdbBand &vb, openvdb::FloatGrid::ConstAccessor &acc,
                             const double p[3], double grad[3])
{
  double u[3], f[3];
  int c[3];
  for (int a = 0; a < 3; a++) {
    u[a] = (p[a] - vb.origin[a]) / vb.h;
    c[a] = (int)std::floor(u[a]);
    f[a] = u[a] - c[a];
  }
  float d[2][2][2];
  openvdb::tools::BoxSampler::probeValues(d, acc, openvdb::Coord(c[0], c[1], c[2]));
  const float v[8] = {d[0][0][0], d[1][0][0], d[0][1][0], d[1][1][0],
                      d[0][0][1], d[1][0][1], d[0][1][1], d[1][1][1]};
  return trilinear(v, f, grad);
}

// (2) OpenVDB's own API: BoxSampler::sample for the value, math::ISGradient (second-order
// central differences at the nearest voxel) for the gradient, normalised.
inline double vdb_eval_api(const VdbBand &vb, openvdb::FloatGrid::ConstAccessor &acc,
                           const double p[3], double grad[3])
{
  const openvdb::Vec3R u((p[0] - vb.origin[0]) / vb.h, (p[1] - vb.origin[1]) / vb.h,
                         (p[2] - vb.origin[2]) / vb.h);
  float v;
  openvdb::tools::BoxSampler::sample(acc, u, v);
  const openvdb::Coord c(openvdb::Coord::round(u));
  openvdb::Vec3f g = openvdb::math::ISGradient<openvdb::math::CD_2ND>::result(acc, c);
  const double n = g.length();
  if (n > 0) grad[0] = g[0] / n, grad[1] = g[1] / n, grad[2] = g[2] / n;
  else grad[0] = 1, grad[1] = grad[2] = 0;
  return v;
}

// ---------------------------------------------------------------- statistics ----

struct Diff {
  double max = 0, sum2 = 0, gmax = 0, gsum2 = 0;
  long n = 0, sign = 0;
  void add(double a, const double ga[3], double b, const double gb[3])
  {
    const double e = std::fabs(a - b);
    max = std::max(max, e), sum2 += e * e;
    const double c = std::min(1.0, std::max(-1.0, ga[0] * gb[0] + ga[1] * gb[1] + ga[2] * gb[2]));
    const double ang = std::acos(c) * 180.0 / M_PI;
    gmax = std::max(gmax, ang), gsum2 += ang * ang;
    if ((a < 0) != (b < 0)) sign++;
    n++;
  }
  double rms() const { return n ? std::sqrt(sum2 / n) : NAN; }
  double grms() const { return n ? std::sqrt(gsum2 / n) : NAN; }
  double mx() const { return n ? max : NAN; }
  double gmx() const { return n ? gmax : NAN; }
};

// The stored samples themselves against the exact distance clamped to the band, at every
// sample within width of the surface in every stride-th column of samples over the
// footprint (sample (i, j, k) at origin + h (i, j, k); both structures share the lattice).
struct Lattice {
  long n = 0, off = 0, sign = 0;
  double max = 0;
};

template <class F>
Lattice lattice_check(const Terrain &t, const Mesh &m, const double origin[3], double h,
                      double width, int stride, F sample)
{
  Lattice L;
  const int i0 = (int)std::ceil((0.0 - origin[0]) / h), i1 = (int)std::floor((t.N - origin[0]) / h);
  const int j0 = (int)std::ceil((0.0 - origin[1]) / h), j1 = (int)std::floor((t.N - origin[1]) / h);
  for (int j = j0; j <= j1; j += stride)
    for (int i = i0; i <= i1; i += stride) {
      const double x = origin[0] + h * i, y = origin[1] + h * j, H = t.height(x, y);
      const int k0 = (int)std::floor((H - 2 * width - h - origin[2]) / h);
      const int k1 = (int)std::ceil((H + 2 * width + h - origin[2]) / h);
      for (int k = std::max(k0, 0); k <= k1; k++) {
        const double p[3] = {x, y, origin[2] + h * k};
        double g[3];
        const double d = exact_distance(t, m, p, width + h, g);
        if (!(std::fabs(d) < width)) continue;
        const double v = sample(i, j, k, p), e = std::fabs(v - d);
        L.n++;
        L.max = std::max(L.max, e);
        if (e > 1e-4 * h) L.off++;
        if ((v < 0) != (d < 0)) L.sign++;
      }
    }
  return L;
}

template <class F>
double time_lookups(int reps, const std::vector<double> &pts, F eval, double *sink)
{
  const size_t n = pts.size() / 3;
  double best = HUGE_VAL;
  for (int r = 0; r < reps; r++) {
    double acc = 0, g[3];
    const auto t0 = Clock::now();
    for (size_t k = 0; k < n; k++) acc += eval(&pts[3 * k], g) + g[2];
    best = std::min(best, seconds_since(t0));
    *sink += acc;
  }
  return best / (double)n * 1e9;
}

void usage()
{
  std::fprintf(stderr,
               "usage: band_vs_openvdb [--n N] [--points M] [--exact K] [--reps R] [--seed S]\n"
               "                       [--signed-test] [--no-ours] [--no-vdb]\n"
               "  --n N          terrain cells per side (default 1000; e.g. 4000)\n"
               "  --points M     lookup points within the band (default 1000000)\n"
               "  --exact K      of which K compared with the exact distance (default: all M)\n"
               "  --reps R       timing repetitions, the fastest kept (default 3)\n"
               "  --lattice S    check the stored samples in every S-th column (default 5,\n"
               "                 0: not)\n"
               "  --signed-test  also build OpenVDB's signed conversion (meshToLevelSet's)\n"
               "                 of the open surface and count its sign errors\n");
}

} // namespace

int main(int argc, char **argv)
{
  int N = 1000, reps = 3, stride = 5;
  long M = 1000000, K = -1;
  uint64_t seed = 42;
  bool signed_test = false, do_ours = BENCH_HAVE_BAND_BUILDER, do_vdb = true;
  for (int a = 1; a < argc; a++) {
    std::string s = argv[a];
    auto next = [&]() -> const char * {
      if (a + 1 >= argc) { usage(); std::exit(2); }
      return argv[++a];
    };
    if (s == "--n") N = std::atoi(next());
    else if (s == "--points") M = std::atol(next());
    else if (s == "--exact") K = std::atol(next());
    else if (s == "--reps") reps = std::atoi(next());
    else if (s == "--lattice") stride = std::atoi(next());
    else if (s == "--seed") seed = std::strtoull(next(), nullptr, 10);
    else if (s == "--signed-test") signed_test = true;
    else if (s == "--no-ours") do_ours = false;
    else if (s == "--no-vdb") do_vdb = false;
    else { usage(); return 2; }
  }
  if (N < 8 || M < 1 || reps < 1 || stride < 0) { usage(); return 2; }
  if (K < 0 || K > M) K = M;
  const double h = 1.0, width = 2.0;

  std::setvbuf(stdout, nullptr, _IOLBF, 0); // progress lines as they come, also into a pipe
  // one thread everywhere (OpenVDB's conversion uses TBB)
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  openvdb::initialize();

  auto t0 = Clock::now();
  Terrain ter = make_terrain(N, seed);
  Mesh mesh = make_mesh(ter);
  // The project's triangulation when it takes this size (lsdem_heightmap_mesh refuses more
  // than LSDEM_MESH_MAX_TRIS triangles, N > 2896), checked to be the bench's own.
  const char *mesh_from = "the bench's own triangulation (above LSDEM_MESH_MAX_TRIS for "
                          "lsdem_heightmap_mesh)";
  if (2.0 * N * N <= LSDEM_MESH_MAX_TRIS) {
    lsdem_heightmap hm;
    hm.nx = hm.ny = N + 1, hm.x0 = hm.y0 = 0.0, hm.cell = h, hm.z = ter.z.data();
    lsdem_mesh lm;
    lsdem_error err;
    if (lsdem_heightmap_mesh(&hm, &lm, &err) != LSDEM_OK) {
      std::printf("lsdem_heightmap_mesh failed: %s\n", err.msg);
      return 1;
    }
    const bool same = (size_t)lm.nverts * 3 == mesh.verts.size() &&
                      (size_t)lm.ntris * 3 == mesh.tris.size() &&
                      !std::memcmp(lm.verts, mesh.verts.data(), mesh.verts.size() * sizeof(double)) &&
                      !std::memcmp(lm.tris, mesh.tris.data(), mesh.tris.size() * sizeof(int));
    lsdem_mesh_free(&lm);
    if (!same) {
      std::printf("lsdem_heightmap_mesh's triangles differ from the bench's\n");
      return 1;
    }
    mesh_from = "lsdem_heightmap_mesh (identical to the bench's own)";
  }
  std::printf("terrain: %d x %d cells (cell %g), heights %.2f..%.2f (relief %.1f), %zu triangles "
              "from %s (%.1f s to make)\n",
              N, N, h, ter.zmin, ter.zmax, ter.zmax - ter.zmin, mesh.tris.size() / 3, mesh_from,
              seconds_since(t0));

  // ---- lookup points: uniform over the footprint, within the band by the exact distance
  t0 = Clock::now();
  std::vector<double> pts, exact, exact_grad;
  pts.reserve(3 * M), exact.reserve(M), exact_grad.reserve(3 * M);
  {
    std::mt19937_64 rng(seed + 1);
    std::uniform_real_distribution<double> ux(0.0, (double)N), uz(-2.4, 2.4);
    while ((long)exact.size() < M) {
      double p[3] = {ux(rng), ux(rng), 0.0}, g[3];
      p[2] = ter.height(p[0], p[1]) + uz(rng);
      const double d = exact_distance(ter, mesh, p, 2.5, g);
      if (!(std::fabs(d) < width)) continue;
      pts.insert(pts.end(), p, p + 3);
      exact.push_back(d);
      exact_grad.insert(exact_grad.end(), g, g + 3);
    }
  }
  // the same points in a coherent order (by 8 x 8 column of cells, rows of columns)
  std::vector<double> pts_sorted(pts.size());
  {
    std::vector<uint32_t> order(M);
    for (long k = 0; k < M; k++) order[k] = (uint32_t)k;
    auto key = [&](uint32_t k) {
      return (int64_t)((int)pts[3 * k + 1] >> 3) * (N / 8 + 1) + ((int)pts[3 * k] >> 3);
    };
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
    for (long k = 0; k < M; k++) std::memcpy(&pts_sorted[3 * k], &pts[3 * (size_t)order[k]], 24);
  }
  std::printf("points: %ld within |d| < %g (exact distance, %.1f s), %ld compared with it\n", M,
              width, seconds_since(t0), K);

  const double relief = ter.zmax - ter.zmin;
  const double dense_bytes = (double)(N / h + 1) * (N / h + 1) * (std::ceil((relief + 2 * width) / h) + 1) * 4.0;
  std::printf("dense grid: (N+1)^2 x (relief + 2 width)/h = %d^2 x %.0f floats = %.1f MB\n",
              (int)(N / h) + 1, std::ceil((relief + 2 * width) / h) + 1, dense_bytes / 1e6);

  double origin[3] = {0.0, 0.0, std::floor(ter.zmin - width - 1.0)};
  double sink = 0;

  // ---- (b) ours
  double ours_build = NAN, ours_far = NAN, ours_bytes = NAN, ours_total_bytes = NAN, ours_ns = NAN, ours_ns_sorted = NAN;
  long ours_bricks = 0;
  Lattice ours_lat, vdb_lat;
  std::vector<double> ours_phi, ours_grad;
#if BENCH_HAVE_BAND_BUILDER
  lsdem_band band;
  std::memset(&band, 0, sizeof band);
  uint16_t *far = nullptr;
  if (do_ours) {
    lsdem_mesh lm;
    lm.nverts = (int)(mesh.verts.size() / 3), lm.ntris = (int)(mesh.tris.size() / 3);
    lm.verts = mesh.verts.data(), lm.tris = mesh.tris.data();
    lsdem_error err;
    err.msg[0] = 0;
    t0 = Clock::now();
    lsdem_status st = lsdem_band_from_mesh(&lm, h, width, LSDEM_BAND_TERRAIN, &band, &err);
    ours_build = seconds_since(t0);
    if (st != LSDEM_OK) {
      std::printf("ours: lsdem_band_from_mesh failed: %s (%s)\n", lsdem_status_name(st), err.msg);
      do_ours = false;
    } else {
      t0 = Clock::now();
      st = lsdem_band_far(&band, &far, &err);
      ours_far = seconds_since(t0);
      if (st != LSDEM_OK) {
        std::printf("ours: lsdem_band_far failed: %s\n", err.msg);
        return 1;
      }
      band.far = far;
      // the level set alone (index, coarse level, bricks): what OpenVDB's grid holds; a band
      // that also keeps its surface (triangles and per-brick lists) counts it in
      // lsdem_band_bytes, printed beside
      const double slots = (double)band.nb[0] * band.nb[1] * band.nb[2];
      ours_bytes = slots * (sizeof(int32_t) + sizeof(uint16_t)) +
                   (double)band.nbricks * LSDEM_BAND_BRICK_SAMPLES * sizeof(float);
      ours_total_bytes = (double)lsdem_band_bytes(&band);
      ours_bricks = (long)band.nbricks;
      std::memcpy(origin, band.origin, sizeof origin); // OpenVDB's voxels on our samples
      // stored bricks none of whose samples lies strictly within the band (all +-width):
      // what the conservative selection (triangle boxes grown by width) adds
      long idle = 0;
      const float w = (float)band.width;
      for (long b = 0; b < ours_bricks; b++) {
        const float *q = band.phi + (size_t)b * LSDEM_BAND_BRICK_SAMPLES;
        bool any = false;
        for (int k = 0; k < LSDEM_BAND_BRICK_SAMPLES && !any; k++) any = std::fabs(q[k]) < w;
        idle += !any;
      }
      std::printf("ours: n = %d x %d x %d samples, origin (%g, %g, %g), %d x %d x %d brick "
                  "slots, %ld stored, of which %ld hold no sample within the band\n",
                  band.n[0], band.n[1], band.n[2], band.origin[0], band.origin[1],
                  band.origin[2], band.nb[0], band.nb[1], band.nb[2], ours_bricks, idle);
      ours_ns = time_lookups(reps, pts, [&](const double *p, double *g) {
        return lsdem_band_eval(&band, p, g); }, &sink);
      ours_ns_sorted = time_lookups(reps, pts_sorted, [&](const double *p, double *g) {
        return lsdem_band_eval(&band, p, g); }, &sink);
      if (stride > 0)
        ours_lat = lattice_check(ter, mesh, origin, h, width, stride,
                                 [&](int, int, int, const double *p) {
                                   double g[3];
                                   return lsdem_band_eval(&band, p, g);
                                 });
      ours_phi.resize(M), ours_grad.resize(3 * M);
      lsdem_band_eval_many(&band, (int)M, pts.data(), ours_phi.data(), ours_grad.data());
    }
  }
#else
  do_ours = false;
  std::printf("ours: lsdem_band_from_mesh not available in this tree (built without it)\n");
#endif

  // ---- (a) OpenVDB
  double vdb_build = NAN, vdb_mesh = NAN, vdb_sign = NAN, vdb_bytes = NAN, vdb_ns = NAN,
         vdb_ns_sorted = NAN, api_ns = NAN, api_ns_sorted = NAN;
  long vdb_leaves = 0, vdb_active = 0;
  std::vector<double> vdb_phi, vdb_grad, api_phi, api_grad;
  if (do_vdb) {
    t0 = Clock::now();
    VdbBand vb = build_vdb(ter, mesh, origin, h, width, false);
    vdb_build = seconds_since(t0);
    vdb_mesh = vb.t_mesh, vdb_sign = vb.t_sign;
    vdb_bytes = (double)vb.grid->memUsage();
    vdb_leaves = (long)vb.grid->tree().leafCount();
    vdb_active = (long)vb.grid->activeVoxelCount();
    std::printf("openvdb %s: %ld leaves (8^3), %ld active voxels, background %g; "
                "meshToVolume %.2f s + sign and flood fill %.2f s\n",
                openvdb::getLibraryVersionString(), vdb_leaves, vdb_active,
                (double)vb.grid->background(), vb.t_mesh, vb.t_sign);
    openvdb::FloatGrid::ConstAccessor acc = vb.grid->getConstAccessor();
    vdb_ns = time_lookups(reps, pts, [&](const double *p, double *g) {
      return vdb_eval_probe(vb, acc, p, g); }, &sink);
    vdb_ns_sorted = time_lookups(reps, pts_sorted, [&](const double *p, double *g) {
      return vdb_eval_probe(vb, acc, p, g); }, &sink);
    api_ns = time_lookups(reps, pts, [&](const double *p, double *g) {
      return vdb_eval_api(vb, acc, p, g); }, &sink);
    api_ns_sorted = time_lookups(reps, pts_sorted, [&](const double *p, double *g) {
      return vdb_eval_api(vb, acc, p, g); }, &sink);
    if (stride > 0)
      vdb_lat = lattice_check(ter, mesh, origin, h, width, stride,
                              [&](int i, int j, int k, const double *) {
                                return (double)acc.getValue(openvdb::Coord(i, j, k));
                              });
    vdb_phi.resize(M), vdb_grad.resize(3 * M), api_phi.resize(M), api_grad.resize(3 * M);
    for (long k = 0; k < M; k++) {
      vdb_phi[k] = vdb_eval_probe(vb, acc, &pts[3 * k], &vdb_grad[3 * k]);
      api_phi[k] = vdb_eval_api(vb, acc, &pts[3 * k], &api_grad[3 * k]);
    }
    if (signed_test) {
      t0 = Clock::now();
      VdbBand vs = build_vdb(ter, mesh, origin, h, width, true);
      const double ts = seconds_since(t0);
      openvdb::FloatGrid::ConstAccessor as = vs.grid->getConstAccessor();
      Diff ds;
      for (long k = 0; k < K; k++) {
        double g[3];
        const double v = vdb_eval_probe(vs, as, &pts[3 * k], g);
        ds.add(v, g, exact[k], &exact_grad[3 * k]);
      }
      std::printf("openvdb signed conversion of the open surface (meshToLevelSet's): %.2f s, "
                  "%.1f MB; against the exact distance at %ld points: %ld wrong signs "
                  "(%.2f %%), max |diff| %.3f h, RMS %.3f h\n",
                  ts, vs.grid->memUsage() / 1e6, K, ds.sign, 100.0 * ds.sign / K, ds.max / h,
                  ds.rms() / h);
    }
  }

  // ---- agreement and accuracy
  Diff ours_vs_vdb, ours_ex, vdb_ex, api_ex, api_vs_vdb;
  for (long k = 0; k < M; k++) {
    if (do_ours && do_vdb) ours_vs_vdb.add(ours_phi[k], &ours_grad[3 * k], vdb_phi[k], &vdb_grad[3 * k]);
    if (do_vdb) api_vs_vdb.add(api_phi[k], &api_grad[3 * k], vdb_phi[k], &vdb_grad[3 * k]);
    if (k >= K) continue;
    if (do_ours) ours_ex.add(ours_phi[k], &ours_grad[3 * k], exact[k], &exact_grad[3 * k]);
    if (do_vdb) {
      vdb_ex.add(vdb_phi[k], &vdb_grad[3 * k], exact[k], &exact_grad[3 * k]);
      api_ex.add(api_phi[k], &api_grad[3 * k], exact[k], &exact_grad[3 * k]);
    }
  }

  auto cell = [](double v, const char *fmt) {
    static char buf[8][64];
    static int i = 0;
    i = (i + 1) % 8;
    if (std::isnan(v)) std::snprintf(buf[i], 64, "%s", "-");
    else std::snprintf(buf[i], 64, fmt, v);
    return buf[i];
  };
  std::printf("\n| N = %d, h = %g, width = %g, one thread | ours (lsdem_band) | OpenVDB %s |\n",
              N, h, width, openvdb::getLibraryVersionString());
  std::printf("|---|---|---|\n");
  std::printf("| build time, s | %s (+ coarse level %s) | %s (meshToVolume %s + sign %s) |\n",
              cell(ours_build, "%.2f"), cell(ours_far, "%.3f"), cell(vdb_build, "%.2f"),
              cell(vdb_mesh, "%.2f"), cell(vdb_sign, "%.2f"));
  std::printf("| memory, MB | %s (%ld bricks of 9^3; lsdem_band_bytes %s) | %s (%ld leaves of 8^3) |\n",
              cell(ours_bytes / 1e6, "%.1f"), ours_bricks, cell(ours_total_bytes / 1e6, "%.1f"),
              cell(vdb_bytes / 1e6, "%.1f"), vdb_leaves);
  std::printf("| memory, %% of the dense grid (%.0f MB) | %s | %s |\n", dense_bytes / 1e6,
              cell(100.0 * ours_bytes / dense_bytes, "%.2f"), cell(100.0 * vdb_bytes / dense_bytes, "%.2f"));
  std::printf("| lookup value + gradient, ns/point, random order | %s | %s (BoxSampler + ISGradient: %s) |\n",
              cell(ours_ns, "%.1f"), cell(vdb_ns, "%.1f"), cell(api_ns, "%.1f"));
  std::printf("| same, points sorted by 8x8 column | %s | %s (BoxSampler + ISGradient: %s) |\n",
              cell(ours_ns_sorted, "%.1f"), cell(vdb_ns_sorted, "%.1f"), cell(api_ns_sorted, "%.1f"));
  if (do_ours && do_vdb)
    std::printf("| ours vs OpenVDB at %ld points: max / RMS |phi diff|, h | %s / %s | (gradient angle max / RMS: %s / %s deg) |\n",
                M, cell(ours_vs_vdb.mx() / h, "%.2g"), cell(ours_vs_vdb.rms() / h, "%.2g"),
                cell(ours_vs_vdb.gmx(), "%.2g"), cell(ours_vs_vdb.grms(), "%.2g"));
  std::printf("| vs exact distance at %ld points: max / RMS error, h | %s / %s | %s / %s (ISGradient path: %s / %s) |\n",
              K, cell(ours_ex.mx() / h, "%.4f"), cell(ours_ex.rms() / h, "%.4f"),
              cell(vdb_ex.mx() / h, "%.4f"), cell(vdb_ex.rms() / h, "%.4f"),
              cell(api_ex.mx() / h, "%.4f"), cell(api_ex.rms() / h, "%.4f"));
  std::printf("| vs exact: gradient angle max / RMS, deg | %s / %s | %s / %s (ISGradient path: %s / %s) |\n",
              cell(ours_ex.gmx(), "%.2f"), cell(ours_ex.grms(), "%.2f"), cell(vdb_ex.gmx(), "%.2f"),
              cell(vdb_ex.grms(), "%.2f"), cell(api_ex.gmx(), "%.2f"), cell(api_ex.grms(), "%.2f"));
  std::printf("| vs exact: wrong signs | %s | %s |\n", cell(do_ours ? (double)ours_ex.sign : NAN, "%.0f"),
              cell(do_vdb ? (double)vdb_ex.sign : NAN, "%.0f"));
  if (stride > 0) {
    auto lat = [&](const Lattice &L, bool on) {
      static char buf[2][128];
      static int i = 0;
      i ^= 1;
      if (!on || !L.n) std::snprintf(buf[i], 128, "-");
      else std::snprintf(buf[i], 128, "%ld of %ld (max %.3f h), %ld wrong signs", L.off, L.n, L.max / h, L.sign);
      return buf[i];
    };
    std::printf("| stored samples within the band off the exact distance by > 1e-4 h (every %d-th column) | %s | %s |\n",
                stride, lat(ours_lat, do_ours), lat(vdb_lat, do_vdb));
  }
  std::printf("(checksum %g)\n", sink);
#if BENCH_HAVE_BAND_BUILDER
  if (do_ours) {
    free(far);
    band.far = nullptr;
    lsdem_band_free(&band);
  }
#endif
  return 0;
}
