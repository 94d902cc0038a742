"""bench/avalanche/anchor_split.py against LAMMPS: the nets' anchor reaction split into the
bonds' pull on the clamped balls and the grains' contacts on them.

The scene of test_avalanche_nets (the 100 lowest grains of examples/avalanche's source, two
nets close below them: x = -1, 0.6 high, overtopped by the flow; x = -3.5, 2.5 high),
penalty, 5,400 steps on 1 rank (t = 1.5: the flow is on net 1), the balls dumped at each of
the last 20 steps (in.avalanche -var netsteps -var netfrom). anchor_split.py recomputes the
bonds' part from the dumped positions and velocities. The expectation is LAMMPS's own: after
the run, `run 0` with the grains' contacts on the clamped balls excluded (neigh_modify
exclude) leaves only the bond forces on them, and fix net/lsdem's outputs 1-3 then give the
bonds' reaction at the last step: the script's must equal it (to 1e-6, or 1e-3 for the
unloaded net 2: the dump's digits). And the split must
matter: at that step the grains' contacts are more than 1 % of net 1's reaction."""
import os
import subprocess
import sys

import numpy as np

from lsdemtest import HERE, check, near, finish, run_lmp
from avalanche_scene import EX, make_scene

TOP = os.path.normpath(os.path.join(HERE, "..", ".."))
NGRAINS, NSTEPS, WINDOW, DT = 100, 5400, 20, 0.00028
make_scene(NGRAINS)

# the example's deck, then the bonds' reaction at its last step from LAMMPS
with open("in.split", "w") as f:
    f.write("include %s\n" % os.path.join(EX, "in.avalanche"))
    f.write("neigh_modify exclude group grains net1_clamp exclude group grains net2_clamp\n")
    f.write("run 0 post no\n")
    for n in (1, 2):
        f.write('print "bonds %d $(f_net%d[1]:%%.12g) $(f_net%d[2]:%%.12g) $(f_net%d[3]:%%.12g)"\n'
                % (n, n, n, n))
rc, log = run_lmp("in.split", vars={"nets": 2, "dt": DT, "nsteps": NSTEPS, "vtkevery": 10,
                                    "netsteps": WINDOW - 1,
                                    "netfrom": "%.10g" % ((NSTEPS - WINDOW + 1) * DT)})
check(rc == 0, "lmp failed")
lammps = {int(l.split()[1]): np.linalg.norm([float(v) for v in l.split()[2:5]])
          for l in log.splitlines() if l.startswith("bonds ")}
check(set(lammps) == {1, 2}, "the deck's bonds-only reactions were not printed")

p = subprocess.run([sys.executable, os.path.join(TOP, "bench", "avalanche", "anchor_split.py"),
                    ".", "2"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
check(p.returncode == 0, "anchor_split.py failed:\n" + p.stdout)
print(p.stdout.strip())
text = [l.split() for l in open("anchor_split.csv") if l.strip()]
split = [dict(zip(text[0], map(float, r))) for r in text[1:]]
check(len(split) == WINDOW and int(split[-1]["step"]) == NSTEPS,
      "anchor_split.csv: %d rows ending at step %g, expected %d ending at %d"
      % (len(split), split[-1]["step"], WINDOW, NSTEPS))
last = split[-1]
for n in (1, 2):
    # atol: the dump's 10 digits of the positions, times k = 5,000 over some 250 bonds
    near(last["bonds_%d" % n], lammps[n], rtol=1e-6, atol=1e-3,
         msg="net %d: the script's bonds' part = LAMMPS's reaction with the contacts excluded" % n)
    print("net %d at step %d: total %.6g, bonds' part %.6g (LAMMPS %.6g)"
          % (n, NSTEPS, last["total_%d" % n], last["bonds_%d" % n], lammps[n]))
check(abs(last["total_1"] - last["bonds_1"]) > 0.01 * last["total_1"],
      "net 1: the grains' contacts on the clamped balls are under 1 %% of its reaction "
      "(total %g, bonds %g): the check above does not test the split" % (last["total_1"],
                                                                       last["bonds_1"]))
finish()
