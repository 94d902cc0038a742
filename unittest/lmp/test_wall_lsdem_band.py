"""fix wall/lsdem mesh|terrain: walls of any shape as narrow-band level sets (issue 32).

Against independent expectations:
  - a terrain that is a tilted plane gives the plane wall's trajectory of a sliding cube
    (bricks sample the same distance in float: agreement to a relative 1e-5; kept as heights
    on a slope floats hold exactly: 1e-6 over 1,000 steps, the issue's figure);
  - on a 25 deg terrain with mu = 0.2 the cube slides at g (sin - mu cos) = 0.2413 g and
    decelerates on a 3 deg run-out at g (mu cos - sin) = 0.1474 g, within 2 %;
  - a cube dropped on the top face of an STL cube lands as on the plane of that face, also
    at the block's edge with exact yes (the grid path rounds the edge by about h);
  - 1 and 2 ranks give the same bits;
  - a plate half a band spacing thick (exact yes) stops a cube moving within the thin-wall
    time-step bound, and a cube beyond it stops the run naming grain, wall and step;
  - a grain driven deeper than the band is wide stops the run naming it; a file made from
    the other source, a damaged file and a missing one stop with named errors."""
import math
import os

from lsdemtest import run_lmp, thermo, check, near, finish, shape_tool
from contact_decks import Grain, write_data, head, GRAIN1, write_cube_stl
from terrain_decks import HALF, G, H, cube_library, terrain_band, slide

lib = cube_library()


def plane_wall(theta_deg):
    th = math.radians(theta_deg)
    return "plane 0 0 0 %r 0 %r" % (-math.sin(th), math.cos(th))


# ---- a tilted-plane terrain against the plane wall: 1,000 steps -------------------------
T30 = math.tan(math.radians(30.0))
band30 = terrain_band("tilt30", lambda x, y: x * T30)
ref = slide("plane30", plane_wall(30.0), 30.0, 0.3, 0.5, 2.0, every=50)
ter = slide("terrain30", "terrain " + band30, 30.0, 0.3, 0.5, 2.0, every=50)
if check(len(ref) == len(ter) and len(ref) > 10, "tilted plane: %d and %d thermo rows"
         % (len(ref), len(ter))):
    travel = abs(ref[-1]["v_px"] - ref[0]["v_px"])
    check(travel > 0.01, "tilted plane: the cube did not slide (%g)" % travel)
    worst = max(abs(a[k] - b[k]) for a, b in zip(ref, ter) for k in ("v_px", "v_pz"))
    check(worst <= 1e-5 * travel, "tilted plane: terrain and plane trajectories differ by %.3g "
          "(travel %.3g, relative %.3g > 1e-5)" % (worst, travel, worst / travel))
    near(ter[-1]["f_w[3]"], ref[-1]["f_w[3]"], rtol=1e-3, msg="tilted plane: wall force z")
    print("tilted plane: trajectories agree to %.3g of the travel %.4g" % (worst / travel, travel))

# A terrain kept as heights is the exact distance to its triangles: on a slope of 1/2,
# whose heights (multiples of 1/8) floats hold exactly, it is the plane itself, and the
# trajectory is the plane wall's to 1e-6 of the travel over 1,000 steps. (At 30 deg above,
# both storages round the heights or samples to floats, ~1e-7 of a length, which the
# contact's small overlaps turn into 3e-6 of the travel.)
TH = math.degrees(math.atan(0.5))
band_half = terrain_band("tilt_half", lambda x, y: 0.5 * x, width=0.5, heights=True)
ref_h = slide("plane_half", plane_wall(TH), TH, 0.3, 0.5, 2.0, every=50)
ter_h = slide("heights_half", "terrain " + band_half, TH, 0.3, 0.5, 2.0, every=50,
              keys="exact yes")
if check(len(ref_h) == len(ter_h) and len(ref_h) > 10, "slope 1/2: %d and %d thermo rows"
         % (len(ref_h), len(ter_h))):
    travel = abs(ref_h[-1]["v_px"] - ref_h[0]["v_px"])
    check(travel > 0.01, "slope 1/2: the cube did not slide (%g)" % travel)
    worst = max(abs(a[k] - b[k]) for a, b in zip(ref_h, ter_h) for k in ("v_px", "v_pz"))
    check(worst <= 1e-6 * travel, "slope 1/2: terrain kept as heights and plane differ by "
          "%.3g (relative %.3g > 1e-6)" % (worst, worst / travel))
    print("slope 1/2, terrain kept as heights: trajectories agree to %.3g of the travel %.4g"
          % (worst / travel, travel))

# ---- 25 deg slope, mu = 0.2, running out onto 3 deg ------------------------------------
T25, T3 = math.tan(math.radians(25.0)), math.tan(math.radians(3.0))
band_run = terrain_band("runout", lambda x, y: x * (T25 if x > 0 else T3), x0=-10.0, x1=6.0)
rows = slide("runout", "terrain " + band_run, 25.0, 0.2, 11.0, 4.0, every=200,
             box=(-14, 10, -5, 5, -6, 8))


def speed(r):
    return math.hypot(r["v_vx"], r["v_vz"])


def acceleration(rows, t0, t1):
    """Rate of change of the speed between times t0 and t1."""
    a = min(rows, key=lambda r: abs(r["Time"] - t0))
    b = min(rows, key=lambda r: abs(r["Time"] - t1))
    return (speed(b) - speed(a)) / (b["Time"] - a["Time"])


if check(len(rows) > 20, "run-out: no thermo output"):
    s25, c25 = math.sin(math.radians(25.0)), math.cos(math.radians(25.0))
    s3, c3 = math.sin(math.radians(3.0)), math.cos(math.radians(3.0))
    down = G * (s25 - 0.2 * c25)              # 0.2413 g
    out = G * (0.2 * c3 - s3)                 # 0.1474 g: deceleration
    s0 = 4.0 / c25                            # along the slope from the start to the kink
    t_front, t_back = (math.sqrt(2 * (s0 + d) / down) for d in (-HALF, HALF))
    t_stop = math.sqrt(2 * s0 / down) + down * math.sqrt(2 * s0 / down) / out
    window_out = (t_back + 0.5, min(t_stop - 0.5, 10.5))
    near(acceleration(rows, 1.0, t_front - 0.5), down, rtol=0.02,
         msg="run-out: acceleration down the 25 deg slope")
    near(-acceleration(rows, *window_out), out, rtol=0.02,
         msg="run-out: deceleration on the 3 deg run-out")
    print("run-out: slope %.4f g (expected %.4f), run-out %.4f g (expected %.4f)" % (
        acceleration(rows, 1.0, t_front - 0.5), down, -acceleration(rows, *window_out), out))

# ---- 1 and 2 ranks --------------------------------------------------------------------
ter2 = slide("terrain30_np2", "terrain " + band30, 30.0, 0.3, 0.5, 2.0, np=2, every=50)
check(len(ter2) == len(ter) and all(a[k] == b[k] for a, b in zip(ter, ter2) for k in a),
      "terrain: 2 ranks differ from 1 rank")

# ---- an STL cube: its top face is the plane z = 0 --------------------------------------
stl = write_cube_stl("block.stl", (-3.0, -3.0, -2.0), (3.0, 3.0, 0.0))
block = os.path.abspath("block.band")
shape_tool("wall", stl, block, "--spacing", H, "--width", 2 * H)
flat = slide("plane0", "plane 0 0 0 0 0 1", 0.0, 0.3, 0.3, 0.0, every=50)
mesh = slide("mesh0", "mesh " + block, 0.0, 0.3, 0.3, 0.0, every=50)
if check(len(flat) == len(mesh) and len(flat) > 3, "STL cube: thermo rows differ"):
    worst = max(abs(a["v_pz"] - b["v_pz"]) for a, b in zip(flat, mesh))
    check(worst < 1e-7, "STL cube: the cube rests %.3g off the plane's result" % worst)
    near(mesh[-1]["f_w[3]"], -G, rtol=1e-3, msg="STL cube: it carries the weight")

# ---- exact mode: a cube at the block's edge (its side 0.01 from the edge, within h = 0.1
# of it): trilinear interpolation rounds the edge by about h, the exact mode does not --
# the cube rests as on the plane
EDGE_X = 3.0 - HALF - 0.01
flat_edge = slide("plane_edge", "plane 0 0 0 0 0 1", 0.0, 0.3, 0.3, EDGE_X, every=50)
grid_edge = slide("mesh_edge", "mesh " + block, 0.0, 0.3, 0.3, EDGE_X, every=50)
exact_edge = slide("exact_edge", "mesh " + block, 0.0, 0.3, 0.3, EDGE_X, every=50,
                   keys="exact yes")
if check(len(flat_edge) == len(exact_edge) == len(grid_edge) > 3, "edge: thermo rows differ"):
    worst_exact = max(abs(a["v_pz"] - b["v_pz"]) + abs(a["v_px"] - b["v_px"])
                      for a, b in zip(flat_edge, exact_edge))
    worst_grid = max(abs(a["v_pz"] - b["v_pz"]) + abs(a["v_px"] - b["v_px"])
                     for a, b in zip(flat_edge, grid_edge))
    check(worst_exact < 1e-7, "edge: exact mode %.3g off the plane's result" % worst_exact)
    print("edge of the block: grid path %.3g off the plane's rest, exact %.3g" % (worst_grid,
                                                                               worst_exact))

# ---- impulse mode (report 4.4.1): a terrain takes part like a plane -------------------
# A block on flat terrain under gravity tilted by theta: it sticks at 20 deg (mu = 0.5) at
# 16 times the step, slides at 35 deg with g (sin - mu cos) within 2 %, as on a plane.
from impulse_decks import header as impulse_header, library as impulse_library

BLOCK = impulse_library("block.lslib", "box", 0.5, 0.5, 0.25, nodes=120, spacing=0.05)
flat_imp = terrain_band("flat_impulse", lambda x, y: 0.0, x0=-3.0, x1=3.0, y0=-3.0, y1=3.0)


def impulse_incline(name, wall, theta_deg, steps, dt):
    th = math.radians(theta_deg)
    with open(name + ".data", "w") as f:
        f.write("grain\n\n1 atoms\n1 atom types\n\n-3 3 xlo xhi\n-3 3 ylo yhi\n-1 4 zlo zhi\n\n"
                "Atoms # lsdem\n\n1 1 1 1.0 0 0 0.25 1 0 0 0\n")
    deck = (impulse_header(BLOCK, name + ".data")
            + "fix floor all wall/lsdem %s 1.0e4 0 0.5\n" % wall
            + "fix grav all gravity 9.81 vector %r 0 %r\n" % (math.sin(th), -math.cos(th))
            + "fix imp all impulse/lsdem 0.5 0.0\ntimestep %r\n" % dt
            + "variable x equal x[1]\nvariable vx equal vx[1]\n"
            + "thermo_style custom step time v_x v_vx\nthermo_modify format float %.15g\n"
            + "thermo 50\nrun %d\n" % steps)
    rc, log = run_lmp(deck, cwd=os.path.abspath(name))
    return thermo(log)


# impulse mode does not test a wall's twoway points: refused, not ignored
with open("imp_twoway.data", "w") as f:
    f.write("grain\n\n1 atoms\n1 atom types\n\n-3 3 xlo xhi\n-3 3 ylo yhi\n-1 4 zlo zhi\n\n"
            "Atoms # lsdem\n\n1 1 1 1.0 0 0 0.25 1 0 0 0\n")
rc, log = run_lmp(impulse_header(BLOCK, "imp_twoway.data")
                  + "fix floor all wall/lsdem mesh %s 1.0e4 0 0.5 twoway yes\n" % block
                  + "fix imp all impulse/lsdem 0.5 0.0\ntimestep 1e-3\nrun 1\n",
                  cwd=os.path.abspath("impulse_twoway"), expect_fail=True)
check(rc != 0 and "has twoway yes" in log and "impulse mode does not test" in log,
      "impulse with twoway: expected a named error:\n%s" % log[-800:])

for wall, tag in (("plane 0 0 0 0 0 1", "plane"), ("terrain " + flat_imp, "terrain")):
    stick = impulse_incline("impulse_stick_" + tag, wall, 20.0, 300, 16e-3)
    if check(len(stick) > 3, "impulse %s: no output" % tag):
        creep = stick[-1]["v_x"] - stick[1]["v_x"]
        check(abs(creep) < 1e-9, "impulse %s: the block creeps %g at 20 deg" % (tag, creep))
    slide_rows = impulse_incline("impulse_slide_" + tag, wall, 35.0, 1500, 1e-3)
    if check(len(slide_rows) > 10, "impulse %s slide: no output" % tag):
        r1 = next(r for r in slide_rows if r["Step"] == 500)
        r2 = slide_rows[-1]
        a = (r2["v_vx"] - r1["v_vx"]) / (r2["Time"] - r1["Time"])
        th = math.radians(35.0)
        near(a, 9.81 * (math.sin(th) - 0.5 * math.cos(th)), rtol=0.02,
             msg="impulse %s: acceleration at 35 deg" % tag)

# ---- errors -------------------------------------------------------------------------


def deck_with(wall, v=(0.0, 0.0, 0.0), z=HALF + 1e-4, steps=10, law="100 100 0.3"):
    write_data("err.data", (-12, 12, -5, 5, -12, 12), [Grain((0.0, 0.0, z), v=v)])
    return head(lib, "err.data", boundary="f f f") + """
pair_style zero 2.0
pair_coeff * *
fix 1 all nve/lsdem
fix w all wall/lsdem %s %s
timestep 5e-4
run %d
""" % (wall, law, steps)


def refuses(name, deck, *words):
    rc, log = run_lmp(deck, cwd=os.path.abspath(name), expect_fail=True)
    ok = rc != 0 and all(w in log for w in words)
    check(ok, "%s: exit %d, expected an error naming %s:\n%s" % (name, rc, words, log[-1500:]))


refuses("wrong_kind", deck_with("terrain " + block), "made from a mesh", "mesh " + block)
refuses("missing", deck_with("terrain nothere.band"), "nothere.band", "cannot open")
# a band no wider than the node skin plus 5 % of the cube's bounding radius 0.866
refuses("thin_band", deck_with("terrain " + band_half, law="100 100 0.3 nodelist 0.47"),
        "no wider than the node skin 0.47 plus the largest expected overlap 0.0433",
        "--width above 0.513")
refuses("heights_map", deck_with("terrain " + band_half, law="100 100 0.3 map 10 hmap"),
        "kept as heights",
        "without --heights")
refuses("heights_as_mesh", deck_with("mesh " + band_half), "made from a height map",
        "terrain " + band_half)
damaged = os.path.abspath("damaged.band")
data = bytearray(open(band30, "rb").read())
data[len(data) // 2] ^= 0x40
open(damaged, "wb").write(bytes(data))
refuses("damaged", deck_with("terrain " + damaged), "damaged.band", "checksum")
# a soft wall and a fast cube: its nodes go deeper than the band is wide (0.2), while its
# centre stays in front of the surface
flat_band = terrain_band("flat", lambda x, y: 0.0)
refuses("tunnel", deck_with("terrain " + flat_band, v=(0.0, 0.0, -30.0), z=HALF + 0.01,
                            steps=400, law="100 0 0.0"),
        "grain 1", "tunnelled", "--width")

# a plate half a band spacing thick (0.05 at h = 0.1; exact yes holds it): a cube dropped
# on it within the thin-wall bound ((|v| + |omega| R) dt below the plate's 0.05) bounces
# off without entering it deeper than its static overlap; beyond the bound (0.075 a step)
# the run stops naming the grain, the wall, the step and the plate
plate = os.path.abspath("plate.band")
shape_tool("wall", write_cube_stl("plate.stl", (-3.0, -3.0, -0.05), (3.0, 3.0, 0.0)), plate,
           "--spacing", 0.1, "--width", 0.2)
write_data("plate.data", (-12, 12, -5, 5, -12, 12), [Grain((0.0, 0.0, HALF + 0.01), v=(0, 0, -2.0))])
rc, log = run_lmp(head(lib, "plate.data", boundary="f f f") + """
pair_style zero 2.0
pair_coeff * *
fix 1 all nve/lsdem
fix w all wall/lsdem mesh %s 5000 0 0.0 exact yes
%s
thermo_style custom step v_pz v_vz
thermo_modify format float %%.10g
thermo 10
timestep 5e-4
run 1000
""" % (plate, GRAIN1), cwd=os.path.abspath("plate_ok"))
rows = thermo(log)
if check(len(rows) > 5 and "thinnest ridge 0.05 across" in log, "thin plate: no run or no "
         "thinnest ridge in the log:\n%s" % log[-1500:]):
    lowest = min(r["v_pz"] for r in rows)
    check(lowest > HALF - 0.01 and rows[-1]["v_vz"] > 0.0, "thin plate: the cube went %.4g "
          "deep into the 0.05 plate (centre lowest %.6g), or did not bounce (vz %.3g)"
          % (HALF - lowest, lowest, rows[-1]["v_vz"]))
refuses("thin_fast", deck_with("mesh " + plate, v=(0.0, 0.0, -150.0), z=HALF + 0.01, steps=20,
                               law="5000 0 0.0 exact yes"),
        "grain 1 touches the wall at step", "thinnest ridge, 0.05 across", "a time step below")

# beyond its border the terrain continues flat (lsdem-shape terrain pads the raster with
# the edge heights): cubes resting 0.5 and 1.5 beyond the edge of the flat terrain rest as
# on the plane z = 0 (before the padding the border was a cliff edge that threw them up)
for beyond in (0.5, 1.5):
    tag = "beyond%g" % beyond
    on_plane = slide(tag + "_plane", "plane 0 0 0 0 0 1", 0.0, 0.3, 0.3, 6.0 + beyond, every=50)
    on_band = slide(tag + "_terrain", "terrain " + flat_band, 0.0, 0.3, 0.3, 6.0 + beyond, every=50)
    if check(len(on_plane) == len(on_band) > 3, "%s: thermo rows differ" % tag):
        worst = max(abs(a["v_pz"] - b["v_pz"]) + abs(a["v_px"] - b["v_px"])
                    for a, b in zip(on_plane, on_band))
        check(worst < 1e-7, "%s: the cube beyond the terrain's edge is %.3g off the plane's "
              "rest" % (tag, worst))

# an analytic sphere touches the wall by its centre's value: a band no wider than the
# sphere's radius is refused at the start (it would push every sphere by r - width)
ball = os.path.abspath("ball.lslib")
shape_tool("analytic", ball, "sphere", 0.5, "--nodes", 20, "--analytic")
write_data("ball.data", (-12, 12, -5, 5, -12, 12), [Grain((0.0, 0.0, 3.0))])
rc, log = run_lmp(head(ball, "ball.data", boundary="f f f") + """
pair_style zero 2.0
pair_coeff * *
fix 1 all nve/lsdem
fix w all wall/lsdem terrain %s 100 100 0.3
run 1
""" % flat_band, cwd=os.path.abspath("narrow_for_spheres"), expect_fail=True)
check(rc != 0 and "no wider than the library's sphere 1 of radius 0.5" in log,
      "a band narrower than a sphere was not refused:\n%s" % log[-1200:])

finish()
