"""Node lists (pair_style lsdem / fix wall/lsdem keyword nodelist) change the work, not
the result.

A frictional pile of cubes drops on a floor and on each other (many contacts start,
slide and end). The same deck runs with nodelist off, auto (the default) and an explicit
skin, serially: kinetic energy, rotational energy, the floor force and the number of
contacts after 300 steps are the same to round-off (the lists leave out only nodes that
cannot touch, so the sums are bit-identical in practice; 1e-13 allowed). With lists on,
the pair style looks up far fewer nodes (compute pair lsdem, third value). On 2 ranks
with lists, migrating grains carry their lists: the serial answer to 1e-8 (only the order
of ghost force sums differs). The contact state compute pair reports (values 5-8): every
penetrating node of a step keeps one shear entry (mu > 0 everywhere), node-list entries only
with lists, each stored pair at most one list, and the store's bytes cover what it holds
(56 bytes a shear entry, 64 a node-list entry against a grid, 80 a list head); the bytes it
reports in use (value 9) are that
count of the entries it holds, the shear entries being one a penetrating node. A bad
keyword value is named."""
import os
import random

from lsdemtest import run_lmp, thermo, check, near, finish
from contact_decks import Grain, box_library, write_data, head, quat_axis_angle, THERMO_FULL

box_library("cube.lslib", 0.5, 0.05, 600)
rng = random.Random(11)
grains = []
SP = 1.15
for k in range(3):
    for j in range(3):
        for i in range(3):
            axis = (rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))
            q = quat_axis_angle(axis, rng.uniform(-0.6, 0.6)) if k else (1, 0, 0, 0)
            v = tuple(rng.uniform(-0.5, 0.5) for _ in range(3))
            grains.append(Grain((SP * (i + 0.5), SP * (j + 0.5), 0.5 + 1e-3 + 1.2 * k),
                                q=q, v=v))
write_data("pile.data", (0, 3 * SP, 0, 3 * SP, 0, 8), grains)


def deck(nodelist):
    opt = "" if nodelist is None else " nodelist %s" % nodelist
    return head("cube.lslib", "pile.data", boundary="p p f", extra="processors * 1 1") + """
pair_style lsdem%s
pair_coeff * * 3000 2500 0.5 cn 2.0
fix grav all gravity 1.0 vector 0 0 -1
fix 1 all nve/lsdem
fix floor all wall/lsdem plane 0 0 0 0 0 1 3000 2500 0.4 cn 2.0%s
compute er all erotate/lsdem
compute w all pair lsdem
thermo_style custom step ke c_er f_floor[1] f_floor[2] f_floor[3] c_w[2] c_w[3] c_w[4] c_w[5] c_w[6] c_w[7] c_w[8] c_w[9]
%s
thermo 100
timestep 5e-4
run 300
""" % (opt, opt, THERMO_FULL)


def last_row(name, text, np=1):
    rc, log = run_lmp(text, np=np, cwd=os.path.abspath(name))
    rows = thermo(log)
    return rows[-1] if check(len(rows) == 4, "%s: thermo output missing" % name) else None


off = last_row("off", deck("off"))
auto = last_row("auto", deck(None))
skin = last_row("skin", deck("0.05"))
par = last_row("auto-np2", deck(None), np=2)
if off and auto and skin and par:
    check(off["c_w[2]"] >= 20 and off["f_floor[3]"] < 0,
          "the pile has %d contacts and floor force %g: it tests little"
          % (off["c_w[2]"], off["f_floor[3]"]))
    for name, row, tol in (("auto", auto, 1e-13), ("skin 0.05", skin, 1e-13),
                           ("auto on 2 ranks", par, 1e-8)):
        for key in ("KinEng", "c_er", "f_floor[3]"):
            near(row[key], off[key], rtol=tol, msg="%s vs off: %s" % (name, key))
        for key in ("f_floor[1]", "f_floor[2]"):
            near(row[key], off[key], atol=tol * abs(off["f_floor[3]"]),
                 msg="%s vs off: %s" % (name, key))
        check(row["c_w[2]"] == off["c_w[2]"] and row["c_w[4]"] == off["c_w[4]"],
              "%s: %d contacts / %d penetrating nodes, off %d / %d" % (
                  name, row["c_w[2]"], row["c_w[4]"], off["c_w[2]"], off["c_w[4]"]))
    for name, row in (("auto", auto), ("skin 0.05", skin)):
        check(row["c_w[3]"] < 0.5 * off["c_w[3]"],
              "%s: %d lookups, %d without lists" % (name, row["c_w[3]"], off["c_w[3]"]))

    for name, row in (("off", off), ("auto", auto), ("skin 0.05", skin), ("auto on 2 ranks", par)):
        check(row["c_w[8]"] == row["c_w[4]"], "%s: %d shear entries held for %d penetrating nodes"
              % (name, row["c_w[8]"], row["c_w[4]"]))
        check((row["c_w[7]"] > 0) == (name != "off"), "%s: %d node-list entries held"
              % (name, row["c_w[7]"]))
        check(row["c_w[6]"] >= row["c_w[2]"], "%s: %d pair states for %d contacts"
              % (name, row["c_w[6]"], row["c_w[2]"]))
        # bytes in use (value 9) against the kernel's own count: 56 a penetrating node's
        # shear entry, 64 a node-list entry (its node and cell: every partner here is a
        # grid grain), 80 a list head (at most one a pair state)
        heads = (row["c_w[9]"] - 56 * row["c_w[4]"] - 64 * row["c_w[7]"]) / 80
        if name == "off":
            check(row["c_w[9]"] == 56 * row["c_w[4]"], "off: %d bytes in use for %d shear entries"
                  % (row["c_w[9]"], row["c_w[4]"]))
        else:
            check(heads == int(heads) and row["c_w[2]"] <= heads <= row["c_w[6]"],
                  "%s: %d bytes in use: %g list heads beside %d entries, %d pair states, %d contacts"
                  % (name, row["c_w[9]"], heads, row["c_w[7]"], row["c_w[6]"], row["c_w[2]"]))
        check(row["c_w[9]"] <= row["c_w[5]"] <= 8 * row["c_w[9]"] + 2e6,
              "%s: store %d bytes reserved for %d in use" % (name, row["c_w[5]"], row["c_w[9]"]))

rc, log = run_lmp(deck("wide"), cwd=os.path.abspath("bad"), expect_fail=True)
check("nodelist must be auto, off or a skin length > 0, not wide" in log,
      "bad nodelist value not named:\n" + log[-400:])
finish()
