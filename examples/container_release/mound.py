#!/usr/bin/env python3
"""The mound of a container-release run (report §4.6.1, Figure 4.12): its height and spread
from the grains' centroids in a dump of in.release (columns id type x y z radius ...).

  height  the 99th percentile of the centroids' heights z (the top of the mound without the
          odd grain perched on it)
  spread  the 95th percentile of the centroids' distances from the container's axis
          (x = y = 0; without the few grains that rolled far out)

  mound.py DUMP...   prints one line per dump: its name, height, spread, grains
"""
import math
import sys


def last_frame(path):
    """Columns and rows of the last frame of a dump custom file."""
    lines = open(path).read().splitlines()
    starts = [k for k, ln in enumerate(lines) if ln.startswith("ITEM: ATOMS")]
    if not starts:
        raise SystemExit("%s: no ITEM: ATOMS frame" % path)
    k = starts[-1]
    cols = lines[k].split()[2:]
    n = int(lines[k - 5])  # ITEM: NUMBER OF ATOMS, then n, then the box (4 lines)
    return cols, [dict(zip(cols, map(float, ln.split()))) for ln in lines[k + 1:k + 1 + n]]


def percentile(values, p):
    """Linear-interpolated percentile p (0-100) of values."""
    v = sorted(values)
    if not v:
        return float("nan")
    pos = (len(v) - 1) * p / 100.0
    lo = int(math.floor(pos))
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (pos - lo)


def mound(path):
    """(height, spread, grains) of the last frame of a dump."""
    _, rows = last_frame(path)
    height = percentile([r["z"] for r in rows], 99.0)
    spread = percentile([math.hypot(r["x"], r["y"]) for r in rows], 95.0)
    return height, spread, len(rows)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        print(__doc__.strip().splitlines()[-1].strip(), file=sys.stderr)
        sys.exit(2)
    for p in sys.argv[1:]:
        h, s, n = mound(p)
        print("%s height %.4f spread %.4f grains %d" % (p, h, s, n))
