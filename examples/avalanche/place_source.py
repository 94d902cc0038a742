#!/usr/bin/env python3
"""Lay a packed box of grains (lsdem-shape pack: the box [0,A] x [0,B] x [0,C]) on the
slope of the avalanche valley as a slab: the box is turned by SLOPE degrees about y (its
base parallel to the slope z = x tan(SLOPE), which make_terrain.py's floor is for x > 2),
its downhill base edge at x = X0, centred on the valley's axis y = 0 and raised by LIFT
above the slope so that its base clears the valley's sides (by default the rise of
make_terrain.py's U or V, --shape, at the slab's edges, plus 0.05). Positions and orientations (quaternions) are turned together: the packing is the
same packing, tilted. The data file gets the simulation box BOX (xlo xhi ylo yhi zlo zhi).

    place_source.py IN.data OUT.data [--slope 25] [--x0 3.5] [--lift L | --shape U|V]
                    [--depth 3] [--yhalf 8] [--box -42 18 -16 16 -6 18]

Prints the slab's extent and its crown (the highest grain centre at the uphill end)."""
import argparse
import math


def qmul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("src")
    p.add_argument("dst")
    p.add_argument("--slope", type=float, default=25.0)
    p.add_argument("--x0", type=float, default=3.5)
    p.add_argument("--lift", type=float, default=None,
                   help="vertical gap above the slope (default: the valley's rise at the "
                        "slab's edges + 0.05)")
    p.add_argument("--shape", choices=("U", "V"), default="U", help="valley shape, for --lift")
    p.add_argument("--depth", type=float, default=3.0, help="valley depth, for --lift")
    p.add_argument("--yhalf", type=float, default=8.0, help="valley half-width, for --lift")
    p.add_argument("--box", type=float, nargs=6, default=[-42, 18, -16, 16, -6, 18])
    a = p.parse_args()

    lines = open(a.src).read().split("\n")
    lo = {}
    for ln in lines:
        w = ln.split()
        if len(w) == 4 and w[2][1:] == "lo":
            lo[w[2][0]] = (float(w[0]), float(w[1]))
    width = lo["y"][1] - lo["y"][0]
    if a.lift is not None:
        lift = a.lift
    elif a.shape == "U":             # make_terrain.py's cross-sections
        lift = a.depth * (0.5 * width / a.yhalf) ** 2 + 0.05
    else:
        lift = a.depth * (math.hypot(0.5 * width, 1.0) - 1.0) / (math.hypot(a.yhalf, 1.0) - 1.0) + 0.05
    th = math.radians(-a.slope)             # turning z towards -x: the slope's normal
    c, s = math.cos(th), math.sin(th)
    qr = (math.cos(th / 2), 0.0, math.sin(th / 2), 0.0)
    ymid = 0.5 * (lo["y"][0] + lo["y"][1])
    z_base = a.x0 * math.tan(math.radians(a.slope)) + lift
    out, atoms, pos = [], False, []
    for ln in lines:
        w = ln.split()
        if w[-2:] == ["xlo", "xhi"]:
            ln = "%g %g xlo xhi" % tuple(a.box[0:2])
        elif w[-2:] == ["ylo", "yhi"]:
            ln = "%g %g ylo yhi" % tuple(a.box[2:4])
        elif w[-2:] == ["zlo", "zhi"]:
            ln = "%g %g zlo zhi" % tuple(a.box[4:6])
        elif ln.startswith("Atoms"):
            atoms = True
        elif atoms and len(w) == 11:
            x, y, z = (float(v) for v in w[4:7]) 
            x -= lo["x"][0]
            z -= lo["z"][0]
            xn = c * x + s * z + a.x0
            zn = -s * x + c * z + z_base
            yn = y - ymid
            q = qmul(qr, tuple(float(v) for v in w[7:11]))
            n = math.sqrt(sum(v * v for v in q))
            q = tuple(v / n for v in q)
            pos.append((xn, yn, zn))
            ln = " ".join(w[:4]) + " %.12g %.12g %.12g %.15g %.15g %.15g %.15g" % (
                (xn, yn, zn) + q)
        elif atoms and w and not w[0].isdigit():
            atoms = False
        out.append(ln)
    open(a.dst, "w").write("\n".join(out))
    xs, zs = [p[0] for p in pos], [p[2] for p in pos]
    print("%s: %d grains on the %g deg slope, x %.2f..%.2f, centre z %.2f..%.2f, lifted %.3f;"
          " crown (highest centre) z = %.3f at x = %.3f"
          % (a.dst, len(pos), a.slope, min(xs), max(xs), min(zs), max(zs), lift, max(zs),
             pos[zs.index(max(zs))][0]))


if __name__ == "__main__":
    main()
