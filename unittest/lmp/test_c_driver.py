"""The C driver (examples/c_driver) runs a scene through LAMMPS's C library interface and
reads back positions, quaternions and shape ids. Checked against a second code path: lmp
running the same deck and dumping the same fields; and 1 rank against 2 ranks."""
import os
import shutil
import subprocess

import grain_decks as gd
from lsdemtest import LMP, check, finish, mpi_prefix, near, run_lmp

HERE = os.path.dirname(os.path.abspath(__file__))
DECK = os.path.join(HERE, "..", "..", "examples", "c_driver", "in.driver")
DRIVER = os.path.join(os.path.dirname(LMP), "lsdem-c-driver")
STEPS = 300

gd.library()  # 1 ellipsoid, 2 analytic ball, 3 box
grains = [dict(id=i + 1, shape=(1, 3, 1, 2, 3)[i], density=2.0,
               x=(-9.0 + 4.5 * i, 0.3 * (i % 2), 2.5 + 0.5 * i),
               q=gd.qaxis((1, i, 2), 0.4 * i)) for i in range(5)]
gd.write_data("data.driver", grains, box=(-12.0, 12.0, -4.0, 4.0, -1.0, 8.0))
shutil.copy(DECK, "in.driver")


def driver(np):
    p = subprocess.run(mpi_prefix(np) + [DRIVER, "in.driver", str(STEPS)],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    check(p.returncode == 0, "driver on %d rank(s) exited %d: %s" % (np, p.returncode, p.stdout[-2000:]))
    rows = {}
    for line in p.stdout.splitlines():
        parts = line.split()
        if len(parts) == 9:
            rows[int(parts[0])] = (int(parts[1]), [float(v) for v in parts[2:]])
    return rows


one = driver(1)
two = driver(2)
check(sorted(one) == [g["id"] for g in grains], "driver printed every grain: %r" % sorted(one))

# second code path: the same deck in lmp, dumping id x y z and the same per-atom compute
run_lmp("include in.driver\ncompute orient all property/atom qw qx qy qz shape\n"
        "dump d all custom %d ref.dump id x y z c_orient[1] c_orient[2] c_orient[3] "
        "c_orient[4] c_orient[5]\ndump_modify d sort id format float %%.15g\nrun %d\n"
        % (STEPS, STEPS))
ref = {}
with open("ref.dump") as f:
    lines = f.read().splitlines()
start = max(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
for l in lines[start + 1:]:
    p = l.split()
    ref[int(p[0])] = (int(float(p[8])), [float(v) for v in p[1:8]])

for g in grains:
    i = g["id"]
    if i not in one or i not in ref or i not in two:
        check(False, "grain %d missing" % i)
        continue
    check(one[i][0] == g["shape"] == ref[i][0], "shape id of grain %d: driver %d, data %d, lmp %d"
          % (i, one[i][0], g["shape"], ref[i][0]))
    q = one[i][1][3:]
    near(sum(c * c for c in q), 1.0, atol=1e-12, msg="unit quaternion of grain %d" % i)
    for k in range(7):
        near(one[i][1][k], ref[i][1][k], rtol=1e-12, atol=1e-12,
             msg="driver vs lmp, grain %d field %d" % (i, k))
        near(two[i][1][k], one[i][1][k], rtol=1e-8, atol=1e-10,
             msg="driver 2 ranks vs 1 rank, grain %d field %d" % (i, k))
    # the grains fell under gravity from where they started
    check(one[i][1][2] < g["x"][2], "grain %d fell: z %g -> %g" % (i, g["x"][2], one[i][1][2]))
finish()
