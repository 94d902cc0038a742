"""Shear bands and micro bands counted in a strain field (tools/lsdem_bands.py), on synthetic
fields of known bands: a cylinder of 22 D50 across and 36 D50 high on a grid of D50/3 (the
20,000-grain specimen's fields: 23 x 39 D50, d/3), a background of smoothed noise (the
fields' 1 d kernel; sd 0.005 about 0.05) and bands as Gaussian profiles of shear strain
across known planes (the strain of an erf displacement profile), 0.1 high, 2 D50 wide.

1. One band (dip 55 deg, azimuth 30 deg): one band found, dip within 1 deg, azimuth within
   2 deg, its length over half the specimen's diameter.
2. An X (dips 55 deg, azimuths 0 and 180 deg, crossing on the axis): one zone, two bands,
   each within 1.5 deg of its dip and 3 deg of its azimuth.
3. Three parallel micro bands (dip 60 deg; discs 10 D50 across, centred on the axis 10 D50
   apart): three bands, each within 1.5 deg of the dip.
4. A blob (a Gaussian of 3 D50 radius) and noise only: no band; the noise alone gives zones
   (the mean + 2 sd cut always leaves nodes) but none of them a band.
5. Independent of the grid: the same band on a grid of D50/2 gives the same dip within
   1 deg.
6. A barrel (strain 0.1 higher at mid-height than at the platens, parabolic in z, and 0.02
   higher on the axis than at the membrane) under a band 0.03 or 0.015 high: the detrended
   count finds one band (dip within 1.5 deg, over 20 D50 long; the weaker one in pieces
   counted once) and nothing else; without the detrending the cut keeps only the band's
   part in the barrel's belly (under 15 D50 long), or nothing.
7. A zone whose nodes lie on one line (every RANSAC draw degenerate): no sheet."""
import math
import os
import sys

import numpy as np
from scipy import ndimage

from lsdemtest import HERE, check, finish

sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import lsdem_bands  # noqa: E402

D50 = 3.0


def grid(h):
    nx, nz = int(round(24 * D50 / h)), int(round(38 * D50 / h))
    k, j, i = np.meshgrid(np.arange(nz), np.arange(nx), np.arange(nx), indexing="ij")
    origin = np.array([-12 * D50, -12 * D50, 0.0])
    x, y, z = origin[0] + h * i, origin[1] + h * j, h * k
    mask = (x * x + y * y <= (11 * D50) ** 2) & (z >= D50) & (z <= 37 * D50)
    return (x, y, z), mask, origin


def noise(shape, h, seed=3):
    r = ndimage.gaussian_filter(np.random.default_rng(seed).normal(size=shape), D50 / (2 * h))
    return 0.05 + 0.005 * r / r.std()


def normal(dip, az):
    d, a = math.radians(dip), math.radians(az)
    return np.array([math.sin(d) * math.cos(a), math.sin(d) * math.sin(a), math.cos(d)])


def band(xyz, dip, az, centre, half_length=None):
    """0.1 x a Gaussian profile (sd D50) across the plane; cut at half_length from the
    centre along the plane when given."""
    n = normal(dip, az)
    rel = [c - p for c, p in zip(xyz, centre)]
    dist = sum(r * m for r, m in zip(rel, n))
    f = 0.1 * np.exp(-0.5 * (dist / D50) ** 2)
    if half_length is not None:
        along = np.sqrt(np.maximum(sum(r * r for r in rel) - dist * dist, 0.0))
        f = f * (along <= half_length)
    return f


def find(field, mask, origin, h):
    zones, planes, _ = lsdem_bands.strain_zones(field, mask, origin, h, D50)
    return zones, planes


def angle_off(a, b):
    return abs((a - b + 180.0) % 360.0 - 180.0)


H = D50 / 3
xyz, mask, origin = grid(H)
back = noise(mask.shape, H)
mid = (0.0, 0.0, 19 * D50)

# 1. one band
zones, bands = find(back + band(xyz, 55, 30, mid), mask, origin, H)
check(len(bands) == 1, "one band: %d found" % len(bands))
if bands:
    b = bands[0]
    check(abs(b["dip"] - 55) <= 1 and angle_off(b["azimuth"], 30) <= 2 and b["length"] > 11,
          "one band: dip %.2f azimuth %.2f length %.1f D50 thickness %.2f"
          % (b["dip"], b["azimuth"], b["length"], b["thickness"]))

# 2. an X
zones, bands = find(back + np.maximum(band(xyz, 55, 0, mid), band(xyz, 55, 180, mid)),
                    mask, origin, H)
check(len(bands) == 2 and zones[0]["sheets"] == 2, "X: %d bands, %d sheets in the largest zone"
      % (len(bands), zones[0]["sheets"] if zones else 0))
got = sorted(((b["azimuth"] + 90.0) % 360.0 - 90.0, b["dip"]) for b in bands)
if len(got) == 2:
    check(all(abs(d - 55) <= 1.5 for _, d in got) and angle_off(got[0][0], 0) <= 3
          and angle_off(got[1][0], 180) <= 3, "X: (azimuth, dip) %s" % got)

# 3. three parallel micro bands
f = back.copy()
for s in (-10, 0, 10):
    f = np.maximum(f, back + band(xyz, 60, 90, (0.0, 0.0, mid[2] + s * D50), 5 * D50))
zones, bands = find(f, mask, origin, H)
check(len(bands) == 3 and all(abs(b["dip"] - 60) <= 1.5 for b in bands),
      "micro bands: %d found, dips %s, lengths %s" % (len(bands), [round(b["dip"], 1) for b in bands],
                                                     [round(b["length"], 1) for b in bands]))

# 4. a blob; noise only
r2 = sum((c - m) ** 2 for c, m in zip(xyz, mid))
zones, bands = find(back + 0.1 * np.exp(-0.5 * r2 / (3 * D50) ** 2), mask, origin, H)
check(len(bands) == 0, "blob: %d bands (largest zone %.1f x %.1f x %.1f D50)"
      % (len(bands), zones[0]["length"], zones[0]["breadth"], zones[0]["thickness"]))
zones, bands = find(back, mask, origin, H)
check(len(zones) > 10 and len(bands) == 0, "noise: %d zones, %d bands (largest %.1f D50 long)"
      % (len(zones), len(bands), zones[0]["length"]))

# 5. a coarser grid
H2 = D50 / 2
xyz2, mask2, origin2 = grid(H2)
zones, bands = find(noise(mask2.shape, H2) + band(xyz2, 55, 30, mid), mask2, origin2, H2)
check(len(bands) == 1 and abs(bands[0]["dip"] - 55) <= 1,
      "grid D50/2: %s" % [(round(b["dip"], 2), round(b["azimuth"], 1)) for b in bands])

# 6. a barrel
x, y, z = xyz
barrel = 0.1 * (1 - ((z - mid[2]) / (18 * D50)) ** 2) + 0.02 * (1 - (x * x + y * y) / (11 * D50) ** 2)
for amp in (0.03, 0.015):
    f = back + barrel + amp * band(xyz, 55, 30, mid) / 0.1
    zones, bands = find(f, mask, origin, H)
    check(len(bands) == 1 and abs(bands[0]["dip"] - 55) <= 1.5 and bands[0]["length"] > 20,
          "barrel, band %.2f, detrended: %s" % (amp, [(round(b["dip"], 2), round(b["azimuth"], 1),
                                                      round(b["length"], 1), b["pieces"]) for b in bands]))
    _, bands, _ = lsdem_bands.strain_zones(f, mask, origin, H, D50, detrend=False)
    check(all(b["length"] < 15 for b in bands), "barrel, band %.2f, not detrended: lengths %s"
          % (amp, [round(b["length"], 1) for b in bands]))

# 7. nodes on one line
line = np.array([[0.0, 0.0, float(z)] for z in range(30)])
measured, bands = lsdem_bands.zone_bands([line], 1.0, 6.0)
check(measured[0]["sheets"] == 0 and bands == [] and abs(measured[0]["length"] - math.sqrt(
    12 * np.var(line[:, 2]))) < 1e-6, "nodes on one line: no sheet, length %.3f (%s, %s)"
      % (measured[0]["length"], measured, bands))
finish()
