"""fix wall/lsdem map: per-triangle force maps of a mesh wall (issue 32 item 4).

Cubes on the top face of an STL block (z = 0), against independent expectations:
  - at rest, the map's normal forces add up to the weights, on the top face's triangles
    only, and the pressure is the normal force over the triangle's area;
  - one impact per cube dropped on the block;
  - a cube sliding to rest from v0 with friction mu books a friction work
    sum fn |v_t| dt = m v0^2 / (2 mu) (the work of friction) within 2 %;
  - the map files are the same bits on 1 and 2 ranks, and a run restarted mid-way writes
    the uninterrupted run's map;
  - map on a plane wall is refused."""
import os
import re

from lsdemtest import run_lmp, check, near, finish, shape_tool
from contact_decks import Grain, box_library, write_data, head, THERMO_FULL, write_cube_stl

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
