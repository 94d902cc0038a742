#!/usr/bin/env python3
"""Triaxial specimens side by side, against the report (PEER 2022/06 §3.4.5, Figures 3.12-3.13).

usage: compare.py OUT.png LABEL=triaxial.csv [LABEL=triaxial.csv ...] [--title TEXT] [--spread]
       compare.py --join PART.csv PART.csv ... > JOINED.csv

A CSV may be given as the parts of one interrupted or extended run, PART+PART+... (a resumed
run's CSV, in.triaxial -var part): they are joined as --join does.

For each CSV (examples/triaxial's output) prints one row -- peak mobilised friction angle and
the axial strain there (and the first strain within 0.5 deg of the peak: a flat-topped
peak's argmax wanders along the plateau), the largest dilatancy angle (eq 3.10 over a 1 % strain window), the
volumetric strain at the peak and at the end (+ = contraction), the critical-state angle (mean
phi over the last 3 % of axial strain, from 12 % on when the run is that long) and whether the
specimen softens after its peak and dilates; with run.sh's voids.txt next to the CSV also the
packing's void ratio in the mould and in its core -- and draws phi(eps_a) and eps_v(eps_a) in one
PNG with the report's figures marked: dense high-resolution avatars peak at 46-49 deg at eps_a
2-3.5 % and soften while dilating; its spheres harden and contract to ~35 deg, its loose
(pluviated low-resolution) specimens to 29-30 deg. The summary goes to stdout and, as JSON,
to OUT.json. With --spread (the runs are packings of one specimen) it also prints each
figure's mean, standard deviation and range over the runs, and writes them to OUT.json
under "spread"."""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

REPORT = {
    "dense_peak_phi": (46.0, 49.0),     # §3.5.1: 46.2 deg (mu 0.6) to 49.0 deg (mu 0.75)
    "dense_peak_eps": (2.0, 3.5),       # §3.4.5: a peak at around eps_a = 2.0-3.5 %
    "sphere_phi": 35.0,                 # §3.4.5: phi_p = 35 deg for spheres (hardening)
    "loose_phi": (29.0, 30.0),          # §3.5.1: the pluviated specimen hardens to 29-30 deg
}


def joined_lines(paths):
    """The CSV lines of a run's parts joined: an earlier part's rows before the strain its
    successor's first row has, then the successor's rows. A successor resumed from a
    checkpoint repeats the checkpoint's row with fresh interval averages: there the earlier
    part's row is kept and the repeat dropped."""
    parts = [open(f).read().splitlines() for f in paths]
    rows = parts[0][1:]
    for p in parts[1:]:
        first = p[1].split(",")[0]
        repeat = any(r.split(",")[0] == first for r in rows)
        rows = [r for r in rows if float(r.split(",")[0]) < float(first)] + \
            [r for r in rows if repeat and r.split(",")[0] == first] + p[2 if repeat else 1:]
    return parts[0][:1] + rows


def load(path):
    paths = path.split("+")
    path = paths[0]
    rows = list(csv.DictReader(joined_lines(paths)))
    c = {k: [float(r[k]) for r in rows] for k in rows[0]}
    # the packing's void ratio from run.sh's voids.txt (lattice measure: mould, core)
    vf = os.path.join(os.path.dirname(os.path.abspath(path)), "voids.txt")
    if os.path.exists(vf):
        for line in open(vf):
            w = line.split()
            if len(w) >= 10 and w[8] == "void_ratio":
                c["e_" + w[0]] = float(w[9])
    return c


def window_mean(xs, ys, lo, hi):
    v = [y for x, y in zip(xs, ys) if lo <= x <= hi]
    return sum(v) / len(v) if v else float("nan")


def slope(xs, ys, x0, x1):
    """Least-squares slope of ys over xs in [x0, x1]."""
    pts = [(x, y) for x, y in zip(xs, ys) if x0 <= x <= x1]
    if len(pts) < 3:
        return float("nan")
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx if sxx > 0 else float("nan")


def summary(c):
    ea = [100 * e for e in c["eps_a"]]
    ev = [100 * e for e in c["eps_v"]]
    phi = c["phi_deg"]
    k = max(range(len(phi)), key=lambda i: phi[i])
    # a flat-topped peak: the argmax wanders along the plateau with the noise, so also the
    # first strain where phi comes within 0.5 deg of the peak
    k05 = next(i for i in range(len(phi)) if phi[i] >= phi[k] - 0.5)
    end = ea[-1]
    lo = max(12.0, end - 3.0) if end >= 15.0 else end - 3.0
    crit = window_mean(ea, phi, lo, end)
    # dilatancy angle, eq 3.10, from the slope x = d eps_v / d eps_a over 1 % windows
    psis = []
    x0 = 0.0
    while x0 + 1.0 <= end:
        x = slope(ea, ev, x0, x0 + 1.0)
        if not math.isnan(x):
            psis.append((math.degrees(math.asin(max(-1.0, min(1.0, -x / (2.0 - x))))), x0 + 0.5))
        x0 += 0.5
    psi_max, psi_at = max(psis) if psis else (float("nan"), float("nan"))
    ev_max = max(ev)
    return {
        "peak_phi": phi[k], "eps_peak": ea[k], "eps_peak_within_05": ea[k05], "crit_phi": crit, "crit_window": [lo, end],
        "psi_max": psi_max, "psi_max_at": psi_at, "epsv_peak": ev[k], "epsv_end": ev[-1],
        "epsv_max_contraction": ev_max, "softening": phi[k] - crit,
        "dilates": ev[-1] < ev_max - 0.5, "e0": c["e"][0] if "e" in c else None,
        "e_mould": c.get("e_mould"), "e_core": c.get("e_core"),
        "eps_end": end, "Z0": c["Z"][0] if "Z" in c else None,
    }


SPREAD_KEYS = ("e_mould", "e_core", "e0", "peak_phi", "eps_peak", "eps_peak_within_05", "psi_max",
               "epsv_max_contraction", "epsv_end", "crit_phi", "softening")


def spread(rows):
    """Mean, sample standard deviation, min and max of each figure over the runs."""
    out = {}
    for key in SPREAD_KEYS:
        v = [s[key] for _, s in rows if s.get(key) is not None]
        if not v:
            continue
        m = sum(v) / len(v)
        sd = math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1)) if len(v) > 1 else 0.0
        out[key] = {"mean": m, "sd": sd, "min": min(v), "max": max(v), "n": len(v)}
    return out


def main():
    args = sys.argv[1:]
    if args[:1] == ["--join"]:
        print("\n".join(joined_lines(args[1:])))
        return
    title = None
    with_spread = "--spread" in args
    if with_spread:
        args.remove("--spread")
    if "--title" in args:
        i = args.index("--title")
        title = args[i + 1]
        del args[i:i + 2]
    if len(args) < 2:
        sys.exit(__doc__)
    out = args[0]
    runs = []
    for a in args[1:]:
        label, path = a.split("=", 1)
        runs.append((label, load(path)))
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.8))
    # the report's figures
    a1.add_patch(plt.Rectangle((REPORT["dense_peak_eps"][0], REPORT["dense_peak_phi"][0]),
                               REPORT["dense_peak_eps"][1] - REPORT["dense_peak_eps"][0],
                               REPORT["dense_peak_phi"][1] - REPORT["dense_peak_phi"][0],
                               color="0.6", alpha=0.45, lw=0,
                               label="report: dense avatars' peak (46-49 deg, 2-3.5 %)"))
    a1.axhline(REPORT["sphere_phi"], color="0.4", ls="--", lw=1,
               label="report: spheres, hardening to ~35 deg")
    a1.axhspan(*REPORT["loose_phi"], color="0.4", alpha=0.25, lw=0,
               label="report: loose (pluviated) specimen, 29-30 deg")
    rows = []
    for label, c in runs:
        s = summary(c)
        rows.append((label, s))
        ea = [100 * e for e in c["eps_a"]]
        line, = a1.plot(ea, c["phi_deg"], label=label, lw=1.4)
        a1.plot([s["eps_peak"]], [s["peak_phi"]], "o", color=line.get_color())
        a2.plot(ea, [100 * e for e in c["eps_v"]], label=label, lw=1.4, color=line.get_color())
    a1.set_xlabel("axial strain eps_a (%)")
    a1.set_ylabel("mobilised friction angle phi (deg)")
    a1.set_ylim(0, 55)
    a1.grid(alpha=0.3)
    a1.legend(fontsize=7, loc="lower right")
    a2.set_xlabel("axial strain eps_a (%)")
    a2.set_ylabel("volumetric strain eps_v (%, + = contraction)")
    a2.axhline(0, color="0.5", lw=0.8)
    a2.invert_yaxis()  # dilation up, as the report draws it
    a2.grid(alpha=0.3)
    a2.legend(fontsize=8)
    if title:
        fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    head = ("%-28s %7s %7s %7s %7s %7s %7s %9s %9s %9s %8s %8s %7s" %
            ("specimen", "e_mould", "e_core", "e0", "peak", "eps_pk", "pk-0.5", "psi_max", "epsv_pk",
             "epsv_end", "crit", "soften", "dilates"))
    print(head)
    for label, s in rows:
        fmt = lambda v: "%.3f" % v if v is not None else "-"
        print("%-28s %7s %7s %7s %6.1f° %6.1f%% %6.1f%% %8.1f° %8.2f%% %8.2f%% %7.1f° %7.1f° %7s" %
              (label, fmt(s["e_mould"]), fmt(s["e_core"]), fmt(s["e0"]), s["peak_phi"],
               s["eps_peak"], s["eps_peak_within_05"], s["psi_max"], s["epsv_peak"], s["epsv_end"], s["crit_phi"],
               s["softening"], "yes" if s["dilates"] else "no"))
    result = {label: s for label, s in rows}
    if with_spread:
        result["spread"] = spread(rows)
        print("over %d runs: mean +- sd (min - max)" % len(rows))
        for key, v in result["spread"].items():
            print("  %-20s %8.3f +- %6.3f  (%.3f - %.3f)" % (key, v["mean"], v["sd"], v["min"], v["max"]))
    json.dump(result, open(out.rsplit(".", 1)[0] + ".json", "w"), indent=1)
    print("plot: %s" % out)


if __name__ == "__main__":
    main()
