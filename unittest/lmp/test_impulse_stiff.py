"""Impulse mode, the stiff cases of report Figures 4.3 and 4.8: each either converges
(finite velocities at every step, the grains kept apart) or stops with the island report
(its size, its grains' ids, the mass ratio, the step and what to change) -- never a NaN,
never a hang.

  sandwich  a small sphere between two large ones pushed together by a constant force
            (Figure 4.3 left), mass ratios 30 and 1000;
  on wall   a small sphere on a plane under a large one (Figure 4.3 right; gravity),
            mass ratios 30 and 1000;
  enclosed  a small ellipsoid (nodes) moving inside a large one (Figure 4.8 right): every
            node of the small grain is inside the large one, impulses from all sides."""
import math
import os
import re

from grain_decks import read_dump, write_data
from impulse_decks import header, library
from lsdemtest import run_lmp, thermo, check, finish, shape_tool

SMALL, LARGE = 0.1, 0.2
if not os.path.exists("spheres.lslib"):
    shape_tool("analytic", "s.lslib", "sphere", SMALL, "--analytic", "--nodes", 20)
    shape_tool("analytic", "l.lslib", "sphere", LARGE, "--analytic", "--nodes", 20)
    shape_tool("merge", "spheres.lslib", "s.lslib", "l.lslib")
if not os.path.exists("ells.lslib"):
    shape_tool("analytic", "es.lslib", "ellipsoid", 0.12, 0.1, 0.08, "--nodes", 100,
               "--spacing", 0.01)
    shape_tool("analytic", "el.lslib", "ellipsoid", 0.5, 0.4, 0.35, "--nodes", 200,
               "--spacing", 0.025)
    shape_tool("merge", "ells.lslib", "es.lslib", "el.lslib")
BOX = (-2.0, 2.0, -2.0, 2.0, -1.0, 3.0)
CAPS = "iterations 200000 rounds 2000"
DUMP = ("dump d all custom {n} end.dump id x y z\ndump_modify d sort id format float %.17g\n")


def density_for(ratio):
    """Density of a large sphere whose mass is `ratio` times a small one of density 1."""
    return ratio * (SMALL / LARGE) ** 3


def outcome(name, lib, grains, extra, steps, dt=1e-3, caps=CAPS, apart=None):
    """Runs the case; apart: (i, j, distance) the centres of grains i and j must keep
    (within 10 % of the small radius) when it converges."""
    data = write_data(os.path.abspath(name + ".data"), grains, box=BOX)
    deck = (header(lib, data) + extra + "fix imp all impulse/lsdem 0.5 0.3 %s\n" % caps
            + "timestep %r\n" % dt + DUMP.format(n=steps)
            + "thermo_style custom step ke f_imp[1] f_imp[2] f_imp[4] f_imp[6]\n"
            + "thermo_modify norm no format float %%.10g\nthermo 10\nrun %d\n" % steps)
    rc, log = run_lmp(deck, cwd=os.path.abspath(name), expect_fail=True, timeout=300)
    rows = thermo(log)
    finite = all(math.isfinite(v) for r in rows for v in r.values())
    check(finite and "nan" not in log.lower().split("error")[0], "%s: no NaN in the output" % name)
    if rc == 0:
        check(rows and rows[-1]["Step"] == steps, "%s: ran to the end" % name)
        print("%s: converged at every step (largest island %d, ETM iterations up to %d)"
              % (name, max(r["f_imp[2]"] for r in rows), max(r["f_imp[4]"] for r in rows)))
        if apart:
            end = read_dump(os.path.join(name, "end.dump"))[-1][1]
            i, j, dist = apart
            d = math.dist([end[i][k] for k in "xyz"], [end[j][k] for k in "xyz"])
            check(d > dist - 0.1 * SMALL, "%s: grains %d and %d %.4g apart, in contact at %.4g"
                  % (name, i, j, d, dist))
        return "converged"
    m = re.search(r"ERROR: (Fix impulse/lsdem: step \d+.*)", log)
    if not check(m, "%s: stopped without the island report:\n%s" % (name, log[-1500:])):
        return "failed"
    mesg = m.group(1)
    for what, pattern in (("step", r"step \d+"), ("size", r"island of \d+ bodies"),
                          ("ids", r"ids \d+"), ("mass ratio", r"mass ratio [\d.e+]+"),
                          ("advice", r"Try a smaller time step")):
        check(re.search(pattern, mesg), "%s: the island report names the %s: %s"
              % (name, what, mesg))
    print("%s: stopped with the island report: %s" % (name, mesg[:300]))
    return "reported"


for ratio in (30, 1000):
    rho = density_for(ratio)
    sandwich = [dict(id=1, shape=2, density=rho, x=(-0.3, 0, 0.5), q=(1, 0, 0, 0)),
                dict(id=2, shape=1, density=1.0, x=(0.0, 0, 0.5), q=(1, 0, 0, 0)),
                dict(id=3, shape=2, density=rho, x=(0.3, 0, 0.5), q=(1, 0, 0, 0))]
    m_large = rho * 4.0 / 3.0 * math.pi * LARGE ** 3
    push = ("group left id 1\ngroup right id 3\n"
            "fix pl left addforce %r 0 0\nfix pr right addforce %r 0 0\n"
            % (10 * m_large, -10 * m_large))
    outcome("sandwich%d" % ratio, "spheres.lslib", sandwich, push, 500,
            apart=(1, 2, SMALL + LARGE))
    if ratio == 1000:  # the same with a low cap: the island report, not a silent result
        check(outcome("capped", "spheres.lslib", sandwich, push, 500,
                      caps="iterations 2000") == "reported", "a capped island is reported")

    on_wall = [dict(id=1, shape=1, density=1.0, x=(0, 0, SMALL), q=(1, 0, 0, 0)),
               dict(id=2, shape=2, density=rho, x=(0.02, 0, 2 * SMALL + LARGE), q=(1, 0, 0, 0))]
    walls = ("fix floor all wall/lsdem plane 0 0 0 0 0 1 1.0e4 0 0.3\n"
             "fix grav all gravity 9.81 vector 0 0 -1\n")
    outcome("onwall%d" % ratio, "spheres.lslib", on_wall, walls, 500, apart=(1, 2, SMALL + LARGE))

enclosed = [dict(id=1, shape=1, density=1.0, x=(0.05, 0, 0.5), q=(1, 0, 0, 0), v=(0.5, 0.2, 0)),
            dict(id=2, shape=2, density=1.0, x=(0, 0, 0.5), q=(1, 0, 0, 0))]
outcome("enclosed", "ells.lslib", enclosed, "", 200)
finish()
