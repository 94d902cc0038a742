#!/usr/bin/python3
"""The triaxial example's figure pack (report Figures 3.12-3.25) from a finished run's folder.

usage: figures.py RUN_DIR [--out DIR]          (DIR default RUN_DIR/figures)

Reads what in.triaxial writes in RUN_DIR: triaxial.csv, snapshots.csv, dump.band,
fields_<step>.vti, chains_<step>.vtp (the snapshots at 5, 10, 15 % axial strain) and, from a
cyclic run, cycles.csv. Writes into DIR (examples/triaxial/README.md maps them to the report):
  response.png          q, phi_mob, eps_v and Z against eps_a (Figures 3.12-3.14)
  band.png              the fitted band's dip and thickness against eps_a, with the Coulomb,
                        Roscoe and Arthur inclinations of the run's peak phi and largest psi
  strain_slices.png     von Mises shear strain (Green, since shearing began) on the vertical
                        slice through the band, one panel per snapshot (Figure 3.15)
  rotation_slices.png   the continuum rotation's angle on the same slice (Figure 3.15)
  band_grains.png       the grains seen along the slice's normal, those rotated more than
                        mean + 2 sd since shearing began marked (Figure 3.16)
  chains.png            the contact network in a slab of 2 D50 about the slice, line width by
                        normal force, strong lines (above the mean) dark (Figures 3.18, 3.20)
  fabric_surfaces.png   the long axes' second-order density 1 + D:nn inside and outside the
                        band at the last snapshot (Figures 3.21-3.22)
  rose_inside.png, rose_outside.png   the long axes' spherical histograms (Figures 3.23-3.24)
  rose_normals_inside.png, rose_normals_outside.png   the same of the grain contacts' normals
                        (inside: both grains in the band, as fix network/lsdem's keyword band)
  cycles.png, loops.csv the loading-unloading cycles (Figure 3.25; plot.py --cycles)
and the numbers: slice_<step>.csv (the slice's samples: s, z, x, y, shear strain, rotation
angle), chains.csv (strong-chain statistics per snapshot), fabric.csv (long-axis and
contact-normal fabric inside and outside the band per snapshot), bands.csv (the bands of
each snapshot's strain field: tools/lsdem_bands.py's count of shear and micro bands, their
dip, azimuth and size; only its header when there is none), summary.txt (band, theories,
strain-field bands, chains).

The slice: the vertical plane through the band of the last snapshot that has one, containing
its dip direction (so the band shows at its true dip), through the centroid of the grains
compute shearband/lsdem puts in it; without a band, the x-z plane through the grains'
centroid. s is the horizontal coordinate along the dip direction from that centroid."""
import argparse
import csv
import glob
import math
import os
import re
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import lsdem_bands  # noqa: E402
import lsdem_rose as rose  # noqa: E402
from lsdem_vti import node_grid, read_vti  # noqa: E402
import plot as curves  # noqa: E402

# dump.band's columns (in.triaxial): id x y z rotation flag band long-axis[3]
ID, X, ROT, FLAG, BAND, AXIS = 0, slice(1, 4), 4, 5, 6, slice(7, 10)


# ---- reading ------------------------------------------------------------------------------
def read_csv(path):
    """Rows of a CSV as dicts of floats (nan kept)."""
    return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(path))]


def read_parts(run, name):
    """The rows of name.csv and of a resumed run's parts name.<part>.csv (in.triaxial's
    -var part: .2, .3, ... or bench/specimen.sh's .r1, .r2, ...), in the parts' number order."""
    parts = sorted(glob.glob(os.path.join(run, name + ".*.csv")),
                   key=lambda p: int(re.sub(r"\D", "", os.path.basename(p)) or 0))
    first = os.path.join(run, name + ".csv")
    return [r for p in ([first] if os.path.exists(first) else []) + parts for r in read_csv(p)]


def read_dump_frames(paths):
    """{step: array (atoms x columns)} of every frame of LAMMPS custom dumps."""
    frames = {}
    for path in paths:
        for block in open(path).read().split("ITEM: TIMESTEP\n")[1:]:
            lines = block.splitlines()
            start = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS")) + 1
            frames[int(lines[0])] = np.array([[float(w) for w in l.split()]
                                              for l in lines[start:] if l.strip()])
    return frames


def read_grid(path):
    """A fields file's grid (lsdem_vti.read_vti) and its arrays as (nz, ny, nx, components);
    the slices are drawn for orthogonal grids only."""
    vti = read_vti(path)
    if vti["skewed"]:  # a tilted periodic box's skewed grid
        sys.exit("figures.py: %s holds a skewed grid (a tilted box); its slices are drawn for "
                 "orthogonal grids only -- open the file in ParaView (5.10 or later)" % path)
    return vti, {name: node_grid(vti, name) for name in vti["names"]}


def read_vtp(path):
    """fix network/lsdem's lines: {cell array name: array}, and each line's points (list of
    arrays of 2 or 3 points: centre, contact point[, centre])."""
    text = open(path).read()
    arr = {name: np.array(body.split(), float)
           for name, body in re.findall(r'Name="(\w+)"[^>]*>\n([^<]*)</DataArray>', text)}
    pts = np.array(re.search(r"<Points>\n<DataArray[^>]*>\n([^<]*)</DataArray>", text)
                   .group(1).split(), float).reshape(-1, 3)
    ends = arr["offsets"].astype(int)
    starts = np.concatenate([[0], ends[:-1]])
    arr["normal"] = arr["normal"].reshape(-1, 3)
    return arr, [pts[a:b] for a, b in zip(starts, ends)]


# ---- geometry -----------------------------------------------------------------------------
def band_centroid(grains):
    """The centroid of the grains in the first band (compute shearband/lsdem's number 1),
    or None."""
    inside = grains[:, BAND] == 1
    return grains[inside, X].mean(axis=0) if inside.any() else None


def slice_plane(snaps):
    """(p0, t): a point and the horizontal unit vector of the vertical slice: through the
    band of the last snapshot that has one, along its dip direction; else x through the
    grains' centroid."""
    for s in reversed(snaps):
        n = np.array([s["band_nx"], s["band_ny"], s["band_nz"]])
        p = band_centroid(s["grains"])
        if np.all(np.isfinite(n)) and p is not None and math.hypot(n[0], n[1]) > 1e-9:
            return p, np.array([n[0], n[1], 0.0]) / math.hypot(n[0], n[1])
    return snaps[-1]["grains"][:, X].mean(axis=0), np.array([1.0, 0.0, 0.0])


def to_slice(points, p0, t):
    """(s, z, off): points (m, 3) in the slice's coordinates and their distance off it."""
    d = points - p0
    m = np.array([-t[1], t[0], 0.0])          # the slice's horizontal normal
    return d @ t, points[:, 2], d @ m


def band_trace(snap, p0, t, s):
    """z on the slice of the snapshot's own band plane at s (nan without a band): the plane
    n.(x - c) = 0 through its centroid c, x = p0 + s t + (z - p0_z) e_z."""
    n = np.array([snap["band_nx"], snap["band_ny"], snap["band_nz"]])
    c = band_centroid(snap["grains"])
    if c is None or not np.all(np.isfinite(n)) or n[2] == 0.0:
        return np.full_like(s, np.nan)
    return c[2] - (n[0] * (p0[0] - c[0]) + n[1] * (p0[1] - c[1]) + s * (n @ t)) / n[2]


def trilinear(grid, values, points):
    """values (nz, ny, nx) interpolated trilinearly at points (m, 3); nan outside the grid
    or where a corner is nan."""
    f = (points - grid["origin"]) / grid["h"]
    i = np.floor(f).astype(int)
    w = f - i
    n = np.array(grid["n"])
    ok = np.all((i >= 0) & (i < n - 1), axis=1)
    i = np.where(ok[:, None], i, 0)
    out = np.zeros(len(points))
    for corner in range(8):
        c = np.array([(corner >> k) & 1 for k in range(3)])
        weight = np.prod(np.where(c == 1, w, 1.0 - w), axis=1)
        j = i + c
        out += weight * values[j[:, 2], j[:, 1], j[:, 0]]
    return np.where(ok, out, np.nan)


def slice_samples(grid, p0, t, extent, step):
    """Sample points of the slice: s from -extent[0] to extent[0], z from extent[1] to
    extent[2], spaced `step`; returns (s, z, points (ns*nz, 3))."""
    s = np.arange(-extent[0], extent[0] + 0.5 * step, step)
    z = np.arange(extent[1], extent[2] + 0.5 * step, step)
    ss, zz = np.meshgrid(s, z)
    pts = np.stack([p0[0] + ss.ravel() * t[0], p0[1] + ss.ravel() * t[1], zz.ravel()], axis=1)
    return s, z, pts


# ---- force chains -------------------------------------------------------------------------
def classify_lines(ids_a, ids_b, grain_ids):
    """Each line's kind: 'grain' (two grains), 'platen' (a wall), 'membrane' (a grain and a
    membrane sphere), or '' (no grain: left out)."""
    kinds = []
    for a, b in zip(ids_a, ids_b):
        ga, gb = a in grain_ids, b in grain_ids
        kinds.append("platen" if b < 0 else "grain" if ga and gb else
                     "membrane" if ga or gb else "")
    return np.array(kinds)


def strong_stats(fn):
    """(lines, mean normal force, fraction above the mean, their share of the total)."""
    if len(fn) == 0:
        return 0, math.nan, math.nan, math.nan
    mean = fn.mean()
    strong = fn > mean
    return len(fn), mean, strong.mean(), fn[strong].sum() / fn.sum()


def angle_from_vertical(normals):
    """Angles (degrees, 0-90) between axial directions and the z axis."""
    return np.degrees(np.arccos(np.clip(np.abs(normals[:, 2]), 0.0, 1.0)))


def chain_stats(arr, kinds):
    """The strong-chain statistics of one network: over all lines with a grain (grains,
    platens, membrane) and over the grain-grain lines, with the strong and the weak
    grain-grain lines' mean contact-normal angle from the vertical."""
    fn = arr["normal_force"]
    kept = kinds != ""
    out = dict(zip(("lines", "mean_fn", "strong_fraction", "strong_share"), strong_stats(fn[kept])))
    for kind in ("grain", "platen", "membrane"):
        out[kind + "_lines"] = int(np.sum(kinds == kind))
    g = kinds == "grain"
    _, mean_g, out["grain_strong_fraction"], out["grain_strong_share"] = strong_stats(fn[g])
    ang = angle_from_vertical(arr["normal"][g])
    strong = fn[g] > mean_g
    out["grain_strong_angle_deg"] = ang[strong].mean() if strong.any() else math.nan
    out["grain_weak_angle_deg"] = ang[~strong].mean() if (~strong).any() else math.nan
    return out


# ---- fabric -------------------------------------------------------------------------------
def fabric_deviator(axes):
    """Kanatani's deviator D = 15/2 (<n n> - I/3) and anisotropy sqrt(3/2 D:D) of unit
    directions (compute fabric/lsdem's definition); nan for none."""
    if len(axes) == 0:
        return np.full((3, 3), np.nan), math.nan
    u = axes / np.linalg.norm(axes, axis=1)[:, None]
    D = 7.5 * (u.T @ u / len(u) - np.eye(3) / 3.0)
    return D, math.sqrt(1.5 * np.sum(D * D))


# ---- figures ------------------------------------------------------------------------------
def pct(v):
    return "%.1f %%" % (100 * v)


def draw_response(rows, out):
    """Figures 3.12-3.14: q, phi_mob, eps_v, Z against eps_a."""
    ea = [100 * r["eps_a"] for r in rows]
    panels = (("q", 1, "deviatoric stress q (x sigma_c)"), ("phi_deg", 1, "phi_mob (deg)"),
              ("eps_v", 100, "eps_v (%, + = contraction)"), ("Z", 1, "coordination number Z"))
    fig, axs = plt.subplots(2, 2, figsize=(9, 6.5), sharex=True)
    for ax, (key, scale, label) in zip(axs.ravel(), panels):
        ax.plot(ea, [scale * r[key] for r in rows], lw=1)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    for ax in axs[1]:
        ax.set_xlabel("axial strain eps_a (%)")
    fig.suptitle("stress, strain and coordination (report Figures 3.12-3.14)", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "response.png"), dpi=100)
    plt.close(fig)


def theories(rows):
    """Coulomb, Roscoe and Arthur inclinations (deg) from the peak phi and largest psi."""
    phi = max(r["phi_deg"] for r in rows)
    psi = max((r["psi_deg"] for r in rows if math.isfinite(r["psi_deg"])), default=math.nan)
    return phi, psi, {"Coulomb": 45 + phi / 2, "Roscoe": 45 + psi / 2,
                      "Arthur": 45 + (phi + psi) / 4}


def draw_band(rows, out):
    """The band's dip and thickness against eps_a, the three theories as lines."""
    phi, psi, th = theories(rows)
    ea = [100 * r["eps_a"] for r in rows]
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    a1.plot(ea, [r["band_dip"] for r in rows], ".", ms=3)
    for (name, v), style in zip(th.items(), ("--", ":", "-.")):
        a1.axhline(v, ls=style, color="k", lw=0.8, label="%s %.1f deg" % (name, v))
    a1.set_ylabel("band dip (deg from horizontal)")
    a1.legend(fontsize=8, title="peak phi %.1f, largest psi %.1f deg" % (phi, psi),
              title_fontsize=8)
    a2.plot(ea, [r["band_thickness"] for r in rows], ".", ms=3)
    a2.set_ylabel("band thickness (D50)")
    a2.set_xlabel("axial strain eps_a (%)")
    for a in (a1, a2):
        a.grid(alpha=0.3)
    a1.set_title("shear band (compute shearband/lsdem, rotation > mean + 2 sd)", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "band.png"), dpi=100)
    plt.close(fig)
    return phi, psi, th


def slice_extent(snaps, p0, t):
    """Half width along s and z range of the slice: the grains' reach, plus a grain."""
    pts = np.concatenate([s["grains"][:, X] for s in snaps])
    s, z, _ = to_slice(pts, p0, t)
    pad = snaps[-1]["D50"]
    return np.abs(s).max() + pad, z.min() - pad, z.max() + pad


def field_bands(grid, arr, d50):
    """The bands of the shear strain field inside the membrane where the fit is regular
    (lsdem_bands: detrended, cut at mean + 2 sd, sheets 6 D50 long found by RANSAC)."""
    mask = (arr["inside"][..., 0] > 0) & (arr["regular"][..., 0] > 0)
    zones, planes, _ = lsdem_bands.strain_zones(arr["shear_strain"][..., 0], mask,
                                                grid["origin"], grid["h"], d50)
    return zones, planes


BAND_FIELDS = ("step", "eps_a", "zones", "bands", "band", "dip", "azimuth", "length_D50",
               "breadth_D50", "thickness_D50", "pieces", "x", "y", "z")


def band_rows(snaps):
    """bands.csv: every snapshot's bands of the strain field, one row each (BAND_FIELDS)."""
    return [dict(zip(BAND_FIELDS, (snap["step"], snap["eps_a"], len(snap["zones"]),
                                   len(snap["planes"]), i + 1, p["dip"], p["azimuth"],
                                   p["length"], p["breadth"], p["thickness"], p["pieces"],
                                   *p["centre"])))
            for snap in snaps for i, p in enumerate(snap["planes"])]


def sample_slices(snaps, p0, t, out):
    """Shear strain and rotation angle on the slice of every snapshot, and the bands of its
    strain field (snap["zones"], snap["planes"]: field_bands); writes slice_<step>.csv and
    returns [(s, z, strain (nz, ns), rotation (nz, ns))]."""
    extent = slice_extent(snaps, p0, t)
    result = []
    for snap in snaps:
        grid, arr = read_grid(snap["vti"])
        snap["zones"], snap["planes"] = field_bands(grid, arr, snap["D50"])
        s, z, pts = slice_samples(grid, p0, t, extent, 0.5 * grid["h"])
        strain = trilinear(grid, arr["shear_strain"][..., 0], pts)
        angle = np.degrees(np.linalg.norm(arr["rotation"], axis=3))
        rot = trilinear(grid, angle, pts)
        np.savetxt(os.path.join(out, "slice_%d.csv" % snap["step"]),
                   np.column_stack([np.tile(s, len(z)), np.repeat(z, len(s)), pts[:, 0],
                                    pts[:, 1], strain, rot]),
                   delimiter=",", fmt="%.17g", header="s,z,x,y,shear_strain,rotation_deg",
                   comments="")
        result.append((s, z, strain.reshape(len(z), len(s)), rot.reshape(len(z), len(s))))
    return result


def draw_slices(snaps, slices, which, p0, t, name, label, out):
    """One panel per snapshot of slices[k][which] with every snapshot's band trace."""
    values = np.concatenate([sl[which].ravel() for sl in slices])
    finite = values[np.isfinite(values)]
    vmax = np.percentile(finite, 99) if finite.size else 1.0
    fig, axs = plt.subplots(1, len(snaps), figsize=(3.2 * len(snaps) + 1, 5.2), squeeze=False)
    for ax, snap, sl in zip(axs[0], snaps, slices):
        s, z = sl[0], sl[1]
        im = ax.imshow(sl[which], origin="lower", extent=(s[0], s[-1], z[0], z[-1]),
                       vmin=0, vmax=vmax, cmap="magma", interpolation="nearest")
        ax.plot(s, band_trace(snap, p0, t, s), "c--", lw=1)
        ax.set_ylim(z[0], z[-1])
        ax.set_title("eps_a %s" % pct(snap["eps_a"]), fontsize=9)
        ax.set_xlabel("s along the dip direction (px)")
    axs[0][0].set_ylabel("z (px)")
    fig.colorbar(im, ax=axs[0].tolist(), label=label, shrink=0.8)
    fig.suptitle("%s on the vertical slice through the band (dashed: each snapshot's fitted "
                 "plane)" % label, fontsize=9)
    fig.savefig(os.path.join(out, name), dpi=100)
    plt.close(fig)


def draw_band_grains(snaps, p0, t, out):
    """Figure 3.16: every grain seen along the slice's normal; rotated > mean + 2 sd red."""
    fig, axs = plt.subplots(1, len(snaps), figsize=(3.2 * len(snaps), 5.2), squeeze=False)
    for ax, snap in zip(axs[0], snaps):
        g = snap["grains"]
        s, z, _ = to_slice(g[:, X], p0, t)
        flag = g[:, FLAG] == 1
        ax.scatter(s[~flag], z[~flag], s=6, c="0.75", lw=0)
        ax.scatter(s[flag], z[flag], s=14, c="crimson", lw=0, label="rotated > mean + 2 sd")
        line = np.linspace(s.min(), s.max(), 50)
        ax.plot(line, band_trace(snap, p0, t, line), "k--", lw=1, label="fitted plane")
        pad = snap["D50"]
        ax.set_xlim(s.min() - pad, s.max() + pad)
        ax.set_ylim(z.min() - pad, z.max() + pad)
        ax.set_aspect("equal")
        ax.set_title("eps_a %s: %d of %d grains" % (pct(snap["eps_a"]), flag.sum(), len(g)),
                     fontsize=9)
        ax.set_xlabel("s (px)")
    axs[0][0].set_ylabel("z (px)")
    axs[0][0].legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "band_grains.png"), dpi=100)
    plt.close(fig)


def draw_chains(snaps, p0, t, out):
    """Figures 3.18/3.20: the lines whose contact point lies within D50 of the slice,
    projected on it; width by normal force (linear to 4 times the mean, then constant),
    strong (above the mean of all lines with a grain) dark red between grains, blue at
    platens and membrane, weak grey; each snapshot's band plane dashed."""
    fig, axs = plt.subplots(1, len(snaps), figsize=(3.2 * len(snaps), 5.2), squeeze=False,
                            sharey=True)
    stats = []
    for ax, snap in zip(axs[0], snaps):
        arr, lines = read_vtp(snap["vtp"])
        kinds = classify_lines(arr["id_a"], arr["id_b"], set(snap["grains"][:, ID]))
        st = chain_stats(arr, kinds)
        stats.append(dict(step=snap["step"], eps_a=snap["eps_a"], **st))
        fn = arr["normal_force"]
        contact = np.array([l[1] for l in lines])
        _, _, off = to_slice(contact, p0, t)
        keep = (kinds != "") & (np.abs(off) <= snap["D50"])
        strong = fn > st["mean_fn"]
        segs, widths, colours = [], [], []
        for k in np.argsort(fn):          # strong lines drawn last, on top
            if not keep[k]:
                continue
            s, z, _ = to_slice(lines[k], p0, t)
            segs.append(np.column_stack([s, z]))
            widths.append(0.2 + 0.8 * min(fn[k] / st["mean_fn"], 4.0))
            colours.append("0.7" if not strong[k] else
                           "darkred" if kinds[k] == "grain" else "royalblue")
        ax.add_collection(LineCollection(segs, linewidths=widths, colors=colours))
        ax.autoscale()
        line = np.array(ax.get_xlim())
        ax.plot(line, band_trace(snap, p0, t, line), "c--", lw=1)
        ax.set_aspect("equal")
        ax.set_title("eps_a %s: %d lines in the slab,\nstrong %.0f %% of all, carrying %.0f %%"
                     % (pct(snap["eps_a"]), keep.sum(), 100 * st["strong_fraction"],
                        100 * st["strong_share"]), fontsize=8)
        ax.set_xlabel("s (px)")
    axs[0][0].set_ylabel("z (px)")
    fig.suptitle("force chains, slab of 2 D50 about the slice (dark red: strong grain "
                 "contacts; blue: strong platen/membrane contacts; dashed: the fitted band)",
                 fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "chains.png"), dpi=90)
    plt.close(fig)
    return stats


def draw_fabric(snap, out):
    """Figures 3.21-3.24 at the last snapshot: the long axes' density 1 + D:nn (surfaces)
    and spherical histograms inside and outside the band."""
    g = snap["grains"]
    fig = plt.figure(figsize=(9, 4.5))
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 48), np.linspace(0, np.pi, 24))
    n = np.stack([np.sin(v) * np.cos(u), np.sin(v) * np.sin(u), np.cos(v)], axis=-1)
    for k, (name, sel) in enumerate((("inside", g[:, BAND] == 1), ("outside", g[:, BAND] != 1))):
        axes = g[sel, AXIS]
        D, a = fabric_deviator(axes)
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        if np.isfinite(a):
            r = 1.0 + np.einsum("...i,ij,...j->...", n, D, n)
            ax.plot_surface(*(np.clip(r, 0, None)[..., None] * n).transpose(2, 0, 1),
                            facecolors=plt.cm.viridis(r / max(r.max(), 1e-12)), lw=0)
            lim = r.max()
            ax.set(xlim=(-lim, lim), ylim=(-lim, lim), zlim=(-lim, lim), xlabel="x",
                   ylabel="y", zlabel="z")
            ax.set_box_aspect((1, 1, 1))
        ax.set_title("%s the band: %d grains, a = %.2f" % (name, len(axes), a), fontsize=9)
        counts = rose.histogram([tuple(x) for x in axes], 6, 4)
        rose.draw(os.path.join(out, "rose_%s.png" % name), counts, 6, 4, len(axes),
                  "long axes %s the band, eps_a %s" % (name, pct(snap["eps_a"])))
    fig.suptitle("long-axis fabric density 1 + D:nn (report Figures 3.21-3.22)", fontsize=9)
    fig.savefig(os.path.join(out, "fabric_surfaces.png"), dpi=100)
    plt.close(fig)


def band_contact_normals(snap):
    """The grain-grain contact normals of the snapshot's network inside the band (both
    grains in band 1) and outside it (the other grain-grain lines): fix network/lsdem's
    rule for its keyword band."""
    arr, _ = read_vtp(snap["vtp"])
    g = snap["grains"]
    kinds = classify_lines(arr["id_a"], arr["id_b"], set(g[:, ID]))
    band_ids = set(g[g[:, BAND] == 1, ID])
    both = np.array([a in band_ids and b in band_ids for a, b in zip(arr["id_a"], arr["id_b"])],
                    dtype=bool)
    grain = kinds == "grain"
    return arr["normal"][grain & both], arr["normal"][grain & ~both]


def fabric_rows(snaps):
    """Long-axis and contact-normal anisotropy inside and outside the band at every
    snapshot."""
    rows = []
    for snap in snaps:
        g = snap["grains"]
        inside = g[:, BAND] == 1
        n_in, n_out = band_contact_normals(snap)
        rows.append({"step": snap["step"], "eps_a": snap["eps_a"],
                     "inside_grains": int(inside.sum()),
                     "inside_anisotropy": fabric_deviator(g[inside, AXIS])[1],
                     "outside_grains": int((~inside).sum()),
                     "outside_anisotropy": fabric_deviator(g[~inside, AXIS])[1],
                     "inside_contacts": len(n_in),
                     "inside_normal_anisotropy": fabric_deviator(n_in)[1],
                     "outside_contacts": len(n_out),
                     "outside_normal_anisotropy": fabric_deviator(n_out)[1]})
    return rows


def draw_contact_roses(snap, out):
    """The grain contacts' normals as spherical histograms inside and outside the band at
    the last snapshot (the contact-normal counterpart of Figures 3.23-3.24)."""
    for name, normals in zip(("inside", "outside"), band_contact_normals(snap)):
        counts = rose.histogram([tuple(x) for x in normals], 6, 4)
        rose.draw(os.path.join(out, "rose_normals_%s.png" % name), counts, 6, 4, len(normals),
                  "contact normals %s the band, eps_a %s" % (name, pct(snap["eps_a"])))


def write_rows(path, rows, fields=None):
    """A CSV of rows (dicts); its columns those of the first row, or `fields` (so that a file
    of no rows still has its header)."""
    with open(path, "w") as f:
        w = csv.DictWriter(f, fieldnames=fields or list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.10g" % v if isinstance(v, float) else v) for k, v in r.items()})


def load_snapshots(run):
    """snapshots.csv's rows, each with its grains (dump.band), .vti and .vtp."""
    frames = read_dump_frames(sorted(glob.glob(os.path.join(run, "dump.band*"))))
    snaps = []
    for row in read_parts(run, "snapshots"):
        step = int(row["step"])
        snap = dict(row, step=step, grains=frames[step],
                    vti=os.path.join(run, "fields_%d.vti" % step),
                    vtp=os.path.join(run, "chains_%d.vtp" % step))
        snaps.append(snap)
    return snaps


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run")
    ap.add_argument("--out")
    a = ap.parse_args(argv)
    out = a.out or os.path.join(a.run, "figures")
    os.makedirs(out, exist_ok=True)
    rows = read_parts(a.run, "triaxial")
    draw_response(rows, out)
    phi, psi, th = draw_band(rows, out)
    snaps = load_snapshots(a.run)
    snapped = draw_snapshots(snaps, out) if snaps else None
    cyc = os.path.join(a.run, "cycles.csv")
    if os.path.exists(cyc):
        curves.plot_cycles(cyc, out)
    write_summary(rows, phi, psi, th, snapped, out)
    print("figures in %s" % out)


def draw_snapshots(snaps, out):
    """The figures of the snapshots; returns the slice (p0, t), the chains' statistics and
    the snapshots (with their strain fields' bands)."""
    p0, t = slice_plane(snaps)
    slices = sample_slices(snaps, p0, t, out)
    draw_slices(snaps, slices, 2, p0, t, "strain_slices.png", "von Mises shear strain", out)
    draw_slices(snaps, slices, 3, p0, t, "rotation_slices.png", "rotation angle (deg)", out)
    draw_band_grains(snaps, p0, t, out)
    chains = draw_chains(snaps, p0, t, out)
    write_rows(os.path.join(out, "chains.csv"), chains)
    write_rows(os.path.join(out, "bands.csv"), band_rows(snaps), BAND_FIELDS)
    write_rows(os.path.join(out, "fabric.csv"), fabric_rows(snaps))
    draw_fabric(snaps[-1], out)
    draw_contact_roses(snaps[-1], out)
    return p0, t, chains, snaps


def write_summary(rows, phi, psi, th, snapped, out):
    """summary.txt (and the screen): the band at the end, the theories, the chains
    (snapped: draw_snapshots' slice and statistics, None without snapshots)."""
    last = rows[-1]
    with open(os.path.join(out, "summary.txt"), "w") as f:
        if not snapped:
            f.write("no snapshots (in.triaxial writes them at snap_at = 5 %, 10 %, ...)\n")
        else:
            p0, t, chains, _ = snapped
            f.write("slice: through (%.1f, %.1f, %.1f) px along (%.4f, %.4f, 0)\n"
                    % (*p0, t[0], t[1]))
        f.write("band at eps_a %s: dip %.1f deg, thickness %.2f D50; theories from peak phi "
                "%.1f and largest psi %.1f deg: %s\n"
                % (pct(last["eps_a"]), last["band_dip"], last["band_thickness"], phi, psi,
                   ", ".join("%s %.1f" % kv for kv in th.items())))
        for snap in (snapped[3] if snapped else []):
            f.write("strain field at eps_a %s: %d localised zones, %d bands (dip/azimuth deg, "
                    "length D50: %s)\n"
                    % (pct(snap["eps_a"]), len(snap["zones"]), len(snap["planes"]),
                       "; ".join("%.1f/%.0f, %.1f" % (p["dip"], p["azimuth"], p["length"])
                                 for p in snap["planes"]) or "none"))
        for c in (snapped[2] if snapped else []):
            f.write("chains at eps_a %s: %d lines (%d grain, %d platen, %d membrane), strong "
                    "%.3f of them carrying %.3f; grain contacts strong %.3f, strong normals "
                    "%.1f deg from vertical (weak %.1f)\n"
                    % (pct(c["eps_a"]), c["lines"], c["grain_lines"], c["platen_lines"],
                       c["membrane_lines"], c["strong_fraction"], c["strong_share"],
                       c["grain_strong_fraction"], c["grain_strong_angle_deg"],
                       c["grain_weak_angle_deg"]))
    print(open(os.path.join(out, "summary.txt")).read(), end="")


if __name__ == "__main__":
    main(sys.argv[1:])
