#!/usr/bin/python3
"""segment_summary.py SAND.txt OUT.png -- the mean of bench/segment.sh's sand rows per D50
and artifacts (printed as a Markdown table), the labels lsdem-segment's check named as two
grains joined against those that are (summed over the seeds), and one-to-one recovery and
mean |volume error| against D50 as a PNG (matplotlib)."""
import sys
from collections import defaultdict

import numpy as np

FIGS = ("fraction", "small", "vol_err_mean_abs", "vol_err_mean", "centroid_err",
        "axis_err_deg", "merged", "split", "true")
NAMED = ("merged_labels", "named", "named_merged", "good_labels", "named_good")


def main(rows_file, png):
    groups = defaultdict(list)
    for line in open(rows_file):
        kv = dict(w.split("=", 1) for w in line.split())
        groups[(float(kv["d50"]), kv["artifacts"])].append({k: float(kv[k]) for k in FIGS + NAMED})
    print("| D50 | artifacts | seeds | grains | one-to-one | smallest third | mean abs volume "
          "error | mean volume error | centroid error | major-axis error | merged | split |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    mean = {}
    for (d50, art), rows in sorted(groups.items()):
        m = {k: np.mean([r[k] for r in rows]) for k in FIGS}
        lo = min(r["fraction"] for r in rows)
        mean[(d50, art)] = m
        print("| %g | %s | %d | %.0f | %.1f %% (lowest %.1f) | %.1f %% | %.1f %% | %+.1f %% | "
              "%.2f vox | %.1f deg | %.1f | %.1f |"
              % (d50, art, len(rows), m["true"], 100 * m["fraction"], 100 * lo,
                 100 * m["small"], 100 * m["vol_err_mean_abs"], 100 * m["vol_err_mean"],
                 m["centroid_err"], m["axis_err_deg"], m["merged"], m["split"]))
    print("\n| D50 | artifacts | labels holding two grains | named by the check (recall) | "
          "named that hold two (precision) | good labels named |")
    print("|---|---|---|---|---|---|")
    for (d50, art), rows in sorted(groups.items()):
        s = {k: sum(r[k] for r in rows) for k in NAMED}
        print("| %g | %s | %d | %d (%.0f %%) | %d of %d (%.0f %%) | %d of %d (%.1f %%) |"
              % (d50, art, s["merged_labels"], s["named_merged"],
                 100 * s["named_merged"] / max(s["merged_labels"], 1), s["named_merged"],
                 s["named"], 100 * s["named_merged"] / max(s["named"], 1), s["named_good"],
                 s["good_labels"], 100 * s["named_good"] / max(s["good_labels"], 1)))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for art, style in (("clean", "o-"), ("all", "s-"), ("zero", "^--")):
        d = sorted(k[0] for k in mean if k[1] == art)
        if not d:
            continue
        ax[0].plot(d, [100 * mean[(x, art)]["fraction"] for x in d], style, label=art)
        ax[1].plot(d, [100 * mean[(x, art)]["vol_err_mean_abs"] for x in d], style, label=art)
    ax[0].set_ylabel("recovered one-to-one (IoU >= 0.5), %")
    ax[1].set_ylabel("mean |volume error| of the recovered grains, %")
    for a in ax:
        a.set_xlabel("D50, voxels")
        a.grid(alpha=0.3)
        a.legend(title="artifacts")
    fig.suptitle("lsdem-segment on synthetic sand scans (bench/segment.sh)")
    fig.tight_layout()
    fig.savefig(png, dpi=90)


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
