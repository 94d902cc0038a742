"""fix membrane/lsdem + bond_style lsdem/membrane + lsdem-shape membrane, through lmp.

1. Generated data file reads as atom_style hybrid lsdem bond (write_data round trip keeps
   the Atoms layout id type x y z shape density q molecule).
2. Step 0: the distributed enclosed volume equals the prismatoid closed form of the
   lattice; the pressure forces on the closed membrane sum to zero (bonds at rest); the
   radial pressure force equals p (w_in A_in + w_out A_out).
3. Empty membrane, fixed end rings, pressure: contracts, every sphere of a ring moves the
   same (rotational symmetry), volume decreases.
4. Membrane around a rigid core grain: at equilibrium the measured radial stress equals the
   pressure carried by the membrane, p (w_in + w_out R_out/R_in) (force balance, hoop
   tension negligible at rest length).
5. 1 and 2 ranks agree to 1e-8 over 100 steps.
6. Bad apparatus input stops with messages naming the parameter and a safe range."""
import math
import os
import re
import subprocess

from lsdemtest import SHAPE_TOOL, run_lmp, shape_tool, thermo, check, near, finish

RS, H, RB, OUTER = 3.0, 4.0, 0.4, 1.1
P = 0.5
KNB = 2000.0


def make_library():
    shape_tool("analytic", "ball_in.lslib", "sphere", RB, "--analytic")
    shape_tool("analytic", "ball_out.lslib", "sphere", RB * OUTER, "--analytic")
    shape_tool("analytic", "core.lslib", "cylinder", RS, H / 2 + 1.0, "--spacing", 0.1,
               "--nodes", 200)
    shape_tool("merge", "mem.lslib", "core.lslib", "ball_in.lslib", "ball_out.lslib")


def make_membrane(prefix, rs=RS, rb=RB, grains=None, outer=OUTER):
    args = ["membrane", prefix, "--radius", rs, "--height", H, "--rb", rb, "--library",
            "mem.lslib", "--shapes", 2, 3, "--z0", 0.0, "--density", 1.0,
            "--knbb", 50, "--ksbb", 50, "--outer", outer]
    if grains:
        args += ["--grains", grains]
    return shape_tool(*args)


def lattice(out):
    """nper, rings, dz, R_in, R_out from the tool's summary line."""
    m = re.search(r"(\d+) per ring, (\d+) inner \+ (\d+) outer rings, ring spacing (\S+)\), "
                  r".*inner centres on radius (\S+), outer (\S+);", out)
    return (int(m.group(1)), int(m.group(2)), int(m.group(3)), float(m.group(4)),
            float(m.group(5)), float(m.group(6)))


def read_dump(path):
    frames, cur = [], None
    lines = open(path).read().splitlines()
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: ATOMS"):
            cols = lines[i].split()[2:]
            n = int(lines[i - 5])
            cur = {}
            for l in lines[i + 1:i + 1 + n]:
                v = dict(zip(cols, map(float, l.split())))
                cur[int(v["id"])] = v
            frames.append(cur)
            i += n
        i += 1
    return frames


def prismatoid_volume(n, rings, dz, r):
    """Closed form of the lattice volume (see unittest/core/test_membrane.c)."""
    step = 2 * math.pi / n
    a = 0.5 * n * r * r * math.sin(step)
    amid = n * r * r * math.cos(step / 4) ** 2 * math.sin(step / 2)
    return (rings - 1) * dz / 6.0 * (2 * a + 4 * amid)


def lateral_area(n, rings, dz, r):
    step = 2 * math.pi / n
    tri = r * math.sin(step / 2) * math.sqrt(dz * dz + (r * (1 - math.cos(step / 2))) ** 2)
    return 2 * n * (rings - 1) * tri


def read_sections(path):
    """The count-prefixed sections of a triangles file: {keyword: [int rows]}."""
    rows = [l.split("#")[0].split() for l in open(path)]
    rows = [r for r in rows if r]
    out, i = {}, 0
    while i < len(rows):
        if rows[i][0] in ("vertices", "triangles", "cap_edges"):
            n = int(rows[i][1])
            out[rows[i][0]] = [list(map(int, r)) for r in rows[i + 1:i + 1 + n]]
            i += n + 1
        else:
            i += 1
    return out


def bond_force(xi, xj, kn, ks, r0, hoop, axial):
    """Force on j of bond_style lsdem/membrane (axis at the origin), written out again."""
    d = [xj[k] - xi[k] for k in range(3)]
    L = math.sqrt(sum(c * c for c in d))
    u = [c / L for c in d]
    mx, my = (xi[0] + xj[0]) / 2, (xi[1] + xj[1]) / 2
    r = math.hypot(mx, my)
    t = (-my / r, mx / r, 0.0)
    et = d[0] * t[0] + d[1] * t[1] - hoop
    e = (et * t[0], et * t[1], d[2] - axial)
    eu = sum(e[k] * u[k] for k in range(3))
    return [-kn * (L - r0) * u[k] - ks * (e[k] - eu * u[k]) for k in range(3)]


def cross_half(a, b, c):
    ab = [b[k] - a[k] for k in range(3)]
    ac = [c[k] - a[k] for k in range(3)]
    return [0.5 * (ab[1] * ac[2] - ab[2] * ac[1]), 0.5 * (ab[2] * ac[0] - ab[0] * ac[2]),
            0.5 * (ab[0] * ac[1] - ab[1] * ac[0])]


def specimen_share(a, b, c, S):
    """Specimen-surface area behind a triangle: radial projection of its area vector at the
    centroid (radius r), scaled to the surface r_b further in by (r - r_b) / r."""
    cx, cy = (a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3
    r = math.hypot(cx, cy)
    return (S[0] * cx + S[1] * cy) / r * (r - RB) / r


def reconstruct_radial_stress(prefix, frame, p, w=(0.8, 0.2)):
    """(contact from dumped forces, contact from equilibrium) radial stress on the middle
    rings of both layers: sum f.r over their spheres / specimen area behind the inner middle
    spheres (sum of a third of each inner triangle's share), f = dumped - bond - pressure or
    -(bond + pressure)."""
    X = {i: (v["x"], v["y"], v["z"]) for i, v in frame.items()}
    coeff = {}
    for l in open(prefix + ".in"):
        if l.startswith("bond_coeff"):
            q = l.split()
            coeff[int(q[1])] = list(map(float, q[2:7]))
    fb = {i: [0.0, 0.0, 0.0] for i in X}
    data = open(prefix + ".data").read()
    for l in data.split("Bonds")[1].strip().splitlines():
        _, t, i, j = map(int, l.split())
        f = bond_force(X[i], X[j], *coeff[t])
        for k in range(3):
            fb[j][k] += f[k]
            fb[i][k] -= f[k]
    x0 = {}
    for l in data.split("Atoms # hybrid")[1].split("Bonds")[0].strip().splitlines():
        q = l.split()
        x0[int(q[0])] = tuple(map(float, q[2:5]))
    sec = read_sections(prefix + ".tri")
    norm = lambda v: math.sqrt(sum(c * c for c in v))
    a0 = [sum(norm(cross_half(x0[a], x0[b], x0[c])) for a, b, c, ly in sec["triangles"]
              if ly == layer) for layer in (0, 1)]
    scale = (w[0], w[1] * a0[0] / a0[1])
    fp = {i: [0.0, 0.0, 0.0] for i in X}
    area = {i: 0.0 for i in X}
    for a, b, c, ly in sec["triangles"]:
        S = cross_half(X[a], X[b], X[c])
        for v in (a, b, c):
            for k in range(3):
                fp[v][k] -= scale[ly] * p * S[k] / 3
            if ly == 0:
                area[v] += specimen_share(X[a], X[b], X[c], S) / 3
    mid = [v[0] for v in sec["vertices"] if v[2] == 0]
    radial = lambda i, f: (f[0] * X[i][0] + f[1] * X[i][1]) / math.hypot(X[i][0], X[i][1])
    amid = sum(area[i] for i in mid)  # specimen-surface area of the middle rings (inner)
    dumped = sum(radial(i, [frame[i]["f" + c] - fb[i][k] - fp[i][k]
                            for k, c in enumerate("xyz")]) for i in mid)
    equil = sum(radial(i, [-fb[i][k] - fp[i][k] for k in range(3)]) for i in mid)
    return dumped / amid, equil / amid


HERE = os.getcwd()
HEAD = """units lj
atom_style hybrid lsdem library """ + HERE + """/mem.lslib bond
boundary f f f
newton on
comm_modify vel yes
read_data """ + HERE + """/%s.data
include """ + HERE + """/%s.in
pair_style lsdem
pair_coeff * * %g 0 0
timestep 0.005
"""

make_library()
out = make_membrane("empty")
N, RINGS, ORINGS, DZ, RIN, ROUT = lattice(out)
check(N == round(math.pi / math.asin(RB / (RS + RB))), "spheres per ring %d" % N)
near(RIN, RS + RB, rtol=1e-12, msg="inner centre radius")

# ---- 1. data layout round trip ------------------------------------------------------
rc, log = run_lmp(HEAD % ("empty", "empty", KNB) + "run 0\nwrite_data back.data\n")
text = open("back.data").read()
first = open("empty.data").read().split("Atoms # hybrid")[1].split("\n\n")[1].splitlines()[0]
line = [l for l in text.split("Atoms # hybrid")[1].split("\n\n")[1].splitlines()
        if l.split()[0] == first.split()[0]][0]
a, b = first.split(), line.split()
check(len(b) >= 12 and a[1] == b[1] and a[5:12] == [str(int(float(b[5])))] + b[6:12]
      if len(b) >= 12 else False, "Atoms layout round trip: %s -> %s" % (first, line))
near(float(b[2]), float(a[2]), atol=1e-12, msg="x round trip")
check(int(b[11]) == int(a[11]), "molecule ID round trip")

# ---- 2. step 0 quantities ------------------------------------------------------------
DECK0 = HEAD % ("empty", "empty", KNB) + """
fix conf membrane membrane/lsdem pressure %g triangles empty.tri knb %g
compute fsum membrane reduce sum fx fy fz
thermo_style custom step f_conf[1] f_conf[2] f_conf[3] f_conf[5] f_conf[6] c_fsum[1] c_fsum[2] c_fsum[3]
thermo_modify format float %%.15g
dump d membrane custom 1 f0.dump id x y fx fy
dump_modify d format float %%.15g
run 0
""" % (P, KNB)
rc, log = run_lmp(DECK0)
row = thermo(log)[0]
near(row["f_conf[1]"], prismatoid_volume(N, RINGS, DZ, RIN), rtol=1e-10, msg="volume, 1 rank")
near(row["f_conf[6]"], prismatoid_volume(N, ORINGS, DZ, ROUT), rtol=1e-10, msg="outer volume")
a_in = lateral_area(N, RINGS, DZ, RIN)
near(row["f_conf[3]"], a_in, rtol=1e-10, msg="inner lateral area")
near(row["f_conf[5]"], P, rtol=1e-15, msg="pressure")
fscale = P * a_in
for k in (1, 2, 3):
    near(row["c_fsum[%d]" % k], 0.0, atol=1e-11 * fscale, msg="net pressure force %d" % k)
# radial force: the triangles are tilted slightly; their horizontal area is within the
# polygon error of the area
a_out = lateral_area(N, ORINGS, DZ, ROUT)
frad = sum((v["fx"] * v["x"] + v["fy"] * v["y"]) / math.hypot(v["x"], v["y"])
           for v in read_dump("f0.dump")[0].values())
# the layers share the force P A_in (outer pressure scaled by A_in / A_out)
near(-frad, P * a_in, rtol=0.01, msg="radial pressure force")
near(row["f_conf[2]"], 0.0, atol=1e-12, msg="no grains: no radial stress")
rc, log2 = run_lmp(DECK0, np=2, log="log2.lammps")
row2 = thermo(log2)[0]
near(row2["f_conf[1]"], row["f_conf[1]"], rtol=1e-12, msg="volume, 2 ranks")

# ---- 3. empty membrane contracts symmetrically ----------------------------------------
DECK3 = HEAD % ("empty", "empty", KNB) + """
group ends union membrane_bottom membrane_top
fix conf membrane membrane/lsdem pressure %g triangles empty.tri knb %g
fix nve membrane nve/lsdem damping 2.0
fix hold ends setforce 0 0 0
thermo_style custom step f_conf[1] f_conf[2]
thermo_modify format float %%.15g
thermo 100
dump d membrane custom 400 mem.dump id mol type x y z
dump_modify d sort id format float %%.15g
run 400
""" % (P, KNB)
rc, log = run_lmp(DECK3)
rows = thermo(log)
print("empty membrane: volume %.8g -> %.8g" % (rows[0]["f_conf[1]"], rows[-1]["f_conf[1]"]))
check(rows[-1]["f_conf[1]"] < 0.995 * rows[0]["f_conf[1]"],
      "volume decreases: %g -> %g" % (rows[0]["f_conf[1]"], rows[-1]["f_conf[1]"]))


last = read_dump("mem.dump")[-1]
ids = sorted(last)
# inner sphere k of ring m has id = first + m*N + k (tool order); radii per ring
first_id = ids[0]
spread, contracted = 0.0, 0
for m in range(RINGS):
    radii = [math.hypot(last[first_id + m * N + k]["x"], last[first_id + m * N + k]["y"])
             for k in range(N)]
    zs = [last[first_id + m * N + k]["z"] for k in range(N)]
    spread = max(spread, max(radii) - min(radii), max(zs) - min(zs))
    if 0 < m < RINGS - 1 and max(radii) < RIN - 1e-3:
        contracted += 1
check(spread < 1e-9, "rings stay circular and level (spread %g)" % spread)
check(contracted == RINGS - 2, "all middle rings contracted (%d of %d)" % (contracted, RINGS - 2))
mid = (RINGS - 1) // 2
check(math.hypot(last[first_id + mid * N]["x"], last[first_id + mid * N]["y"]) < RIN - 0.01,
      "middle ring moved inward")

# ---- 4. rigid core: radial stress = pressure ----------------------------------------
CORE = """LAMMPS data file (core)

1 atoms
1 atom types

-4 4 xlo xhi
-4 4 ylo yhi
-1 5 zlo zhi

Atoms # lsdem

1 1 1 1.0 0 0 %r 1 0 0 0
""" % (H / 2)
open("core.data", "w").write(CORE)
DECK4 = HEAD + """
group ends union membrane_bottom membrane_top
fix conf membrane membrane/lsdem pressure %g triangles %s.tri knb %g
fix nve membrane nve/lsdem damping 4.0
fix hold ends setforce 0 0 0
thermo_style custom step f_conf[1] f_conf[2] f_conf[4]
thermo_modify format float %%.15g
thermo 100
run 1500
"""
# single layer: every middle sphere carries P on its tributary area of the centres'
# surface (tilt of the triangles and the tiny sink into the core aside); the fix reports it
# per area of the specimen surface, smaller by RS / (RS + RB). With "surface specimen" P
# acts on the specimen surface.
SHARE = RS / (RS + RB)
make_membrane("single", grains="core.data", outer=0)
rc, log = run_lmp(DECK4 % ("single", "single", KNB, P, HERE + "/single", KNB))
rows = thermo(log)
print("radial stress, single layer on a rigid core: %.8g (P / SHARE = %.8g)"
      % (rows[-1]["f_conf[2]"], P / SHARE))
near(rows[-1]["f_conf[2]"], P / SHARE, rtol=0.02, msg="radial stress on a rigid core, single layer")
near(rows[-1]["f_conf[2]"], rows[-2]["f_conf[2]"], rtol=0.01, msg="radial stress settled")
rc, log = run_lmp((DECK4 % ("single", "single", KNB, P, HERE + "/single", KNB)).replace(
    "knb %g\n" % KNB, "knb %g surface specimen\n" % KNB))
print("radial stress, single layer, surface specimen: %.8g (P = %g)"
      % (thermo(log)[-1]["f_conf[2]"], P))
near(thermo(log)[-1]["f_conf[2]"], P, rtol=0.02, msg="radial stress, surface specimen")
# specimen volume estimate: the core cylinder of radius RS between the end-ring planes,
# within the inscribed-polygon error
near(rows[-1]["f_conf[4]"], math.pi * RS * RS * H, rtol=0.02, msg="specimen volume estimate")
# double layer, 80/20, free ends: the outer share reaches the specimen through the
# inter-layer bonds, less what the outer shell's own springs carry. Check the fix's
# measurement against a reconstruction from the dumped state: contact = total force -
# bond forces (formula re-implemented below) - pressure forces (from the triangles file).
make_membrane("cored", grains="core.data")
DECK4D = (DECK4 % ("cored", "cored", KNB, P, HERE + "/cored", KNB)).replace(
    "fix hold ends setforce 0 0 0\n", "").replace(
    "run 1500", "dump d all custom 1500 eq.dump id x y z fx fy fz\n"
    "dump_modify d sort id format float %.17g\nrun 1500")
rc, log = run_lmp(DECK4D)
rows = thermo(log)
sig = rows[-1]["f_conf[2]"]
rec, eq = reconstruct_radial_stress("cored", read_dump("eq.dump")[-1], P)
print("radial stress, double layer on a rigid core: %.8g (P = %g; reconstructed %.8g, "
      "from equilibrium %.8g)" % (sig, P, rec, eq))
near(sig, rec, rtol=1e-6, msg="radial stress vs reconstruction from the dump")
near(sig, eq, rtol=1e-3, msg="radial stress vs equilibrium -(bond + pressure)")
near(sig, P / SHARE, rtol=0.05, msg="radial stress on a rigid core, double layer, free ends")

# ---- 5. 1 vs 2 ranks, 100 steps -------------------------------------------------------
DECK5 = HEAD % ("cored", "cored", KNB) + """
group ends union membrane_bottom membrane_top
fix conf membrane membrane/lsdem pressure v_p triangles """ + HERE + """/cored.tri knb %g
variable p equal ramp(0,%g)
fix nve membrane nve/lsdem damping 1.0
fix hold ends setforce 0 0 0
dump d all custom 100 par.dump id x y z
dump_modify d sort id format float %%.17g
run 100
""" % (KNB, 2 * P)
run_lmp(DECK5, cwd="np1")
run_lmp(DECK5, np=2, cwd="np2")
d1, d2 = read_dump("np1/par.dump")[-1], read_dump("np2/par.dump")[-1]
worst = max(abs(d1[i][c] - d2[i][c]) for i in d1 for c in ("x", "y", "z"))
print("1 vs 2 ranks, 100 steps: max position difference %g" % worst)
check(len(d1) == len(d2) and worst < 1e-8, "1 vs 2 ranks after 100 steps: max diff %g" % worst)
moved = max(abs(d1[i]["x"] - read_dump("np1/par.dump")[0][i]["x"]) for i in d1)
check(moved > 1e-4, "the parallel check moved the membrane (%g)" % moved)

# restart: 50 steps, write_restart, read_restart (bond coefficients and axis from the file),
# 50 more steps == 100 uninterrupted steps (the fix keeps no state but its input file)
FIXES5 = """group ends union membrane_bottom membrane_top
variable p equal %g*step/100
fix conf membrane membrane/lsdem pressure v_p triangles %s/cored.tri knb %g
fix nve membrane nve/lsdem damping 1.0
fix hold ends setforce 0 0 0
""" % (2 * P, HERE, KNB)
run_lmp(HEAD % ("cored", "cored", KNB) + FIXES5 + "run 50\nwrite_restart half.restart\n",
        cwd="rs")
run_lmp("read_restart half.restart\ncomm_modify vel yes\n" + FIXES5 + "dump d all custom 50 par.dump id x y z\n"
    "dump_modify d sort id format float %.17g\nrun 50\n", cwd="rs")
d3 = read_dump("rs/par.dump")[-1]
worst = max(abs(d1[i][c] - d3[i][c]) for i in d1 for c in ("x", "y", "z"))
check(worst < 1e-10, "restart at step 50 reproduces step 100: max diff %g" % worst)

# ---- 6. bad apparatus input ----------------------------------------------------------
make_membrane("fat", rs=1.5, rb=0.4)
rc, log = run_lmp(HEAD % ("fat", "fat", KNB) + "fix conf membrane membrane/lsdem pressure "
                  "%g triangles fat.tri knb %g\nrun 0\n" % (P, KNB), expect_fail=True)
check(rc != 0 and "membrane sphere radius r_b = 0.4 is too large" in log and "r_b <= 0.3" in log,
      "r_b too large message:\n" + log[-500:])
rc, log = run_lmp(HEAD % ("empty", "empty", KNB) + "fix conf membrane membrane/lsdem pressure "
                  "500 triangles empty.tri knb 10\nrun 0\n", expect_fail=True)
check(rc != 0 and "pressure 500 is too high" in log and "use pressure <=" in log,
      "pressure too high message:\n" + log[-500:])
rc, log = run_lmp(HEAD % ("empty", "empty", KNB) + "variable p equal ramp(0,500)\n"
                  "fix conf membrane membrane/lsdem pressure v_p triangles empty.tri knb 10\n"
                  "fix nve membrane nve/lsdem\nrun 50\n", expect_fail=True)
check(rc != 0 and "is too high for the grain-membrane stiffness knb = 10" in log,
      "ramped pressure too high message:\n" + log[-500:])
rc, log = run_lmp(HEAD % ("empty", "empty", KNB) + "fix conf membrane membrane/lsdem pressure "
                  "1 triangles nofile.tri\nrun 0\n", expect_fail=True)
check(rc != 0 and "cannot open triangles file nofile.tri" in log, "missing file message")
rc, log = run_lmp(HEAD % ("empty", "empty", KNB) + "group some id 1:10\nfix conf some "
                  "membrane/lsdem pressure 1 triangles empty.tri\nrun 0\n", expect_fail=True)
check(rc != 0 and "membrane spheres are not in fix group some" in log, "group message")
# a membrane torn across ranks: sphere 21 (y = -3.39, rank 0 of the 1 by 2 by 1 grid) moved to
# y = 0.5 (rank 1; still a ghost of rank 0): the triangles it is lowest of are rank 1's, and
# their other vertices are out of rank 1's reach. Rank 1 alone finds it; all ranks stop, and
# rank 0's log carries the message (it was lost with an error->one on rank 1 alone).
rc, log = run_lmp("processors 1 2 1\n" + HEAD % ("empty", "empty", KNB) +
                  "thermo_modify lost/bond ignore\nset atom 21 y 0.5\n"
                  "fix conf membrane membrane/lsdem pressure 1 triangles empty.tri\nrun 0\n",
                  np=2, log="torn.log", expect_fail=True)
torn = open("torn.log").read()
check(rc != 0 and "is neither owned nor a ghost on rank 1" in torn
      and "(found on rank 1)" in torn and "MPI_ABORT" not in log,
      "torn membrane on rank 1: message in rank 0's log, no abort:\n" + log[-800:])
# generator input errors
def tool_fails(*args):
    p = subprocess.run([SHAPE_TOOL, "membrane"] + [str(a) for a in args], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    return p.returncode, p.stdout


rc, msg = tool_fails("bad", "--radius", RS, "--height", H, "--rb", RB, "--library", "mem.lslib",
                     "--shapes", 1, 3)
check(rc == 1 and "shape-ID 1 of mem.lslib must be an analytic sphere of radius 0.4" in msg,
      "wrong membrane shape message: " + msg)
rc, msg = tool_fails("bad", "--radius", 0.3, "--height", H, "--rb", RB, "--library", "mem.lslib",
                     "--shapes", 2, 3)
check(rc == 1 and "sphere radius 0.4 too large for specimen radius 0.3" in msg,
      "rb > Rs message: " + msg)
rc, msg = tool_fails("bad", "--radius", RS, "--height", H)
check(rc == 2 and "are required" in msg, "missing options: " + msg)
finish()
