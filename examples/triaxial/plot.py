#!/usr/bin/env python3
"""Plot the triaxial example's CSV: q, mobilised friction angle and volumetric strain
against axial strain (three PNGs next to the CSV), and print the peak friction angle.

usage: plot.py triaxial.csv [label]"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def main():
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
