/* shape_image.c -- `lsdem-shape to-raw`: any TIFF that libtiff reads (a grey-level CT
 * stack or a label image: compressed, tiled, BigTIFF, ...) to a raw little-endian volume
 * that numpy, ImageJ or the segmentation step (tools/lsdem_segment.py) read without a
 * TIFF codec of their own. Prints "OUT: NX NY NZ TYPE". */
#include "lsdem.h"
#include "lsdem_shape_cmds.h"

#include <stdio.h>
#include <string.h>

int cmd_to_raw(int argc, char **argv)
{
  if (argc != 2) {
    fprintf(stderr, "usage: lsdem-shape to-raw IMAGE.tif OUT.raw\n");
    return 2;
  }
  lsdem_volume v;
  lsdem_error err;
  if (lsdem_tiff_read_volume(argv[0], &v, &err) != LSDEM_OK) {
    fprintf(stderr, "lsdem-shape: to-raw: %s\n", err.msg);
    return 1;
  }
  const unsigned probe = 1;
  const int little = *(const unsigned char *)&probe == 1;
  FILE *f = little ? fopen(argv[1], "wb") : NULL;
  const size_t count = (size_t)v.n[0] * v.n[1] * v.n[2];
  int rc = 0;
  if (!little) {
    fprintf(stderr, "lsdem-shape: to-raw: writes little-endian raw files on little-endian "
            "hosts only\n");
    rc = 1;
  } else if (!f || fwrite(v.data, (size_t)v.bytes, count, f) != count) {
    fprintf(stderr, "lsdem-shape: to-raw: %s: cannot write\n", argv[1]);
    rc = 1;
  }
  if (f && fclose(f) != 0 && !rc) {
    fprintf(stderr, "lsdem-shape: to-raw: %s: cannot write\n", argv[1]);
    rc = 1;
  }
  if (!rc) printf("%s: %d %d %d %s\n", argv[1], v.n[0], v.n[1], v.n[2], lsdem_volume_type_name(&v));
  lsdem_volume_free(&v);
  return rc;
}
