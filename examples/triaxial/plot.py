#!/usr/bin/env python3
"""Plot the triaxial example's CSV: q, mobilised friction angle and volumetric strain
against axial strain (three PNGs next to the CSV), and print the peak friction angle.
With --cycles, a cyclic run's cycles.csv (in.triaxial -var cycles N): report Figure 3.25
(cycles.png: the axial deviator and the volumetric strain against axial strain, each cycle in
its colour, the holds marked) and each loop's secant modulus, loop energy, damping ratio and
residual volumetric strain (cycles.py) printed and written to loops.csv next to it.

usage: plot.py triaxial.csv [label]
       plot.py --cycles cycles.csv[+cycles.2.csv ...]"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import cycles


def plot_cycles(spec, outdir=None):
    """Figure 3.25 and loops.csv from a cyclic run's cycles.csv (parts joined with +), into
    outdir (default: the CSV's folder)."""
    rows = cycles.read(spec)
    measured = cycles.loops(rows)
    outdir = outdir or os.path.dirname(os.path.abspath(spec.split("+")[0]))
    cycles.write(os.path.join(outdir, "loops.csv"), measured)
    fig, (aq, av) = plt.subplots(2, 1, figsize=(6, 7), sharex=True)
    for k in sorted({r["cycle"] for r in rows}):
        part = [r for r in rows if r["cycle"] == k]
        ea = [100 * r["eps_a"] for r in part]
        aq.plot(ea, [r["qz"] for r in part], lw=1, label="cycle %d" % k)
        av.plot(ea, [100 * r["eps_v"] for r in part], lw=1)
        held = [r for r in part if r["phase"] == "hold"]
        aq.plot([100 * r["eps_a"] for r in held], [r["qz"] for r in held], "k.", ms=2)
    aq.set_ylabel("axial deviator qz (x sigma_c)")
    av.set_ylabel("volumetric strain (%, + = contraction)")
    av.set_xlabel("axial strain (%)")
    aq.legend(fontsize=8)
    for a in (aq, av):
        a.grid(alpha=0.3)
    aq.set_title("loading-unloading cycles (report Figure 3.25); dots: holds")
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "cycles.png"), dpi=110)
    plt.close(fig)
    print("cycle  eps_a top %  q top  secant modulus  loop energy  damping  residual eps_v %")
    for lp in measured:
        if lp["closed"]:
            print("%5d  %11.3f  %5.3g  %14.4g  %11.4g  %7.4f  %16.4f"
                  % (lp["cycle"], 100 * lp["eps_top"], lp["q_top"], lp["secant_modulus"],
                     lp["loop_energy"], lp["damping_ratio"], 100 * lp["residual_eps_v"]))
        else:
            print("%5d  reload ended before the unloading's strain: loop open" % lp["cycle"])


def main():
    if sys.argv[1] == "--cycles":
        plot_cycles(sys.argv[2])
        return
    src = sys.argv[1]
    label = sys.argv[2] if len(sys.argv) > 2 else ""
    rows = list(csv.DictReader(open(src)))
    col = {k: [float(r[k]) for r in rows] for k in rows[0]}
    ea = [100 * e for e in col["eps_a"]]
    outdir = os.path.dirname(os.path.abspath(src))
    for key, ylabel, name, scale in (("q", "deviatoric stress q (x sigma_c)", "q_eps.png", 1),
                                     ("phi_deg", "mobilised friction angle (deg)",
                                      "phi_eps.png", 1),
                                     ("eps_v", "volumetric strain (%, + = contraction)",
                                      "epsv_eps.png", 100)):
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot(ea, [scale * v for v in col[key]], label=label or None)
        ax.set_xlabel("axial strain (%)")
        ax.set_ylabel(ylabel)
        if label:
            ax.legend()
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, name), dpi=110)
        plt.close(fig)
    k = max(range(len(rows)), key=lambda i: col["phi_deg"][i])
    print("peak mobilised friction angle %.1f deg at eps_a %.1f%% (q %.3g, p %.3g); "
          "max inertial number %.2g" % (col["phi_deg"][k], ea[k], col["q"][k], col["p"][k],
                                         max(col["inertial"])))


if __name__ == "__main__":
    main()
