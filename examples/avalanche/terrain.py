#!/usr/bin/env python3
"""The avalanche's terrain as heights (valley.asc, an ESRI ASCII grid): read_asc reads it,
ground gives the ground's height anywhere (bilinear between the cell centres, clamped at the
grid's edges as the band is). plot.py draws with it; make_nets.sh stands the nets on the
channel's floor with it:

    /usr/bin/python3 terrain.py valley.asc X [Y]    prints the height at (X, Y) (Y: 0)"""
import sys

import numpy as np


def read_asc(path):
    """(x of the columns, y of the rows from south, heights [row, column], cell)"""
    hdr, vals = {}, []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0][0].isalpha():
                hdr[w[0].lower()] = float(w[1])
            else:
                vals.extend(float(v) for v in w)
    nx, ny, cell = int(hdr["ncols"]), int(hdr["nrows"]), hdr["cellsize"]
    x0 = hdr["xllcenter"] if "xllcenter" in hdr else hdr["xllcorner"] + 0.5 * cell
    y0 = hdr["yllcenter"] if "yllcenter" in hdr else hdr["yllcorner"] + 0.5 * cell
    z = np.array(vals).reshape(ny, nx)[::-1]            # row 0 = south
    return x0 + cell * np.arange(nx), y0 + cell * np.arange(ny), z, cell


def ground(grid, x, y):
    """Bilinear interpolation of the height map grid = read_asc(...) at (x, y)."""
    gx, gy, gz, cell = grid
    fx = np.clip((np.asarray(x) - gx[0]) / cell, 0, len(gx) - 1.000001)
    fy = np.clip((np.asarray(y) - gy[0]) / cell, 0, len(gy) - 1.000001)
    i, j = fx.astype(int), fy.astype(int)
    ax, ay = fx - i, fy - j
    return ((1 - ax) * (1 - ay) * gz[j, i] + ax * (1 - ay) * gz[j, i + 1]
            + (1 - ax) * ay * gz[j + 1, i] + ax * ay * gz[j + 1, i + 1])


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    y = float(sys.argv[3]) if len(sys.argv) == 4 else 0.0
    print(repr(float(ground(read_asc(sys.argv[1]), float(sys.argv[2]), y))))
