"""Impulse mode, free collisions (fix impulse/lsdem without walls or gravity).

Elastic (e = 1, mu = 0): two ellipsoids (level-set grids, 300 nodes, random orientations and
spins) meeting off-centre, and three spheres, one running into two that touch at an angle:
kinetic energy, linear momentum and angular momentum about the origin, computed here from
the dumped states (masses, principal moments, quaternions), are the same before and after
to 1e-6 (ETM conserves them: equal and opposite impulses, energy stored and released in
full; the drift keeps a free body's energy and angular momentum).
Inelastic (e = 0.5, report Figure 4.2's bookkeeping): the kinetic energy lost is what the
fix reports dissipated at the contacts; at every step the dissipated energy is (1 - e^2)
of the energy absorbed in compression and the rest is released in separation."""
import math
import os

from grain_decks import qaxis, qnormalize, write_data
from impulse_decks import dump, energy, header, library, momenta, states
from lsdemtest import run_lmp, thermo, check, near, finish

ELL = library("ell.lslib", "ellipsoid", 0.5, 0.35, 0.25, nodes=300, spacing=0.025)
BALL = library("ball.lslib", "sphere", 0.2, nodes=20, analytic=True)
BOX = (-5.0, 5.0, -5.0, 5.0, -5.0, 5.0)


def run(name, lib, grains, e, steps, dt=2e-4):
    data = write_data(os.path.abspath(name + ".data"), grains, box=BOX)
    deck = (header(lib, data) + "fix imp all impulse/lsdem %r 0.0\n" % e
            + "timestep %r\n" % dt + dump(steps, "states.dump")
            + "thermo_style custom step ke f_imp[1] f_imp[10] f_imp[11] f_imp[12] f_imp[13]\n"
            + "thermo_modify norm no format float %%.17g\nthermo 1\nrun %d\n" % steps)
    _, log = run_lmp(deck, cwd=os.path.abspath(name))
    frames = states(os.path.join(name, "states.dump"))
    return frames, thermo(log)


def conserved(name, frames, rows):
    if not check(len(frames) == 2, "%s: two dump frames" % name):
        return
    (_, a0), (_, a1) = frames
    collided = sum(r["f_imp[1]"] for r in rows)
    check(collided > 0, "%s: the grains collided" % name)
    e0, e1 = energy(a0), energy(a1)
    p0, L0 = momenta(a0)
    p1, L1 = momenta(a1)
    pscale = sum(a["mass"] * math.sqrt(a["vx"] ** 2 + a["vy"] ** 2 + a["vz"] ** 2)
                 for a in a0.values())
    Lscale = max(math.sqrt(sum(c * c for c in L0)), pscale * 1.0)
    print("%s: KE %.12g -> %.12g, p %s -> %s" % (name, e0, e1, p0, p1))
    near(e1, e0, rtol=1e-6, msg="%s: kinetic energy" % name)
    for k in range(3):
        near(p1[k], p0[k], atol=1e-6 * pscale, msg="%s: momentum %s" % (name, "xyz"[k]))
        near(L1[k], L0[k], atol=1e-6 * Lscale, msg="%s: angular momentum %s" % (name, "xyz"[k]))
    # the velocities did change: a real collision, not a miss
    dv = max(abs(a1[i]["vx"] - a0[i]["vx"]) for i in a0)
    check(dv > 0.1, "%s: the collision changed the velocities (|dvx| %g)" % (name, dv))


q1 = qnormalize((0.9, 0.2, -0.3, 0.25))
q2 = qnormalize((0.4, -0.6, 0.5, 0.3))
two = [dict(id=1, shape=1, density=1.0, x=(-0.9, 0.12, 0.0), q=q1, v=(1.0, 0.0, 0.05),
            w=(0.0, 0.5, -0.3)),
       dict(id=2, shape=1, density=1.5, x=(0.9, -0.1, 0.08), q=q2, v=(-0.6, 0.02, 0.0),
            w=(0.4, 0.0, 0.2))]
frames, rows = run("two", ELL, two, 1.0, 7000)
conserved("two ellipsoids, e = 1", frames, rows)

# three spheres (radius 0.2): 2 and 3 touch, 1 runs into 2 off its line of centres
c = math.cos(math.radians(25.0)) * 0.4
s = math.sin(math.radians(25.0)) * 0.4
three = [dict(id=1, shape=1, density=1.0, x=(-1.0, 0.05, 0.0), q=(1, 0, 0, 0), v=(2.0, 0, 0)),
         dict(id=2, shape=1, density=2.0, x=(0.0, 0.0, 0.0), q=(1, 0, 0, 0)),
         dict(id=3, shape=1, density=1.0, x=(c, s, 0.0), q=(1, 0, 0, 0))]
frames, rows = run("three", BALL, three, 1.0, 3000)
conserved("three spheres, e = 1", frames, rows)

# e = 0.5: the energy lost is the energy dissipated (report Figure 4.2)
E = 0.5
frames, rows = run("inelastic", BALL, three, E, 3000)
if check(len(frames) == 2 and rows, "inelastic run"):
    lost = energy(frames[0][1]) - energy(frames[1][1])
    absorbed = sum(r["f_imp[10]"] for r in rows)
    dissipated = sum(r["f_imp[11]"] for r in rows)
    released = sum(r["f_imp[12]"] for r in rows)
    print("e = 0.5: KE lost %.12g, absorbed %.12g, dissipated %.12g, released %.12g"
          % (lost, absorbed, dissipated, released))
    check(lost > 0.1 * energy(frames[0][1]), "e = 0.5: energy was lost")
    near(lost, rows[-1]["f_imp[13]"], rtol=1e-6, msg="e = 0.5: KE lost = total dissipated")
    near(dissipated, (1 - E * E) * absorbed, rtol=1e-9, msg="dissipated = (1 - e^2) absorbed")
    near(absorbed, dissipated + released, rtol=1e-6, msg="absorbed = dissipated + released")
finish()
