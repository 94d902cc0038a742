#!/usr/bin/python3
"""synthetic_sand.py -- a harder grey-level CT scan of known grains, closer to a real sand
scan than synthetic_scan.py's (doc/lsdem_segment.rst, "How well it segments").

  synthetic_sand.py make PREFIX [--size N] [--d50 D] [--seed S] [--solid F] [--snr R]
                    [--blur B] [--cupping C] [--rings A] [--inclusions K] [--specimen F]
                    [--zero-corners] [--clean]
      PREFIX.tif        the scan: uint16, one page per z slice, uncompressed
      PREFIX.truth.raw  the grains it was made from: uint32 labels, x fastest
  score a segmentation with synthetic_scan.py score PREFIX.truth.raw FOUND.raw N

Grains: angular convex polyhedra (18 faces cut tangent to a randomly oriented ellipsoid of
axis ratios about 1 : 0.8 : 0.65, each face pushed out by up to 15 % of the size) with a
rough surface (2 % of the size), equivalent diameters lognormal about D50 (--d50 voxels,
geometric standard deviation 1.25). They are centred on a dense random packing of spheres
inside a cylinder along z of radius F times half the size (--specimen, default 0.85), and
each polyhedron is made large enough that the union fills about --solid of the cylinder
(default 0.58): where two polyhedra overlap the voxel goes to the grain of the lower power
distance (|x - c|^2 - r^2, the Laguerre cell of its sphere), so neighbours touch along
flat faces (measured at D50 25, 14, 8: 4.5-5.6, 5.4-5.5, 6.4-6.7 contacts per grain, solid
fraction 0.57-0.63 in the middle half of the specimen).

The grey image is the solid fraction of each voxel (a one-voxel linear ramp across each
surface: partial volume) between pore 10000 and grain 30000, then:
  * blur: a Gaussian point-spread of B voxels (default 0.8);
  * cupping (beam hardening): the grey level scaled by 1 - C (1 - (r/R)^2) inside the field
    of view's radius R, C = 0.15 by default (the centre 15 % darker than the edge);
  * rings: 6 thin rings about the axis, the same in every slice, of +-A times the contrast
    (default 0.15);
  * inclusions: K small dense minerals (radius 1-2 voxels, grey 2.5 times the contrast
    above the grain's) inside random grains (default 4); part of their grain in the truth;
  * noise: Gaussian, of the contrast divided by R (--snr, default 8).
Outside the specimen's cylinder is air (the pore grey level); --zero-corners sets the voxels
outside the circle inscribed in each slice (the field of view) to 0. --clean leaves out
every artifact but the partial volume and the blur.
"""
import argparse
import sys

import numpy as np
from scipy import ndimage as ndi
from scipy.spatial import cKDTree

from synthetic_scan import GRAIN, PORE, radius_from_axis, random_rotation, touching_fraction

GSD = 1.25  # geometric standard deviation of the equivalent diameters
SCALE = 1.02  # polyhedra over their spheres at --solid 0.58 (gives the measured figures above)


def fibonacci_directions(k):
    i = np.arange(k) + 0.5
    phi, cost = np.pi * (1 + 5 ** 0.5) * i, 1 - 2 * i / k
    sint = np.sqrt(1 - cost ** 2)
    return np.stack([np.cos(phi) * sint, np.sin(phi) * sint, cost], axis=1)


def pack_spheres(n, radius_cyl, d50, fill, rng):
    """Centres (x, y, z) and radii of a dense random packing of spheres of lognormal
    diameters inside the cylinder of radius radius_cyl about the slices' centre line,
    whole inside the volume: random positions, then overlaps pushed apart."""
    mid = (n - 1) / 2
    volume = np.pi * radius_cyl ** 2 * (n - d50)
    d = []
    while sum(np.pi / 6 * x ** 3 for x in d) < fill * volume:
        d.append(d50 * GSD ** rng.normal())
    r = 0.5 * np.minimum(np.array(d), 0.9 * radius_cyl)
    theta = rng.uniform(0, 2 * np.pi, r.size)
    rho = (radius_cyl - r) * np.sqrt(rng.uniform(0, 1, r.size))
    c = np.stack([mid + rho * np.cos(theta), mid + rho * np.sin(theta),
                  rng.uniform(r, n - 1 - r)], axis=1)
    for _ in range(200):
        pairs = cKDTree(c).query_pairs(2 * r.max(), output_type="ndarray")
        i, j = pairs[:, 0], pairs[:, 1]
        gap = c[j] - c[i]
        dist = np.maximum(np.linalg.norm(gap, axis=1), 1e-9)
        over = r[i] + r[j] - dist
        hit = over > 0.01 * (r[i] + r[j])
        push = np.zeros_like(c)
        u = gap[hit] / dist[hit, None] * (0.5 * over[hit, None])
        np.add.at(push, i[hit], -u)
        np.add.at(push, j[hit], u)
        c += push
        # back inside the cylinder and the volume
        off = c[:, :2] - mid
        rr = np.maximum(np.linalg.norm(off, axis=1), 1e-9)
        out = rr > radius_cyl - r
        c[out, :2] = mid + off[out] * ((radius_cyl - r[out]) / rr[out])[:, None]
        c[:, 2] = np.clip(c[:, 2], r, n - 1 - r)
        if not hit.any():
            break
    return c, r


def grain_planes(radius, rng):
    """Normals and offsets of an angular polyhedron of about the given equivalent radius,
    centred at 0, and a roughness function of the direction."""
    axes = np.array([1.0, rng.uniform(0.72, 0.88), rng.uniform(0.58, 0.72)])
    axes *= radius / np.prod(axes) ** (1 / 3)
    rot = random_rotation(rng)
    normals = fibonacci_directions(18) + rng.normal(0, 0.15, (18, 3))
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    normals = normals @ rot.T
    support = np.sqrt(((normals @ rot) ** 2 * axes ** 2).sum(axis=1))  # ellipsoid's h(n)
    offsets = support * (1 + rng.uniform(0, 0.15, 18)) / 1.166  # 1.166: the mean equivalent
    # radius of such a polyhedron over the ellipsoid's (Monte Carlo, 30 shapes, sd 0.015)
    waves = [(rng.normal(size=3), rng.uniform(3, 6), rng.uniform(0, 6.3)) for _ in range(4)]
    return normals, offsets, waves


def make_grains(n, d50, seed, solid, specimen):
    """Labels [z, y, x] and the solid fraction of each voxel (0..1, a one-voxel ramp across
    every surface) of the packed polyhedra."""
    rng = np.random.default_rng(seed)
    radius_cyl = specimen * n / 2
    centres, radii = pack_spheres(n, radius_cyl, d50, 0.62, rng)
    labels = np.zeros((n, n, n), np.uint32)
    power = np.full((n, n, n), np.inf, np.float32)
    frac = np.zeros((n, n, n), np.float32)
    # each sphere's polyhedron is scaled so that the union holds about `solid` of the
    # cylinder: the spheres fill ~0.62 of it, the polyhedra overlap their neighbours
    scale = SCALE * (solid / 0.58) ** (1 / 3)
    for k, (c, r) in enumerate(zip(centres, radii), start=1):
        normals, offsets, waves = grain_planes(scale * r, rng)
        reach = offsets.max() * 1.9 + 1
        lo = np.maximum(np.floor(c - reach).astype(int), 0)
        hi = np.minimum(np.ceil(c + reach).astype(int) + 1, n)
        z, y, x = np.ogrid[lo[2]:hi[2], lo[1]:hi[1], lo[0]:hi[0]]
        d = np.stack(np.broadcast_arrays(x - c[0], y - c[1], z - c[2]), axis=-1).astype(np.float32)
        sd = (d @ normals.T.astype(np.float32) - offsets.astype(np.float32)).max(axis=-1)
        u = d / np.maximum(np.linalg.norm(d, axis=-1, keepdims=True), 1e-6)
        sd += sum(0.02 * 2 * r * np.sin(f * (u @ w.astype(np.float32)) + p) for w, f, p in waves)
        box = (slice(lo[2], hi[2]), slice(lo[1], hi[1]), slice(lo[0], hi[0]))
        np.maximum(frac[box], np.clip(0.5 - sd, 0, 1), out=frac[box])
        pw = (d ** 2).sum(axis=-1) - r * r
        mine = (sd < 0) & (pw < power[box])
        labels[box][mine] = k
        power[box][mine] = pw[mine]
    # a voxel whose centre no grain holds but that a grain partly fills stays pore in the
    # truth; grains cut to nothing by their neighbours are dropped
    from skimage.segmentation import relabel_sequential
    labels, _, _ = relabel_sequential(labels)
    return labels.astype(np.uint32), frac


def grey_scan(labels, frac, seed, a):
    rng = np.random.default_rng(seed + 1)
    n = labels.shape[0]
    contrast = GRAIN - PORE
    g = PORE + contrast * frac
    if a.inclusions:
        sizes = np.bincount(labels.ravel())
        hosts = rng.choice(np.arange(1, labels.max() + 1), size=min(a.inclusions, labels.max()),
                           replace=False, p=sizes[1:] / sizes[1:].sum())
        com = ndi.center_of_mass(labels > 0, labels, hosts)
        z, y, x = np.ogrid[0:n, 0:n, 0:n]
        for h, c in zip(hosts, com):
            rad = rng.uniform(1, 2)
            ball = ((z - c[0]) ** 2 + (y - c[1]) ** 2 + (x - c[2]) ** 2 <= rad * rad) & (labels == h)
            g[ball] = GRAIN + 2.5 * contrast
    if a.blur > 0:
        g = ndi.gaussian_filter(g, a.blur)
    r = radius_from_axis(n) / (n / 2)
    if a.cupping:
        g = g * np.where(r <= 1, 1 - a.cupping * (1 - r ** 2), 1)[None]
    if a.rings:
        rings = np.zeros_like(r)
        for rk in rng.uniform(0.1, 0.95, 6):
            rings += rng.choice([-1, 1]) * a.rings * contrast * np.exp(-0.5 * ((r - rk) * n / 2 / 0.6) ** 2)
        g = g + rings[None]
    if a.snr:
        g = g + rng.normal(0.0, contrast / a.snr, g.shape).astype(np.float32)
    if a.zero_corners:
        g[:, r > 1] = 0.0
    return np.clip(np.rint(g), 0, 65535).astype(np.uint16)


def contacts_per_grain(labels):
    """Mean number of other grains each grain shares a face with."""
    pairs = set()
    for ax in range(3):
        s = np.moveaxis(labels, ax, 0)
        p, q = s[:-1].ravel(), s[1:].ravel()
        m = (p > 0) & (q > 0) & (p != q)
        pairs.update(zip(np.minimum(p[m], q[m]).tolist(), np.maximum(p[m], q[m]).tolist()))
    return 2 * len(pairs) / max(int(labels.max()), 1)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="cmd", required=True)
    m = sub.add_parser("make")
    m.add_argument("prefix")
    m.add_argument("--size", type=int, default=96)
    m.add_argument("--d50", type=float, default=14.0, help="median equivalent diameter, voxels")
    m.add_argument("--seed", type=int, default=1)
    m.add_argument("--solid", type=float, default=0.58, help="solid fraction in the specimen")
    m.add_argument("--specimen", type=float, default=0.85,
                   help="radius of the specimen's cylinder, a fraction of half the size")
    m.add_argument("--snr", type=float, default=8.0, help="contrast / noise (0: no noise)")
    m.add_argument("--blur", type=float, default=0.8, help="point-spread, voxels")
    m.add_argument("--cupping", type=float, default=0.15)
    m.add_argument("--rings", type=float, default=0.15)
    m.add_argument("--inclusions", type=int, default=4)
    m.add_argument("--zero-corners", action="store_true",
                   help="grey level 0 outside the circle inscribed in each slice")
    m.add_argument("--clean", action="store_true", help="no noise, cupping, rings, inclusions")
    a = p.parse_args()
    if not 4 <= a.d50 <= a.size / 3:
        p.error("--d50 from 4 to a third of the size")
    if a.clean:
        a.snr, a.cupping, a.rings, a.inclusions = 0.0, 0.0, 0.0, 0
    import tifffile
    labels, frac = make_grains(a.size, a.d50, a.seed, a.solid, a.specimen)
    grey = grey_scan(labels, frac, a.seed, a)
    tifffile.imwrite(a.prefix + ".tif", grey, photometric="minisblack")
    labels.astype("<u4").tofile(a.prefix + ".truth.raw")
    cyl = radius_from_axis(a.size) <= a.specimen * a.size / 2
    d_eq = (6 / np.pi * np.bincount(labels.ravel())[1:]) ** (1 / 3)
    print("%s.tif: %d^3 voxels, %d grains (D50 %.1f voxels, %.0f %% touching another, %.1f "
          "contacts each), solid fraction %.3f in the specimen's middle half"
          % (a.prefix, a.size, labels.max(), np.median(d_eq), 100 * touching_fraction(labels),
             contacts_per_grain(labels), (labels[a.size // 4:3 * a.size // 4, cyl] > 0).mean()))


if __name__ == "__main__":
    sys.exit(main())
