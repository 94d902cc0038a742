"""bond_style lsdem/net + fix net/lsdem + lsdem-shape net, through lmp.

1. Statics: a clamped hexagonal net with pretension under gravity, run to rest with
   damping, against an independent Newton solve of the same spring network (numpy, the
   bond law written out again): every ball within 1e-6; the anchors' reaction equals the
   free balls' weight; the residual height and largest strain equal the solve's. Once
   horizontal, once in a plane tilted by 45 degrees (given by a skew e2).
2. Waves: a 1-D ball chain (clamped ends) in its first longitudinal mode oscillates at the
   frequency of a wave speed a sqrt(k/m), within 1 % (and the discrete chain's dispersion
   relation within 0.1 %).
3. Rupture: a chain stretched uniformly (every ball driven), one bond of it with a break
   strain: it breaks at the first step whose strain exceeds the limit, once, the same on
   1 and 2 ranks (the bond crosses the ranks' boundary) and with newton_bond off; its force is gone afterwards, and
   stays gone across a restart (the outputs after read_restart equal those before).
4. Bad input: a net file with a bond to a missing ball, an empty clamp group, a break
   limit <= 0 stop with messages that say what is wrong.
5. Grains through the net: a grain falling through a cell of the net counts from the step
   its centre is below the net, not before; a grain beside the footprint never counts."""
import math
import re

import numpy as np

from lsdemtest import run_lmp, shape_tool, thermo, check, near, finish
from net_common import HERE, RB, make_ball, make_net, head, bonds, read_dump

make_ball()

# ---- 1. statics against a Newton solve -------------------------------------------------
K, R0, G = 0.1, 0.9, 0.2


def atoms(prefix):
    """{id: (type, position)} of the data file's Atoms section as written."""
    text = open(prefix + ".data").read().split("Atoms # hybrid")[1].split("\nBonds")[0]
    rows = [l.split() for l in text.strip().splitlines()]
    return {int(r[0]): (int(r[1]), np.array(list(map(float, r[2:5])))) for r in rows}


def newton(bl, x0, free, mass):
    """Rest positions of the free balls (bonds + weight along -z), Newton's method on the
    spring network written out again; returns {id: position}."""
    col = {i: n for n, i in enumerate(free)}
    pos = lambda X, i: X[3 * col[i]:3 * col[i] + 3] if i in col else x0[i]

    def residual_and_jacobian(X):
        F = np.zeros(3 * len(free))
        J = np.zeros((3 * len(free), 3 * len(free)))
        for i in free:
            F[3 * col[i] + 2] -= mass[i] * G
        for _, i, j in bl:
            d = pos(X, j) - pos(X, i)
            L = np.linalg.norm(d)
            u = d / L
            fj = -K * (L - R0) * u
            # d fj / d xj = -K [(1 - R0/L)(I - u u) + u u]
            Kb = -K * ((1 - R0 / L) * (np.eye(3) - np.outer(u, u)) + np.outer(u, u))
            for a, s in ((j, 1.0), (i, -1.0)):
                if a not in col:
                    continue
                F[3 * col[a]:3 * col[a] + 3] += s * fj
                for b, t in ((j, 1.0), (i, -1.0)):
                    if b in col:
                        J[3 * col[a]:3 * col[a] + 3, 3 * col[b]:3 * col[b] + 3] += s * t * Kb
        return F, J

    X = np.concatenate([x0[i] - np.array([0, 0, 0.1]) for i in free])
    for it in range(50):
        F, J = residual_and_jacobian(X)
        X -= np.linalg.solve(J, F)
        if np.abs(F).max() < 1e-15:
            break
    F, _ = residual_and_jacobian(X)
    check(np.abs(F).max() < 1e-14, "Newton solve did not converge: residual %g"
          % np.abs(F).max())
    return {i: pos(X, i) for i in x0}


def statics(prefix, origin, e1, e2):
    """A net in the plane (origin, e1, e2) sags under gravity along -z: rest state against
    the Newton solve; anchors, residual height along the net's normal, largest strain."""
    make_net(prefix, "--spacing", 1, "--size", 5, 4, "--rest", R0, "--k", K, "--damp", 0.02,
             "--origin", *origin, "--e1", *e1, "--e2", *e2)
    deck = head(prefix) + """
fix int net_free nve/lsdem damping 0.5
fix g net_free gravity {g} vector 0 0 -1
fix net net net/lsdem {here}/{p}.net clamp net_clamp
timestep 0.02
thermo 1000
thermo_style custom step ke f_net[1] f_net[2] f_net[3] f_net[4] f_net[5]
thermo_modify format float %.17g
run 8000
write_dump net custom rest.dump id type x y z mass modify format float %.17g
""".format(g=G, p=prefix, here=HERE)
    rc, log = run_lmp(deck, cwd=prefix)
    rest = read_dump(prefix + "/rest.dump")
    built = atoms(prefix)
    bl = bonds(prefix)
    free = sorted(i for i in built if built[i][0] == 1)
    mass = {i: rest[i]["mass"] for i in rest}
    x = newton(bl, {i: built[i][1] for i in built}, free, mass)
    err = max(np.abs(np.array([rest[i][c] for c in "xyz"]) - x[i]).max() for i in free)
    check(err < 1e-6, "%s: rest positions differ from the Newton solve by %g (> 1e-6)"
          % (prefix, err))
    n = np.cross(e1, np.array(e2) - np.dot(e2, e1) / np.dot(e1, e1) * np.array(e1))
    n = n / np.linalg.norm(n)
    low = min(np.dot(x[i] - np.array(origin), n) for i in x)
    print("statics (%s): %d free balls, residual height %.9f, largest difference to the "
          "Newton solve %.3g" % (prefix, len(free), low, err))
    row = thermo(log)[-1]
    weight = sum(mass[i] for i in free) * G
    near(row["f_net[3]"], weight, rtol=1e-9, msg="%s: anchor reaction = free balls' weight"
         % prefix)
    near(row["f_net[1]"], 0.0, atol=1e-9, msg="%s: anchor reaction x" % prefix)
    near(row["f_net[5]"], low, atol=1e-6, msg="%s: residual height = the solve's" % prefix)
    strain = max((np.linalg.norm(x[j] - x[i]) - R0) / R0 for _, i, j in bl)
    near(row["f_net[4]"], strain, atol=1e-6, msg="%s: largest strain = the solve's" % prefix)


statics("sag", (0, 0, 0), (1, 0, 0), (0, 1, 0))
statics("tilted", (0.5, -0.2, 1.0), (1, 0, 1), (0.3, 1, 0))  # 45 degrees about y, skew e2

# ---- 2. a 1-D chain carries waves at a sqrt(k/m) ---------------------------------------
KC, A, NSEG, AMP = 1.0, 1.0, 50, 0.01
make_net("chain", "--lattice", "square", "--spacing", A, "--size", NSEG * A, 0,
         "--clamp", "u0,u1", "--k", KC)
deck = head("chain") + """
variable dx atom {amp}*sin(PI*x/{L})
displace_atoms net_free move v_dx 0 0
fix int net_free nve/lsdem
timestep 0.01
variable xm equal x[{mid}]-{xmid}
variable m equal mass[{mid}]
thermo 5
thermo_style custom step time v_xm v_m
thermo_modify format float %.17g
run 4000
""".format(amp=AMP, L=NSEG * A, mid=NSEG // 2 + 1, xmid=(NSEG // 2) * A)
rc, log = run_lmp(deck)
rows = thermo(log)
m = rows[0]["v_m"]
t = [r["Time"] for r in rows]
u = [r["v_xm"] for r in rows]
down = [t[k] + (t[k + 1] - t[k]) * u[k] / (u[k] - u[k + 1])
        for k in range(len(u) - 1) if u[k] > 0 >= u[k + 1]]
check(len(down) >= 2, "middle ball: %d downward zero crossings" % len(down))
if len(down) >= 2:
    period = (down[-1] - down[0]) / (len(down) - 1)
    q = math.pi / (NSEG * A)
    c = 2 * math.pi / period / q
    c0 = A * math.sqrt(KC / m)
    print("waves: period %.6f, speed %.6f against a sqrt(k/m) = %.6f (ratio %.5f)"
          % (period, c, c0, c / c0))
    near(c, c0, rtol=0.01, msg="wave speed against a sqrt(k/m)")
    omega = 2 * math.sqrt(KC / m) * math.sin(q * A / 2)  # the discrete chain's mode 1
    near(2 * math.pi / period, omega, rtol=1e-3, msg="mode-1 frequency of the chain")

# ---- 3. rupture at the step the law says, once, on 1 and 2 ranks ------------------------
RATE, DT, S = 0.01, 0.01, 0.012345
make_net("pull", "--lattice", "square", "--spacing", 1, "--size", 10, 0, "--clamp", "u0",
         "--k", 1, "--margin", 3)
text = open("pull.data").read().replace("1 bond types", "2 bond types")
text = re.sub(r"\n(\d+) 1 5 6\n", r"\n\1 2 5 6\n", text)  # the bond x = 4 -> 5
open("pull.data", "w").write(text)
deck = head("pull", pre="processors * 1 1\n") + """
bond_coeff 2 1 1 break strain {s}
fix x0 all store/state 0 x
variable dx atom {rate}*time*f_x0
variable vx atom {rate}*f_x0
fix drive net_free move variable v_dx NULL NULL v_vx NULL NULL
fix net net net/lsdem {here}/pull.net clamp net_clamp
timestep {dt}
thermo 1
thermo_style custom step ebond f_net[4] f_net[6]
thermo_modify format float %.17g norm no
run 200
write_restart pull.200
""".format(s=S, rate=RATE, dt=DT, here=HERE)
runs = {}
for np_ in (1, 2):
    rc, log = run_lmp(deck, np=np_, cwd="pull%d" % np_)
    runs[np_] = thermo(log)
rows = runs[1]
expect = next(r["Step"] for r in rows if RATE * r["Step"] * DT > S)
broken = [int(r["f_net[6]"]) for r in rows]
first = next((r["Step"] for r in rows if r["f_net[6]"] > 0), None)
print("rupture: strain limit %g, expected at step %d, broke at step %s" % (S, expect, first))
first = int(first) if first is not None else None
check(first == expect, "the bond broke at step %s, the law says %d" % (first, expect))
check(max(broken) == 1 and broken[-1] == 1, "bonds broken over the run: %s" % sorted(set(broken)))
for r in rows:
    strain = RATE * r["Step"] * DT
    intact = 10 if r["Step"] < expect else 9
    near(r["E_bond"], intact * 0.5 * strain * strain, rtol=1e-9, atol=1e-15,
         msg="bond energy at step %d (%d intact bonds)" % (r["Step"], intact))
# newton_bond off: both ranks of the crossing bond compute it and break their own halves
rc, log = run_lmp(deck.replace("newton on\n", "newton on off\n"), np=2, cwd="pull_off")
runs["off"] = thermo(log)
net_cols = lambda rows: [(r["Step"], r["f_net[4]"], r["f_net[6]"]) for r in rows]
check(net_cols(runs[1]) == net_cols(runs[2]), "1 and 2 ranks give different net outputs")
check(net_cols(runs[1]) == net_cols(runs["off"]), "newton_bond off gives other net outputs")
for r1, r2 in zip(runs[1], runs[2]):  # energy: LAMMPS's sum over ranks, last bits aside
    near(r2["E_bond"], r1["E_bond"], rtol=1e-12, msg="bond energy on 2 ranks")

# restart: the broken bond stays broken (type 0 in the restart file), the coefficients
# come back, and the outputs follow from the atoms alone
rc, log = run_lmp("""read_restart pull1/pull.200
fix net net net/lsdem {here}/pull.net clamp net_clamp
thermo_style custom step ebond f_net[4] f_net[6]
thermo_modify format float %.17g norm no
run 0
""".format(here=HERE))
back = thermo(log)[-1]
check(back["f_net[6]"] == 1 and back["E_bond"] == rows[-1]["E_bond"] and
      back["f_net[4]"] == rows[-1]["f_net[4]"],
      "after the restart: %s, before: %s" % (back, rows[-1]))

# ---- 4. bad input: named errors ---------------------------------------------------------
text = open("sag.net").read().splitlines()
k = text.index(next(l for l in text if l.startswith("bonds")))
text[k + 3] = text[k + 3].split()[0] + " 999"
open("broken.net", "w").write("\n".join(text) + "\n")
cases = [
    ("fix net net net/lsdem %s/broken.net clamp net_clamp" % HERE + "\nrun 0\n",
     r"bond 3 joins atom ID 999, which is not a ball"),
    ("group nothing id 100000\nfix net net net/lsdem %s/sag.net clamp nothing" % HERE + "\nrun 0\n",
     r"clamp group 'nothing' is empty"),
    ("bond_coeff 1 0.1 0.9 break strain 0\n", r"break strain limit \(0\) must be > 0"),
    ("bond_coeff 1 0.1 0.9 break force -1\n", r"break force limit \(-1\) must be > 0"),
]
for n, (tail, pattern) in enumerate(cases):
    rc, log = run_lmp(head("sag") + tail, expect_fail=True, cwd="bad%d" % n)
    check(rc != 0 and re.search(pattern, log), "case %d: expected an error matching '%s', got:\n%s"
          % (n, pattern, log[-600:]))

# ---- 5. grains through the net ------------------------------------------------------------
# a sphere grain (radius 0.2) falls through the middle of a square cell (spacing 1, balls of
# radius 0.1) without touching; a second one falls beside the footprint
make_ball(0.1, "small.lslib")
make_ball(0.2, "grain.lslib")
shape_tool("merge", "through.lslib", "small.lslib", "grain.lslib")
open("two.data", "w").write("""two grains

2 atoms
1 atom types

-1 9 xlo xhi
-1 4 ylo yhi
-3 3 zlo zhi

Atoms # lsdem

1 1 2 1.0 1.5 1.5 1.0 1 0 0 0
2 1 2 1.0 8.0 1.5 1.0 1 0 0 0
""")
make_net("hole", "--library", "through.lslib", "--shape", 1, "--rb", 0.1, "--lattice", "square",
         "--spacing", 1, "--size", 3, 3, "--grains", "two.data", library=None)
deck = head("hole", library="through.lslib") + """
velocity grains set 0 0 -1
fix int grains nve/lsdem
fix net net net/lsdem {here}/hole.net clamp net_clamp grains grains
timestep 0.01
variable z1 equal z[1]
thermo 10
thermo_style custom step v_z1 f_net[5] f_net[7]
thermo_modify format float %.17g
run 250
""".format(here=HERE)
rc, log = run_lmp(deck)
rows = thermo(log)
check(len(rows) == 26, "thermo rows %d" % len(rows))
for r in rows:
    if abs(r["v_z1"]) > 1e-6:
        check(r["f_net[7]"] == (1 if r["v_z1"] < 0 else 0),
              "grain at z = %g: %g grains through" % (r["v_z1"], r["f_net[7]"]))
check(all(r["f_net[5]"] == 0 for r in rows), "the net moved without contact")

finish()
