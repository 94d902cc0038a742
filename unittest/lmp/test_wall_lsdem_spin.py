"""fix wall/lsdem spin: walls turning at a prescribed angular velocity (issue 32).

  - a turntable (a plane spinning about its normal): a cube at rest at radius 1 with
    mu g > omega^2 r is brought to the table's angular velocity (within 1 %); a cube
    moving with the table from the start stays at its radius (within 0.2 %);
  - a spinning flat terrain (a band wall) carries the cube as the spinning plane does;
  - a spinning cylindrical drum (axis horizontal) lifts a cube from the bottom on the
    side its bottom moves to;
  - a run restarted mid-way gives the uninterrupted run's bits, and 1 and 2 ranks agree;
  - spin by equal-style variables: a rate that reverses after 1500 steps turns a plane by
    the rate's integral and back to the start (1e-12), a constant variable gives the
    number's bits, and a direction change stops the run naming the step;
  - a platen cannot also spin, omega = 0 is refused."""
import math
import os

from lsdemtest import run_lmp, thermo, check, near, finish, shape_tool
from contact_decks import Grain, box_library, write_data, head, THERMO_FULL, GRAIN1

HALF = 0.25
lib = box_library("cube.lslib", HALF, 0.025, 300)
W = 0.5       # table angular velocity: omega^2 r = 0.25 < mu g = 0.5
DT = 1e-3


def table(name, wall, steps=6000, np=1, tail="", every=500, read=None, moving=False):
    """The cube on a table turning at W about z, at radius 1: at rest, or (moving) with
    the table's velocity and spin."""
    if read:
        top = "read_restart %s\n" % read
    else:
        v, w = ((0.0, W, 0.0), (0.0, 0.0, W)) if moving else ((0.0,) * 3, (0.0,) * 3)
        write_data(name + ".data", (-3, 3, -3, 3, -1, 3),
                   [Grain((1.0, 0.0, HALF + 1e-4), v=v, w=w)])
        top = head(lib, name + ".data", boundary="f f f")
    d = top + """
pair_style zero 1.0
pair_coeff * *
fix grav all gravity 1.0 vector 0 0 -1
fix 1 all nve/lsdem
fix w all wall/lsdem %(wall)s 300 300 0.5 cn 0.5 spin 0 0 0 0 0 %(w)r
variable r equal sqrt(x[1]^2+y[1]^2)
variable om equal (x[1]*vy[1]-y[1]*vx[1])/(x[1]^2+y[1]^2)
%(grain1)sthermo_style custom step v_px v_py v_pz v_vx v_vy v_r v_om f_w[11] f_w[12] f_w[13]
%(thermo)s
thermo %(every)d
timestep %(dt)r
%(tail)s
run %(steps)d
""" % dict(grain1=GRAIN1, wall=wall, w=W, thermo=THERMO_FULL, every=every, dt=DT, tail=tail, steps=steps)
    rc, log = run_lmp(d, np=np, cwd=os.path.abspath(name))
    return thermo(log)


rows = table("turntable", "plane 0 0 0 0 0 1")
if check(len(rows) > 5, "turntable: no thermo output"):
    last = rows[-1]
    near(last["v_om"], W, rtol=0.01, msg="turntable: the cube turns with the table")
    near(last["f_w[13]"], W, rtol=0.0, msg="turntable: output 13 is the spin")
    check(abs(math.atan2(last["v_py"], last["v_px"])) > 0.5,
          "turntable: the cube did not go round (angle %g)"
          % math.atan2(last["v_py"], last["v_px"]))

carried = table("carried", "plane 0 0 0 0 0 1", moving=True)
if check(len(carried) > 5, "carried: no thermo output"):
    near(max(abs(r["v_r"] - 1.0) for r in carried), 0.0, atol=2e-3,
         msg="carried: a cube moving with the table stays at its radius")
    near(carried[-1]["v_om"], W, rtol=1e-3, msg="carried: ... at the table's rate")

# ---- the same with a flat terrain band as the table -----------------------------------
with open("flat.asc", "w") as f:
    f.write("ncols 25\nnrows 25\nxllcenter -3\nyllcenter -3\ncellsize 0.25\n")
    for j in range(25):
        f.write(" ".join(["0"] * 25) + "\n")
shape_tool("terrain", "flat.asc", "flat.band", "--spacing", 0.05, "--width", 0.1)
band_rows = table("terrain_table", "terrain " + os.path.abspath("flat.band"))
if check(len(band_rows) == len(rows), "terrain table: thermo rows differ"):
    worst = max(abs(a[k] - b[k]) for a, b in zip(rows, band_rows) for k in ("v_px", "v_py"))
    check(worst < 1e-5, "terrain table: %.3g off the spinning plane's trajectory" % worst)

# ---- restart mid-run, and 2 ranks ----------------------------------------------------
ref = table("ref", "plane 0 0 0 0 0 1", steps=1000, tail="restart 500 mid.*", every=500)
if check(os.path.exists("ref/mid.500") and len(ref) == 3, "restart reference failed"):
    again = table("again", "plane 0 0 0 0 0 1", steps=500, read=os.path.abspath("ref/mid.500"))
    if check(len(again) == 2, "restart: thermo output missing"):
        check(all(again[-1][k] == ref[-1][k] for k in ref[-1]),
              "restart: the resumed spin differs from the uninterrupted run:\n%s\n%s"
              % (ref[-1], again[-1]))
two = table("np2", "plane 0 0 0 0 0 1", steps=1000, np=2)
check(len(two) == len(ref) and all(a[k] == b[k] for a, b in zip(ref, two) for k in a),
      "2 ranks differ from 1 rank")

# ---- a drum: horizontal cylinder spinning about y lifts a cube ------------------------
# the cube's bottom edges (x = +-HALF) just inside the drum of radius 1
write_data("drum.data", (-2, 2, -2, 2, -2, 2),
           [Grain((0.0, 0.0, -(math.sqrt(1.0 - HALF ** 2) - HALF) + 1e-3))])
d = head(lib, "drum.data", boundary="f f f") + """
pair_style zero 1.0
pair_coeff * *
fix grav all gravity 1.0 vector 0 0 -1
fix 1 all nve/lsdem
fix w all wall/lsdem cylinder 0 0 1.0 300 300 0.8 cn 0.5 axis y spin 0 0 0 0 0.3 0
variable ang equal atan2(x[1],-z[1])
%sthermo_style custom step v_px v_pz v_ang
%s
thermo 1000
timestep 1e-3
run 3000
""" % (GRAIN1, THERMO_FULL)
rc, log = run_lmp(d, cwd=os.path.abspath("drum"))
drum = thermo(log)
if check(len(drum) > 2, "drum: no thermo output"):
    # spin +0.3 about y moves the drum's bottom (0, 0, -1) along omega x r = -x: the cube
    # rides up the -x side (mu = 0.8 holds it to ~38 deg; 3 s turn the drum 0.9 rad)
    check(drum[-1]["v_ang"] < -0.3, "drum: the cube was not lifted (angle %g)" % drum[-1]["v_ang"])


# ---- spin by variables ---------------------------------------------------------------
# an equal-style variable of constant value gives the number's bits
DT2 = 1.0 / 1024.0  # binary time step: the switch time and the angles are exact
write_data("turn.data", (-3, 3, -3, 3, -1, 3), [Grain((2.0, 2.0, 2.0))])


def turning_plane(name, spin, steps, pre="", expect_fail=False):
    """A plane spinning about x (no grain near it): its normal f_w[7..9] each 1500 steps."""
    d = head(lib, "turn.data", boundary="f f f") + """
pair_style zero 1.0
pair_coeff * *
fix 1 all nve/lsdem
%s
fix w all wall/lsdem plane 0 0 -0.9 0 0 1 300 300 0.5 spin 0 0 0 %s
thermo_style custom step time f_w[7] f_w[8] f_w[9] f_w[11]
thermo_modify format float %%.17g
thermo 1500
timestep %r
run %d
""" % (pre, spin, DT2, steps)
    rc, log = run_lmp(d, cwd=os.path.abspath(name), expect_fail=expect_fail)
    return (rc, log) if expect_fail else thermo(log)


# the rate reverses after 1500 steps: the plane turns by 0.3 * 1500 dt about x, then back
rev = turning_plane("reverse", "v_wx 0 0", 3000,
                    pre="variable wx equal 0.3*(1-2*(time>%r))" % (1500 * DT2))
if check(len(rev) == 3, "reversing spin: %d thermo rows" % len(rev)):
    th = 0.3 * 1500 * DT2
    mid, end = rev[1], rev[2]
    near(mid["f_w[8]"], -math.sin(th), atol=1e-12, msg="reversing spin: normal y after the turn")
    near(mid["f_w[9]"], math.cos(th), atol=1e-12, msg="reversing spin: normal z after the turn")
    near(end["f_w[8]"], 0.0, atol=1e-12, msg="reversing spin: back to the start (y)")
    near(end["f_w[9]"], 1.0, atol=1e-12, msg="reversing spin: back to the start (z)")
    near(end["f_w[11]"], -0.3, rtol=0.0, msg="reversing spin: output 11 is the rate now")
# a constant variable gives the number's bits
num = turning_plane("spin_number", "0.3 0 0", 3000)
var = turning_plane("spin_variable", "v_wx 0 0", 3000, pre="variable wx equal 0.3")
check(len(num) == 3 and num == var, "spin by a constant variable differs from the number:\n%s\n%s"
      % (num, var))
# the axis may not turn
rc, log = turning_plane("spin_turns", "v_wx 0 v_wz", 100, expect_fail=True,
                        pre="variable wx equal 0.3\nvariable wz equal 0.3*(step>10)")
check(rc != 0 and "not along the axis" in log and "at step 11" in log,
      "spin changing direction: expected an error naming the step:\n%s" % log[-1500:])


def refuses(name, wall, *words):
    write_data("err.data", (-3, 3, -3, 3, -1, 3), [Grain((1.0, 0.0, HALF + 1e-4))])
    d = head(lib, "err.data", boundary="f f f") + """
pair_style zero 1.0
pair_coeff * *
fix 1 all nve/lsdem
fix w all wall/lsdem %s
run 1
""" % wall
    rc, log = run_lmp(d, cwd=os.path.abspath(name), expect_fail=True)
    check(rc != 0 and all(w in log for w in words), "%s: expected an error naming %s:\n%s"
          % (name, words, log[-1500:]))


refuses("platen_spin", "plane 0 0 0 0 0 1 300 300 0.5 pivot 1 1 spin 0 0 0 0 0 1",
        "platen cannot also spin")
refuses("zero_spin", "plane 0 0 0 0 0 1 300 300 0.5 spin 0 0 0 0 0 0", "must not be zero")
finish()
