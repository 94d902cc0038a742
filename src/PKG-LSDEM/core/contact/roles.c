/* roles.c -- master and slave of a pair: whose nodes are tested against whose level set
 * (report §2.2.5: the grain with the smaller index is master; here by default the grain
 * whose nodes resolve the partner), and with what weight. */
#include "lsdem_contact.h"

#include <math.h>

double lsdem_contact_node_scale(const lsdem_shape *s)
{
  return cbrt(s->volume) / sqrt(s->nnodes > 0 ? (double)s->nnodes : 1.0) * s->radius;
}

double lsdem_contact_roles(const lsdem_shape *a, double scale_a, int64_t id_a,
                           const lsdem_shape *b, double scale_b, int64_t id_b,
                           lsdem_roles_rule rule)
{
  if (id_a == id_b) return 0.0;
  const int sa = a->sdf.kind == LSDEM_SDF_SPHERE, sb = b->sdf.kind == LSDEM_SDF_SPHERE;
  if (sa != sb) return sa ? 1.0 : 0.0; /* the sphere: one lookup, no node loop */
  if (!sa && rule == LSDEM_ROLES_TWOWAY) return 0.5;
  if (!sa && rule == LSDEM_ROLES_ONEWAY) {
    /* the same shapes: equal scales, the id decides */
    if (scale_a != scale_b) return scale_a < scale_b ? 1.0 : 0.0;
  }
  return id_a < id_b ? 1.0 : 0.0;
}
