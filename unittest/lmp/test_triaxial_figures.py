"""The triaxial figure pack (examples/triaxial/figures.py) on a tiny run of in.triaxial: the
small test specimen of triaxial_specimen.py, consolidated 600 steps, sheared at erate 5e-3
(3e-5 axial strain a step) to 0.6 % with snapshots every 0.2 % (-var snap_at 0.002), 2 ranks.

Independent expectations:
1. the snapshots (fields, chains, band dump, snapshots.csv) come on the steps the deck's
   definition gives: the first step at or beyond k snap_at, k = 1, 2, 3, by the platen's step
   count D from the start of shearing, step0 + ceil((1 - e^-eps) / (erate dt)); their eps_a is
   -ln(1 - D erate dt) (the platen moves erate H0 dt a step); fix field/lsdem and fix
   network/lsdem (N = v_snap_next) write on those steps and no others;
2. every PNG of the pack is written and is a PNG; bands.csv has its header;
3. the strain slice: every sample of slice_<step>.csv lies on the vertical plane through the
   band's grain centroid (dump.band, band number 1) normal to the band's horizontal
   direction (snapshots.csv's normal), and its shear strain equals a trilinear interpolation,
   done here with the test's own VTI reader (vti.py), of the .vti's shear_strain at the
   sample's point, to 1e-12 relative, where the eight nodes around it are regular;
4. the force chains: chains.csv's statistics over every line with a grain (grains, platens,
   membrane) equal fix network/lsdem's own (the C core lsdem_strong_chains, printed in
   snapshots.csv) to 1e-8, and the grain-grain figures equal a count done here on the .vtp
   parsed as XML (mean normal force, fraction above it, their share, the strong lines'
   mean normal angle from the vertical) to 1e-9."""
import csv
import math
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np

from lsdemtest import run_lmp, check, near, finish
from triaxial_specimen import make, DECK, EXAMPLE
from vti import read_vti

ERATE, DT, SNAP = 5.0e-3, 0.006, 0.002
rc, log = run_lmp(DECK, np=2, vars=dict(make(), ncons=600, every=10, erate=ERATE,
                                        epsmax=0.006, snap_at=SNAP))
step0 = int(re.search(r"variable step0 equal (\d+)", open("shear_state.in").read()).group(1))
snaps = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open("snapshots.csv"))]

# 1. the snapshot steps
want = [step0 + math.ceil((1 - math.exp(-k * SNAP)) / (ERATE * DT)) for k in (1, 2, 3)]
steps = [int(s["step"]) for s in snaps]
check(steps == want, "snapshot steps %s, expected %s" % (steps, want))
for s in snaps:
    near(s["eps_a"], -math.log(1 - (s["step"] - step0) * ERATE * DT), rtol=2e-5,
         msg="eps_a at step %d" % s["step"])
for pattern in (r"fields_(\d+)\.vti$", r"chains_(\d+)\.vtp$"):
    written = sorted(int(m.group(1)) for m in map(re.compile(pattern).match, os.listdir("."))
                     if m)
    check(written == want, "%s written on steps %s, no others" % (pattern, written))

# 2. the figure pack
p = subprocess.run([sys.executable, os.path.join(EXAMPLE, "figures.py"), "."],
                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
check(p.returncode == 0, "figures.py: %s" % p.stdout[-3000:])
for png in ("response", "band", "strain_slices", "rotation_slices", "band_grains", "chains",
            "fabric_surfaces", "rose_inside", "rose_outside", "rose_normals_inside",
            "rose_normals_outside"):
    path = os.path.join("figures", png + ".png")
    ok = os.path.exists(path) and open(path, "rb").read(8) == b"\x89PNG\r\n\x1a\n"
    check(ok, "%s is a PNG" % path)
# bands.csv is written with its header even when no snapshot has a band
bands = open(os.path.join("figures", "bands.csv")).read().splitlines() \
    if os.path.exists(os.path.join("figures", "bands.csv")) else []
check(bands[:1] == ["step,eps_a,zones,bands,band,dip,azimuth,length_D50,breadth_D50,"
                    "thickness_D50,pieces,x,y,z"], "figures/bands.csv header: %s" % bands[:1])


def grains_of(step):
    """dump.band's frame of `step`: rows id x y z rotation flag band axis[3]."""
    text = open("dump.band").read().split("ITEM: TIMESTEP\n")
    frame = next(f for f in text[1:] if int(f.split("\n", 1)[0]) == step)
    rows = frame.split("ITEM: ATOMS")[1].splitlines()[1:]
    return np.array([[float(w) for w in r.split()] for r in rows if r.strip()])


# 2b. the fields are masked by the membrane (in.triaxial: mask membrane conf): the nodes
# near the specimen's axis at mid-height are inside, every node further from the axis than
# the outermost grain centre plus two grain sizes is outside
for s in snaps:
    f = read_vti("fields_%d.vti" % int(s["step"]))
    g = grains_of(int(s["step"]))
    nx, ny, nz = f["n"]
    k, j, i = np.meshgrid(np.arange(nz), np.arange(ny), np.arange(nx), indexing="ij")
    pts = np.column_stack([i.ravel(), j.ravel(), k.ravel()]) * np.array(f["spacing"]) + f["origin"]
    axis = g[:, 1:3].mean(axis=0)
    rad = np.hypot(pts[:, 0] - axis[0], pts[:, 1] - axis[1])
    rmax = np.hypot(g[:, 1] - axis[0], g[:, 2] - axis[1]).max()
    zlo, zhi = g[:, 3].min(), g[:, 3].max()
    inside = f["inside"][:, 0] == 1
    core = (rad < 0.5 * rmax) & (np.abs(pts[:, 2] - 0.5 * (zlo + zhi)) < 0.25 * (zhi - zlo))
    far = rad > rmax + 2.0 * s["D50"]
    check(core.any() and inside[core].all(),
          "step %d: %d of %d nodes near the axis masked" % (s["step"], (~inside[core]).sum(), core.sum()))
    check(far.any() and not inside[far].any(),
          "step %d: %d nodes beyond the membrane not masked" % (s["step"], inside[far].sum()))

# 3. the slice: its plane, and its values against the field
plane = None
for s in reversed(snaps):
    g = grains_of(int(s["step"]))
    inband = g[:, 6] == 1
    if math.isfinite(s["band_nx"]) and inband.any():
        h = np.array([s["band_nx"], s["band_ny"]])
        plane = (g[inband, 1:3].mean(axis=0), h / np.linalg.norm(h))
        break
if plane is None:                      # no band: the x-z plane through the centroid
    g = grains_of(steps[-1])
    plane = (g[:, 1:3].mean(axis=0), np.array([1.0, 0.0]))
centre, dipdir = plane
normal = np.array([-dipdir[1], dipdir[0]])
checked = 0
for st in steps:
    rows = np.loadtxt(os.path.join("figures", "slice_%d.csv" % st), delimiter=",", skiprows=1)
    off = np.abs((rows[:, 2:4] - centre) @ normal).max()
    check(off < 1e-9, "step %d: the slice's samples within %.3g px of the band's plane" % (st, off))
    f = read_vti("fields_%d.vti" % st)
    nx, ny, nz = f["n"]
    strain = f["shear_strain"][:, 0].reshape(nz, ny, nx)
    worst, n = 0.0, 0
    for s_, z, x, y, value, _ in rows[::37]:
        u = (np.array([x, y, z]) - f["origin"]) / f["h"]
        i = np.floor(u).astype(int)
        if np.any(i < 0) or np.any(i + 1 >= np.array([nx, ny, nz])):
            continue
        cube = strain[i[2]:i[2] + 2, i[1]:i[1] + 2, i[0]:i[0] + 2]
        if not np.all(np.isfinite(cube)):
            continue
        w = u - i
        wx, wy, wz = np.array([1 - w[0], w[0]]), np.array([1 - w[1], w[1]]), np.array([1 - w[2], w[2]])
        direct = np.einsum("k,j,i,kji->", wz, wy, wx, cube)
        worst = max(worst, abs(value - direct) / max(abs(direct), 1e-300))
        n += 1
    check(n >= 20 and worst <= 1e-12,
          "step %d: %d slice samples equal the field's trilinear value within %.3g" % (st, n, worst))
    checked += n

# 4. the force chains
chains = {int(float(r["step"])): {k: float(v) for k, v in r.items()}
          for r in csv.DictReader(open(os.path.join("figures", "chains.csv")))}
for s in snaps:
    st = int(s["step"])
    c = chains[st]
    for mine, fix in (("lines", "chain_lines"), ("mean_fn", "chain_mean_fn"),
                      ("strong_fraction", "chain_strong_fraction"),
                      ("strong_share", "chain_strong_share")):
        near(c[mine], s[fix], rtol=1e-8, msg="step %d: %s as fix network/lsdem's" % (st, mine))
    cells = {a.get("Name"): a.text.split() for a in
             ET.parse("chains_%d.vtp" % st).getroot().iter("DataArray") if a.get("Name")}
    grain_ids = set(int(v) for v in grains_of(st)[:, 0])
    fn, cosz = [], []
    for k, (a, b) in enumerate(zip(cells["id_a"], cells["id_b"])):
        if int(a) in grain_ids and int(b) in grain_ids:
            fn.append(float(cells["normal_force"][k]))
            cosz.append(abs(float(cells["normal"][3 * k + 2])))
    fn, cosz = np.array(fn), np.array(cosz)
    strong = fn > fn.mean()
    check(c["grain_lines"] == len(fn), "step %d: %d grain lines" % (st, len(fn)))
    near(c["grain_strong_fraction"], strong.mean(), rtol=1e-9, msg="step %d: grain strong fraction" % st)
    near(c["grain_strong_share"], fn[strong].sum() / fn.sum(), rtol=1e-9,
         msg="step %d: grain strong share" % st)
    near(c["grain_strong_angle_deg"], np.degrees(np.arccos(cosz[strong])).mean(), rtol=1e-9,
         msg="step %d: strong normals' angle from the vertical" % st)

# 5. the contact-normal fabric inside and outside the band (fabric.csv): recounted from the
#    network's XML and dump.band's band numbers, inside = both grains in band 1
fabric = {int(float(r["step"])): {k: float(v) for k, v in r.items()}
          for r in csv.DictReader(open(os.path.join("figures", "fabric.csv")))}


def anisotropy(normals):
    """sqrt(3/2 D:D), D = 15/2 (<n n> - I/3) (Kanatani), written out by components."""
    if not normals:
        return float("nan")
    D = [[7.5 * (sum(n[i] * n[j] for n in normals) / len(normals) - (i == j) / 3.0)
          for j in range(3)] for i in range(3)]
    return math.sqrt(1.5 * sum(D[i][j] ** 2 for i in range(3) for j in range(3)))


for s in snaps:
    st = int(s["step"])
    g = grains_of(st)
    grain_ids = set(int(v) for v in g[:, 0])
    band_ids = set(int(v) for v in g[g[:, 6] == 1, 0])
    cells = {a.get("Name"): a.text.split() for a in
             ET.parse("chains_%d.vtp" % st).getroot().iter("DataArray") if a.get("Name")}
    sides = {"inside": [], "outside": []}
    for k, (a, b) in enumerate(zip(cells["id_a"], cells["id_b"])):
        a, b = int(a), int(b)
        if a in grain_ids and b in grain_ids:
            n = [float(v) for v in cells["normal"][3 * k:3 * k + 3]]
            sides["inside" if a in band_ids and b in band_ids else "outside"].append(n)
    for side, normals in sides.items():
        check(fabric[st][side + "_contacts"] == len(normals),
              "step %d: %d grain contacts %s the band" % (st, len(normals), side))
        a = anisotropy(normals)
        if math.isnan(a):
            check(math.isnan(fabric[st][side + "_normal_anisotropy"]), "step %d: no %s contacts" % (st, side))
        else:
            near(fabric[st][side + "_normal_anisotropy"], a, rtol=1e-9,
                 msg="step %d: contact-normal anisotropy %s the band" % (st, side))
finish()
