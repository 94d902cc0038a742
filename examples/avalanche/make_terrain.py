#!/usr/bin/env python3
"""A synthetic valley for the avalanche example, written as an ESRI ASCII grid (.asc).

The channel runs along -x. Its floor (y = 0) is inclined at SLOPE degrees from the top of
the terrain (x = XTOP) down to x = 0, where it bends, over a transition of 2 B (the floor's
gradient varies linearly from x = B down to x = -B), onto a run-out plane: flat
(--runout 0, the default) or inclined at 3 degrees downhill along -x (--runout 3). Across
the channel the valley is a U (depth A (y / YHALF)^2) or a V (A (sqrt(y^2 + r^2) - r) /
(sqrt(YHALF^2 + r^2) - r), rounded over r = 1 at its axis), full on the slope (x >= 0) and
fading out over the first 8 units of the run-out (a smoothstep from x = 0 to x = -8), so
the valley opens onto the plane as a fan:

    z(x, y) = gr x + (gs - gr) ramp(x) + w(x) c(y)
    ramp(x) = 0 (x < -B), (x + B)^2 / (4 B) (|x| <= B), x (x > B)
    gs = tan(SLOPE), gr = tan(RUNOUT): the floor has gradient gs above B, gr below -B

Heights are given at cell centres (xllcenter/yllcenter), rows from north (largest y) to
south, as the format has them.

    make_terrain.py [OUT.asc] [--runout 0|3] [--shape U|V] [--cell C] [--slope DEG]
                    [--x0 X0] [--xtop XTOP] [--yhalf YHALF] [--depth A] [--ywidth W]
                    [--bend B] [--fan F] [--profile FILE]

Defaults: 52 x 22 units (x from -38 to 14, y from -11 to 11), cell 0.5, slope 25 deg, U
valley 3 deep at y = +-8 (YHALF; its sides rise on to 5.7 at the terrain's edges y =
+-11), bend half-length B = 2, fan F = 8. Keep the grains away from the terrain's edges:
beyond them the band is not the flat continuation the documentation describes (README.md).
Prints the grid's size, the floor's height at the top, the kink and the west end.
--profile FILE also writes the floor's profile z(x, 0) (two columns).
"""
import argparse
import math
import sys


def parse():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("out", nargs="?", default="valley.asc")
    p.add_argument("--runout", type=float, default=0.0,
                   help="run-out inclination in degrees, downhill along -x (0 or 3)")
    p.add_argument("--shape", choices=("U", "V"), default="U")
    p.add_argument("--cell", type=float, default=0.5)
    p.add_argument("--slope", type=float, default=25.0)
    p.add_argument("--x0", type=float, default=-38.0, help="west (downstream) end")
    p.add_argument("--xtop", type=float, default=14.0, help="east end: top of the slope")
    p.add_argument("--yhalf", type=float, default=8.0, help="the valley's half-width: it is "
                   "--depth deep at y = +-yhalf")
    p.add_argument("--depth", type=float, default=3.0, help="valley depth at y = +-yhalf")
    p.add_argument("--ywidth", type=float, default=11.0, help="the terrain's half-width (y from "
                   "-ywidth to ywidth); the valley's sides rise on beyond +-yhalf")
    p.add_argument("--bend", type=float, default=2.0, help="half-length of the bend")
    p.add_argument("--fan", type=float, default=8.0, help="length over which the valley opens")
    p.add_argument("--profile", default=None)
    return p.parse_args()


def make_height(a):
    gs = math.tan(math.radians(a.slope))
    gr = math.tan(math.radians(a.runout))
    b = a.bend

    def ramp(x):
        if x < -b:
            return 0.0
        if x > b:
            return x
        return (x + b) ** 2 / (4.0 * b)

    def floor(x):
        return gr * x + (gs - gr) * ramp(x)

    def across(y):
        if a.shape == "U":
            return a.depth * (y / a.yhalf) ** 2
        r = 1.0
        return a.depth * (math.hypot(y, r) - r) / (math.hypot(a.yhalf, r) - r)

    def fan(x):
        s = min(1.0, max(0.0, (x + a.fan) / a.fan))
        return s * s * (3.0 - 2.0 * s)

    return floor, lambda x, y: floor(x) + fan(x) * across(y)


def main():
    a = parse()
    floor, height = make_height(a)
    nx = int(round((a.xtop - a.x0) / a.cell)) + 1
    ny = int(round(2 * a.ywidth / a.cell)) + 1
    y0 = -a.ywidth
    with open(a.out, "w") as f:
        f.write("ncols %d\nnrows %d\nxllcenter %.10g\nyllcenter %.10g\ncellsize %.10g\n"
                "NODATA_value -9999\n" % (nx, ny, a.x0, y0, a.cell))
        for j in reversed(range(ny)):                 # north first
            y = y0 + j * a.cell
            f.write(" ".join("%.6f" % height(a.x0 + i * a.cell, y) for i in range(nx)) + "\n")
    if a.profile:
        with open(a.profile, "w") as f:
            f.write("# x z_floor (y = 0)\n")
            for i in range(nx):
                x = a.x0 + i * a.cell
                f.write("%.4f %.6f\n" % (x, floor(x)))
    print("%s: %d x %d heights, cell %g, x %g..%g, y %g..%g; %s valley %g deep, slope %g deg, "
          "run-out %g deg; floor z = %.3f at the top (x = %g), %.3f at the kink, %.3f at the "
          "west end" % (a.out, nx, ny, a.cell, a.x0, a.x0 + (nx - 1) * a.cell, y0,
                        y0 + (ny - 1) * a.cell, a.shape, a.depth, a.slope, a.runout,
                        floor(a.xtop), a.xtop, floor(0.0), floor(a.x0)))


if __name__ == "__main__":
    sys.exit(main())
