"""fix wall/lsdem plane ... pivot h I c: a platen that tilts about the ram contact point
(report §3.2.1).

A platen at z = 1 facing down (normal -z) with its pivot P = (0, 0, 1 + h) presses on two
immobile analytic spheres (radius 0.5, no time integration, no gravity) at x = +2 and
x = -1.5 with overlaps 0.05 and 0.02. With mu = 0 each sphere pushes the platen up along
its normal with kn d (the sphere fast path), so the torque about P is about y:
T_y = -(x1 kn d1 + x2 kn d2), and from rest the platen turns about y by
theta = (T_y / I) dt^2 N(N+1)/2 ~ 0.5 (T_y / I) t^2 after N steps of the centred
difference (I large, so the overlaps barely change while it tilts): the
normal goes from (0,0,-1) to (-sin theta, 0, -cos theta) and the plane's point, h in
front of P along the normal, to P + h n. Checked against these closed forms (the wall
force f_ID[3] against kn (d1 + d2)); a sliding sphere's drag turns the platen with the
arm from P (not from the plane); a single sphere on the axis gives no tilt; 2 ranks
(one sphere each) give the 1-rank result; a restart mid-run (moving ram) continues as
if uninterrupted, and restart files cross between fixes with and without pivot; bad input
stops with the keyword and the valid range."""
import math
import os

from lsdemtest import run_lmp, shape_tool, thermo, check, near, finish
from contact_decks import Grain, write_data, head, THERMO_FULL

lib = "asphere.lslib"   # an analytic sphere: the one-lookup fast path, fn = kn d
if not os.path.exists(lib):
    shape_tool("analytic", lib, "sphere", 0.5, "--spacing", 0.05, "--nodes", 400, "--analytic")
KN, H, I, DT, N = 1000.0, 0.5, 1.0e5, 1.0e-3, 200
Z0 = 1.0
SPHERES = ((2.0, 0.05), (-1.5, 0.02))   # (x, overlap with the platen)
# tilt per unit angular acceleration after N steps of the centred difference (eqs
# 2.18-2.19) from rest: dt^2 (1 + 2 + ... + N); 0.5 t^2 (t = N dt) is 0.5% less
SWEEP = DT * DT * N * (N + 1) / 2


def grains(spheres):
    return [Grain((x, 0.0, Z0 - 0.5 + d)) for x, d in spheres]


def deck(data, extra_fix="", run=N, tail=""):
    return head(lib, data, boundary="f f f", extra="processors * 1 1") + """
pair_style zero 1.0
pair_coeff * *
fix top all wall/lsdem plane 0 0 %r 0 0 -1 %r 0 0 pivot %r %r 0.0 %s
thermo_style custom step f_top[1] f_top[2] f_top[3] f_top[4] f_top[5] f_top[6] &
  f_top[7] f_top[8] f_top[9] f_top[10] f_top[11] f_top[12] f_top[13]
%s
thermo %d
timestep %r
%s
run %d
""" % (Z0, KN, H, I, extra_fix, THERMO_FULL, run // 2, DT, tail, run)


box = (-4, 4, -4, 4, -1, 4)
write_data("two.data", box, grains(SPHERES))
write_data("axis.data", box, grains(((0.0, 0.05),)))

# ---- off-axis load: angular acceleration T/I about the right axis, 1 and 2 ranks
torque_y = -sum(x * KN * d for x, d in SPHERES)
ends = {}
for np in (1, 2):
    rc, log = run_lmp(deck(os.path.abspath("two.data")), np=np, cwd=os.path.abspath("np%d" % np))
    rows = thermo(log)
    if not check(len(rows) == 3, "np=%d: thermo output missing" % np):
        continue
    first, last = rows[0], rows[-1]
    near(first["f_top[3]"], KN * sum(d for _, d in SPHERES), rtol=1e-6,
         msg="np=%d: wall force = kn (d1 + d2)" % np)
    near(first["f_top[10]"], 0.0, atol=0.0, msg="np=%d: no tilt at the start" % np)
    theta = math.asin(-last["f_top[7]"])
    near(theta, SWEEP * torque_y / I, rtol=2e-3,
         msg="np=%d: tilt about y after %d steps vs (T/I) dt^2 N(N+1)/2" % (np, N))
    check(theta < 0, "np=%d: the side of the deeper load (+x) must rise (rotation about -y)"
          % np)
    near(last["f_top[8]"], 0.0, atol=1e-15, msg="np=%d: no tilt about x" % np)
    near(last["f_top[12]"], N * DT * torque_y / I, rtol=2e-3,
         msg="np=%d: angular velocity about y = (T/I) t" % np)
    near(abs(last["f_top[11]"]) + abs(last["f_top[13]"]), 0.0, atol=1e-15,
         msg="np=%d: angular velocity only about y" % np)
    near(last["f_top[10]"], abs(theta) * 180 / math.pi, rtol=1e-6,
         msg="np=%d: f_ID[10] is the tilt angle in degrees" % np)
    # the plane's point is h in front of the fixed pivot, along the tilted normal
    pivot = (0.0, 0.0, Z0 + H)
    for d in range(3):
        near(last["f_top[%d]" % (4 + d)], pivot[d] + H * last["f_top[%d]" % (7 + d)],
             atol=1e-12, msg="np=%d: plane point = P + h n, component %d" % (np, d))
    ends[np] = last
if check(len(ends) == 2, "both rank counts ran"):
    for key in ("f_top[3]", "f_top[7]", "f_top[9]", "f_top[4]"):
        near(ends[2][key], ends[1][key], rtol=1e-12, atol=1e-300,
             msg="2 ranks vs 1 rank: %s" % key)

# ---- a tangential load acts with the lever arm from P: one sphere at x = 2 sliding
# along +x (velocity given but not integrated) drags the platen through ct (ks = 0,
# mu = 1 above the cap): F_x on the wall at the contact point, the middle of the overlap
# (z = Z0 + d/2), so T_y = -(h - d/2) F_x - x F_z (about the plane's point it would be
# +d/2 F_x - x F_z, 5% off)
XS, DS, CT = 2.0, 0.05, 10.0
write_data("slide.data", box, [Grain((XS, 0.0, Z0 - 0.5 + DS), v=(1.0, 0.0, 0.0))])
slide = deck(os.path.abspath("slide.data")).replace(
    "%r 0 0 pivot" % KN, "%r 0 1.0 ct %r pivot" % (KN, CT))
rc, log = run_lmp(slide, cwd=os.path.abspath("slide"))
rows = thermo(log)
if check(len(rows) == 3, "slide: thermo output missing"):
    fx, fz = rows[0]["f_top[1]"], rows[0]["f_top[3]"]
    near(fx, CT * 1.0, rtol=1e-6, msg="slide: the drag on the platen is ct v")
    torque_y = -(H - DS / 2) * fx - XS * fz
    near(math.asin(-rows[-1]["f_top[7]"]), SWEEP * torque_y / I, rtol=2e-3,
         msg="slide: tilt about y with the tangential force's arm from P")

# ---- symmetric load (one sphere on the axis): no tilt
rc, log = run_lmp(deck(os.path.abspath("axis.data")), cwd=os.path.abspath("axis"))
rows = thermo(log)
if check(len(rows) == 3, "axis: thermo output missing"):
    check(rows[-1]["f_top[3]"] > 0.9 * KN * 0.05, "axis: the sphere does not press the platen")
    near(rows[-1]["f_top[7]"], 0.0, atol=1e-14, msg="axis: normal x")
    near(rows[-1]["f_top[8]"], 0.0, atol=1e-14, msg="axis: normal y")

# ---- restart mid-run with a moving ram: pivot point, frame and rate persist
ram = "velocity 0 0 -0.05"
rc, log = run_lmp(deck(os.path.abspath("two.data"), ram, run=400, tail="restart 200 mid.*"),
                  cwd=os.path.abspath("ref"))
ref = thermo(log)
if check(len(ref) == 3 and os.path.exists("ref/mid.200"), "restart reference failed"):
    restarted = """read_restart %s
pair_style zero 1.0
pair_coeff * *
fix top all wall/lsdem plane 0 0 %r 0 0 -1 %r 0 0 pivot %r %r 0.0 %s
thermo_style custom step f_top[3] f_top[4] f_top[6] f_top[7] f_top[9]
%s
thermo 200
timestep %r
run 200
""" % (os.path.abspath("ref/mid.200"), Z0, KN, H, I, ram, THERMO_FULL, DT)
    rc, log = run_lmp(restarted, cwd=os.path.abspath("restart"))
    rows = thermo(log)
    if check(len(rows) == 2, "restart: thermo output missing"):
        check(ref[-1]["f_top[6]"] < Z0 - 0.019, "restart reference: the ram did not move")
        for key in ("f_top[3]", "f_top[4]", "f_top[6]", "f_top[7]", "f_top[9]"):
            near(rows[0][key], ref[1][key], rtol=1e-12, atol=1e-300,
                 msg="restart, step 200: %s" % key)
            near(rows[-1][key], ref[-1][key], rtol=1e-10, atol=1e-300,
                 msg="restart, step 400: %s" % key)

# ---- restart files across the two kinds of fix: a fix without pivot reads a pivot file's
# wall point; a pivot fix reads a file without pivot as a level platen at rest where the
# wall was (the moving ram's point after 200 steps: Z0 - 0.05 * 200 dt)
def cross_restart(name, restart_file, fix_args):
    d = """read_restart %s
pair_style zero 1.0
pair_coeff * *
fix top all wall/lsdem plane 0 0 %r 0 0 -1 %r 0 0 %s
thermo_style custom step f_top[4] f_top[6] f_top[7] f_top[10]
%s
timestep %r
run 0
""" % (restart_file, Z0, KN, fix_args, THERMO_FULL, DT)
    rc, log = run_lmp(d, cwd=os.path.abspath(name))
    rows = thermo(log)
    return rows[0] if check(len(rows) == 1, "%s: thermo output missing" % name) else None


if os.path.exists("ref/mid.200") and len(ref) == 3:
    row = cross_restart("plain_reads_pivot", os.path.abspath("ref/mid.200"), ram)
    if row:
        near(row["f_top[4]"], ref[1]["f_top[4]"], rtol=1e-12, atol=1e-300,
             msg="a fix without pivot reads the wall point of a pivot restart (x)")
        near(row["f_top[6]"], ref[1]["f_top[6]"], rtol=1e-12, msg="... (z)")
        near(row["f_top[10]"], 0.0, atol=0.0, msg="... and has no tilt")
plain = head(lib, os.path.abspath("two.data"), boundary="f f f") + """
pair_style zero 1.0
pair_coeff * *
fix top all wall/lsdem plane 0 0 %r 0 0 -1 %r 0 0 %s
timestep %r
run 200
write_restart plain.200
""" % (Z0, KN, ram, DT)
rc, log = run_lmp(plain, cwd=os.path.abspath("plain"))
if check(os.path.exists("plain/plain.200"), "restart without pivot failed"):
    row = cross_restart("pivot_reads_plain", os.path.abspath("plain/plain.200"),
                        "pivot %r %r 0.0 %s" % (H, I, ram))
    if row:
        near(row["f_top[6]"], Z0 - 0.05 * 200 * DT, rtol=1e-12,
             msg="a pivot fix reads the wall point of a restart without pivot")
        near(row["f_top[7]"], 0.0, atol=0.0, msg="... level (normal x)")
        near(row["f_top[10]"], 0.0, atol=0.0, msg="... no tilt")

# ---- bad input: the keyword and the valid range
for name, args, words in (
        ("cylinder", "cylinder 0 0 3.0 1000 0 0 pivot 0.5 1.0", ("pivot", "plane")),
        ("inertia", "plane 0 0 1 0 0 -1 1000 0 0 pivot 0.5 0.0", ("pivot I", "> 0")),
        ("height", "plane 0 0 1 0 0 -1 1000 0 0 pivot -0.1 1.0", ("pivot h", ">= 0")),
        ("damping", "plane 0 0 1 0 0 -1 1000 0 0 pivot 0.5 1.0 -2", ("pivot c", ">= 0"))):
    bad = head(lib, os.path.abspath("axis.data"), boundary="f f f") + """
fix top all wall/lsdem %s
run 0
""" % args
    rc, log = run_lmp(bad, cwd=os.path.abspath("bad-" + name), expect_fail=True)
    check(rc != 0, "%s: bad input was accepted" % name)
    line = [l for l in log.splitlines() if "ERROR" in l]
    check(line and all(w in line[0] for w in words),
          "%s: the error should name %s: %s" % (name, words, line[:1]))

finish()
