"""The net outputs of fix net/lsdem (anchor reaction, largest strain, residual height,
bonds broken, grains through, peak anchor force, grains before the net) and every ball's
and grain's position are bit-identical on 1, 2 and 4 ranks (4 oversubscribed), over the
first 2,500 steps of examples/net_drop (the grains land on the net from step ~1,500): bond
forces and the anchors' sum are rounded to power-of-two quanta (doc/howto_parallel.rst),
so no sum depends on the decomposition. The same on 1 and 2 ranks for the impulse method
(400 steps of 2e-3)."""
import os
import shutil

from lsdemtest import run_lmp, thermo, check, finish

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.normpath(os.path.join(HERE, "..", "..", "examples", "net_drop"))
shutil.rmtree("net_drop", ignore_errors=True)
shutil.copytree(EXAMPLE, "net_drop", ignore=shutil.ignore_patterns("out", "vtk", "log.*"))
deck = open(os.path.join("net_drop", "in.net_drop")).read()
deck = deck.replace("thermo          1000", "thermo          100")
deck = deck.replace("run             ${nsteps}",
                    "thermo_style custom step f_net[1] f_net[2] f_net[3] f_net[4] f_net[5] "
                    "f_net[6] f_net[7] f_net[9] f_net[10]\n"
                    "thermo_modify format float %.17g\nrun ${nsteps}\n"
                    "write_dump all custom end.dump id x y z vx vy vz modify sort id "
                    "format float %.17g")
open(os.path.join("net_drop", "in.test"), "w").write(deck)
out = {}
for np_ in (1, 2, 4):
    rc, log = run_lmp(os.path.abspath("net_drop/in.test"), np=np_, cwd="net_drop",
                      vars={"vtk": 0, "nsteps": 2500}, log="log.%d" % np_)
    rows = thermo(log)
    dump = open("net_drop/end.dump").read().split("ITEM: ATOMS")[1]
    out[np_] = (rows, dump)
rows1 = out[1][0]
check(len(rows1) == 26, "thermo rows on 1 rank: %d" % len(rows1))
check(any(r["f_net[5]"] < -0.1 for r in rows1), "the net did not sag")
check(rows1[-1]["f_net[9]"] > 0 and rows1[-1]["f_net[10]"] == 10,
      "peak anchor force %g, grains before the net %g (expected > 0 and all 10)"
      % (rows1[-1]["f_net[9]"], rows1[-1]["f_net[10]"]))
for np_ in (2, 4):
    check(out[np_][0] == rows1, "net outputs on %d ranks differ from 1 rank" % np_)
    check(out[np_][1] == out[1][1], "positions/velocities on %d ranks differ from 1 rank" % np_)
# the impulse method (10 times the step, to t = 0.8: past the impact), 1 against 2 ranks
imp = {}
for np_ in (1, 2):
    rc, log = run_lmp(os.path.abspath("net_drop/in.test"), np=np_, cwd="net_drop",
                      vars={"vtk": 0, "nsteps": 400, "method": "impulse", "dt": 2e-3},
                      log="log.impulse.%d" % np_)
    imp[np_] = (thermo(log), open("net_drop/end.dump").read().split("ITEM: ATOMS")[1])
check(any(r["f_net[5]"] < -0.1 for r in imp[1][0]), "impulse: the net did not sag")
check(imp[2] == imp[1], "impulse method: net outputs or atoms on 2 ranks differ from 1 rank")
print("net ranks: %d thermo rows and %d atoms compared on 1, 2, 4 ranks"
      % (len(rows1), len(out[1][1].strip().splitlines()) - 1))
finish()
