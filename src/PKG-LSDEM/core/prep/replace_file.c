/* replace_file.c -- a file written under a temporary name and renamed onto its path
 * (replace_file.h). */
#define _POSIX_C_SOURCE 200809L
#include "replace_file.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

lsdem_status replace_file_open(replace_file *r, const char *path, const char *what,
                               lsdem_error *err)
{
  memset(r, 0, sizeof *r);
  r->path = path, r->what = what;
  /* The new file is renamed onto path: a device, pipe or folder there would be replaced. */
  struct stat sb;
  if (stat(path, &sb) == 0 && !S_ISREG(sb.st_mode))
    return lsdem_fail(err, LSDEM_ERR_IO, "%s '%s': exists and is not a regular file (a "
                      "device, pipe, socket or folder, which writing the %s would replace); "
                      "give the path of a file", what, path, what);
  r->tmp = (char *)malloc(strlen(path) + 32);
  if (!r->tmp) return lsdem_fail(err, LSDEM_ERR_NOMEM, "%s '%s': out of memory", what, path);
  sprintf(r->tmp, "%s.tmp%ld", path, (long)getpid());
  r->f = fopen(r->tmp, "wb");
  if (!r->f) {
    const lsdem_status st = lsdem_fail(err, LSDEM_ERR_IO, "%s '%s': cannot write: %s", what,
                                       path, strerror(errno));
    free(r->tmp);
    r->tmp = NULL;
    return st;
  }
  return LSDEM_OK;
}

lsdem_status replace_file_close(replace_file *r, int ok, lsdem_error *err)
{
  if (r->f && fclose(r->f) != 0) ok = 0;
  r->f = NULL;
  if (ok && rename(r->tmp, r->path) != 0) ok = 0;
  lsdem_status st = LSDEM_OK;
  if (!ok) {
    st = lsdem_fail(err, LSDEM_ERR_IO, "%s '%s': cannot write: %s", r->what, r->path,
                    strerror(errno));
    remove(r->tmp);
  }
  free(r->tmp);
  r->tmp = NULL;
  return st;
}
