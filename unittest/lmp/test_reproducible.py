"""The same answer on any rank count and across restarts, bit for bit (issue #22.1).

A pile of 200 angular grains falls into a box under strong gravity and piles up (grains
with several contacts, many grain-grain and wall contacts, friction history and node
lists): run on 1, 2, 3 (uneven) and 4 ranks, every grain's position, velocity, angular
velocity and orientation after 1,500 steps, and the floor's load and the contact counts
at every output step, are bit-identical (LAMMPS's own sum of the kinetic energy over ranks
agrees to round-off); so is a run stopped after 750 steps on 2 ranks and continued from
its restart file on 3; and the symmetric two-way mode on 1 and 2 ranks. Before forces were summed order-free (each contact's force and
torque rounded to a power-of-two quantum, so that every partial sum is exact), the
same deck differed between rank counts from the first output step with contacts."""
import os

from lsdemtest import run_lmp, thermo, check, near, finish, shape_tool

STEPS, HALF, EVERY = 1500, 750, 300
if not os.path.exists("pile.lslib"):
    shape_tool("random", "pile.lslib", "--count", 6, "--size", 1.0, "--size-spread", 0.2,
               "--elongation", 0.7, "--flatness", 0.7, "--angularity", 0.15,
               "--roughness", 0.02, "--seed", 11, "--nodes", 100, "--spacing", 0.06)
if not os.path.exists("pile.data"):
    shape_tool("pack", "pile.lslib", "pile.data", "--count", 200, "--box", 6, 6, 9,
               "--density", 1.0, "--seed", 5)
LIB, DATA = os.path.abspath("pile.lslib"), os.path.abspath("pile.data")

# strong gravity and a short time: the grains land within a few hundred steps
CONTACT = """pair_coeff      * * 1.0e4 0.9e4 0.5 cn 2.0
neighbor        0.1 bin
neigh_modify    delay 0 every 1 check yes
fix             floor all wall/lsdem plane 0 0 0 0 0 1 1.0e4 0.9e4 0.5 cn 2.0
fix             wx0 all wall/lsdem plane 0 0 0 1 0 0 1.0e4 0.9e4 0.5 cn 2.0
fix             wx1 all wall/lsdem plane 6 0 0 -1 0 0 1.0e4 0.9e4 0.5 cn 2.0
fix             wy0 all wall/lsdem plane 0 0 0 0 1 0 1.0e4 0.9e4 0.5 cn 2.0
fix             wy1 all wall/lsdem plane 0 6 0 0 -1 0 1.0e4 0.9e4 0.5 cn 2.0
fix             grav all gravity 100.0 vector 0 0 -1
fix             integrate all nve/lsdem damping 1.0
timestep        2.0e-4
compute         w all pair lsdem
compute         q all property/atom qw qx qy qz
thermo_style    custom step ke c_w[2] c_w[4] f_floor[3]
thermo_modify   norm no format float %.17g
thermo          {every}
"""
DUMP = ("dump            d all custom {steps} final.dump id x y z vx vy vz omegax omegay "
        "omegaz c_q[1] c_q[2] c_q[3] c_q[4]\n"
        "dump_modify     d sort id format float %.17g\n")


def deck(mode, steps, restart=None):
    return ("units lj\natom_style lsdem library %s\nboundary f f f\nnewton on\n"
            "comm_modify vel yes\nread_data %s\npair_style lsdem mode %s\n" % (LIB, DATA, mode)
            + CONTACT.format(every=EVERY) + ("" if restart else DUMP.format(steps=steps))
            + "run %d\n" % steps + ("write_restart %s\n" % restart if restart else ""))


def continued(steps):
    return ("read_restart half.restart\n" + CONTACT.format(every=EVERY)
            + DUMP.format(steps=STEPS) + "run %d\n" % steps)


def run(name, text, np):
    rc, log = run_lmp(text, np=np, cwd=os.path.abspath(name))
    dump = os.path.join(os.path.abspath(name), "final.dump")
    # the frame of the last step (a dump every STEPS steps: the run's end)
    atoms = open(dump).read().split("ITEM: ATOMS")[-1] if os.path.exists(dump) else None
    # the package's sums (the floor's load, contact counts) are exact; LAMMPS's own
    # reductions over ranks (thermo ke) sum in rank order: compared to round-off below
    rows = [(r["Step"], r["f_floor[3]"], r["c_w[2]"], r["c_w[4]"]) for r in thermo(log)]
    return atoms, rows, thermo(log)


ref_atoms, ref_rows, ref_thermo = run("oneway-np1", deck("oneway", STEPS), 1)
if check(ref_atoms and len(ref_rows) == STEPS // EVERY + 1, "the serial pile ran"):
    last = ref_thermo[-1]
    # a pile worth testing: most grains down, touching several others and the floor
    check(last["c_w[2]"] > 200 and last["c_w[4]"] > 500 and last["f_floor[3]"] < 0,
          "pile: %d contacts, %d penetrating nodes, floor %g" % (last["c_w[2]"], last["c_w[4]"],
                                                                 last["f_floor[3]"]))
for np in (2, 3, 4):
    atoms, rows, full = run("oneway-np%d" % np, deck("oneway", STEPS), np)
    check(atoms == ref_atoms, "np=%d: grains differ from the serial run" % np)
    check(rows == ref_rows, "np=%d: floor load or contacts differ from the serial run:\n%s\n%s"
          % (np, rows, ref_rows))
    for r, s0 in zip(full, ref_thermo):
        near(r["KinEng"], s0["KinEng"], rtol=1e-13, msg="np=%d step %d: ke" % (np, r["Step"]))

# stopped on 2 ranks, continued from the restart on 3
run_lmp(deck("oneway", HALF, restart="half.restart"), np=2, cwd=os.path.abspath("restart"))
atoms, rows, _ = run("restart", continued(STEPS - HALF), 3)
check(atoms == ref_atoms, "restart 2 -> 3 ranks: grains differ from the uninterrupted run")
check(rows and rows[-1] == ref_rows[-1], "restart 2 -> 3 ranks: last thermo row differs")

two1, rows1, _ = run("twoway-np1", deck("twoway", STEPS // 2), 1)
two2, rows2, _ = run("twoway-np2", deck("twoway", STEPS // 2), 2)
check(two1 and two1 == two2 and rows1 == rows2, "twoway: 2 ranks differ from 1")
finish()
