/* coulomb.c -- the impulse of one ETM increment with Coulomb friction (report eqs
 * 4.14-4.20, Algorithm 3 lines 11-14 and 27-30). World frame. */
#include "lsdem_impulse.h"

#include <math.h>

/* P = du_n / (n . K n) n: the normal impulse raising u_n by du_n (eq 4.29). */
static int frictionless(const double K[9], const double n[3], double du_n, double P[3])
{
  double Kn[3];
  lsdem_mat_vec(K, n, Kn);
  const double pn = du_n / lsdem_dot3(n, Kn);
  for (int i = 0; i < 3; i++) P[i] = pn * n[i];
  return 1;
}

int lsdem_coulomb_impulse(const double K[9], const double Kinv[9], const double n[3],
                          const double u[3], double du_n, double mu, double P[3])
{
  if (mu == 0.0) return frictionless(K, n, du_n, P);
  const double un = lsdem_dot3(u, n);
  double ut[3], target[3], Pt[3];
  for (int i = 0; i < 3; i++) {
    ut[i] = u[i] - un * n[i];
    target[i] = du_n * n[i] - ut[i]; /* normal change du_n, slip removed */
  }
  lsdem_mat_vec(Kinv, target, P); /* eq 4.14 */
  const double pn = lsdem_dot3(P, n);
  for (int i = 0; i < 3; i++) Pt[i] = P[i] - pn * n[i]; /* eqs 4.16-4.17 */
  const double pt = sqrt(lsdem_dot3(Pt, Pt));
  if (pn > 0.0 && pt <= mu * pn) return 0; /* sticks */

  /* slides: t against the slip, or without slip along the stick impulse's tangential
   * part (pt > 0 then, K being positive definite) */
  const double slip = sqrt(lsdem_dot3(ut, ut));
  double dir[3], Kdir[3];
  for (int i = 0; i < 3; i++) {
    const double t = slip > 0.0 ? -ut[i] / slip : Pt[i] / pt;
    dir[i] = n[i] + mu * t;
  }
  lsdem_mat_vec(K, dir, Kdir);
  const double denom = lsdem_dot3(n, Kdir);               /* eq 4.20 */
  if (!(denom > 0.0)) return frictionless(K, n, du_n, P); /* friction would attract */
  const double pn_slide = du_n / denom;
  for (int i = 0; i < 3; i++) P[i] = pn_slide * dir[i]; /* eq 4.19 */
  return 1;
}
