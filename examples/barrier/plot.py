#!/usr/bin/env python3
"""The barrier test against time: the cube's velocity along the impact, the net's
deflection and the anchors' vertical reaction, penalty and impulse runs.
    python3 plot.py barrier_penalty.csv barrier_impulse.csv barrier.png"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import barrier  # noqa: E402

*csvs, png = sys.argv[1:] if len(sys.argv) > 2 else ("barrier.csv", "barrier.png")
fig, ax = plt.subplots(3, 1, figsize=(7, 8), sharex=True)
for path in csvs:
    rows = [r for r in barrier.read(path) if r["phase"] == 0]
    t = [r["time"] for r in rows]
    label = os.path.basename(path).replace("barrier_", "").replace(".csv", "")
    ax[0].plot(t, [r["vz"] for r in rows], label=label)
    ax[1].plot(t, [rows[0]["height"] - r["height"] for r in rows], label=label)
    ax[2].plot(t, [r["rz"] for r in rows], label=label)
ax[0].set_ylabel("cube's vz")
ax[1].set_ylabel("net deflection")
ax[2].set_ylabel("anchors' reaction z")
ax[2].set_xlabel("time from release")
for a in ax:
    a.grid(alpha=0.3)
ax[0].legend()
fig.tight_layout()
fig.savefig(png, dpi=100)
