"""compute shearband/lsdem: a lattice packing is displaced by a smooth-step simple shear
across a plane of dip 55 deg and azimuth 30 deg through the origin (displace_atoms with
atom-style variables; LAMMPS variables have no erf: an atan step); compute strain/lsdem's
von Mises shear feeds compute shearband/lsdem, whose band must have that dip and azimuth
(within 1 and 2 deg), with the per-grain flag set on the plane and not far from it; the numbers are bit-identical on 1 and 2 ranks.
The width values: the D50 equals the sieve median computed here from the library's shape
volumes (half balls, half boxes), the thickness in D50 is the thickness over it, and the
indicator profile's width (core-tested against Gaussian bands) is finite, no wider than the
specimen, and unchanged without a kernel; `kernel W` removes W in quadrature."""
import math
import os
import random

import grain_decks as gd
from lsdemtest import check, finish, near, run_lmp, shape_tool

DIP, AZIMUTH = 55.0, 30.0
d, a = math.radians(DIP), math.radians(AZIMUTH)
NORMAL = (math.sin(d) * math.cos(a), math.sin(d) * math.sin(a), math.cos(d))
SLIP = (math.cos(d) * math.cos(a), math.cos(d) * math.sin(a), -math.sin(d))  # in the plane
JUMP, WIDTH = 0.4, 0.5   # u = SLIP JUMP/pi atan(n.x / WIDTH)
rng = random.Random(36)
grains = []
for i in range(10):
    for j in range(10):
        for k in range(10):
            x = [2.5 * (c - 4.5) + rng.uniform(-0.3, 0.3) for c in (i, j, k)]
            grains.append({"id": len(grains) + 1, "shape": 2 + len(grains) % 2, "density": 1.0,
                           "x": x, "q": gd.qnormalize([rng.gauss(0, 1) for _ in range(4)])})
DATA = os.path.abspath(gd.write_data("grains.data", grains, box=(-14, 14, -14, 14, -14, 14)))
LIB = os.path.abspath(gd.library())


def sieve_d50(volumes):
    """The diameter at which half the volume is finer, each grain at the middle of its
    share, linear between grains (independent of the core's code)."""
    v = sorted(volumes)
    total, below, prev = sum(v), 0.0, None
    for vol in v:
        d = (6.0 * vol / math.pi) ** (1.0 / 3.0)
        f = (below + 0.5 * vol) / total
        below += vol
        if f >= 0.5:
            return d if prev is None else prev[1] + (d - prev[1]) * (0.5 - prev[0]) / (f - prev[0])
        prev = (f, d)


VOLUME = {}
for line in shape_tool("list", LIB).splitlines()[2:]:
    f = line.split()
    if len(f) > 4 and f[0].isdigit():
        VOLUME[int(f[0]) + 1] = float(f[-4])  # shape index 0.. -> type in the data file 1..
D50 = sieve_d50([VOLUME[g["shape"]] for g in grains])

DECK = """units lj
atom_style lsdem library %s
atom_modify map array
boundary f f f
comm_modify vel yes cutoff 5.0
read_data %s
pair_style lsdem
pair_coeff * * 1000 1000 0.5
compute s all strain/lsdem cutoff 3.2 strain small
compute b all shearband/lsdem c_s[8] threshold 3.0 k 1.5 planes 1 phi v_phi psi v_psi
variable phi equal 40.0
variable psi equal 10.0
thermo_style custom step c_b[*]
thermo_modify format float %%.17g
run 0
variable f atom %r*atan((%r*x+%r*y+%r*z)/%r)
variable dx atom %r*v_f
variable dy atom %r*v_f
variable dz atom %r*v_f
displace_atoms all move v_dx v_dy v_dz
dump d all custom 1 band.dump id c_b
dump_modify d sort id
run 0
""" % ((LIB, DATA, JUMP / math.pi) + NORMAL + (WIDTH,) + SLIP)


def thermo_values(log):
    lines = log.splitlines()
    for n, line in enumerate(lines):
        if line.split()[:2] == ["Step", "c_b[1]"]:
            last = n
    return [float(v) for v in lines[last + 1].split()[1:]]


def run(np):
    rc, log = run_lmp(DECK, np=np, cwd="np%d" % np)
    check(rc == 0, "np=%d: lmp ran" % np)
    if rc != 0:
        return None, None
    frames = gd.read_dump(os.path.join("np%d" % np, "band.dump"))
    return thermo_values(log), frames[-1][1]


results = {}
for np in (1, 2):
    vec, flags = run(np)
    if vec is None:
        continue
    results[np] = (vec, flags)
    check(len(vec) == 15, "np=%d: 7 plane values, 3 theory angles, D50 and 4 widths, got %d"
          % (np, len(vec)))
    near(vec[10], D50, rtol=1e-12, msg="np=%d: D50" % np)
    near(vec[11], vec[3] / D50, rtol=1e-12, msg="np=%d: thickness in D50" % np)
    check(0.0 < vec[12] < 28.0 and vec[13] == vec[12] and vec[14] == vec[13] / vec[10],
          "np=%d: profile width %r, corrected %r, in D50 %r" % (np, vec[12], vec[13], vec[14]))
    near(vec[0], DIP, atol=1.0, msg="np=%d dip" % np)
    gap = abs(vec[1] - AZIMUTH) % 360.0
    check(min(gap, 360.0 - gap) <= 2.0, "np=%d azimuth %r, expected %r" % (np, vec[1], AZIMUTH))
    near(sum(c * c for c in vec[4:7]), 1.0, atol=1e-12, msg="unit normal")
    near(vec[7], 65.0, atol=1e-12, msg="Coulomb")
    near(vec[8], 50.0, atol=1e-12, msg="Roscoe")
    near(vec[9], 57.5, atol=1e-12, msg="Arthur")
    on = off = on_flagged = off_flagged = 0
    for g in grains:
        dist = abs(sum(n * c for n, c in zip(NORMAL, g["x"])))
        f = flags[g["id"]]["c_b"]
        if dist < 0.5:
            on += 1
            on_flagged += f == 1
        elif dist > 6.0:
            off += 1
            off_flagged += f != 0
    check(on > 20 and on_flagged == on, "np=%d: %d of %d grains on the plane flagged"
          % (np, on_flagged, on))
    check(off_flagged == 0, "np=%d: %d of %d grains far from the plane flagged"
          % (np, off_flagged, off))
if len(results) == 2:
    check(results[1][0] == results[2][0],
          "1 and 2 ranks: %r != %r" % (results[1][0], results[2][0]))
    check(all(results[1][1][i]["c_b"] == results[2][1][i]["c_b"] for i in results[1][1]),
          "1 and 2 ranks: the same flags")

# kernel W: the profile width with W taken out in quadrature
if 1 in results:
    W = 0.5 * results[1][0][12]
    rc, log = run_lmp(DECK.replace("planes 1", "planes 1 kernel %r" % W), cwd="kernel")
    if check(rc == 0, "kernel run"):
        vec = thermo_values(log)
        near(vec[13], math.sqrt(vec[12] ** 2 - W * W), rtol=1e-12, msg="kernel removed")
        near(vec[12], results[1][0][12], rtol=1e-12, msg="the measured width unchanged")

# the indicator must be a per-atom column of the compute
rc, log = run_lmp(DECK.replace("c_s[8]", "c_s[13]"), cwd="column", expect_fail=True)
check(rc != 0 and "has no per-atom column 13" in log, "a column beyond the compute's is refused")
finish()
