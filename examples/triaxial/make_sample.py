#!/usr/bin/env python3
"""Write a data file of N grains on a jittered lattice inside a cylinder (axis z through
x = y = 0, radius R, base at z = 0), random shapes 1..NSHAPES, uniformly random
orientations (Shoemake), given density. A stand-in for `lsdem-shape pack --cylinder` when
that subcommand is not available; the grains are loose and get packed by in.prepare.

usage: make_sample.py N NSHAPES SPACING R DENSITY SEED > sample0.data
The lattice spacing must exceed the largest grain's bounding diameter."""
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
    s, R, rho = float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
    rng = random.Random(int(sys.argv[6]))
    m = int(R / s) + 1
    sites = [(i * s, j * s) for i in range(-m, m + 1) for j in range(-m, m + 1)
             if math.hypot(i * s, j * s) <= R - 0.5 * s]
    if not sites:
        sys.exit("make_sample.py: radius %g holds no lattice site of spacing %g" % (R, s))
    layers = (n + len(sites) - 1) // len(sites)
    top = s * (layers + 0.5)
    print("LSDEM triaxial sample: %d grains on a lattice in a cylinder of radius %g\n" % (n, R))
    print("%d atoms\n1 atom types\n" % n)
    print("%g %g xlo xhi\n%g %g ylo yhi\n%g %g zlo zhi\n" % (-1.5 * R, 1.5 * R, -1.5 * R,
                                                            1.5 * R, -0.5 * s, top + s))
    print("Atoms # lsdem\n")
    jitter = 0.05 * s
    for k in range(n):
        layer, site = divmod(k, len(sites))
        x = sites[site][0] + rng.uniform(-jitter, jitter)
        y = sites[site][1] + rng.uniform(-jitter, jitter)
        z = s * (layer + 0.5) + rng.uniform(-jitter, jitter)
        q = random_quaternion(rng)
        print("%d 1 %d %g %.9g %.9g %.9g %.12g %.12g %.12g %.12g"
              % (k + 1, rng.randrange(nshapes) + 1, rho, x, y, z, *q))


if __name__ == "__main__":
    main()
