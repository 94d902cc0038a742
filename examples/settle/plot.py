#!/usr/bin/env python3
"""Plot the settle example's CSV: kinetic energies and floor load against time."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def main():
    src, dst = sys.argv[1], sys.argv[2]
    rows = list(csv.DictReader(open(src)))
    t = [float(r["time"]) for r in rows]
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    # energies are zero before the first contact: plot from the first positive value on
    for key, label in (("ke", "translational KE"), ("erot", "rotational KE")):
        pts = [(ti, float(r[key])) for ti, r in zip(t, rows) if float(r[key]) > 0]
        a1.semilogy([p[0] for p in pts], [p[1] for p in pts], label=label)
    a1.set_ylabel("energy (J)")
    a1.legend()
    a1.set_title("%s angular level-set grains settling under gravity" % sys.argv[3] if len(sys.argv) > 3 else "angular level-set grains settling under gravity")
    a2.plot(t, [float(r["floor_load_over_weight"]) for r in rows])
    a2.axhline(1.0, color="k", lw=0.8, ls="--")
    a2.set_ylabel("floor force / total weight")
    a2.set_xlabel("time (s)")
    fig.tight_layout()
    fig.savefig(dst, dpi=110)
    # the settled bed still rings (the floor load swings by some 10 % from row to row):
    # its mean over the last fifth of the run is the figure to compare with 1
    last = rows[-1]
    tail = [float(r["floor_load_over_weight"]) for ti, r in zip(t, rows) if ti >= 0.8 * t[-1]]
    print("final: KE %.3g J, floor force / weight %.4f (over the last fifth of the run: mean %.3f,"
          " %.3f to %.3f)" % (float(last["ke"]), float(last["floor_load_over_weight"]),
                              sum(tail) / len(tail), min(tail), max(tail)))


if __name__ == "__main__":
    main()
