"""Sleeping islands (fix impulse/lsdem keyword sleep, issue 33 item 7).

Scene: a row of four touching spheres (radius 0.1) on a floor, straddling x = 0 (so that on
2 and 4 ranks its island spans ranks), a separate pair of spheres at x = 1.2, and a ball
falling from z = 1.2 into the groove between the row's 2nd and 3rd spheres; impulse method
e = mu = 0.5, dt 1e-3, sleep 0.02 0.05 (a grain slow below 0.02, an island asleep after
0.05 s). From step 1200 the floor rises at 0.05. Expected, independently of the code:

- while the ball falls, both islands sleep: no contact is detected, the grains do not move
  (bit for bit), and the floor still reads the weight of the six sleeping spheres (from
  their last resting impulses) -- 6 m g, m = 4/3 pi r^3;
- the ball's arrival wakes the row (not the pair: it is 1 away); once everything has
  settled all seven sleep and the floor reads 7 m g; the ball rests where the same run
  without sleeping puts it (the second code path), to 1e-9;
- the rising floor wakes every island at once, and the grains rise with it (0.05 x 0.05 s
  by step 1250); grains given a velocity between runs wake and move;
- 2, 3 and 4 ranks, and 2 and 4 threads (-sf omp), give the serial run's grains bit for bit; a run stopped at step 700 on 2
  ranks (the pair asleep, the ball falling) and continued from its restart file on 3 is the
  uninterrupted run (sleep clocks and labels travel in the restart file)."""
import math
import os

from impulse_decks import header, library, dump
from lsdemtest import run_lmp, thermo, check, near, finish

G, R, EPS = 9.81, 0.1, 1e-6
MASS = 4.0 / 3.0 * math.pi * R ** 3  # density 1
BALL = library("ball.lslib", "sphere", R, nodes=20, analytic=True)
STEPS, HALF, MOVE = 1500, 700, 1200
SLEEP = "sleep 0.02 0.05"


def scene():
    row = [(-0.3 + k * (2 * R - EPS), 0.0, R - EPS) for k in range(4)]
    pair = [(1.2, 0.0, R - EPS), (1.2 + 2 * R - EPS, 0.0, R - EPS)]
    ball = [(-0.3 + 1.5 * (2 * R - EPS), 0.0, 1.2)]
    path = os.path.abspath("sleep.data")
    with open(path, "w") as f:
        atoms = row + pair + ball
        f.write("sleep\n\n%d atoms\n1 atom types\n\n-2 2 xlo xhi\n-2 2 ylo yhi\n-1 4 zlo zhi\n\n"
                "Atoms # lsdem\n\n" % len(atoms))
        for k, (x, y, z) in enumerate(atoms):
            f.write("%d 1 1 1.0 %r %r %r 1 0 0 0\n" % (k + 1, x, y, z))
    return path


DATA = scene()
AFTER_READ = header(BALL, DATA).split("read_data")[1].split("\n", 1)[1]
SETUP = ("variable vf equal (step>%d)*0.05\n" % MOVE
         + "fix floor all wall/lsdem plane 0 0 0 0 0 1 1.0e4 0 0.5 velocity 0 0 v_vf\n"
         + "fix grav all gravity %r vector 0 0 -1\n" % G
         + "fix imp all impulse/lsdem 0.5 0.5 {opts}\ntimestep 1e-3\n"
         + "variable zb equal z[7]\nvariable z3 equal z[3]\nvariable x5 equal x[5]\n"
         + "variable z5 equal z[5]\n"
         + "thermo_style custom step ke f_floor[3] v_zb v_z3 v_x5 v_z5 f_imp[25] f_imp[32] "
           "f_imp[33]\nthermo_modify norm no format float %.17g\nthermo 10\n")


def deck(opts, steps=STEPS, restart=None):
    text = header(BALL, DATA) + SETUP.format(opts=opts)
    if restart:
        return text + "run %d\nwrite_restart %s\n" % (steps, restart)
    return text + dump(STEPS, "final.dump") + "run %d\n" % steps


def run(name, text, np=1, args=None):
    _, log = run_lmp(text, np=np, cwd=os.path.abspath(name), args=args)
    path = os.path.join(os.path.abspath(name), "final.dump")
    atoms = open(path).read().split("ITEM: ATOMS")[-1] if os.path.exists(path) else None
    return atoms, thermo(log)


ref_atoms, rows = run("np1", deck(SLEEP))
_, plain = run("nosleep", deck(""))
if check(len(rows) == STEPS // 10 + 1 and len(plain) == len(rows), "the runs ran"):
    at = {int(r["Step"]): r for r in rows}
    falling = [r for r in rows if 100 <= r["Step"] <= 400]
    check(all(r["f_imp[32]"] == 6 and r["f_imp[25]"] == 0 for r in falling),
          "while the ball falls: 6 grains asleep, no contact (%s)"
          % sorted({(r["f_imp[32]"], r["f_imp[25]"]) for r in falling}))
    for r in falling:
        near(-r["f_floor[3]"], 6 * MASS * G, rtol=1e-9,
             msg="step %d: the floor carries the sleeping grains" % r["Step"])
    check(len({(r["v_z3"], r["v_x5"], r["v_z5"]) for r in falling}) == 1,
          "sleeping grains moved")
    # the pair is never woken until the floor moves: the same bits from step 100 to 1200
    before = [r for r in rows if 100 <= r["Step"] <= MOVE]
    check(len({(r["v_x5"], r["v_z5"]) for r in before}) == 1, "the far pair moved or woke")
    impact = [r for r in rows if 420 <= r["Step"] <= 600]
    check(min(r["f_imp[32]"] for r in impact) <= 2, "the ball's arrival woke the row (asleep "
          "%s)" % sorted({r["f_imp[32]"] for r in impact}))
    settled = [r for r in rows if 1100 <= r["Step"] <= MOVE]
    check(all(r["f_imp[32]"] == 7 and r["f_imp[25]"] == 0 and r["KinEng"] == 0
              for r in settled), "settled: all 7 asleep, no contact, at rest")
    # asleep, the floor reads the island's last awake step's resting impulses: those hold the
    # weight to the resting solve's tolerance, 1e-2 of the resting speed 2 g dt (2e-2 of the
    # weight); an ETM residual (keyword residual) left to that step moves them within it
    for r in settled:
        near(-r["f_floor[3]"], 7 * MASS * G, rtol=2e-2,
             msg="step %d: the floor carries all seven" % r["Step"])
    print("settled: the floor carries %.3e of the weight off" %
          max(abs(-r["f_floor[3]"] / (7 * MASS * G) - 1) for r in settled))
    ref = {int(r["Step"]): r for r in plain}
    near(at[MOVE]["v_zb"], ref[MOVE]["v_zb"], rtol=1e-9,
         msg="the ball rests where the run without sleeping puts it")
    print("ball at rest: z %.15g (sleep) %.15g (no sleep); groove height %.15g"
          % (at[MOVE]["v_zb"], ref[MOVE]["v_zb"], R + math.sqrt(3.0) * R))
    check(at[MOVE + 10]["f_imp[32]"] == 0, "the moving floor woke every island")
    near(at[MOVE + 50]["v_z5"] - at[MOVE]["v_z5"], 0.05 * 0.05, rtol=0.02,
         msg="the pair rises with the floor")

for np, threads in ((2, 1), (3, 1), (4, 1), (1, 2), (1, 4)):
    name = "np%d-omp%d" % (np, threads)
    args = ["-sf", "omp", "-pk", "omp", threads] if threads > 1 else None
    atoms, rows_np = run(name, deck(SLEEP), np, args)
    check(atoms == ref_atoms, "%s: grains differ from the serial run" % name)
    check([r["f_imp[32]"] for r in rows_np] == [r["f_imp[32]"] for r in rows],
          "%s: grains asleep differ" % name)

# a sleeping grain given a velocity between runs wakes (with its island) and moves
_, log = run_lmp(header(BALL, DATA) + SETUP.format(opts=SLEEP) + "run 300\n"
                 + "velocity all set 0.1 0 0\nrun 20\n", cwd=os.path.abspath("kicked"))
before, after = thermo(log, 0), thermo(log)
check(before and after and before[-1]["f_imp[32]"] == 6 and after[0]["f_imp[32]"] == 0 and
      after[-1]["v_x5"] > before[-1]["v_x5"] + 0.25 * 0.1 * 0.02,
      "grains asleep given a velocity: woken and moved (asleep %s, moved %.3g; a quarter of "
      "v t expected at least, friction slowing it)"
      % ([r["f_imp[32]"] for r in before[-1:] + after[:1]],
         after[-1]["v_x5"] - before[-1]["v_x5"]))

run_lmp(deck(SLEEP, HALF, "half.restart"), np=2, cwd=os.path.abspath("restart"))
atoms, cont = run("restart", "read_restart half.restart\n" + AFTER_READ
                  + SETUP.format(opts=SLEEP) + dump(STEPS, "final.dump")
                  + "run %d\n" % (STEPS - HALF), 3)
check(atoms == ref_atoms, "restart 2 -> 3 ranks: grains differ from the uninterrupted run")
asleep = {int(r["Step"]): r["f_imp[32]"] for r in rows}
check(cont and cont[0]["f_imp[32]"] > 0 and
      all(r["f_imp[32]"] == asleep[int(r["Step"])] for r in cont),
      "restart: the grains asleep differ from the uninterrupted run's (%s)"
      % [(r["Step"], r["f_imp[32]"], asleep[int(r["Step"])]) for r in cont[:3]])
finish()
