"""The small avalanche scene of the nets tests (test_avalanche_nets,
test_avalanche_anchor_split): the NGRAINS lowest grains of examples/avalanche's source and
two nets close below them (make_nets.sh: x = -1, 0.6 high, which the flow overtops; x = -3.5,
2.5 high), written into the current folder with the example's shapes and terrain."""
import os
import shutil
import subprocess

from lsdemtest import HERE, SHAPE_TOOL, check

EX = os.path.normpath(os.path.join(HERE, "..", "..", "examples", "avalanche"))


def make_scene(ngrains):
    """source.data (the ngrains lowest grains), net1/net2 files; returns make_nets.sh's
    output (check() records a failure)."""
    for f in ("grains.lslib", "valley.band", "valley.asc"):
        shutil.copy(os.path.join(EX, f), f)
    lines = open(os.path.join(EX, "source.data")).read().split("\n")
    a = lines.index("Atoms # lsdem")
    rows = [l.split() for l in lines[a + 2:] if l.strip()]
    rows = sorted(rows, key=lambda r: float(r[4]))[:ngrains]
    head = "\n".join(lines[:a]).replace("400 atoms", "%d atoms" % ngrains)
    with open("source.data", "w") as f:
        f.write(head + "\nAtoms # lsdem\n\n")
        for i, r in enumerate(rows):
            f.write(" ".join([str(i + 1)] + r[1:]) + "\n")
    p = subprocess.run(["bash", os.path.join(EX, "make_nets.sh"), ".", "2", "-1", "-3.5", "0.6",
                        "2.5"], env=dict(os.environ, LSDEM_SHAPE_TOOL=SHAPE_TOOL),
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    check(p.returncode == 0, "make_nets.sh failed:\n" + p.stdout)
    return p.stdout.strip()
