#!/usr/bin/env python3
"""Plot lsdem-bench-accuracy's CSV: force error against grid resolution (one line per node
count) and against the time of one contact test, one panel per overlap."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def main():
    src, dst = sys.argv[1], sys.argv[2]
    rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(src))]
    overlaps = sorted({r["overlap_over_R"] for r in rows})
    counts = sorted({r["nodes"] for r in rows})
    fig, axes = plt.subplots(2, len(overlaps), figsize=(4.2 * len(overlaps), 7.5), squeeze=False)
    for col, d in enumerate(overlaps):
        top, bottom = axes[0][col], axes[1][col]
        for n in counts:
            pts = sorted((r["R_over_h"], r["err_mean"], r["ns_per_test"]) for r in rows
                         if r["overlap_over_R"] == d and r["nodes"] == n)
            label = "%d nodes" % n
            top.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=label)
            bottom.loglog([p[2] for p in pts], [p[1] for p in pts], "o-", label=label)
            for rh, err, ns in pts:
                bottom.annotate("%g" % rh, (ns, err), fontsize=6, alpha=0.7)
        top.set_title("overlap %g R" % d)
        top.set_xlabel("grid resolution R/h")
        bottom.set_xlabel("time per contact test, no node list (ns)")
        for ax in (top, bottom):
            ax.axhline(0.01, color="k", lw=0.6, ls="--")
            ax.grid(True, which="both", lw=0.3)
        if col == 0:
            top.set_ylabel("mean relative force error")
            bottom.set_ylabel("mean relative force error\n(labels: R/h)")
            top.legend(fontsize=7)
    fig.suptitle("Two level-set spheres, traction law, against the exact-sphere limit")
    fig.tight_layout()
    fig.savefig(dst, dpi=110)


if __name__ == "__main__":
    main()
