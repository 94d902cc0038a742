/* filemap.h -- read-only memory mapping of a whole file, for the kernel's file readers
 * (shape libraries, band files): ranks on one machine share the pages through the page
 * cache. Private to core/geom. */
#ifndef LSDEM_GEOM_FILEMAP_H
#define LSDEM_GEOM_FILEMAP_H

#include "../base/lsdem_base.h"

/* Maps regular file `path` (at least min_size bytes) into *map, *size bytes; `what`
 * names the file kind in messages ("shape library"). LSDEM_ERR_IO when it cannot be
 * opened or mapped, LSDEM_ERR_FORMAT when it is shorter than min_size. */
lsdem_status lsdem_map_file(const char *path, const char *what, size_t min_size, void **map,
                            size_t *size, lsdem_error *err);
void lsdem_unmap_file(void *map, size_t size);

#endif /* LSDEM_GEOM_FILEMAP_H */
