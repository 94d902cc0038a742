"""Table, CSV and plot of bench/node_stride.sh: per stride N, the wall time of the triaxial
deck (LAMMPS's 'Total wall time' of log.lammps: consolidation and shearing, the specimen's
preparation left out), its contact workload, the peak mobilised friction angle and the
volumetric strain at the end, and their differences from stride 1 (or the smallest stride).

Usage: node_stride_plot.py OUTDIR N1 DIR1 [N2 DIR2 ...]
Writes OUTDIR/node_stride.csv and OUTDIR/node_stride.png; prints the table and last
  stride=<N>:time_ratio=<t>,dphi_deg=<d>,depsv=<e> ... (relative to the smallest stride)."""
import csv
import os
import re
import sys

from figures import save_panels  # bench/figures.py, next to this script


def wall_seconds(log):
    m = re.findall(r"^Total wall time: (\d+):(\d+):(\d+)", open(log).read(), re.M)
    if not m:
        raise SystemExit("node_stride_plot.py: no 'Total wall time' in %s (did it finish?)" % log)
    h, mi, s = map(int, m[-1])
    return 3600 * h + 60 * mi + s


def curves(path):
    rows = list(csv.DictReader(open(path)))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main(argv):
    if len(argv) < 4 or len(argv) % 2:
        sys.exit(__doc__)
    outdir = argv[1]
    runs = sorted((int(n), d) for n, d in zip(argv[2::2], argv[3::2]))
    res = []
    for n, d in runs:
        c = curves(os.path.join(d, "triaxial.csv"))
        k = max(range(len(c["phi_deg"])), key=lambda i: c["phi_deg"][i])
        res.append({"stride": n, "seconds": wall_seconds(os.path.join(d, "log.lammps")),
                    "phi_peak_deg": c["phi_deg"][k], "eps_a_at_peak": c["eps_a"][k],
                    "eps_v_end": c["eps_v"][-1], "q_end": c["q"][-1], "curves": c})
    base = res[0]
    print("%6s %10s %10s %14s %14s %12s %10s" % ("stride", "seconds", "time/N1", "peak phi (deg)",
                                                 "eps_a at peak", "eps_v end", "q end"))
    for r in res:
        print("%6d %10d %10.3f %14.2f %13.1f%% %11.2f%% %10.3f" % (
            r["stride"], r["seconds"], r["seconds"] / base["seconds"], r["phi_peak_deg"],
            100 * r["eps_a_at_peak"], 100 * r["eps_v_end"], r["q_end"]))
    keys = ("stride", "seconds", "phi_peak_deg", "eps_a_at_peak", "eps_v_end", "q_end")
    with open(os.path.join(outdir, "node_stride.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(keys)
        for r in res:
            w.writerow([r[k] for k in keys])

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for r in res:
        c = r["curves"]
        ea = [100 * e for e in c["eps_a"]]
        label = "N = %d (%d s)" % (r["stride"], r["seconds"])
        ax[0].plot(ea, c["phi_deg"], label=label)
        ax[1].plot(ea, [100 * e for e in c["eps_v"]], label=label)
    ax[0].set(xlabel="axial strain (%)", ylabel="mobilised friction angle (deg)",
              title="every N-th node tested (report §3.4.1)")
    ax[1].set(xlabel="axial strain (%)", ylabel="volumetric strain (%, + = contraction)",
              title="volumetric strain")
    save_panels(fig, ax, os.path.join(outdir, "node_stride.png"))
    print(" ".join("stride=%d:time_ratio=%.3f,dphi_deg=%.2f,depsv=%.4f" % (
        r["stride"], r["seconds"] / base["seconds"], r["phi_peak_deg"] - base["phi_peak_deg"],
        r["eps_v_end"] - base["eps_v_end"]) for r in res))


if __name__ == "__main__":
    main(sys.argv)
