/* chains.c -- strong and weak force networks (lsdem_specimen.h). */
#include "lsdem_specimen.h"

void lsdem_strong_chains(int n, const double *fn, lsdem_chain_stats *out)
{
  double total = 0.0, strong_total = 0.0;
  for (int k = 0; k < n; k++) total += fn[k];
  out->contacts = n;
  out->mean = n > 0 ? total / n : 0.0;
  out->strong = 0;
  for (int k = 0; k < n; k++)
    if (fn[k] > out->mean) {
      out->strong++;
      strong_total += fn[k];
    }
  out->strong_fraction = n > 0 ? (double)out->strong / n : 0.0;
  out->strong_share = total != 0.0 ? strong_total / total : 0.0;
}
