#!/usr/bin/env python3
"""net_drop.csv (in.net_drop's time, kinetic energies, net outputs) -> net_drop.png: the
net's kinetic energy against time (Figure 4.6's run: the waves have mostly subsided by
step 12,000, t = 2.4) and the residual height, with the step at which the net's kinetic
energy stays below 1 % of its peak."""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

src = sys.argv[1] if len(sys.argv) > 1 else "net_drop.csv"
out = sys.argv[2] if len(sys.argv) > 2 else "net_drop.png"
rows = [l.split() for l in open(src) if l.strip() and not l.startswith("#")]
rows = [list(map(float, r)) for r in rows if r[0] != "time"]
t = [r[0] for r in rows]
ke = [r[1] for r in rows]
height = [r[5] for r in rows]
peak = max(ke)
k_peak = ke.index(peak)
below = next((t[k] for k in range(k_peak, len(t)) if all(e < 0.01 * peak for e in ke[k:])),
             float("nan"))
fig, ax = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
ax[0].semilogy(t, ke, "k-", label="net (free balls)")
ax[0].semilogy(t, [r[2] for r in rows], "b-", lw=0.8, label="grains")
ax[0].axhline(0.01 * peak, color="r", ls="--", label="1 % of the net's peak")
ax[0].axvline(2.4, color="g", ls=":", label="step 12,000")
ax[0].set_ylabel("kinetic energy")
ax[0].legend(fontsize=8)
ax[1].plot(t, height, "k-")
ax[1].set_ylabel("residual height (lowest ball)")
ax[1].set_xlabel("time (at dt = 2e-4: 5,000 steps per unit)")
fig.suptitle("Grains falling into a flexible net (report Figure 4.6)")
fig.tight_layout()
fig.savefig(out, dpi=120)
print("%s: net KE peak %.3e at t = %.2f, below 1 %% of it from t = %.2f (step %.0f at dt = "
      "2e-4); residual height %.4f" % (out, peak, t[k_peak], below, below / 2e-4, height[-1]))
