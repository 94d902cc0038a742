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

Crossing bands touch, so one zone can hold several, and a weak band breaks under the cut
into several zones. So sheets are sought in every zone at least min_length / 2 long by
sequential RANSAC: the plane (through three of its nodes, 400 deterministic draws; then
refitted to the principal axes of its nodes within 3 tol) with the most nodes within tol
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
import math

import numpy as np
from scipy import ndimage

MIN_LENGTH = 6.0   # D50
ASPECT = 2.0       # breadth / thickness
TOL = 1.0          # D50, the slab half-width of a plane's inliers
DRAWS = 400


def principal_sizes(points):
    """(length, breadth, thickness, normal) of a point set: sqrt(12 eigenvalue) of its
    covariance (the sides of a uniformly filled box with that covariance), the normal the
    smallest eigenvalue's axis, pointing up."""
    c = np.cov(points.T, bias=True)
    lam, vec = np.linalg.eigh(c)
    sizes = np.sqrt(12.0 * np.clip(lam[::-1], 0.0, None))
    n = vec[:, 0]
    if n[2] < 0:
        n = -n
    return sizes[0], sizes[1], sizes[2], n


def dip_azimuth(n):
    """Dip (deg from the horizontal) and dip direction (deg from +x counterclockwise) of a
    plane of upward unit normal n."""
    dip = math.degrees(math.acos(min(1.0, max(-1.0, n[2]))))
    az = math.degrees(math.atan2(n[1], n[0])) % 360.0 if dip > 1e-9 else 0.0
    return dip, az


def plane_of(points):
    """A plane's (centre, upward unit normal) from three or more points (least squares)."""
    centre = points.mean(axis=0)
    return centre, principal_sizes(points)[3]


def best_plane(pts, tol, rng):
    """RANSAC: of DRAWS planes through three of pts, the one with the most points within tol;
    then refitted (three times) to the principal axes of the points within 3 tol of it, the
    band's whole thickness; returns (centre, normal), or None when every draw was
    degenerate (the points on one line)."""
    best, best_count = None, -1
    for _ in range(DRAWS):
        a, b, c = pts[rng.choice(len(pts), 3, replace=False)]
        n = np.cross(b - a, c - a)
        norm = np.linalg.norm(n)
        if norm == 0.0:
            continue
        count = np.count_nonzero(np.abs((pts - a) @ (n / norm)) <= tol)
        if count > best_count:
            best, best_count = (a, n / norm), count
    if best is None:
        return None
    centre, n = best
    for _ in range(3):
        near = pts[np.abs((pts - centre) @ n) <= 3 * tol]
        if len(near) < 3:
            break
        centre, n = plane_of(near)
    return centre, n


def zone_sheets(pts, tol, min_piece, aspect, rng):
    """The sheets of one zone's node positions by sequential RANSAC (module docstring): dicts
    of points (the inliers), centre, normal, thickness (distance units)."""
    sheets = []
    left = pts
    while len(left) >= 3:
        plane = best_plane(left, tol, rng)
        if plane is None:
            break
        centre, n = plane
        dist = (left - centre) @ n
        inl = np.abs(dist) <= tol
        length, breadth, _, _ = principal_sizes(left[inl])
        near = np.abs(dist) <= 3 * tol
        thick = math.sqrt(12.0 * dist[near].var())
        if length < min_piece or breadth < aspect * thick:
            break
        sheets.append({"points": left[inl], "centre": centre, "normal": n, "thickness": thick})
        left = left[~near]
    return sheets


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


def distinct_planes(sheets, d50, tol, min_length, angle=10.0):
    """The sheets of all zones grouped by plane: a sheet whose normal lies within `angle` deg
    of a larger one's and whose centre lies within 2 tol of that one's plane is a piece of
    it (a band broken by the cut into separate zones). Each group measured as one: its
    pieces' points refitted (centre, normal, length and breadth), thickness their
    node-weighted mean; the groups at least min_length D50 long are the bands, largest
    first, dicts of nodes, pieces, normal, centre, length, breadth, thickness (D50), dip,
    azimuth (deg)."""
    groups = []
    for sh in sorted(sheets, key=lambda x: -len(x["points"])):
        for g in groups:
            lead = g[0]
            if (abs(sh["normal"] @ lead["normal"]) >= math.cos(math.radians(angle))
                    and abs((sh["centre"] - lead["centre"]) @ lead["normal"]) <= 2 * tol):
                g.append(sh)
                break
        else:
            groups.append([sh])
    bands = []
    for g in groups:
        pts = np.concatenate([sh["points"] for sh in g])
        length, breadth, _, n = principal_sizes(pts)
        if length < min_length * d50:
            continue
        dip, az = dip_azimuth(n)
        thick = sum(len(sh["points"]) * sh["thickness"] for sh in g) / len(pts)
        bands.append({"nodes": len(pts), "pieces": len(g), "normal": n,
                      "centre": pts.mean(axis=0), "length": length / d50,
                      "breadth": breadth / d50, "thickness": thick / d50, "dip": dip,
                      "azimuth": az})
    return bands


def strain_zones(shear, mask, origin, h, d50, k=2.0, min_length=MIN_LENGTH, aspect=ASPECT,
                 tol=TOL, detrend=True, seed=1):
    """The localised zones and bands of a field (module docstring), as (zones, bands, cut):
    zones largest first, each a dict of nodes, volume (D50^3), length, breadth, thickness
    (D50), dip, azimuth (deg), centre (world) and the number of sheets found in it; bands
    those of distinct_planes; cut the value above which a node is localised (of the field
    less its axisymmetric trend with detrend)."""
    if detrend:
        shear = shear - axisymmetric_trend(shear, mask, origin, h)
    values = shear[mask]
    cut = values.mean() + k * values.std()
    labels, count = ndimage.label(mask & (shear > cut), structure=np.ones((3, 3, 3), bool))
    order = np.argsort(labels, axis=None, kind="stable")
    starts = np.searchsorted(labels.ravel()[order], np.arange(1, count + 2))
    rng = np.random.default_rng(seed)
    zones, sheets = [], []
    for lab in range(1, count + 1):
        kk, jj, ii = np.unravel_index(order[starts[lab - 1]:starts[lab]], shear.shape)
        pts = np.asarray(origin, float) + h * np.stack([ii, jj, kk], axis=1)
        length, breadth, thick, n = principal_sizes(pts) if len(pts) > 1 else \
            (h, h, h, np.array([0.0, 0.0, 1.0]))
        dip, az = dip_azimuth(n)
        zone = {"nodes": len(pts), "volume": len(pts) * h ** 3 / d50 ** 3,
                "length": length / d50, "breadth": breadth / d50, "thickness": thick / d50,
                "dip": dip, "azimuth": az, "centre": pts.mean(axis=0), "sheets": 0}
        if length >= 0.5 * min_length * d50:
            found = zone_sheets(pts, tol * d50, 0.5 * min_length * d50, aspect, rng)
            zone["sheets"] = len(found)
            sheets += found
        zones.append(zone)
    zones.sort(key=lambda z: -z["nodes"])
    return zones, distinct_planes(sheets, d50, tol * d50, min_length), cut
