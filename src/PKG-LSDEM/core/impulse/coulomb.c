/* coulomb.c -- the impulse of one ETM increment with Coulomb friction (report eqs
 * 4.14-4.20, Algorithm 3 lines 11-14 and 27-30). World frame. The rule is in
 * lsdem_impulse.h (lsdem_coulomb_impulse). */
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

int lsdem_coulomb_impulse(const double K[9], const double n[3], const double u[3],
                          double du_n, double mu, double slip_share, double P[3])
{
  double Kn[3], w[3], t[3], Kt[3];
  lsdem_mat_vec(K, n, Kn);
  const double knn = lsdem_dot3(n, Kn), un = lsdem_dot3(u, n);
  /* w: the slip a frictionless increment would leave (u_t plus what its normal impulse
   * drives sideways through K) -- friction opposes that */
  for (int i = 0; i < 3; i++) w[i] = u[i] - un * n[i] + (Kn[i] - knn * n[i]) * du_n / knn;
  const double slip = sqrt(lsdem_dot3(w, w));
  if (mu == 0.0 || !(slip > 0.0)) return frictionless(K, n, du_n, P);
  for (int i = 0; i < 3; i++) t[i] = -w[i] / slip;

  /* stick: eq 4.14 in the plane of n and t -- normal change du_n, and the fraction
   * slip_share of that slip removed */
  lsdem_mat_vec(K, t, Kt);
  const double knt = lsdem_dot3(n, Kt), ktt = lsdem_dot3(t, Kt);
  const double rhs_t = knt * du_n / knn + slip_share * slip;
  const double det = knn * ktt - knt * knt;
  const double pn = (ktt * du_n - knt * rhs_t) / det, pt = (knn * rhs_t - knt * du_n) / det;
  if (pn > 0.0 && pt <= mu * pn) {
    for (int i = 0; i < 3; i++) P[i] = pn * n[i] + pt * t[i];
    return 0;
  }
  /* slide: |P_t| = mu |P_n| against the slip (eqs 4.18-4.20) */
  const double denom = knn + mu * knt;                    /* n . K (n + mu t) */
  if (!(denom > 0.0)) return frictionless(K, n, du_n, P); /* friction would attract */
  const double pn_slide = du_n / denom;
  for (int i = 0; i < 3; i++) P[i] = pn_slide * (n[i] + mu * t[i]); /* eq 4.19 */
  return 1;
}
