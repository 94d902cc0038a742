"""pair_style lsdem + fix wall/lsdem on 1, 2 and 4 ranks give the serial answer.

1. A small frictional settling deck (spheres and cubes, periodic in x and y, a floor
   wall): kinetic energy and the force on the floor after 200 steps agree with the
   serial run to 1e-8 relative. Only the order in which ghost forces are summed differs
   between rank counts, so differences must stay at round-off level. The same holds
   for a serial run whose atoms are re-sorted mid-run (history lists move between local
   slots).
2. Friction history across a processor boundary: a stack of two cubes slides down an
   incline through the boundary between two ranks while the top cube sticks to the
   bottom one (grain-grain shear springs) and both slide on the wall (grain-wall
   springs). Migrating grains carry their history: the 2-rank run reproduces the
   serial trajectory. Losing a spring at migration would jolt the stack."""
import math
import os
import random

from lsdemtest import run_lmp, thermo, check, near, finish, shape_tool
from contact_decks import (Grain, sphere_library, box_library, write_data, head,
                           quat_axis_angle, THERMO_FULL)

sphere_library("sphere.lslib", 0.5, 0.05, 300)
box_library("cube.lslib", 0.5, 0.05, 600)
if not os.path.exists("mixed.lslib"):
    shape_tool("merge", "mixed.lslib", "sphere.lslib", "cube.lslib")   # shape 1 sphere, 2 cube
lib = "mixed.lslib"


def run_ranks(name, deck, np):
    rc, log = run_lmp(deck, np=np, cwd=os.path.abspath("%s-np%d" % (name, np)))
    return thermo(log)


# ---- 1. settling deck ------------------------------------------------------------
rng = random.Random(7)
grains = []
SP = 1.1
for k in range(2):
    for j in range(4):
        for i in range(4):
            cube = (i + j + k) % 2
            axis = (rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))
            # the bottom layer rests on the floor (cubes face down), the top one tumbles
            q = quat_axis_angle(axis, rng.uniform(-0.15, 0.15)) if cube and k else (1, 0, 0, 0)
            v = tuple(rng.uniform(-1, 1) * (0.3 if k == 0 and d == 2 else 1) for d in range(3))
            w = tuple(rng.uniform(-2, 2) for _ in range(3))
            grains.append(Grain((SP * (i + 0.5), SP * (j + 0.5), 0.499 + SP * k), q=q, v=v, w=w,
                                shape=2 if cube else 1))
write_data("settle.data", (0, 4 * SP, 0, 4 * SP, 0, 6), grains)

settle = head(lib, "settle.data", boundary="p p f", extra="processors * * 1") + """
pair_style lsdem
pair_coeff * * 2000 2000 0.5 cn 2.0
fix grav all gravity 1.0 vector 0 0 -1
fix 1 all nve/lsdem
fix floor all wall/lsdem plane 0 0 0 0 0 1 2000 2000 0.5 cn 2.0
compute er all erotate/lsdem
compute w all pair lsdem
thermo_style custom step ke c_er f_floor[1] f_floor[2] f_floor[3] c_w[2] c_w[4]
%s
thermo 50
timestep 5e-4
run 200
""" % THERMO_FULL

# atom sorting moves grains (and their history lists) between local slots: the same
# grains (same IDs) listed in shuffled order, run unsorted for 100 steps, then sorted
# spatially at the setup of a second run, with all contact histories in place
order = list(range(len(grains)))
rng.shuffle(order)
write_data("shuffled.data", (0, 4 * SP, 0, 4 * SP, 0, 6), [grains[k] for k in order],
           ids=[k + 1 for k in order])
sorted_deck = settle.replace("read_data", "atom_modify sort 0 0.0\nread_data").replace(
    os.path.abspath("settle.data"), os.path.abspath("shuffled.data")).replace(
    "run 200", "run 100\natom_modify sort 1000 0.6\nrun 100")
ref = None
for np, deck in ((1, settle), (2, settle), (4, settle), (1, sorted_deck)):
    name = "settle" if deck is settle else "sorted"
    rows = run_ranks(name, deck, np)
    if not check(len(rows) == (5 if deck is settle else 3),
                 "%s np=%d: thermo output missing" % (name, np)):
        continue
    last = rows[-1]
    if ref is None:
        ref = last
        check(ref["c_w[2]"] >= 5, "settle: only %d contacts, the deck tests little"
              % ref["c_w[2]"])
        check(ref["f_floor[3]"] < 0, "settle: nothing touches the floor")
        continue
    for key in ("KinEng", "c_er", "f_floor[3]"):
        near(last[key], ref[key], rtol=1e-8, msg="%s np=%d vs settle np=1: %s" % (name, np, key))
    for key in ("f_floor[1]", "f_floor[2]"):
        near(last[key], ref[key], atol=1e-8 * abs(ref["f_floor[3]"]),
             msg="%s np=%d vs settle np=1: %s" % (name, np, key))
    check(last["c_w[2]"] == ref["c_w[2]"], "%s np=%d: %d contacts, serial %d"
          % (name, np, last["c_w[2]"], ref["c_w[2]"]))

# ---- 2. friction history crossing a processor boundary -----------------------------
TH = math.radians(25.0)
n = (-math.sin(TH), 0.0, math.cos(TH))
q = quat_axis_angle((0, 1, 0), -TH)
# start uphill of x = 0 (the boundary between the two ranks) and slide down through it
start = 0.5
base = (start * math.cos(TH), 0.0, start * math.sin(TH))
stack = [Grain(tuple(base[d] + (0.5 + 1e-4) * n[d] for d in range(3)), q=q, shape=2),
         Grain(tuple(base[d] + (1.5 + 1e-4) * n[d] for d in range(3)), q=q, shape=2)]
write_data("stack.data", (-4, 4, -2, 2, -3, 5), stack)
incline = head(lib, "stack.data", boundary="f f f", extra="processors * 1 1") + """
pair_style lsdem
pair_coeff * * 500 500 0.9 cn 2.0
neigh_modify every 1 delay 0
fix grav all gravity 1.0 vector 0 0 -1
fix 1 all nve/lsdem
fix w all wall/lsdem plane 0 0 0 %r %r %r 500 500 0.2 cn 2.0
variable x1 equal x[1]
variable x2 equal x[2]
variable z2 equal z[2]
variable vx2 equal vx[2]
thermo_style custom step v_x1 v_x2 v_z2 v_vx2 f_w[1] f_w[3]
%s
thermo 200
timestep 1e-3
run 3000
""" % (n[0], n[1], n[2], THERMO_FULL)

serial = run_ranks("stack", incline, 1)
par = run_ranks("stack", incline, 2)
if check(len(serial) > 5 and len(serial) == len(par), "stack: thermo output missing"):
    check(serial[0]["v_x1"] > 0 > serial[-1]["v_x1"],
          "stack: the stack did not cross x = 0 (from %g to %g)"
          % (serial[0]["v_x1"], serial[-1]["v_x1"]))
    # the top cube rides on the bottom one: their separation barely changes
    d0 = serial[0]["v_x2"] - serial[0]["v_x1"]
    d1 = serial[-1]["v_x2"] - serial[-1]["v_x1"]
    check(abs(d1 - d0) < 0.01, "stack: the top cube slid on the bottom one (%g)" % (d1 - d0))
    for s, p in zip(serial, par):
        for key in ("v_x1", "v_x2", "v_z2", "v_vx2", "f_w[1]", "f_w[3]"):
            near(p[key], s[key], rtol=1e-9, atol=1e-12,
                 msg="stack 2 ranks vs serial, step %d: %s" % (s["Step"], key))

finish()
