"""lsdem-rose (tools/lsdem_rose.py): spherical histograms on equal-area bins.

1. The partition (6 rings x 4 sectors, and 9 x 3): every bin's area, on the sphere
   (d_phi (cos theta_lo - cos theta_hi)) and in the Lambert azimuthal equal-area map
   (d_phi (r_hi^2 - r_lo^2) / 2, r = 2 sin(theta/2)), equals 2 pi / (K N^2) to 1e-12; the
   areas add up to the hemisphere's 2 pi; ring i has K (2i - 1) sectors covering 0-360 deg.
2. Known sets: every direction along +z or -z lands in ring 1, sector 0; along +x or -x in
   the last ring, sector 0 (an equatorial axis is taken with azimuth in [0, 180) deg); a
   uniform set -- the centres of an m x m equal-area subdivision of every bin, and their
   antipodes -- puts 2 m^2 in every bin; the bin of a direction contains it (its angles lie
   between the bin's edges) for 2,000 random directions.
3. The command on a fix network/lsdem .vtp whose normals are vertical or nearly (three cubes
   stacked, as test_fix_network_lsdem; written here in the fix's format; a downward normal
   is the same axis as the upward one): both grain lines in ring 1 sector 0, the wall lines
   left out (with --walls in too); and on a dump of long axes (columns
   c_fab[3-5]): a PNG and a CSV whose counts are those of the bins."""
import math
import os
import random
import subprocess
import sys

from lsdemtest import HERE, SHAPE_TOOL, check, finish, near

sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import lsdem_rose as rose  # noqa: E402

ROSE = os.path.join(os.path.dirname(SHAPE_TOOL), "lsdem-rose")

# 1. equal areas
for N, K in ((6, 4), (9, 3)):
    parts = rose.bins(N, K)
    want = 2 * math.pi / (K * N * N)
    worst = 0.0
    for i, j, t0, t1, p0, p1 in parts:
        sphere = (p1 - p0) * (math.cos(t0) - math.cos(t1))
        r0, r1 = 2 * math.sin(t0 / 2), 2 * math.sin(t1 / 2)
        lambert = 0.5 * (p1 - p0) * (r1 * r1 - r0 * r0)
        worst = max(worst, abs(sphere - want) / want, abs(lambert - want) / want)
    check(worst <= 1e-12, "%dx%d: bin areas within %.3g of 2 pi/(K N^2)" % (N, K, worst))
    near(sum((p1 - p0) * (math.cos(t0) - math.cos(t1)) for _, _, t0, t1, p0, p1 in parts),
         2 * math.pi, rtol=1e-12, msg="%dx%d: the hemisphere" % (N, K))
    for i in range(1, N + 1):
        ring = [b for b in parts if b[0] == i]
        check(len(ring) == K * (2 * i - 1) and ring[0][4] == 0.0
              and abs(ring[-1][5] - 2 * math.pi) < 1e-15, "%dx%d: ring %d sectors" % (N, K, i))
    near(parts[-1][3], math.pi / 2, rtol=1e-15, msg="the last ring ends at the equator")

# 2. known sets
N, K = 6, 4
check(set(rose.bin_of(v, N, K) for v in ((0, 0, 1), (0, 0, -2.5), (0.0, -0.0, -1e-3))) == {(1, 0)},
      "z axis in ring 1 sector 0")
check(set(rose.bin_of(v, N, K) for v in ((1, 0, 0), (-3, 0, 0))) == {(N, 0)},
      "x axis in ring %d sector 0" % N)
m = 3
pts = []
for i, j, t0, t1, p0, p1 in rose.bins(N, K):
    for a in range(m):
        for b in range(m):
            z = math.cos(t0) + (a + 0.5) / m * (math.cos(t1) - math.cos(t0))
            phi = p0 + (b + 0.5) / m * (p1 - p0)
            s = math.sqrt(1 - z * z)
            pts += [(s * math.cos(phi), s * math.sin(phi), z), (-s * math.cos(phi), -s * math.sin(phi), -z)]
counts = rose.histogram(pts, N, K)
check(set(counts.values()) == {2 * m * m}, "uniform set: %s per bin" % sorted(set(counts.values())))
rng = random.Random(5)
edges = {(b[0], b[1]): b[2:] for b in rose.bins(N, K)}
inside = 0
for _ in range(2000):
    v = [rng.gauss(0, 1) for _ in range(3)]
    x, y, z = rose.upper(v)
    t, p = math.acos(z), math.atan2(y, x) % (2 * math.pi)
    t0, t1, p0, p1 = edges[rose.bin_of(v, N, K)]
    inside += t0 - 1e-12 <= t <= t1 + 1e-12 and p0 - 1e-12 <= p <= p1 + 1e-12
check(inside == 2000, "random directions inside their bins: %d of 2000" % inside)

# 3. the command
VTP = """<?xml version="1.0"?>
<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
<PolyData>
<Piece NumberOfPoints="10" NumberOfVerts="0" NumberOfLines="4" NumberOfStrips="0" NumberOfPolys="0">
<CellData Scalars="normal_force">
<DataArray type="Int64" Name="id_a" format="ascii">
1
1
2
2
</DataArray>
<DataArray type="Int64" Name="id_b" format="ascii">
-1
3
-1
3
</DataArray>
<DataArray type="Float64" Name="normal" NumberOfComponents="3" format="ascii">
0 0 1
0 0 -1
0 0 1
-0.001 -0.002 -0.9999975
</DataArray>
</CellData>
</Piece>
</PolyData>
</VTKFile>
"""
open("net_4000.vtp", "w").write(VTP)
for args, n in (([], 2), (["--walls"], 4)):
    p = subprocess.run([ROSE, "normals.png", "net_4000.vtp"] + args, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    check(p.returncode == 0, "lsdem-rose on a .vtp: %s" % p.stdout)
    rows = [r.split(",") for r in open("normals.csv").read().splitlines()[1:]]
    full = {(int(r[0]), int(r[1])): int(r[7]) for r in rows if int(r[7])}
    check(full == {(1, 0): n}, "%s: normals in ring 1, sector 0: %s" % (args, full))
    check(os.path.getsize("normals.png") > 10000, "normals.png drawn")
axes = [(rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1)) for _ in range(50)]
with open("axes.dump", "w") as f:
    for step in (0, 100):   # two frames: the last is read
        f.write("ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n51\nITEM: BOX BOUNDS ff ff ff\n"
                "0 1\n0 1\n0 1\nITEM: ATOMS id c_fab[3] c_fab[4] c_fab[5]\n" % step)
        for k, v in enumerate(axes if step else [(0, 0, 1)] * 50):
            f.write("%d %r %r %r\n" % ((k + 1,) + v))
        f.write("51 0 0 0\n")    # an atom outside the compute's group
p = subprocess.run([ROSE, "axes.png", "axes.dump"], stdout=subprocess.PIPE,
                   stderr=subprocess.STDOUT, text=True)
check(p.returncode == 0, "lsdem-rose on a dump: %s" % p.stdout)
rows = [r.split(",") for r in open("axes.csv").read().splitlines()[1:]]
want = rose.histogram(axes, 6, 4)
check({(int(r[0]), int(r[1])): int(r[7]) for r in rows} == want, "dump: counts of the last frame")
near(sum(float(r[6]) for r in rows), 2 * math.pi, rtol=1e-9, msg="CSV areas")
finish()
