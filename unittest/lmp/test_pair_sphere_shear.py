"""The shear springs of analytic sphere masters, kept in their slots (fix LSDEM_SPHERE_SHEAR):

1. They survive every neighbour-list build: a sphere pressed onto a fixed sphere and pushed
   sideways by Ft = 0.3 mu Fn (no spin: `spheres fixed`, damped) sticks, its tangential
   spring holding Ft: it comes to rest Ft / ks from where it started (to the normal's small
   turn). A spring lost at a build would let it slide at Ft / (m xi) ~ 10 per time unit
   (tens of radii). The run with a build every step gives the same bits as the run with
   none.
2. They travel with the spheres and are saved in restart files: a frictional settling of
   analytic spheres (periodic in x and y, a floor wall, neighbour-list builds on the way)
   ends with the same bits on 1 rank, on 2 ranks (spheres migrate with their springs),
   with 2 threads; split in two runs by a restart file it ends where the single run does
   (to the round-off a LAMMPS restart brings, amplified by the pile); springs are held at
   the end (compute pair lsdem: pair states and shear entries)."""
import os
import random

from lsdemtest import run_lmp, thermo, check, near, finish, shape_tool
from contact_decks import Grain, write_data, head, THERMO_FULL

R = 0.5
if not os.path.exists("ball.lslib"):
    shape_tool("analytic", "ball.lslib", "sphere", R, "--analytic")
KN, KS, MU = 1.0e4, 8.0e3, 0.5

# ---- 1. a stuck sphere across neighbour-list builds ---------------------------------
DEPTH = 0.01
FN = KN * DEPTH
FT = 0.3 * MU * FN
write_data("stuck.data", (-2.0, 2.0, -2.0, 2.0, -2.0, 3.0),
           [Grain((0.0, 0.0, 0.0)), Grain((0.0, 0.0, 2 * R - DEPTH))])


def stuck(every, check_flag):
    deck = head("ball.lslib", "stuck.data", boundary="f f f") + """
pair_style lsdem
pair_coeff * * %r %r %r
neighbor 0.05 bin
neigh_modify every %d delay 0 check %s
group top id 2
fix push top addforce %r 0.0 %r
fix 1 top nve/lsdem damping 20 spheres fixed
compute work all pair lsdem
variable px equal x[2]
variable vx equal vx[2]
thermo_style custom step v_px v_vx c_work[6] c_work[8]
%s
thermo 4000
timestep 0.0005
run 4000
""" % (KN, KS, MU, every, check_flag, FT, -FN, THERMO_FULL)
    rc, log = run_lmp(deck, cwd=os.path.abspath("stuck-%d-%s" % (every, check_flag)))
    return log


log_builds = stuck(1, "no")
rows = thermo(log_builds)
check(len(rows) == 2, "stuck: thermo rows %d" % len(rows))
if len(rows) == 2:
    end = rows[-1]
    near(end["v_px"], FT / KS, rtol=0.05, msg="stuck sphere at rest Ft/ks from its start")
    check(abs(end["v_vx"]) < 1e-6 * FT / KS / 0.0005, "stuck sphere at rest: vx %r" % end["v_vx"])
    check(end["c_work[6]"] == 1 and end["c_work[8]"] == 1,
          "one pair state, one shear entry held: %r %r" % (end["c_work[6]"], end["c_work[8]"]))
check("Neighbor list builds = 4000" in log_builds, "a neighbour-list build every step")
log_none = stuck(100000, "no")
check("Neighbor list builds = 0" in log_none, "no neighbour-list build")
check(thermo(log_none) == rows, "the same bits with a build every step and with none")

# ---- 2. ranks, threads, restart --------------------------------------------------------
rng = random.Random(3)
grains = []
for k in range(4):
    for j in range(4):
        for i in range(4):
            g = Grain((0.6 + 1.2 * i + 0.1 * rng.random(), 0.6 + 1.2 * j + 0.1 * rng.random(),
                          0.6 + 1.15 * k))
            g.v = (1.0 + rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5))
            grains.append(g)
write_data("pile.data", (0.0, 4.8, 0.0, 4.8, 0.0, 8.0), grains)
# the pile drifts in x over a frictionless floor (1.5 units in all), through the boundary
# between the two ranks of `processors 2 1 1` with its contacts' springs
LAWS = """pair_style lsdem
pair_coeff * * %r %r %r cn 5.0
neighbor 0.05 bin
neigh_modify every 1 delay 0 check yes
fix floor all wall/lsdem plane 0 0 0 0 0 1 %r %r 0.0 cn 5.0
fix g all gravity 10.0 vector 0 0 -1
fix 1 all nve/lsdem
timestep 0.0005
""" % (KN, KS, MU, KN, KS)


def settle_deck(np):
    return (head("ball.lslib", "pile.data", extra="processors %d 1 1" % np) + LAWS + """
compute work all pair lsdem
thermo_style custom step ke c_work[6] c_work[8]
%s
thermo 1000
""" % THERMO_FULL)


def atoms_of(path):
    """The Atoms and Velocities lines of a data file, each section sorted by atom ID (ranks
    write their atoms in their own order)."""
    text = open(path).read() if os.path.exists(path) else ""
    atoms, _, vels = text[text.find("Atoms"):].partition("Velocities")
    return [sorted((l for l in s.splitlines() if l.split() and l.split()[0].isdigit()),
                   key=lambda l: int(l.split()[0]))
            for s in (atoms, vels)]


def final_state(name, body, np=1, args=None):
    where = os.path.abspath(name)
    rc, log = run_lmp(settle_deck(np) + body + "write_data final.data nocoeff\n", np=np, cwd=where,
                      args=args)
    return atoms_of(os.path.join(where, "final.data")), log


serial, log1 = final_state("serial", "run 3000\n")
check(len(serial[0]) == len(grains) and len(serial[1]) == len(grains),
      "serial run wrote its state")
end = thermo(log1)[-1]
check(end["c_work[6]"] > 10 and end["c_work[8]"] == end["c_work[6]"],
      "springs held at the end: %r pair states, %r shear entries"
      % (end["c_work[6]"], end["c_work[8]"]))
builds = int(log1.split("Neighbor list builds = ")[1].split()[0]) if "builds = " in log1 else 0
check(builds > 5, "neighbour-list builds on the way: %d" % builds)
ranks, _ = final_state("ranks", "run 3000\n", np=2)
check(ranks == serial, "2 ranks: the serial bits")
threads, _ = final_state("threads", "run 3000\n", args=["-sf", "omp", "-pk", "omp", "2"])
check(threads == serial, "2 threads: the serial bits")
first, _ = final_state("restart", "run 1500\nwrite_restart half.restart\n")
rc, log = run_lmp("read_restart half.restart\n" + LAWS + "run 1500\nwrite_data final2.data nocoeff\n",
                  cwd=os.path.abspath("restart"))
check("Resetting peratom fix info from restart file" in log, "the springs were read back")
# a restart is not bit-exact in LAMMPS (the pair style's and the old store's alike): to
# round-off, amplified by the pile (1e-8 here; with the springs lost at the restart, 0.3)
split = atoms_of(os.path.join("restart", "final2.data"))[0]
moved = max([abs(float(a) - float(b)) for la, lb in zip(split, serial[0])
             for a, b in zip(la.split()[4:7], lb.split()[4:7])] or [1.0])
check(len(split) == len(grains) and moved < 1e-6,
      "split by a restart file: positions within %g of the serial run's" % moved)
finish()
