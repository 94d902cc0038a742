"""fix wall/lsdem twoway: a mesh wall's sharp edges tested against the grains' level sets
(issue 32).

Against independent expectations:
  - a cube (flat face down) dropped on two knife-edge ridges (two triangular prisms whose
    sharp top edges run along y at height 0) rests at 0.5 - m g / (kn N): N the ridges'
    points under its face (the edges' vertices and samples at most h apart), each a spring
    kn, within 0.5 % of that static overlap (mu = 0); without twoway its nodes miss the edges
    and it sinks 100 times deeper;
  - on the flat top face of an STL block twoway changes nothing (no sharp edge there: the
    same bits as without);
  - the cube sliding along the ridges with friction (history per wall point) gives the same
    bits on 1 and 2 ranks (split across its path: it moves from rank 0 to rank 1 while
    sliding, its points' history with it) and
    with fix wall/lsdem/omp on 2 threads;
  - under gravity tilted along the ridges (0.1 < mu) the points' shear springs hold the cube
    (it moves < 1e-3 from t = 0.5 to 2; without their history it would creep 7.9e-3),
    and a run restarted mid-way ends with the uninterrupted run's bits;
  - twoway on a terrain kept as heights, or on a plane wall, stops with a named error."""
import math
import os

from lsdemtest import run_lmp, thermo, check, near, finish, shape_tool
from contact_decks import (Grain, box_library, write_data, head, THERMO_FULL, GRAIN1,
                           write_cube_stl, write_ridges_stl)

HALF = 0.5           # the cube's half-side; density 1
H = 0.1              # band spacing (and the points' spacing along an edge)
KN = 100.0
RIDGE_X = (-0.32, 0.32)
RIDGE_Y = 0.4        # ridges from y = -0.4 to 0.4: wholly under the cube's face
lib = box_library("cube.lslib", HALF, 0.05, 600)


ridges = os.path.abspath("ridges.band")
shape_tool("wall", write_ridges_stl("ridges.stl", RIDGE_X, RIDGE_Y), ridges, "--spacing", H,
           "--width", 2 * H)
stl = write_cube_stl("block.stl", (-3.0, -3.0, -2.0), (3.0, 3.0, 0.0))
block = os.path.abspath("block.band")
shape_tool("wall", stl, block, "--spacing", H, "--width", 2 * H)


def drop(name, wall, keys="", np=1, steps=2000, every=100, v=(0.0, 0.0, 0.0), y0=0.0,
         read=None, tail="", procs="", args=None, gy=0.0, mu=0.3):
    """The cube above `wall` (fix wall/lsdem geometry) under gravity 1; thermo rows."""
    folder = os.path.abspath(name)
    if read:
        top = "read_restart %s\n" % read
    else:
        write_data(name + ".data", (-3, 3, -3, 3, -2, 3), [Grain((0.0, y0, HALF + 1e-4), v=v)])
        top = head(lib, name + ".data", boundary="f f f", extra=procs)
    deck = top + """
pair_style zero 2.0
pair_coeff * *
neighbor 0.02 bin
fix grav all gravity 1.0 vector 0 %(gy)r -1
fix 1 all nve/lsdem
fix w all wall/lsdem %(wall)s %(kn)r %(kn)r %(mu)r cn 1.0 %(keys)s
%(grain1)svariable m equal mass[1]
compute proc all property/atom proc
compute owner all reduce max c_proc
thermo_style custom step time v_px v_py v_pz v_vx v_vy v_vz v_m f_w[1] f_w[2] f_w[3] c_owner
%(thermo)s
thermo %(every)d
timestep 5e-4
%(tail)s
run %(steps)d
""" % dict(wall=wall, kn=KN, keys=keys, grain1=GRAIN1, thermo=THERMO_FULL, every=every,
           steps=steps, tail=tail, gy=gy, mu=mu)
    rc, log = run_lmp(deck, np=np, cwd=folder, args=args)
    if args:
        check("style = wall/lsdem/omp" in log, "%s: the threaded wall did not run" % name)
    return thermo(log)


# ---- a cube on two knife edges -----------------------------------------------------------
# the points under the face: per ridge its two vertices and the samples between them, the
# edge (length 2 RIDGE_Y) cut into ceil(length / h) pieces
pieces = math.ceil((RIDGE_Y - (-RIDGE_Y)) / H)
N = 2 * (pieces + 1)
# without friction: the normal law alone (with mu = 0.3 the cube rests 1.4 % less deep, the
# shear springs set while it lands taking part; not analysed further)
two = drop("ridges_twoway", "mesh " + ridges, "twoway yes", mu=0.0)
one = drop("ridges_oneway", "mesh " + ridges, mu=0.0)
if check(len(two) > 10 and len(one) > 10, "ridges: no thermo output"):
    m = two[-1]["v_m"]
    overlap = m * 1.0 / (KN * N)            # the static overlap m g / (kn N)
    sink_two = HALF - two[-1]["v_pz"]
    sink_one = HALF - one[-1]["v_pz"]
    near(sink_two, overlap, rtol=0.005, msg="ridges, twoway: the static overlap")
    near(-two[-1]["f_w[3]"], m, rtol=1e-3, msg="ridges, twoway: the wall carries the weight")
    check(abs(two[-1]["v_vz"]) < 1e-4, "ridges, twoway: not at rest (vz %g)" % two[-1]["v_vz"])
    check(sink_one > 5 * overlap, "ridges, one way: sinks %.3g, not past the edges (static "
          "overlap %.3g)" % (sink_one, overlap))
    print("ridges: %d points under the face, rest %.6g below the edges with twoway "
          "(expected m g / (kn N) = %.6g), %.4g without" % (N, sink_two, overlap, sink_one))

# ---- a flat face: nothing changes ------------------------------------------------------------
flat_two = drop("flat_twoway", "mesh " + block, "twoway yes", steps=1000)
flat_one = drop("flat_oneway", "mesh " + block, steps=1000)
check(len(flat_two) == len(flat_one) > 5 and
      all(a[k] == b[k] for a, b in zip(flat_two, flat_one) for k in a),
      "flat face: twoway changes the cube's rest on the block's top face")
if flat_two:
    print("flat face: rest %.6g below the face with and without twoway"
          % (HALF - flat_two[-1]["v_pz"]))

# ---- friction history: ranks and restart -----------------------------------------------------
# the cube slides along the ridges from y = -0.1 at 0.3 and stops by friction (mu g = 0.3,
# after 0.15 in y); 2 ranks split the box at y = 0, which it crosses
slide_keys = "twoway yes"
ref = drop("slide_np1", "mesh " + ridges, slide_keys, steps=1200, v=(0.0, 0.3, 0.0), y0=-0.1)
ranks = drop("slide_np2", "mesh " + ridges, slide_keys, np=2, steps=1200, v=(0.0, 0.3, 0.0),
             y0=-0.1, procs="processors 1 2 1")
if check(len(ref) > 10, "slide: no thermo output"):
    travel = ref[-1]["v_py"] - (-0.1)
    check(0.05 < travel < 0.3 and abs(ref[-1]["v_vy"]) < 0.3,
          "slide: the cube travelled %g (friction did not act?)" % travel)
    check(len(ranks) == len(ref) and all(a[k] == b[k] for a, b in zip(ref, ranks)
                                         for k in a if k != "c_owner"),
          "slide: 2 ranks differ from 1 rank")
    check(ranks and ranks[0]["c_owner"] == 0 and ranks[-1]["c_owner"] == 1,
          "slide: the cube did not move from rank 0 to rank 1")
    threads = drop("slide_omp2", "mesh " + ridges, slide_keys, steps=1200, v=(0.0, 0.3, 0.0),
                   y0=-0.1, tail="info fixes out log", args=["-sf", "omp", "-pk", "omp", 2])
    check(len(threads) == len(ref) and all(a[k] == b[k] for a, b in zip(ref, threads) for k in a),
          "slide: fix wall/lsdem/omp on 2 threads differs from the plain style")
    print("slide: travelled %.4g along the ridges; 2 ranks and 2 threads give the same bits"
          % travel)

# ---- static friction: the points' shear springs hold the cube ---------------------------------
# gravity tilted along the ridges by g_y / g_z = 0.1 < mu, tangential damping ct: the cube
# lands (slipping a little while the normal forces build up) and sticks, held by the
# points' springs, about which it sways (by ~1e-4, the springs' stretch m g_y / (ks N) is
# 5.5e-5): from t = 0.5 to 2 it moves by less than 1e-3. Without the points' shear history
# each step's spring would start from zero and the cube would creep at
# m g_y / (N (ks dt + ct)) = 5.3e-3 per time, 7.9e-3 in that time. A run restarted mid-way
# must end with the uninterrupted run's bits.
GY = 0.1
STICK = "twoway yes ct 1.0"
stick = drop("stick", "mesh " + ridges, STICK, steps=4000, gy=GY, tail="restart 1000 mid.*")
if check(len(stick) > 10, "stick: no thermo output"):
    half_way = next(r for r in stick if r["Step"] == 1000)
    creep = stick[-1]["v_py"] - half_way["v_py"]
    check(abs(creep) < 1e-3, "stick: the cube creeps %.3g along the ridges from t = 0.5 to 2"
          % creep)
    # (Time restarts from 0 after read_restart: compared are the step and the state)
    again = drop("stick_restart", "mesh " + ridges, STICK, steps=3000, gy=GY,
                 read=os.path.join(os.path.abspath("stick"), "mid.1000"))
    check(len(again) > 2 and again[-1]["Step"] == stick[-1]["Step"] and
          all(again[-1][k] == stick[-1][k] for k in again[-1] if k != "Time"),
          "stick: the run restarted at step 1000 ends off the uninterrupted run")
    print("stick: moved %.3g along the ridges from t = 0.5 to 2 (limit 1e-3); the restart "
          "gives the same bits" % creep)

# ---- refused -----------------------------------------------------------------------------


def refuses(name, wall, *words):
    write_data(name + ".data", (-3, 3, -3, 3, -2, 3), [Grain((0.0, 0.0, HALF + 1e-4))])
    deck = head(lib, name + ".data", boundary="f f f") + """
pair_style zero 2.0
pair_coeff * *
fix 1 all nve/lsdem
fix w all wall/lsdem %s 100 100 0.3 twoway yes
run 1
""" % wall
    rc, log = run_lmp(deck, cwd=os.path.abspath(name), expect_fail=True)
    check(rc != 0 and all(w in log for w in words),
          "%s: exit %d, expected an error naming %s:\n%s" % (name, rc, words, log[-1200:]))


with open("flat.asc", "w") as f:
    f.write("ncols 5\nnrows 5\nxllcenter -2\nyllcenter -2\ncellsize 1\nNODATA_value -9999\n"
            + "0 0 0 0 0\n" * 5)
heights = os.path.abspath("flat_heights.band")
shape_tool("terrain", "flat.asc", heights, "--width", 1.0, "--heights")
refuses("heights", "terrain " + heights, "twoway needs the terrain's triangles",
        "kept as heights")
refuses("plane", "plane 0 0 0 0 0 1", "keyword twoway is for mesh and terrain walls")

finish()
