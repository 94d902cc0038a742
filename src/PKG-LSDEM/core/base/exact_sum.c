/* exact_sum.c -- order-free sums: terms rounded to a power-of-two quantum (lsdem_base.h). */
#include "lsdem_base.h"

#include <math.h>

lsdem_quantum lsdem_quantum_for(double scale)
{
  lsdem_quantum qt = {0.0, 0.0};
  if (!(scale > 0.0) || !isfinite(scale)) return qt;
  const int e = ilogb(scale) + 1 - LSDEM_EXACT_SUM_BITS; /* 2^(e + 40) > scale */
  qt.q = ldexp(1.0, e);
  qt.inv_q = ldexp(1.0, -e);
  return qt;
}
