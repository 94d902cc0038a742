"""fix wall/lsdem keeps the grains that may touch it from one reneighbouring to the next
(found with the neighbour skin as margin), instead of testing every grain at every step.
Second code path: the same deck with neighbour lists rebuilt at every step
(`neigh_modify check no`), where the candidates are found afresh at every step without a
margin. The two runs must give the same wall forces and kinetic energy at every step.
Two scenes: cubes flying at a plane and a cylinder wall (crossing the skin between
reneighbourings) and settling on a floor with friction; and cubes at rest (nothing
reneighbours) under a lid that comes down fast from far above, so that only the wall's
own motion since the list was made can renew it. A third scene runs with lists built once
per run (`neigh_modify once yes`): nothing then bounds how far a grain moves between
builds, so the wall must find its candidates at every step; a lone cube flies at it.
A fourth (away and back): a ball moved by fix move half a skin down and a skin up (never
more than half a skin from where the lists were built: LAMMPS does not rebuild them) while
a lid comes down, fast enough to renew its candidates between the two: the lid must still
find the ball (with one skin of margin at that renewal it did not, and the ball went 0.078
into the lid without a force)."""
import math
import os
import re

from lsdemtest import run_lmp, thermo, check, near, finish
from contact_decks import Grain, box_library, quat_axis_angle, write_data, head, THERMO_FULL
from impulse_decks import library

lib = box_library("cube.lslib", 0.5, 0.05, 600)
SCENES = {
    # cubes flying at a plane wall and at a cylinder wall (each crosses the skin between
    # reneighbourings), sliding and dropping on a floor with friction
    "flying": ([
        Grain((0.0, 0.0, -4.45)),
        Grain((1.5, 0.0, -4.45), v=(0.3, 0.0, 0.0)),
        Grain((-1.5, 1.0, -4.3), q=quat_axis_angle((1, 1, 0), 0.4)),
        # corner first (a corner reaches the bounding sphere: no slack in the screening)
        Grain((2.0, 0.0, 0.0), q=quat_axis_angle((0, 1, -1), math.acos(1 / math.sqrt(3))),
              v=(6.0, 0.0, 0.0)),
        Grain((-2.0, 2.0, 1.0), q=quat_axis_angle((-1, -1, 2), math.pi / 2), v=(-2.5, 2.5, 0.0)),
    ], """fix side all wall/lsdem plane 4 0 0 -1 0 0 2000 1500 0.4
fix can all wall/lsdem cylinder 0 0 5.0 2000 1500 0.4 axis z
""", ("f_floor[3]", "f_side[1]", "f_can[1]"), "check yes"),
    # cubes at rest on the floor (no reneighbouring) and a lid coming down fast from far
    # above, stopped just after it touches: only the lid's own motion renews its list
    "lid": ([
        Grain((0.0, 0.0, -4.45)),
        Grain((2.0, 1.0, -4.45), q=quat_axis_angle((0, 0, 1), 0.3)),
    ], """variable vz equal -5.0*(step<596)
fix lid all wall/lsdem plane 0 0 -1.0 0 0 -1 2000 1500 0.4 velocity 0 0 v_vz
""", ("f_floor[3]", "f_lid[3]"), "check yes"),
    # a lone cube flying at a wall with lists built once per run (neigh_modify once yes):
    # LAMMPS never rebuilds them, so the wall may keep no candidates across steps
    "once": ([
        Grain((2.0, 0.0, 0.0), q=quat_axis_angle((0, 1, -1), math.acos(1 / math.sqrt(3))),
              v=(6.0, 0.0, 0.0)),
    ], """fix side all wall/lsdem plane 4 0 0 -1 0 0 2000 1500 0.4
""", ("f_side[1]",), "check yes once yes"),
}

DECK = """
pair_style lsdem
pair_coeff * * 2000 1500 0.5
neighbor 0.3 bin
neigh_modify delay 0 every 1 %s
fix floor all wall/lsdem plane 0 0 -5 0 0 1 2000 1500 0.6
%s
fix grav all gravity 1.0 vector 0 0 -1
fix 1 all nve/lsdem
compute ke all ke
thermo_style custom step c_ke %s
%s
thermo 1
timestep 1e-3
run 650
"""

for name, (grains, walls, cols, kept_neigh) in SCENES.items():
    write_data(name + ".data", (-6, 6, -6, 6, -6, 6), grains)
    runs = {}
    for mode, neigh in (("yes", kept_neigh), ("no", "check no")):
        deck = head(lib, name + ".data", boundary="f f f", extra="atom_modify sort 0 0.0") + \
            DECK % (neigh, walls, " ".join(cols), THERMO_FULL)
        rc, log = run_lmp(deck, cwd=os.path.abspath(name + "_" + mode))
        builds = re.search(r"Neighbor list builds = (\d+)", log)
        runs[mode] = (thermo(log), int(builds.group(1)) if builds else -1)
    kept, fresh = runs["yes"][0], runs["no"][0]
    if not check(len(kept) == 651 and len(fresh) == 651, "%s: thermo rows: %d and %d, want 651"
                 % (name, len(kept), len(fresh))):
        continue
    # the lists were kept for many steps in one run and made at every step in the other
    check(runs["yes"][1] < 200 and runs["no"][1] >= 650,
          "%s: neighbour list builds: %d (kept), %d (check no)"
          % (name, runs["yes"][1], runs["no"][1]))
    # every wall was touched, so each one's candidates were put to the test
    for col in cols:
        check(any(abs(r[col]) > 0.0 for r in kept), "%s: %s never non-zero" % (name, col))
    for a, b in zip(kept, fresh):
        same = [near(a[col], b[col], rtol=1e-12, atol=1e-12,
                     msg="%s, step %d: %s differs with kept candidates" % (name, a["Step"], col))
                for col in a]
        if not all(same):
            break

AWAY_AND_BACK = """
pair_style lsdem
pair_coeff * * 2000 1500 0.5
neighbor 0.2 bin
neigh_modify delay 0 every 1 %s
# the ball (radius 0.5, its bounding sphere): down 0.095 in 100 steps, then up 0.19 in 100
# steps; the lid 0.216 above its top: down 0.101 in 100 steps (its candidates renewed), then 0.098
variable s equal step
variable zg equal "(v_s<=100)*(-0.00095*v_s) + (v_s>100)*(-0.095+0.0019*(v_s-100))"
variable vg equal "(v_s<=100)*(-0.95) + (v_s>100)*1.9"
variable vw equal "(v_s<100)*(-1.01) + (v_s>=100)*(-0.98)"
fix mv all move variable NULL NULL v_zg NULL NULL v_vg
fix lid all wall/lsdem plane 0 0 0.716 0 0 -1 2000 0 0 velocity 0 0 v_vw
variable fz equal fz[1]
thermo_style custom step v_fz f_lid[3]
%s
thermo 1
timestep 1e-3
run 200
"""
write_data("away.data", (-3, 3, -3, 3, -3, 3), [Grain((0.0, 0.0, 0.0))])
ball = library("ball.lslib", "sphere", 0.5, nodes=200, analytic=True)
runs = {}
for mode, neigh in (("yes", "check yes"), ("no", "check no")):
    deck = head(ball, "away.data", boundary="f f f") + AWAY_AND_BACK % (neigh, THERMO_FULL)
    rc, log = run_lmp(deck, cwd=os.path.abspath("away_" + mode))
    builds = re.search(r"Neighbor list builds = (\d+)", log)
    runs[mode] = (thermo(log), int(builds.group(1)) if builds else -1)
kept, fresh = runs["yes"][0], runs["no"][0]
if check(len(kept) == 201 and len(fresh) == 201, "away and back: thermo rows %d and %d"
         % (len(kept), len(fresh))):
    check(runs["yes"][1] == 0, "away and back: the lists were rebuilt (%d)" % runs["yes"][1])
    check(fresh[-1]["v_fz"] < -100.0, "away and back: the lid does not press the ball (%g)"
          % fresh[-1]["v_fz"])
    for a, b in zip(kept, fresh):
        if not near(a["v_fz"], b["v_fz"], rtol=1e-12, atol=1e-12,
                    msg="away and back, step %d: the ball's force with kept candidates"
                    % a["Step"]):
            break
finish()
