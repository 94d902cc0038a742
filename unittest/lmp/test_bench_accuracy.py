"""bench/accuracy.sh on a small set of level-set spheres (the error-against-cost study of
bench/README.md). Independent expectations: the exact force at overlap 0.01 R is the
small-overlap limit pi R delta^2 / 2 (kn = 1) to 1 %; the grid's surface offset is second
order in h (halving h divides it by about 4); with 4,000 nodes the measured error is what the
offset alone predicts, the overlap seen being delta + 2 offset and the force going as its
square; the finest grid is within 2 % at overlap 0.1 R; the plot is written; a bad value
is refused."""
import csv
import math
import os
import subprocess

from lsdemtest import SHAPE_TOOL, check, finish, near

RUN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench", "accuracy.sh")
env = dict(os.environ, LSDEM_BUILD_DIR=os.path.dirname(SHAPE_TOOL))
p = subprocess.run(["bash", RUN, "out", "--grids", "8,16,32", "--nodes", "4000",
                    "--overlaps", "0.01,0.1"], env=env, stdout=subprocess.PIPE,
                   stderr=subprocess.PIPE, text=True, timeout=300)
check(p.returncode == 0, "accuracy.sh failed (%d): %s%s" % (p.returncode, p.stdout[-2000:],
                                                            p.stderr[-2000:]))
rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open("out/accuracy.csv"))]
check(len(rows) == 6, "3 grids x 1 node count x 2 overlaps: %d rows" % len(rows))
row = {(r["R_over_h"], r["overlap_over_R"]): r for r in rows}

near(row[(8, 0.01)]["force_exact"], math.pi * 0.01 ** 2 / 2, rtol=0.01,
     msg="exact force at overlap 0.01 R against pi R delta^2 / 2")
offsets = [row[(rh, 0.1)]["surface_offset_over_R"] for rh in (8, 16, 32)]
check(all(o < 0 for o in offsets), "a trilinear sphere lies inside the exact one: %s" % offsets)
for coarse, fine in zip(offsets, offsets[1:]):
    check(3.0 < coarse / fine < 5.0, "surface offset second order in h: %s" % offsets)
for (rh, d), r in row.items():
    predicted = 1.0 - ((d + 2.0 * r["surface_offset_over_R"]) / d) ** 2
    near(r["err_mean"], predicted, atol=0.05,
         msg="R/h %g, overlap %g: error against the surface-offset prediction" % (rh, d))
check(row[(32, 0.1)]["err_mean"] < 0.02, "R/32, 4000 nodes, overlap 0.1 R: error %g"
      % row[(32, 0.1)]["err_mean"])
check(all(r["ns_per_test"] > 0 for r in rows), "a time per test in every row")
check(os.path.getsize("out/accuracy.png") > 10000, "the plot is written")

# a bad value stops the script (no plot of a half-empty CSV) and names the option
bad = subprocess.run(["bash", RUN, "bad", "--grids", "8,0"], env=env, stdout=subprocess.PIPE,
                     stderr=subprocess.PIPE, text=True, timeout=60)
check(bad.returncode != 0 and "bad option '--grids 8,0'" in bad.stderr
      and not os.path.exists("bad/accuracy.png"),
      "a grid resolution of 0 is refused: %d %s" % (bad.returncode, bad.stderr[-500:]))
finish()
