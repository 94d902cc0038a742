#!/usr/bin/env python3
"""shear.csv and the last fields file of in.shear_cell -> shear.png: the stress ratio
tau / p, the pressure and the inertial number against the shear strain, and the shear strain
field (von Mises shear of the Green strain, fix field/lsdem's shear_strain) on the grid's
middle layer in z, drawn where its nodes are: the grid is skewed with the tilted box.
    plot.py [shear.csv] [fields/shear.pvd] [shear.png]"""
import os
import re
import sys

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from lsdem_vti import node_grid, node_positions, read_vti  # noqa: E402


def last_vti(pvd):
    """the newest file a .pvd series lists (its path relative to the .pvd's folder)"""
    names = re.findall(r'file="([^"]+)"', open(pvd).read())
    folder = pvd.rsplit("/", 1)[0] + "/" if "/" in pvd else ""
    return folder + names[-1]


def middle_layer(path, name="shear_strain"):
    """(x, y, values) of node layer n_z / 2 of a fix field/lsdem .vti, at the world positions
    of its (possibly skewed) nodes"""
    vti = read_vti(path)
    k = vti["n"][2] // 2
    world = node_positions(vti, k)
    return world[..., 0], world[..., 1], node_grid(vti, name)[k, :, :, 0]


src = sys.argv[1] if len(sys.argv) > 1 else "shear.csv"
pvd = sys.argv[2] if len(sys.argv) > 2 else "fields/shear.pvd"
out = sys.argv[3] if len(sys.argv) > 3 else "shear.png"
rows = np.array([[float(w) for w in l.split()] for l in open(src)
                 if l.strip() and not l.startswith("#") and not l.startswith("gamma")])
gamma, p, tau, ratio, inertial = rows[:, 0], rows[:, 1], rows[:, 2], rows[:, 3], rows[:, 6]
steady = gamma >= 0.5 * gamma[-1]
mean_ratio = ratio[steady].mean()
fig = plt.figure(figsize=(11, 5))
ax = fig.add_subplot(1, 2, 1)
ax.plot(gamma, ratio, "b-", label="tau / p")
ax.axhline(mean_ratio, color="b", ls="--", lw=0.8,
           label="mean over the second half %.3f" % mean_ratio)
ax.set_xlabel("shear strain gamma")
ax.set_ylabel("tau / p")
ax.set_ylim(0, 1.5)
ax2 = ax.twinx()
ax2.semilogy(gamma, p, "k-", lw=0.8, label="p")
ax2.semilogy(gamma, inertial, "g-", lw=0.8, label="inertial number")
ax2.set_ylabel("p, inertial number")
ax.legend(loc="upper left", fontsize=8)
ax2.legend(loc="upper right", fontsize=8)
ax.set_title("simple shear at constant volume")
vti = last_vti(pvd)
x, y, v = middle_layer(vti)
ax = fig.add_subplot(1, 2, 2)
# colours up to the 98th percentile: a few nodes by a rattler or a void carry much more
top = np.nanpercentile(v, 98)
mesh = ax.pcolormesh(x, y, np.ma.masked_invalid(v), shading="auto", cmap="viridis", vmax=top)
fig.colorbar(mesh, ax=ax, label="shear strain (Green, von Mises; %.2f and above: top)" % top)
ax.set_aspect("equal")
ax.set_xlabel("x")
ax.set_ylabel("y")
ax.set_title("%s, middle layer in z" % vti.rsplit("/", 1)[-1])
fig.tight_layout()
fig.savefig(out, dpi=110)
print("%s: tau / p %.3f over the second half of the shear (gamma %.2f); the field of %s"
      % (out, mean_ratio, gamma[-1], vti))
