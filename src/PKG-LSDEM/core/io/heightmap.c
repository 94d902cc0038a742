/* heightmap.c -- terrain height maps (lsdem_io.h): ESRI ASCII grids, GeoTIFF (through
 * tiff.c) and grey PNG (through png.c), and the terrain surface as a triangle mesh for
 * the narrow band of a wall (lsdem-shape terrain). */
#include "lsdem_io.h"
#include "text_lexer.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define ASC_MAX_FILE_BYTES ((size_t)1 << 33) /* 8 GB of text */

void lsdem_heightmap_free(lsdem_heightmap *hm)
{
  if (!hm) return;
  free(hm->z);
  memset(hm, 0, sizeof *hm);
}

static lsdem_status alloc_heights(lsdem_heightmap *hm, long nx, long ny, const char *path,
                                  lsdem_error *err)
{
  if (nx < 1 || ny < 1 || (double)nx * (double)ny > (double)LSDEM_HEIGHTMAP_MAX_SAMPLES)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: %ld x %ld heights: not within 1 .. %ld "
                      "heights", path, nx, ny, (long)LSDEM_HEIGHTMAP_MAX_SAMPLES);
  hm->nx = (int)nx, hm->ny = (int)ny;
  hm->z = malloc((size_t)nx * (size_t)ny * sizeof(float));
  if (!hm->z) return lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: cannot allocate %ld x %ld heights",
                                path, nx, ny);
  return LSDEM_OK;
}

lsdem_status lsdem_heightmap_pad(lsdem_heightmap *hm, int cells, lsdem_error *err)
{
  if (cells < 0) return lsdem_fail(err, LSDEM_ERR_ARG, "height map: pad by %d cells", cells);
  const long nx = (long)hm->nx + 2L * cells, ny = (long)hm->ny + 2L * cells;
  lsdem_heightmap out = *hm;
  lsdem_status st = alloc_heights(&out, nx, ny, "height map (padded)", err);
  if (st != LSDEM_OK) return st;
  for (long j = 0; j < ny; j++)
    for (long i = 0; i < nx; i++) { /* the nearest height of the raster: its edge's */
      const long si = i < cells ? 0 : (i - cells >= hm->nx ? hm->nx - 1 : i - cells);
      const long sj = j < cells ? 0 : (j - cells >= hm->ny ? hm->ny - 1 : j - cells);
      out.z[(size_t)j * nx + i] = hm->z[(size_t)sj * hm->nx + si];
    }
  out.x0 = hm->x0 - cells * hm->cell;
  out.y0 = hm->y0 - cells * hm->cell;
  free(hm->z);
  *hm = out;
  return LSDEM_OK;
}

/* A raster of only nodata holds no terrain. */
static lsdem_status check_some_data(const lsdem_heightmap *hm, const char *path,
                                    lsdem_error *err)
{
  const size_t n = (size_t)hm->nx * hm->ny;
  for (size_t i = 0; i < n; i++)
    if (!isnan(hm->z[i])) return LSDEM_OK;
  return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: every height is nodata: no terrain", path);
}

/* ------------------------------------------------------------ ESRI ASCII grid ---- */

enum { K_NCOLS, K_NROWS, K_XLLCORNER, K_XLLCENTER, K_YLLCORNER, K_YLLCENTER, K_CELLSIZE,
       K_NODATA, K_COUNT };
static const char *const ASC_KEYS[K_COUNT] = {"ncols", "nrows", "xllcorner", "xllcenter",
                                              "yllcorner", "yllcenter", "cellsize",
                                              "NODATA_value"};
#define ASC_KEY_LIST "ncols, nrows, xllcorner or xllcenter, yllcorner or yllcenter, " \
                     "cellsize, NODATA_value"

/* The header: "key value" lines until the first line that starts with a number. */
static lsdem_status read_asc_header(text_lexer *lx, double val[K_COUNT], long at[K_COUNT],
                                    const char *path, lsdem_error *err)
{
  for (int k = 0; k < K_COUNT; k++) at[k] = 0;
  for (;;) {
    const char *save = lx->p, *tok;
    const long save_line = lx->line;
    size_t len;
    if (!lexer_next(lx, &tok, &len))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: the file ends in the header "
                        "(no heights)", path, lx->line);
    if (!isalpha((unsigned char)tok[0]) || (len == 3 && !strncasecmp(tok, "nan", 3)) ||
        (len >= 3 && !strncasecmp(tok, "inf", 3))) {
      lx->p = save, lx->line = save_line; /* the first height */
      break;
    }
    int key = -1;
    for (int k = 0; k < K_COUNT; k++)
      if (strlen(ASC_KEYS[k]) == len && !strncasecmp(tok, ASC_KEYS[k], len)) key = k;
    if (key < 0) {
      const int dxdy = (len == 2 && (!strncasecmp(tok, "dx", 2) || !strncasecmp(tok, "dy", 2)));
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: unknown header key '%.*s'%s "
                        "(keys: " ASC_KEY_LIST ")", path, lx->line, (int)(len < 40 ? len : 40),
                        tok, dxdy ? ": cells that are not square (dx, dy) are not supported"
                                  : "");
    }
    if (at[key])
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: header key '%s' repeated (first "
                        "on line %ld)", path, lx->line, ASC_KEYS[key], at[key]);
    const char *v;
    size_t vlen;
    if (!lexer_next_on_line(lx, &v, &vlen) || !token_number(v, vlen, &val[key]))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: header key '%s' needs a finite "
                        "number", path, lx->line, ASC_KEYS[key]);
    const char *extra;
    size_t elen;
    if (lexer_next_on_line(lx, &extra, &elen))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: '%.*s' after the value of '%s' "
                        "(one key and one value per header line)", path, lx->line,
                        (int)(elen < 40 ? elen : 40), extra, ASC_KEYS[key]);
    at[key] = lx->line;
  }
  const long end = lx->line;
  for (int pair = 0; pair < 2; pair++) {
    const int corner = pair ? K_YLLCORNER : K_XLLCORNER, centre = corner + 1;
    if (at[corner] && at[centre])
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: both '%s' and '%s': give one",
                        path, at[centre] > at[corner] ? at[centre] : at[corner],
                        ASC_KEYS[corner], ASC_KEYS[centre]);
    if (!at[corner] && !at[centre])
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: missing header key '%s' or '%s' (the "
                        "header ends before line %ld)", path, ASC_KEYS[corner],
                        ASC_KEYS[centre], end);
  }
  static const int required[3] = {K_NCOLS, K_NROWS, K_CELLSIZE};
  for (int r = 0; r < 3; r++)
    if (!at[required[r]])
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: missing header key '%s' (the header ends "
                        "before line %ld)", path, ASC_KEYS[required[r]], end);
  for (int k = K_NCOLS; k <= K_NROWS; k++)
    if (val[k] < 1 || val[k] != floor(val[k]) || val[k] > 2147483647.0)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: '%s' %g is not a positive "
                        "integer", path, at[k], ASC_KEYS[k], val[k]);
  if (!(val[K_CELLSIZE] > 0.0))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: 'cellsize' %g is not > 0", path,
                      at[K_CELLSIZE], val[K_CELLSIZE]);
  return LSDEM_OK;
}

/* The heights: file rows north to south, so value v goes to row ny - 1 - v / nx. */
static lsdem_status read_asc_values(text_lexer *lx, lsdem_heightmap *hm, int has_nodata,
                                    double nodata, const char *path, lsdem_error *err)
{
  const size_t nx = (size_t)hm->nx, total = nx * (size_t)hm->ny;
  const char *tok;
  size_t len, count = 0;
  long last = lx->line; /* the line of the last value */
  while (lexer_next(lx, &tok, &len)) {
    double v;
    last = lx->line;
    if (count == total)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: more than the ncols x nrows = "
                        "%d x %d = %zu values", path, lx->line, hm->nx, hm->ny, total);
    if (!token_double(tok, len, &v))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: '%.*s' is not a number", path,
                        lx->line, (int)(len < 40 ? len : 40), tok);
    if (!isfinite(v))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: value '%.*s' is not finite (mark "
                        "missing heights with NODATA_value)", path, lx->line,
                        (int)(len < 40 ? len : 40), tok);
    float z = (float)v;
    if (has_nodata && v == nodata) z = NAN;
    else if (!isfinite(z))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: value %g is beyond the float "
                        "range", path, lx->line, v);
    const size_t row = count / nx, col = count % nx;
    hm->z[((size_t)hm->ny - 1 - row) * nx + col] = z;
    count++;
  }
  if (count < total)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: line %ld: the file ends after %zu of the "
                      "ncols x nrows = %d x %d = %zu values", path, last, count, hm->nx,
                      hm->ny, total);
  return LSDEM_OK;
}

lsdem_status lsdem_heightmap_read_asc(const char *path, lsdem_heightmap *hm, lsdem_error *err)
{
  if (!path || !hm) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  memset(hm, 0, sizeof *hm);
  unsigned char *text = NULL;
  size_t size = 0;
  lsdem_status st = lsdem_read_file(path, ASC_MAX_FILE_BYTES, &text, &size, err);
  if (st != LSDEM_OK) return st;
  if (memchr(text, '\0', size))
    st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: binary bytes in an ASCII grid", path);
  text_lexer lx = {(const char *)text, 1};
  double val[K_COUNT] = {0};
  long at[K_COUNT];
  if (st == LSDEM_OK) st = read_asc_header(&lx, val, at, path, err);
  if (st == LSDEM_OK) st = alloc_heights(hm, (long)val[K_NCOLS], (long)val[K_NROWS], path, err);
  if (st == LSDEM_OK) st = read_asc_values(&lx, hm, at[K_NODATA] != 0, val[K_NODATA], path, err);
  if (st == LSDEM_OK) st = check_some_data(hm, path, err);
  if (st == LSDEM_OK) {
    const double c = val[K_CELLSIZE];
    hm->cell = c;
    hm->x0 = at[K_XLLCORNER] ? val[K_XLLCORNER] + 0.5 * c : val[K_XLLCENTER];
    hm->y0 = at[K_YLLCORNER] ? val[K_YLLCORNER] + 0.5 * c : val[K_YLLCENTER];
  }
  free(text);
  if (st != LSDEM_OK) lsdem_heightmap_free(hm);
  return st;
}

/* ------------------------------------------------------------ GeoTIFF, PNG ---- */

/* Sample i of a decoded TIFF page as a double. */
static double volume_sample(const lsdem_volume *v, size_t i)
{
  const unsigned char *s = (const unsigned char *)v->data + i * (size_t)v->bytes;
  if (v->kind == LSDEM_SAMPLE_FLOAT) {
    if (v->bytes == 8) { double d; memcpy(&d, s, 8); return d; }
    float f;
    memcpy(&f, s, 4);
    return f;
  }
  const int sgn = v->kind == LSDEM_SAMPLE_INT;
  switch (v->bytes) {
  case 1: return sgn ? (double)*(const int8_t *)s : (double)*s;
  case 2: { uint16_t u; memcpy(&u, s, 2); return sgn ? (double)(int16_t)u : (double)u; }
  default: { uint32_t u; memcpy(&u, s, 4); return sgn ? (double)(int32_t)u : (double)u; }
  }
}

/* Pixel centres from the georeferencing, or (cell given) the south-west one at 0, 0. */
static lsdem_status tiff_placement(const lsdem_tiff_georef *g, double cell, int ny,
                                   lsdem_heightmap *hm, const char *path, lsdem_error *err)
{
  if (!g->has_scale) {
    if (g->has_transform)
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: placed by a ModelTransformationTag "
                        "(34264: a rotated or sheared raster), not supported: give a raster "
                        "with ModelPixelScaleTag and ModelTiepointTag", path);
    if (!(cell > 0.0) || !isfinite(cell))
      return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: no ModelPixelScaleTag (33550): the pixel "
                        "size is not in the file; give it (--cell)", path);
    hm->cell = cell, hm->x0 = 0.0, hm->y0 = 0.0;
    return LSDEM_OK;
  }
  if (cell > 0.0)
    return lsdem_fail(err, LSDEM_ERR_ARG, "%s: the file gives its pixel size (ModelPixelScaleTag "
                      "%g x %g): no cell size to give", path, g->scale[0], g->scale[1]);
  const double sx = g->scale[0], sy = g->scale[1];
  if (!(sx > 0.0) || !(sy > 0.0) || !isfinite(sx) || !isfinite(sy) ||
      fabs(sx - sy) > 1e-9 * sx)
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: pixels of %g x %g (ModelPixelScaleTag): "
                      "square pixels > 0 are needed", path, sx, sy);
  const double *t = g->tiepoint; /* raster (I, J) at model (X, Y); raster rows go south */
  const double off = g->pixel_is_point ? 0.0 : 0.5;
  hm->cell = sx;
  hm->x0 = t[3] + (off - t[0]) * sx;
  hm->y0 = t[4] - ((double)(ny - 1) + off - t[1]) * sx;
  if (!isfinite(hm->x0) || !isfinite(hm->y0))
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: ModelTiepointTag is not finite", path);
  return LSDEM_OK;
}

lsdem_status lsdem_heightmap_read_tiff(const char *path, double cell, lsdem_heightmap *hm,
                                       lsdem_error *err)
{
  if (!path || !hm) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  memset(hm, 0, sizeof *hm);
  lsdem_volume v;
  lsdem_status st = lsdem_tiff_read_volume(path, &v, err);
  if (st != LSDEM_OK) return st;
  lsdem_tiff_georef g;
  if (v.n[2] != 1)
    st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: %d pages or planes: a height map has one", path,
                    v.n[2]);
  if (st == LSDEM_OK) st = lsdem_tiff_read_georef(path, &g, err);
  if (st == LSDEM_OK) st = alloc_heights(hm, v.n[0], v.n[1], path, err);
  if (st == LSDEM_OK) st = tiff_placement(&g, cell, v.n[1], hm, path, err);
  for (int r = 0; st == LSDEM_OK && r < v.n[1]; r++) /* raster row r: map row ny-1-r */
    for (int i = 0; i < v.n[0]; i++) {
      const double s = volume_sample(&v, (size_t)r * v.n[0] + i);
      const int nodata = isnan(s) || (g.has_nodata && s == g.nodata);
      const float z = nodata ? NAN : (float)s;
      if (!nodata && !isfinite(z)) {
        st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: pixel (%d, %d) is %g: not a finite height",
                        path, i, r, s);
        break;
      }
      hm->z[(size_t)(v.n[1] - 1 - r) * v.n[0] + i] = z;
    }
  if (st == LSDEM_OK) st = check_some_data(hm, path, err);
  lsdem_volume_free(&v);
  if (st != LSDEM_OK) lsdem_heightmap_free(hm);
  return st;
}

lsdem_status lsdem_heightmap_read_png(const char *path, double cell, double zscale,
                                      lsdem_heightmap *hm, lsdem_error *err)
{
  if (!path || !hm) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  memset(hm, 0, sizeof *hm);
  if (!(cell > 0.0) || !isfinite(cell) || !(zscale > 0.0) || !isfinite(zscale))
    return lsdem_fail(err, LSDEM_ERR_ARG, "%s: a PNG height map needs a cell size > 0 "
                      "(--cell, %g) and a height scale > 0 (--zscale, %g)", path, cell, zscale);
  int w, h, bits;
  uint16_t *values;
  lsdem_status st = lsdem_png_read_grey(path, &w, &h, &bits, &values, err);
  if (st != LSDEM_OK) return st;
  st = alloc_heights(hm, w, h, path, err);
  for (int r = 0; st == LSDEM_OK && r < h; r++)
    for (int i = 0; i < w; i++)
      hm->z[(size_t)(h - 1 - r) * w + i] = (float)(values[(size_t)r * w + i] * zscale);
  free(values);
  if (st != LSDEM_OK) return st;
  hm->cell = cell, hm->x0 = 0.0, hm->y0 = 0.0;
  return LSDEM_OK;
}

lsdem_status lsdem_heightmap_read(const char *path, double cell, double zscale,
                                  lsdem_heightmap *hm, lsdem_error *err)
{
  if (!path || !hm) return lsdem_fail(err, LSDEM_ERR_ARG, "NULL argument");
  memset(hm, 0, sizeof *hm);
  if (lsdem_path_has_extension(path, ".png"))
    return lsdem_heightmap_read_png(path, cell, zscale, hm, err);
  if (!(zscale > 0.0) || !isfinite(zscale))
    return lsdem_fail(err, LSDEM_ERR_ARG, "%s: height scale %g is not > 0", path, zscale);
  lsdem_status st;
  if (lsdem_path_has_extension(path, ".asc")) {
    if (cell > 0.0)
      return lsdem_fail(err, LSDEM_ERR_ARG, "%s: an ASCII grid gives its cell size "
                        "(cellsize): no cell size to give", path);
    st = lsdem_heightmap_read_asc(path, hm, err);
  } else if (lsdem_path_has_extension(path, ".tif") || lsdem_path_has_extension(path, ".tiff")) {
    st = lsdem_heightmap_read_tiff(path, cell, hm, err);
  } else {
    return lsdem_fail(err, LSDEM_ERR_ARG, "%s: unknown height-map format: the name must end "
                      "in .asc (ESRI ASCII grid), .tif or .tiff (GeoTIFF) or .png", path);
  }
  if (st == LSDEM_OK && zscale != 1.0) {
    const size_t n = (size_t)hm->nx * hm->ny;
    for (size_t i = 0; i < n; i++) hm->z[i] = (float)(hm->z[i] * zscale);
  }
  return st;
}

/* ------------------------------------------------------------ terrain mesh ---- */

/* Cell c (its south-west height's index) has four heights. */
static int cell_complete(const lsdem_heightmap *hm, size_t c)
{
  const size_t nx = (size_t)hm->nx;
  return !isnan(hm->z[c]) && !isnan(hm->z[c + 1]) && !isnan(hm->z[c + nx]) &&
         !isnan(hm->z[c + nx + 1]);
}

lsdem_status lsdem_heightmap_mesh(const lsdem_heightmap *hm, lsdem_mesh *m, lsdem_error *err)
{
  if (!hm || !m || !hm->z) return lsdem_fail(err, LSDEM_ERR_ARG, "height map: NULL argument");
  memset(m, 0, sizeof *m);
  const int nx = hm->nx, ny = hm->ny;
  if (nx < 2 || ny < 2)
    return lsdem_fail(err, LSDEM_ERR_ARG, "height map: %d x %d heights: a surface needs at "
                      "least 2 x 2", nx, ny);
  if (!(hm->cell > 0.0) || !isfinite(hm->cell) || !isfinite(hm->x0) || !isfinite(hm->y0))
    return lsdem_fail(err, LSDEM_ERR_ARG, "height map: cell size %g (> 0) or origin (%g, %g) "
                      "not finite", hm->cell, hm->x0, hm->y0);
  const size_t nv = (size_t)nx * ny;
  const double cells = (double)(nx - 1) * (ny - 1);
  int *id = malloc(nv * sizeof(int)); /* vertex number of each height, -1: unused */
  if (!id) return lsdem_fail(err, LSDEM_ERR_NOMEM, "height map: out of memory");
  for (size_t v = 0; v < nv; v++) id[v] = -1;
  long kept = 0;
  for (int j = 0; j + 1 < ny; j++)
    for (int i = 0; i + 1 < nx; i++) {
      const size_t c = (size_t)j * nx + i;
      if (!cell_complete(hm, c)) continue;
      id[c] = id[c + 1] = id[c + nx] = id[c + nx + 1] = 0;
      kept++;
    }
  lsdem_status st = LSDEM_OK;
  if (kept == 0)
    st = lsdem_fail(err, LSDEM_ERR_ARG, "height map: no cell has four heights (every cell "
                    "touches nodata): no surface");
  else if (2.0 * kept > LSDEM_MESH_MAX_TRIS)
    st = lsdem_fail(err, LSDEM_ERR_ARG, "height map: %ld cells make %ld triangles, above the "
                    "limit %d (of %.0f cells): resample it coarser", kept, 2 * kept,
                    LSDEM_MESH_MAX_TRIS, cells);
  int nverts = 0;
  for (size_t v = 0; st == LSDEM_OK && v < nv; v++)
    if (id[v] == 0) id[v] = nverts++;
  if (st == LSDEM_OK) {
    m->verts = malloc(3 * (size_t)nverts * sizeof(double));
    m->tris = malloc(6 * (size_t)kept * sizeof(int));
    if (!m->verts || !m->tris)
      st = lsdem_fail(err, LSDEM_ERR_NOMEM, "height map: cannot allocate %ld triangles", 2 * kept);
  }
  if (st == LSDEM_OK) {
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++) {
        const int v = id[(size_t)j * nx + i];
        if (v < 0) continue;
        m->verts[3 * v] = hm->x0 + hm->cell * i;
        m->verts[3 * v + 1] = hm->y0 + hm->cell * j;
        m->verts[3 * v + 2] = hm->z[(size_t)j * nx + i];
      }
    int t = 0;
    for (int j = 0; j + 1 < ny; j++)
      for (int i = 0; i + 1 < nx; i++) {
        const size_t c = (size_t)j * nx + i;
        if (!cell_complete(hm, c)) continue;
        const int a = id[c], b = id[c + 1], d = id[c + nx], e = id[c + nx + 1];
        int *o = m->tris + 3 * t;
        o[0] = a, o[1] = b, o[2] = e; /* (i,j), (i+1,j), (i+1,j+1) */
        o[3] = a, o[4] = e, o[5] = d; /* (i,j), (i+1,j+1), (i,j+1) */
        t += 2;
      }
    m->nverts = nverts, m->ntris = t;
  }
  free(id);
  if (st != LSDEM_OK) lsdem_mesh_free(m);
  return st;
}
