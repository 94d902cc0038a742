#!/usr/bin/env python3
"""Write a hopper as a closed, outward-oriented triangle mesh (ASCII STL) for
`lsdem-shape wall` (fix wall/lsdem mesh): a thick-walled cylindrical bin on a conical
bottom with a circular orifice, the solid of revolution about the z axis of this profile
(r, z), the orifice's edge at the origin's height z = 0:

        (R, H) +--+ (R+t, H)          top annulus
               |  |
   inner wall  |  |  outer wall        bin: inner radius R
    (R, zc)    +  |
              /   |                    cone: half-angle A from the vertical,
             /    |                          zc = (R - D/2) / tan A  (A = 90: a flat bottom)
    (D/2, 0)+     |
             \\    |                    rim: a 45-degree chamfer below the orifice, so that
              +---+ (R+t, -t)               grains leaving it touch only its edge
      (D/2+t, -t)

Usage: make_hopper.py OUT.stl --orifice D [--half-angle A] [--radius R] [--height H]
                      [--thickness T] [--segments N]
  D orifice diameter (required), A cone half-angle from the vertical in degrees (default 60;
  90 = flat-bottomed silo), R inner bin radius (default max(D, D/2 + 4)), H top of the wall
  above the orifice (default 3 R), T wall thickness (default 1), N facets around the axis
  (default 96). Prints the geometry as `key value` lines (the decks take them as -var).
The inner surface's vertices lie on the radii given, so the flat facets of the bin lie
inside R by at most R (1 - cos(pi/N)) (0.0005 R at N = 96)."""
import argparse
import math
import sys


def profile(D, A, R, H, t):
    """The wall's cross-section in the (r, z) half-plane, a closed polygon."""
    zc = 0.0 if A >= 90.0 else (R - D / 2.0) / math.tan(math.radians(A))
    # flat bottom (A = 90): zc = 0, the edge (D/2, 0) -> (R, 0) is the floor
    pts = [(D / 2.0, 0.0), (R, zc), (R, H), (R + t, H), (R + t, -t), (D / 2.0 + t, -t)]
    return pts, zc


def revolve(pts, n):
    """Triangles (as vertex-coordinate triples) of the closed polygon pts turned about z."""
    ring = []
    for r, z in pts:
        ring.append([(r * math.cos(2 * math.pi * j / n), r * math.sin(2 * math.pi * j / n), z)
                     for j in range(n)])
    tris = []
    m = len(pts)
    for i in range(m):
        a, b = ring[i], ring[(i + 1) % m]
        for j in range(n):
            k = (j + 1) % n
            tris.append((a[j], b[j], b[k]))
            tris.append((a[j], b[k], a[k]))
    return tris


def volume(tris):
    return sum(
        (p[0] * (q[1] * s[2] - q[2] * s[1]) - p[1] * (q[0] * s[2] - q[2] * s[0])
         + p[2] * (q[0] * s[1] - q[1] * s[0])) for p, q, s in tris) / 6.0


def area(p, q, s):
    u = [q[i] - p[i] for i in range(3)]
    v = [s[i] - p[i] for i in range(3)]
    c = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    return 0.5 * math.sqrt(sum(x * x for x in c)), c


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("--orifice", type=float, required=True)
    ap.add_argument("--half-angle", type=float, default=60.0)
    ap.add_argument("--radius", type=float)
    ap.add_argument("--height", type=float)
    ap.add_argument("--thickness", type=float, default=1.0)
    ap.add_argument("--segments", type=int, default=96)
    a = ap.parse_args(argv)
    D, A, t, n = a.orifice, a.half_angle, a.thickness, a.segments
    R = a.radius if a.radius is not None else max(D, D / 2.0 + 4.0)
    H = a.height if a.height is not None else 3.0 * R
    if not (D > 0 and R > D / 2.0 and t > 0 and 0 < A <= 90 and n >= 8):
        sys.exit("make_hopper.py: need D > 0, R > D/2, T > 0, 0 < A <= 90, N >= 8")
    pts, zc = profile(D, A, R, H, t)
    if H <= zc:
        sys.exit("make_hopper.py: the height %g is below the top of the cone %g" % (H, zc))
    tris = revolve(pts, n)
    if volume(tris) < 0.0:  # faces must point out of the solid
        tris = [(p, s, q) for p, q, s in tris]
    fmt = "%.9g"
    smallest = min(area(*tri)[0] for tri in tris)
    if smallest <= 1e-9:
        sys.exit("make_hopper.py: a degenerate triangle (area %g)" % smallest)
    with open(a.out, "w") as f:
        f.write("solid hopper\n")
        for tri in tris:
            _, c = area(*tri)
            norm = math.sqrt(sum(x * x for x in c))
            f.write(" facet normal %s %s %s\n  outer loop\n" % tuple(fmt % (x / norm) for x in c))
            for p in tri:
                f.write("   vertex %s %s %s\n" % tuple(fmt % x for x in p))
            f.write("  endloop\n endfacet\n")
        f.write("endsolid hopper\n")
    print("orifice %r\nhalf_angle %r\nradius %r\nheight %r\nthickness %r\ncone_top %r\n"
          "segments %d\ntriangles %d\nsolid_volume %.6g" % (D, A, R, H, t, zc, n, len(tris),
                                                            volume(tris)))


if __name__ == "__main__":
    main(sys.argv[1:])
