"""The shear springs of analytic spheres kept in slots (fix LSDEM_SPHERE_SHEAR): a sphere
master's, one per pair (pair_style lsdem), and a sphere's on a wall, one per wall
(fix wall/lsdem with friction).

1. They survive every neighbour-list build (and so, for a wall, every search for
   candidates): a sphere pressed onto a fixed sphere, or onto a frictional floor, and pushed
   sideways by Ft = 0.3 mu Fn (no spin: `spheres fixed`, damped) sticks, its tangential
   spring holding Ft: it comes to rest Ft / ks from where it started (to the normal's small
   turn). A spring lost at a build would let it slide at Ft / (m xi) ~ 10 per time unit
   (tens of radii). The run with a build every step gives the same bits as the run with
   none.
2. They travel with the spheres and are saved in restart files: a frictional settling of
   analytic spheres (periodic in x and y, a floor wall, neighbour-list builds on the way),
   and spheres sliding down a frictional floor without rolling (gravity tilted beyond the
   friction angle), end with the same bits on 1 rank, on 2 ranks (the spheres cross the
   rank boundary with their springs) and with 2 threads; split in two runs by a restart
   file they end where the single run does (to the round-off a LAMMPS restart brings,
   amplified by the pile), and the sliding spheres do not when the wall is given another ID
   in the second run, so that its springs are not read back. The pair's springs are held at
   the end (compute pair lsdem: pair states and shear entries)."""
import os
import random

from lsdemtest import run_lmp, thermo, check, near, finish
from contact_decks import (Grain, write_data, head, THERMO_FULL, atoms_of, largest_move,
                           lattice, final_state, check_ranks_threads, ball_library)

R = 0.5
ball_library("ball.lslib", R)
KN, KS, MU = 1.0e4, 8.0e3, 0.5
DEPTH = 0.01
FN = KN * DEPTH
FT = 0.3 * MU * FN


# ---- 1. a stuck sphere across neighbour-list builds ---------------------------------
def stuck(name, data, body, every):
    """The pushed sphere (variables px, vx) of `body` on `data`, 4,000 steps with a
    neighbour-list build every `every` steps; its log."""
    deck = head("ball.lslib", data, boundary="f f f") + """
pair_style lsdem
pair_coeff * * %r %r %r
neighbor 0.05 bin
neigh_modify every %d delay 0 check no
%s
%s
thermo 4000
timestep 0.0005
run 4000
""" % (KN, KS, MU, every, body, THERMO_FULL)
    rc, log = run_lmp(deck, cwd=os.path.abspath("stuck-%s-%d" % (name, every)))
    return log


def check_stuck(name, data, body):
    """Both runs of stuck(): at rest Ft / ks from the start, the same bits; the last row."""
    log_builds = stuck(name, data, body, 1)
    rows = thermo(log_builds)
    check(len(rows) == 2, "%s: thermo rows %d" % (name, len(rows)))
    end = rows[-1] if len(rows) == 2 else {"v_px": 0.0, "v_vx": 1.0}
    near(end["v_px"], FT / KS, rtol=0.05, msg="%s: stuck sphere at rest Ft/ks from its start"
         % name)
    check(abs(end["v_vx"]) < 1e-6 * FT / KS / 0.0005,
          "%s: stuck sphere at rest: vx %r" % (name, end["v_vx"]))
    check("Neighbor list builds = 4000" in log_builds, "%s: a build every step" % name)
    log_none = stuck(name, data, body, 100000)
    check("Neighbor list builds = 0" in log_none, "%s: no neighbour-list build" % name)
    check(thermo(log_none) == rows, "%s: the same bits with a build every step and with none"
          % name)
    return end


write_data("stuck.data", (-2.0, 2.0, -2.0, 2.0, -2.0, 3.0),
           [Grain((0.0, 0.0, 0.0)), Grain((0.0, 0.0, 2 * R - DEPTH))])
end = check_stuck("pair", "stuck.data", """group top id 2
fix push top addforce %r 0.0 %r
fix 1 top nve/lsdem damping 20 spheres fixed
compute work all pair lsdem
variable px equal x[2]
variable vx equal vx[2]
thermo_style custom step v_px v_vx c_work[6] c_work[8]""" % (FT, -FN))
check(end.get("c_work[6]") == 1 and end.get("c_work[8]") == 1,
      "pair: one pair state, one shear entry held: %r %r"
      % (end.get("c_work[6]"), end.get("c_work[8]")))

write_data("floor.data", (-2.0, 2.0, -2.0, 2.0, -1.0, 3.0), [Grain((0.0, 0.0, R - DEPTH))])
end = check_stuck("wall", "floor.data", """fix floor all wall/lsdem plane 0 0 0 0 0 1 %r %r %r
fix push all addforce %r 0.0 %r
fix 1 all nve/lsdem damping 20 spheres fixed
variable px equal x[1]
variable vx equal vx[1]
thermo_style custom step v_px v_vx f_floor[1] f_floor[3]""" % (KN, KS, MU, FT, -FN))
near(end.get("f_floor[1]", 0.0), FT, rtol=0.01, msg="wall: the floor's spring holds Ft")
near(end.get("f_floor[3]", 0.0), -FN, rtol=0.01, msg="wall: the floor carries Fn")


# ---- 2. ranks, threads, restart --------------------------------------------------------
def laws(wall_id, wall_mu, gravity, integrate):
    return """pair_style lsdem
pair_coeff * * %r %r %r cn 5.0
neighbor 0.05 bin
neigh_modify every 1 delay 0 check yes
fix %s all wall/lsdem plane 0 0 0 0 0 1 %r %r %r cn 5.0
fix g all gravity 10.0 vector %s
fix 1 all nve/lsdem %s
timestep 0.0005
""" % (KN, KS, MU, wall_id, KN, KS, wall_mu, gravity, integrate)


def split_run(make_deck, wall_laws, folder):
    """make_deck(1) run 1,500 steps, written to a restart file, then 1,500 more from it with
    wall_laws: the final Atoms section and the second run's log."""
    final_state(make_deck(1) + "run 1500\nwrite_restart half.restart\n", folder)
    rc, log = run_lmp("read_restart half.restart\n" + wall_laws
                      + "run 1500\nwrite_data final2.data nocoeff\n",
                      cwd=os.path.abspath(folder))
    return atoms_of(os.path.join(folder, "final2.data"))[0], log


# the pile drifts in x over a frictionless floor (1.5 units in all), through the boundary
# between the two ranks of `processors 2 1 1` with its contacts' springs
grains = lattice(random.Random(3), 4, 0.6, 1.15,
                 lambda rng: (1.0 + rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5),
                              rng.uniform(-0.5, 0.5)))
write_data("pile.data", (0.0, 4.8, 0.0, 4.8, 0.0, 8.0), grains)
PILE = laws("floor", 0.0, "0 0 -1", "")


def pile_deck(np):
    return (head("ball.lslib", "pile.data", extra="processors %d 1 1" % np) + PILE + """
compute work all pair lsdem
thermo_style custom step ke c_work[6] c_work[8]
%s
thermo 1000
""" % THERMO_FULL)


serial, log1 = final_state(pile_deck(1) + "run 3000\n", "pile-serial")
check(len(serial[0]) == len(grains) and len(serial[1]) == len(grains),
      "pile: serial run wrote its state")
end = thermo(log1)[-1] if thermo(log1) else {}
check(end.get("c_work[6]", 0) > 10 and end.get("c_work[8]") == end.get("c_work[6]"),
      "pile: springs held at the end: %r pair states, %r shear entries"
      % (end.get("c_work[6]"), end.get("c_work[8]")))
builds = int(log1.split("Neighbor list builds = ")[1].split()[0]) if "builds = " in log1 else 0
check(builds > 5, "pile: neighbour-list builds on the way: %d" % builds)
check_ranks_threads(pile_deck, "run 3000\n", serial, "pile")
# a restart is not bit-exact in LAMMPS (the pair style's and the old store's alike): to
# round-off, amplified by the pile (1e-8 here; with the springs lost at the restart, 0.3)
split, log = split_run(pile_deck, PILE, "pile-restart")
check("Resetting peratom fix info from restart file" in log, "pile: the springs were read back")
moved = largest_move(split, serial[0])
check(len(split) == len(grains) and moved < 1e-6,
      "pile split by a restart file: positions within %g of the serial run's" % moved)

# tan 17 deg = 0.3 > mu = 0.2 on the floor: the bottom layer slides on in x (the spheres do
# not spin, so they cannot roll), across the boundary between the two ranks, its springs
# on the wall at the friction cap
grains = lattice(random.Random(5), 2, 0.55, 1.1,
                 lambda rng: (rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), 0.0))
write_data("slide.data", (0.0, 4.8, 0.0, 4.8, 0.0, 6.0), grains)


def slide_laws(wall_id):
    return laws(wall_id, 0.2, "0.3 0 -1", "spheres fixed")


def slide_deck(np):
    return (head("ball.lslib", "slide.data", extra="processors %d 1 1" % np)
            + slide_laws("floor")
            + "thermo_style custom step ke f_floor[1] f_floor[3]\n%sthermo 1000\n" % THERMO_FULL)


serial, log1 = final_state(slide_deck(1) + "run 3000\n", "slide-serial")
check(len(serial[0]) == len(grains) and len(serial[1]) == len(grains),
      "slide: serial run wrote its state")
end = thermo(log1)[-1] if thermo(log1) else {}
# the floor's friction at its cap: mu = 0.2 of the load it carries, against the slide
near(end.get("f_floor[1]", 0.0), -0.2 * end.get("f_floor[3]", 0.0), rtol=0.05,
     msg="slide: the spheres slide on the floor: its friction force mu times its load")
check_ranks_threads(slide_deck, "run 3000\n", serial, "slide")
split, log = split_run(slide_deck, slide_laws("floor"), "slide-restart")
check("Resetting peratom fix info from restart file" in log,
      "slide: the springs were read back")
moved = largest_move(split, serial[0])
check(len(split) == len(grains) and moved < 1e-6,
      "slide split by a restart file: positions within %g of the serial run's" % moved)
lost, _ = split_run(slide_deck, slide_laws("floor2"), "slide-lost")
moved_lost = largest_move(lost, serial[0])
check(len(lost) == len(grains) and moved_lost > 100 * max(moved, 1e-9),
      "slide: the wall's springs lost at the restart (another wall ID): positions %g away"
      % moved_lost)
finish()
