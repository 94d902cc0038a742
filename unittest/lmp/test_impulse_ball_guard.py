"""fix impulse/lsdem's ball guard (keyword balls; report §4.4.2, Figure 4.4): a spherical
grain (radius 0.3) thrown at 10 into a free square net of 81 balls (radius 0.1, spacing
0.25, no clamps, no gravity) at a step where it moves a third of its radius per step
(dt 0.01, resting speed 0.05: the guard's tolerance 2 x 0.05 x 0.01 = 1e-3). Overlaps are
measured here from the dumped centres and radii (sphere-sphere: r1 + r2 - |x1 - x2|), at
the end of every step:
1. with the guard no grain-ball overlap exceeds the tolerance (the advance goes where the
   guard predicted: spheres translate, no damping); it acted (values 34 and 35);
2. without it the grain sinks into the balls (more than 20 times the tolerance): the
   check has teeth;
3. both runs keep the linear momentum of grain and net (bonds, collisions and the guard's
   impulses are equal and opposite) to 1e-12 of the grain's;
4. the guard's run gives the same bits on 1 and 2 ranks (the pairs' impulses summed in
   the order of their atom IDs, the owners' counts sent to the ghosts)."""
import math

from impulse_decks import net_scene
from lsdemtest import run_lmp, check, near, finish

HEAD = net_scene()
REST, DT = 0.05, 0.01
TOL = 2 * REST * DT  # the guard's depth tolerance with method split (2 x the slop r dt)
DECK = HEAD + """velocity grains set 0 0 -10
group moving union grains net_free
fix move moving impulse/lsdem 0.5 0.3 rest {rest} {balls}
timestep {dt}
variable corr equal f_move[34]
variable deep equal f_move[35]
fix most all ave/time 1 1 1 v_corr v_deep
thermo 1
thermo_style custom step f_move[34] f_move[35]
dump d all custom 1 dump.{name} id mass radius x y z vx vy vz
dump_modify d sort id format float %.17g
run 40
"""


def frames(path):
    """[(step, {id: {column: value}})] of a multi-frame text dump."""
    lines = open(path).read().splitlines()
    out, i = [], 0
    while i < len(lines):
        step, n = int(lines[i + 1]), int(lines[i + 3])
        cols = lines[i + 8].split()[2:]
        atoms = {}
        for l in lines[i + 9:i + 9 + n]:
            v = dict(zip(cols, map(float, l.split())))
            atoms[int(v["id"])] = v
        out.append((step, atoms))
        i += 9 + n
    return out


def run(name, balls, np=1):
    rc, log = run_lmp(DECK.format(rest=REST, dt=DT, name=name, balls=balls), np=np,
                      cwd=name, log="log." + name)
    fr = frames(name + "/dump." + name)
    worst = 0.0
    for step, atoms in fr:
        g = atoms[1]
        for k, b in atoms.items():
            if k != 1:
                d = math.dist((g["x"], g["y"], g["z"]), (b["x"], b["y"], b["z"]))
                worst = max(worst, g["radius"] + b["radius"] - d)
    p = [[sum(a["mass"] * a["v" + c] for a in atoms.values()) for c in "xyz"]
         for _, atoms in (fr[0], fr[-1])]
    grain_p = abs(p[0][2])
    drift = max(abs(p[1][c] - p[0][c]) for c in range(3))
    print("%s: deepest grain-ball overlap at a step's end %.4g (tolerance %g); momentum "
          "drift %.3g of %.4g" % (name, worst, TOL, drift, grain_p))
    check(drift < 1e-12 * grain_p, "%s: momentum drift %g" % (name, drift))
    check(len(fr) == 41, "%s: %d frames" % (name, len(fr)))
    return worst, log, open(name + "/dump." + name).read()


guarded, log, dump1 = run("guard", "balls net")
check(guarded <= TOL, "guard: overlap %g above the tolerance %g" % (guarded, TOL))
rows = [l.split() for l in log.splitlines() if l.strip() and l.split()[0].isdigit()
        and len(l.split()) == 3]
corrections = sum(float(r[1]) for r in rows)
deepest = max(float(r[2]) for r in rows)
print("guard: %d pairs corrected; deepest predicted overlap %.4g" % (corrections, deepest))
check(corrections > 0 and deepest > 20 * TOL, "the guard did not act: %d corrections, %g"
      % (corrections, deepest))
free, _, _ = run("free", "")
check(free > 20 * TOL, "without the guard the grain sank only %g (the check has no teeth)"
      % free)
_, _, dump2 = run("guard2", "balls net", np=2)
check(dump2.replace("dump.guard2", "") == dump1.replace("dump.guard", ""),
      "the guard's run differs on 1 and 2 ranks")

finish()
