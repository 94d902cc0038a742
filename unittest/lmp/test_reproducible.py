"""The same answer on any rank count and across restarts, bit for bit (issue #22.1).

A pile of 140 angular grains falls into a box under strong gravity and piles up (grains
with several contacts, many grain-grain and wall contacts, friction history and node
lists): run on 1, 2, 3 (uneven) and 4 ranks, every grain's position, velocity, angular
velocity and orientation after 1,500 steps, and the floor's load and the contact counts
at every output step, are bit-identical (LAMMPS's own sum of the kinetic energy over ranks
agrees to round-off); so is a run stopped after 750 steps on 2 ranks and continued from
its restart file on 3; and the symmetric two-way mode on 1 and 2 ranks. Before forces
were summed order-free (each contact's force and torque rounded to a power-of-two
quantum, so that every partial sum is exact), the same deck differed between rank counts
from the first output step with contacts. The pile is pile_deck.py's."""
import os

from lsdemtest import run_lmp, check, near, finish
from pile_deck import STEPS, HALF, EVERY, run, deck, continued

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
