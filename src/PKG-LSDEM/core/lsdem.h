/* lsdem.h -- the whole LSDEM core API in one include: the kernel (lsdem_kernel.h) and
 * preparation and file I/O (prep/lsdem_prep.h, io/lsdem_io.h). Level-set grains as plain C11.
 *
 * No LAMMPS and no MPI in here. Memory is owned by the caller unless a function says
 * it allocates (then a matching *_free exists). Errors come back as an lsdem_status
 * with a message in a caller-supplied lsdem_error (which may be NULL); the core never
 * calls exit() or abort().
 *
 * Conventions used throughout:
 *   - Quaternions are scalar-first (w, x, y, z), unit length, and rotate body (principal)
 *     frame vectors into the world frame: v_world = R(q) v_body.
 *   - Matrices are 3x3 row-major double[9].
 *   - A level set phi is a signed distance: negative inside the solid, positive outside,
 *     in the same length unit as positions. Gradients point outward.
 *   - A grain shape lives in its principal frame: centroid at the origin, inertia
 *     tensor diagonal. Inertia values are per unit density (volume-weighted), so
 *     mass = density * volume and I = density * inertia.
 */
#ifndef LSDEM_H
#define LSDEM_H

#include "lsdem_kernel.h"
#include "prep/lsdem_prep.h"
#include "io/lsdem_io.h"

#endif /* LSDEM_H */
