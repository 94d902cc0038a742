"""compute strain/lsdem: a spread-out random set of grains is mapped affinely
(displace_atoms with atom-style variables, x -> (I + H) x); every grain's local strain,
volumetric and shear invariants, D2min, continuum rotation and neighbour count are checked
against values computed here from H and the positions, on 1 and 2 ranks."""
import math
import os
import random

import grain_decks as gd
from lsdemtest import check, finish, near, run_lmp

CUTOFF = 4.0
rng = random.Random(35)
grains = []
for i in range(4):
    for j in range(4):
        for k in range(3):
            x = [2.5 * (i - 1.5), 2.5 * (j - 1.5), 2.5 * (k - 1.0)]
            x = [c + rng.uniform(-0.3, 0.3) for c in x]
            q = gd.qnormalize([rng.gauss(0, 1) for _ in range(4)])
            grains.append({"id": len(grains) + 1, "shape": 2 + len(grains) % 2, "density": 1.0,
                           "x": x, "q": q})
DATA = os.path.abspath(gd.write_data("grains.data", grains))
LIB = os.path.abspath(gd.library())

DECK = """units lj
atom_style lsdem library %s
atom_modify map array
boundary f f f
comm_modify vel yes cutoff ${ghost}
read_data %s
pair_style lsdem
pair_coeff * * 1000 1000 0.5
compute s all strain/lsdem cutoff %r strain ${kind}
dump d all custom 1 strain.dump id c_s[*]
dump_modify d format float %%.17g sort id
run 0
variable dx atom ${h00}*x+${h01}*y+${h02}*z
variable dy atom ${h10}*x+${h11}*y+${h12}*z
variable dz atom ${h20}*x+${h21}*y+${h22}*z
displace_atoms all move v_dx v_dy v_dz
run 1
""" % (LIB, DATA, CUTOFF)

VOIGT = ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))


def expected_strain(H, kind):
    """eps = (H + H^T)/2 or E = (H + H^T + H^T H)/2 of F = I + H"""
    return [[0.5 * (H[i][j] + H[j][i]) + (0.5 * sum(H[k][i] * H[k][j] for k in range(3))
                                          if kind == "green" else 0.0)
             for j in range(3)] for i in range(3)]


def neighbour_counts():
    out = {}
    for a in grains:
        out[a["id"]] = sum(1 for b in grains if b is not a
                           and gd.norm([p - r for p, r in zip(a["x"], b["x"])]) < CUTOFF)
    return out


def run(label, H, kind, np):
    vars = {"kind": kind, "ghost": CUTOFF + 1.0}
    for i in range(3):
        for j in range(3):
            vars["h%d%d" % (i, j)] = repr(H[i][j])
    wd = "%s_np%d" % (label, np)
    run_lmp(DECK, np=np, vars=vars, cwd=wd)
    path = os.path.join(wd, "strain.dump")
    return gd.read_dump(path) if os.path.exists(path) else []


def check_map(name, H, kind, angle, np):
    frames = run(name.split(",")[0].replace(" ", "_"), H, kind, np)
    check(len(frames) == 2, "%s np=%d: two frames, got %d" % (name, np, len(frames)))
    if len(frames) != 2:
        return None
    E = expected_strain(H, kind)
    scale = max(abs(c) for row in E for c in row)
    tr = E[0][0] + E[1][1] + E[2][2]
    dev = [[E[i][j] - (tr / 3 if i == j else 0.0) for j in range(3)] for i in range(3)]
    shear = math.sqrt(0.5 * sum(c * c for row in dev for c in row))
    counts = neighbour_counts()
    for gid, a in frames[0][1].items():
        check(all(abs(a["c_s[%d]" % c]) <= 1e-14 for c in range(1, 12)),
              "%s: grain %d is strained at the reference: %r" % (name, gid, a))
    for gid, a in frames[1][1].items():
        tag = "%s np=%d grain %d" % (name, np, gid)
        for c, (i, j) in enumerate(VOIGT):
            near(a["c_s[%d]" % (c + 1)], E[i][j], atol=1e-9 * scale, msg=tag + " strain %d" % c)
        near(a["c_s[7]"], tr, atol=1e-9 * scale, msg=tag + " volumetric")
        near(a["c_s[8]"], shear, atol=1e-9 * scale, msg=tag + " shear")
        check(0.0 <= a["c_s[9]"] <= 1e-20, "%s D2min %r" % (tag, a["c_s[9]"]))
        near(a["c_s[10]"], angle, atol=1e-12, msg=tag + " continuum rotation")
        # the grains were moved, not turned: relative to the continuum they turned back
        near(a["c_s[11]"], angle, atol=1e-12, msg=tag + " grain rotation relative")
        check(a["c_s[12]"] == counts[gid], "%s: %r neighbours, expected %d"
              % (tag, a["c_s[12]"], counts[gid]))
    return frames[1][1]


g = 0.01
simple = [[0.0, g, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
pure_dilation = [[g, 0.0, 0.0], [0.0, -g, 0.0], [0.0, 0.0, g]]
# simple shear's polar rotation: tan(theta) = gamma / 2, about z
for np in (1, 2):
    one = check_map("simple shear, green", simple, "green", math.atan(g / 2), np)
    if np == 1:
        first = one
    elif one and first:
        worst = max(abs(one[i]["c_s[%d]" % c] - first[i]["c_s[%d]" % c])
                    for i in one for c in range(1, 12))
        check(worst <= 1e-14, "1 and 2 ranks differ by %g" % worst)
check_map("pure shear and dilation, small", pure_dilation, "small", 0.0, 2)

# the neighbourhood must fit in the ghost range
rc, log = run_lmp(DECK, vars={"kind": "small", "ghost": 1.0, **{"h%d%d" % (i, j): 0
                                                                 for i in range(3)
                                                                 for j in range(3)}},
                  cwd="ghost", expect_fail=True)
check(rc != 0 and "exceeds the ghost atom range" in log, "a short ghost range is refused")
finish()
