#!/usr/bin/env python3
"""Write a LAMMPS data file (atom_style lsdem) of N^3 grains on a cubic lattice of the
given spacing in a box of side N*spacing, each with a random shape (1..NSHAPES of the
library) and a uniformly random orientation (Shoemake; quaternions scalar-first, w x y z).
The layout of the reference benchmark scene (../shared/bench: lengths in voxels, density
2650 kg/m^3 at 0.1 um per voxel), small enough for a training run.

usage: lattice.py N NSHAPES SPACING SEED > scene.data"""
import math
import random
import sys

DENSITY = 2.65e-18  # rho k^3 with k = 1e-7 m per voxel (report Table 3.1)


def random_quaternion(rng):
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    return (b * math.cos(2 * math.pi * u3), a * math.sin(2 * math.pi * u2),
            a * math.cos(2 * math.pi * u2), b * math.sin(2 * math.pi * u3))


def main():
    n, nshapes = int(sys.argv[1]), int(sys.argv[2])
    spacing, rng = float(sys.argv[3]), random.Random(int(sys.argv[4]))
    side = n * spacing
    print("LSDEM training lattice: %d^3 grains\n" % n)
    print("%d atoms\n1 atom types\n" % n**3)
    print("0 %g xlo xhi\n0 %g ylo yhi\n0 %g zlo zhi\n" % (side, side, side))
    print("Atoms # lsdem\n")
    tag = 0
    for k in range(n):
        for j in range(n):
            for i in range(n):
                tag += 1
                x, y, z = ((i + 0.5) * spacing, (j + 0.5) * spacing, (k + 0.5) * spacing)
                print("%d 1 %d %g %g %g %g %.12g %.12g %.12g %.12g"
                      % (tag, rng.randrange(nshapes) + 1, DENSITY, x, y, z,
                         *random_quaternion(rng)))


if __name__ == "__main__":
    main()
