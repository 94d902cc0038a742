"""mode oneway picks as master the grain whose nodes resolve its partner (issue #22.2).

A cube of half-size 0.25 is dropped on a cube of half-size 2.5 resting on a floor. Both
have 200 nodes: the large cube's nodes are about 0.9 apart, farther than the small cube is
wide. With the default (master nodes) the small cube comes to rest on the large one's top
face whichever of the two has the lower ID; with the report's rule (master id) and the
large cube first it sinks into it, as before (the reason for the default). master id with
mode twoway is refused."""
import os

from lsdemtest import run_lmp, thermo, check, finish, shape_tool
from contact_decks import Grain, write_data, head

for name, half in (("small", 0.25), ("large", 2.5)):
    if not os.path.exists(name + ".lslib"):
        shape_tool("analytic", name + ".lslib", "box", half, half, half, "--spacing", half / 10,
                   "--nodes", 200)
if not os.path.exists("both.lslib"):
    shape_tool("merge", "both.lslib", "large.lslib", "small.lslib")  # shape 1 large, 2 small

TOP = 5.0  # the large cube's top face: it rests on the floor at z = 0
big = Grain((0, 0, 2.5), shape=1, density=1.0)
little = Grain((0.3, -0.2, TOP + 0.25 + 0.05), shape=2, density=1.0)


def drop(order, pair_style):
    grains = [big, little] if order == "large_first" else [little, big]
    data = write_data("%s.data" % order, (-6, 6, -6, 6, -1, 10), grains)
    deck = head("both.lslib", data, boundary="f f f") + """
pair_style %s
pair_coeff * * 2000 1800 0.5 cn 5.0
fix floor all wall/lsdem plane 0 0 0 0 0 1 2000 1800 0.5 cn 5.0
fix grav all gravity 10.0 vector 0 0 -1
fix 1 all nve/lsdem damping 2.0
variable zs equal z[%d]
thermo_style custom step v_zs
thermo 1000
timestep 1e-3
run 4000
""" % (pair_style, 2 if order == "large_first" else 1)
    name = "%s-%s" % (order, pair_style.replace(" ", "_"))
    rc, log = run_lmp(deck, cwd=os.path.abspath(name))
    rows = thermo(log)
    return rows[-1]["v_zs"] if rows else float("nan")


for order in ("large_first", "small_first"):
    z = drop(order, "lsdem")
    # resting on the top face: its centre half a side above it, less a small overlap
    check(TOP + 0.2 < z < TOP + 0.26, "master nodes, %s: the small cube's centre at z = %.4g, "
          "on the large cube it would be at %.3g" % (order, z, TOP + 0.25))
z = drop("large_first", "lsdem master id")
check(z < TOP, "master id, large cube first: the small cube did not sink (z = %.4g), "
      "the test shows nothing" % z)

rc, log = run_lmp(head("both.lslib", "large_first.data", boundary="f f f") +
                  "pair_style lsdem mode twoway master id\n", cwd=os.path.abspath("twoway_id"),
                  expect_fail=True)
check(rc != 0 and "master id is for mode oneway" in log, "master id with twoway accepted")
finish()
