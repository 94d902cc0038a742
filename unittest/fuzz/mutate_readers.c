/* mutate_readers.c -- deterministic mutation test of the file readers (CTest, under ASan
 * and UBSan): valid morphology, positions, rotations, shape-library, multi-page TIFF (one
 * written by hand, two by libtiff: LZW strips, a Deflate-tiled BigTIFF volume), binary and
 * ASCII STL and OBJ files and a net file are written, then every reader runs over all their truncations and a few thousand variants with
 * flipped, replaced, inserted or deleted bytes. For library variants whose header/TOC was
 * edited, the header checksum is re-sealed half of the time (lsdem_fuzz_reseal_library)
 * so the mutation reaches the TOC checks instead of stopping at the checksum. Passes when
 * nothing crashes, no sanitizer reports, every failure is a known status with a message,
 * and both outcomes (accepted, rejected) occur.
 *
 *   mutate_readers               run the test
 *   mutate_readers --seeds DIR   write the valid seed files to DIR (a libFuzzer corpus) */
#include "file_writers.h"
#include "fuzz_readers.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MUTATIONS_PER_SEED = 800, NSEEDS = 11 };

typedef struct {
  unsigned char *data;
  size_t size;
  int is_library;
} seed_file;

static uint64_t rng_state = 0x9e3779b97f4a7c15ULL;

static uint64_t rng_next(void) /* xorshift64* */
{
  rng_state ^= rng_state >> 12;
  rng_state ^= rng_state << 25;
  rng_state ^= rng_state >> 27;
  return rng_state * 2685821657736338717ULL;
}

static size_t rng_below(size_t n) { return n ? (size_t)(rng_next() % n) : 0; }

/* The whole file, or NULL; the core's reader (no size limit needed for test files). */
static unsigned char *slurp(const char *path, size_t *n)
{
  unsigned char *b = NULL;
  *n = 0;
  return lsdem_read_file(path, SIZE_MAX, &b, n, NULL) == LSDEM_OK ? b : NULL;
}

static void spill(const char *path, const void *b, size_t n)
{
  FILE *f = fopen(path, "wb");
  if (!f) return;
  fwrite(b, 1, n, f);
  fclose(f);
}

/* A 6x5x7 grid of a sphere of radius 2 (spacing 1), 8 nodes, as a morph and as a shape. */
static float sphere_phi[6 * 5 * 7];
static double sphere_nodes[3 * 8];

static void make_sphere_morph(lsdem_morph *m)
{
  memset(m, 0, sizeof *m);
  m->n[0] = 6, m->n[1] = 5, m->n[2] = 7;
  m->cm_grid[0] = 2.5, m->cm_grid[1] = 2.0, m->cm_grid[2] = 3.0;
  size_t q = 0;
  for (int k = 0; k < 7; k++)
    for (int j = 0; j < 5; j++)
      for (int i = 0; i < 6; i++)
        sphere_phi[q++] = (float)(sqrt(pow(i - 2.5, 2) + pow(j - 2.0, 2) + pow(k - 3.0, 2)) - 2.0);
  for (int v = 0; v < 8; v++)
    for (int a = 0; a < 3; a++) sphere_nodes[3 * v + a] = ((v >> a) & 1 ? 2.0 : -2.0) / sqrt(3.0);
  m->phi = sphere_phi;
  m->nodes = sphere_nodes;
  m->nnodes = 8;
  m->mass = 4.0 / 3.0 * 3.14159265358979323846 * 8.0;
  for (int a = 0; a < 3; a++) m->inertia[a] = 0.4 * m->mass * 4.0;
  m->radius = 2.0;
}

/* The label image and mesh seeds: a 2-page 16-bit TIFF in two strips per page (written
 * here), the same labels written by libtiff as big-endian LZW strips and as a Deflate-
 * compressed tiled BigTIFF volume (one page, ImageDepth 2), a cube as binary and ASCII STL,
 * and a quad cube as OBJ. */
static void make_image_mesh_seeds(void)
{
  uint32_t v[3 * 4 * 2];
  for (int i = 0; i < 24; i++) v[i] = (uint32_t)(i % 5 == 0 ? 0 : 1 + i % 3);
  const int n[3] = {3, 4, 2};
  const tiff_opts o = {0, 16, 2, 1, 1};
  bytes t = make_tiff(n, v, o, NULL, NULL);
  spill("seed_image.tif", t.b, t.n);
  free(t.b);
  const libtiff_opts lzw = {16, SAMPLEFORMAT_UINT, COMPRESSION_LZW, 0, 0, 1, 0};
  const libtiff_opts zip = {8, SAMPLEFORMAT_UINT, COMPRESSION_ADOBE_DEFLATE, 1, 1, 0, 1};
  write_tiff_libtiff("seed_image_lzw.tif", n, v, lzw);
  write_tiff_libtiff("seed_image_zip.tif", n, v, zip);
  tris cube = {0};
  const double c[3] = {0.5, 0, 0}, h[3] = {1, 0.5, 0.75};
  add_box(&cube, c, h, -1);
  write_stl_binary("seed_mesh_binary.stl", &cube, 0);
  write_stl_ascii("seed_mesh_ascii.stl", &cube);
  free(cube.t);
  const char *obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf -8 -4 -1 -5\n";
  spill("seed_mesh.obj", obj, strlen(obj));
}

/* The net seed: a 3 x 3 hexagonal net, two sides clamped (lsdem_net_write). */
static int make_net_seed(void)
{
  lsdem_net_params p = {LSDEM_NET_HEX, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 1.8}, 1.0, 0.9,
                        LSDEM_NET_EDGE_U0 | LSDEM_NET_EDGE_V1};
  lsdem_net net;
  lsdem_error err;
  if (lsdem_net_build(&p, &net, &err) != LSDEM_OK) return 0;
  for (int b = 0; b < net.nballs; b++) net.id[b] = 10 + b;
  const lsdem_status st = lsdem_net_write("seed_net.net", &net, &err);
  lsdem_net_free(&net);
  return st == LSDEM_OK;
}

/* Valid seeds: a morph file, positions, rotations, a library of a grid shape (from the
 * morph) and an analytic sphere, then the image and mesh seeds. */
static int make_seeds(seed_file seeds[NSEEDS])
{
  lsdem_error err;
  lsdem_morph m;
  make_sphere_morph(&m);
  if (lsdem_morph_write("seed_morph.dat", &m, &err) != LSDEM_OK) {
    fprintf(stderr, "seed morph: %s\n", err.msg);
    return 0;
  }
  const char *pos = "1.5 2.5 3.5\n4 5 6\n\n-7.25 8e1 9\n";
  const char *rot = "0 0 0 1\n0.5 0.5 0.5 0.5\n0.6 0 0.8 0\n";
  spill("seed_positions.dat", pos, strlen(pos));
  spill("seed_rotations.dat", rot, strlen(rot));
  double nodes[24], area[8], sph[32];
  int start[9];
  lsdem_shape shapes[2];
  if (lsdem_morph_to_shape(&m, nodes, area, start, sph, &shapes[0], &err) != LSDEM_OK) {
    fprintf(stderr, "seed shape: %s\n", err.msg);
    return 0;
  }
  shapes[1] = shapes[0];
  memset(&shapes[1].sdf, 0, sizeof shapes[1].sdf);
  shapes[1].sdf.kind = LSDEM_SDF_SPHERE;
  shapes[1].sdf.a[0] = 2.0;
  const char *names[2] = {"grid sphere", "analytic sphere"};
  if (lsdem_library_write("seed_library.lslib", shapes, names, 2, &err) != LSDEM_OK) {
    fprintf(stderr, "seed library: %s\n", err.msg);
    return 0;
  }
  make_image_mesh_seeds();
  if (!make_net_seed()) return 0;
  const char *files[NSEEDS] = {"seed_morph.dat", "seed_positions.dat", "seed_rotations.dat",
                               "seed_library.lslib", "seed_image.tif", "seed_image_lzw.tif",
                               "seed_image_zip.tif", "seed_mesh_binary.stl",
                               "seed_mesh_ascii.stl", "seed_mesh.obj", "seed_net.net"};
  for (int s = 0; s < NSEEDS; s++) {
    seeds[s].data = slurp(files[s], &seeds[s].size);
    seeds[s].is_library = s == 3;
    if (!seeds[s].data || !seeds[s].size) return 0;
  }
  return 1;
}

/* One random edit of buf (length *n, capacity cap). */
static void mutate(unsigned char *buf, size_t *n, size_t cap, int is_library)
{
  static const unsigned char interesting[] = {0, 0xff, 0x7f, 0x80, '-', '9', '.', 'e', 'n',
                                              '\n', ' ', '\r', '+', 'i'};
  const int edits = 1 + (int)rng_below(4);
  for (int e = 0; e < edits && *n > 0; e++) {
    /* Libraries: aim half of the edits at the header and TOC. */
    size_t limit = is_library && (rng_next() & 1) && *n > 64 + 2 * 360 ? 64 + 2 * 360 : *n;
    const size_t at = rng_below(limit);
    switch (rng_below(5)) {
    case 0: buf[at] ^= (unsigned char)(1u << rng_below(8)); break;
    case 1: buf[at] = interesting[rng_below(sizeof interesting)]; break;
    case 2: buf[at] = (unsigned char)rng_next(); break;
    case 3: /* delete a byte */
      memmove(buf + at, buf + at + 1, *n - at - 1);
      (*n)--;
      break;
    default: /* insert a byte */
      if (*n < cap) {
        memmove(buf + at + 1, buf + at, *n - at);
        buf[at] = interesting[rng_below(sizeof interesting)];
        (*n)++;
      }
    }
  }
  if (is_library && (rng_next() & 1)) lsdem_fuzz_reseal_library(buf, *n);
}

static void write_seeds(const char *dir, const seed_file seeds[NSEEDS])
{
  const char *names[NSEEDS] = {"morph.dat", "positions.dat", "rotations.dat", "library.lslib",
                               "image.tif", "image_lzw.tif", "image_zip.tif", "mesh_binary.stl",
                               "mesh_ascii.stl", "mesh.obj", "net.net"};
  char path[4096];
  for (int s = 0; s < NSEEDS; s++) {
    snprintf(path, sizeof path, "%s/%s", dir, names[s]);
    spill(path, seeds[s].data, seeds[s].size);
  }
}

int main(int argc, char **argv)
{
  seed_file seeds[NSEEDS];
  if (!make_seeds(seeds)) {
    fprintf(stderr, "could not build the seed files\n");
    return 1;
  }
  if (argc == 3 && strcmp(argv[1], "--seeds") == 0) {
    write_seeds(argv[2], seeds);
    for (int s = 0; s < NSEEDS; s++) free(seeds[s].data);
    return 0;
  }

  fuzz_tally t = {0};
  long variants = 0, broken = 0;
  for (int s = 0; s < NSEEDS; s++) {
    /* The unmodified seed must be accepted by its own reader. */
    fuzz_tally before = t;
    broken += lsdem_fuzz_readers(seeds[s].data, seeds[s].size, &t);
    const int accepted = s == 0 ? t.morph_ok > before.morph_ok
                       : s == 3 ? t.library_shapes_ok == before.library_shapes_ok + 2
                       : s >= 4 && s <= 6 ? t.image_ok > before.image_ok
                       : s == 10 ? t.net_ok > before.net_ok
                       : s >= 7 ? t.mesh_ok > before.mesh_ok
                                : t.rows_ok > before.rows_ok || s == 2;
    if (!accepted) {
      fprintf(stderr, "seed %d rejected by its reader\n", s);
      broken++;
    }
    const size_t stride = seeds[s].size > 2000 ? 5 : 1;
    for (size_t cut = 0; cut < seeds[s].size; cut += stride, variants++)
      broken += lsdem_fuzz_readers(seeds[s].data, cut, &t);
    const size_t cap = seeds[s].size + 8;
    unsigned char *buf = malloc(cap);
    for (int k = 0; k < MUTATIONS_PER_SEED; k++, variants++) {
      memcpy(buf, seeds[s].data, seeds[s].size);
      size_t n = seeds[s].size;
      mutate(buf, &n, cap, seeds[s].is_library);
      broken += lsdem_fuzz_readers(buf, n, &t);
    }
    free(buf);
  }
  printf("%ld variants: morph accepted %ld, positions accepted %ld, library opened %ld "
         "(shapes verified %ld), images accepted %ld, meshes accepted %ld, nets accepted %ld, "
         "contract violations %ld\n", variants, t.morph_ok, t.rows_ok, t.library_open,
         t.library_shapes_ok, t.image_ok, t.mesh_ok, t.net_ok, broken);
  const int both_outcomes = t.morph_ok > 1 && t.rows_ok > 1 && t.library_open > 1 &&
                            t.morph_ok < variants && t.library_open < variants &&
                            t.image_ok > 1 && t.image_ok < variants && t.mesh_ok > 1 &&
                            t.mesh_ok < variants && t.net_ok > 1 && t.net_ok < variants;
  if (!both_outcomes) fprintf(stderr, "mutations did not reach both outcomes\n");
  for (int s = 0; s < NSEEDS; s++) free(seeds[s].data);
  return broken != 0 || !both_outcomes;
}
