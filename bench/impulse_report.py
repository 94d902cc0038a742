#!/usr/bin/env python3
"""The figures of bench/impulse.sh: the container release (report §4.6.1) by the penalty
method at dt and the impulse method at multiples of dt, from the runs' logs and final dumps.

  impulse_report.py OUTDIR GRAINS TAG...   (TAG: penalty, impulse_x<m>, impulse_x<m>_np2)

Prints a table (loop s = the run's loop time, wall clock, and LAMMPS's CPU use of it: below
100 % the machine was shared and the loop time is inflated; speed-up over the penalty run;
mound height and spread, examples/container_release/mound.py, and their difference from the
penalty run; islands, ETM iterations and passes per step sampled at the thermo rows;
label-exchange rounds and the deepest grain-grain penetration seen) and writes impulse.csv, impulse_error.png (error
in height and spread against run time) and, from lsdem-shape renders when present,
impulse_mounds.png."""
import csv
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "examples", "container_release"))
from mound import mound  # noqa: E402


def log_figures(path):
    """Loop time, steps, ranks, CPU use (%) and the thermo rows of a LAMMPS log."""
    text = open(path).read()
    m = re.search(r"Loop time of ([\d.e+-]+) on (\d+) procs for (\d+) steps", text)
    if not m:
        raise SystemExit("%s: no 'Loop time' line (the run did not finish)" % path)
    use = re.search(r"([\d.]+)% CPU use", text)
    rows, header = [], None
    for ln in text.splitlines():
        parts = ln.split()
        if parts[:1] == ["Step"]:
            header = parts
            continue
        if header and len(parts) == len(header):
            try:
                rows.append(dict(zip(header, map(float, parts))))
            except ValueError:
                header = None
        elif header and not ln.startswith("WARNING"):
            header = None
    return (float(m.group(1)), int(m.group(2)), int(m.group(3)),
            float(use.group(1)) if use else float("nan"), rows)


def mean(vals):
    return sum(vals) / len(vals) if vals else float("nan")


def main():
    out, grains, tags = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
    runs = []
    for tag in tags:
        seconds, procs, steps, use, rows = log_figures(os.path.join(out, "log.%s" % tag))
        h, s, n = mound(os.path.join(out, "mound_%s.dump" % tag))
        r = dict(tag=tag, seconds=seconds, use=use, procs=procs, steps=steps, height=h, spread=s,
                 grains=n, us=1e6 * seconds * procs / (grains * steps))
        imp = [x for x in rows if "f_integrate[1]" in x and x["Step"] > 0]
        if imp:
            r.update(islands=mean([x["f_integrate[1]"] for x in imp]),
                     largest=max(x["f_integrate[2]"] for x in imp),
                     iterations=mean([x["f_integrate[4]"] for x in imp]),
                     passes=mean([x["f_integrate[5]"] for x in imp]),
                     rounds=max(x["f_integrate[8]"] for x in imp),
                     depth=max(x["f_integrate[20]"] for x in imp),
                     split=[imp[-1]["f_integrate[%d]" % k] for k in range(15, 20)])
        runs.append(r)
    ref = next((r for r in runs if r["tag"] == "penalty"), None)
    if ref is None:
        raise SystemExit("no penalty run among %s" % tags)

    cols = ("run", "ranks", "steps", "loop s", "CPU use %", "us/grain-step", "speed-up",
            "height", "spread",
            "dH %", "dS %", "islands", "largest", "ETM it/step", "passes", "rounds", "depth")
    print(" | ".join(cols))
    table = []
    for r in runs:
        row = [r["tag"], r["procs"], r["steps"], "%.4g" % r["seconds"], "%.0f" % r["use"],
               "%.2f" % r["us"],
               "%.2f" % (ref["seconds"] / r["seconds"]), "%.3f" % r["height"],
               "%.3f" % r["spread"], "%+.1f" % (100 * (r["height"] / ref["height"] - 1)),
               "%+.1f" % (100 * (r["spread"] / ref["spread"] - 1))]
        if "islands" in r:
            row += ["%.0f" % r["islands"], "%d" % r["largest"], "%.0f" % r["iterations"],
                    "%.1f" % r["passes"], "%d" % r["rounds"], "%.3g" % r["depth"]]
        else:
            row += ["-"] * 6
        table.append(row)
        print(" | ".join(str(c) for c in row))
    for r in runs:
        if "split" in r:
            print("%s time split (s): detection %.3g, islands %.3g, ETM %.3g, walls %.3g, "
                  "communication %.3g" % ((r["tag"],) + tuple(r["split"])))
    with open(os.path.join(out, "impulse.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        w.writerows(table)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sys.path.insert(0, HERE)
    from figures import save_panels
    fig, ax = plt.subplots(1, 1, figsize=(6, 4))
    one = [r for r in runs if r["procs"] == 1 and r["tag"] != "penalty"]
    for key, name, mark in (("height", "height", "o"), ("spread", "spread", "s")):
        ax.plot([r["seconds"] for r in one],
                [100 * abs(r[key] / ref[key] - 1) for r in one], mark + "-",
                label="impulse: |error| in mound %s" % name)
        for r in one:
            ax.annotate(r["tag"].replace("impulse_", ""), (r["seconds"], 100 * abs(
                r[key] / ref[key] - 1)), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.axvline(ref["seconds"], color="k", ls="--", label="penalty run (the reference)")
    ax.set_xscale("log")
    ax.set_xlabel("run time (s, one rank)")
    ax.set_ylabel("difference from the penalty mound (%)")
    ax.set_title("container release, %d grains: error against run time" % grains, fontsize=9)
    save_panels(fig, [ax], os.path.join(out, "impulse_error.png"))

    pics = [(r["tag"], os.path.join(out, "render_%s.png" % r["tag"])) for r in runs]
    pics = [(t, p) for t, p in pics if os.path.exists(p)]
    if pics:
        fig, axes = plt.subplots(1, len(pics), figsize=(3.2 * len(pics), 3.4))
        axes = axes if len(pics) > 1 else [axes]
        for a, (t, p) in zip(axes, pics):
            a.imshow(plt.imread(p))
            a.set_title(t, fontsize=9)
            a.axis("off")
        fig.tight_layout()
        fig.savefig(os.path.join(out, "impulse_mounds.png"), dpi=110)


if __name__ == "__main__":
    main()
