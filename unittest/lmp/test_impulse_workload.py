"""compute pair on pair_style lsdem/impulse: its 9 values are pair_style lsdem's (the same
detection, a second code path). The angular pile is dropped into its box for 300 steps by the
impulse method and written out; from that state a run of 0 steps with each style (node lists
on, as both default) counts the same contact tests, touching pairs, node lookups and
penetrating nodes, and both keep node lists in their history store (values 5-7 and 9 positive, list entries
held the same); only the penalty style keeps shear springs (value 8). After a further step of the impulse run the values are those
of that step's detection (they change as the pile moves), and on a step that tallies no
energy compute pair is not asked (LAMMPS's rule), so the values stay numbers, never NaN."""
from grain_decks import pile
from impulse_decks import header
from lsdemtest import run_lmp, thermo, check, finish

lib, data = pile()

WALLS = """fix floor all wall/lsdem plane 0 0 0 0 0 1 1.0e4 0 0.5
fix wx0 all wall/lsdem plane 0 0 0 1 0 0 1.0e4 0 0.5
fix wx1 all wall/lsdem plane 6 0 0 -1 0 0 1.0e4 0 0.5
fix wy0 all wall/lsdem plane 0 0 0 0 1 0 1.0e4 0 0.5
fix wy1 all wall/lsdem plane 0 6 0 0 -1 0 1.0e4 0 0.5
"""
COLUMNS = "step c_w[1] c_w[2] c_w[3] c_w[4] c_w[5] c_w[6] c_w[7] c_w[8] c_w[9]"

drop = (header(lib, data) + WALLS
        + "fix grav all gravity 100.0 vector 0 0 -1\n"
        + "fix imp all impulse/lsdem 0.5 0.5 damping 1.0\ntimestep 1e-3\n"
        + "run 300\nwrite_data piled.data\n")
run_lmp(drop, log="log.drop")

impulse = (header(lib, "piled.data") + WALLS
           + "fix grav all gravity 100.0 vector 0 0 -1\n"
           + "fix imp all impulse/lsdem 0.5 0.5 damping 1.0\ntimestep 1e-3\n"
           + "compute w all pair lsdem/impulse\nthermo_style custom %s\n" % COLUMNS
           + "thermo_modify norm no format float %.17g\nthermo 1\nrun 0\nrun 1\n")
penalty = (header(lib, "piled.data").replace("pair_style lsdem/impulse\npair_coeff * *",
                                             "pair_style lsdem\npair_coeff * * 1.0e4 0 0.5")
           + "compute w all pair lsdem\nthermo_style custom %s\n" % COLUMNS
           + "thermo_modify norm no format float %.17g\nrun 0\n")
imp_log = run_lmp(impulse, log="log.impulse")[1]
pen = thermo(run_lmp(penalty, log="log.penalty")[1])[0]
start, later = thermo(imp_log, 0)[0], thermo(imp_log, 1)[-1]
names = ["contact tests", "touching pairs", "node lookups", "penetrating nodes"]
for k, name in enumerate(names):
    col = "c_w[%d]" % (k + 1)
    check(start[col] == pen[col], "%s: impulse %g, penalty %g" % (name, start[col], pen[col]))
check(pen["c_w[2]"] > 20 and pen["c_w[4]"] > pen["c_w[2]"],
      "the piled grains touch: %g pairs, %g nodes" % (pen["c_w[2]"], pen["c_w[4]"]))
for k in (5, 6, 7, 9):
    col = "c_w[%d]" % k
    check(start[col] > 0 and pen[col] > 0, "%s held: impulse %g, penalty %g"
          % (col, start[col], pen[col]))
check(start["c_w[8]"] == 0 and pen["c_w[8]"] > 0, "shear entries: the impulse style keeps "
      "none (its friction is in the fix's impulses), %g; the penalty style %g"
      % (start["c_w[8]"], pen["c_w[8]"]))
check(start["c_w[7]"] == pen["c_w[7]"], "node-list entries held: impulse %g, penalty %g"
      % (start["c_w[7]"], pen["c_w[7]"]))
check(later["Step"] == start["Step"] + 1 and later["c_w[1]"] > 0 and
      any(later["c_w[%d]" % k] != start["c_w[%d]" % k] for k in (3, 4)),
      "the next step's detection: %s against %s" % (later, start))
finish()
