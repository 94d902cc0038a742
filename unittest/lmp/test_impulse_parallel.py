"""Impulse mode on any rank count and across restarts (fix impulse/lsdem, islands across
ranks, report §4.5).

140 angular grains fall into a box under strong gravity and pile up: islands of many grains
that span the ranks' sub-domains (found by label exchange through ghost communication,
solved on the rank holding most of their contacts). On 1, 2, 3 (uneven) and 4 ranks every
grain's position, velocity, angular velocity and orientation after 500 steps is the same,
bit for bit (each island is assembled in the order of global ids wherever it is solved),
and so are the fix's island counts, ETM iterations and wall corrections at every output
step (energies summed over ranks to round-off); with more than one rank some islands span
ranks and the label exchange takes rounds. A run stopped after 250 steps on 2 ranks and
continued from its restart file on 3 is the uninterrupted run: the resting contacts'
warm-start impulses (method split, the default) travel with their grains between ranks
and through the restart file. Threads (-sf omp: pair_style lsdem/impulse/omp shares each
rank's detection among them, fix wall/lsdem/omp each wall's detection of its grains) give
the same bits too: 1 rank with 2 threads, and with colours yes (the resting sweeps colour by
colour, shared by the threads) 1 rank with 3 threads and 2 ranks with 2 threads each against
a serial colours-yes run (the log must name the threaded pair style and the five walls'
threaded style, and the fix's value 46 that as many threads shared the pile's resting sweeps
with colours, one without)."""
import os
import re

from grain_decks import pile
from impulse_decks import header
from lsdemtest import run_lmp, thermo, check, near, finish

STEPS, HALF, EVERY = 500, 250, 50
pile()

SCENE = """fix floor all wall/lsdem plane 0 0 0 0 0 1 1.0e4 0 0.5
fix wx0 all wall/lsdem plane 0 0 0 1 0 0 1.0e4 0 0.5
fix wx1 all wall/lsdem plane 6 0 0 -1 0 0 1.0e4 0 0.5
fix wy0 all wall/lsdem plane 0 0 0 0 1 0 1.0e4 0 0.5
fix wy1 all wall/lsdem plane 0 6 0 0 -1 0 1.0e4 0 0.5
fix grav all gravity 100.0 vector 0 0 -1
fix imp all impulse/lsdem 0.5 0.5 damping 1.0 alpha 1 tolerance 1e-3 passes 3
timestep 1e-3
compute q all property/atom qw qx qy qz
thermo_style custom step ke f_imp[1] f_imp[2] f_imp[3] f_imp[4] f_imp[5] f_imp[6] f_imp[7] &
             f_imp[8] f_imp[10] f_imp[13] f_imp[20] f_imp[22] f_imp[23] f_imp[24] f_imp[25] &
             f_imp[46]
thermo_modify norm no format float %.17g
thermo {every}
"""
DUMP = ("dump d all custom {steps} final.dump id x y z vx vy vz omegax omegay omegaz c_q[1] "
        "c_q[2] c_q[3] c_q[4]\ndump_modify d sort id format float %.17g\n")
EXACT = ("f_imp[1]", "f_imp[2]", "f_imp[4]", "f_imp[5]", "f_imp[6]", "f_imp[7]", "f_imp[20]",
         "f_imp[22]", "f_imp[23]", "f_imp[24]", "f_imp[25]")


def deck(steps, restart=None, info=False, colours=False):
    text = header("pile.lslib", "pile.data") + SCENE.format(every=EVERY)
    if colours:
        text = text.replace("passes 3\n", "passes 3 colours yes\n")
    if info:  # the fixes' styles into the log (the walls' /omp style)
        text += "info fixes out log\n"
    if restart:
        return text + "run %d\nwrite_restart %s\n" % (steps, restart)
    return text + DUMP.format(steps=steps) + "run %d\n" % steps


def continued(steps):
    # the lines of header() after read_data: pair style and neighbor settings
    after = header("pile.lslib", "pile.data").split("read_data")[1].split("\n", 1)[1]
    return ("read_restart half.restart\n" + after + SCENE.format(every=EVERY)
            + DUMP.format(steps=STEPS) + "run %d\n" % steps)


def run(name, text, np, args=None):
    _, log = run_lmp(text, np=np, cwd=os.path.abspath(name), args=args)
    dump = os.path.join(os.path.abspath(name), "final.dump")
    atoms = open(dump).read().split("ITEM: ATOMS")[-1] if os.path.exists(dump) else None
    return atoms, thermo(log)


ref_atoms, ref = run("np1", deck(STEPS), 1)
if check(ref_atoms and len(ref) == STEPS // EVERY + 1, "the serial pile ran"):
    last = ref[-1]
    check(last["f_imp[2]"] > 100 and last["f_imp[22]"] > 100,
          "a pile worth testing: largest island %d grains, %d resting contacts"
          % (last["f_imp[2]"], last["f_imp[22]"]))
    check(all(r["f_imp[3]"] == 0 and r["f_imp[8]"] == 0 for r in ref),
          "one rank: no island spans ranks, no label exchange")
    check(max(r["f_imp[46]"] for r in ref) == 1, "no threads: the resting sweeps on one")
for np in (2, 3, 4):
    atoms, rows = run("np%d" % np, deck(STEPS), np)
    check(atoms == ref_atoms, "np=%d: grains differ from the serial run" % np)
    check(len(rows) == len(ref), "np=%d: thermo rows" % np)
    for r, s in zip(rows, ref):
        for col in EXACT:
            check(r[col] == s[col], "np=%d step %d: %s %r vs %r" % (np, r["Step"], col, r[col],
                                                                    s[col]))
        for col in ("KinEng", "f_imp[10]", "f_imp[13]"):
            near(r[col], s[col], rtol=1e-10, atol=1e-300,
                 msg="np=%d step %d: %s" % (np, r["Step"], col))
    cross = max(r["f_imp[3]"] for r in rows)
    rounds = max(r["f_imp[8]"] for r in rows)
    print("np=%d: up to %d islands span ranks, up to %d label-exchange rounds per pass"
          % (np, cross, rounds))
    check(cross > 0 and rounds >= 2, "np=%d: islands span ranks (%d), labels exchanged in %d "
          "rounds" % (np, cross, rounds))

# colours yes: the resting sweeps colour by colour (another order: its own serial run)
col_atoms, col_ref = run("np1-colours", deck(STEPS, colours=True), 1)
check(col_atoms and col_atoms != ref_atoms, "colours yes ran, and sweeps in another order")
check(max(r["f_imp[46]"] for r in col_ref) == 1, "colours yes, no threads: the sweeps on one")
for np, nthreads, colours in ((1, 2, False), (1, 3, True), (2, 2, True)):
    name = "np%d-omp%d%s" % (np, nthreads, "-colours" if colours else "")
    atoms, rows = run(name, deck(STEPS, info=True, colours=colours), np,
                      args=["-sf", "omp", "-pk", "omp", nthreads])
    log = open(os.path.join(os.path.abspath(name), "log.lammps")).read()
    check("pair_style lsdem/impulse/omp" in log, "%s: the threaded pair style ran" % name)
    check(len(re.findall(r"style = wall/lsdem/omp", log)) == 5,
          "%s: the walls' threaded style ran" % name)
    serial_atoms, serial = (col_atoms, col_ref) if colours else (ref_atoms, ref)
    check(atoms == serial_atoms, "%s: grains differ from the serial run" % name)
    check(len(rows) == len(serial) and all(r[col] == s[col] for r, s in zip(rows, serial)
                                           for col in EXACT), "%s: counters differ" % name)
    # with colours the pile's island is large enough for the threads to share its resting
    # sweeps (64 pairs per thread) on one rank at least once; without, one thread sweeps
    teams = max(r["f_imp[46]"] for r in rows)
    print("%s: up to %d threads shared an island's resting sweeps" % (name, teams))
    check(teams == (nthreads if colours else 1),
          "%s: the resting sweeps were shared by %d threads" % (name, teams))

# stopped on 2 ranks, continued from the restart on 3
run_lmp(deck(HALF, restart="half.restart"), np=2, cwd=os.path.abspath("restart"))
atoms, rows = run("restart", continued(STEPS - HALF), 3)
check(atoms == ref_atoms, "restart 2 -> 3 ranks: grains differ from the uninterrupted run")
if check(rows, "restarted run"):
    for col in EXACT:
        check(rows[-1][col] == ref[-1][col], "restart: last row %s %r vs %r"
              % (col, rows[-1][col], ref[-1][col]))
    near(rows[-1]["f_imp[13]"], ref[-1]["f_imp[13]"], rtol=1e-10,
         msg="restart: total dissipated energy carried over")
finish()
