"""Extreme cases end in a stable run or a clear error naming the grain -- never a silent
blow-up (issue: mass ratio 1000, a grain squeezed between two walls, a grain created inside
another, also wholly inside a lower-ID grain in mode oneway, which tests only its nodes; a
fast grain that would pass through a wall between two steps). 'Stable' is checked against
physics, not just a finished run: force balance, ordering of the grains, finite energies."""
import math
import os
import re

import contact_decks as cd
from lsdemtest import check, finish, near, run_lmp, shape_tool, thermo

R, H, NODES = 0.5, 0.05, 200
lib = cd.sphere_library("ball.lslib", R, H, NODES)
cube = cd.box_library("cube.lslib", 0.5, H, NODES)
KN, G = 2.0e4, 1.0
VOL = 4.0 / 3.0 * math.pi * R ** 3


def finite_thermo(log, what):
    rows = thermo(log)
    check(rows and all(all(math.isfinite(v) for v in r.values()) for r in rows),
          "%s: thermo has non-finite values or is empty" % what)
    return rows


# ---- 1. mass ratio 1000: a heavy cube resting on a light cube on the floor ---------------
# dt = 0.02 sqrt(m_light / kn): the light grain, squeezed face to face (~60 nodes on each
# face), sets the time step. At rest the floor carries the total weight and the heavy cube
# stays on top of the light one.
light, heavy = 1.0, 1000.0
m_light = light * 1.0
dt = 0.02 * math.sqrt(m_light / KN)
cd.write_data("mass.data", (-3, 3, -3, 3, 0, 6),
              [cd.Grain((0, 0, 0.5 + 0.002), density=light),
               cd.Grain((0.05, 0, 1.5 + 0.01), density=heavy)])
rc, log = run_lmp(cd.head(cube, "mass.data") + """
pair_style lsdem mode twoway
pair_coeff * * %g %g 0.5 cn 1.0
fix floor all wall/lsdem plane 0 0 0 0 0 1 %g %g 0.5 cn 1.0
fix g all gravity %g vector 0 0 -1
fix nve all nve/lsdem damping 5.0
variable z1 equal z[1]
variable z2 equal z[2]
timestep %.10g
thermo_style custom step ke f_floor[3] v_z1 v_z2
%s
thermo 2000
run 20000
""" % (KN, 0.9 * KN, KN, 0.9 * KN, G, dt, cd.THERMO_FULL), log="mass.log")
check(rc == 0, "mass ratio 1000: the run must finish (rc %d)" % rc)
rows = finite_thermo(log, "mass ratio 1000")
if rows:
    last = rows[-1]
    weight = (light + heavy) * 1.0 * G
    near(-last["f_floor[3]"], weight, rtol=0.01, msg="mass ratio 1000: floor carries the weight")
    check(last["v_z2"] > last["v_z1"] + 0.9, "mass ratio 1000: heavy cube stays on the light "
          "one (z %g vs %g)" % (last["v_z2"], last["v_z1"]))
    check(last["v_z1"] > 0.45, "mass ratio 1000: light cube not pushed through the floor "
          "(z %g)" % last["v_z1"])

# ---- 2. a cube squeezed between two closing walls ---------------------------------------
# The walls close from a gap of 1.2 to 0.96 (4% of the cube's side) and stop: the cube is
# held, the two walls carry equal and opposite forces of the size the penetrations imply.
cd.write_data("squeeze.data", (-3, 3, -3, 3, -2, 2), [cd.Grain((0, 0, 0))])
dts = 0.02 * math.sqrt(8 * 0.125 / KN)
steps = 6000
vwall = 0.12 / (steps * dts)
rc, log = run_lmp(cd.head(cube, "squeeze.data") + """
pair_style lsdem
pair_coeff * * %g %g 0.3
variable v equal "%.10g * (step < %d)"
variable vn equal -v_v
fix lo all wall/lsdem plane 0 0 -0.6 0 0 1 %g %g 0.3 cn 2.0 velocity 0 0 v_v
fix hi all wall/lsdem plane 0 0 0.6 0 0 -1 %g %g 0.3 cn 2.0 velocity 0 0 v_vn
fix nve all nve/lsdem damping 2.0
timestep %.10g
thermo_style custom step ke f_lo[3] f_hi[3]
%s
thermo 1000
run %d
""" % (KN, 0.9 * KN, vwall, steps, KN, 0.9 * KN, KN, 0.9 * KN, dts, cd.THERMO_FULL, 2 * steps),
    log="squeeze.log", expect_fail=True)
if rc == 0:
    rows = finite_thermo(log, "squeeze")
    last = rows[-1] if rows else None
    if last:
        near(last["f_lo[3]"], -last["f_hi[3]"], rtol=1e-3, msg="squeeze: walls balance")
        check(last["f_hi[3]"] > 0, "squeeze: the cube pushes the upper wall up (%g)" % last["f_hi[3]"])
else:
    check("grain 1" in log and "unstable" in log, "squeeze: a failure must name grain 1")

# ---- 3. a grain created inside another ----------------------------------------------------
# Two balls whose centres are 0.4 apart (radius 0.5: nodes 80% of the radius deep): setup warns with both ids and the depth; the run then
# either pushes them apart (finite energies, separated) or stops naming the grain.
cd.write_data("inside.data", (-4, 4, -4, 4, -4, 4),
              [cd.Grain((0, 0, 0)), cd.Grain((0.4, 0.02, 0.0))])
rc, log = run_lmp(cd.head(lib, "inside.data") + """
pair_style lsdem mode twoway
pair_coeff * * %g %g 0.5
fix nve all nve/lsdem damping 1.0
timestep %.10g
thermo_style custom step ke
%s
thermo 500
run 3000
""" % (KN, 0.9 * KN, 0.05 * math.sqrt(VOL / KN), cd.THERMO_FULL), log="inside.log",
    expect_fail=True)
check("grains 1 and 2" in log or "grains 2 and 1" in log,
      "inside: the setup warning names both grains")
if rc == 0:
    finite_thermo(log, "inside")
else:
    check("unstable" in log and ("grain 1" in log or "grain 2" in log),
          "inside: a failure must name the grain and say it became unstable")
# ---- 4. a small cube wholly inside a ball of lower ID, mode oneway -----------------------
# With the report's master rule (master id) the ball's nodes are all outside the cube, so
# the one-way test (the ball's nodes in the cube) finds nothing and no force acts; setup
# still warns, naming both grains and the mode, from the reverse test (the cube's nodes
# ~0.3 deep in the ball). The default (master nodes: the small cube's nodes test the ball)
# and mode twoway push it out.
cd.box_library("small.lslib", 0.12, 0.01, 60)
if not os.path.exists("ball_small.lslib"):
    shape_tool("merge", "ball_small.lslib", lib, "small.lslib")
cd.write_data("embedded.data", (-4, 4, -4, 4, -4, 4),
              [cd.Grain((0, 0, 0)), cd.Grain((0.05, 0.0, 0.0), shape=2)])
for mode in ("oneway master id", "oneway", "twoway"):
    rc, log = run_lmp(cd.head("ball_small.lslib", "embedded.data") + """
pair_style lsdem mode %s
pair_coeff * * %g %g 0.5
compute pe all pair lsdem
fix nve all nve/lsdem
timestep %.10g
thermo_style custom step ke c_pe[4]
run 0
""" % (mode, KN, 0.9 * KN, 0.01 * math.sqrt(VOL / KN)), cwd=os.path.abspath("embedded_" + mode.replace(" ", "_")))
    warned = [l for l in log.splitlines()
              if "deepest: grains 1 and 2" in l or "deepest: grains 2 and 1" in l]
    check(len(warned) == 1, "embedded, %s: setup warning names grains 1 and 2: %s"
          % (mode, log[-800:]))
    rows = thermo(log)
    pen = rows[0]["c_pe[4]"] if rows else -1
    if mode == "oneway master id":
        check(warned and "mode oneway does not test" in warned[0] and pen == 0,
              "oneway: no penetrating node found (%s), and the warning says why" % pen)
    else:
        check(warned and "Large repulsive forces" in warned[0] and pen > 0,
              "%s: the cube's nodes are found (%s penetrating)" % (mode, pen))

# ---- 5. a fast grain oblique to a plane wall on the box face (#22.3) ----------------------
# Moving 0.45 of its bounding radius per step (under the runaway limit of 0.5) towards a
# soft wall at x = -3 (the box face), it enters the wall faster than the contact can stop
# it: its centre passes the wall's surface at the next step, and LAMMPS deleted it there
# with only "Lost atoms". The wall stops the run first, naming grain, wall, step and the
# time step that would hold it (0.1 R / |v_n|); so does fix wall/lsdem/omp on 2 threads,
# which finds it in a thread's lane. The same grain against a stiff wall bounces off (no
# false alarm).
dt = 1e-3
r_cube = 0.5 * math.sqrt(3.0)
speed = 0.45 * r_cube / dt
vx, vy = -speed * math.cos(0.5), speed * math.sin(0.5)
cd.write_data("fast.data", (-3, 3, -3, 3, -3, 3),
              [cd.Grain((-3 + r_cube + 0.5 * speed * dt * math.cos(0.5), 0.0, 0.0),
                        v=(vx, vy, 0.0))])
for kn_wall, name, args in ((50.0, "fast_soft", None), (2.0e4, "fast_stiff", None),
                            (50.0, "fast_soft_omp2", ["-sf", "omp", "-pk", "omp", "2"])):
    rc, log = run_lmp(cd.head(cube, "fast.data", boundary="f f f") + """
pair_style lsdem
pair_coeff * * %g %g 0.5
fix side all wall/lsdem plane -3 0 0 1 0 0 %g %g 0.0
fix nve all nve/lsdem
variable xc equal x[1]
thermo_style custom step v_xc
thermo 1
timestep %g
run 8
""" % (KN, KN, kn_wall, kn_wall, dt), cwd=os.path.abspath(name),
                      expect_fail=name.startswith("fast_soft"), args=args)
    if name == "fast_stiff":
        rows = thermo(log)
        check(rc == 0 and rows and rows[-1]["v_xc"] > rows[-2]["v_xc"] > -3 + r_cube,
              "fast grain, stiff wall: it should bounce back, got rc %d:\n%s" % (rc, log[-600:]))
        continue
    m = re.search(r"fix wall/lsdem side: grain 1 would go through the wall at step (\d+): its "
                  r"centre is \S+ in front of the wall's surface and it moves at (\S+) towards "
                  r"the wall .* its radius (\S+) through .* a time step below (\S+) would", log)
    check(rc != 0 and m is not None and "Lost atoms" not in log,
          "%s: expected the wall's stop naming grain 1 and wall side, got:\n%s"
          % (name, log[-1200:]))
    if m:
        near(float(m.group(4)), 0.1 * float(m.group(3)) / float(m.group(2)), rtol=1e-5,
             msg="fast grain: the time step that holds it, 0.1 R / |v_n|")
finish()
