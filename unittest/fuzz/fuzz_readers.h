/* fuzz_readers.h -- the shared reader harness of fuzz_readers.c (libFuzzer) and
 * mutate_readers.c (deterministic CTest mutation test). */
#ifndef LSDEM_FUZZ_READERS_H
#define LSDEM_FUZZ_READERS_H
#include "lsdem.h"

#include <stddef.h>
#include <stdint.h>

/* How many inputs each reader accepted (to show that mutations reach both outcomes). */
typedef struct {
  long morph_ok, rows_ok, library_open, library_shapes_ok;
  long image_ok, mesh_ok; /* TIFF or raw label images, STL/OBJ meshes accepted */
  long net_ok;            /* net files accepted */
} fuzz_tally;

/* Run every reader over `data`; returns the number of contract violations (a non-OK
 * status without message, an unknown status, output left allocated on failure).
 * Crashes and out-of-bounds accesses are the sanitizers' to report. t may be NULL. */
int lsdem_fuzz_readers(const uint8_t *data, size_t size, fuzz_tally *t);

/* Recompute a library's header/TOC checksum in place (FNV-1a 64 as doc/shape_library.rst
 * defines it), so an edited TOC gets past the checksum; no-op if the TOC does not fit. */
void lsdem_fuzz_reseal_library(unsigned char *b, size_t n);
#endif
