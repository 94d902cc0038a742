"""A run that fails on one rank of two loses nothing: the message and the lines written
before it reach rank 0's log, and dumps stay complete.

1. A grain owned by rank 1 goes unstable (fix nve/lsdem): all ranks stop together; rank 0's
   log has every thermo row before the failure and the message naming the grain, the step
   and the rank that found it; the dump's last frame is the last step before it (also
   with dump_modify flush no); no MPI_Abort. With 1 rank the same message, without the rank.
2. A stock LAMMPS error->one on rank 1 alone (a division by zero in an atom-style variable,
   evaluated for rank 1's grain only): rank 1 aborts at once; rank 0's log still has every
   line written before (it is line-buffered, also a log opened later by the log command; it
   used to come out empty), the dump written by rank 0 with flush no every frame before the
   error (rank 0 flushes when mpirun terminates it; the dump used to come out empty), and
   rank 1, which shows no output under -screen none, writes the message to its standard
   error.
(fix membrane/lsdem's torn-membrane stop is tested in test_membrane_lsdem.py.)"""
import contact_decks as cd
from lsdemtest import check, finish, run_lmp, thermo

lib = cd.sphere_library("ball.lslib", 0.5, 0.05, 200)
# two grains far apart along x, split by a 2 by 1 by 1 grid: grain 2 is rank 1's
cd.write_data("two.data", (-4, 4, -2, 2, -2, 2), [cd.Grain((-2, 0, 0)), cd.Grain((2, 0, 0))])
DECK = cd.head(lib, "two.data", boundary="f f f", extra="processors * 1 1") + """
pair_style lsdem
pair_coeff * * 1e4 1e4 0.5
fix nve all nve/lsdem
variable push atom %s
fix push all addforce v_push 0 0
timestep 0.001
thermo_style custom step fmax
thermo 10
dump d all custom 10 grains.dump id x y z
dump_modify d flush no
run 100
"""
KICK = '"(step==50)*(x>0)*1e9"'       # at step 50, a huge force on grain 2 only
DIVIDE = '"1/((x<0)+(step<50))"'      # from step 50, 1/0 for grain 2 only


def dump_steps(path):
    lines = open(path).read().splitlines()
    return [int(lines[k + 1]) for k, l in enumerate(lines) if l.startswith("ITEM: TIMESTEP")]


# ---- 1. instability on rank 1 --------------------------------------------------------------
for np in (1, 2):
    rc, out = run_lmp(DECK % KICK, np=np, log="unstable%d.log" % np, expect_fail=True)
    log = open("unstable%d.log" % np).read()
    rows = thermo(log)
    check(rc != 0, "np %d: the unstable run fails" % np)
    check([int(r["Step"]) for r in rows] == list(range(0, 51, 10)),
          "np %d: thermo rows 0..50 kept in the log: %s" % (np, [r["Step"] for r in rows]))
    check("ERROR: Fix nve/lsdem: grain 2 became unstable at step 51 with a runaway speed" in log,
          "np %d: the message names grain and step in rank 0's log:\n%s" % (np, log[-1500:]))
    check(("(found on rank 1)" in log) == (np == 2), "np %d: the finding rank is named only "
          "when there are several" % np)
    check("MPI_ABORT" not in out, "np %d: all ranks stop normally, no MPI_Abort" % np)
    check(dump_steps("grains.dump") == list(range(0, 51, 10)),
          "np %d: dump complete to step 50: %s" % (np, dump_steps("grains.dump")))

# ---- 2. a stock error->one on rank 1 alone -------------------------------------------------
# (also when the run writes to a log file opened after atom_style, by the 'log' command)
for name, switch in (("divide.log", ""), ("switched.log", "log switched.log\n")):
    rc, out = run_lmp((DECK % DIVIDE).replace("run 100", switch + "run 100"), np=2,
                      log="divide.log", expect_fail=True)
    log = open(name).read()
    check(rc != 0, "%s: division by zero on rank 1 fails the run" % name)
    check([int(r["Step"]) for r in thermo(log)] == list(range(0, 41, 10)),
          "%s: rank 0's log keeps the rows written before rank 1 aborted:\n%s"
          % (name, log[-800:]))
    check(dump_steps("grains.dump") == list(range(0, 41, 10)),
          "%s: dump (flush no) keeps the frames written before rank 1 aborted: %s"
          % (name, dump_steps("grains.dump")))
    # lmp runs with -screen none: rank 1 shows nothing, so the message goes to its stderr
    check(out.count("ERROR on proc 1: Divide by 0 in variable formula") == 1,
          "%s: rank 1's message on its standard error, once:\n%s" % (name, out[-800:]))

finish()
