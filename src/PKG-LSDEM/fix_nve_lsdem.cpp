// clang-format off
/* ----------------------------------------------------------------------
   LSDEM package: level-set discrete element method for LAMMPS.

   fix nve/lsdem [damping xi]: the report's leapfrog for rigid grains (§2.2.7).
   Time levels: x and quat at whole steps, v and omega at half steps. The whole update
   runs in initial_integrate, where f and torque still hold the forces of step n
   (LAMMPS clears them after initial_integrate):
     v^{n-1/2} -> v^{n+1/2}, x^n -> x^{n+1}             (eqs 2.18-2.19)
     torque to the body frame with q^n, Euler equations by predictor-corrector
     (eqs 2.21-2.25), q^n -> q^{n+1}, omega back to the world frame with q^{n+1}.
   All formulas live in the core (lsdem_step_body, lsdem_step_translation).
------------------------------------------------------------------------- */

#include "fix_nve_lsdem.h"

#include "atom.h"
#include "atom_vec_lsdem.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "lsdem_input.h"
#include "modify.h"
#include "pair_lsdem.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

/* ---------------------------------------------------------------------- */

FixNVELsdem::FixNVELsdem(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), xi(0.0), avec(nullptr), spheres_rotate(true), fixed_spin(0),
  warned_dt(0.0)
{
  time_integrate = 1;

  int iarg = 3;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "damping") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "Illegal fix nve/lsdem command: damping needs a value");
      xi = LsdemInput::number(FLERR, arg[iarg + 1], "fix nve/lsdem", "damping", lmp);
      if (xi < 0.0) error->all(FLERR, "Illegal fix nve/lsdem command: damping {} < 0", xi);
      iarg += 2;
    } else if (strcmp(arg[iarg], "spheres") == 0) {
      const std::string val = iarg + 1 < narg ? arg[iarg + 1] : "";
      if (val == "rotate") spheres_rotate = true;
      else if (val == "fixed") spheres_rotate = false;
      else error->all(FLERR, "Illegal fix nve/lsdem command: spheres must be rotate or fixed, "
                      "not '{}'", val);
      iarg += 2;
    } else error->all(FLERR, "Illegal fix nve/lsdem command: unknown keyword {}", arg[iarg]);
  }

  if (!dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem")))
    error->all(FLERR, "Fix nve/lsdem requires atom_style lsdem");
}

/* ---------------------------------------------------------------------- */

int FixNVELsdem::setmask()
{
  return INITIAL_INTEGRATE;
}

/* ---------------------------------------------------------------------- */

void FixNVELsdem::init()
{
  avec = dynamic_cast<AtomVecLsdem *>(atom->style_match("lsdem"));
  if (!avec) error->all(FLERR, "Fix nve/lsdem requires atom_style lsdem");
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "Fix nve/lsdem does not support run_style respa");
  // a flexible membrane's balls keep 3 degrees of freedom (report §3.3.2): their spin would
  // only feed the friction of the membrane's contacts
  fixed_spin = 0;
  for (int k = 0; k < modify->nfix; k++)
    if (utils::strmatch(modify->fix[k]->style, "^membrane/lsdem"))  // and membrane/lsdem/omp
      fixed_spin |= modify->fix[k]->groupbit;
  check_timestep();
}

/* ----------------------------------------------------------------------
   warn when dt > 0.2 sqrt(m / k) for some grain of the group: m its mass, k the normal
   stiffness of the stiffest contact it can form, a flat face pressing many node springs
   at once (PairLsdem::stiffest_contact; a wall of the same kn alike). Its contact period
   2 pi sqrt(m / k) then spans fewer than ~30 steps. The grain with the smallest bound
   (lowest rank on a tie) is named.
------------------------------------------------------------------------- */

void FixNVELsdem::check_timestep()
{
  PairLsdem *pair = PairLsdem::of(force);
  if (!pair) return;
  struct { double dt; int rank; } mine = {HUGE_VAL, comm->me}, least;
  double worst[4] = {0.0, 0.0, 0.0, 0.0};  // its tag, mass, stiffness, node springs
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    double nodes;
    const double k = pair->stiffest_contact(avec->shape[i], nodes);
    if (!(k > 0.0)) continue;
    const double dt = 0.2 * std::sqrt(atom->rmass[i] / (k * force->ftm2v));
    if (dt < mine.dt) {
      mine.dt = dt;
      worst[0] = (double) atom->tag[i];
      worst[1] = atom->rmass[i];
      worst[2] = k;
      worst[3] = nodes;
    }
  }
  MPI_Allreduce(&mine, &least, 1, MPI_DOUBLE_INT, MPI_MINLOC, world);
  if (least.dt == HUGE_VAL || update->dt <= least.dt || update->dt == warned_dt) return;
  warned_dt = update->dt;
  MPI_Bcast(worst, 4, MPI_DOUBLE, least.rank, world);
  // suggestion: the bound rounded down to two significant digits
  const double decade = std::pow(10.0, std::floor(std::log10(least.dt)) - 1.0);
  const double suggest = std::floor(least.dt / decade) * decade;
  if (comm->me == 0)
    error->warning(FLERR, "Fix nve/lsdem: timestep {:.6g} > 0.2*sqrt(m/k) = {:.6g} for grain "
                   "{} (mass m = {:.6g}; k = {:.6g}: the pair style's kn {:.6g} times the {:.6g} "
                   "{} one flat contact of its shape presses); suggest timestep {:.2g}",
                   update->dt, least.dt, (tagint) worst[0], worst[1], worst[2],
                   worst[2] / worst[3], worst[3],
                   pair->traction() ? "node area" : "nodes", suggest);
}

/* ---------------------------------------------------------------------- */

void FixNVELsdem::initial_integrate(int /*vflag*/)
{
  const char *what = nullptr;
  const int bad = step_grains(0, integrated_count(), what);
  stop_if_unstable(bad, what);
}

/* ----------------------------------------------------------------------
   the local atoms this fix integrates are among the first n (the group's atoms first
   when it is atom_modify first)
------------------------------------------------------------------------- */

int FixNVELsdem::integrated_count() const
{
  return igroup == atom->firstgroup ? atom->nfirst : atom->nlocal;
}

/* ----------------------------------------------------------------------
   what is wrong with a grain's state (x, v, omega, quat; bounding radius) after its step,
   or nullptr: a non-finite state, or a move of more than half its bounding radius in one
   step (the run has gone unstable and every later step is garbage). Inline in the step's
   loop, on the values it has just written
------------------------------------------------------------------------- */

static inline const char *state_problem(const double *x, const double *v, const double *w,
                                        const double *q, double radius, double dt)
{
  double sum = 0.0;
  for (int k = 0; k < 3; k++) sum += x[k] + v[k] + w[k];
  sum += q[0] + q[1] + q[2] + q[3];
  if (!std::isfinite(sum)) return "a non-finite (NaN/inf) state";

  const double v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  const double rlim = 0.5 * radius;
  if (v2 * dt * dt > rlim * rlim) return "a runaway speed";
  return nullptr;
}

/* ----------------------------------------------------------------------
   one step of the group's local grains from..to-1; returns the first of them found
   unstable (what: how), or -1. Grains are independent: threads share them out
   (fix nve/lsdem/omp)
------------------------------------------------------------------------- */

int FixNVELsdem::step_grains(int from, int to, const char *&what)
{
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  double **omega = atom->omega;
  double **torque = atom->torque;
  double *rmass = atom->rmass;
  double *radius = atom->radius;
  double **quat = avec->quat;
  int *mask = atom->mask;

  const double dt = update->dt;
  const double ftm2v = force->ftm2v;
  const lsdem_damped_step k = lsdem_damped_step_of(xi, dt);  // eq 2.18's factors, once
  int bad = -1;
  what = nullptr;

  for (int i = from; i < to; i++) {
    if (!(mask[i] & groupbit)) continue;

    // force and torque in velocity units: f dt/m and M dt/I then come out as velocities
    const double fs[3] = {ftm2v * f[i][0], ftm2v * f[i][1], ftm2v * f[i][2]};

    if (avec->shape_of(i)->sdf.kind == LSDEM_SDF_SPHERE) {
      const double ts[3] = {ftm2v * torque[i][0], ftm2v * torque[i][1], ftm2v * torque[i][2]};
      if (spheres_rotate && !(mask[i] & fixed_spin)) {
        // analytic spheres turn about their centre: one moment of inertia, no gyroscopic term
        lsdem_step_sphere(x[i], v[i], quat[i], omega[i], fs, ts, rmass[i], avec->inertia[i][0],
                          &k);
      } else {
        // 3 degrees of freedom (membrane balls, report §3.3.2, or spheres fixed): torque is
        // ignored, quat is unchanged and omega is held at zero (a spin left from a data file
        // would otherwise feed the contacts' friction)
        lsdem_step_translation(x[i], v[i], fs, rmass[i], &k);
        omega[i][0] = omega[i][1] = omega[i][2] = 0.0;
      }
    } else {
      const double ts[3] = {ftm2v * torque[i][0], ftm2v * torque[i][1], ftm2v * torque[i][2]};
      double *q = quat[i];
      double wbody[3];
      lsdem_quat_rotate_inv(q, omega[i], wbody);  // omega^{n-1/2} to the body frame with q^n
      lsdem_step_body(x[i], v[i], q, wbody, avec->dwprev[i], fs, ts, rmass[i],
                      avec->inertia[i], xi, dt, omega[i]);
    }
    if (bad < 0 && (what = state_problem(x[i], v[i], omega[i], quat[i], radius[i], dt))) bad = i;
  }
  return bad;
}

/* ----------------------------------------------------------------------
   all ranks stop together, so that the message and everything written reach the files;
   a problem another style found since the last check (a grain through a wall) first,
   then grain bad (>= 0) of this rank
------------------------------------------------------------------------- */

void FixNVELsdem::stop_if_unstable(int bad, const char *what)
{
  std::string found = avec->take_deferred_stop();
  if (found.empty() && bad >= 0) found = unstable_message(bad, update->dt, what);
  AtomVecLsdem::stop_if_any_rank(lmp, FLERR, found);
}

/* ---------------------------------------------------------------------- */

std::string FixNVELsdem::unstable_message(int i, double dt, const char *what) const
{
  const double *x = atom->x[i], *v = atom->v[i], *w = atom->omega[i];
  const double *q = avec->quat[i];
  const double *fi = atom->f[i], *t = atom->torque[i];
  const double speed = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return fmt::format(
      "Fix nve/lsdem: grain {} became unstable at step {} with {}: "
      "x = ({:.6g} {:.6g} {:.6g}), v = ({:.6g} {:.6g} {:.6g}), "
      "omega = ({:.6g} {:.6g} {:.6g}), quat = ({:.6g} {:.6g} {:.6g} {:.6g}), "
      "force = ({:.6g} {:.6g} {:.6g}), torque = ({:.6g} {:.6g} {:.6g}); "
      "|v|*dt = {:.6g} vs half the bounding radius {:.6g}. Likely causes: initial overlap "
      "between grains (or a grain starting behind a wall or outside its container), a time "
      "step too large for the contact stiffness kn (reduce the "
      "timestep or kn), or a stiffness/force far too large",
      atom->tag[i], update->ntimestep, what, x[0], x[1], x[2], v[0], v[1], v[2],
      w[0], w[1], w[2], q[0], q[1], q[2], q[3], fi[0], fi[1], fi[2], t[0], t[1], t[2],
      speed * dt, 0.5 * atom->radius[i]);
}
