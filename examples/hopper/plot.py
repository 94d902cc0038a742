#!/usr/bin/env python3
"""Analyse a hopper run of in.hopper: the settled bed's bulk density and height, the steady
discharge rate, Beverloo's law; draw the discharged mass and the rate against time.

Usage: plot.py PREFIX.csv PREFIX_settled.dump HOPPER.txt OUT.png [--window F1 F2] [--g G]
  HOPPER.txt: make_hopper.py's `key value` lines (orifice, radius, half_angle, cone_top);
  --window: fit the rate where the discharged mass is between F1 and F2 of the bed's mass
  (default 0.1 0.6); --g gravity (default 1, as in.hopper).
Prints `key value` lines (bulk_density, fill_height, rate, rate_err, beverloo ...).

Definitions
  bulk density rho_b: mass of the grains whose centres lie in the bin's cylinder r < R
    between z = cone_top + 1 and the bed's surface less 2.5 d (the surface: the 99th
    percentile of the grains' heights), over that slab's volume pi R^2 dz;
  fill height: the height above the orifice of a level surface holding the bed's mass at
    rho_b (the cone's frustum plus a cylinder);
  rate W: slope of a least-squares line through the discharged mass in the window; its
    error: the spread (standard deviation / sqrt(n)) of the slopes of the window's 4
    quarters;
  Beverloo: W = C rho_b sqrt(g) (D - k d)^(5/2), here with C = 0.58, k = 1.4, d = 1."""
import math
import sys


def read_kv(path):
    out = {}
    for line in open(path):
        p = line.split()
        if len(p) >= 2:
            try:
                out[p[0]] = float(p[1])
            except ValueError:
                out[p[0]] = p[1]
    return out


def read_csv(path):
    lines = [l.strip() for l in open(path) if l.strip() and not l.startswith("#")]
    head = lines[0].split(",")
    rows = [dict(zip(head, map(float, l.split(",")))) for l in lines[1:]]
    return rows


def read_dump(path):
    """(x, y, z, mass) of a LAMMPS text dump's last frame with columns id x y z mass."""
    lines = open(path).read().split("\n")
    i = max(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[i].split()[2:]
    ix, iy, iz, im = (cols.index(c) for c in ("x", "y", "z", "mass"))
    out = []
    for l in lines[i + 1:]:
        p = l.split()
        if len(p) == len(cols):
            out.append((float(p[ix]), float(p[iy]), float(p[iz]), float(p[im])))
    return out


def bed(grains, geo):
    """Bulk density, surface height, fill height, bed mass of the settled grains."""
    R, D, zc = geo["radius"], geo["orifice"], geo["cone_top"]
    zs = sorted(g[2] for g in grains)
    surface = zs[min(len(zs) - 1, int(0.99 * len(zs)))] + 0.5
    z0, z1 = zc + 1.0, surface - 2.5
    if z1 - z0 < 1.0:  # a bed hardly above the cone: the whole bed above the orifice
        z0, z1 = 0.0, surface
        vol = frustum(D, R, zc, min(z1, zc)) + math.pi * R * R * max(0.0, z1 - zc)
    else:
        vol = math.pi * R * R * (z1 - z0)
    m = sum(g[3] for g in grains if z0 <= g[2] < z1)
    rho = m / vol
    total = sum(g[3] for g in grains if g[2] > 0.0)
    cone = frustum(D, R, zc, zc)
    if total / rho <= cone:
        fill = zc * (total / rho / cone) ** (1.0 / 3.0)  # rough: within the cone
    else:
        fill = zc + (total / rho - cone) / (math.pi * R * R)
    return dict(bulk_density=rho, surface=surface, fill_height=fill, bed_mass=total,
                slab=(z0, z1))


def frustum(D, R, zc, z):
    """Volume of the cone's inside from z = 0 to z (<= zc)."""
    if zc <= 0.0 or z <= 0.0:
        return 0.0
    r1 = D / 2.0
    r2 = r1 + (R - r1) * z / zc
    return math.pi * z / 3.0 * (r1 * r1 + r1 * r2 + r2 * r2)


def linfit(t, m):
    n = len(t)
    tm, mm = sum(t) / n, sum(m) / n
    stt = sum((a - tm) ** 2 for a in t)
    slope = sum((a - tm) * (b - mm) for a, b in zip(t, m)) / stt
    return slope, mm - slope * tm


def rate(rows, m0, window=(0.1, 0.6), tmin=0.0):
    """Steady discharge rate: a line through the discharged mass between F1 and F2 of m0,
    from time tmin on."""
    sel = [r for r in rows if window[0] * m0 <= r["discharged_mass"] <= window[1] * m0
           and r["time"] >= tmin]
    if len(sel) < 8:
        return None
    t = [r["time"] for r in sel]
    m = [r["discharged_mass"] for r in sel]
    w, b = linfit(t, m)
    q = len(sel) // 4
    parts = [linfit(t[k * q:(k + 1) * q], m[k * q:(k + 1) * q])[0] for k in range(4)]
    mean = sum(parts) / 4
    err = math.sqrt(sum((p - mean) ** 2 for p in parts) / 3) / 2
    return dict(rate=w, intercept=b, rate_err=err, t0=t[0], t1=t[-1], quarters=parts)


def beverloo(rho, D, C=0.58, k=1.4, g=1.0):
    return C * rho * math.sqrt(g) * max(D - k, 0.0) ** 2.5


def analyse(csv, dump, geo, window=(0.1, 0.6), g=1.0, tmin=0.0):
    rows = read_csv(csv)
    b = bed(read_dump(dump), geo)
    r = rate(rows, b["bed_mass"], window, tmin)
    out = dict(b)
    out["grains"] = int(rows[0]["grains_above_orifice"]) if rows else 0
    out["rows"] = rows
    if r:
        out.update(r)
        pred = beverloo(b["bulk_density"], geo["orifice"], g=g)
        out["beverloo"] = pred
        out["C_fixed_k"] = r["rate"] / (b["bulk_density"] * math.sqrt(g)
                                        * (geo["orifice"] - 1.4) ** 2.5)
    return out


def draw(res, geo, png, title=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = res["rows"]
    t = [r["time"] for r in rows]
    m = [r["discharged_mass"] for r in rows]
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    a1.plot(t, m, "k-", lw=1.2, label="discharged mass")
    if "rate" in res:
        tt = [res["t0"], res["t1"]]
        a1.plot(tt, [res["intercept"] + res["rate"] * x for x in tt], "r--", lw=2,
                label="fit: W = %.3g $\\pm$ %.2g" % (res["rate"], res["rate_err"]))
    a1.set_xlabel("time since the plug was removed [$\\sqrt{d/g}$]")
    a1.set_ylabel("discharged mass [$\\rho_s d^3$]")
    a1.legend(loc="upper left")
    a1.grid(alpha=0.3)
    # the rate over sliding windows of ~1 time unit
    k = max(1, int(round(1.0 / (t[1] - t[0])))) if len(t) > 1 else 1
    tc = [(t[i] + t[i + k]) / 2 for i in range(len(t) - k)]
    wc = [(m[i + k] - m[i]) / (t[i + k] - t[i]) for i in range(len(t) - k)]
    a2.plot(tc, wc, "k-", lw=1, label="dM/dt over %.2g time units" % (t[k] - t[0] if k < len(t) else 0))
    if "rate" in res:
        a2.axhline(res["rate"], color="r", ls="--", label="steady rate (fit)")
        a2.axhline(res["beverloo"], color="b", ls=":",
                   label="Beverloo C = 0.58, k = 1.4: %.3g" % res["beverloo"])
    a2.set_xlabel("time since the plug was removed [$\\sqrt{d/g}$]")
    a2.set_ylabel("discharge rate W [$\\rho_s d^3 / \\sqrt{d/g}$]")
    a2.legend(loc="lower center", fontsize=8)
    a2.grid(alpha=0.3)
    fig.suptitle(title or "hopper D = %g d, half-angle %g deg, bin R = %g d: %d grains, "
                 "bed %.1f d, rho_b = %.3f" % (geo["orifice"], geo["half_angle"], geo["radius"],
                                               res["grains"], res["fill_height"],
                                               res["bulk_density"]))
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def main(argv):
    if len(argv) < 4:
        sys.exit(__doc__)
    csv, dump, geo_path, png = argv[:4]
    window, g = (0.1, 0.6), 1.0
    if "--window" in argv:
        i = argv.index("--window")
        window = (float(argv[i + 1]), float(argv[i + 2]))
    if "--g" in argv:
        g = float(argv[argv.index("--g") + 1])
    geo = read_kv(geo_path)
    res = analyse(csv, dump, geo, window, g)
    draw(res, geo, png)
    for key in ("grains", "bed_mass", "bulk_density", "surface", "fill_height", "rate",
                "rate_err", "t0", "t1", "beverloo", "C_fixed_k"):
        if key in res:
            v = res[key]
            print("%s %s" % (key, ("%.5g" % v) if isinstance(v, float) else v))
    grains = read_dump(dump)
    rho_s = sum(g[3] for g in grains) / len(grains) / (math.pi / 6.0)  # spheres of d = 1
    print("solid_fraction %.4f" % (res["bulk_density"] / rho_s))


if __name__ == "__main__":
    main(sys.argv[1:])
