"""fix wall/lsdem cylinder: a container. A level-set sphere (radius 0.5) inside a cylinder
of radius 2 falls under gravity perpendicular to the axis and comes to rest against the
wall: its centre ends 2 - 0.5 = 1.5 from the axis, on the gravity side, and the wall
carries its weight (the force on the wall along gravity is m g). Checked for axis z (gravity +x) and axis x (gravity -z, the two
centre coordinates are y z)."""
import math
import os

from lsdemtest import run_lmp, thermo, check, near, finish
from contact_decks import Grain, sphere_library, write_data, head, THERMO_FULL

lib = sphere_library("sphere.lslib", 0.5, 0.05, 400)
MASS = 4.0 / 3.0 * math.pi * 0.5 ** 3

for name, axis, centre, start, gvec in (
        ("axisz", "z", (0.5, -0.3), (0.5, -0.3, 0.0), (1, 0, 0)),
        ("axisx", "x", (0.2, 0.4), (0.0, 0.2, 0.4), (0, 0, -1))):
    # start 0.1 short of the rest position, at rest
    x0 = tuple(s + 1.4 * g for s, g in zip(start, gvec))
    write_data(name + ".data", (-4, 4, -4, 4, -4, 4), [Grain(x0)])
    deck = head(lib, name + ".data", boundary="f f f") + """
pair_style zero 2.0
pair_coeff * *
fix grav all gravity 1.0 vector %d %d %d
fix 1 all nve/lsdem damping 5.0
fix w all wall/lsdem cylinder %r %r 2.0 1000 1000 0.3 cn 1.0 axis %s
variable x equal x[1]
variable y equal y[1]
variable z equal z[1]
variable speed equal sqrt(vx[1]^2+vy[1]^2+vz[1]^2)
thermo_style custom step v_speed v_x v_y v_z f_w[1] f_w[2] f_w[3]
%s
thermo 1000
timestep 5e-4
run 8000
""" % (gvec + (centre[0], centre[1], axis, THERMO_FULL))
    rc, log = run_lmp(deck, cwd=os.path.abspath(name))
    rows = thermo(log)
    if not check(len(rows) > 3, "%s: thermo output missing" % name):
        continue
    last = rows[-1]
    # a faceted sphere may still roll slowly along the wall (rolling is free); the radial
    # balance is what the wall decides
    check(last["v_speed"] < 0.01, "%s: the sphere did not settle (speed %g)"
          % (name, last["v_speed"]))
    pos = (last["v_x"], last["v_y"], last["v_z"])
    ax = "xyz".index(axis)
    c = [s for s in start]
    rel = [p - q for p, q in zip(pos, c)]
    rel[ax] = 0.0
    near(math.sqrt(sum(r * r for r in rel)), 1.5, atol=0.01,
         msg="%s: distance of the sphere centre from the axis" % name)
    along = sum(r * g for r, g in zip(rel, gvec))
    near(along, 1.5, atol=0.02, msg="%s: the sphere rests on the gravity side" % name)
    fw = [last["f_w[%d]" % (d + 1)] for d in range(3)]
    near(sum(f * g for f, g in zip(fw, gvec)), MASS, rtol=0.01,
         msg="%s: the wall carries the weight" % name)

finish()
