"""compute stress/lsdem and the variable-velocity platen of fix wall/lsdem.

1. A static packing of 27 level-set grains (spheres and cubes) in a cell periodic in x and
   y, squeezed between a floor and a servo-controlled top platen (velocity from an
   equal-style variable) to a platen force F, then held until it is at rest. Independent
   expectation: the Love-Weber axial stress of the grains equals the platen force over the
   cell's cross-section, F / A, with V = A H (H = platen height above the floor); the same
   holds for the floor's force. Tolerance 1%: node contact points sit inside the walls by
   the penetration depth (~0.2% of H here). A missing or double-counted wall or pair
   contribution is off by 50% or more.
2. The packed state (restart) evaluated on 1 and 2 ranks: the stress vector agrees to
   1e-10 at once and to 1e-8 after 100 steps.
3. A platen whose velocity is a step-dependent variable ends where the integral of that
   velocity puts it.
4. A plane platen that leaves the whole box on its solid side is refused, naming the point
   and the range of n.p that cuts the box.
5. compute dilatancy/lsdem on prescribed strain histories (eq 3.10 by hand).
6. compute inertial/lsdem of one grain (eq 3.5 by hand from its mass and density): inf and no
   warning while the pressure is 0, then the formula, and one warning above LIMIT.
7. compute fabric/lsdem rotations: none flagged at rest (round-off alone), and of 27 grains
   the one spun at w about z for t is flagged, with mean and sd of the angles from w t.
8. compute fabric/lsdem long axes (per-atom columns 3-5) of three rods (boxes 1.2 x 0.6 x 0.3,
   turned by known quaternions): each is +-R(q) e_x, the body axis of the smallest moment, to
   1e-12, and the deviator 15/2 (<n n> - I/3) of the three equals the global c_fab[1-6].
"""
import math
import os
import random

from lsdemtest import run_lmp, thermo, check, near, finish, shape_tool
from contact_decks import Grain, write_data, sphere_library, box_library, quat_axis_angle, head

L = 4.0        # periodic cell side: A = L^2
TARGET = 16.0  # platen force: axial stress 1.0

sphere_library("s.lslib", 0.5, 0.05, 120)
box_library("b.lslib", 0.4, 0.05, 120)
if not os.path.exists("g.lslib"):
    shape_tool("merge", "g.lslib", "s.lslib", "b.lslib")

rng = random.Random(7)
grains = []
for k in range(3):
    for j in range(3):
        for i in range(3):
            x = (0.67 + 1.33 * i + rng.uniform(-0.1, 0.1),
                 0.67 + 1.33 * j + rng.uniform(-0.1, 0.1), 0.7 + 1.3 * k)
            q = quat_axis_angle((rng.random(), rng.random(), rng.random()), rng.uniform(0, 3))
            grains.append(Grain(x, q=q, shape=1 + (i + j + k) % 2))
write_data("pack.data", (0, L, 0, L, -1, 6), grains)

WALLS = """pair_style lsdem master id
pair_coeff * * 1000 900 0.3
neighbor 0.1 bin
fix bottom all wall/lsdem plane 0 0 0 0 0 1 1000 900 0.3
variable target equal %r
variable hold equal 1
variable e equal 0.05*(f_top[3]-v_target)
variable vz equal (1-v_hold)*(v_e*(abs(v_e)<=0.5)+0.5*(v_e>0.5)-0.5*(v_e<-0.5))
fix top all wall/lsdem plane 0 0 4.0 0 0 -1 1000 900 0.3 velocity 0 0 v_vz
fix nve all nve/lsdem damping 10
timestep 0.0005
variable V equal lx*ly*f_top[6]
compute s all stress/lsdem volume v_V wall bottom top
variable sA equal f_top[3]/(lx*ly)
variable sB equal -f_bottom[3]/(lx*ly)
thermo_style custom step ke f_top[3] f_top[6] v_sA v_sB c_s[*]
thermo_modify norm no format float %%.17g
""" % TARGET

# 1. settle under gravity, squeeze with the servo platen, hold until at rest
deck = head("g.lslib", "pack.data", boundary="p p f") + WALLS + """
thermo 2000
fix g all gravity 2.0 vector 0 0 -1
run 8000
unfix g
variable hold equal 0
run 20000
variable hold equal 1
run 10000
write_restart packed.restart
"""
rc, log = run_lmp(deck, cwd=os.path.abspath("pack"))
rows = thermo(log)
if check(len(rows) > 2, "packing: no thermo output"):
    last = rows[-1]
    check(last["KinEng"] < 1e-12, "packing not at rest: KE %g" % last["KinEng"])
    near(last["f_top[3]"], TARGET, rtol=0.01, msg="the servo brought the platen force to target")
    near(last["v_sB"], last["v_sA"], rtol=1e-6, msg="floor and platen carry the same force")
    near(last["c_s[3]"], last["v_sA"], rtol=0.01, msg="Love-Weber szz vs platen force / area")
    check(abs(last["c_s[1]"]) < 0.05 * last["c_s[3]"] and abs(last["c_s[4]"]) < 0.05 *
          last["c_s[3]"], "lateral and shear stresses are small without lateral walls")
    near(last["c_s[7]"], (last["c_s[1]"] + last["c_s[2]"] + last["c_s[3]"]) / 3, rtol=1e-12,
         msg="p = tr/3")
    s1, s3 = last["c_s[10]"], last["c_s[11]"]
    near(last["c_s[9]"], math.degrees(math.asin(min(1.0, (s1 - s3) / (s1 + s3)))), atol=1e-9,
         msg="phi_mob from the principal stresses")

# 2. the packed state on 1 and 2 ranks
deck2 = """units lj
atom_style lsdem library %s
atom_modify map array
newton on
comm_modify vel yes
read_restart %s
""" % (os.path.abspath("g.lslib"), os.path.abspath("pack/packed.restart")) + WALLS.replace(
    "fix bottom", "fix bottom").replace("variable hold equal 1", "variable hold equal 1") + """
thermo 100
run 100
"""
results = {}
for np in (1, 2):
    rc, log = run_lmp(deck2, np=np, cwd=os.path.abspath("np%d" % np))
    results[np] = thermo(log)
if check(len(results[1]) == 2 and len(results[2]) == 2, "ranks: thermo rows missing"):
    for k in range(2):
        for c in range(1, 12):
            key = "c_s[%d]" % c
            a, b = results[1][k][key], results[2][k][key]
            near(b, a, atol=(1e-10 if k == 0 else 1e-8) * (1 + abs(a)),
                 msg="%s at step %d, 1 vs 2 ranks" % (key, results[1][k]["Step"]))
    if results[1]:
        near(results[1][0]["c_s[3]"], rows[-1]["c_s[3]"] if rows else 0.0, rtol=1e-9,
             msg="restart reproduces the packed stress")

# 3. a platen moving as an equal-style variable prescribes (no grains in its way)
DT = 0.001
write_data("one.data", (0, L, 0, L, -1, 6), [Grain((2.0, 2.0, 1.0))])
deck3 = head("s.lslib", "one.data", boundary="p p f") + """
pair_style zero 1.0
pair_coeff * *
variable vz equal -0.02*(step<=100)+0.01*(step>100)*(step<=300)+0.03*sin(0.01*step)*(step>300)
fix top all wall/lsdem plane 0 0 5.0 0 0 -1 1000 900 0.3 velocity 0 0 v_vz
fix nve all nve/lsdem
timestep %r
thermo_style custom step f_top[4] f_top[5] f_top[6]
thermo_modify norm no format float %%.17g
thermo 100
run 400
""" % DT
rc, log = run_lmp(deck3, cwd=os.path.abspath("platen"))
rows3 = {int(r["Step"]): r for r in thermo(log)}
def expected(n):
    # the velocity at step s moves the platen during step s (evaluated when s starts)
    z = 5.0
    for s in range(1, n + 1):
        v = -0.02 if s <= 100 else (0.01 if s <= 300 else 0.03 * math.sin(0.01 * s))
        z += DT * v
    return z
if check(set(rows3) >= {0, 100, 200, 300, 400}, "platen: thermo rows missing"):
    for n in (0, 100, 200, 300, 400):
        near(rows3[n]["f_top[6]"], expected(n), atol=1e-12, msg="platen z at step %d" % n)
        near(rows3[n]["f_top[4]"], 0.0, atol=0.0, msg="platen x does not move")

# 4. a platen whose solid side holds the whole box stops with the range that works
deck4 = head("s.lslib", "one.data", boundary="p p f") + """
pair_style zero 1.0
pair_coeff * *
fix top all wall/lsdem plane 0 0 7.5 0 0 1 1000 900 0.3
fix nve all nve/lsdem
run 0
"""
rc, log = run_lmp(deck4, cwd=os.path.abspath("outside"), expect_fail=True)
check(rc != 0 and "plane point (0 0 7.5) is outside the box" in log and "[-1, 6]" in log,
      "a platen outside the box is refused naming the point and the range: %s" % log[-600:])

# 5. dilatancy angle from strain increments: eps_v = -eps_a (dilation) gives sin psi = 1/3,
#    eps_v = eps_a (no lateral strain) gives -90 deg; the first evaluation gives 0
deck5 = head("s.lslib", "one.data", boundary="p p f") + """
pair_style zero 1.0
pair_coeff * *
fix nve all nve/lsdem
variable ea equal 1e-4*step
variable ev equal -1e-4*step*(step<=20)+(-2e-3+1e-4*(step-20))*(step>20)
compute psi all dilatancy/lsdem v_ev v_ea
thermo_style custom step v_ea v_ev c_psi
thermo_modify format float %.17g
thermo 10
run 40
"""
rc, log = run_lmp(deck5, cwd=os.path.abspath("dilatancy"))
rows5 = {int(r["Step"]): r["c_psi"] for r in thermo(log)}
if check(set(rows5) >= {0, 10, 20, 30, 40}, "dilatancy: thermo rows missing"):
    near(rows5[0], 0.0, atol=0.0, msg="first evaluation")
    for n in (10, 20):
        near(rows5[n], math.degrees(math.asin(1.0 / 3.0)), atol=1e-9, msg="psi at step %d" % n)
    for n in (30, 40):
        near(rows5[n], -90.0, atol=1e-6, msg="psi at step %d" % n)

# 6. inertial number of one grain of density 1: V = m / rho, d = (6 V / pi)^(1/3),
#    I = rate d / sqrt(p / rho); p ramps from 0, so step 0 is unconfined (inf, no warning)
deck6 = head("s.lslib", "one.data", boundary="p p f") + """
pair_style zero 1.0
pair_coeff * *
fix nve all nve/lsdem
variable p equal 0.01*step
variable m atom mass
compute m all reduce sum v_m
compute inert all inertial/lsdem 0.5 v_p warn 1e-6
thermo_style custom step v_p c_m c_inert
thermo_modify format float %.17g
thermo 10
run 30
"""
rc, log = run_lmp(deck6, cwd=os.path.abspath("inertial"))
rows6 = {int(r["Step"]): r for r in thermo(log)}
if check(set(rows6) >= {0, 10, 20, 30}, "inertial: thermo rows missing"):
    check(math.isinf(float(rows6[0]["c_inert"])), "unconfined: I = inf, got %s"
          % rows6[0]["c_inert"])
    for n in (10, 20, 30):
        d = (6.0 * float(rows6[n]["c_m"]) / 1.0 / math.pi) ** (1.0 / 3.0)
        near(float(rows6[n]["c_inert"]), 0.5 * d / math.sqrt(float(rows6[n]["v_p"]) / 1.0),
             rtol=1e-12, msg="inertial number at step %d" % n)
warnings = [l for l in log.splitlines() if "not quasi-static" in l]
check(len(warnings) == 1 and "at step 10" in warnings[0],
      "one quasi-static warning, at the first confined step: %s" % warnings)

# 7. rotation angles of compute fabric/lsdem: grain 1 (a sphere, no contacts) spins at w
#    about z, so its angle is w t and the other 26 stay at 0: mean = w t / 27,
#    sd = w t sqrt(26) / 27, and only grain 1 lies above mean + 2 sd
W = 2.0
spin = [Grain(g.x, q=g.q, shape=g.shape, w=(0.0, 0.0, W if k == 0 else 0.0))
        for k, g in enumerate(grains)]
write_data("spin.data", (0, L, 0, L, -1, 6), spin)
deck7 = head("g.lslib", "spin.data", boundary="p p f") + """
pair_style lsdem
pair_coeff * * 1000 900 0.3
fix nve all nve/lsdem
compute fab all fabric/lsdem
thermo_style custom step time c_fab[8] c_fab[9] c_fab[10]
thermo_modify format float %.17g
thermo 10
run 20
"""
rc, log = run_lmp(deck7.replace("run 20", "run 0"), cwd=os.path.abspath("fabric"))
rows7 = thermo(log)
check(rows7 and rows7[0]["c_fab[10]"] == 0 and rows7[0]["c_fab[8]"] < 1e-15,
      "at rest: no grain flagged, angles at round-off: %s" % rows7)
rc, log = run_lmp(deck7, cwd=os.path.abspath("fabric"))
rows7 = {int(r["Step"]): r for r in thermo(log)}
if check(set(rows7) >= {10, 20}, "fabric: thermo rows missing"):
    for n in (10, 20):
        th = W * rows7[n]["Time"]
        near(rows7[n]["c_fab[8]"], th / 27, rtol=1e-9, msg="mean rotation at step %d" % n)
        near(rows7[n]["c_fab[9]"], th * math.sqrt(26) / 27, rtol=1e-9,
             msg="sd of the rotations at step %d" % n)
        check(rows7[n]["c_fab[10]"] == 1, "one grain flagged at step %d" % n)

# 8. long axes of three rods
shape_tool("analytic", "rod.lslib", "box", 0.6, 0.3, 0.15, "--spacing", 0.05, "--nodes", 120)
turns = [((1, 2, 3), 0.7), ((0, 0, 1), 1.2), ((-1, 0.5, 0.2), 2.5)]
rods = [Grain((1.5 + 2 * i, 1.5, 1.5), q=quat_axis_angle(ax, an)) for i, (ax, an) in enumerate(turns)]
write_data("rods.data", (0, 6, 0, 3, 0, 3), rods)
deck8 = head("rod.lslib", "rods.data", boundary="f f f") + """
pair_style lsdem
pair_coeff * * 1000 900 0.3
compute fab all fabric/lsdem
dump axes all custom 1 axes.dump id c_fab[3] c_fab[4] c_fab[5]
dump_modify axes format float %.17g sort id
thermo_style custom step c_fab[1] c_fab[2] c_fab[3] c_fab[4] c_fab[5] c_fab[6]
thermo_modify format float %.17g
run 0
"""
rc, log = run_lmp(deck8, cwd=os.path.abspath("axes"))
row8 = thermo(log)[-1] if rc == 0 else {}
dump = open(os.path.join("axes", "axes.dump")).read().split("ITEM: ATOMS")[-1].split("\n")[1:4]
axes = [[float(v) for v in line.split()[1:]] for line in dump]
F = [[0.0] * 3 for _ in range(3)]
for g, n in zip(rods, axes):
    w, x, y, z = g.q
    ex = (1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y))  # R(q) e_x
    near(abs(sum(a * b for a, b in zip(ex, n))), 1.0, atol=1e-12, msg="long axis %r of %r" % (n, g.q))
    for i in range(3):
        for j in range(3):
            F[i][j] += n[i] * n[j] / 3
for k, (i, j) in enumerate(((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))):
    near(row8.get("c_fab[%d]" % (k + 1), float("nan")), 7.5 * (F[i][j] - (i == j) / 3.0),
         atol=1e-12, msg="fabric deviator from the dumped axes, component %d" % (k + 1))

finish()
