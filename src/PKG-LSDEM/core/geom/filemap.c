/* filemap.c -- read-only mapping of a whole file (filemap.h). */
#include "filemap.h"

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

lsdem_status lsdem_map_file(const char *path, const char *what, size_t min_size, void **map,
                            size_t *size, lsdem_error *err)
{
  *map = NULL;
  *size = 0;
  const int fd = open(path, O_RDONLY);
  if (fd < 0)
    return lsdem_fail(err, LSDEM_ERR_IO, "%s '%s': cannot open: %s", what, path,
                      strerror(errno));
  struct stat sb;
  if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
    close(fd);
    return lsdem_fail(err, LSDEM_ERR_IO, "%s '%s': not a regular file", what, path);
  }
  const size_t n = (size_t)sb.st_size;
  if (n < min_size) {
    close(fd);
    return lsdem_fail(err, LSDEM_ERR_FORMAT, "%s '%s': %zu bytes, too short for the %zu-byte "
                      "header", what, path, n, min_size);
  }
  void *m = mmap(NULL, n, PROT_READ, MAP_SHARED, fd, 0);
  close(fd);
  if (m == MAP_FAILED)
    return lsdem_fail(err, LSDEM_ERR_IO, "%s '%s': cannot map: %s", what, path,
                      strerror(errno));
  *map = m;
  *size = n;
  return LSDEM_OK;
}

void lsdem_unmap_file(void *map, size_t size)
{
  if (map) munmap(map, size);
}
