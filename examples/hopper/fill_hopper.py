#!/usr/bin/env python3
"""Fill the hopper of make_hopper.py with spheres: a LAMMPS data file (atom_style lsdem) of
N spheres of diameter d = 1 (shape 1 of the library, an analytic sphere of radius 0.5) on
a jittered simple-cubic lattice inside the hopper, from the orifice's plane z = 0 (closed by
the deck's plug) upwards, each sphere at least 0.5 + GAP from the inner wall (the profile's
cone and bin lines, less the facets' chord inset), with random velocities. The grains
fall and settle in the deck.

Usage: fill_hopper.py OUT.data --orifice D --count N [--half-angle A] [--radius R]
                      [--height H] [--thickness T] [--pitch P] [--gap G] [--density RHO]
                      [--below B] [--seed S] [--speed V] [--segments N]
  geometry as make_hopper.py (same defaults); P lattice pitch (default 1.12), G clearance
  (default 0.05), RHO grain density (default 1), B depth of the box below the orifice
  (default 10: room for the falling jet before the deck deletes the grains), S seed (1),
  V random initial velocities in [-V, V] per component (default 0.5: the lattice collapses
  into a disordered bed).
Prints the number placed, the top of the lattice and the box."""
import argparse
import math
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_hopper import profile  # noqa: E402


def seg_dist(p, a, b):
    """Distance from p to the segment ab in the plane."""
    ax, az = b[0] - a[0], b[1] - a[1]
    t = ((p[0] - a[0]) * ax + (p[1] - a[1]) * az) / (ax * ax + az * az)
    t = min(1.0, max(0.0, t))
    return math.hypot(p[0] - a[0] - t * ax, p[1] - a[1] - t * az)


def main(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--orifice", type=float, required=True)
    ap.add_argument("--count", type=int, required=True)
    ap.add_argument("--half-angle", type=float, default=60.0)
    ap.add_argument("--radius", type=float)
    ap.add_argument("--height", type=float)
    ap.add_argument("--thickness", type=float, default=1.0)
    ap.add_argument("--segments", type=int, default=96)
    ap.add_argument("--pitch", type=float, default=1.12)
    ap.add_argument("--gap", type=float, default=0.05)
    ap.add_argument("--density", type=float, default=1.0)
    ap.add_argument("--below", type=float, default=10.0)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--speed", type=float, default=0.5)
    a = ap.parse_args(argv)
    D, A, t = a.orifice, a.half_angle, a.thickness
    R = a.radius if a.radius is not None else max(D, D / 2.0 + 4.0)
    H = a.height if a.height is not None else 3.0 * R
    pts, zc = profile(D, A, R, H, t)
    inner = pts[:3]  # (D/2, 0) -> (R, zc) -> (R, H)
    inset = R * (1.0 - math.cos(math.pi / a.segments))  # facets' chords inside the radius
    clear = 0.5 + a.gap + inset
    rng = random.Random(a.seed)
    p = a.pitch
    jit = 0.5 * (p - 1.0 - a.gap)  # a jitter that keeps neighbours apart
    grains = []
    k = 0
    nx = int(R / p) + 1
    while len(grains) < a.count:
        z = clear + k * p
        if z > H - 0.5:
            sys.exit("fill_hopper.py: only %d grains fit below the top %g (pitch %g)"
                     % (len(grains), H, p))
        layer = []
        for i in range(-nx, nx + 1):
            for j in range(-nx, nx + 1):
                x, y = i * p, j * p
                r = math.hypot(x, y)
                # inside the wall's inner profile, clear of it and of the plug (z = 0)
                rw = R if z >= zc else D / 2.0 + (R - D / 2.0) * z / zc
                if r >= rw or min(seg_dist((r, z), inner[0], inner[1]),
                                  seg_dist((r, z), inner[1], inner[2])) < clear + jit:
                    continue
                layer.append((x, y, z))
        rng.shuffle(layer)
        for x, y, z in layer:
            if len(grains) == a.count:
                break
            grains.append((x + rng.uniform(-jit, jit), y + rng.uniform(-jit, jit),
                           z + rng.uniform(-jit, jit)))
        k += 1
    top = max(g[2] for g in grains)
    L = R + t + 1.0
    box = (-L, L, -L, L, -a.below, H + 2.0)
    lines = ["LSDEM hopper: %d spheres d = 1 in a hopper D = %g, half-angle %g, R = %g"
             % (len(grains), D, A, R), "", "%d atoms" % len(grains), "1 atom types", "",
             "%r %r xlo xhi" % box[0:2], "%r %r ylo yhi" % box[2:4], "%r %r zlo zhi" % box[4:6],
             "", "Atoms # lsdem", ""]
    for i, (x, y, z) in enumerate(grains, 1):
        lines.append("%d 1 1 %r %.6f %.6f %.6f 1 0 0 0" % (i, a.density, x, y, z))
    lines += ["", "Velocities", ""]
    for i in range(1, len(grains) + 1):
        lines.append("%d %.5f %.5f %.5f 0 0 0" % (i, rng.uniform(-a.speed, a.speed),
                                                  rng.uniform(-a.speed, a.speed),
                                                  rng.uniform(-a.speed, a.speed)))
    with open(a.out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("grains %d\nlattice_top %.4f\nbox %s" % (len(grains), top, " ".join("%g" % b for b in box)))


if __name__ == "__main__":
    main(sys.argv[1:])
