#!/usr/bin/python3
"""lsdem-rose: a spherical histogram of directions on equal-area bins, drawn as a PNG
hemisphere map (doc/lsdem_rose.rst).

usage: lsdem-rose OUT.png INPUT [--rings N] [--sectors K] [--walls] [--columns A B C]
                  [--title TEXT]

INPUT is a .vtp of fix network/lsdem (its *normal* cell array: the contact normals of the
grain-grain lines; --walls adds the wall lines) or a LAMMPS custom dump, whose last frame's
columns A B C (default c_fab[3] c_fab[4] c_fab[5], compute fabric/lsdem's long axes) are the
directions. Directions are axial (n and -n the same): each is taken on the upper hemisphere
(z > 0; on the equator the one with azimuth in [0, 180) deg).

Bins: N rings (default 6) of polar angle theta with 1 - cos(theta_i) = (i/N)^2, ring i cut
into K (2i - 1) sectors of azimuth (default K = 4): every bin has the area 2 pi / (K N^2) of
the unit hemisphere. In the Lambert azimuthal equal-area projection (r = 2 sin(theta/2)) the
ring edges are evenly spaced circles, r_i = sqrt(2) i / N, so the map shows the bins with
their true relative areas. Writes OUT.png (each bin coloured by its density: count over the
count a uniform distribution would put there) and OUT.csv (one row per bin)."""
import argparse
import math
import re
import sys


def bins(rings, sectors):
    """The equal-area partition of the upper hemisphere: a list of (ring, sector, theta_lo,
    theta_hi, phi_lo, phi_hi), rings 1..N from the pole, angles in radians."""
    out = []
    for i in range(1, rings + 1):
        t0 = math.acos(1.0 - ((i - 1) / rings) ** 2)
        t1 = math.acos(1.0 - (i / rings) ** 2)
        m = sectors * (2 * i - 1)
        for j in range(m):
            out.append((i, j, t0, t1, 2 * math.pi * j / m, 2 * math.pi * (j + 1) / m))
    return out


def upper(v):
    """The axial direction v (any length > 0) as a unit vector on the upper hemisphere."""
    x, y, z = v
    n = math.sqrt(x * x + y * y + z * z)
    if z < 0 or (z == 0 and (y < 0 or (y == 0 and x < 0))):
        x, y, z = -x, -y, -z
    return x / n + 0.0, y / n + 0.0, z / n + 0.0   # + 0.0: no -0 (its azimuth would be 180)


def bin_of(v, rings, sectors):
    """(ring, sector) of direction v: ring i where (i-1)^2 <= N^2 (1 - cos theta) < i^2."""
    x, y, z = upper(v)
    i = min(rings, 1 + int(math.floor(rings * math.sqrt(max(0.0, 1.0 - z)))))
    m = sectors * (2 * i - 1)
    phi = math.atan2(y, x) % (2 * math.pi)
    return i, min(m - 1, int(math.floor(phi / (2 * math.pi) * m)))


def histogram(vectors, rings, sectors):
    """{(ring, sector): count} over every bin of bins()."""
    counts = {(b[0], b[1]): 0 for b in bins(rings, sectors)}
    for v in vectors:
        counts[bin_of(v, rings, sectors)] += 1
    return counts


def read_vtp(path, walls):
    text = open(path).read()
    arrays = dict(re.findall(r'Name="(\w+)"[^>]*>\n([^<]*)</DataArray>', text))
    if "normal" not in arrays:
        sys.exit("lsdem-rose: %s has no normal array (fix network/lsdem writes one)" % path)
    ids = [float(v) for v in arrays["id_b"].split()]
    n = [float(v) for v in arrays["normal"].split()]
    return [tuple(n[3 * k:3 * k + 3]) for k, b in enumerate(ids) if walls or b > 0]


def read_dump(path, columns):
    frames = open(path).read().split("ITEM: TIMESTEP")
    lines = frames[-1].split("ITEM: ATOMS")[1].splitlines()
    head = lines[0].split()
    missing = [c for c in columns if c not in head]
    if missing:
        sys.exit("lsdem-rose: %s has no column %s (columns: %s)" % (path, missing, head))
    idx = [head.index(c) for c in columns]
    return [tuple(float(w[k]) for k in idx) for w in (line.split() for line in lines[1:] if line.strip())]


def draw(png, counts, rings, sectors, total, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PatchCollection
    from matplotlib.patches import Wedge
    patches, dens = [], []
    uniform = total / (sectors * rings * rings) if total else 1.0
    for i, j, t0, t1, p0, p1 in bins(rings, sectors):
        r0, r1 = 2 * math.sin(t0 / 2), 2 * math.sin(t1 / 2)
        patches.append(Wedge((0, 0), r1, math.degrees(p0), math.degrees(p1), width=r1 - r0))
        dens.append(counts[(i, j)] / uniform)
    fig, ax = plt.subplots(figsize=(5.5, 4.6))
    pc = PatchCollection(patches, cmap="viridis", edgecolor="white", linewidth=0.4)
    pc.set_array(dens)
    ax.add_collection(pc)
    fig.colorbar(pc, ax=ax, label="density / uniform")
    lim = math.sqrt(2) * 1.08
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_aspect("equal")
    ax.axis("off")
    for label, x, y in (("+x", lim, 0), ("+y", 0, lim)):
        ax.text(x, y, label, ha="center", va="center", fontsize=9)
    ax.set_title("%s\n%d directions, %d equal-area bins, upper hemisphere (Lambert)"
                 % (title, total, len(patches)), fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(prog="lsdem-rose", description=__doc__.split("\n\n")[0])
    ap.add_argument("png")
    ap.add_argument("input")
    ap.add_argument("--rings", type=int, default=6)
    ap.add_argument("--sectors", type=int, default=4)
    ap.add_argument("--walls", action="store_true")
    ap.add_argument("--columns", nargs=3, default=["c_fab[3]", "c_fab[4]", "c_fab[5]"])
    ap.add_argument("--title", default=None)
    a = ap.parse_args(argv)
    if a.rings < 1 or a.sectors < 1:
        sys.exit("lsdem-rose: --rings and --sectors must be at least 1")
    vtp = a.input.endswith(".vtp")
    vectors = read_vtp(a.input, a.walls) if vtp else read_dump(a.input, a.columns)
    vectors = [v for v in vectors if any(v)]      # atoms outside the compute's group: 0
    counts = histogram(vectors, a.rings, a.sectors)
    title = a.title or ("contact normals" if vtp else "long axes")
    draw(a.png, counts, a.rings, a.sectors, len(vectors), title)
    area = 2 * math.pi / (a.sectors * a.rings ** 2)
    uniform = len(vectors) / (a.sectors * a.rings ** 2) if vectors else 1.0
    csv = re.sub(r"\.png$", "", a.png) + ".csv"
    with open(csv, "w") as f:
        f.write("ring,sector,theta_lo_deg,theta_hi_deg,phi_lo_deg,phi_hi_deg,area,count,density\n")
        for i, j, t0, t1, p0, p1 in bins(a.rings, a.sectors):
            f.write("%d,%d,%.6f,%.6f,%.6f,%.6f,%.12g,%d,%.6g\n"
                    % (i, j, math.degrees(t0), math.degrees(t1), math.degrees(p0),
                       math.degrees(p1), area, counts[(i, j)], counts[(i, j)] / uniform))
    top = max(counts, key=counts.get)
    print("%s: %d directions in %d bins; the fullest: ring %d sector %d, %d (%.2f x uniform)"
          % (a.png, len(vectors), len(counts), top[0], top[1], counts[top],
             counts[top] / uniform))


if __name__ == "__main__":
    main(sys.argv[1:])
