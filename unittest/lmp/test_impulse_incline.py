"""Impulse mode, resting contact with friction and moving or curved walls (fix
impulse/lsdem with fix wall/lsdem, report §4.4.1).

A block 1 x 1 x 0.5 (level-set grid, surface nodes) rests on a plane z = 0 with friction
mu = 0.5 under gravity tilted by theta (the incline's frame): for tan(theta) < mu it stays
put (no creep, no spin), held by the resting solve (method split, the default) at dt 1e-3
and at 16 times that step (where the report's wall correction let it creep), and by the
report's wall correction with method etm; for tan(theta) > mu it slides with a = g
(sin(theta) - mu cos(theta)) within 2 %, measured from its velocity along the slope. A ball resting on a
platen that moves up at a constant speed rides on it (velocity of the platen, on its face);
a ball pressed by a sideways gravity against the inside of a cylinder container rests
against it at R - r. The wall's node lists (its own detection keeps them in impulse mode as
in penalty mode) change nothing: the sliding block with nodelist off on the wall runs the
same to the printed digits."""
import math
import os

from impulse_decks import header, library
from lsdemtest import run_lmp, thermo, check, near, finish

G, MU = 9.81, 0.5
BOX = library("block.lslib", "box", 0.5, 0.5, 0.25, nodes=120, spacing=0.05)
BALL = library("ball.lslib", "sphere", 0.2, nodes=20, analytic=True)


def data(name, z, xyz=(0.0, 0.0)):
    path = os.path.abspath(name + ".data")
    with open(path, "w") as f:
        f.write("grain\n\n1 atoms\n1 atom types\n\n-3 3 xlo xhi\n-3 3 ylo yhi\n-1 4 zlo zhi\n\n"
                "Atoms # lsdem\n\n1 1 1 1.0 %r %r %r 1 0 0 0\n" % (xyz[0], xyz[1], z))
    return path


def incline(theta_deg, steps, dt=1e-3, opts="", name=None, wall=""):
    th = math.radians(theta_deg)
    deck = (header(BOX, data("block", 0.25))
            + "fix floor all wall/lsdem plane 0 0 0 0 0 1 1.0e4 0 %r %s\n" % (MU, wall)
            + "fix grav all gravity %r vector %r 0 %r\n" % (G, math.sin(th), -math.cos(th))
            + "fix imp all impulse/lsdem 0.5 0.0 %s\ntimestep %r\n" % (opts, dt)
            + "variable x equal x[1]\nvariable z equal z[1]\nvariable vx equal vx[1]\n"
            + "variable vy equal vy[1]\ncompute w all property/atom omegax omegay omegaz\n"
            # grain 1's |omega| through an atom-style variable: an equal-style c_w[1][1] is
            # LAMMPS 2021's syntax, C_w[1][1] that of 2025; v_w2[1] works in both
            + "variable w2 atom c_w[1]^2+c_w[2]^2+c_w[3]^2\nvariable w equal sqrt(v_w2[1])\n"
            + "thermo_style custom step v_x v_z v_vx v_vy v_w f_imp[6] f_imp[22]\n"
            + "thermo_modify format float %%.15g\nthermo 50\nrun %d\n" % steps)
    _, log = run_lmp(deck, cwd=os.path.abspath(name or "theta%g" % theta_deg))
    return thermo(log)


# stays: tan(20 deg) = 0.36 < mu; at dt 1e-3 and 16e-3 (split), and by the report's method
for dt, opts, name in ((1e-3, "", "theta20"), (16e-3, "", "theta20_x16"),
                       (1e-3, "method etm", "theta20_etm")):
    rows = incline(20.0, 2000, dt, opts, name)
    if not check(len(rows) > 10, "%s ran" % name):
        continue
    late = [r for r in rows if r["Step"] >= 500]
    creep = late[-1]["v_x"] - late[0]["v_x"]
    print("%s: creep %.3g over %d steps, |vx| up to %.3g, spin up to %.3g" % (
        name, creep, late[-1]["Step"] - late[0]["Step"], max(abs(r["v_vx"]) for r in late),
        max(r["v_w"] for r in late)))
    if opts:  # the report's wall correction: creep below 1e-3 (it is not zero)
        check(abs(creep) < 1e-3, "%s: the block creeps %g along the slope" % (name, creep))
        check(late[-1]["f_imp[6]"] >= 1, "%s: the wall correction holds it" % name)
    else:  # the resting solve: it sticks
        check(abs(creep) < 1e-9, "%s: the block creeps %g along the slope" % (name, creep))
        check(late[-1]["f_imp[22]"] >= 1, "%s: resting contacts hold it" % name)
        check(late[-1]["f_imp[6]"] == 0, "%s: the wall guard did not act" % name)
    check(max(abs(r["v_vx"]) for r in late) < 2 * G * dt, "%s: it stays at rest" % name)
    check(max(r["v_w"] for r in late) < 0.05, "%s: no spin" % name)
    # on the plane, within the resting overlap left alone (the slop, 2 g dt^2)
    check(all(abs(r["v_z"] - 0.25) < 2e-3 + 2 * G * dt * dt for r in late),
          "%s: it rests on the plane" % name)

# slides: tan(35 deg) = 0.70 > mu
th = math.radians(35.0)
rows = incline(35.0, 1500)
if check(len(rows) > 10, "incline 35 deg ran"):
    r1 = next(r for r in rows if r["Step"] == 500)
    r2 = rows[-1]
    a = (r2["v_vx"] - r1["v_vx"]) / ((r2["Step"] - r1["Step"]) * 1e-3)
    expect = G * (math.sin(th) - MU * math.cos(th))
    print("theta 35: a = %.5f, g (sin - mu cos) = %.5f (ratio %.5f)" % (a, expect, a / expect))
    near(a, expect, rtol=0.02, msg="tan(theta) > mu: sliding acceleration")
    check(abs(r2["v_vy"]) < 1e-3 * abs(r2["v_vx"]), "it slides straight down the slope")
    check(incline(35.0, 1500, wall="nodelist off", name="theta35_nodelist_off") == rows,
          "the wall's node lists changed the slide")

# a platen moving up at 0.3 carries a ball resting on it
V = 0.3
deck = (header(BALL, data("platen", 0.2))
        + "fix floor all wall/lsdem plane 0 0 0 0 0 1 1.0e4 0 0.5 velocity 0 0 %r\n" % V
        + "fix grav all gravity %r vector 0 0 -1\n" % G
        + "fix imp all impulse/lsdem 0.3 0.0\ntimestep 1e-3\n"
        + "variable z equal z[1]\nvariable vz equal vz[1]\n"
        + "thermo_style custom step v_z v_vz f_floor[6]\nthermo_modify format float %.15g\n"
        + "thermo 100\nrun 2000\n")
_, log = run_lmp(deck, cwd=os.path.abspath("platen"))
late = [r for r in thermo(log) if r["Step"] >= 1000]
if check(late, "platen ran"):
    gaps = [r["v_z"] - 0.2 - V * r["Step"] * 1e-3 for r in late]
    print("platen: ball bottom minus platen %.3g .. %.3g, vz %.6g" % (min(gaps), max(gaps),
                                                                     late[-1]["v_vz"]))
    check(all(abs(g) < 2 * G * 1e-6 + 1e-9 for g in gaps), "the ball stays on the moving platen")
    near(late[-1]["v_vz"], V, atol=2 * G * 1e-3, msg="the ball moves with the platen")

# a cylinder container (radius 1) holds a ball pressed against its side
deck = (header(BALL, data("cylinder", 0.0, (0.5, 0.0)))
        + "fix can all wall/lsdem cylinder 0 0 1.0 1.0e4 0 0.5\n"
        + "fix grav all gravity %r vector 1 0 0\n" % G
        + "fix imp all impulse/lsdem 0.3 0.0\ntimestep 1e-3\n"
        + "variable x equal x[1]\nthermo_style custom step v_x\nthermo_modify format float %.15g\n"
        + "thermo 100\nrun 2000\n")
_, log = run_lmp(deck, cwd=os.path.abspath("cylinder"))
late = [r for r in thermo(log) if r["Step"] >= 1500]
if check(late, "cylinder ran"):
    print("cylinder: x = %.9g (R - r = 0.8)" % late[-1]["v_x"])
    check(all(abs(r["v_x"] - 0.8) < 2 * G * 1e-6 + 1e-9 for r in late),
          "the ball rests against the cylinder wall at R - r")
finish()
