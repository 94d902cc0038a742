"""pair_style lsdem, fix wall/lsdem, compute contact/lsdem: wrong setups stop with a
message that says what to add or fix; a number too large for a double (1e400, read as inf)
in any numeric argument of the styles is refused naming the style and the keyword. And an error raised on one rank by LAMMPS itself
(error->one, which ends in MPI_Abort) still reaches the log file, with the log lines before
it (src/PKG-LSDEM/abort_flush.cpp)."""
import os

from lsdemtest import run_lmp, check, finish, near, thermo
from contact_decks import Grain, box_library, write_data, head

lib = box_library("cube.lslib", 0.5, 0.05, 600)
write_data("one.data", (-3, 3, -3, 3, -3, 3), [Grain((0, 0, 0))])
good = head(lib, "one.data", boundary="f f f")
write_data("narrow.data", (-0.7, 0.7, -3, 3, -3, 3), [Grain((0, 0, 0))])  # cube R = 0.87

CASES = [
    ("newton", good.replace("newton on", "newton off") +
     "pair_style lsdem\npair_coeff * * 1 1 0\nrun 0\n", "add 'newton on'"),
    ("ghostvel", good.replace("comm_modify vel yes", "comm_modify vel no") +
     "pair_style lsdem\npair_coeff * * 1 1 0\nrun 0\n", "add 'comm_modify vel yes'"),
    ("mode", good + "pair_style lsdem mode both\n", "mode must be oneway or twoway"),
    ("keyword", good + "pair_style lsdem damping 2\n", "unknown keyword damping"),
    ("coeff", good + "pair_style lsdem\npair_coeff * * -1 1 0\n", "need kn > 0"),
    ("coeffvalue", good + "pair_style lsdem\npair_coeff * * 1 1 0.5 ct -2\n",
     "got kn = 1, ks = 1, mu = 0.5, cn = 0, ct = -2"),
    ("wallzero", good + "fix w all wall/lsdem plane 0 0 0 0 0 0 1 1 0\n",
     "plane normal must be finite and not zero"),
    ("wallvalue", good + "fix w all wall/lsdem plane 0 0 0 0 0 1 1 1 -0.1\n",
     "fix wall/lsdem: need kn > 0 and ks, mu, cn, ct >= 0; got kn = 1, ks = 1, mu = -0.1"),
    ("dimension", good.replace("units lj", "units lj\ndimension 2").replace(
        "boundary f f f", "boundary f f p") + "pair_style lsdem\npair_coeff * * 1 1 0\nrun 0\n",
     "atom_style lsdem needs a 3d simulation"),
    ("wallkind", good + "fix w all wall/lsdem sphere 0 0 0 1 1 1 0\n",
     "unknown wall sphere"),
    ("wallaxis", good + "fix w all wall/lsdem plane 0 0 0 0 0 1 1 1 0 axis x\n",
     "axis is for cylinder walls"),
    ("periodic", head(lib, "narrow.data", boundary="p f f") +
     "pair_style lsdem\npair_coeff * * 1 1 0\nrun 0\n", "periodic box is 1.4 long in x"),
    ("compute", good + "pair_style zero 1.0\npair_coeff * *\n"
     "compute c all contact/lsdem\ndump d all custom 1 d.dump id c_c\nrun 0\n",
     "requires pair_style lsdem"),
]
# a number too large for a double (read as inf) is refused by name, in every numeric
# argument of every style (#22.6); BIG is 1e400
BIG = "1e400"
pair = "pair_style lsdem\npair_coeff * * 1 1 0\n"
NONFINITE = [
    ("kn", pair.replace("* * 1 1 0", "* * %s 1e4 0.5" % BIG), "pair_coeff for lsdem: kn = 1e400"),
    ("ks", pair.replace("* * 1 1 0", "* * 1 %s 0.5" % BIG), "pair_coeff for lsdem: ks = 1e400"),
    ("mu", pair.replace("* * 1 1 0", "* * 1 1 %s" % BIG), "pair_coeff for lsdem: mu = 1e400"),
    ("cn", pair.replace("* * 1 1 0", "* * 1 1 0 cn %s" % BIG), "pair_coeff for lsdem: cn = 1e400"),
    ("ct", pair.replace("* * 1 1 0", "* * 1 1 0 ct %s" % BIG), "pair_coeff for lsdem: ct = 1e400"),
    ("nodelist", "pair_style lsdem nodelist %s\n" % BIG, "pair_style lsdem: nodelist = 1e400"),
    ("wallkn", "fix w all wall/lsdem plane 0 0 0 0 0 1 %s 1 0\n" % BIG, "fix wall/lsdem: kn = 1e400"),
    ("wallgeom", "fix w all wall/lsdem plane 0 0 %s 0 0 1 1 1 0\n" % BIG,
     "fix wall/lsdem: the wall geometry = 1e400"),
    ("wallvel", "fix w all wall/lsdem plane 0 0 0 0 0 1 1 1 0 velocity 0 0 %s\n" % BIG,
     "fix wall/lsdem: velocity = 1e400"),
    ("wallcn", "fix w all wall/lsdem plane 0 0 0 0 0 1 1 1 0 cn %s\n" % BIG,
     "fix wall/lsdem: cn = 1e400"),
    ("pivot", "fix w all wall/lsdem plane 0 0 0 0 0 1 1 1 0 pivot 1 %s\n" % BIG,
     "fix wall/lsdem: pivot I = 1e400"),
    ("damping", "fix n all nve/lsdem damping %s\n" % BIG, "fix nve/lsdem: damping = 1e400"),
    ("stress", "compute s all stress/lsdem volume %s\n" % BIG,
     "compute stress/lsdem: volume = 1e400"),
    ("inertial", "compute s all inertial/lsdem %s 1.0\n" % BIG,
     "compute inertial/lsdem: RATE or PRESSURE = 1e400"),
    ("vtk", "dump d all lsdem/vtk 10 vtk spacing %s\n" % BIG, "dump lsdem/vtk: spacing = 1e400"),
    ("membrane", "fix m all membrane/lsdem pressure %s triangles none\n" % BIG,
     "fix membrane/lsdem: pressure = 1e400"),
    ("knb", "fix m all membrane/lsdem pressure 1 triangles none knb %s\n" % BIG,
     "fix membrane/lsdem: knb = 1e400"),
]
for name, lines, expect in NONFINITE:
    CASES.append(("inf_" + name, good + lines, expect + " is not a finite number"))

for name, deck, expect in CASES:
    rc, log = run_lmp(deck, cwd=os.path.abspath(name), expect_fail=True)
    check(rc != 0 and expect in log, "%s: expected an error containing %r, got rc %d:\n%s"
          % (name, expect, rc, log[-800:]))

# a plane normal given with huge components is normalised without overflow: (0, 1, 1)/sqrt 2
rc, log = run_lmp(good + "fix w all wall/lsdem plane 0 0 -2 0 1e200 1e200 1 1 0\n"
                  "thermo_style custom step f_w[7] f_w[8] f_w[9]\n"
                  "thermo_modify format float %.17g\nrun 0\n", cwd=os.path.abspath("wallhuge"))
rows = thermo(log)
if check(len(rows) == 1, "huge normal: one thermo row"):
    for k, want in ((7, 0.0), (8, 0.5 ** 0.5), (9, 0.5 ** 0.5)):
        near(rows[0]["f_w[%d]" % k], want, atol=1e-15, msg="huge normal component %d" % (k - 6))

# a word where the data file wants a density: LAMMPS's own reader stops in error->one
good_data = open("one.data").read()
with open("bad.data", "w") as f:
    f.write(good_data.replace("\n1 1 1 1.0 ", "\n1 1 1 abc "))
check(open("bad.data").read() != good_data, "the density field of atom 1 was replaced")
deck = head(lib, "bad.data", boundary="f f f").replace(
    "read_data", 'print "before the data file"\nread_data')
rc, _ = run_lmp(deck, cwd=os.path.abspath("one_rank"), expect_fail=True)
logged = open(os.path.join("one_rank", "log.lammps")).read()
check(rc != 0 and "before the data file" in logged
      and "Expected floating point parameter instead of 'abc'" in logged,
      "error->one of LAMMPS itself lost from the log: rc %d, log:\n%s" % (rc, logged[-600:]))

finish()
