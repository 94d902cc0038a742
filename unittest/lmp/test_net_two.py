"""Two nets in one scene (lsdem-shape net --grains FIRST.data --name NAME): the second net
is added to the first's data file with its own atom IDs, atom types, molecule and bond
type, and its own groups; the two run side by side in one deck, each with its own fix
net/lsdem.

1. The files: the second data file holds the first's atoms and bonds unchanged and the
   new net after them (IDs, types, molecule and bond type one past the first's); the
   second .in leaves bond_style to the first and sets only its own bond type.
2. Independence: each net in the two-net deck (out of each other's reach) moves as it does
   alone in a deck of its own (net A: square, stiff, no damping, never breaks; net B:
   hexagonal, damped, bonds that break under its weight): every output of fix net/lsdem
   (anchors, strain, height, bonds broken, damping work, peak anchor force) equals the
   lone net's to round-off, at every thermo step. A second net that shared the first's
   bond type, groups or bond damping book would not.
3. The peak anchor force (output 9) is the largest |R| over every step of the run (R
   printed at every step by fix print), and above the final |R| (a net dropped under a
   sudden load overshoots its rest)."""
import math

from lsdemtest import run_lmp, check, near, finish
from net_common import HERE, make_ball, make_net

make_ball()
G = 0.2
A_ARGS = ["--lattice", "square", "--spacing", 1, "--size", 5, 4, "--rest", 0.9, "--k", 1.0,
          "--origin", 0, 0, 0]
B_ARGS = ["--lattice", "hex", "--spacing", 1, "--size", 4, 3, "--rest", 0.95, "--k", 0.3,
          "--damp", 0.05, "--mass", 0.05, "--break", "force", 0.025, "--origin", 0.5, 0, -6]

make_net("A", *A_ARGS)
make_net("B", *B_ARGS, "--grains", "A.data", "--name", "netb")
make_net("Balone", *B_ARGS)


def section(path, name, end):
    text = open(path).read().split("\n%s" % name)[1]
    text = text.split("\n%s" % end)[0] if end else text
    return [l.split() for l in text.splitlines()[1:] if l.strip()]


def header(path, key):
    for l in open(path):
        if l.strip().endswith(key):
            return int(l.split()[0])
    return None


# ---- 1. the files ----------------------------------------------------------------------
atoms_a = section("A.data", "Atoms", "Bonds")
atoms_b = section("B.data", "Atoms", "Bonds")
bonds_a = section("A.data", "Bonds", None)
bonds_b = section("B.data", "Bonds", None)
check(atoms_b[:len(atoms_a)] == atoms_a, "B.data does not begin with A.data's atoms")
check(bonds_b[:len(bonds_a)] == bonds_a, "B.data does not begin with A.data's bonds")
new_atoms, new_bonds = atoms_b[len(atoms_a):], bonds_b[len(bonds_a):]
lone_atoms = section("Balone.data", "Atoms", "Bonds")
check(len(new_atoms) == len(lone_atoms), "B adds %d balls, alone it has %d"
      % (len(new_atoms), len(lone_atoms)))
last_a = max(int(r[0]) for r in atoms_a)
check([int(r[0]) for r in new_atoms] == list(range(last_a + 1, last_a + 1 + len(new_atoms))),
      "B's atom IDs do not follow A's")
check({int(r[1]) for r in atoms_a} == {1, 2} and {int(r[1]) for r in new_atoms} == {3, 4},
      "atom types: A %s, B %s (expected 1 2 and 3 4)"
      % ({r[1] for r in atoms_a}, {r[1] for r in new_atoms}))
check({r[-1] for r in atoms_a} == {"1"} and {r[-1] for r in new_atoms} == {"2"},
      "molecules: A %s, B %s (expected 1 and 2)"
      % ({r[-1] for r in atoms_a}, {r[-1] for r in new_atoms}))
check({r[1] for r in bonds_a} == {"1"} and {r[1] for r in new_bonds} == {"2"},
      "bond types: A %s, B %s" % ({r[1] for r in bonds_a}, {r[1] for r in new_bonds}))
check([int(r[0]) for r in bonds_b] == list(range(1, len(bonds_b) + 1)), "bond IDs not 1..N")
check(header("B.data", "atoms") == len(atoms_b) and header("B.data", "bonds") == len(bonds_b)
      and header("B.data", "bond types") == 2 and header("B.data", "atom types") == 4,
      "B.data's header counts")
# the lone B's balls shifted by A's IDs: the same positions and clamps (types 1 2 -> 3 4)
for r, s in zip(new_atoms, lone_atoms):
    check(r[2:5] == s[2:5] and int(r[1]) == int(s[1]) + 2, "ball %s: %s against lone %s"
          % (r[0], r[:5], s[:5]))
b_in = open("B.in").read()
check("bond_style" not in b_in.replace("# bond_style", ""), "B.in sets bond_style again:\n"
      + b_in)
check("bond_coeff 2 0.3 0.95 damp 0.05 break force 0.025" in b_in, "B.in's bond_coeff:\n" + b_in)
check("group netb type 3 4" in b_in and "group netb_clamp type 4" in b_in,
      "B.in's groups:\n" + b_in)
# ghost cutoff: two of the longest bond (A's, 1) + 2 radii; A's own the same
check("cutoff 2.4\n" in b_in and "cutoff 2.4\n" in open("A.in").read(), "ghost cutoffs")

# ---- 2. each net as alone --------------------------------------------------------------
OUT = " ".join("f_{n}[%d]" % k for k in range(1, 11))


def deck(data, nets):
    """nets: [(prefix, name)]"""
    text = """units lj
atom_style hybrid lsdem library {here}/ball.lslib bond
boundary f f m
newton on
read_data {here}/{data}.data
""".format(here=HERE, data=data)
    for prefix, name in nets:
        text += "include {here}/{p}.in\n".format(here=HERE, p=prefix)
    text += "pair_style lsdem\npair_coeff * * 100 0 0\ntimestep 0.02\n"
    cols = []
    for prefix, name in nets:
        text += """fix int_{n} {n}_free nve/lsdem damping 0.2
fix g_{n} {n}_free gravity {g} vector 0 0 -1
fix {n} {n} net/lsdem {here}/{p}.net clamp {n}_clamp
variable r_{n} equal sqrt(f_{n}[1]^2+f_{n}[2]^2+f_{n}[3]^2)
fix pr_{n} all print 1 "$(step) $(v_r_{n}:%.17g)" file r_{n}.txt screen no
""".format(n=name, g=G, here=HERE, p=prefix)
        cols.append(OUT.format(n=name) + " v_r_%s" % name)
    text += """thermo 500
thermo_style custom step {cols}
thermo_modify format float %.17g lost/bond ignore
run 6000
""".format(cols=" ".join(cols))
    return text


def rows(log):
    """thermo rows of the run as {step: {column: value}}"""
    lines = log.splitlines()
    i = next(k for k, l in enumerate(lines) if l.split()[:1] == ["Step"])
    cols = lines[i].split()
    out = {}
    for l in lines[i + 1:]:
        v = l.split()
        if len(v) != len(cols) or not v[0].isdigit():
            break
        out[int(v[0])] = dict(zip(cols, map(float, v)))
    return out


_, log2 = run_lmp(deck("B", [("A", "net"), ("B", "netb")]), cwd="two")
_, loga = run_lmp(deck("A", [("A", "net")]), cwd="alone_a")
_, logb = run_lmp(deck("Balone", [("Balone", "net")]), cwd="alone_b")
two, alone_a, alone_b = rows(log2), rows(loga), rows(logb)
check(len(two) == 13 and two.keys() == alone_a.keys() == alone_b.keys(),
      "thermo steps %s / %s / %s" % (sorted(two), sorted(alone_a), sorted(alone_b)))
for step in sorted(two):
    for k in range(1, 11):
        for name, lone in (("net", alone_a), ("netb", alone_b)):
            a, b = two[step]["f_%s[%d]" % (name, k)], lone[step]["f_net[%d]" % k]
            near(a, b, rtol=1e-8, atol=1e-12,
                 msg="step %d: %s output %d, two nets %r, alone %r" % (step, name, k, a, b))
end = two[6000]
broken = end["f_netb[6]"]
check(broken > 0 and end["f_net[6]"] == 0,
      "bonds broken: A %g (expected 0), B %g (expected some)" % (end["f_net[6]"], broken))
check(end["f_netb[8]"] > 0 and end["f_net[8]"] == 0,
      "damping work: A %g (no damping: 0), B %g (> 0)" % (end["f_net[8]"], end["f_netb[8]"]))
print("two nets: A's anchors carry %.6g, B's %.6g with %d bonds broken; damping work %.6g"
      % (end["f_net[3]"], end["f_netb[3]"], broken, end["f_netb[8]"]))

# ---- 3. the peak anchor force ----------------------------------------------------------
for name in ("net", "netb"):
    printed = {}
    for l in open("two/r_%s.txt" % name):
        if l.strip() and not l.startswith("#"):
            s, r = l.split()
            printed[int(s)] = float(r)
    check(len(printed) >= 6000, "%s: %d steps printed" % (name, len(printed)))
    expect = max(list(printed.values()) + [two[0]["v_r_%s" % name]])
    near(end["f_%s[9]" % name], expect, rtol=1e-14,
         msg="%s: peak anchor force = the largest |R| of any step" % name)
    check(expect > 1.2 * end["v_r_%s" % name], "%s: peak %g not above the final |R| %g"
          % (name, expect, end["v_r_%s" % name]))
    print("%s: peak anchor force %.6g at step %d, final %.6g"
          % (name, expect, max(printed, key=printed.get), end["v_r_%s" % name]))
finish()
