#!/usr/bin/env python3
"""Write data.settle: N grains on a jittered lattice above the floor of a box, with random
shapes (1..nshapes of the library), random orientations and density 2650 kg/m^3.

usage: make_grains.py N NSHAPES SPACING NX NY BOX_X BOX_Y BOX_Z SEED > data.settle
Lengths in metres. Quaternions are scalar-first (w x y z), uniformly random (Shoemake)."""
import math
import random
import sys


def random_quaternion(rng):
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    return (b * math.cos(2 * math.pi * u3), a * math.sin(2 * math.pi * u2),
            a * math.cos(2 * math.pi * u2), b * math.sin(2 * math.pi * u3))


def main():
    n, nshapes = int(sys.argv[1]), int(sys.argv[2])
    spacing = float(sys.argv[3])
    nx, ny = int(sys.argv[4]), int(sys.argv[5])
    box = [float(v) for v in sys.argv[6:9]]
    rng = random.Random(int(sys.argv[9]))
    per_layer = nx * ny
    layers = (n + per_layer - 1) // per_layer
    top = spacing * (layers + 0.5)
    if top > box[2]:
        sys.exit("make_grains.py: %d layers of spacing %g need a box taller than %g" % (layers, spacing, top))
    print("LSDEM settle example: %d grains above the floor\n" % n)
    print("%d atoms\n1 atom types\n" % n)
    print("0 %g xlo xhi\n0 %g ylo yhi\n0 %g zlo zhi\n" % tuple(box))
    print("Atoms # lsdem\n")
    x0 = (box[0] - spacing * (nx - 1)) / 2
    y0 = (box[1] - spacing * (ny - 1)) / 2
    jitter = 0.05 * spacing
    for i in range(n):
        layer, k = divmod(i, per_layer)
        iy, ix = divmod(k, nx)
        x = x0 + ix * spacing + rng.uniform(-jitter, jitter)
        y = y0 + iy * spacing + rng.uniform(-jitter, jitter)
        z = spacing * (layer + 1) + rng.uniform(-jitter, jitter)
        q = random_quaternion(rng)
        print("%d 1 %d 2650 %.9g %.9g %.9g %.12g %.12g %.12g %.12g"
              % (i + 1, rng.randrange(nshapes) + 1, x, y, z, *q))


if __name__ == "__main__":
    main()
