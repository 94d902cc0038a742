#!/usr/bin/env python3
"""The avalanche's figures, from in.avalanche's outputs and the shipped inputs:

  avalanche.png: (a) the front (the most advanced grain) and the centroid along the valley
  (x) against time, (b) the grains' mean speed and kinetic energy against time, (c) a side
  view: the valley floor's profile, the source and the deposit (grain centres), and the
  line from the crown to the front whose slope is H/L, (d) H/L on a Scheidegger-style
  chart: H/L against the deposit's volume, with Scheidegger's (1973) fit to field
  avalanches log10(H/L) = -0.15666 log10(V) + 0.62419 (V in m^3), and this run's point.
  deposit.png: the deposit's thickness, the grains' footprint binned on x-y at the end:
  per bin (the terrain's cell) the highest point of the grains' equivalent spheres (radius
  r from the grain's mass) over the bin minus the ground's height at the bin's centre
  (valley.asc), as a field survey takes it (the surface after the event minus before);
  the terrain's contours beneath.
  nets.png, with nets (in.avalanche -var nets N: nets.csv beside avalanche.csv, and the net
  files net1.net, ... there): per net against time (a) the retained fraction (grains
  upslope of it over all grains), (b) the anchor force |R| and its peak so far (over every
  step); the nets are drawn in (c) and on the deposit map.

    /usr/bin/python3 plot.py [avalanche.csv] [deposit.dump] [valley.asc] [source.data]
                             [avalanche.png] [deposit.png] [nets.png]

Prints the run's figures: the final front (the most advanced grain, and the front of the
bulk: the 2 % most advanced grains left out) and centroid, H/L (front, bulk front and
centroid), the deposit's volume, area, and largest and mean thickness; a warning if
grains came near the terrain's edges (avalanche.csv's near_edge); with nets, each net's
final retained fraction and peak anchor force."""
import math
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from terrain import read_asc

RHO = 2.65                 # grain density (make_scene.sh: pack --density)
MU_WALL = 0.2              # the terrain's friction (in.avalanche)


def arg(i, default):
    return sys.argv[i] if len(sys.argv) > i else default


csv_path, dump_path, asc_path, src_path, png, dep_png, nets_png = (
    arg(1, "avalanche.csv"), arg(2, "deposit.dump"), arg(3, "valley.asc"),
    arg(4, "source.data"), arg(5, "avalanche.png"), arg(6, "deposit.png"), arg(7, "nets.png"))


# ---- inputs -------------------------------------------------------------------------
def read_csv(path):
    """{column: array} of a fix print file with a 'time ...' title"""
    with open(path) as f:
        head = None
        rows = []
        for line in f:
            w = line.split()
            if not w or w[0].startswith("#"):
                continue
            if w[0] == "time":
                head = w
                continue
            rows.append([float(v) for v in w])
    return {name: np.array([r[i] for r in rows]) for i, name in enumerate(head)}


def read_net(path):
    """origin, e1, e2 and size of a net file (lsdem-shape net)"""
    net = {}
    for line in open(path):
        w = line.split("#")[0].split()
        if w and w[0] in ("origin", "e1", "e2", "size"):
            net[w[0]] = np.array([float(v) for v in w[1:]])
    return net


col = read_csv(csv_path)
t = col["time"]
nets_csv = os.path.join(os.path.dirname(csv_path), "nets.csv")
netcol = read_csv(nets_csv) if os.path.exists(nets_csv) else {}
nnets = sum(1 for c in netcol if c.startswith("retained_"))
nets = [read_net(os.path.join(os.path.dirname(csv_path), "net%d.net" % n))
        for n in range(1, nnets + 1)]


def read_dump(path):
    with open(path) as f:
        lines = f.read().split("\n")
    i = lines.index(next(l for l in lines if l.startswith("ITEM: ATOMS")))
    names = lines[i].split()[2:]
    data = np.array([[float(v) for v in l.split()] for l in lines[i + 1:] if l.strip()])
    return {n: data[:, k] for k, n in enumerate(names)}


def read_source(path):
    pos, atoms = [], False
    for line in open(path):
        w = line.split()
        if line.startswith("Atoms"):
            atoms = True
        elif atoms and len(w) == 11:
            pos.append([float(v) for v in w[4:7]])
        elif atoms and w and not w[0][0].isdigit():
            break
    return np.array(pos)


gx, gy, gz, cell = read_asc(asc_path)
dep = read_dump(dump_path)
src = read_source(src_path)
r_eq = (3.0 * dep["mass"] / (4.0 * math.pi * RHO)) ** (1.0 / 3.0)
volume = float(np.sum(dep["mass"]) / RHO)


# crown (the source's highest grain centre, its uphill end) and the final front, as in.avalanche
x_crown, z_crown = src[:, 0].max(), src[:, 2].max()
k = int(np.argmin(dep["x"]))
x_front, z_front = dep["x"][k], dep["z"][k]
hl = (z_crown - z_front) / (x_crown - x_front)
# the front of the bulk: the 2 % most advanced grains left out (the 9th grain of 400)
order = np.argsort(dep["x"])
k2 = int(order[int(0.02 * len(order))])
hl_bulk = (z_crown - dep["z"][k2]) / (x_crown - dep["x"][k2])
hl_cm = col["H_over_L_centroid"][-1]

# ---- avalanche.png -----------------------------------------------------------------
fig, ax = plt.subplots(2, 2, figsize=(12, 8.5))
a = ax[0, 0]
a.plot(t, col["front_x"], "r-", label="front (most advanced grain)")
a.plot(t, col["centroid_x"], "b-", label="centroid")
a.set_xlabel("time")
a.set_ylabel("x along the valley (flow towards -x)")
a.axhline(0.0, color="0.6", lw=0.8, ls=":")
a.text(t[-1], 0.3, "foot of the slope (x = 0)", ha="right", va="bottom", fontsize=8,
       color="0.4")
a.legend(loc="upper right")
a.set_title("(a) front and centroid")

a = ax[0, 1]
a.plot(t, col["mean_speed"], "k-", label="mean speed")
a.set_xlabel("time")
a.set_ylabel("mean speed of the grains")
b = a.twinx()
b.semilogy(t, np.maximum(col["ke"], 1e-6), "g--", label="kinetic energy (translation)")
b.set_ylabel("kinetic energy", color="g")
a.legend(loc="upper right")
b.legend(loc="center right")
a.set_title("(b) speed")

a = ax[1, 0]
mid = int(np.argmin(np.abs(gy)))
a.fill_between(gx, gz[mid], gz[mid].min() - 1.0, color="0.85", label="valley floor (y = 0)")
a.plot(gx, gz[mid], "k-", lw=1)
a.plot(src[:, 0], src[:, 2], "o", ms=2, color="tab:orange", label="source (t = 0)")
a.plot(dep["x"], dep["z"], "o", ms=2, color="tab:blue", label="deposit (end)")
a.plot([x_crown, x_front], [z_crown, z_front], "r--", lw=1,
       label="crown to front: H/L = %.3f" % hl)
for n, net in enumerate(nets):
    ends = [net["origin"], net["origin"] + net["size"][1] * net["e2"]]
    a.plot([e[0] for e in ends], [e[2] for e in ends], "-", color="tab:red", lw=2.5,
           label="nets (as built)" if n == 0 else None)
a.set_aspect("equal")
a.set_xlabel("x")
a.set_ylabel("z")
a.legend(loc="upper left", fontsize=8)
a.set_title("(c) side view: grain centres")

a = ax[1, 1]
v = np.logspace(1, 11, 100)
a.loglog(v, 10 ** (-0.15666 * np.log10(v) + 0.62419), "k-",
         label="Scheidegger (1973): field avalanches")
a.axhline(MU_WALL, color="0.5", ls=":", label="basal friction mu = %.1f (a sliding block)"
          % MU_WALL)
a.loglog([volume], [hl], "r*", ms=14, label="this run, front: H/L = %.3f" % hl)
a.loglog([volume], [hl_bulk], "m^", ms=8, label="this run, front of the bulk "
         "(2 %% of the grains beyond): %.3f" % hl_bulk)
a.loglog([volume], [hl_cm], "bs", ms=7, label="this run, centroid: %.3f" % hl_cm)
a.set_xlabel("deposit volume V (solids; m^3 if the lengths are metres)")
a.set_ylabel("H/L (fall height over travel)")
a.set_ylim(0.05, 3)
a.legend(loc="lower left", fontsize=8)
a.text(1.5e5, 1.5, "Scheidegger's data: V > 1e5 m^3;\nsmaller volumes extrapolate", fontsize=8)
a.set_title("(d) mobility: H/L against volume")
fig.suptitle("Rock avalanche down a 25 deg valley: %d grains, run to t = %.2f"
             % (len(dep["x"]), t[-1]))
fig.tight_layout()
fig.savefig(png, dpi=100)

# ---- deposit.png: thickness map ----------------------------------------------------------
xs, ys = np.meshgrid(gx, gy)
top = np.full(xs.shape, -np.inf)
for x, y, z, r in zip(dep["x"], dep["y"], dep["z"], r_eq):
    i0, i1 = np.searchsorted(gx, [x - r - cell / 2, x + r + cell / 2])
    j0, j1 = np.searchsorted(gy, [y - r - cell / 2, y + r + cell / 2])
    sub = (slice(j0, j1), slice(i0, i1))
    # the grain's equivalent sphere over the bin: its top above the bin's nearest point
    dx = np.maximum(np.abs(xs[sub] - x) - cell / 2, 0.0)
    dy = np.maximum(np.abs(ys[sub] - y) - cell / 2, 0.0)
    d2 = dx * dx + dy * dy
    h = np.where(d2 < r * r, z + np.sqrt(np.maximum(r * r - d2, 0.0)), -np.inf)
    top[sub] = np.maximum(top[sub], h)
thick = np.where(np.isfinite(top), top - gz, np.nan)
thick = np.where(thick > 0, thick, np.nan)
covered = np.isfinite(thick)
area = covered.sum() * cell * cell
fig, a = plt.subplots(figsize=(12, 4.8))
cs = a.contour(gx, gy, gz, levels=np.arange(gz.min() + 0.5, gz.max(), 1.0),
               colors="0.6", linewidths=0.6)
a.clabel(cs, fontsize=7, fmt="%g")
m = a.pcolormesh(gx, gy, np.ma.masked_invalid(thick), shading="nearest", cmap="viridis")
fig.colorbar(m, ax=a, shrink=0.75, label="deposit thickness (top of the grains - ground)")
a.plot(src[:, 0], src[:, 1], ".", ms=1.5, color="tab:orange", label="source (grain centres)")
a.plot([x_front], [dep["y"][k]], "r*", ms=10, label="front (most advanced grain)")
a.plot([dep["x"][k2]], [dep["y"][k2]], "m^", ms=8, label="front of the bulk (2 % beyond)")
for n, net in enumerate(nets):
    ends = [net["origin"], net["origin"] + net["size"][0] * net["e1"]]
    a.plot([e[0] for e in ends], [e[1] for e in ends], "-", color="tab:red", lw=2,
           label="nets (as built)" if n == 0 else None)
a.set_aspect("equal")
a.set_xlabel("x (flow towards -x)")
a.set_ylabel("y")
a.set_title("Deposit thickness at t = %.2f (bins %.2g x %.2g; terrain contours every 1 from 0.5 above its lowest point)"
            % (t[-1], cell, cell))
a.legend(loc="upper right", fontsize=8)
fig.tight_layout()
fig.savefig(dep_png, dpi=100)

if "near_edge" in col and col["near_edge"].max() > 0:
    print("plot.py: WARNING: up to %d grains came within 1 of the terrain's edges (at t = %.2f), "
          "where the band is not the ground's flat continuation" % (col["near_edge"].max(),
                                                                   t[np.argmax(col["near_edge"])]))
print("%s, %s: t = %.2f: front x = %.2f (of the bulk, 2 %% beyond: %.2f), centroid x = %.2f, "
      "mean speed %.3f; H/L = %.3f (front), %.3f (bulk front), %.3f (centroid); deposit "
      "volume %.1f (solids), area %.1f, thickness max %.2f, mean %.2f"
      % (png, dep_png, t[-1], x_front, dep["x"][k2], col["centroid_x"][-1],
         col["mean_speed"][-1], hl, hl_bulk, hl_cm, volume, area, np.nanmax(thick),
         np.nanmean(thick)))

# ---- nets.png ----------------------------------------------------------------------------
if nnets:
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    tn = netcol["time"]
    for n in range(1, nnets + 1):
        c = "C%d" % (n - 1)
        ax[0].plot(tn, netcol["retained_%d" % n], "-", color=c,
                   label="net %d (x = %g): retained" % (n, nets[n - 1]["origin"][0]))
        ax[1].plot(tn, netcol["anchor_%d" % n], "-", color=c, lw=0.8,
                   label="net %d: anchor force |R|" % n)
        ax[1].plot(tn, netcol["peak_anchor_%d" % n], "--", color=c,
                   label="net %d: peak so far (every step)" % n)
        print("%s: net %d at x = %g: retained fraction %.4f, grains through %d, peak anchor force "
              "%.1f, at the end %.1f" % (nets_png, n, nets[n - 1]["origin"][0],
                                         netcol["retained_%d" % n][-1],
                                         netcol["through_%d" % n][-1],
                                         netcol["peak_anchor_%d" % n][-1],
                                         netcol["anchor_%d" % n][-1]))
    ax[0].set_xlabel("time")
    ax[0].set_ylabel("fraction of the grains upslope of the net")
    ax[0].set_ylim(0, 1.05)
    ax[0].legend(loc="lower left", fontsize=8)
    ax[0].set_title("(a) retained fraction")
    ax[1].set_xlabel("time")
    ax[1].set_ylabel("anchor force (sum over the clamped balls)")
    ax[1].legend(loc="upper left", fontsize=8)
    ax[1].set_title("(b) anchor force")
    fig.suptitle("Nets across the channel: %d net(s)" % nnets)
    fig.tight_layout()
    fig.savefig(nets_png, dpi=100)
