"""fix wall/lsdem: a level-set cube on an inclined plane under gravity.

Coulomb friction (per node, report eq 2.10) gives the textbook block on an incline:
  tan(theta) < mu: the cube stays at rest, and the wall carries its whole weight;
  tan(theta) > mu: it slides with a = g (sin(theta) - mu cos(theta)) (within 2%),
  and with mu = 0 with a = g sin(theta); the same with the traction law and with a
  node stride (the Coulomb limit does not depend on how the normal force is spread)."""
import math
import os

from lsdemtest import run_lmp, thermo, check, near, finish
from contact_decks import Grain, box_library, write_data, head, quat_axis_angle, THERMO_FULL

HALF = 0.5           # cube half-side; density 1: mass 1
G = 1.0
lib = box_library("cube.lslib", HALF, 0.05, 600)


def incline(name, theta_deg, mu, wall_law="100 100 %(mu)r cn 1.0", t_end=2.0, dt=5e-4):
    """Run the cube on a plane tilted by theta about y; return thermo rows."""
    th = math.radians(theta_deg)
    n = (-math.sin(th), 0.0, math.cos(th))          # plane normal, towards the cube
    # the cube's bottom face on the plane: body z -> n (rotation by -theta about y)
    q = quat_axis_angle((0, 1, 0), -th)
    x = tuple((HALF + 1e-4) * c for c in n)
    write_data(name + ".data", (-20, 20, -5, 5, -20, 20), [Grain(x, q=q)])
    deck = head(lib, name + ".data", boundary="f f f") + """
pair_style zero 2.0
pair_coeff * *
fix grav all gravity %(g)r vector 0 0 -1
fix 1 all nve/lsdem
fix w all wall/lsdem plane 0 0 0 %(nx)r %(ny)r %(nz)r %(law)s
# downhill speed and distance (downhill = -(cos th, 0, sin th))
variable vs equal -(vx[1]*%(c)r+vz[1]*%(s)r)
variable xs equal -(x[1]*%(c)r+z[1]*%(s)r)
variable h equal x[1]*%(nx)r+z[1]*%(nz)r
thermo_style custom step time v_vs v_xs v_h f_w[1] f_w[2] f_w[3]
%(thermo)s
thermo 100
timestep %(dt)r
run %(steps)d
""" % dict(law=wall_law % dict(mu=mu), g=G, nx=n[0], ny=n[1], nz=n[2], mu=mu, c=math.cos(th), s=math.sin(th),
           thermo=THERMO_FULL, dt=dt, steps=int(round(t_end / dt)))
    rc, log = run_lmp(deck, cwd=os.path.abspath(name))
    return thermo(log)


def at_time(rows, t):
    return min(rows, key=lambda r: abs(r["Time"] - t))


# at rest below the friction angle: tan(20 deg) = 0.364 < 0.5
rows = incline("static", 20.0, 0.5)
if check(len(rows) > 10, "static: no thermo output"):
    last = rows[-1]
    check(abs(last["v_xs"] - rows[0]["v_xs"]) < 1e-3,
          "static: the cube crept %g down a slope it should stick to" % (last["v_xs"] - rows[0]["v_xs"]))
    check(abs(last["v_vs"]) < 1e-3, "static: the cube moves (v = %g)" % last["v_vs"])
    check(abs(last["v_h"] - HALF) < 0.01, "static: cube centre at height %g above the plane"
          % last["v_h"])
    near(last["f_w[3]"], -1.0 * G, rtol=0.01, msg="static: the wall carries the weight")
    near(last["f_w[1]"], 0.0, atol=0.01, msg="static: no net horizontal force on the wall")

# sliding above the friction angle, without friction, and with the other node laws:
# traction (600 nodes share the area 6: kn, ks per area = per-node values / 0.01) and a
# node stride of 2 (half the nodes, forces doubled)
for name, theta, mu, law in (
        ("slide", 30.0, 0.3, "100 100 %(mu)r cn 1.0"),
        ("frictionless", 30.0, 0.0, "100 100 %(mu)r cn 1.0"),
        ("traction", 30.0, 0.3, "1e4 1e4 %(mu)r cn 1.0 normal traction"),
        ("stride", 30.0, 0.3, "100 100 %(mu)r cn 0.5 stride 2")):
    rows = incline(name, theta, mu, law)
    if not check(len(rows) > 10, "%s: no thermo output" % name):
        continue
    th = math.radians(theta)
    expect = G * (math.sin(th) - mu * math.cos(th))
    r1, r2 = at_time(rows, 1.0), at_time(rows, 2.0)
    a = (r2["v_vs"] - r1["v_vs"]) / (r2["Time"] - r1["Time"])
    near(a, expect, rtol=0.02, msg="%s: acceleration down the slope" % name)
    check(abs(r2["v_h"] - HALF) < 0.01, "%s: the cube left the plane (height %g)"
          % (name, r2["v_h"]))

finish()
