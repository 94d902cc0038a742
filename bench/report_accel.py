#!/usr/bin/env python3
"""Write the body accelerations of the report code's benchmark driver as LAMMPS atomfiles.

The driver (Tan & Sitar's LSDEM_Test_benchmark) seeds a std::mt19937 with 123123 at every
step and gives grain i (0-based, in index order on one rank) the acceleration
(u_x, u_y, u_z) x 10 / s, u uniform in [-1, 1) from std::uniform_real_distribution, with
s = 0.1 x (um per voxel) = 0.01 at its 0.1 um per voxel: each grain keeps the same
acceleration at every step. GCC evaluates the three draws of the vector's constructor right
to left, so u_z is drawn first. This reproduces that stream: MT19937 seeded as
std::mt19937(seed) (init_genrand), each uniform from two 32-bit outputs as libstdc++'s
generate_canonical<double, 53> does; checked against the values the driver applies (the
first grains' accelerations to the last digit).

Usage: report_accel.py NGRAINS OUTDIR [--seed 123123] [--um-per-voxel 0.1]
writes OUTDIR/accel_x.txt, accel_y.txt, accel_z.txt (atom ID = grain index + 1)."""
import argparse
import os
import random


def mt19937(seed):
    """A random.Random whose getrandbits(32) is std::mt19937(seed)'s output."""
    mt = [seed & 0xFFFFFFFF]
    for i in range(1, 624):
        mt.append((1812433253 * (mt[-1] ^ (mt[-1] >> 30)) + i) & 0xFFFFFFFF)
    r = random.Random()
    r.setstate((3, tuple(mt + [624]), None))
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("ngrains", type=int)
    ap.add_argument("outdir")
    ap.add_argument("--seed", type=int, default=123123)
    ap.add_argument("--um-per-voxel", type=float, default=0.1)
    a = ap.parse_args()
    r = mt19937(a.seed)
    s = a.um_per_voxel * 1e-1

    def uniform():  # std::uniform_real_distribution<double>(-1, 1)
        lo, hi = r.getrandbits(32), r.getrandbits(32)
        u = (float(lo) + float(hi) * 4294967296.0) / 18446744073709551616.0
        return (u if u < 1.0 else 1.0 - 2.0 ** -53) * 2.0 - 1.0

    acc = []
    for _ in range(a.ngrains):
        uz, uy, ux = uniform(), uniform(), uniform()
        acc.append([u * 10.0 / s for u in (ux, uy, uz)])
    for c, name in enumerate("xyz"):
        with open(os.path.join(a.outdir, "accel_%s.txt" % name), "w") as f:
            f.write("# report driver's body acceleration, %s component (voxel/time^2)\n%d\n"
                    % (name, a.ngrains))
            f.writelines("%d %.17g\n" % (i + 1, v[c]) for i, v in enumerate(acc))


if __name__ == "__main__":
    main()
