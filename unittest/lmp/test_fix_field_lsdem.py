"""fix field/lsdem: continuum fields written as .vti + .pvd.

A: a spread-out random set of 216 grains is mapped affinely (displace_atoms, x -> (I + H) x,
   simple shear of 1 %): at every regular node the displacement gradient is H and the Green
   strain (H + H^T + H^T H) / 2 to 1e-10 relative; integrated density and solid fraction are
   the total mass and solid volume to 1e-12; 1 and 2 ranks write the same bytes; a run
   restarted from a file written after the map (the fix defined again with its ID) keeps
   the reference and writes the same bytes.
B: three cubes settled on a floor wall: the integrated contact stress over the specimen
   volume V equals compute stress/lsdem's with the same V and wall to 1e-10; 1, 2 and 4
   ranks write the same bytes; the mask leaves nodes outside the cylinder NaN."""
import os
import random

import numpy as np

import grain_decks as gd
from contact_decks import Grain, box_library, head, THERMO_FULL
from contact_decks import write_data as write_contact_data
from lsdemtest import check, finish, run_lmp, thermo
from vti import read_vti, runs_on_ranks

# ---- A: affine map of a random spread-out set --------------------------------------
rng = random.Random(35)
grains = []
for i in range(6):
    for j in range(6):
        for k in range(6):
            x = [2.5 * (c - 2.5) + rng.uniform(-0.4, 0.4) for c in (i, j, k)]
            q = gd.qnormalize([rng.gauss(0, 1) for _ in range(4)])
            grains.append({"id": len(grains) + 1, "shape": 2 + len(grains) % 2,
                           "density": 1.0 + 0.5 * rng.random(), "x": x, "q": q})
DATA = os.path.abspath(gd.write_data("grains.data", grains))
LIB = os.path.abspath(gd.library())
H = [[0.0, 0.01, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]

DECK_A = """units lj
atom_style lsdem library %s
atom_modify map array
boundary f f f
comm_modify vel yes
read_data %s
pair_style lsdem
pair_coeff * * 1000 1000 0.5
fix f all field/lsdem 1 field kernel 2.5 spacing 1.0
fix strict all field/lsdem 1 strict kernel 2.5 spacing 1.0 regular 0.5 0.2
variable mt equal mass(all)
thermo_style custom step v_mt
%s
run 0
variable dx atom %r*x+%r*y+%r*z
variable dy atom %r*x+%r*y+%r*z
variable dz atom %r*x+%r*y+%r*z
displace_atoms all move v_dx v_dy v_dz
run 1
""" % (LIB, DATA, THERMO_FULL, *[c for row in H for c in row])


def check_affine(wd):
    f = read_vti(os.path.join(wd, "field_1.vti"))
    reg = f["regular"][:, 0] == 1
    nodes = f["n"][0] * f["n"][1] * f["n"][2]
    check(reg.sum() > nodes // 10, "A: %d regular nodes of %d" % (reg.sum(), nodes))
    Hm = np.array(H)
    E = 0.5 * (Hm + Hm.T + Hm.T @ Hm)
    err_h = np.abs(f["displacement_gradient"][reg] - Hm.reshape(9)).max()
    err_e = np.abs(f["strain_green"][reg] - E.reshape(9)).max()
    check(err_h <= 1e-10 * 0.01, "A: gradient off by %g" % err_h)
    check(err_e <= 1e-10 * np.abs(E).max(), "A: Green strain off by %g" % err_e)
    check(np.isnan(f["displacement_gradient"][~reg]).all(), "A: irregular nodes are NaN")
    # stricter thresholds (keyword regular): fewer regular nodes, all of them regular by the
    # default thresholds too, with the same values
    s = read_vti(os.path.join(wd, "strict_1.vti"))
    sreg = s["regular"][:, 0] == 1
    check(0 < sreg.sum() < reg.sum() and not (sreg & ~reg).any(),
          "A: regular 0.5 0.2 gives %d regular nodes, the default %d" % (sreg.sum(), reg.sum()))
    check((s["displacement_gradient"][sreg] == f["displacement_gradient"][sreg]).all(),
          "A: the thresholds changed values")
    dv = f["h"] ** 3
    mass = thermo(open(os.path.join(wd, "log.lammps")).read())[-1]["v_mt"]
    volume = sum(gd.closed_form(g["shape"])[0] for g in grains)
    check(abs(f["density"].sum() * dv - mass) <= 1e-12 * mass,
          "A: integrated density %r, mass %r" % (f["density"].sum() * dv, mass))
    check(abs(f["solid_fraction"].sum() * dv - volume) <= 1e-12 * volume,
          "A: integrated solid fraction %r, volume %r" % (f["solid_fraction"].sum() * dv, volume))
    # before the map: no strain anywhere
    f0 = read_vti(os.path.join(wd, "field_0.vti"))
    pvd = open(os.path.join(wd, "field.pvd")).read()
    check('file="field_0.vti"' in pvd and 'file="field_1.vti"' in pvd, "A: the .pvd lists both")
    return open(os.path.join(wd, "field_1.vti"), "rb").read(), f0


outs = {}
for np_ in (1, 2):
    wd = "affine_np%d" % np_
    run_lmp(DECK_A, np=np_, cwd=wd)
    if os.path.exists(os.path.join(wd, "field_1.vti")):
        outs[np_] = check_affine(wd)[0]
check(len(outs) == 2 and outs[1] == outs[2], "A: 1 and 2 ranks write different fields")

# the reference survives a restart: map the grains, write the file, read it, define the fix
# again and run (a reference taken anew would see no displacement)
mapped = DECK_A[:DECK_A.rindex("run 1\n")]
run_lmp(mapped + "write_restart mapped.restart\n", cwd="restart")
run_lmp("""atom_style lsdem library %s
read_restart mapped.restart
comm_modify vel yes
pair_style lsdem
pair_coeff * * 1000 1000 0.5
fix f all field/lsdem 1 field kernel 2.5 spacing 1.0
run 1
""" % LIB, cwd="restart")
path = os.path.join("restart", "field_1.vti")
check(os.path.exists(path) and open(path, "rb").read() == outs.get(1),
      "A: the restarted run lost the reference")

# ---- B: contact stress of a little settled pile -------------------------------------
lib = box_library("cube.lslib", 0.5, 0.05, 600)
write_contact_data("wall.data", (-3, 3, -3, 3, 0, 4),
                   [Grain((-0.55, 0, 0.5)), Grain((0.55, 0, 0.5)), Grain((0, 0, 1.5))])
V = 8.0
DECK_B = head(lib, "wall.data", boundary="f f f") + """
pair_style lsdem
pair_coeff * * 1000 1000 0.5 cn 2.0
fix grav all gravity 1.0 vector 0 0 -1
fix 1 all nve/lsdem damping 4.0
fix floor all wall/lsdem plane 0 0 0 0 0 1 1000 1000 0.5 cn 2.0
fix f all field/lsdem 500 field kernel 0.4 spacing 0.1 wall floor mask cylinder 0 0 2.2 -1.5 3.5
compute st all stress/lsdem volume %r wall floor
thermo_style custom step c_st[1] c_st[2] c_st[3] c_st[4] c_st[5] c_st[6]
%s
thermo 1000
timestep 1e-3
run 1000
""" % (V, THERMO_FULL)

outs, first = runs_on_ranks(DECK_B, "pile", "field_1000.vti")
if first:
    path, log = first
    f = read_vti(path)
    row = thermo(log)[-1]
    sigma = [row["c_st[%d]" % k] for k in range(1, 7)]
    inside = f["inside"][:, 0] == 1
    # the cylinder holds the cubes, their branches and the kernel's reach (3 x 0.4) around
    # them: the masked nodes held no stress, so the integral over the inside is the whole
    s = np.nansum(f["stress"][inside], axis=0) * f["h"] ** 3 / V
    got = [s[0], s[4], s[8], s[1], s[2], s[5]]
    scale = max(abs(c) for c in sigma)
    check(scale > 0.1, "B: the pile carries stress (%r)" % sigma)
    check(all(abs(a - b) <= 1e-10 * scale for a, b in zip(got, sigma)),
          "B: integrated field stress %r, compute stress/lsdem %r" % (got, sigma))
    n = f["n"]
    idx = np.arange(n[0] * n[1] * n[2])
    x = f["origin"][0] + f["h"] * (idx % n[0])
    y = f["origin"][1] + f["h"] * (idx // n[0] % n[1])
    z = f["origin"][2] + f["h"] * (idx // (n[0] * n[1]))
    expect = (x * x + y * y <= 2.2 ** 2) & (z >= -1.5) & (z <= 3.5)
    check((inside == expect).all() and (~inside).sum() > 0,
          "B: mask cylinder: %d nodes differ, %d outside" % ((inside != expect).sum(),
                                                             (~inside).sum()))
    check(np.isnan(f["stress"][~inside]).all() and not np.isnan(f["stress"][inside]).any(),
          "B: NaN outside the mask only")
check(len(outs) == 3 and outs[1] == outs[2] == outs[4], "B: 1, 2, 4 ranks differ")
finish()
