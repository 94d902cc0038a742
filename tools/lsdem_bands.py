"""Counting shear bands and micro bands in a strain field (report §3.5.3: "micro bands" at
5 % axial strain, more at 10 %, one band at the critical state), shared by
examples/triaxial/figures.py and its test.

    zones, planes, cut = strain_zones(shear, mask, origin, h, d50, k=2.0)

shear: a scalar field on a regular grid as (nz, ny, nx) -- fix field/lsdem's von Mises
shear strain; mask: the nodes to use (its `inside` and `regular`); origin: world position
of node (0, 0, 0); h: grid spacing (the same along x, y, z; distance units); d50: the
length the sizes are given in.

The method. A triaxial specimen barrels: its strain is largest at mid-height and smallest at
the platens, a smooth trend that a plain cut would take for a horizontal band. So the
trend is removed first (detrend, default on): the least-squares fit of a polynomial of
degree 4 in z and 2 in r^2 about the specimen's axis. The localised nodes are then the
masked nodes whose value exceeds mean + k sd of the masked nodes (k = 2: the cut compute
shearband/lsdem puts on its grains). They are grouped
into zones by 26-connectivity (scipy.ndimage.label). Each zone's nodes are fitted by their
principal axes (covariance eigenvalues l1 >= l2 >= l3); a uniformly filled box of sides
L has variance L^2 / 12 along each, so the zone's length, breadth and thickness are
sqrt(12 l), in D50. The normal is the axis of l3 (n_z >= 0); dip = arccos n_z and azimuth
= the direction of (n_x, n_y) from +x counterclockwise, as compute shearband/lsdem's.
The geometry (principal sizes, the sheets' RANSAC and refits, the joining of pieces) is the
core's (lsdem_point_sizes, lsdem_sheets_fit, lsdem_sheets_join in
src/PKG-LSDEM/core/specimen/shearband.c, the RANSAC and least-squares refit compute
shearband/lsdem uses), reached through `lsdem-shape bands`: found as $LSDEM_SHAPE_TOOL,
else in $LSDEM_BUILD_DIR or the repository's build/, else on the PATH. This module does the
field's part: the trend, the cut and the zones.

Crossing bands touch, so one zone can hold several, and a weak band breaks under the cut
into several zones. So sheets are sought in every zone at least min_length / 2 long by
sequential RANSAC: the plane (through three of its nodes, 400 deterministic draws; then
refitted to the principal axes of its nodes within 3 tol until that set no longer changes)
with the most nodes within tol
D50 of it (default 1) is a **sheet** when its inliers are at least min_length / 2 long and
their breadth is at least aspect x the thickness of the zone's nodes within 3 tol of the
plane (a sheet, not a rod or a blob); those nodes are set aside and the next plane sought
in the rest, until one fails. Sheets of all zones whose normals lie within 10 deg of one
another and whose centres lie within 2 tol of one another's plane are pieces of one plane;
each plane, its pieces' nodes refitted together, is a **band** when at least min_length D50
long. Defaults: min_length 6 D50, aspect 2, tol 1 D50. Why: smoothed noise (the fields'
1 d Gaussian kernel) cut at mean + 2 sd leaves worm-like zones up to 5.6 D50 long, under
3 D50 broad and about as thick as broad (rods; unittest/lmp/test_band_zones.py); a blob is
as thick as broad. The report counts micro bands by eye on its strain pictures; this count
is the rule above, and each zone's and band's sizes are returned so another rule can be
applied."""
import os
import shutil
import subprocess
import tempfile

import numpy as np
from scipy import ndimage

MIN_LENGTH = 6.0   # D50
ASPECT = 2.0       # breadth / thickness
TOL = 1.0          # D50, the slab half-width of a plane's inliers
DRAWS = 400


def shape_tool():
    """The lsdem-shape executable (module docstring)."""
    if os.environ.get("LSDEM_SHAPE_TOOL"):
        return os.environ["LSDEM_SHAPE_TOOL"]
    here = os.path.dirname(os.path.abspath(__file__))
    for build in (os.environ.get("LSDEM_BUILD_DIR"), os.path.join(here, "..", "build")):
        if build and os.access(os.path.join(build, "lsdem-shape"), os.X_OK):
            return os.path.join(build, "lsdem-shape")
    found = shutil.which("lsdem-shape")
    if not found:
        raise RuntimeError("lsdem_bands: cannot find lsdem-shape (build LSDEM first, or set "
                           "LSDEM_SHAPE_TOOL)")
    return found


def zone_bands(zones, tol, min_length, aspect=ASPECT, seed=1):
    """The core's measure of zones of node positions (a list of (m, 3) arrays, distance
    units): per zone (length, breadth, thickness, dip, azimuth, centre, sheets), then the
    bands of their sheets joined across zones (dicts of nodes, pieces, normal, centre, length,
    breadth, thickness, dip, azimuth: distance units and degrees). lsdem-shape bands."""
    rec = np.concatenate([np.column_stack([np.full(len(z), k, float), z]) for k, z in
                          enumerate(zones)]) if zones else np.zeros((0, 4))
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "points.f64")
        rec.astype("<f8").tofile(path)
        p = subprocess.run([shape_tool(), "bands", path, "--tol", repr(tol), "--min-length",
                            repr(min_length), "--aspect", repr(aspect), "--samples",
                            str(DRAWS), "--seed", str(seed)], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        raise RuntimeError("lsdem-shape bands failed: " + p.stderr.strip())
    measured, bands = [], []
    for line in p.stdout.splitlines():
        kind, item = parse_line(line.split())
        (measured if kind == "zone" else bands).append(item)
    return measured, bands


def parse_line(words):
    """A line of lsdem-shape bands: its kind (zone, band) and its values (numbers; centre
    and normal as arrays; counts as ints)."""
    kind, i, item = words[0], 2 if words[0] == "zone" else 1, {}
    while i < len(words):
        key = words[i]
        if key in ("centre", "normal"):
            item[key] = np.array([float(v) for v in words[i + 1:i + 4]])
            i += 4
        else:
            item[key] = int(words[i + 1]) if key in ("nodes", "sheets", "pieces") else \
                float(words[i + 1])
            i += 2
    return kind, item


def axisymmetric_trend(shear, mask, origin, h):
    """The least-squares fit to the masked values of a polynomial of degree 4 in z and 2 in
    r^2 (r from the masked nodes' mean x, y): the barrel's smooth trend (strain largest at
    mid-height, smallest at the platens), as a field of shear's shape."""
    nz, ny, nx = shear.shape
    k, j, i = np.indices(shear.shape)
    x, y = origin[0] + h * i, origin[1] + h * j
    z = (k - 0.5 * (nz - 1)) / max(nz - 1, 1)
    r2 = ((x - x[mask].mean()) ** 2 + (y - y[mask].mean()) ** 2) / max(nx * ny * h * h, 1e-300)
    basis = [z ** a * r2 ** b for a in range(5) for b in range(3)]
    coef = np.linalg.lstsq(np.stack([f[mask] for f in basis], axis=1), shear[mask],
                           rcond=None)[0]
    return sum(c * f for c, f in zip(coef, basis))


def strain_zones(shear, mask, origin, h, d50, k=2.0, min_length=MIN_LENGTH, aspect=ASPECT,
                 tol=TOL, detrend=True, seed=1):
    """The localised zones and bands of a field (module docstring), as (zones, bands, cut):
    zones largest first, each a dict of nodes, volume (D50^3), length, breadth, thickness
    (D50), dip, azimuth (deg), centre (world) and the number of sheets found in it; bands
    largest group first, dicts of nodes, pieces, normal, centre, length, breadth, thickness
    (D50), dip, azimuth (deg); cut the value above which a node is localised (of the field
    less its axisymmetric trend with detrend)."""
    if detrend:
        shear = shear - axisymmetric_trend(shear, mask, origin, h)
    values = shear[mask]
    cut = values.mean() + k * values.std()
    labels, count = ndimage.label(mask & (shear > cut), structure=np.ones((3, 3, 3), bool))
    order = np.argsort(labels, axis=None, kind="stable")
    starts = np.searchsorted(labels.ravel()[order], np.arange(1, count + 2))
    points = []
    for lab in range(1, count + 1):
        kk, jj, ii = np.unravel_index(order[starts[lab - 1]:starts[lab]], shear.shape)
        points.append(np.asarray(origin, float) + h * np.stack([ii, jj, kk], axis=1))
    measured, bands = zone_bands(points, tol * d50, min_length * d50, aspect, seed)
    zones = []
    for pts, z in zip(points, measured):
        single = len(pts) == 1  # no extent: a node's own size
        zones.append({"nodes": len(pts), "volume": len(pts) * h ** 3 / d50 ** 3,
                      "length": (h if single else z["length"]) / d50,
                      "breadth": (h if single else z["breadth"]) / d50,
                      "thickness": (h if single else z["thickness"]) / d50,
                      "dip": z["dip"], "azimuth": z["azimuth"], "centre": pts.mean(axis=0),
                      "sheets": z["sheets"]})
    zones.sort(key=lambda z: -z["nodes"])
    for b in bands:
        for key in ("length", "breadth", "thickness"):
            b[key] /= d50
    return zones, bands, cut
