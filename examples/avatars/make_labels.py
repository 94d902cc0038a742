#!/usr/bin/env python3
"""Write a small synthetic labelled CT volume: NB random blobs (ellipsoids with a low-order
bumpy surface, random orientations) in an N^3 voxel grid, one label per grain (1..NB),
background 0, as raw little-endian uint16 (x fastest, then y, then z) -- the layout of a
watershed segmentation exported as raw binary.

usage: make_labels.py OUT.raw N NB SEED
Blobs do not touch (each keeps a one-voxel gap to the others) and stay inside the volume."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from synthetic_scan import random_rotation  # noqa: E402  (the grains of a synthetic grey scan)


def main():
    out, n, nb, seed = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
    rng = np.random.default_rng(seed)
    labels = np.zeros((n, n, n), dtype=np.uint16)  # indexed [z, y, x]
    z, y, x = np.mgrid[0:n, 0:n, 0:n].astype(float)
    placed, tries = 0, 0
    while placed < nb and tries < 100 * nb:
        tries += 1
        axes = rng.uniform(5.0, 10.0, size=3)
        r = axes.max() + 2
        c = rng.uniform(r, n - 1 - r, size=3)
        lo = np.maximum((c - r).astype(int), 0)
        hi = np.minimum((c + r).astype(int) + 2, n)
        sl = (slice(lo[2], hi[2]), slice(lo[1], hi[1]), slice(lo[0], hi[0]))
        d = np.stack([x[sl] - c[0], y[sl] - c[1], z[sl] - c[2]], axis=-1) @ random_rotation(rng)
        rho = np.sqrt(((d / axes) ** 2).sum(axis=-1))
        # a bumpy surface: a few random low-order waves on the ellipsoid's radius
        u = d / np.maximum(np.linalg.norm(d, axis=-1, keepdims=True), 1e-9)
        bump = sum(0.08 * np.sin(rng.uniform(2, 4) * (u @ rng.normal(size=3)) + rng.uniform(0, 6.3))
                   for _ in range(3))
        inside = rho < 1.0 + bump
        grown = rho < 1.0 + bump + 1.5 / axes.min()  # one voxel and a half of clearance
        if labels[sl][grown].any():
            continue
        placed += 1
        labels[sl][inside] = placed
    labels.astype('<u2').tofile(out)
    print("%s: %d^3 voxels, %d labelled grains" % (out, n, placed))


if __name__ == "__main__":
    main()
