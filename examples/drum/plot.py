#!/usr/bin/env python3
"""drum.csv (in.drum's time, bed surface angle, kinetic energy) -> drum.png: the bed's
surface angle against time. The drum carries the bed up to the angle at which it
avalanches (the peak: the upper angle of repose), after which it slumps back; longer spins
(-var spin 12) show the slumps repeat."""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

src = sys.argv[1] if len(sys.argv) > 1 else "drum.csv"
out = sys.argv[2] if len(sys.argv) > 2 else "drum.png"
rows = [l.split() for l in open(src) if l.strip() and not l.startswith("#")]
rows = [r for r in rows if r[0] != "time"]
t = [float(r[0]) for r in rows]
angle = [abs(float(r[1])) for r in rows]
ke = [float(r[2]) for r in rows]
# after the settling (1 time unit) and the fall's transient
turning = [(tt, a) for tt, a in zip(t, angle) if tt >= 1.5]
t_peak, peak = max(turning, key=lambda p: p[1]) if turning else (float("nan"), float("nan"))
fig, ax = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
ax[0].plot(t, angle, "b-")
ax[0].axhline(peak, color="r", ls="--", label="peak (avalanche onset) %.1f deg at t = %.1f"
              % (peak, t_peak))
ax[0].set_ylabel("bed surface angle (deg)")
ax[0].set_ylim(0, 60)
ax[0].legend()
ax[1].semilogy(t, ke, "k-")
ax[1].set_ylabel("kinetic energy")
ax[1].set_xlabel("time")
fig.suptitle("Rotating drum: dynamic angle of repose")
fig.tight_layout()
fig.savefig(out, dpi=120)
print("%s: the bed avalanches at %.1f deg (t = %.1f); at the end %.1f deg" % (out, peak, t_peak,
                                                                       angle[-1]))
