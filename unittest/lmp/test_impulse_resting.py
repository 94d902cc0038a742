"""Impulse mode's resting contacts as warm-started constraints (fix impulse/lsdem, method
split, the default; issue 33).

- A column of L = 5 and 40 spheres (radius 0.1) on a floor, at dt 1e-3 and 16e-3, comes to
  rest and stays at rest (speeds below the resting solve's tolerance, the top grain moving
  less than the slop): the floor carries the column's weight (fix wall/lsdem's force
  output, now fed by the impulse fix) within 1 %, no collision solve runs once at rest,
  and the resting solve's sweeps per step stay at 1-2 whatever L (warm-started; the shock
  sweep stops the cold column).
- A sphere dropped on the floor faster than the resting speed (2 g dt) bounces; one
  arriving slower does not (e = 0 below the threshold, documented).
- Newton's cradle (e = 1, five touching spheres, no gravity): the collision solve carries
  the momentum through the resting contacts to the last sphere, as the report's method.
- A small sphere (mass ratio 1000) under a large one on the floor: neither sinks into the
  floor, and the floor carries both weights within 1 %.
- A column of 6 boxes (level-set grids, 120 surface nodes each) at 16 times the step of the
  report's method's test does not walk sideways or turn (it did, at 2e-5 of a box per step)."""
import os

from impulse_decks import floor_drop, header, library
from lsdemtest import run_lmp, thermo, check, near, finish, shape_tool

G, R = 9.81, 0.1
BALL = library("ball.lslib", "sphere", R, nodes=20, analytic=True)
BOX = library("block.lslib", "box", 0.5, 0.5, 0.25, nodes=120, spacing=0.05)
TWO = "two.lslib"
if not os.path.exists(TWO):
    library("small.lslib", "sphere", 0.05, nodes=20, analytic=True)
    library("large.lslib", "sphere", 0.5, nodes=20, analytic=True)
    shape_tool("merge", TWO, "small.lslib", "large.lslib")


def data(name, atoms, box="-2 2 xlo xhi\n-2 2 ylo yhi\n-1 12 zlo zhi\n", types=1):
    """atoms: (shape, x, y, z); every grain of density 1 at rest."""
    path = os.path.abspath(name + ".data")
    with open(path, "w") as f:
        f.write("grains\n\n%d atoms\n%d atom types\n\n%s\nAtoms # lsdem\n\n" % (len(atoms), types, box))
        for k, (shape, x, y, z) in enumerate(atoms):
            f.write("%d 1 %d 1.0 %r %r %r 1 0 0 0\n" % (k + 1, shape, x, y, z))
    return path


def on_floor(name, lib, data_path, dt, variables, columns, every, steps, opts=""):
    """Grains under gravity on a floor (friction 0.5), impulse method e = mu = 0.5 with the
    fix's defaults and opts; variables: deck lines; columns: thermo columns. The thermo
    rows."""
    deck = (header(lib, data_path)
            + "fix floor all wall/lsdem plane 0 0 0 0 0 1 1.0e4 0 0.5\n"
            + "fix grav all gravity %r vector 0 0 -1\n" % G
            + "fix imp all impulse/lsdem 0.5 0.5 %s\ntimestep %r\n" % (opts, dt)
            + variables + "variable m equal mass(all)\n"
            + "thermo_style custom step %s\n" % columns
            + "thermo_modify norm no format float %%.15g\nthermo %d\nrun %d\n" % (every, steps))
    _, log = run_lmp(deck, cwd=os.path.abspath(name))
    return thermo(log)


def column(L, dt, steps):
    eps = 1e-6  # each contact starts slightly overlapped, so it is found at step 0
    atoms = [(1, 0.0, 0.0, R - eps + k * (2 * R - eps)) for k in range(L)]
    name = "column%d_dt%g" % (L, dt)
    return on_floor(name, BALL, data(name, atoms), dt, "variable top equal z[%d]\n" % L,
                    "ke v_top v_m f_floor[3] f_imp[22] f_imp[23] f_imp[24] f_imp[6] f_imp[29]",
                    steps // 20, steps)


sweeps = {}
for L in (5, 40):
    for dt in (1e-3, 16e-3):
        rows = column(L, dt, 400)
        name = "column of %d, dt %g" % (L, dt)
        if not check(len(rows) > 10, name + " ran"):
            continue
        late = rows[len(rows) // 2:]
        weight = late[-1]["v_m"] * G
        print("%s: floor force %.6g (weight %.6g), top %.9g .. %.9g, sweeps %s, ETM islands %s, "
              "KE %.3g" % (name, late[-1]["f_floor[3]"], weight, min(r["v_top"] for r in late),
                           max(r["v_top"] for r in late), [r["f_imp[23]"] for r in late[-3:]],
                           [r["f_imp[24]"] for r in late[-3:]], late[-1]["KinEng"]))
        for r in late:
            near(-r["f_floor[3]"], weight, rtol=0.01,
                 msg="%s step %d: the floor carries the weight" % (name, r["Step"]))
        # at rest to the resting solve's tolerance (1e-2 of the resting speed 2 g dt): the
        # top moves less than the slop (the overlap left alone, 2 g dt^2) and the speeds
        # stay below the tolerance (no energy pumped in)
        vr = 2 * G * dt
        check(max(r["v_top"] for r in late) - min(r["v_top"] for r in late) < vr * dt,
              "%s: the top grain moves (sinks or jitters)" % name)
        vrms = max((2 * r["KinEng"] / r["v_m"]) ** 0.5 for r in late)
        check(vrms < 1e-2 * vr, "%s: rms speed %g at rest (tolerance %g)" % (name, vrms, 1e-2 * vr))
        check(all(r["f_imp[24]"] == 0 for r in late), "%s: a collision solve at rest" % name)
        check(all(r["f_imp[6]"] == 0 for r in late), "%s: the wall guard acted at rest" % name)
        check(all(r["f_imp[22]"] == L for r in late), "%s: %d resting contacts, %d expected"
              % (name, late[-1]["f_imp[22]"], L))
        sweeps[(L, dt)] = max(r["f_imp[23]"] for r in late)
for dt in (1e-3, 16e-3):
    if (5, dt) in sweeps and (40, dt) in sweeps:
        check(sweeps[(40, dt)] <= 2 and sweeps[(5, dt)] <= 2,
              "dt %g: sweeps per step once warm %d (L 5), %d (L 40)" % (dt, sweeps[(5, dt)],
                                                                     sweeps[(40, dt)]))


# a drop onto the floor: faster than the resting speed 2 g dt it bounces, slower it does not
def drop(v0, dt=1e-3, rest=None):
    """rest: fix keywords setting the resting speed (default: rest 2 g dt, given)."""
    name = "drop_v%g%s" % (v0, "_" + rest.replace(" ", "") if rest else "")
    rest = rest or "rest %r" % (2 * G * dt)
    deck = floor_drop(BALL, data(name, [(1, 0.0, 0.0, R + 0.5 * v0 * dt)]), 0.65, dt, 20,
                      g=G if "rest_steps" in rest else None, opts=rest,
                      setup="velocity all set 0 0 %r\n" % -v0)
    _, log = run_lmp(deck, cwd=os.path.abspath(name))
    return thermo(log)


vr = 2 * G * 1e-3
for factor, bounces in ((0.5, False), (3.0, True)):
    rows = drop(factor * vr)
    if check(rows, "drop at %g x the resting speed ran" % factor):
        vmax = max(r["v_vz"] for r in rows)
        print("drop at %.1f x the resting speed: largest upward speed %.6g (e v0 = %.6g)"
              % (factor, vmax, 0.65 * factor * vr))
        if bounces:
            near(vmax, 0.65 * factor * vr, rtol=1e-6, msg="faster than the resting speed: e v0")
        else:
            check(abs(vmax) < 1e-12, "slower than the resting speed: no bounce (%g)" % vmax)

# rest auto is rest_steps x g dt (gravity the largest external acceleration): arriving at
# 3 g dt (4 g dt after the step's gravity kick) a ball bounces with rest_steps 2 and does not
# with rest_steps 8
for steps, bounces in ((2, True), (8, False)):
    rows = drop(3.0 * G * 1e-3, rest="rest_steps %d" % steps)
    if check(rows, "drop with rest_steps %d ran" % steps):
        vmax = max(r["v_vz"] for r in rows)
        check((vmax > 0.5 * 0.65 * 3.0 * G * 1e-3) == bounces,
              "rest_steps %d: largest upward speed %g (bounce expected: %s)" % (steps, vmax, bounces))

# A ball dropped under gravity with e = 0.65 bounces lower and lower and comes to rest (its
# contact classified by the approach it arrived with, before the step's kick: classified
# after it, the ball kept a 4-step micro-bounce at 3.3 g dt for ever, pumped by the kick's
# g dt and by sinking a step below the floor before each impact)
deck = floor_drop(BALL, data("settle", [(1, 0.0, 0.0, 2.0 * R)]), 0.65, 1e-3, 2000, g=G)
_, log = run_lmp(deck, cwd=os.path.abspath("settle"))
rows = thermo(log)
if check(rows, "the settling drop ran"):
    ups = [k for k in range(1, len(rows)) if rows[k]["v_vz"] > 0.0 >= rows[k - 1]["v_vz"]]
    tail = rows[-500:]
    print("settling drop: %d bounces, the last at step %d; last 500 steps: |vz| <= %g, z %g..%g"
          % (len(ups), rows[ups[-1]]["Step"] if ups else -1, max(abs(r["v_vz"]) for r in tail),
             min(r["v_z"] for r in tail), max(r["v_z"] for r in tail)))
    check(ups and rows[ups[-1]]["Step"] < 1500, "the ball still bounces after step 1500")
    check(max(abs(r["v_vz"]) for r in tail) < 1e-9, "the ball is not at rest at the end")

# Newton's cradle: sphere 1 at speed 1 hits four touching spheres at rest; the split method
# gives the report's ETM result (method etm) bit for bit: the collision's impulse crosses
# the resting contacts elastically
def cradle(opts):
    atoms = [(1, -0.3, 0.0, 1.0)] + [(1, 2 * R * k - 1e-9 * k, 0.0, 1.0) for k in range(4)]
    name = "cradle_" + (opts.split()[-1] if opts else "split")
    deck = (header(BALL, data(name, atoms))
            + "velocity all set 0 0 0\ngroup first id 1\nvelocity first set 1 0 0\n"
            + "fix imp all impulse/lsdem 1.0 0.0 %s\ntimestep 1e-3\n" % opts
            + "variable v1 equal vx[1]\nvariable v5 equal vx[5]\nvariable p equal "
              "vx[1]+vx[2]+vx[3]+vx[4]+vx[5]\n"
            + "thermo_style custom step ke v_v1 v_v5 v_p f_imp[22] f_imp[24]\n"
            + "thermo_modify norm no format float %.15g\nthermo 10\nrun 300\n")
    _, log = run_lmp(deck, cwd=os.path.abspath(name))
    return thermo(log)


rows, ref = cradle(""), cradle("method etm")
if check(rows and ref, "cradle ran"):
    last = rows[-1]
    print("cradle: first %.6g, last %.6g (report's method %.6g, %.6g), momentum %.15g, KE %.15g, "
          "resting contacts seen %d" % (last["v_v1"], last["v_v5"], ref[-1]["v_v1"], ref[-1]["v_v5"],
                                        last["v_p"], last["KinEng"], max(r["f_imp[22]"] for r in rows)))
    check(max(r["f_imp[22]"] for r in rows) >= 3, "the touching spheres rest on each other")
    check(last["v_v5"] == ref[-1]["v_v5"] and last["v_v1"] == ref[-1]["v_v1"],
          "the split method's cradle is the report's")
    check(last["v_v5"] > 0.9, "the momentum reaches the last sphere: last %g" % last["v_v5"])
    near(last["v_p"], 1.0, rtol=1e-12, msg="momentum kept")
    near(last["KinEng"], rows[0]["KinEng"], rtol=1e-3, msg="e = 1: energy kept")

# mass ratio 1000: a small sphere (r 0.05) under a large one (r 0.5) on the floor
atoms = [(1, 0.0, 0.0, 0.05 - 1e-6), (2, 0.0, 0.0, 0.1 + 0.5 - 3e-6)]
rows = on_floor("ratio", TWO, data("ratio", atoms), 1e-3, "variable zs equal z[1]\n",
                "v_zs v_m f_floor[3] f_imp[23]", 100, 2000)
if check(rows, "mass ratio 1000 ran"):
    late = rows[len(rows) // 2:]
    sink = max(0.05 - r["v_zs"] for r in late)
    print("mass ratio 1000: the small sphere %.3g of its radius into the floor; floor force "
          "%.6g, weight %.6g; sweeps %d" % (sink / 0.05, -late[-1]["f_floor[3]"],
                                            late[-1]["v_m"] * G, late[-1]["f_imp[23]"]))
    check(sink < 0.01 * 0.05, "the small sphere sinks %.3g of its radius" % (sink / 0.05))
    near(-late[-1]["f_floor[3]"], late[-1]["v_m"] * G, rtol=0.01, msg="floor carries both")
# six boxes 1 x 1 x 0.5 stacked on the floor, friction 0.5, at dt 16e-3: the resting sweeps
# in the island's order (the default) and colour by colour (colours yes)
for opts in ("", "colours yes"):
    name = "boxes" + ("_colours" if opts else "")
    atoms = [(1, 0.0, 0.0, 0.25 + 0.5 * k - 1e-4 * (k + 1)) for k in range(6)]
    rows = on_floor(name, BOX, data(name, atoms, box="-3 3 xlo xhi\n-3 3 ylo yhi\n-1 6 zlo zhi\n"),
                    16e-3, "variable x equal x[6]\nvariable y equal y[6]\nvariable z equal z[6]\n"
                    "compute w all property/atom omegax omegay omegaz\n"
                    "variable w2 atom c_w[1]^2+c_w[2]^2+c_w[3]^2\nvariable w equal sqrt(v_w2[6])\n",
                    "v_x v_y v_z v_w v_m f_floor[3] f_imp[6]", 50, 1000, opts)
    if check(rows, "box column ran (%s)" % (opts or "defaults")):
        late = rows[len(rows) // 2:]
        walk = max(abs(r["v_x"] - late[0]["v_x"]) + abs(r["v_y"] - late[0]["v_y"]) for r in late)
        print("box column (%s): top box at (%.3g, %.3g), z %.9g .. %.9g, spin up to %.3g; floor "
              "force %.6g (weight %.6g)" % (opts or "defaults", late[-1]["v_x"], late[-1]["v_y"],
                                          min(r["v_z"] for r in late), max(r["v_z"] for r in late),
                                          max(r["v_w"] for r in late), -late[-1]["f_floor[3]"],
                                          late[-1]["v_m"] * G))
        check(walk < 1e-9, "the box column walks sideways (%s): %g over the last 500 steps"
              % (opts or "defaults", walk))
        # a tolerance, not a derived bound: the top box within 1 % of its width of the axis
        # (the first steps' node-level asymmetry moves it there: 0.007 measured)
        check(abs(late[-1]["v_x"]) + abs(late[-1]["v_y"]) < 0.01,
              "the top box settled off-centre (%s)" % (opts or "defaults"))
        check(max(r["v_w"] for r in late) < 1e-9, "the top box turns (%s)" % (opts or "defaults"))
        near(-late[-1]["f_floor[3]"], late[-1]["v_m"] * G, rtol=0.01,
             msg="box column: floor force (%s)" % (opts or "defaults"))
finish()
