/* lsdem_kernel.h -- what a simulation needs of the LSDEM core (the library lsdem_kernel,
 * all that lmp links): base, geometry, contact, dynamics, boundaries (walls), impulse mode,
 * specimen. No image codecs, meshes import, packing, random grains or pictures: those are
 * in lsdem.h (lsdem_prep).
 * Conventions in lsdem.h. */
#ifndef LSDEM_KERNEL_H
#define LSDEM_KERNEL_H

#include "base/lsdem_base.h"
#include "geom/lsdem_geom.h"
#include "contact/lsdem_contact.h"
#include "dynamics/lsdem_dynamics.h"
#include "boundary/lsdem_boundary.h"
#include "impulse/lsdem_impulse.h"
#include "specimen/lsdem_specimen.h"

#endif /* LSDEM_KERNEL_H */
