"""Threads inside a rank give the serial answer, bit for bit (issue #23.1).

The pile of pile_deck.py (140 angular grains, friction history, node lists, five walls)
runs with LAMMPS's OPENMP package (-sf omp -pk omp N: pair_style lsdem/omp,
fix wall/lsdem/omp and fix nve/lsdem/omp share each rank's grains among N threads) on 1 rank with 1, 2 and 3
threads and on 2 ranks with 2 threads each: every grain's final state, the floor's load,
the contact counts and the specimen's stress tensor (compute stress/lsdem, which reads the
threads' contact lists) at every output step are those of the run without threads. So is
a shorter two-way run with a coordination cap (zcap: the count over all threads' contacts
scales the forces). The log must name the threaded styles (else the test would compare the
serial code with itself): the last active one, and the walls in `info fixes`."""
import re

from lsdemtest import check, finish
from pile_deck import STEPS, run, deck

STRESS = ("info            fixes out log\n"
          "compute         s all stress/lsdem volume 324\n"
          "thermo_style    custom step ke c_w[2] c_w[4] f_floor[3] c_s[1] c_s[3] c_s[4]\n"
          "thermo_modify   norm no format float %.17g\n")


def omp(n):
    return ["-sf", "omp", "-pk", "omp", n]


def stress_rows(full):
    return [(r["c_s[1]"], r["c_s[3]"], r["c_s[4]"]) for r in full]


def threaded(log_dir):
    log = open(log_dir + "/log.lammps").read()
    return (re.search(r"Last active /omp style is (pair_style lsdem/omp|fix nve/lsdem/omp)", log)
            and len(re.findall(r"style = wall/lsdem/omp", log)) == 5)


ref = run("serial", deck("oneway", STEPS, before_run=STRESS), 1)
check(ref[0] is not None and ref[1][-1][2] > 200, "the serial pile ran and piled up")
for np, nthreads in ((1, 1), (1, 2), (1, 3), (2, 2)):
    name = "np%d-omp%d" % (np, nthreads)
    atoms, rows, full = run(name, deck("oneway", STEPS, before_run=STRESS), np,
                            args=omp(nthreads))
    check(threaded(name), "%s: the log does not name the /omp styles" % name)
    check(atoms == ref[0], "%s: grains differ from the run without threads" % name)
    check(rows == ref[1], "%s: floor load or contact counts differ:\n%s\n%s"
          % (name, rows, ref[1]))
    if np == 1:  # one rank: the stress sums the same contacts in the same order
        check(stress_rows(full) == stress_rows(ref[2]), "%s: stress differs" % name)

ZCAP = deck("twoway", STEPS // 2).replace("pair_style lsdem mode twoway",
                                           "pair_style lsdem mode twoway zcap 3")
zref = run("zcap-serial", ZCAP, 1)
zthr = run("zcap-omp2", ZCAP, 1, args=omp(2))
check(zref[0] is not None and zthr[0] == zref[0] and zthr[1] == zref[1],
      "zcap 3: two threads differ from the run without threads")
finish()
