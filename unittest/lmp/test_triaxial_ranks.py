"""Triaxial acceptance: results on 1 and 2 ranks are identical for the first hundred steps
(to 1e-8) on a real specimen. The specimen is made by the example's own run.sh (small: 120
grains, a short preparation, a tiny final strain); then the example's in.triaxial, cut after
its consolidation `run`, runs 100 steps on 1 and on 2 ranks and every thermo column is
compared. Label 'long' (about two minutes): CI skips it."""
import os
import subprocess

from lsdemtest import LMP, SHAPE_TOOL, check, finish, near, run_lmp, thermo

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.join(HERE, "..", "..", "examples", "triaxial")
spec = os.path.abspath("specimen")

env = dict(os.environ, OUT=spec, NP="2", NGRAINS="120", NPREP="1500", EPSMAX="0.001",
           LSDEM_LMP=LMP, LSDEM_SHAPE_TOOL=SHAPE_TOOL)
p = subprocess.run(["bash", os.path.join(EXAMPLE, "run.sh")], env=env, stdout=subprocess.PIPE,
                   stderr=subprocess.STDOUT, text=True, timeout=1200)
check(p.returncode == 0, "examples/triaxial/run.sh failed (%d): %s" % (p.returncode, p.stdout[-3000:]))

# the example's deck up to and including the consolidation run, thermo at full precision
deck = []
for line in open(os.path.join(EXAMPLE, "in.triaxial")):
    if line.startswith("thermo_modify"):
        line = line.rstrip("\n") + " format float %.15g\n"
    deck.append(line)
    if line.split()[:2] == ["run", "${ncons}"]:
        break
check(any(l.startswith("run") for l in deck), "in.triaxial has a consolidation run")
with open(os.path.join(spec, "in.cut"), "w") as f:
    f.writelines(deck)

vars = dict(lib="all.lslib", data="mem.data", memin="mem.in", memtri="mem.tri", ncons=100,
            every=20)
rows = {}
for np in (1, 2):
    rc, log = run_lmp(os.path.join(spec, "in.cut"), np=np, vars=vars, cwd=spec,
                      log="log.ranks%d" % np)
    rows[np] = thermo(log)
check(len(rows[1]) == len(rows[2]) == 6, "thermo rows: %d and %d" % (len(rows[1]), len(rows[2])))
for r1, r2 in zip(rows[1], rows[2]):
    for key in r1:
        near(r2[key], r1[key], rtol=1e-8, atol=1e-12,
             msg="step %d, %s: 2 ranks vs 1 rank" % (r1["Step"], key))
# the specimen is loaded: the platen and membrane stresses are non-zero after 100 steps
check(any(abs(v) > 0 for k, v in rows[1][-1].items() if k != "Step"), "non-trivial state")
finish()
