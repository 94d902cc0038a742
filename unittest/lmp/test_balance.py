"""Load balancing moves grains between ranks without changing the answer (issue #23.2).

The pile of pile_deck.py falls to the floor, so that the ranks of a split along z soon
hold very different numbers of grains. Balanced by LAMMPS's own balance and fix balance
commands with the grains' node counts as weights (compute property/atom nodes, a weight
variable), it runs on 2 ranks with the shift method along z and on 4 ranks with recursive
bisection (comm_style tiled, rcb); every grain's final state, the floor's load and the
contact counts are bit-identical to the serial run's (pair states and node lists move with
their grains; the box's edges are powers of two, so that the shift balancer's conversion
of positions to box fractions and back is exact, see pile_deck.py), and the balancing did something: fix balance reports a lower imbalance
after its last rebalancing than before it, and ranks that would otherwise hold most of the
pile end up near even."""
from lsdemtest import check, finish
from pile_deck import STEPS, run, deck

WEIGHT = ("compute         nodes all property/atom nodes\n"
          "variable        w atom 10+c_nodes\n")
OUT = ("thermo_style    custom step ke c_w[2] c_w[4] f_floor[3] f_bal f_bal[3]\n"
       "thermo_modify   norm no format float %.17g\n")

CASES = {
    "shift-np2": (2, "processors      1 1 2\n",
                  WEIGHT + "fix             bal all balance 250 1.05 shift z 10 1.02 weight var w\n"),
    "rcb-np4": (4, "comm_style      tiled\n",
                WEIGHT + "fix             bal all balance 250 1.05 rcb weight var w\n"),
}

ref = run("serial", deck("oneway", STEPS), 1)
check(ref[0] is not None and ref[1][-1][2] > 200, "the serial pile ran and piled up")
for name, (np, box, balance) in CASES.items():
    atoms, rows, full = run(name, deck("oneway", STEPS, before_box=box,
                                       before_run=balance + OUT), np)
    check(atoms == ref[0], "%s: grains differ from the serial run" % name)
    check(rows == ref[1], "%s: floor load or contact counts differ:\n%s\n%s"
          % (name, rows, ref[1]))
    if check(full, "%s: no thermo output" % name):
        last = full[-1]
        check(last["f_bal"] < last["f_bal[3]"] and last["f_bal"] < 1.3,
              "%s: imbalance %g after the last rebalancing, %g before" %
              (name, last["f_bal"], last["f_bal[3]"]))
finish()
