"""terrain_decks -- a level-set cube sliding on a terrain wall (fix wall/lsdem terrain) in
penalty mode: the height map (ESRI ASCII), its band file and the sliding deck, shared by
test_wall_lsdem_band and test_terrain_slide."""
import math
import os

from lsdemtest import run_lmp, thermo, shape_tool
from contact_decks import Grain, box_library, write_data, head, quat_axis_angle, THERMO_FULL, GRAIN1

HALF = 0.5           # the sliding cube's half-side; density 1: mass 1
G = 1.0
H = 0.1              # band spacing


def cube_library():
    """The cube's shape library in the current folder (made once)."""
    return box_library("cube.lslib", HALF, 0.05, 600)


def write_asc(path, x0, y0, cell, nx, ny, height):
    """An ESRI ASCII grid of height(x, y) at cell corners (xllcenter: samples at x0 + i cell)."""
    rows = []
    for j in reversed(range(ny)):          # north (largest y) first
        y = y0 + j * cell
        rows.append(" ".join("%.17g" % height(x0 + i * cell, y) for i in range(nx)))
    with open(path, "w") as f:
        f.write("ncols %d\nnrows %d\nxllcenter %r\nyllcenter %r\ncellsize %r\n"
                "NODATA_value -9999\n" % (nx, ny, x0, y0, cell))
        f.write("\n".join(rows) + "\n")
    return path


def terrain_band(name, height, x0=-6.0, x1=6.0, y0=-3.0, y1=3.0, cell=0.25, width=2 * H,
                 heights=False):
    """The terrain's band file: bricks at spacing H, or kept as heights (--heights: the
    raster's own spacing, exact distances)."""
    asc = write_asc(name + ".asc", x0, y0, cell, int(round((x1 - x0) / cell)) + 1,
                    int(round((y1 - y0) / cell)) + 1, height)
    out = os.path.abspath(name + ".band")
    store = ("--heights",) if heights else ("--spacing", H)
    shape_tool("terrain", asc, out, "--width", width, *store)
    return out


def slide(name, wall, theta_deg, mu, t_end, x_start, np=1, dt=5e-4, every=100, box=None,
          keys="", z_start=None):
    """The cube resting on a slope tilted by theta about y (surface z = x tan theta, downhill
    -x, or through (x_start, z_start) when given) at x_start, under gravity, against `wall`
    (a fix wall/lsdem geometry); thermo rows."""
    lib = cube_library()
    th = math.radians(theta_deg)
    n = (-math.sin(th), 0.0, math.cos(th))
    q = quat_axis_angle((0, 1, 0), -th)
    base = (x_start, 0.0, x_start * math.tan(th) if z_start is None else z_start)
    x = tuple(b + (HALF + 1e-4) * c for b, c in zip(base, n))
    write_data(name + ".data", box or (-12, 12, -5, 5, -12, 12), [Grain(x, q=q)])
    deck = head(lib, name + ".data", boundary="f f f") + """
pair_style zero 2.0
pair_coeff * *
fix grav all gravity %(g)r vector 0 0 -1
fix 1 all nve/lsdem
fix w all wall/lsdem %(wall)s 100 100 %(mu)r cn 1.0 %(keys)s
%(grain1)sthermo_style custom step time v_px v_py v_pz v_vx v_vz f_w[1] f_w[2] f_w[3]
%(thermo)s
thermo %(every)d
timestep %(dt)r
run %(steps)d
""" % dict(grain1=GRAIN1, keys=keys, g=G, wall=wall, mu=mu, thermo=THERMO_FULL, dt=dt, every=every,
           steps=int(round(t_end / dt)))
    rc, log = run_lmp(deck, np=np, cwd=os.path.abspath(name))
    return thermo(log)
