#!/usr/bin/python3
"""synthetic_scan.py -- a grey-level CT scan of known grains, and the score of a
segmentation against them (doc/lsdem_segment.rst, "How well it segments").

  synthetic_scan.py make PREFIX [--size N] [--grains K] [--seed S] [--blur B] [--noise F]
                    [--gradient G] [--touch T] [--specimen F [--zero-corners]]
      PREFIX.tif        the scan: uint16, one page per z slice, uncompressed (compress it
                        with libtiff's tiffcp, e.g. tiffcp -c lzw)
      PREFIX.truth.raw  the grains it was made from: uint32 labels, x fastest
  synthetic_scan.py score PREFIX.truth.raw FOUND.raw N [--named "L1 L2 ..."]
      prints one line of key=value figures (see score()); --named: the label ids that
      lsdem-segment's check named as likely two grains joined, scored against the truth

Grains are randomly oriented ellipsoids (semi-axes 6 to 12 voxels) with a bumpy surface,
placed one after the other at random where they overlap earlier grains by at most a
fraction T of their own volume (default 0.04): the overlap goes to the earlier grain, so
grains touch along flat faces and narrow necks, as in a dense sand. The grey image is
pore 10000 and grain 30000, blurred by a Gaussian of B voxels (the scanner's point-spread;
default 1), plus a linear grey-level trend of G times the contrast along z (beam hardening;
default 0.3) and Gaussian noise of F times the contrast (default 0.1).

With --specimen F the grains lie whole inside a cylinder along z of radius F times half the
size, centred in the slices, with air (the pore grey level) around it, as in a scan of a
triaxial specimen; --zero-corners also sets every voxel outside the scanner's circular field
of view (the circle inscribed in each slice) to 0, as many reconstructions do.
"""
import argparse
import sys

import numpy as np
from scipy import ndimage as ndi

PORE, GRAIN = 10000.0, 30000.0


def random_rotation(rng):
    q = rng.normal(size=4)
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def radius_from_axis(n):
    """Distance [y, x] of each voxel centre from the slices' centre line."""
    y, x = np.ogrid[0:n, 0:n]
    return np.hypot(x - (n - 1) / 2, y - (n - 1) / 2)


def make_grains(n, count, seed, touch, specimen=None, amin=6.0, amax=12.0):
    """Labels [z, y, x] of up to `count` touching grains in an n^3 volume, all inside the
    cylinder of radius `specimen` around the z axis through the slices' centre if given."""
    rng = np.random.default_rng(seed)
    labels = np.zeros((n, n, n), dtype=np.uint32)
    centres, inner = np.zeros((0, 3)), np.zeros(0)
    placed = tries = 0
    while placed < count and tries < 100 * count:
        tries += 1
        axes = rng.uniform(amin, amax, size=3)
        r = axes.max() * 1.2  # bumps add at most 18 %
        c = rng.uniform(r + 2, n - 3 - r, size=3)
        if specimen is not None and np.hypot(*(c[:2] - (n - 1) / 2)) + r > specimen:
            continue
        # cheap rejection: inscribed spheres (min semi-axis, less the bumps) that overlap
        # deeply mean far more than `touch` of the volume is taken
        a_in = 0.82 * axes.min()
        if len(inner) and (np.linalg.norm(centres - c, axis=1) < 0.9 * (inner + a_in)).any():
            continue
        lo = np.maximum((c - r).astype(int), 0)
        hi = np.minimum((c + r).astype(int) + 2, n)
        z, y, x = np.mgrid[lo[2]:hi[2], lo[1]:hi[1], lo[0]:hi[0]].astype(float)
        d = np.stack([x - c[0], y - c[1], z - c[2]], axis=-1) @ random_rotation(rng)
        rho = np.sqrt(((d / axes) ** 2).sum(axis=-1))
        u = d / np.maximum(np.linalg.norm(d, axis=-1, keepdims=True), 1e-9)
        bump = sum(0.06 * np.sin(rng.uniform(2, 4) * (u @ rng.normal(size=3)) + rng.uniform(0, 6.3))
                   for _ in range(3))
        inside = rho < 1.0 + bump
        sub = labels[lo[2]:hi[2], lo[1]:hi[1], lo[0]:hi[0]]
        taken = (sub[inside] > 0).mean() if inside.any() else 1.0
        if taken > touch:
            continue
        placed += 1
        sub[inside & (sub == 0)] = placed
        centres, inner = np.vstack([centres, c]), np.append(inner, a_in)
    return labels


def touching_fraction(labels):
    """Fraction of grains that share a face with another grain."""
    touch = np.zeros(labels.max() + 1, dtype=bool)
    for ax in range(3):
        a = np.moveaxis(labels, ax, 0)
        p, q = a[:-1].ravel(), a[1:].ravel()
        m = (p > 0) & (q > 0) & (p != q)
        touch[p[m]] = touch[q[m]] = True
    return touch[1:].mean() if labels.max() else 0.0


def grey_scan(labels, seed, blur, noise, gradient, zero_corners=False):
    rng = np.random.default_rng(seed + 1)
    g = np.where(labels > 0, GRAIN, PORE).astype(np.float32)
    if blur > 0:
        g = ndi.gaussian_filter(g, blur)
    n = labels.shape[0]
    contrast = GRAIN - PORE
    z = (np.arange(n, dtype=np.float32) / (n - 1) - 0.5)[:, None, None]
    g = g + gradient * contrast * z
    g = g + rng.normal(0.0, noise * contrast, size=g.shape).astype(np.float32)
    if zero_corners:
        g[:, radius_from_axis(n) > n / 2] = 0.0
    return np.clip(np.rint(g), 0, 65535).astype(np.uint16)


def moments(labels, n):
    """Voxel count, centroid [z, y, x] and major principal axis of labels 0..n-1."""
    lab = labels.ravel().astype(np.int64)
    idx = np.indices(labels.shape).reshape(3, -1).astype(np.float64)
    v = np.bincount(lab, minlength=n).astype(np.float64)
    w = np.maximum(v, 1)
    c = np.stack([np.bincount(lab, idx[a], n) / w for a in range(3)], axis=1)
    cov = np.empty((n, 3, 3))
    for a in range(3):
        for b in range(a, 3):
            cov[:, a, b] = cov[:, b, a] = np.bincount(lab, idx[a] * idx[b], n) / w - c[:, a] * c[:, b]
    return v, c, np.linalg.eigh(cov)[1][:, :, -1]


def score(truth, found, named=()):
    """One-to-one recovery: a true grain is recovered when the found label holding most of
    it overlaps it with an intersection over union of at least 0.5 (so each holds more than
    half of the other: the pairing is unique both ways). Of the others, a grain is merged
    when its label holds more than half of it and of another true grain as well, split when
    no label holds more than half of it. Of the recovered grains: volume error
    (found - true) / true, centroid distance (voxels), angle between the major principal
    axes (degrees); `small` is the recovered share of the smallest third of the grains.
    Of the found labels: `merged_labels` hold more than half of two or more true grains,
    `good_labels` are the one-to-one match of a true grain and hold no other (a merged label
    can be the one-to-one match of the larger of its grains); of the labels `named` (ids of
    found), how many are merged labels and how many good ones."""
    t, f = truth.ravel().astype(np.int64), found.ravel().astype(np.int64)
    nt, nf = t.max() + 1, f.max() + 1
    both = (t > 0) & (f > 0)
    pairs = np.bincount(t[both] * nf + f[both], minlength=nt * nf).reshape(nt, nf)
    vt, ct, at = moments(truth, nt)
    vf, cf, af = moments(found, nf)
    best = pairs.argmax(axis=1)
    ov = pairs[np.arange(nt), best]
    real = (np.arange(nt) > 0) & (vt > 0)
    ok = real & (3 * ov >= vt + vf[best])  # IoU = ov / (vt + vf - ov) >= 0.5
    held = pairs * 2 > vt[:, None]  # [i, j]: label j holds more than half of true grain i
    merged = real & ~ok & held[np.arange(nt), best] & (held[1:].sum(axis=0)[best] >= 2)
    split = real & ~ok & ~held.any(axis=1)
    rel = (vf[best[ok]] - vt[ok]) / vt[ok]
    dc = np.linalg.norm(cf[best[ok]] - ct[ok], axis=1)
    dax = np.degrees(np.arccos(np.clip(np.abs((af[best[ok]] * at[ok]).sum(axis=1)), 0, 1)))
    small = real & (vt <= np.percentile(vt[real], 100 / 3)) if real.any() else real
    two = held[1:].sum(axis=0) >= 2  # [j]: label j holds more than half of two true grains
    good = np.zeros(nf, bool)
    good[best[ok]] = True
    good &= ~two  # a grain's one-to-one match that holds half of a smaller one as well
    named = np.asarray(named, np.int64)
    nan = float("nan")
    return {"true": int(real.sum()), "found": int(np.count_nonzero(vf[1:])),
            "recovered": int(ok.sum()), "fraction": float(ok.sum()) / max(real.sum(), 1),
            "small": float((ok & small).sum()) / max(small.sum(), 1),
            "vol_err_mean_abs": float(np.abs(rel).mean()) if rel.size else nan,
            "vol_err_mean": float(rel.mean()) if rel.size else nan,
            "vol_err_max_abs": float(np.abs(rel).max()) if rel.size else nan,
            "centroid_err": float(dc.mean()) if rel.size else nan,
            "axis_err_deg": float(dax.mean()) if rel.size else nan,
            "merged": int(merged.sum()), "split": int(split.sum()),
            "merged_labels": int(two[1:].sum()), "good_labels": int(good[1:].sum()),
            "named": int(named.size), "named_merged": int(two[named].sum()),
            "named_good": int(good[named].sum())}


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="cmd", required=True)
    m = sub.add_parser("make")
    m.add_argument("prefix")
    m.add_argument("--size", type=int, default=96)
    m.add_argument("--grains", type=int, default=60)
    m.add_argument("--seed", type=int, default=1)
    m.add_argument("--blur", type=float, default=1.0)
    m.add_argument("--noise", type=float, default=0.1)
    m.add_argument("--gradient", type=float, default=0.3)
    m.add_argument("--touch", type=float, default=0.04)
    m.add_argument("--specimen", type=float, help="grains inside a cylinder of this radius, "
                   "as a fraction of half the size, air around it")
    m.add_argument("--zero-corners", action="store_true",
                   help="grey level 0 outside the circle inscribed in each slice")
    s = sub.add_parser("score")
    s.add_argument("truth")
    s.add_argument("found")
    s.add_argument("n", type=int)
    s.add_argument("--named", default="", help="label ids named as two grains joined")
    a = p.parse_args()
    if a.cmd == "make":
        import tifffile
        specimen = a.specimen * a.size / 2 if a.specimen else None
        labels = make_grains(a.size, a.grains, a.seed, a.touch, specimen)
        grey = grey_scan(labels, a.seed, a.blur, a.noise, a.gradient, a.zero_corners)
        tifffile.imwrite(a.prefix + ".tif", grey, photometric="minisblack")
        labels.astype("<u4").tofile(a.prefix + ".truth.raw")
        print("%s.tif: %d^3 voxels, %d grains (%.0f %% touching another), solid fraction %.3f"
              % (a.prefix, a.size, labels.max(), 100 * touching_fraction(labels),
                 (labels > 0).mean()))
    else:
        shape = (a.n, a.n, a.n)
        r = score(np.fromfile(a.truth, "<u4").reshape(shape), np.fromfile(a.found, "<u4").reshape(shape),
                  [int(w) for w in a.named.split()])
        print(" ".join("%s=%s" % (k, ("%.4f" % v) if isinstance(v, float) else v) for k, v in r.items()))


if __name__ == "__main__":
    sys.exit(main())
