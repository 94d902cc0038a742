/* fuzz_readers.c -- one input, every file reader of the core: the bytes are read as a
 * morphology file, a positions file, a rotations file, a shape library, a TIFF (through
 * libtiff, as labels and as a grey volume) and a raw label image, and a mesh (STL binary/ASCII or OBJ by content). Whatever a
 * reader accepts is then used the way the package uses it (morph -> shape; library shapes
 * verified, every array touched, the level set evaluated), so a reader that accepts a
 * file it should have rejected shows up as a sanitizer report.
 *
 * Built two ways: as a libFuzzer target (clang, -DLSDEM_FUZZ=ON, LSDEM_LIBFUZZER defined)
 * and inside the deterministic CTest mutation test mutate_readers.c (gcc or clang + ASan). */
#include "fuzz_readers.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The readers take paths: each input goes through one scratch file per process. */
static char scratch[4096];

static void remove_scratch(void) { unlink(scratch); }

static const char *scratch_path(void)
{
  if (!scratch[0]) {
    const char *dir = getenv("TMPDIR");
    snprintf(scratch, sizeof scratch, "%s/lsdem_fuzz_readers_%ld.tmp", dir && *dir ? dir : "/tmp",
             (long)getpid());
    atexit(remove_scratch);
  }
  return scratch;
}

/* A non-OK status must be a known code and come with a message. */
static int contract_broken(lsdem_status st, const lsdem_error *err)
{
  if (st == LSDEM_OK) return 0;
  return st < LSDEM_ERR_ARG || st > LSDEM_ERR_NUMERIC || err->msg[0] == '\0';
}

static double touch(const double *v, size_t n)
{
  double s = 0.0;
  for (size_t i = 0; i < n; i++) s += v[i];
  return s;
}

static int fuzz_morph(const char *path, fuzz_tally *t)
{
  lsdem_morph m;
  lsdem_error err = {{0}};
  lsdem_status st = lsdem_morph_read(path, &m, &err);
  if (contract_broken(st, &err)) return 1;
  if (st != LSDEM_OK) return 0;
  t->morph_ok++;
  const size_t nn = m.nnodes > 0 ? (size_t)m.nnodes : 1;
  double *nodes = malloc(3 * nn * sizeof *nodes), *area = malloc(nn * sizeof *area);
  double *sph = malloc(4 * nn * sizeof *sph);
  int *start = malloc((nn + 1) * sizeof *start);
  lsdem_shape s;
  err.msg[0] = '\0';
  st = lsdem_morph_to_shape(&m, nodes, area, start, sph, &s, &err);
  int broken = contract_broken(st, &err);
  if (st == LSDEM_OK) {
    volatile double sink = touch(s.nodes, 3 * (size_t)s.nnodes) + touch(s.node_area, (size_t)s.nnodes) + s.radius;
    (void)sink;
  }
  free(nodes);
  free(area);
  free(sph);
  free(start);
  lsdem_morph_free(&m);
  return broken;
}

static int fuzz_rows(const char *path, fuzz_tally *t)
{
  double *v = NULL;
  int n = 0;
  lsdem_error err = {{0}};
  lsdem_status st = lsdem_read_positions(path, &v, &n, &err);
  int broken = contract_broken(st, &err) || (st != LSDEM_OK && v != NULL);
  if (st == LSDEM_OK) {
    t->rows_ok++;
    volatile double sink = touch(v, 3 * (size_t)n);
    (void)sink;
  }
  free(v);
  v = NULL;
  err.msg[0] = '\0';
  st = lsdem_read_rotations(path, &v, &n, &err);
  broken |= contract_broken(st, &err) || (st != LSDEM_OK && v != NULL);
  if (st == LSDEM_OK) {
    volatile double sink = touch(v, 4 * (size_t)n);
    (void)sink;
  }
  free(v);
  return broken;
}

/* Use every array of an accepted library the way the contact code would. */
static void use_shape(const lsdem_shape *s)
{
  volatile double sink = touch(s->nodes, 3 * (size_t)s->nnodes) +
                         touch(s->node_area, (size_t)s->nnodes) +
                         touch(s->cluster_sphere, 4 * (size_t)s->nclusters);
  for (int c = 0; c < s->nclusters; c++)
    for (int i = s->cluster_start[c]; i < s->cluster_start[c + 1]; i++) sink += s->nodes[3 * i];
  const double p[2][3] = {{0.0, 0.0, 0.0}, {0.3 * s->radius, -0.2 * s->radius, 2.0 * s->radius}};
  for (int k = 0; k < 2; k++) {
    double g[3];
    sink += lsdem_sdf_eval(&s->sdf, p[k], g);
  }
  (void)sink;
}

static int fuzz_library(const char *path, fuzz_tally *t)
{
  lsdem_library *lib = NULL;
  lsdem_error err = {{0}};
  const lsdem_status st = lsdem_library_open(path, &lib, &err);
  if (contract_broken(st, &err) || (st != LSDEM_OK && lib)) return 1;
  if (st != LSDEM_OK) return 0;
  t->library_open++;
  int broken = 0;
  for (int i = 0; i < lsdem_library_count(lib); i++) {
    err.msg[0] = '\0';
    const lsdem_status v = lsdem_library_verify(lib, i, &err);
    broken |= contract_broken(v, &err) || strlen(lsdem_library_name(lib, i)) >= 128;
    if (v == LSDEM_OK) {
      t->library_shapes_ok++;
      use_shape(lsdem_library_shape(lib, i));
    }
  }
  lsdem_library_close(lib);
  return broken;
}

/* An accepted label image goes through the grain builder when it is small. */
static int use_image(const lsdem_label_image *img)
{
  if ((long)img->n[0] * img->n[1] * img->n[2] > 4096) return 0;
  const lsdem_voxel_options o = {1.0, 1, 1, 1};
  lsdem_voxel_grain *g = NULL;
  int n = 0, dropped = 0;
  lsdem_error err = {{0}};
  const lsdem_status st = lsdem_voxel_grains(img, &o, &g, &n, &dropped, &err);
  const int broken = contract_broken(st, &err) || (st != LSDEM_OK && (g || n));
  lsdem_voxel_grains_free(g, n);
  return broken;
}

static int fuzz_images(const char *path, size_t size, fuzz_tally *t)
{
  lsdem_label_image img;
  lsdem_error err = {{0}};
  lsdem_status st = lsdem_image_read_tiff(path, &img, &err);
  int broken = contract_broken(st, &err) || (st != LSDEM_OK && img.label);
  if (st == LSDEM_OK) t->image_ok++, broken |= use_image(&img);
  lsdem_label_image_free(&img);
  lsdem_volume vol;
  err.msg[0] = '\0';
  st = lsdem_tiff_read_volume(path, &vol, &err);
  broken |= contract_broken(st, &err) || (st != LSDEM_OK && vol.data);
  if (st == LSDEM_OK) { /* every sample is there */
    volatile unsigned char sink = 0;
    const size_t nb = (size_t)vol.n[0] * vol.n[1] * vol.n[2] * vol.bytes;
    for (size_t i = 0; i < nb; i++) sink ^= ((const unsigned char *)vol.data)[i];
    (void)sink;
  }
  lsdem_volume_free(&vol);
  /* raw: as 16-bit little-endian slices of 4 x 2 voxels */
  const int n[3] = {4, 2, (int)(size / 16 > 0 ? size / 16 : 1)};
  err.msg[0] = '\0';
  st = lsdem_image_read_raw(path, n, LSDEM_VOXEL_U16, 0, &img, &err);
  broken |= contract_broken(st, &err) || (st != LSDEM_OK && img.label);
  if (st == LSDEM_OK) t->image_ok++, broken |= use_image(&img);
  lsdem_label_image_free(&img);
  return broken;
}

/* An accepted mesh is checked and, when closed and small, sampled. */
static int fuzz_mesh(const char *path, fuzz_tally *t)
{
  lsdem_mesh m;
  lsdem_error err = {{0}};
  lsdem_status st = lsdem_mesh_read(path, &m, &err);
  if (contract_broken(st, &err) || (st != LSDEM_OK && m.tris)) return 1;
  if (st != LSDEM_OK) return 0;
  t->mesh_ok++;
  int broken = 0;
  for (int i = 0; i < 3 * m.ntris; i++) broken |= m.tris[i] < 0 || m.tris[i] >= m.nverts;
  err.msg[0] = '\0';
  const lsdem_status closed = lsdem_mesh_check_closed(&m, NULL, &err);
  broken |= contract_broken(closed, &err);
  err.msg[0] = '\0';
  const lsdem_status self = lsdem_mesh_check_self_intersection(&m, NULL, &err);
  broken |= contract_broken(self, &err);
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (int i = 0; i < 3 * m.nverts; i++) lo = fmin(lo, m.verts[i]), hi = fmax(hi, m.verts[i]);
  if (closed == LSDEM_OK && self == LSDEM_OK && m.ntris <= 200 && hi > lo && hi - lo < 1e6) {
    lsdem_grid g;
    err.msg[0] = '\0';
    st = lsdem_mesh_sdf_grid(&m, (hi - lo) / 6.0, 1, &g, &err);
    broken |= contract_broken(st, &err);
    if (st == LSDEM_OK) lsdem_grid_free(&g);
  }
  lsdem_mesh_free(&m);
  return broken;
}

/* An accepted net file: every bond joins two balls of the file, clamp flags are 0 or 1. */
static int fuzz_net(const char *path, fuzz_tally *t)
{
  lsdem_net net;
  lsdem_error err = {{0}};
  lsdem_status st = lsdem_net_read(path, &net, &err);
  if (contract_broken(st, &err) || (st != LSDEM_OK && (net.id || net.clamp || net.bond)))
    return 1;
  if (st != LSDEM_OK) return 0;
  t->net_ok++;
  int broken = 0;
  for (int b = 0; b < 2 * net.nbonds; b++) broken |= net.bond[b] < 0 || net.bond[b] >= net.nballs;
  for (int b = 0; b < net.nballs; b++) broken |= net.clamp[b] != 0 && net.clamp[b] != 1;
  lsdem_net_free(&net);
  return broken;
}

/* Header/TOC checksum as doc/shape_library.rst defines it (FNV-1a 64 over header bytes
 * 0..55, then the TOC), stored little-endian at byte 56. */
void lsdem_fuzz_reseal_library(unsigned char *b, size_t n)
{
  if (n < 64) return;
  const uint32_t count = (uint32_t)b[20] | (uint32_t)b[21] << 8 | (uint32_t)b[22] << 16 |
                         (uint32_t)b[23] << 24;
  const uint64_t toc_end = 64 + 360 * (uint64_t)count;
  if (toc_end > n) return;
  uint64_t h = 14695981039346656037ULL;
  for (uint64_t i = 0; i < toc_end; i++) {
    if (i >= 56 && i < 64) continue;
    h = (h ^ b[i]) * 1099511628211ULL;
  }
  for (int i = 0; i < 8; i++) b[56 + i] = (unsigned char)(h >> (8 * i));
}

int lsdem_fuzz_readers(const uint8_t *data, size_t size, fuzz_tally *t)
{
  const char *path = scratch_path();
  FILE *f = fopen(path, "wb");
  if (!f) return 1;
  const int short_write = size && fwrite(data, 1, size, f) != size;
  if (fclose(f) != 0 || short_write) return 1;
  fuzz_tally unused = {0};
  if (!t) t = &unused;
  return fuzz_morph(path, t) + fuzz_rows(path, t) + fuzz_library(path, t) +
         fuzz_images(path, size, t) + fuzz_mesh(path, t) + fuzz_net(path, t);
}

#ifdef LSDEM_LIBFUZZER
/* Library inputs run twice: as given (mostly stopped by the header checksum) and with the
 * checksum re-sealed, so mutations of the TOC reach its checks. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  if (lsdem_fuzz_readers(data, size, NULL)) abort(); /* a reader broke its contract */
  if (size >= 64 && memcmp(data, "LSDEMLIB", 8) == 0) {
    unsigned char *copy = malloc(size);
    if (!copy) return 0;
    memcpy(copy, data, size);
    lsdem_fuzz_reseal_library(copy, size);
    const int broken = lsdem_fuzz_readers(copy, size, NULL);
    free(copy);
    if (broken) abort();
  }
  return 0;
}
#endif
