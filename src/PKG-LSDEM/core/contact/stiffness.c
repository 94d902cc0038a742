/* stiffness.c -- the stiffest contact a shape can form: how many node springs one flat
 * contact presses at once, for the time-step check of the integrator (dt against the
 * period of the stiffest contact, report §2.2.6's 0.1-0.2 sqrt(m/k) rule). */
#include "lsdem_contact.h"

#include <math.h>

/* direction k of n on a Fibonacci sphere (nearly even spacing, no pole clusters) */
static void fibonacci_direction(int k, int n, double u[3])
{
  const double golden = M_PI * (3.0 - sqrt(5.0));
  const double z = 1.0 - (2.0 * k + 1.0) / n, r = sqrt(1.0 - z * z);
  u[0] = r * cos(golden * k);
  u[1] = r * sin(golden * k);
  u[2] = z;
}

/* the nodes of s within depth of its extreme along u: their number, or their summed
 * tributary areas (traction) */
static double nodes_near_extreme(const lsdem_shape *s, const double u[3], double depth,
                                 int traction)
{
  double top = -HUGE_VAL;
  for (int k = 0; k < s->nnodes; k++) top = fmax(top, lsdem_dot3(u, s->nodes + 3 * k));
  double sum = 0.0;
  for (int k = 0; k < s->nnodes; k++)
    if (lsdem_dot3(u, s->nodes + 3 * k) >= top - depth)
      sum += traction ? s->node_area[k] : 1.0;
  return sum;
}

double lsdem_flat_contact_nodes(const lsdem_shape *s, lsdem_normal_law normal)
{
  const int traction = normal == LSDEM_NORMAL_TRACTION;
  if (s->sdf.kind == LSDEM_SDF_SPHERE) /* the sphere path: one point (lsdem_detect) */
    return traction ? lsdem_sphere_contact_area(s->sdf.a[0]) : 1.0;
  const double depth = LSDEM_FLAT_CONTACT_DEPTH * s->radius;
  double most = 0.0;
  for (int a = 0; a < 6; a++) { /* the principal axes: a box's faces */
    double u[3] = {0.0, 0.0, 0.0};
    u[a / 2] = (a % 2) ? -1.0 : 1.0;
    most = fmax(most, nodes_near_extreme(s, u, depth, traction));
  }
  for (int k = 0; k < LSDEM_FLAT_CONTACT_DIRECTIONS; k++) {
    double u[3];
    fibonacci_direction(k, LSDEM_FLAT_CONTACT_DIRECTIONS, u);
    most = fmax(most, nodes_near_extreme(s, u, depth, traction));
  }
  return most;
}
