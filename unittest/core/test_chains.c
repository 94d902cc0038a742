/* test_chains.c -- strong and weak force networks (lsdem_strong_chains). */
#include "lsdem_test.h"

int main(void)
{
  lsdem_chain_stats s;
  /* mean 3: only 6 is above it (3 equals the mean: weak) */
  const double fn[4] = {1.0, 2.0, 3.0, 6.0};
  lsdem_strong_chains(4, fn, &s);
  CHECK(s.contacts == 4 && s.strong == 1, "%d contacts, %d strong", s.contacts, s.strong);
  CHECK_NEAR(s.mean, 3.0, 0.0);
  CHECK_NEAR(s.strong_fraction, 0.25, 0.0);
  CHECK_NEAR(s.strong_share, 0.5, 0.0);
  /* all equal: none strong */
  const double flat[3] = {2.0, 2.0, 2.0};
  lsdem_strong_chains(3, flat, &s);
  CHECK(s.strong == 0 && s.strong_share == 0.0, "%d strong, share %g", s.strong, s.strong_share);
  /* no contacts */
  lsdem_strong_chains(0, NULL, &s);
  CHECK(s.contacts == 0 && s.mean == 0.0 && s.strong_fraction == 0.0 && s.strong_share == 0.0,
        "empty network");
  return lsdem_test_summary();
}
