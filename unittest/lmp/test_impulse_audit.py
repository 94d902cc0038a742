"""Impulse mode's energy audit (fix impulse/lsdem values 36-45; issue 33).

Each step the kinetic energy change of the fix's grains (translation and rotation, measured:
value 43) must equal the sum of the work every stage books by its own arithmetic -- the
kick's (36), ETM's collision impulses' (37), the resting solve's (28), the wall guard's (38),
the ball guard's (39), global damping's (40), the drift's free rotation (41) and sleeping's
(42) -- to round-off: the relative residual (44) <= 1e-9 at every step, printed every step,
and its largest over the run (45) too. Each scene makes the terms it covers act (each is
asserted nonzero where it must act, so that a stage whose booking is missing fails the
test), and the contact stages' bookings add up to value 29, the contacts' change measured:
- a sphere dropped on a plane with restitution, gravity and global damping (kick, ETM,
  damping; the report's method and split);
- spheres thrown sideways on a frictional floor and a column of spheres settling on it
  (the resting solve with friction, the wall guard);
- boxes tumbling onto the floor, the report's method (ETM with friction, the wall guard's
  normal and friction impulses, the free rotation of an anisotropic body);
- a column that falls asleep (keyword sleep);
- balls of a net under a grain (keyword balls: the ball guard), on 1 and 2 ranks."""
import os

from impulse_decks import header, library, net_scene
from lsdemtest import run_lmp, thermo, check, finish

G, R = 9.81, 0.1
BALL = library("ball.lslib", "sphere", R, nodes=20, analytic=True)
BOX = library("block.lslib", "box", 0.3, 0.2, 0.1, nodes=120, spacing=0.05)
TOL = 1e-9
# the audit's values: work of the kick, ETM, resting solve, wall guard, ball guard,
# damping, drift, sleeping; the measured change; the residual and its largest
TERMS = {"kick": 36, "etm": 37, "resting": 28, "wall": 38, "ball": 39, "damping": 40,
         "drift": 41, "sleep": 42}
COLUMNS = " ".join("f_imp[%d]" % k for k in list(TERMS.values()) + [43, 44, 45, 29, 9, 3])


def data(name, atoms, box="-2 2 xlo xhi\n-2 2 ylo yhi\n-1 4 zlo zhi\n"):
    """atoms: (x, y, z, q); every grain of shape 1, density 1."""
    path = os.path.abspath(name + ".data")
    with open(path, "w") as f:
        f.write("grains\n\n%d atoms\n1 atom types\n\n%s\nAtoms # lsdem\n\n" % (len(atoms), box))
        for k, (x, y, z, q) in enumerate(atoms):
            f.write("%d 1 1 1.0 %r %r %r %r %r %r %r\n" % ((k + 1, x, y, z) + tuple(q)))
    return path


def scene(name, lib, atoms, fix, steps, dt=1e-3, extra="", np=1, mu_floor=0.5):
    """The grains under gravity on a floor, fix imp ... (fix: its arguments after
    impulse/lsdem); thermo every step; on np ranks split along x. The thermo rows."""
    grid = "processors %d 1 1\nread_data" % np
    deck = (header(lib, data(name, atoms)).replace("read_data", grid)
            + "fix floor all wall/lsdem plane 0 0 0 0 0 1 1.0e4 0 %r\n" % mu_floor
            + "fix grav all gravity %r vector 0 0 -1\n" % G + extra
            + "fix imp all impulse/lsdem %s\ntimestep %r\n" % (fix, dt)
            + "thermo_style custom step %s\n" % COLUMNS
            + "thermo_modify norm no format float %%.17g\nthermo 1\nrun %d\n" % steps)
    _, log = run_lmp(deck, np=np, cwd=os.path.abspath(name))
    return thermo(log)


def audit(name, rows, acting):
    """The audit closes at every step; the terms in acting act at some step."""
    if not check(len(rows) > 1, name + " ran"):
        return
    worst = max(rows, key=lambda r: r["f_imp[44]"])
    contact = max(abs(r["f_imp[29]"] - sum(r["f_imp[%d]" % TERMS[t]]
                                           for t in ("etm", "resting", "wall", "ball")))
                  / max(r["f_imp[9]"], sum(abs(r["f_imp[%d]" % k]) for k in TERMS.values()),
                        1e-300)
                  for r in rows)
    # each term's largest share of its step's energy scale: a term that acts must reach
    # 1000 times the tolerance at some step, so that the audit fails without its booking
    def scale(r):
        return max(r["f_imp[9]"], r["f_imp[9]"] - r["f_imp[43]"],
                   sum(abs(r["f_imp[%d]" % k]) for k in TERMS.values()), 1e-300)
    size = {t: max(abs(r["f_imp[%d]" % k]) / scale(r) for r in rows) for t, k in TERMS.items()}
    print("%s: residual up to %.3g (step %d), run's largest %.3g; contact stages against value "
          "29 %.3g; largest shares %s" % (name, worst["f_imp[44]"], worst["Step"],
                                         rows[-1]["f_imp[45]"], contact,
                                         " ".join("%s %.3g" % kv for kv in size.items())))
    for r in rows:
        check(r["f_imp[44]"] <= TOL, "%s step %d: audit residual %.3g (KE change %.17g)"
              % (name, r["Step"], r["f_imp[44]"], r["f_imp[43]"]))
    check(rows[-1]["f_imp[45]"] <= TOL and rows[-1]["f_imp[45]"] >= worst["f_imp[44]"],
          "%s: the run's largest residual %.3g" % (name, rows[-1]["f_imp[45]"]))
    check(contact <= TOL, "%s: the contact stages' bookings against value 29: %.3g"
          % (name, contact))
    for t in acting:
        check(size[t] > 1e3 * TOL, "%s: the %s term never acted (largest share %.3g)"
              % (name, t, size[t]))
    # value 43 is the change of the grains' kinetic energy (value 9) between printed steps
    for a, b in zip(rows, rows[1:]):
        change = b["f_imp[9]"] - a["f_imp[9]"]
        if abs(change - b["f_imp[43]"]) > 1e-12 * max(a["f_imp[9]"], b["f_imp[9]"], 1e-300):
            check(False, "%s step %d: value 43 %.17g, KE change %.17g" % (
                name, b["Step"], b["f_imp[43]"], change))
            break


Q0 = (1, 0, 0, 0)
# a sphere dropped from 0.02 above the plane, e = 0.3, damping: bounces (ETM), then rests
for method in ("split", "etm"):
    rows = scene("drop_" + method, BALL, [(0.0, 0.0, R + 0.02, Q0)],
                 "0.3 0.3 damping 0.5 method %s" % method, 400)
    audit("ball drop (%s)" % method, rows, ["kick", "etm", "damping"]
          + (["resting"] if method == "split" else ["wall"]))

# spheres thrown sideways on the frictional floor, and a column of four settling on it
# beside a row of two across x = 0
atoms = [(-1.0 + 0.5 * k, 0.5, R - 1e-6, Q0) for k in range(3)]
atoms += [(0.1, -0.5, R - 1e-6 + k * (2 * R - 1e-6), Q0) for k in range(4)]
atoms += [(0.1 - k * (2 * R - 1e-6), -0.5, R - 1e-6, Q0) for k in (1, 2)]
extra = "group thrown id 1 2 3\nvelocity thrown set 0.8 0.3 0\n"
for method in ("split", "etm"):
    rows = scene("slide_" + method, BALL, atoms, "0.5 0.5 method %s" % method, 300,
                 extra=extra)
    audit("sliding spheres and a column (%s)" % method, rows,
          ["kick", "resting" if method == "split" else "wall"])
    # on 2 ranks the row crosses the ranks' boundary (x = 0): its island spans them and is
    # solved on one (the host books its work); the values are the same sums
    rows2 = scene("slide2_" + method, BALL, atoms, "0.5 0.5 method %s" % method, 300,
                  extra=extra, np=2)
    check(rows2 and max(r["f_imp[3]"] for r in rows2) > 0, "no island spans the ranks")
    audit("sliding spheres and a column (%s), 2 ranks" % method, rows2,
          ["kick", "resting" if method == "split" else "wall"])
    if rows and len(rows2) == len(rows):
        diff = max(abs(a["f_imp[%d]" % k] - b["f_imp[%d]" % k])
                   / max(a["f_imp[9]"], abs(a["f_imp[36]"]), 1e-300)
                   for a, b in zip(rows, rows2) for k in list(TERMS.values()) + [43])
        check(diff <= 1e-12, "%s: the audit's values differ on 1 and 2 ranks by %.3g"
              % (method, diff))

# boxes (principal moments all different) dropped tilted and spinning onto the floor (their
# drift term stays below 1e-9 of the step's energy: the spinning box below has it larger)
c, s = 0.9238795325112867, 0.3826834323650898  # 45 degrees about an axis
atoms = [(-0.6, 0.0, 0.35, (c, s, 0, 0)), (0.0, 0.6, 0.4, (c, 0, s, 0)),
         (0.6, 0.0, 0.45, (c, 0.6 * s, 0.8 * s, 0))]
extra = "velocity all set 0.2 0 0\nset group all omega 3 -2 5\n"
for method in ("split", "etm"):
    rows = scene("boxes_" + method, BOX, atoms, "0.5 0.5 damping 0.2 method %s" % method,
                 600, extra=extra)
    audit("tumbling boxes (%s)" % method, rows,
          ["kick", "etm", "damping"] + (["resting"] if method == "split" else ["wall"]))

# a box spinning about no principal axis in free flight (about 0.1 rad per step): the drift's
# turn changes its kinetic energy by the midpoint's truncation error, booked
rows = scene("spin", BOX, [(0.0, 0.0, 2.5, (c, 0.6 * s, 0.8 * s, 0))], "0.5 0.5", 100,
             dt=2e-3, extra="set group all omega 20 -35 50\n")
audit("spinning box", rows, ["kick", "drift"])

# a sphere sliding to a stop and a column of three settling, asleep (sleep 0.5 0.02: slow
# below 0.5 for 20 steps) while still moving: the energy they had is sleeping's
atoms = [(-1.0, 0.5, R - 1e-6, Q0)] + [(0.0, 0.0, R + 0.01 + k * (2 * R - 1e-6), Q0)
                                       for k in range(3)]
rows = scene("sleep", BALL, atoms, "0.5 0.5 sleep 0.5 0.02", 200,
             extra="group thrown id 1\nvelocity thrown set 0.45 0 0\n")
audit("grains falling asleep", rows, ["kick", "resting", "sleep"])
if rows:
    check(rows[-1]["f_imp[9]"] == 0.0, "the column is not asleep: KE %g" % rows[-1]["f_imp[9]"])

# the ball guard: a sphere (radius 0.3) thrown at 3 into a free net of 81 balls (radius
# 0.1, no gravity), on 1 and 2 ranks (the balls' works summed over their owners)
NET = net_scene() + """velocity grains set 0 0 -3
group moving union grains net_free
fix imp moving impulse/lsdem 0.5 0.3 rest 0.05 balls net damping 1
timestep 0.01
thermo_style custom step {columns} f_imp[34]
thermo_modify norm no format float %.17g
thermo 1
run 60
"""
for np in (1, 2):
    _, log = run_lmp(NET.format(columns=COLUMNS), np=np,
                     cwd=os.path.abspath("net%d" % np))
    rows = thermo(log)
    audit("grain into a net, %d rank%s" % (np, "s" if np > 1 else ""), rows,
          ["kick", "ball", "etm", "damping"])
    check(rows and sum(r["f_imp[34]"] for r in rows) > 0, "the ball guard never acted")
finish()
