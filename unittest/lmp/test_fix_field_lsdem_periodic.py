"""fix field/lsdem in a fully periodic box (issue 35 item 2).

729 balls on a jittered lattice fill the box [0, 9)^3 (a few overlap: contacts, some across
the faces); after run 0 (the reference) the box is deformed homogeneously with change_box
... remap -- pure shear (x scale 1.01, y scale 0.99), dilation of 1 % (x y z scale 1.01),
simple shear 0.01 (a triclinic box of tilt xy = -0.09 sheared to xy = 0, and the cube made
triclinic and sheared to xy = 0.09: a tilted box now), and all three tilts at once (xy 0.09,
xz -0.045, yz 0.18) -- and a run of 1 step writes the fields; and a box that fix deform
flips (xy from 4.3 past half its length in 3 steps: the fields of step 3 come from the
flipped box, xy = 4.5667 - 9, with the reference's period vectors rebased, H = 4.5667 / 9). Checked: the grid spans exactly
the box now (origin boxlo; along each period vector, n times the spacing = its length, the
file's Direction its unit vector); EVERY node is regular and carries H = F - I to 1e-10 relative,
faces included; integrated density = total mass to 1e-12; integrated contact stress =
compute stress/lsdem's sum to 1e-10; 1, 2 and 4 ranks write the same bytes; a run restarted
from a file written after the deformation keeps the reference box (the jumps) and writes
the same bytes."""
import os
import random

import numpy as np

import grain_decks as gd
from lsdemtest import check, finish, run_lmp, thermo
from vti import read_vti, runs_on_ranks

L = 9.0
rng = random.Random(235)
grains = []
for i in range(9):
    for j in range(9):
        for k in range(9):
            x = [c + 0.5 + rng.uniform(-0.06, 0.06) for c in (i, j, k)]
            grains.append({"id": len(grains) + 1, "shape": 2, "density": 1.0 + rng.random(),
                           "x": x, "q": [1.0, 0.0, 0.0, 0.0]})
LIB = os.path.abspath(gd.library())
gd.write_data("cube.data", grains, box=(0.0, L, 0.0, L, 0.0, L))
text = open("cube.data").read()
open("sheared.data", "w").write(text.replace("zlo zhi\n", "zlo zhi\n-0.09 0.0 0.0 xy xz yz\n"))
DATA = {"cube": os.path.abspath("cube.data"), "sheared": os.path.abspath("sheared.data")}

CASES = {
    "pure_shear": ("cube", "change_box all x scale 1.01 y scale 0.99 remap",
                   [[0.01, 0, 0], [0, -0.01, 0], [0, 0, 0]]),
    "dilation": ("cube", "change_box all x scale 1.01 y scale 1.01 z scale 1.01 remap",
                 [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]]),
    "simple_shear": ("sheared", "change_box all xy final 0.0 remap",
                     [[0, 0.01, 0], [0, 0, 0], [0, 0, 0]]),
    "tilted_now": ("cube", "change_box all triclinic\nchange_box all xy final 0.09 remap",
                   [[0, 0.01, 0], [0, 0, 0], [0, 0, 0]]),
    "three_tilts": ("cube", "change_box all triclinic\n"
                    "change_box all xy final 0.09 xz final -0.045 yz final 0.18 remap",
                    [[0, 0.01, -0.005], [0, 0, 0.02], [0, 0, 0]]),
    # fix deform every 2 steps: at step 2 the tilt 4.3 + 0.4 * 2/3 passes half the length,
    # step 3 flips it by - 9 (and deforms no more): the fields of step 3
    "flipped": ("cube", "change_box all triclinic\nchange_box all xy final 4.3 remap\n"
                "fix d all deform 2 xy delta 0.4 remap x flip yes",
                [[0, (4.3 + 0.4 * 2 / 3) / 9, 0], [0, 0, 0], [0, 0, 0]], 3, 1.0),
}

DECK = """units lj
atom_style lsdem library %s
atom_modify map array
boundary p p p
comm_modify vel yes
read_data %s
pair_style lsdem
pair_coeff * * 1000 1000 0.5
variable next equal stride(1,1000,1)
fix f all field/lsdem v_next field kernel 1.2 spacing 0.5
compute st all stress/lsdem volume 1.0
variable mt equal mass(all)
variable lx equal lx
variable ly equal ly
variable lz equal lz
variable xy equal xy
variable xz equal xz
variable yz equal yz
thermo_style custom step v_mt v_lx v_ly v_lz v_xy v_xz v_yz c_st[1] c_st[2] c_st[3] c_st[4] c_st[5] c_st[6]
thermo_modify format float %%.17g
run 0
%s
run %d
"""

for name, case in CASES.items():
    data, change, H = case[:3]
    nrun = case[3] if len(case) > 3 else 1
    # a box tilted near half its length reaches more nodes (the skew): a narrower kernel
    kernel = "kernel %g" % (case[4] if len(case) > 4 else 1.2)
    outs, first = runs_on_ranks((DECK % (LIB, DATA[data], change, nrun)).replace(
        "kernel 1.2", kernel), name, "field_%d.vti" % nrun)
    if first:
        path, log = first
        f = read_vti(path)
        row = thermo(log)[-1]
        n, h = f["n"], f["spacing"]
        period = np.array([[row["v_lx"], 0, 0], [row["v_xy"], row["v_ly"], 0],
                           [row["v_xz"], row["v_yz"], row["v_lz"]]])
        if name == "flipped":
            check(row["v_xy"] < -4.0, "flipped: the box did not flip (xy %r)" % row["v_xy"])
        length = np.linalg.norm(period, axis=1)
        check(all(abs(n[k] * h[k] - length[k]) <= 1e-12 * length[k] for k in range(3)),
              "%s: grid %r x %r, period vectors %r" % (name, n, h, period))
        check(np.abs(f["direction"].T - period / length[:, None]).max() <= 1e-14,
              "%s: Direction %r, period vectors %r" % (name, f["direction"], period))
        check(("Direction" in open(path, "rb").read(2000).decode("latin-1")) ==
              bool(np.abs(period - np.diag(np.diag(period))).max() > 0),
              "%s: a Direction where the box is orthogonal, or none where it is tilted" % name)
        reg = f["regular"][:, 0] == 1
        nodes = n[0] * n[1] * n[2]
        check(reg.all(), "%s: %d of %d nodes regular" % (name, reg.sum(), nodes))
        Hm = np.array(H, dtype=float)
        err = np.abs(f["displacement_gradient"] - Hm.reshape(9)).max()
        check(err <= 1e-10 * np.abs(Hm).max(), "%s: gradient off by %g" % (name, err))
        # the faces' nodes in particular (the first and last of each axis)
        idx = np.arange(nodes)
        ijk = (idx % n[0], idx // n[0] % n[1], idx // (n[0] * n[1]))
        face = np.zeros(nodes, bool)
        for k in range(3):
            face |= (ijk[k] == 0) | (ijk[k] == n[k] - 1)
        err_face = np.abs(f["displacement_gradient"][face] - Hm.reshape(9)).max()
        dv = h[0] * h[1] * h[2] * abs(np.linalg.det(f["direction"]))  # a voxel's volume
        mass = row["v_mt"]
        check(abs(f["density"].sum() * dv - mass) <= 1e-12 * mass,
              "%s: integrated density %r, mass %r" % (name, f["density"].sum() * dv, mass))
        sigma = [row["c_st[%d]" % k] for k in range(1, 7)]
        s = f["stress"].sum(axis=0) * dv
        got = [s[0], s[4], s[8], s[1], s[2], s[5]]
        scale = max(abs(c) for c in sigma)
        check(scale > 0.0, "%s: no contacts" % name)
        check(all(abs(a - b) <= 1e-10 * scale for a, b in zip(got, sigma)),
              "%s: integrated stress %r, compute stress/lsdem %r" % (name, got, sigma))
        print("%s: %d nodes, all regular; gradient error %.2e relative (faces %.2e); "
              "mass %.2e; stress %.2e" % (
                  name, nodes, err / np.abs(Hm).max(), err_face / np.abs(Hm).max(),
                  abs(f["density"].sum() * dv - mass) / mass,
                  max(abs(a - b) for a, b in zip(got, sigma)) / scale))
    check(len(outs) == 3 and outs[1] == outs[2] == outs[4],
          "%s: 1, 2, 4 ranks write different fields (%s)" % (name, sorted(outs)))
    if name != "pure_shear":
        continue
    # the reference box survives a restart written after the deformation
    deck = DECK % (LIB, DATA[data], change, nrun)
    run_lmp(deck[:deck.rindex("run 1\n")] + "write_restart deformed.restart\n", cwd="restart")
    run_lmp("""atom_style lsdem library %s
read_restart deformed.restart
comm_modify vel yes
pair_style lsdem
pair_coeff * * 1000 1000 0.5
variable next equal stride(1,1000,1)
fix f all field/lsdem v_next field kernel 1.2 spacing 0.5
run 1
""" % LIB, cwd="restart")
    path = os.path.join("restart", "field_1.vti")
    check(os.path.exists(path) and open(path, "rb").read() == outs.get(1),
          "%s: the restarted run lost the reference box" % name)
finish()
