"""fix wall/lsdem map: per-triangle force maps of a mesh wall (issue 32 item 4).

Cubes on the top face of an STL block (z = 0), against independent expectations:
  - at rest, the map's normal forces add up to the weights, on the top face's triangles
    only, and the pressure is the normal force over the triangle's area;
  - one impact per cube dropped on the block;
  - a cube sliding to rest from v0 with friction mu books a friction work
    sum fn |v_t| dt = m v0^2 / (2 mu) (the work of friction) within 2 %;
  - the map files are the same bits on 1 and 2 ranks, and a run restarted mid-way writes
    the uninterrupted run's map;
  - a spinning mesh drum with eight cubes: wall force and maps the same bits on 1, 2 and 4
    ranks and after a restart (issue 32's drum check);
  - map on a plane wall is refused."""
import math
import os
import re

from lsdemtest import run_lmp, check, near, finish, shape_tool, thermo
from contact_decks import (Grain, box_library, write_data, head, THERMO_FULL, write_cube_stl,
                           write_stl)

HALF = 0.25
lib = box_library("cube.lslib", HALF, 0.025, 300)
stl = write_cube_stl("block.stl", (-3.0, -3.0, -1.0), (3.0, 3.0, 0.0))
band = os.path.abspath("block.band")
shape_tool("wall", stl, band, "--spacing", 0.05, "--width", 0.1)
MASS = (2 * HALF) ** 3


def cube_at(x, y, z=HALF + 1e-4, v=(0.0, 0.0, 0.0)):
    return Grain((x, y, z), v=v)


def run(name, grains, steps, every, mu=0.5, np=1, read=None, tail="", cn=0.5):
    if read:
        top = "read_restart %s\n" % read
    else:
        write_data(name + ".data", (-4, 4, -4, 4, -2, 4), grains)
        top = head(lib, name + ".data", boundary="f f f")
    d = top + """
pair_style lsdem
pair_coeff * * 300 300 0.5 cn 0.5
fix grav all gravity 1.0 vector 0 0 -1
fix 1 all nve/lsdem
fix w all wall/lsdem mesh %s 300 300 %r cn %r map %d map/w
thermo_style custom step ke f_w[3]
%s
thermo %d
timestep 1e-3
%s
run %d
""" % (band, mu, cn, every, THERMO_FULL, every, tail, steps)
    folder = os.path.abspath(name)
    os.makedirs(os.path.join(folder, "map"), exist_ok=True)
    rc, log = run_lmp(d, np=np, cwd=folder)
    return folder


def cells(path):
    """The CellData arrays of a map .vtp: {name: [values per triangle]}."""
    text = open(path).read()
    out = {}
    for name, body in re.findall(r'<DataArray type="Float64" Name="(\w+)" format="ascii">\n(.*?)</DataArray>',
                                 text, re.S):
        out[name] = [float(v) for v in body.split()]
    return out


# ---- at rest: forces add up to the weights, on the top face -----------------------------
spots = [(-1.5, -1.5), (1.2, -0.8), (-0.7, 1.9), (1.6, 1.4)]
# each cube starts pressed in by its static overlap m g / (nodes kn) ~ 8e-6 (50 nodes on a
# face): it touches from the first step on, and never leaves: one impact each
rest = run("rest", [cube_at(x, y, z=HALF - 8e-6) for x, y in spots], 2000, 1000, cn=3.0)
m = cells(os.path.join(rest, "map", "w_2000.vtp"))
if check("normal_force" in m and len(m["normal_force"]) == 12, "rest: no map of 12 triangles"):
    near(sum(m["normal_force"]), len(spots) * MASS, rtol=2e-3,
         msg="rest: the map's normal forces add up to the weights")
    # the top face (z = 0) is triangles 2 and 3 of write_cube_stl's quads (the second quad)
    loaded = [t for t, f in enumerate(m["normal_force"]) if f > 0]
    check(set(loaded) <= {2, 3}, "rest: load on triangles %s, not only on the top face" % loaded)
    for t in loaded:
        near(m["pressure"][t], m["normal_force"][t] / m["area"][t], rtol=1e-6,
             msg="rest: pressure of triangle %d" % t)
    near(sum(m["impacts"]), len(spots), atol=0, msg="rest: one impact per cube")

# ---- sliding to rest: the friction work -----------------------------------------------
V0, MU = 1.0, 0.4
slide = run("slide", [cube_at(-2.0, 0.0, v=(V0, 0.0, 0.0))], 3000, 3000, mu=MU)  # stops at 2.5
m = cells(os.path.join(slide, "map", "w_3000.vtp"))
if check("friction_work" in m, "slide: no map"):
    near(sum(m["friction_work"]), MASS * V0 ** 2 / (2 * MU), rtol=0.02,
         msg="slide: friction work = m v0^2 / (2 mu)")

# ---- ranks and restart ------------------------------------------------------------------
grains = [cube_at(x, y, v=(0.3, -0.2, 0.0)) for x, y in spots]
one = run("np1", grains, 600, 300)
two = run("np2", grains, 600, 300, np=2)
for step in (300, 600):
    a = open(os.path.join(one, "map", "w_%d.vtp" % step)).read()
    b = open(os.path.join(two, "map", "w_%d.vtp" % step)).read()
    check(a == b, "ranks: the map of step %d differs between 1 and 2 ranks" % step)
ref = run("ref", grains, 600, 300, tail="restart 300 mid.*")
again = run("again", None, 300, 300, read=os.path.join(ref, "mid.300"))
if check(os.path.exists(os.path.join(again, "map", "w_600.vtp")), "restart: no map written"):
    check(open(os.path.join(ref, "map", "w_600.vtp")).read() ==
          open(os.path.join(again, "map", "w_600.vtp")).read(),
          "restart: the resumed map differs from the uninterrupted run's")
check(os.path.exists(os.path.join(one, "map", "w.pvd")), "no ParaView index w.pvd")

# ---- a spinning mesh drum: force and map on 1, 2 and 4 ranks, and across a restart ----
def write_drum_stl(path, radius, y0, y1, segments=24):
    """A closed cylinder about the y axis, faces pointing inwards: a drum (its inside is
    the grains' side, its outside solid)."""
    ring = [(radius * math.cos(2 * math.pi * k / segments), radius * math.sin(2 * math.pi * k / segments))
            for k in range(segments)]
    tris = []
    for k in range(segments):
        (xa, za), (xb, zb) = ring[k], ring[(k + 1) % segments]
        a0, b0, a1, b1 = (xa, y0, za), (xb, y0, zb), (xa, y1, za), (xb, y1, zb)
        tris += [(a0, b1, a1), (a0, b0, b1)]                    # the mantle, facing the axis
        tris += [((0.0, y0, 0.0), b0, a0), ((0.0, y1, 0.0), a1, b1)]  # the end caps, inwards
    return write_stl(path, tris, "drum")


drum_band = os.path.abspath("drum.band")
shape_tool("wall", write_drum_stl("drum.stl", 1.5, -0.6, 0.6), drum_band, "--spacing", 0.05,
           "--width", 0.1)
drum_cubes = [cube_at(x, y, z=-0.6) for x in (-0.7, -0.2, 0.3, 0.8) for y in (-0.28, 0.28)]


def drum(name, steps, np=1, read=None, tail=""):
    """Eight cubes falling into the drum turning at 1 rad/time about y; thermo and map."""
    if read:
        top = "read_restart %s\n" % read
    else:
        write_data(name + ".data", (-2, 2, -1, 1, -2, 2), drum_cubes)
        top = head(lib, name + ".data", boundary="f f f")
    d = top + """
pair_style lsdem
pair_coeff * * 300 300 0.5 cn 0.5
fix grav all gravity 4.0 vector 0 0 -1
fix 1 all nve/lsdem
fix w all wall/lsdem mesh %s 300 300 0.5 cn 0.5 spin 0 0 0 0 1.0 0 map 200 map/w
thermo_style custom step ke f_w[1] f_w[2] f_w[3] f_w[7] f_w[9]
thermo_modify format float %%.17g
thermo 200
timestep 2e-3
%s
run %d
""" % (drum_band, tail, steps)
    folder = os.path.abspath(name)
    os.makedirs(os.path.join(folder, "map"), exist_ok=True)
    rc, log = run_lmp(d, np=np, cwd=folder)
    return folder, thermo(log)


d1, t1 = drum("drum_np1", 800)
if check(len(t1) == 5 and t1[-1]["f_w[3]"] < 0.0, "drum: the cubes did not land (%s)" % t1[-1:]):
    for np in (2, 4):
        dn, tn = drum("drum_np%d" % np, 800, np=np)
        # (KinEng is LAMMPS's own sum over ranks: its last bit may differ on 4 ranks)
        def wall_columns(rows):
            return [{k: v for k, v in row.items() if k.startswith("f_w")} for row in rows]
        check(wall_columns(tn) == wall_columns(t1),
              "drum: wall force on %d ranks differs from 1 rank" % np)
        for step in (400, 800):
            a = open(os.path.join(d1, "map", "w_%d.vtp" % step)).read()
            b = open(os.path.join(dn, "map", "w_%d.vtp" % step)).read()
            check(a == b, "drum: the map of step %d differs between 1 and %d ranks" % (step, np))
    dr, tr = drum("drum_ref", 800, tail="restart 400 mid.*")
    da, ta = drum("drum_again", 400, read=os.path.join(dr, "mid.400"))
    check(ta[-1] == t1[-1], "drum: the restarted run's wall force differs:\n%s\n%s" % (ta[-1], t1[-1]))
    check(open(os.path.join(d1, "map", "w_800.vtp")).read() ==
          open(os.path.join(da, "map", "w_800.vtp")).read(),
          "drum: the restarted run's map differs from the uninterrupted run's")
    m = cells(os.path.join(d1, "map", "w_800.vtp"))
    check(sum(m.get("impacts", [0])) >= 8, "drum: fewer impacts than cubes: %s" % m.get("impacts"))

# ---- map on a plane -----------------------------------------------------------------
write_data("err.data", (-4, 4, -4, 4, -2, 4), [cube_at(0, 0)])
rc, log = run_lmp(head(lib, "err.data", boundary="f f f") + """
pair_style zero 1.0
pair_coeff * *
fix w all wall/lsdem plane 0 0 0 0 0 1 300 300 0.5 map 10 m
run 1
""", cwd=os.path.abspath("plane_map"), expect_fail=True)
check(rc != 0 and "map is for mesh and terrain walls" in log, "plane map: %s" % log[-800:])
finish()
