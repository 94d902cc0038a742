#!/usr/bin/env python3
"""shear.csv and the last fields file of in.shear_cell -> shear.png: the stress ratio
tau / p, the pressure and the inertial number against the shear strain, and the shear strain
field (von Mises shear of the Green strain, fix field/lsdem's shear_strain) on the grid's
middle layer in z, drawn where its nodes are: the grid is skewed with the tilted box.
    plot.py [shear.csv] [fields/shear.pvd] [shear.png]"""
import re
import sys

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def last_vti(pvd):
    """the newest file a .pvd series lists (its path relative to the .pvd's folder)"""
    names = re.findall(r'file="([^"]+)"', open(pvd).read())
    folder = pvd.rsplit("/", 1)[0] + "/" if "/" in pvd else ""
    return folder + names[-1]


def middle_layer(path, name="shear_strain"):
    """(x, y, values) of node layer n_z / 2 of a fix field/lsdem .vti: world positions of a
    possibly skewed grid, origin + Direction (spacing * index)"""
    raw = open(path, "rb").read()
    start = raw.index(b'<AppendedData encoding="raw">')
    base = raw.index(b"_", start) + 1
    head = raw[:base].decode()
    num = lambda key: np.array(re.search(key + r'="([^"]+)"', head).group(1).split(), float)
    n = (num("WholeExtent")[1::2] + 1).astype(int)
    d = re.search(r'Direction="([^"]+)"', head)
    direction = np.array(d.group(1).split(), float).reshape(3, 3) if d else np.eye(3)
    m = re.search(r'Name="%s" NumberOfComponents="1" format="appended" offset="(\d+)"' % name,
                  head)
    at = base + int(m.group(1))
    count = int(np.frombuffer(raw, "<u8", 1, at)[0]) // 8
    values = np.frombuffer(raw, "<f8", count, at + 8).reshape(n[2], n[1], n[0])
    k = n[2] // 2
    i, j = np.meshgrid(np.arange(n[0]), np.arange(n[1]))
    index = np.stack([i, j, np.full_like(i, k)], axis=-1) * num("Spacing")
    world = num("Origin") + index @ direction.T
    return world[..., 0], world[..., 1], values[k]


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
