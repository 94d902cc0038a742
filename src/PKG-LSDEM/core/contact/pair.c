/* pair.c -- one pair end to end: detection into a manifold, then the penalty law, with the
 * pair's node list and shear history carried from the last step to this one. */
#include "lsdem_contact.h"

#include <stddef.h>

int lsdem_contact_penalty(const lsdem_shape *A, const lsdem_pose *pa, const lsdem_shape *B,
                          const lsdem_pose *pb, const lsdem_contact_params *prm,
                          int64_t step, const lsdem_pair_state *in, lsdem_pair_state *out,
                          lsdem_manifold *m, lsdem_contact_result *res)
{
  lsdem_detect(A, pa, B, pb, &prm->detect, step, in ? &in->list : NULL,
               out ? &out->list : NULL, m);
  int nshear = 0;
  lsdem_penalty_apply(m, &prm->law, prm->dt, step, in ? in->shear : NULL, in ? in->nshear : 0,
                      out ? out->shear : NULL, &nshear, res);
  if (out) out->nshear = nshear;
  return res->npen;
}
