/* fileio.c -- reading a whole file into memory, shared by the binary and text readers
 * (TIFF images, STL/OBJ meshes, ASCII grids), and file names' extensions. */
#define _POSIX_C_SOURCE 200809L /* fileno, fstat */
#include "lsdem_io.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

lsdem_status lsdem_read_file(const char *path, size_t max_bytes, unsigned char **data,
                             size_t *size, lsdem_error *err)
{
  *data = NULL;
  *size = 0;
  FILE *f = fopen(path, "rb");
  if (!f) return lsdem_fail(err, LSDEM_ERR_IO, "%s: cannot open", path);
  struct stat sb;
  if (fstat(fileno(f), &sb) == 0 && !S_ISREG(sb.st_mode)) {
    fclose(f);
    return lsdem_fail(err, LSDEM_ERR_IO, "%s: not a regular file (a folder?)", path);
  }
  long long n = -1;
  if (fseek(f, 0, SEEK_END) == 0) n = ftell(f);
  lsdem_status st = LSDEM_OK;
  if (n < 0 || fseek(f, 0, SEEK_SET) != 0)
    st = lsdem_fail(err, LSDEM_ERR_IO, "%s: cannot find the file size", path);
  else if ((unsigned long long)n > max_bytes)
    st = lsdem_fail(err, LSDEM_ERR_FORMAT, "%s: %lld bytes: larger than the %zu this reader "
                    "accepts", path, n, max_bytes);
  unsigned char *buf = st == LSDEM_OK ? malloc((size_t)n + 1) : NULL;
  if (st == LSDEM_OK && !buf) st = lsdem_fail(err, LSDEM_ERR_NOMEM, "%s: out of memory", path);
  if (st == LSDEM_OK && fread(buf, 1, (size_t)n, f) != (size_t)n)
    st = lsdem_fail(err, LSDEM_ERR_IO, "%s: read failed", path);
  fclose(f);
  if (st != LSDEM_OK) {
    free(buf);
    return st;
  }
  buf[n] = '\0'; /* text parsers may rely on a terminator */
  *data = buf;
  *size = (size_t)n;
  return LSDEM_OK;
}

int lsdem_path_has_extension(const char *path, const char *ext)
{
  const size_t n = strlen(path), e = strlen(ext);
  return n >= e && strcasecmp(path + n - e, ext) == 0;
}
