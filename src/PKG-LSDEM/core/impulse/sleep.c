/* sleep.c -- the sleep clock of sleeping islands (fix impulse/lsdem keyword sleep): how
 * long a grain has stayed slow. Which islands fall asleep, and which wake, is decided over
 * the islands' labels (lsdem_islands_build) by the caller, across ranks. */
#include "lsdem_impulse.h"

double lsdem_sleep_clock(double clock, const double v[3], const double omega[3],
                         double radius, double speed, double dt)
{
  const double s2 = speed * speed, r2 = radius * radius;
  const double v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  const double w2 = omega[0] * omega[0] + omega[1] * omega[1] + omega[2] * omega[2];
  /* NaN compares false: a grain with a NaN speed is never slow */
  return (v2 < s2 && w2 * r2 < s2) ? clock + dt : 0.0;
}
