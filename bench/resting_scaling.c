/* resting_scaling.c -- the resting solve's cost per contact against island size (issue 33:
 * "solver time per contact within +-30 % from islands of 10 to 10^4 contacts").
 *
 *   lsdem-bench-resting [STEPS [THREADS [all]]]
 *
 * Islands: cubic lattices of L x L x H unit spheres resting on a floor under gravity (each
 * sphere touches its -x, -y and -z neighbours, the bottom layer the floor; the lattice is
 * a regular frictional pile whose loads are statically indeterminate sideways), L = 1..
 * and H = L, from 1 to ~10^4 contacts. Each step: gravity kick, lsdem_island_solve with
 * every contact resting (warm-started from the previous step), as fix impulse/lsdem runs
 * it (defaults: 10 sweeps at most, the shock sweep). After 20 warm-up steps, STEPS
 * (default 50) steps are timed. Prints per island: contacts, sweeps per step, microseconds
 * per contact and step, nanoseconds per contact and sweep, and the floor's load against
 * the weight. Wall-clock time (timespec_get) and CPU time (clock, all threads). THREADS 0
 * (the default): the sweeps in the island's order (fix impulse/lsdem's colours no); N >= 1:
 * colour by colour on N OpenMP threads (colours yes; lsdem_resting_params.threads, islands
 * of fewer than 64 pairs per thread take one; the same bits on any N), to 1e-3 as the fix.
 * all: every one of the 10 sweeps runs (tolerance 0), to time the sweeps themselves. */
#include "lsdem.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double cpu_seconds(void) { return (double)clock() / CLOCKS_PER_SEC; }

static double wall_seconds(void)
{
  struct timespec ts;
  timespec_get(&ts, TIME_UTC);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void lattice(int L, int H, double dt, int steps, int threads, int all)
{
  const int nb = L * L * H, nbod = nb + 1, floor_id = nb;
  lsdem_impulse_body *b = calloc((size_t)nbod, sizeof *b);
  const int ncmax = 3 * nb;
  lsdem_impulse_contact *c = calloc((size_t)ncmax, sizeof *c);
  double(*P)[3] = calloc((size_t)ncmax, sizeof *P);
  uint8_t *resting = malloc((size_t)ncmax);
  const double zero[3] = {0, 0, 0}, I[3] = {0.1, 0.1, 0.1}, q[4] = {1, 0, 0, 0};
  lsdem_error err;
  for (int k = 0; k < nb; k++) {
    const int ix = k % L, iy = (k / L) % L, iz = k / (L * L);
    const double x[3] = {ix, iy, 0.5 + iz};
    lsdem_impulse_body_grain(&b[k], k + 1, 1.0, I, q, x, zero, zero, &err);
  }
  lsdem_impulse_body_wall(&b[floor_id], -1, zero, zero, zero, &err);
  int nc = 0;
  for (int k = 0; k < nb; k++) {
    const int ix = k % L, iy = (k / L) % L, iz = k / (L * L);
    const int nbr[3] = {ix > 0 ? k - 1 : -1, iy > 0 ? k - L : -1, iz > 0 ? k - L * L : floor_id};
    for (int d = 0; d < 3; d++) {
      if (nbr[d] < 0) continue;
      lsdem_impulse_contact *ct = &c[nc++];
      ct->a = k;
      ct->b = nbr[d];
      for (int i = 0; i < 3; i++) {
        ct->normal[i] = i == d ? 1.0 : 0.0;
        ct->point[i] = b[k].x[i] - (i == d ? 0.5 : 0.0);
      }
      ct->mu = 0.5;
      ct->restitution = 0.5;
    }
  }
  memset(resting, 1, (size_t)nc);
  lsdem_island_params p;
  lsdem_island_params_default(&p);
  p.rest.max_sweeps = 10;
  lsdem_resting_set_colours(&p.rest, threads > 0);
  p.rest.threads = threads > 0 ? threads : 1;
  if (all) p.rest.tolerance = 0.0;
  p.rest.ref_speed = 2.0 * 9.81 * dt;
  p.rest.dt = dt;
  p.collide_speed = p.rest.ref_speed;
  p.approach_floor = 1e-3 * p.rest.ref_speed;
  p.etm.min_approach = p.rest.tolerance * p.rest.ref_speed;
  const size_t wsize = lsdem_island_workspace_size(nbod, nc);
  void *ws = malloc(wsize);
  lsdem_island_result res;
  long sweeps = 0;
  double t = 0.0, cpu = 0.0;
  for (int s = 0; s < 20 + steps; s++) {
    for (int k = 0; k < nb; k++) b[k].v[2] -= 9.81 * dt;
    const double t0 = wall_seconds(), c0 = cpu_seconds();
    if (lsdem_island_solve(b, nbod, c, nc, resting, P, NULL, 1, &p, ws, wsize, &res, &err) !=
        LSDEM_OK) {
      fprintf(stderr, "island solve: %s\n", err.msg);
      exit(1);
    }
    if (s >= 20) {
      t += wall_seconds() - t0;
      cpu += cpu_seconds() - c0;
      sweeps += res.rest.sweeps;
    }
  }
  double load = 0.0;
  for (int k = 0; k < nc; k++)
    if (c[k].b == floor_id) load += P[k][2];
  printf("%7d %8d %8.2f %10.3f %10.3f %10.1f %10.4f\n", nb, nc, (double)sweeps / steps,
         1e6 * t / ((double)steps * nc), 1e6 * cpu / ((double)steps * nc),
         1e9 * t / ((double)(sweeps + steps) * nc), load / (nb * 9.81 * dt));
  free(b);
  free(c);
  free(P);
  free(resting);
  free(ws);
}

int main(int argc, char **argv)
{
  const int steps = argc > 1 ? atoi(argv[1]) : 50;
  const int threads = argc > 2 ? atoi(argv[2]) : 0;
  const int all = argc > 3 && strcmp(argv[3], "all") == 0;
  if (steps < 1 || threads < 0 || (argc > 3 && !all)) {
    fprintf(stderr, "usage: lsdem-bench-resting [STEPS >= 1 [THREADS >= 0 [all]]]\n");
    return 2;
  }
  if (threads > 0) printf("# colours, %d thread(s)", threads);
  else printf("# in the island's order, one thread");
  printf("%s\n# grains contacts sweeps/step us/contact-step(wall) us/contact-step(cpu) "
         "ns/contact-sweep(wall) floor/weight\n", all ? ", every sweep" : "");
  const int sizes[] = {1, 2, 3, 4, 6, 8, 11, 15};
  for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++)
    lattice(sizes[k], sizes[k], 2.76e-3, steps, threads, all);
  return 0;
}
