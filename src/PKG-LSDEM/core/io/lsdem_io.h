/* lsdem_io.h -- files in and out (not linked into lmp): reading whole files, label images
 * and grey-level volumes (raw; TIFF through libtiff), height maps (ESRI ASCII grids,
 * GeoTIFF, grey PNG), surface meshes as VTK/PLY, pictures of grains (ray-marched, PNG
 * through libpng). */
#ifndef LSDEM_IO_H
#define LSDEM_IO_H

#include "../geom/lsdem_geom.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ files ---- */

/* Read a whole file (at most max_bytes) into a new buffer, NUL-terminated (not counted in
 * *size); free(*data) when done. */
lsdem_status lsdem_read_file(const char *path, size_t max_bytes, unsigned char **data,
                             size_t *size, lsdem_error *err);
/* 1 if path ends in ext (".stl"; compared ignoring case), else 0. */
int lsdem_path_has_extension(const char *path, const char *ext);

/* ------------------------------------------------------------ label images ---- */

/* A labelled 3-D image: one label per voxel, x fastest, then y, then z. Label <= 0 is
 * background. Voxel (i,j,k) has its centre at voxel_size * (i,j,k) in scan coordinates. */
typedef struct {
  int n[3];
  int32_t *label; /* n[0]*n[1]*n[2], allocated by the reader */
} lsdem_label_image;

typedef enum { LSDEM_VOXEL_U8 = 0, LSDEM_VOXEL_U16, LSDEM_VOXEL_U32, LSDEM_VOXEL_I32 } lsdem_voxel_type;

#define LSDEM_IMAGE_MAX_VOXELS 1073741824L /* 1024^3 voxels */
#define LSDEM_IMAGE_MAX_PAGES 65536        /* TIFF pages (z slices) */

/* Raw binary labels, no header: exactly n[0]*n[1]*n[2] values of `type`. The file size
 * must match (a mismatch is reported with both sizes); u32 values above INT32_MAX are
 * rejected. */
lsdem_status lsdem_image_read_raw(const char *path, const int n[3], lsdem_voxel_type type,
                                  int big_endian, lsdem_label_image *img, lsdem_error *err);
/* A TIFF label image (tiff.c, through libtiff): whatever lsdem_tiff_read_volume reads,
 * with integer samples (unsigned or signed, 8/16/32-bit; labels <= 0 are background).
 * Floating-point samples and u32 values above INT32_MAX are rejected naming them. */
lsdem_status lsdem_image_read_tiff(const char *path, lsdem_label_image *img, lsdem_error *err);
/* 1 if the file starts with a TIFF or BigTIFF signature ("II*\0", "MM\0*", "II+\0",
 * "MM\0+"), else 0. */
int lsdem_image_is_tiff(const char *path);
void lsdem_label_image_free(lsdem_label_image *img);

/* ----------------------------------------------------------- grey volumes ---- */

/* A 3-D image of samples as stored (a grey-level scan or labels), host byte order, x
 * fastest, then y, then z. */
typedef enum { LSDEM_SAMPLE_UINT = 0, LSDEM_SAMPLE_INT, LSDEM_SAMPLE_FLOAT } lsdem_sample_kind;
typedef struct {
  int n[3];
  lsdem_sample_kind kind;
  int bytes;  /* per sample: 1, 2, 4 (integers), 4 or 8 (floats) */
  void *data; /* n[0]*n[1]*n[2]*bytes, allocated by the reader */
} lsdem_volume;

/* Any TIFF that libtiff reads: every compression it is built with (LZW, Deflate,
 * PackBits, ...), strips or tiles, classic or BigTIFF, either byte order, 8/16/32-bit
 * integer or 32/64-bit float samples, one sample per pixel. Pages are z slices; a page
 * with ImageDepth > 1 (in tiles one plane deep) is a volume, and pages stack in z. All pages
 * must share width, length and sample type; at most LSDEM_IMAGE_MAX_PAGES pages and
 * LSDEM_IMAGE_MAX_VOXELS voxels. A damaged or unsupported file is rejected with the file,
 * the page and libtiff's or this reader's reason. */
lsdem_status lsdem_tiff_read_volume(const char *path, lsdem_volume *v, lsdem_error *err);
/* "u8", "u16", "u32", "i8", "i16", "i32", "f32" or "f64". */
const char *lsdem_volume_type_name(const lsdem_volume *v);
void lsdem_volume_free(lsdem_volume *v);

/* GeoTIFF georeferencing of a TIFF's first page (GeoTIFF 1.1: model space from raster
 * space). Tags absent from the file leave their has_* flag 0. */
typedef struct {
  int has_scale, has_tiepoint, has_transform, has_nodata;
  double scale[3];    /* ModelPixelScaleTag (33550): size of a pixel in x, y, z */
  double tiepoint[6]; /* ModelTiepointTag (33922), first point: raster I J K, model X Y Z */
  int pixel_is_point; /* GTRasterTypeGeoKey = RasterPixelIsPoint (else PixelIsArea) */
  double nodata;      /* GDAL_NODATA (42113), parsed from its text */
} lsdem_tiff_georef;
lsdem_status lsdem_tiff_read_georef(const char *path, lsdem_tiff_georef *g, lsdem_error *err);

/* --------------------------------------------- triangle meshes (mesh_read.c) ---- */

#define LSDEM_MESH_MAX_TRIS 16777216 /* triangles per mesh */

/* STL (ASCII or binary, detected from the content: a binary file's size is
 * 84 + 50 * count) or Wavefront OBJ (v and f lines; polygons fan-triangulated,
 * negative indices relative). The format comes from the extension (.stl / .obj, any
 * case), otherwise from the content. Errors name the file and the line or triangle. */
lsdem_status lsdem_mesh_read(const char *path, lsdem_mesh *m, lsdem_error *err);

/* ------------------------------------------------------------ height maps ---- */

/* A terrain's heights on a square raster: z[j nx + i] at (x0 + i cell, y0 + j cell), row
 * j = 0 first (the south edge: y grows northwards), NaN where there is no data. */
typedef struct {
  int nx, ny;
  double x0, y0, cell;
  float *z; /* nx*ny, allocated by the readers; lsdem_heightmap_free */
} lsdem_heightmap;

#define LSDEM_HEIGHTMAP_MAX_SAMPLES 268435456L /* 2^28 heights (1 GB of floats) */

/* ESRI ASCII grid (.asc): a header of "key value" lines -- ncols, nrows, xllcorner or
 * xllcenter, yllcorner or yllcenter, cellsize, optionally NODATA_value; keys in any order
 * and case -- then nrows x ncols numbers, rows north to south. A corner origin puts the
 * first height at the centre of the south-west cell (+cellsize/2). Values equal to
 * NODATA_value become NaN. LSDEM_ERR_FORMAT naming the file and the line for an unknown,
 * repeated or missing key, a bad header value, a token that is not a number, a NaN or
 * infinite value, too few or too many values, or a raster of only nodata. */
lsdem_status lsdem_heightmap_read_asc(const char *path, lsdem_heightmap *hm, lsdem_error *err);
/* A single-page, single-band TIFF (lsdem_tiff_read_volume: float or 8/16/32-bit integer
 * samples) with GeoTIFF georeferencing when present: ModelPixelScaleTag (square pixels)
 * and ModelTiepointTag place the pixel centres (PixelIsArea, or PixelIsPoint from the
 * GeoKeyDirectory); GDAL_NODATA and NaN samples are nodata. Rows top first (north).
 * cell > 0 gives the pixel size of a file without ModelPixelScaleTag (then the south-west
 * pixel's centre is at x = y = 0); it is refused for a file that has one. */
lsdem_status lsdem_heightmap_read_tiff(const char *path, double cell, lsdem_heightmap *hm,
                                       lsdem_error *err);
/* A grey PNG (8 or 16 bits, lsdem_png_read_grey), rows top first (north): z = value *
 * zscale at pixel centres (i cell, j cell), south-west pixel at the origin. */
lsdem_status lsdem_heightmap_read_png(const char *path, double cell, double zscale,
                                      lsdem_heightmap *hm, lsdem_error *err);
/* By the extension (any case): .asc, .tif/.tiff (cell as above), .png (cell, zscale);
 * zscale also multiplies the heights of the other formats. */
lsdem_status lsdem_heightmap_read(const char *path, double cell, double zscale,
                                  lsdem_heightmap *hm, lsdem_error *err);
void lsdem_heightmap_free(lsdem_heightmap *hm);
/* Grow the raster by `cells` on every side, each new height the nearest edge height (a
 * nodata edge stays nodata): the terrain continues flat beyond its edge, so that a band
 * made from it (whose box reaches width + h beyond the surface) has no cliff at the
 * raster's border. x0, y0 move out by cells * cell. */
lsdem_status lsdem_heightmap_pad(lsdem_heightmap *hm, int cells, lsdem_error *err);

/* The terrain surface as triangles: a vertex per height that a kept cell uses, two
 * triangles per cell with four heights ((i,j), (i+1,j), (i+1,j+1)) and ((i,j), (i+1,j+1),
 * (i,j+1)), counter-clockwise seen from above (normals up: the grains' side); cells with a
 * nodata corner are left out (holes). LSDEM_ERR_ARG for fewer than 2 x 2 heights, a bad
 * cell size, no complete cell, or more than LSDEM_MESH_MAX_TRIS triangles. Allocates m
 * (lsdem_mesh_free). */
lsdem_status lsdem_heightmap_mesh(const lsdem_heightmap *hm, lsdem_mesh *m, lsdem_error *err);

/* ----------------------------------------------------------- surface files ---- */

/* Legacy VTK polydata (ASCII) and PLY (ASCII). */
lsdem_status lsdem_mesh_write_vtk(const char *path, const lsdem_mesh *m, lsdem_error *err);
lsdem_status lsdem_mesh_write_ply(const char *path, const lsdem_mesh *m, lsdem_error *err);

/* ---------------------------------------------------------------- pictures ---- */

/* One posed grain of a picture. */
typedef struct {
  int shape;    /* index into the shapes array */
  int64_t id;   /* grain id: picks the colour */
  double x[3];  /* centroid, world */
  double q[4];  /* body -> world, unit length */
} lsdem_render_grain;

/* Orthographic camera looking along `view`; `up` is the world direction shown upwards
 * (projected; must not be parallel to view). Image right = view x up. pixel > 0 fixes
 * the frame: world point `centre` at the image centre, pixel = world length per pixel;
 * pixel <= 0 fits the grains' bounding spheres with a 5% margin (centre ignored). */
typedef struct {
  int width, height;
  double view[3], up[3];
  double centre[3], pixel;
  int colour_by_shape; /* 0: colour by a hash of the grain id, 1: by shape index */
} lsdem_render_view;

/* Value of all three channels of pixels that see no grain; grain pixels never have it. */
#define LSDEM_RENDER_BACKGROUND 255

/* Ray-march the grains' level sets (render.c): per pixel, bounding spheres from a
 * screen-space bin grid, then sphere tracing in each grain's frame, Lambert + ambient
 * shading with the level-set normal. rgb receives width*height*3 bytes, row 0 at the top.
 * Shapes must be bounded (finite radius). Deterministic. */
lsdem_status lsdem_render(const lsdem_shape *const *shapes, int nshapes,
                          const lsdem_render_grain *grains, int ngrains,
                          const lsdem_render_view *view, unsigned char *rgb, lsdem_error *err);
/* An 8-bit RGB PNG (rows top first), written by libpng (png.c). */
lsdem_status lsdem_png_write(const char *path, int width, int height, const unsigned char *rgb,
                             lsdem_error *err);
/* A grey PNG (1, 2, 4, 8 or 16 bits, any interlacing) read by libpng (png.c): *values
 * receives width*height samples, rows top first (free()), *bits 8 (also for 1, 2 and 4-bit
 * images, expanded) or 16. Colour, palette and alpha images are refused naming them. */
#define LSDEM_PNG_MAX_SIDE 65536
#define LSDEM_PNG_MAX_PIXELS 268435456L
lsdem_status lsdem_png_read_grey(const char *path, int *width, int *height, int *bits,
                                 uint16_t **values, lsdem_error *err);

#ifdef __cplusplus
}
#endif
#endif /* LSDEM_IO_H */
