/* replace_file.h -- writing a file under a temporary name renamed onto its path at the
 * end (replace_file.c), for the mapped formats (shape libraries, band files): processes
 * that have the old file mapped keep a consistent copy, and a failed write leaves no
 * file behind. Private to core/prep. */
#ifndef LSDEM_PREP_REPLACE_FILE_H
#define LSDEM_PREP_REPLACE_FILE_H

#include "lsdem_prep.h"

#include <stdio.h>

typedef struct {
  const char *path, *what; /* what: the file kind in messages ("shape library") */
  char *tmp;
  FILE *f;
} replace_file;

/* Opens the temporary file. A path that exists as anything but a regular file (a device,
 * a pipe, a folder: the rename would replace it) is refused with LSDEM_ERR_IO. */
lsdem_status replace_file_open(replace_file *r, const char *path, const char *what,
                               lsdem_error *err);
/* Closes the temporary file and renames it onto the path when ok (every write went
 * through), else removes it; LSDEM_ERR_IO naming the path when anything failed. */
lsdem_status replace_file_close(replace_file *r, int ok, lsdem_error *err);

#endif /* LSDEM_PREP_REPLACE_FILE_H */
