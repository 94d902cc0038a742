/* impulse_fixtures.h -- bodies, energies and momenta for the impulse-mode tests
 * (test_impulse_*.c). Energies and momenta are computed here from the masses and the
 * world inertia I = R I0 R^T (not from the core's inverse), so they check the core
 * independently. Header-only. */
#ifndef IMPULSE_FIXTURES_H
#define IMPULSE_FIXTURES_H
#include "contact_fixtures.h"
#include "lsdem.h"
#include "lsdem_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A grain's state as the tests keep it (what fix impulse/lsdem keeps per atom). */
typedef struct {
  int64_t id;
  double mass, inertia[3], q[4];
  double x[3], v[3], omega[3];
} fx_state;

static inline fx_state fx_grain(int64_t id, double mass, double i0, double i1, double i2,
                                const double x[3], const double v[3], const double w[3])
{
  fx_state s;
  memset(&s, 0, sizeof s);
  s.id = id;
  s.mass = mass;
  s.inertia[0] = i0;
  s.inertia[1] = i1;
  s.inertia[2] = i2;
  s.q[0] = 1.0;
  memcpy(s.x, x, sizeof s.x);
  memcpy(s.v, v, sizeof s.v);
  memcpy(s.omega, w, sizeof s.omega);
  return s;
}

/* A solid sphere of density 1: m = 4/3 pi r^3, I = 2/5 m r^2. */
static inline fx_state fx_sphere(int64_t id, double r, const double x[3], const double v[3])
{
  const double m = 4.0 / 3.0 * FIX_PI * r * r * r, I = 0.4 * m * r * r;
  const double w[3] = {0, 0, 0};
  return fx_grain(id, m, I, I, I, x, v, w);
}

static inline void fx_body_of(const fx_state *s, lsdem_impulse_body *b)
{
  lsdem_error err;
  const lsdem_status st = lsdem_impulse_body_grain(b, s->id, s->mass, s->inertia, s->q,
                                                   s->x, s->v, s->omega, &err);
  CHECK(st == LSDEM_OK, "body %lld: %s", (long long)s->id, err.msg);
}

static inline void fx_state_from(fx_state *s, const lsdem_impulse_body *b)
{
  memcpy(s->v, b->v, sizeof s->v);
  memcpy(s->omega, b->omega, sizeof s->omega);
}

static inline void fx_wall(lsdem_impulse_body *b, int64_t id, const double x[3],
                           const double v[3])
{
  const double w[3] = {0, 0, 0};
  lsdem_error err;
  CHECK(lsdem_impulse_body_wall(b, id, x, v, w, &err) == LSDEM_OK, "%s", err.msg);
}

/* World inertia R I0 R^T of a state. */
static inline void fx_world_inertia(const fx_state *s, double I[9])
{
  double R[9];
  lsdem_quat_to_matrix(s->q, R);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double sum = 0.0;
      for (int k = 0; k < 3; k++) sum += R[3 * i + k] * s->inertia[k] * R[3 * j + k];
      I[3 * i + j] = sum;
    }
}

/* Kinetic energy 1/2 m v^2 + 1/2 w . I w of body b, I that of state s. */
static inline double fx_kinetic(const fx_state *s, const lsdem_impulse_body *b)
{
  double I[9], Iw[3];
  fx_world_inertia(s, I);
  lsdem_mat_vec(I, b->omega, Iw);
  return 0.5 * s->mass * lsdem_dot3(b->v, b->v) + 0.5 * lsdem_dot3(b->omega, Iw);
}

/* Linear momentum p and angular momentum L about the origin of body b, accumulated. */
static inline void fx_momenta(const fx_state *s, const lsdem_impulse_body *b, double p[3],
                              double L[3])
{
  double I[9], Iw[3], xv[3];
  fx_world_inertia(s, I);
  lsdem_mat_vec(I, b->omega, Iw);
  fix_cross(b->x, b->v, xv);
  for (int i = 0; i < 3; i++) {
    p[i] += s->mass * b->v[i];
    L[i] += s->mass * xv[i] + Iw[i];
  }
}

/* A random unit quaternion. */
static inline void fx_random_quat(double q[4])
{
  for (int i = 0; i < 4; i++) q[i] = srand1();
  lsdem_quat_normalize(q);
}

/* n random grains (ids 1..n) in s and their bodies in b: centres, velocities and spins in
 * (-1, 1]^3, masses in (0.5, 1.5], principal moments in (0.1, 1.1], random orientations. */
static inline void fx_random_grains(fx_state *s, lsdem_impulse_body *b, int n)
{
  for (int k = 0; k < n; k++) {
    const double x[3] = {srand1(), srand1(), srand1()}, v[3] = {srand1(), srand1(), srand1()},
                 w[3] = {srand1(), srand1(), srand1()};
    s[k] = fx_grain(k + 1, 0.5 + urand(), 0.1 + urand(), 0.1 + urand(), 0.1 + urand(), x, v, w);
    fx_random_quat(s[k].q);
    fx_body_of(&s[k], &b[k]);
  }
}

/* A contact between a and b at p with normal n (normalised here). */
static inline lsdem_impulse_contact fx_contact(int a, int b, const double p[3], double n0,
                                               double n1, double n2, double mu, double e)
{
  lsdem_impulse_contact c;
  memset(&c, 0, sizeof c);
  const double len = sqrt(n0 * n0 + n1 * n1 + n2 * n2);
  c.a = a;
  c.b = b;
  memcpy(c.point, p, sizeof c.point);
  c.normal[0] = n0 / len;
  c.normal[1] = n1 / len;
  c.normal[2] = n2 / len;
  c.mu = mu;
  c.restitution = e;
  return c;
}

/* ETM with default parameters and workspace from the heap (tests only). */
static inline lsdem_status fx_etm(lsdem_impulse_body *b, int nb,
                                  const lsdem_impulse_contact *c, int nc,
                                  const lsdem_etm_params *p, lsdem_etm_result *res,
                                  lsdem_error *err)
{
  lsdem_etm_params def;
  lsdem_etm_params_default(&def);
  const size_t ws = lsdem_etm_workspace_size(nb, nc);
  void *mem = malloc(ws);
  const lsdem_status st = lsdem_etm_solve(b, nb, c, nc, p ? p : &def, mem, ws, res, err);
  free(mem);
  return st;
}

#endif
