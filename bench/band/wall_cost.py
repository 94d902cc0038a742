#!/usr/bin/env python3
"""What a band wall costs against a plane wall: 288 level-set cubes (300 nodes) settling on
the floor z = 0 for 6,000 steps, the floor as (1) a plane wall, (2) a flat terrain band
(spacing 0.05, width 0.1), (3) the same band with exact yes and (4) the floor kept as heights
(lsdem-shape terrain --heights, cell 0.05, width 0.1: exact distances); the runs alternate,
ROUNDS times, and the figures are lmp's loop times and their ratios to the first wall's.
With FLOOR = ridges the floor is instead 29 knife-edge ridges (triangular prisms 0.3 wide and
0.3 high, 0.4 apart, their sharp tops at z = 0 along y) as an STL mesh band, without and
with twoway yes (its sharp edges also tested against the cubes' level sets).
    python3 bench/band/wall_cost.py [ROUNDS] [BUILD_DIR] [flat|ridges]  (default 2, build/, flat)"""
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROUNDS = int(sys.argv[1]) if len(sys.argv) > 1 else 2
BUILD = os.path.abspath(sys.argv[2] if len(sys.argv) > 2 else os.path.join(HERE, "..", "..", "build"))
FLOOR = sys.argv[3] if len(sys.argv) > 3 else "flat"
os.environ.setdefault("LSDEM_LMP", os.path.join(BUILD, "lmp"))
os.environ.setdefault("LSDEM_SHAPE_TOOL", os.path.join(BUILD, "lsdem-shape"))
sys.path.insert(0, os.path.join(HERE, "..", "..", "unittest", "lmp"))
from contact_decks import Grain, box_library, write_data, head, write_ridges_stl  # noqa: E402

work = tempfile.mkdtemp(prefix="wall_cost.")
os.chdir(work)
lib = box_library("cube.lslib", 0.25, 0.025, 300)
write_data("g.data", (-6, 6, -6, 6, -1, 8),
           [Grain((-4 + 0.7 * (i % 12), -4 + 0.7 * ((i // 12) % 12), 0.3 + 0.7 * (i // 144)))
            for i in range(288)])
with open("flat.asc", "w") as f:
    f.write("ncols 49\nnrows 49\nxllcenter -6\nyllcenter -6\ncellsize 0.25\n")
    for _ in range(49):
        f.write(" ".join(["0"] * 49) + "\n")
subprocess.run([os.environ["LSDEM_SHAPE_TOOL"], "terrain", "flat.asc", "flat.band", "--spacing",
                "0.05", "--width", "0.1"], check=True, stdout=subprocess.DEVNULL)
with open("flat_fine.asc", "w") as f:  # the same floor at cell 0.05, kept as heights
    f.write("ncols 241\nnrows 241\nxllcenter -6\nyllcenter -6\ncellsize 0.05\n")
    for _ in range(241):
        f.write(" ".join(["0"] * 241) + "\n")
subprocess.run([os.environ["LSDEM_SHAPE_TOOL"], "terrain", "flat_fine.asc", "heights.band",
                "--heights", "--width", "0.1"], check=True, stdout=subprocess.DEVNULL)
WALLS = (("plane", "plane 0 0 0 0 0 1", ""), ("band", "terrain flat.band", ""),
         ("band exact", "terrain flat.band", " exact yes"), ("heights", "terrain heights.band", ""))
if FLOOR == "ridges":
    write_ridges_stl("ridges.stl", [-5.6 + 0.4 * k for k in range(29)], 5.8, half_base=0.15,
                     height=0.3)
    subprocess.run([os.environ["LSDEM_SHAPE_TOOL"], "wall", "ridges.stl", "ridges.band",
                    "--spacing", "0.05", "--width", "0.1"], check=True, stdout=subprocess.DEVNULL)
    WALLS = (("ridges", "mesh ridges.band", ""),
             ("ridges twoway", "mesh ridges.band", " twoway yes"))
times = {name: [] for name, _, _ in WALLS}
for r in range(ROUNDS):
    for name, wall, keys in WALLS:
        deck = head(lib, "g.data", boundary="f f f") + """
pair_style lsdem
pair_coeff * * 300 300 0.5 cn 0.5
fix grav all gravity 1.0 vector 0 0 -1
fix 1 all nve/lsdem damping 0.5
fix w all wall/lsdem %s 300 300 0.5 cn 0.5%s
thermo 1000
timestep 1e-3
run 6000
""" % (wall, keys)
        open("in.deck", "w").write(deck)
        subprocess.run([os.environ["LSDEM_LMP"], "-in", "in.deck", "-log", "log.deck", "-screen",
                        "none"], check=True)
        loop = [l for l in open("log.deck") if l.startswith("Loop time")][0].split()[3]
        times[name].append(float(loop))
first = times[WALLS[0][0]]
print("wall           loop time (s) per round      ratio to the %s per round" % WALLS[0][0])
for name, _, _ in WALLS:
    print("%-14s %-30s %s" % (name, " ".join("%.2f" % t for t in times[name]),
                              " ".join("%.2f" % (t / p) for t, p in zip(times[name], first))))
print("(work folder %s)" % work)
