"""pair_style lsdem, fix wall/lsdem, compute contact/lsdem: wrong setups stop with a
message that says what to add or fix."""
import os

from lsdemtest import run_lmp, check, finish
from contact_decks import Grain, box_library, write_data, head

lib = box_library("cube.lslib", 0.5, 0.05, 600)
write_data("one.data", (-3, 3, -3, 3, -3, 3), [Grain((0, 0, 0))])
good = head(lib, "one.data", boundary="f f f")

CASES = [
    ("newton", good.replace("newton on", "newton off") +
     "pair_style lsdem\npair_coeff * * 1 1 0\nrun 0\n", "add 'newton on'"),
    ("ghostvel", good.replace("comm_modify vel yes", "comm_modify vel no") +
     "pair_style lsdem\npair_coeff * * 1 1 0\nrun 0\n", "add 'comm_modify vel yes'"),
    ("mode", good + "pair_style lsdem mode both\n", "mode must be oneway or twoway"),
    ("keyword", good + "pair_style lsdem damping 2\n", "unknown keyword damping"),
    ("coeff", good + "pair_style lsdem\npair_coeff * * -1 1 0\n", "need kn > 0"),
    ("wallkind", good + "fix w all wall/lsdem sphere 0 0 0 1 1 1 0\n",
     "unknown wall sphere"),
    ("wallaxis", good + "fix w all wall/lsdem plane 0 0 0 0 0 1 1 1 0 axis x\n",
     "axis is for cylinder walls"),
    ("compute", good + "pair_style zero 1.0\npair_coeff * *\n"
     "compute c all contact/lsdem\ndump d all custom 1 d.dump id c_c\nrun 0\n",
     "requires pair_style lsdem"),
]
for name, deck, expect in CASES:
    rc, log = run_lmp(deck, cwd=os.path.abspath(name), expect_fail=True)
    check(rc != 0 and expect in log, "%s: expected an error containing %r, got rc %d:\n%s"
          % (name, expect, rc, log[-800:]))

finish()
