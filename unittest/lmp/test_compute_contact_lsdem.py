"""compute contact/lsdem and the pair's zcap and overlap report, on a little wall of
level-set cubes: cube 3 rests across cubes 1 and 2, which stand on a floor.

At rest under gravity (g = 1, unit masses):
  - local rows: the pair forces on cube 3 balance its weight, and the contact points
    lie on the interface plane between the layers; the floor's rows (other id -1) carry
    all three weights at height 0, and walls no drops them;
  - per-atom coordination (grain-grain contacts, eq 3.15): 1, 1, 2;
  - compute pair lsdem (the pair's workload counters): 2 contacts;
  - two-way mode gives two rows per contact, each carrying half of the force;
  - zcap 1 scales the two contacts of cube 3 by 1/2, so at rest they must overlap twice
    as deep to carry the same weight (linear node springs);
  - grains created overlapping by more than 5% of their size are reported at setup."""
import os

from lsdemtest import run_lmp, thermo, check, near, finish
from contact_decks import Grain, box_library, write_data, head, THERMO_FULL

lib = box_library("cube.lslib", 0.5, 0.05, 600)
write_data("wall.data", (-3, 3, -3, 3, 0, 4),
           [Grain((-0.55, 0, 0.5)), Grain((0.55, 0, 0.5)), Grain((0, 0, 1.5))])


def settle(name, pair_args):
    deck = head(lib, "wall.data", boundary="f f f") + """
pair_style lsdem %s
pair_coeff * * 1000 1000 0.5 cn 2.0
fix grav all gravity 1.0 vector 0 0 -1
fix 1 all nve/lsdem damping 4.0
fix floor all wall/lsdem plane 0 0 0 0 0 1 1000 1000 0.5 cn 2.0
compute c all contact/lsdem
compute w all pair lsdem
variable z1 equal z[1]
variable z3 equal z[3]
thermo_style custom step ke c_w[1] c_w[2] c_w[3] c_w[4] v_z1 v_z3
%s
thermo 1000
timestep 1e-3
dump rows all local 4000 rows.dump c_c[1] c_c[2] c_c[3] c_c[4] c_c[5] c_c[6] c_c[7] c_c[8] c_c[9]
compute nw all contact/lsdem walls no
dump nowall all local 4000 nowall.dump c_nw[1] c_nw[2]
dump_modify rows format float %%.17g
dump coord all custom 4000 coord.dump id c_c
run 4000
""" % (pair_args, THERMO_FULL)
    folder = os.path.abspath(name)
    rc, log = run_lmp(deck, cwd=folder)
    return thermo(log), folder, log


def last_block(path):
    """Rows of the last snapshot of a dump file, as lists of floats."""
    lines = open(path).read().splitlines()
    start = max(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS")
                or l.startswith("ITEM: ENTRIES")) + 1
    return [[float(t) for t in l.split()] for l in lines[start:]]


rows, folder, log = settle("oneway", "")
if check(len(rows) == 5, "oneway: thermo output missing"):
    last = rows[-1]
    check(last["KinEng"] < 1e-8, "oneway: the cubes did not come to rest (KE %g)" % last["KinEng"])
    near(last["c_w[2]"], 2, msg="oneway: contacts")
    check(last["c_w[1]"] >= 2 and last["c_w[3]"] >= last["c_w[4]"] > 0,
          "oneway: workload counters (pairs %g, nodes %g, penetrating %g)"
          % (last["c_w[1]"], last["c_w[3]"], last["c_w[4]"]))
    every = last_block(os.path.join(folder, "rows.dump"))
    local = [r for r in every if r[1] > 0]
    floor = [r for r in every if r[1] < 0]
    check(len(local) == 2, "oneway: %d local rows, expected 2" % len(local))
    check(sorted(int(r[0]) for r in floor) == [1, 2] and all(r[1] == -1 for r in floor),
          "oneway: floor rows %s, expected cubes 1 and 2 against wall -1" % floor)
    near(sum(r[7] for r in floor), 3.0, rtol=1e-3, msg="oneway: the floor carries 3 weights")
    check(all(abs(r[4]) < 0.01 for r in floor), "oneway: floor contact points not at z = 0")
    check(len(last_block(os.path.join(folder, "nowall.dump"))) == 2,
          "oneway: walls no still lists the floor")
    fz3 = 0.0
    for r in local:
        i, j = int(r[0]), int(r[1])
        check({i, j} in ({1, 3}, {2, 3}), "oneway: unexpected contact %d-%d" % (i, j))
        check(i < j, "oneway: master %d is not the lower ID of %d-%d" % (i, i, j))
        near(r[4], 1.0, atol=0.01, msg="oneway: contact point height of %d-%d" % (i, j))
        fz3 += -r[7] if i != 3 else r[7]   # force on cube 3 = minus the force on the master
        check(r[8] >= 10, "oneway: only %d penetrating nodes in %d-%d" % (r[8], i, j))
    near(fz3, 1.0, rtol=1e-3, msg="oneway: contact forces carry cube 3's weight")
    coord = {int(r[0]): r[1] for r in last_block(os.path.join(folder, "coord.dump"))}
    check(coord == {1: 1.0, 2: 1.0, 3: 2.0}, "oneway: coordination numbers %s" % coord)
    check("deeper than" not in log, "oneway: a gentle start was reported as overlapping")
    gap_ref = 1.0 - (last["v_z3"] - last["v_z1"])   # interface overlap without a cap

rows, folder, log = settle("twoway", "mode twoway")
if check(len(rows) == 5, "twoway: thermo output missing"):
    local = [r for r in last_block(os.path.join(folder, "rows.dump")) if r[1] > 0]
    check(len(local) == 4, "twoway: %d local rows, expected 4 (both directions)" % len(local))
    fz3 = sum((r[7] if int(r[0]) == 3 else -r[7]) for r in local)
    near(fz3, 1.0, rtol=1e-3, msg="twoway: contact forces carry cube 3's weight")
    near(rows[-1]["c_w[2]"], 2, msg="twoway: contacts (each pair counted once)")

rows, folder, log = settle("zcap", "zcap 1")
if check(len(rows) == 5, "zcap: thermo output missing"):
    local = [r for r in last_block(os.path.join(folder, "rows.dump")) if r[1] > 0]
    fz3 = sum((r[7] if int(r[0]) == 3 else -r[7]) for r in local)
    near(fz3, 1.0, rtol=1e-3, msg="zcap: the scaled forces still carry cube 3's weight")
    gap = 1.0 - (rows[-1]["v_z3"] - rows[-1]["v_z1"])
    near(gap / gap_ref, 2.0, rtol=0.05, msg="zcap 1: overlap under cube 3 vs uncapped")

# an overlapping start is reported with the grains and the depth
write_data("overlap.data", (-3, 3, -3, 3, -3, 3), [Grain((0, 0, 0)), Grain((0.9, 0, 0))])
deck = head(lib, "overlap.data", boundary="f f f") + """
pair_style lsdem
pair_coeff * * 1000 1000 0.0
run 0
"""
rc, log = run_lmp(deck, cwd=os.path.abspath("overlap"))
check("deeper than 5% of the smaller grain's equivalent radius" in log and
      "grains 1 and 2, depth 0.1" in log,
      "overlap: no warning naming grains 1 and 2 and depth 0.1:\n%s" % log[-1500:])

finish()
