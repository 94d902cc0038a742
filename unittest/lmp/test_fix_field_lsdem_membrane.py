"""fix field/lsdem mask membrane (issue 35 item 2): the nodes outside the membrane's inner
layer (the surface through its sphere centres, closed at the end rings by the core) are NaN.

A two-layer membrane of lsdem-shape membrane (specimen radius 3, height 4, r_b 0.4; inner
centres on radius R_in), the fields of its spheres on a grid of spacing h = 0.25:
1. undeformed: `mask membrane` and `mask cylinder 0 0 R_in zlo zhi` (zlo, zhi: the inner end
   rings' heights) on the same grid mask the same nodes except within one node of the
   cylinder's surface (the membrane is a polygon of N facets with offset rings); the nodes
   that differ are counted;
2. bulged: the spheres moved radially by r -> r (1 + b sin(pi (z - zlo) / (zhi - zlo))),
   b = 0.15: the nodes inside are those inside that radius profile, again except within one
   node of the surface; more nodes than undeformed; 1 and 2 ranks write the same bytes;
3. errors: mask membrane naming a fix that is not fix membrane/lsdem."""
import math
import os

import numpy as np

from lsdemtest import check, finish, run_lmp, shape_tool
from vti import read_vti, runs_on_ranks

RS, H, RB, OUTER, B = 3.0, 4.0, 0.4, 1.1, 0.15
shape_tool("analytic", "ball_in.lslib", "sphere", RB, "--analytic")
shape_tool("analytic", "ball_out.lslib", "sphere", RB * OUTER, "--analytic")
shape_tool("merge", "mem.lslib", "ball_in.lslib", "ball_out.lslib")
shape_tool("membrane", "fm", "--radius", RS, "--height", H, "--rb", RB, "--library",
           "mem.lslib", "--shapes", 1, 2, "--z0", 0.0, "--density", 1.0, "--knbb", 50,
           "--ksbb", 50, "--outer", OUTER)

# the inner layer's vertices (the .tri file: tag layer end) and their positions (data file)
rows = [l.split("#")[0].split() for l in open("fm.tri")]
rows = [r for r in rows if r]
i = [k for k, r in enumerate(rows) if r[0] == "vertices"][0]
inner = {int(r[0]) for r in rows[i + 1:i + 1 + int(rows[i][1])] if int(r[1]) == 0}
atoms = open("fm.data").read().split("Atoms # hybrid")[1].split("Bonds")[0].strip().splitlines()
pos = {int(q[0]): tuple(map(float, q[2:5])) for q in (l.split() for l in atoms)}
R_IN = np.mean([math.hypot(pos[t][0], pos[t][1]) for t in inner])
ZLO = min(pos[t][2] for t in inner)
ZHI = max(pos[t][2] for t in inner)
check(abs(R_IN - (RS + RB)) < 1e-9, "inner centres on radius %r" % R_IN)

HERE = os.getcwd()
DECK = """units lj
atom_style hybrid lsdem library %s/mem.lslib bond
boundary f f f
newton on
comm_modify vel yes
read_data %s/fm.data
include %s/fm.in
pair_style lsdem
pair_coeff * * 2000 0 0
fix conf membrane membrane/lsdem pressure 0.0 triangles %s/fm.tri knb 2000
variable b equal %r
variable s atom v_b*sin(PI*(z-%r)/%r)
variable dx atom x*v_s
variable dy atom y*v_s
%%s
fix mm all field/lsdem 1 mem kernel 0.4 spacing 0.25 mask membrane conf
fix mc all field/lsdem 1 cyl kernel 0.4 spacing 0.25 mask cylinder 0 0 %r %r %r
run 0
""" % (HERE, HERE, HERE, HERE, B, ZLO, ZHI - ZLO, R_IN, ZLO, ZHI)


def coords(f):
    n = f["n"]
    idx = np.arange(n[0] * n[1] * n[2])
    return [f["origin"][k] + f["spacing"][k] * c
            for k, c in enumerate((idx % n[0], idx // n[0] % n[1], idx // (n[0] * n[1])))]


def compare(f, radius, what):
    """nodes inside the mask against r <= radius(z), zlo <= z <= zhi: those that differ lie
    within one node of that surface"""
    x, y, z = coords(f)
    r = np.hypot(x, y)
    R = radius(np.clip(z, ZLO, ZHI))
    expect = (r <= R) & (z >= ZLO) & (z <= ZHI)
    got = f["inside"][:, 0] == 1
    dist = np.minimum(np.abs(r - R), np.minimum(np.abs(z - ZLO), np.abs(z - ZHI)))
    differ = got != expect
    h = f["spacing"][0]
    far = differ & (dist > h)
    check(got.sum() > 1000 and not far.any(),
          "%s: %d nodes inside, %d differ, %d of them farther than a node (h %g) from the "
          "surface" % (what, got.sum(), differ.sum(), far.sum(), h))
    check(np.isnan(f["density"][~got]).all() and not np.isnan(f["density"][got]).any(),
          "%s: NaN outside the mask only" % what)
    print("%s: %d nodes inside, %d differ from the %s, all within one node of its surface"
          % (what, got.sum(), differ.sum(), "cylinder" if "undeformed" in what else "profile"))
    return got.sum()


# ---- 1. undeformed: against mask cylinder on the same grid ---------------------------
run_lmp(DECK % "", cwd="straight")
mem = read_vti(os.path.join("straight", "mem_0.vti"))
cyl = read_vti(os.path.join("straight", "cyl_0.vti"))
check(mem["n"] == cyl["n"] and np.array_equal(mem["origin"], cyl["origin"]), "the same grid")
n_straight = compare(mem, lambda z: R_IN + 0 * z, "undeformed membrane")
got, ref = mem["inside"][:, 0] == 1, cyl["inside"][:, 0] == 1
x, y, z = coords(mem)
near_surface = np.minimum(np.abs(np.hypot(x, y) - R_IN),
                          np.minimum(np.abs(z - ZLO), np.abs(z - ZHI))) <= mem["spacing"][0]
check(not ((got != ref) & ~near_surface).any(),
      "mask membrane and mask cylinder differ farther than a node from the surface")
print("mask membrane vs mask cylinder: %d of %d nodes differ, all within one node of the "
      "surface" % ((got != ref).sum(), got.size))

# ---- 2. bulged -------------------------------------------------------------------------
outs, first = runs_on_ranks(DECK % "displace_atoms membrane move v_dx v_dy 0.0", "bulged",
                            "mem_0.vti", ranks=(1, 2))
if first:
    n_bulged = compare(read_vti(first[0]),
                       lambda z: R_IN * (1 + B * np.sin(np.pi * (z - ZLO) / (ZHI - ZLO))),
                       "bulged membrane")
    check(n_bulged > 1.15 * n_straight, "bulged: %d nodes inside, undeformed %d"
          % (n_bulged, n_straight))
check(len(outs) == 2 and outs[1] == outs[2], "bulged: 1 and 2 ranks differ")

# ---- 3. errors ---------------------------------------------------------------------------
rc, log = run_lmp((DECK % "").replace("mask membrane conf", "mask membrane mc"), cwd="bad",
                  expect_fail=True)
check(rc != 0 and "is not a fix membrane/lsdem" in log, "mask membrane of another fix")
finish()
