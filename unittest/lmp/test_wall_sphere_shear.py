"""The shear springs of analytic spheres on a wall, kept in one slot per sphere
(fix LSDEM_SPHERE_SHEAR of each fix wall/lsdem with friction):

1. They survive every search for candidates: a sphere pressed onto a frictional floor and
   pushed sideways by Ft = 0.3 mu Fn (no spin: `spheres fixed`, damped) sticks, its spring
   holding Ft: it comes to rest Ft / ks from where it started. A spring lost at a search
   would let it slide at Ft / (m xi) (tens of radii over the run). The run with a
   neighbour-list build (and so a new search) every step gives the same bits as the run
   with none.
2. They travel with the spheres and are saved in restart files: spheres sliding down a
   frictional floor without rolling (gravity tilted beyond the friction angle, periodic in x and y, the
   rank boundary of `processors 2 1 1` crossed on the way) end with the same bits on
   1 rank, on 2 ranks and with 2 threads; split in two runs by a restart file they end where
   the single run does (to the round-off a LAMMPS restart brings), and they do not when the
   wall is given another ID in the second run, so that its springs are not read back."""
import os
import random

from lsdemtest import run_lmp, thermo, check, near, finish, shape_tool
from contact_decks import Grain, write_data, head, THERMO_FULL

R = 0.5
if not os.path.exists("ball.lslib"):
    shape_tool("analytic", "ball.lslib", "sphere", R, "--analytic")
KN, KS, MU = 1.0e4, 8.0e3, 0.5

# ---- 1. a stuck sphere across searches for candidates ----------------------------------
DEPTH = 0.01
FN = KN * DEPTH
FT = 0.3 * MU * FN
write_data("stuck.data", (-2.0, 2.0, -2.0, 2.0, -1.0, 3.0), [Grain((0.0, 0.0, R - DEPTH))])


def stuck(every):
    deck = head("ball.lslib", "stuck.data", boundary="f f f") + """
pair_style lsdem
pair_coeff * * %r %r %r
neighbor 0.05 bin
neigh_modify every %d delay 0 check no
fix floor all wall/lsdem plane 0 0 0 0 0 1 %r %r %r
fix push all addforce %r 0.0 %r
fix 1 all nve/lsdem damping 20 spheres fixed
variable px equal x[1]
variable vx equal vx[1]
thermo_style custom step v_px v_vx f_floor[1] f_floor[3]
%s
thermo 4000
timestep 0.0005
run 4000
""" % (KN, KS, MU, every, KN, KS, MU, FT, -FN, THERMO_FULL)
    rc, log = run_lmp(deck, cwd=os.path.abspath("stuck-%d" % every))
    return log


log_builds = stuck(1)
rows = thermo(log_builds)
check(len(rows) == 2, "stuck: thermo rows %d" % len(rows))
if len(rows) == 2:
    end = rows[-1]
    near(end["v_px"], FT / KS, rtol=0.05, msg="stuck sphere at rest Ft/ks from its start")
    check(abs(end["v_vx"]) < 1e-6 * FT / KS / 0.0005, "stuck sphere at rest: vx %r" % end["v_vx"])
    near(end["f_floor[1]"], FT, rtol=0.01, msg="the floor's spring holds Ft")
    near(end["f_floor[3]"], -FN, rtol=0.01, msg="the floor carries Fn")
check("Neighbor list builds = 4000" in log_builds, "a neighbour-list build every step")
log_none = stuck(100000)
check("Neighbor list builds = 0" in log_none, "no neighbour-list build")
check(thermo(log_none) == rows, "the same bits with a search every step and with none")

# ---- 2. ranks, threads, restart --------------------------------------------------------
rng = random.Random(5)
grains = []
for k in range(2):
    for j in range(4):
        for i in range(4):
            g = Grain((0.6 + 1.2 * i + 0.1 * rng.random(), 0.6 + 1.2 * j + 0.1 * rng.random(),
                       0.55 + 1.1 * k))
            g.v = (rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), 0.0)
            grains.append(g)
write_data("slide.data", (0.0, 4.8, 0.0, 4.8, 0.0, 6.0), grains)
# tan 17 deg = 0.3 > mu = 0.2 on the floor: the bottom layer slides on in x (the spheres do
# not spin: `spheres fixed`, so they cannot roll), across the boundary between the two
# ranks, its springs at the friction cap
LAWS = """pair_style lsdem
pair_coeff * * %r %r %r cn 5.0
neighbor 0.05 bin
neigh_modify every 1 delay 0 check yes
fix %%s all wall/lsdem plane 0 0 0 0 0 1 %r %r 0.2 cn 5.0
fix g all gravity 10.0 vector 0.3 0 -1
fix 1 all nve/lsdem spheres fixed
timestep 0.0005
""" % (KN, KS, MU, KN, KS)


def slide_deck(np):
    return (head("ball.lslib", "slide.data", extra="processors %d 1 1" % np) + LAWS % "floor"
            + "thermo_style custom step ke f_floor[1] f_floor[3]\n%sthermo 1000\n" % THERMO_FULL)


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
    rc, log = run_lmp(slide_deck(np) + body + "write_data final.data nocoeff\n", np=np,
                      cwd=where, args=args)
    return atoms_of(os.path.join(where, "final.data")), log


def largest_move(a, b):
    """The largest difference of a coordinate between two Atoms sections."""
    return max([abs(float(p) - float(q)) for la, lb in zip(a, b)
                for p, q in zip(la.split()[4:7], lb.split()[4:7])] or [1.0])


serial, log1 = final_state("serial", "run 3000\n")
check(len(serial[0]) == len(grains) and len(serial[1]) == len(grains),
      "serial run wrote its state")
end = thermo(log1)[-1] if thermo(log1) else {}
# the floor's friction at its cap: mu = 0.2 of the load it carries, against the slide
near(end.get("f_floor[1]", 0.0), -0.2 * end.get("f_floor[3]", 0.0), rtol=0.05,
     msg="the spheres slide on the floor: its friction force mu times its load")
ranks, _ = final_state("ranks", "run 3000\n", np=2)
check(ranks == serial, "2 ranks: the serial bits")
threads, _ = final_state("threads", "run 3000\n", args=["-sf", "omp", "-pk", "omp", "2"])
check(threads == serial, "2 threads: the serial bits")
final_state("restart", "run 1500\nwrite_restart half.restart\n")


def resumed(wall_id):
    rc, log = run_lmp("read_restart half.restart\n" + LAWS % wall_id
                      + "run 1500\nwrite_data final-%s.data nocoeff\n" % wall_id,
                      cwd=os.path.abspath("restart"))
    return atoms_of(os.path.join("restart", "final-%s.data" % wall_id))[0], log


split, log = resumed("floor")
check("Resetting peratom fix info from restart file" in log, "the springs were read back")
moved = largest_move(split, serial[0])
check(len(split) == len(grains) and moved < 1e-6,
      "split by a restart file: positions within %g of the serial run's" % moved)
lost, _ = resumed("floor2")
moved_lost = largest_move(lost, serial[0])
check(len(lost) == len(grains) and moved_lost > 100 * max(moved, 1e-9),
      "the wall's springs lost at the restart (another wall ID): positions %g away" % moved_lost)
finish()
