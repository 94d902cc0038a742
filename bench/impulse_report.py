#!/usr/bin/env python3
"""The figures of bench/impulse.sh: the container release (report §4.6.1) by the penalty
method at dt and the impulse method at multiples of dt, from the runs' logs and final dumps.

  impulse_report.py OUTDIR GRAINS [--dmin D] [--packings "DIR=SEED ..."]
                    [--variant NAME:OPTS ...] TAG...
  TAG: penalty, impulse_x<m>, impulse_x<m>_np2, impulse_<NAME>_x<m>, impulse_<NAME>_x<m>_np2
  --packings: the packings' folders under OUTDIR (default ".", seed 7), each holding the
              runs of every TAG (log.TAG, mound_TAG.dump)
  --variant:  the options of the impulse setting NAME ("" for impulse_x<m>), for the tables
  --dmin:     the smallest grain's equivalent diameter (the penetration's yardstick,
              2.5 % of it; default 0.4)

Prints, per run and packing, a table (loop s = the run's loop time, wall clock, and LAMMPS's
CPU use of it: below 100 % the machine was shared and the loop time is inflated; CPU s =
loop s x CPU use x ranks; speed-up over the packing's penalty run; mound height and spread,
examples/container_release/mound.py, and their difference from the packing's penalty run;
islands, ETM iterations and passes per step sampled at the thermo rows; label-exchange
rounds and the deepest grain-grain penetration seen, also over 2.5 % of d_min); then per
run over the packings the mean, sample std and min..max of height and spread, the mean and
std of the per-packing differences, and whether the mean lies within 5 % of the penalty
runs' mean, within their sample std and within their min..max; then the fix's counters
(every thermo column is read by its name in the log's header, so extra columns of the fix
are listed, not misread). Writes impulse.csv (per run and packing), impulse_summary.csv
(over the packings), impulse_counters.csv (mean, max and last of every counter column),
impulse_error.png (error in height and spread against run time, one series per impulse
setting) and, from lsdem-shape renders when present, impulse_mounds.png (first packing)."""
import argparse
import csv
import math
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "examples", "container_release"))
from mound import mound  # noqa: E402

TAG = re.compile(r"^impulse(?:_([A-Za-z0-9][A-Za-z0-9.-]*))?_x(\d+)(_np2)?$")
# the fix's vector (doc/fix_impulse_lsdem.rst) as far as the tables use it
ISLANDS, LARGEST, ITER, PASSES, ROUNDS, DEPTH = ("f_integrate[%d]" % k
                                                 for k in (1, 2, 4, 5, 8, 20))
SPLIT = ["f_integrate[%d]" % k for k in range(15, 20)]
KNOWN = {"f_integrate[%d]" % k for k in range(1, 22)}
BASE = {"Step", "Time", "KinEng", "CPU", "Elapsed", "Temp", "PotEng", "TotEng", "Press"}


def log_figures(path):
    """Loop time, steps, ranks, CPU use (%), the thermo header and rows of a LAMMPS log.
    Rows are dicts keyed by the header's column names (any number of columns)."""
    text = open(path).read()
    m = re.search(r"Loop time of ([\d.e+-]+) on (\d+) procs for (\d+) steps", text)
    if not m:
        raise SystemExit("%s: no 'Loop time' line (the run did not finish)" % path)
    use = re.search(r"([\d.]+)% CPU use", text)
    rows, header, names = [], None, []
    for ln in text.splitlines():
        parts = ln.split()
        if parts[:1] == ["Step"]:
            header = parts
            names = names + [c for c in parts if c not in names]
            continue
        if header and len(parts) == len(header):
            try:
                rows.append(dict(zip(header, map(float, parts))))
            except ValueError:
                header = None
        elif header and not ln.startswith("WARNING"):
            header = None
    return (float(m.group(1)), int(m.group(2)), int(m.group(3)),
            float(use.group(1)) if use else float("nan"), names, rows)


def mean(vals):
    vals = [v for v in vals if v is not None and not math.isnan(v)]
    return sum(vals) / len(vals) if vals else float("nan")


def std(vals):
    """Sample standard deviation (n - 1); nan below two values."""
    vals = [v for v in vals if v is not None and not math.isnan(v)]
    if len(vals) < 2:
        return float("nan")
    m = mean(vals)
    return math.sqrt(sum((v - m) ** 2 for v in vals) / (len(vals) - 1))


def nmax(vals):
    """The largest value that is a number; nan when none is."""
    vals = [v for v in vals if v is not None and not math.isnan(v)]
    return max(vals) if vals else float("nan")


def fmt(v, f):
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else f % v


def counters(names, rows):
    """Mean, max and last value over the thermo rows after step 0 of every column that is
    not one of thermo's basic keywords (the fix's vector, whatever its length)."""
    rows = [x for x in rows if x.get("Step", 0) > 0]
    out = {}
    for c in names:
        if c in BASE:
            continue
        vals = [x[c] for x in rows if c in x]
        if vals:
            out[c] = dict(rows=len(vals), mean=mean(vals), max=max(vals), last=vals[-1])
    return out


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--dmin", type=float, default=0.4)
    p.add_argument("--packings", default=".")
    p.add_argument("--variant", action="append", default=[])
    p.add_argument("out")
    p.add_argument("grains", type=int)
    p.add_argument("tags", nargs="+")
    return p.parse_intermixed_args(argv)


def describe(tag):
    """(method, variant name or None, dt multiple, ranks-2 flag) of a run's tag."""
    if tag == "penalty":
        return "penalty", None, 1, False
    m = TAG.match(tag)
    if not m:
        return "impulse", "?", float("nan"), False
    return "impulse", m.group(1) or "", int(m.group(2)), bool(m.group(3))


def main():
    a = parse_args(sys.argv[1:])
    out, grains, tags = a.out, a.grains, a.tags
    limit = 0.025 * a.dmin
    packings = []
    for item in a.packings.split():
        d, _, seed = item.partition("=")
        packings.append((d, seed or ("7" if d == "." else d)))
    vopts = {}
    for v in a.variant:
        name, _, o = v.partition(":")
        vopts[name] = o
    if "penalty" not in tags:
        raise SystemExit("no penalty run among %s" % tags)

    runs = []
    for pdir, seed in packings:
        for tag in tags:
            base = os.path.join(out, pdir)
            seconds, procs, steps, use, names, rows = log_figures(
                os.path.join(base, "log.%s" % tag))
            h, s, n = mound(os.path.join(base, "mound_%s.dump" % tag))
            method, variant, mul, _ = describe(tag)
            r = dict(tag=tag, pdir=pdir, packing=seed, method=method, variant=variant, mul=mul,
                     seconds=seconds, use=use, cpu=seconds * use / 100.0 * procs, procs=procs,
                     steps=steps, height=h, spread=s, grains=n,
                     us=1e6 * seconds * procs / (grains * steps), counters=counters(names, rows))
            c = r["counters"]
            get = (lambda k, f: c[k][f] if k in c else float("nan"))
            if any(k.startswith("f_integrate[") for k in c):
                r.update(islands=get(ISLANDS, "mean"), largest=get(LARGEST, "max"),
                         iterations=get(ITER, "mean"), passes=get(PASSES, "mean"),
                         rounds=get(ROUNDS, "max"), depth=get(DEPTH, "max"),
                         split=[get(k, "last") for k in SPLIT])
            runs.append(r)
    ref = {r["pdir"]: r for r in runs if r["tag"] == "penalty"}
    for r in runs:
        p = ref[r["pdir"]]
        r["speedup"] = p["seconds"] / r["seconds"]
        r["dH"] = 100 * (r["height"] / p["height"] - 1)
        r["dS"] = 100 * (r["spread"] / p["spread"] - 1)

    def vname(r):
        return "-" if r["variant"] is None else (r["variant"] or "default")

    # ---- per run and packing
    cols = ("run", "packing", "variant", "x dt", "ranks", "steps", "loop s", "CPU use %",
            "CPU s", "us/grain-step", "speed-up", "height", "spread", "dH %", "dS %",
            "islands", "largest", "ETM it/step", "passes", "rounds", "depth", "depth/limit")
    print("per run (packing = pack seed; dH, dS: against the packing's penalty mound; "
          "depth/limit: deepest grain-grain penetration over 2.5 %% of d_min = %.4g)" % limit)
    print(" | ".join(cols))
    table = []
    for r in runs:
        row = [r["tag"], r["packing"], vname(r), fmt(r["mul"], "%d"), r["procs"], r["steps"],
               "%.4g" % r["seconds"], "%.0f" % r["use"], "%.4g" % r["cpu"], "%.2f" % r["us"],
               "%.2f" % r["speedup"], "%.3f" % r["height"], "%.3f" % r["spread"],
               "%+.1f" % r["dH"], "%+.1f" % r["dS"]]
        if "islands" in r:
            row += [fmt(r["islands"], "%.0f"), fmt(r["largest"], "%d"),
                    fmt(r["iterations"], "%.0f"), fmt(r["passes"], "%.1f"),
                    fmt(r["rounds"], "%d"), fmt(r["depth"], "%.3g"),
                    fmt(r["depth"] / limit, "%.2f")]
        else:
            row += ["-"] * 7
        table.append(row)
        print(" | ".join(str(c) for c in row))
    with open(os.path.join(out, "impulse.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        w.writerows(table)

    # ---- over the packings
    groups = [(t, [r for r in runs if r["tag"] == t]) for t in tags]
    pen = dict(groups)["penalty"]
    npk = len(packings)
    pH = [r["height"] for r in pen]
    pS = [r["spread"] for r in pen]

    def verdicts(vals, pvals):
        m, pm, ps = mean(vals), mean(pvals), std(pvals)
        rel = 100 * (m / pm - 1)
        in5 = "yes" if abs(rel) <= 5.0 else "no"
        if len(pvals) < 2:
            return rel, in5, "n/a", "n/a"
        instd = "yes" if abs(m - pm) <= ps else "no"
        inrange = "yes" if min(pvals) <= m <= max(pvals) else "no"
        return rel, in5, instd, inrange

    scols = ("run", "variant", "x dt", "ranks", "packings", "loop s", "CPU s", "speed-up",
             "height", "height std", "height min", "height max", "spread", "spread std",
             "spread min", "spread max", "dH %", "dH std", "dS %", "dS std",
             "H vs penalty mean %", "H within 5 %", "H within penalty std",
             "H within penalty range", "S vs penalty mean %", "S within 5 %",
             "S within penalty std", "S within penalty range", "passes", "depth",
             "depth/limit", "options")
    summary = []
    print()
    print("over %d packing(s) (seeds %s): mean, sample std [min..max]; dH, dS: mean (std) of "
          "the per-packing differences; vs penalty: the mean against the penalty runs' mean "
          "(within 5 %%, within their std, within their min..max)"
          % (npk, " ".join(s for _, s in packings)))
    print(" | ".join(("run", "variant", "loop s", "CPU s", "speed-up", "height", "spread",
                      "dH %", "dS %", "H vs penalty", "S vs penalty", "passes", "depth/limit")))
    for t, g in groups:
        r0 = g[0]
        H, S = [r["height"] for r in g], [r["spread"] for r in g]
        hv, sv = verdicts(H, pH), verdicts(S, pS)
        if t == "penalty":
            hv = sv = (0.0, "-", "-", "-")
        imp = [r for r in g if "islands" in r]
        passes = mean([r["passes"] for r in imp]) if imp else float("nan")
        depth = nmax([r["depth"] for r in imp])
        row = dict(zip(scols, (
            t, vname(r0), fmt(r0["mul"], "%d"), r0["procs"], len(g),
            "%.4g" % mean([r["seconds"] for r in g]), "%.4g" % mean([r["cpu"] for r in g]),
            "%.2f" % mean([r["speedup"] for r in g]),
            "%.4f" % mean(H), fmt(std(H), "%.4f"), "%.4f" % min(H), "%.4f" % max(H),
            "%.4f" % mean(S), fmt(std(S), "%.4f"), "%.4f" % min(S), "%.4f" % max(S),
            "%+.2f" % mean([r["dH"] for r in g]), fmt(std([r["dH"] for r in g]), "%.2f"),
            "%+.2f" % mean([r["dS"] for r in g]), fmt(std([r["dS"] for r in g]), "%.2f"),
            "%+.2f" % hv[0], hv[1], hv[2], hv[3], "%+.2f" % sv[0], sv[1], sv[2], sv[3],
            fmt(passes, "%.2f"), fmt(depth, "%.3g"), fmt(depth / limit, "%.2f"),
            vopts.get(r0["variant"], "") if r0["variant"] is not None else "")))
        summary.append(row)

        def ms(k):
            if len(g) < 2:
                return row[k]
            return "%s +- %s [%s..%s]" % (row[k], row[k + " std"], row[k + " min"],
                                           row[k + " max"])

        def md(k):
            return row[k] if len(g) < 2 else "%s (%s)" % (row[k], row[k[:2] + " std"])

        def vs(v):
            return "%+.1f %% (5 %%: %s, std: %s, range: %s)" % v
        print(" | ".join(str(c) for c in (
            t, row["variant"], row["loop s"], row["CPU s"], row["speed-up"], ms("height"),
            ms("spread"), md("dH %"), md("dS %"),
            vs(hv) if t != "penalty" else "-", vs(sv) if t != "penalty" else "-",
            row["passes"], row["depth/limit"])))
    with open(os.path.join(out, "impulse_summary.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=scols)
        w.writeheader()
        w.writerows(summary)

    # ---- counters
    print()
    print("counters of fix impulse/lsdem (thermo rows after step 0, every 0.5 s; over the "
          "packings):")
    for t, g in groups:
        imp = [r for r in g if "islands" in r]
        if not imp:
            continue
        depth = nmax([r["depth"] for r in imp])
        if math.isnan(depth):
            pen_text = "not in the log"
        else:
            pen_text = "%.4g = %.2f x 2.5 %% of d_min %.4g (%.4g): %s" % (
                depth, depth / limit, a.dmin, limit,
                "within it" if depth <= limit else "ABOVE it")
        print("  %s: passes (f_integrate[5]) mean %s; deepest grain-grain penetration "
              "(f_integrate[20], max) %s" % (t, fmt(mean([r["passes"] for r in imp]), "%.2f"),
                                            pen_text))
        sp = [mean([r["split"][k] for r in imp]) for k in range(5)]
        if not all(math.isnan(x) for x in sp):
            print("    time split (s): detection %s, islands %s, ETM %s, walls %s, "
                  "communication %s" % tuple(fmt(x, "%.3g") for x in sp))
        extra = sorted({c for r in imp for c in r["counters"]
                        if c.startswith("f_") and c not in KNOWN},
                       key=lambda c: [int(x) if x.isdigit() else x
                                      for x in re.split(r"(\d+)", c)])
        if extra:
            print("    further columns (mean / max): " + ", ".join(
                "%s %s / %s" % (c, fmt(mean([r["counters"][c]["mean"] for r in imp
                                              if c in r["counters"]]), "%.4g"),
                                fmt(nmax([r["counters"][c]["max"] for r in imp
                                          if c in r["counters"]]), "%.4g")) for c in extra))
    with open(os.path.join(out, "impulse_counters.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(("run", "packing", "column", "rows", "mean", "max", "last"))
        for r in runs:
            for c, v in r["counters"].items():
                w.writerow((r["tag"], r["packing"], c, v["rows"], "%.6g" % v["mean"],
                            "%.6g" % v["max"], "%.6g" % v["last"]))

    # ---- error against run time, one series per impulse setting
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sys.path.insert(0, HERE)
    from figures import save_panels
    fig, ax = plt.subplots(1, 1, figsize=(6.4, 4.4))
    names = []
    for t, g in groups:
        if g[0]["method"] == "impulse" and g[0]["procs"] == 1 and g[0]["variant"] not in names:
            names.append(g[0]["variant"])
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, v in enumerate(names):
        one = [(t, g) for t, g in groups
               if g[0]["variant"] == v and g[0]["procs"] == 1 and g[0]["method"] == "impulse"]
        label = "impulse" if not v else "impulse %s" % v
        for key, dkey, pvals, mark, ls in (("height", "dH", pH, "o", "-"),
                                           ("spread", "dS", pS, "s", "--")):
            xs = [mean([r["seconds"] for r in g]) for _, g in one]
            ys = [100 * abs(mean([r[key] for r in g]) / mean(pvals) - 1) for _, g in one]
            es = [std([r[dkey] for r in g]) for _, g in one]
            es = [0.0 if math.isnan(e) else e for e in es]
            ax.errorbar(xs, ys, yerr=es if npk > 1 else None, fmt=mark + ls,
                        color=colours[k % len(colours)], capsize=2,
                        label="%s: |error| in mound %s" % (label, key))
            for (t, _), x, y in zip(one, xs, ys):
                ax.annotate("x%d" % describe(t)[2], (x, y), fontsize=7, xytext=(3, 3),
                            textcoords="offset points")
    ax.axvline(mean([r["seconds"] for r in pen]), color="k", ls="--",
               label="penalty run (the reference)")
    ax.axhline(5.0, color="grey", ls=":", label="5 %")
    if npk > 1:
        for pvals, name, ls in ((pH, "height", "-."), (pS, "spread", (0, (1, 3)))):
            ax.axhline(100 * std(pvals) / mean(pvals), color="tab:grey", ls=ls, lw=0.8,
                       label="penalty %s: std over packings" % name)
    ax.set_xscale("log")
    ax.set_xlabel("run time (s, one rank%s)" % (", mean over %d packings" % npk
                                               if npk > 1 else ""))
    ax.set_ylabel("difference from the penalty mound (%)")
    ax.set_title("container release, %d grains: error against run time%s"
                 % (grains, " (bars: std over packings)" if npk > 1 else ""), fontsize=9)
    save_panels(fig, [ax], os.path.join(out, "impulse_error.png"))

    pdir0 = packings[0][0]
    pics = [(t, os.path.join(out, pdir0, "render_%s.png" % t)) for t in tags]
    pics = [(t, p) for t, p in pics if os.path.exists(p)]
    if pics:
        ncol = min(len(pics), 6)
        nrow = (len(pics) + ncol - 1) // ncol
        fig, axes = plt.subplots(nrow, ncol, figsize=(3.2 * ncol, 3.4 * nrow), squeeze=False)
        axes = [x for row in axes for x in row]
        for x in axes[len(pics):]:
            x.axis("off")
        for x, (t, p) in zip(axes, pics):
            x.imshow(plt.imread(p))
            x.set_title(t if npk == 1 else "%s (seed %s)" % (t, packings[0][1]), fontsize=9)
            x.axis("off")
        fig.tight_layout()
        fig.savefig(os.path.join(out, "impulse_mounds.png"), dpi=110)


if __name__ == "__main__":
    main()
