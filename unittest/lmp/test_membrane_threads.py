"""Threads on the triaxial test give the serial answer, bit for bit (issue #23.1): the
membrane's styles too. The small specimen of triaxial_specimen.py runs the example's
in.triaxial (200 steps of consolidation, 400 of shearing) without threads and with LAMMPS's
OPENMP package (-sf omp -pk omp N: pair_style lsdem/omp, fix wall/lsdem/omp,
fix nve/lsdem/omp, fix membrane/lsdem/omp, bond_style lsdem/membrane/omp): on 1 rank with 2
and 3 threads the CSV (stresses, volume, the membrane's radial stress, every 100 steps) and
the SHEARED line (full precision) are those of the serial run; so are 2 ranks x 2 threads
those of 2 ranks x 1 thread (the membrane's bond and pressure sums are not order-free across
ranks, so ranks are compared with ranks). The log must name the threaded membrane styles
(else the test would compare the serial code with itself)."""
import os
import re

from lsdemtest import run_lmp, check, finish
from triaxial_specimen import make, shear_strain, DECK

VARS = dict(make(), ncons=200, epsmax=shear_strain(400), every=100)
# the styles in use, in the log
INFO = "info system fixes out log\n"


def run(name, np, nthreads):
    os.makedirs(name, exist_ok=True)
    deck = open(DECK).read().replace("\nrun             ${ncons}", "\n" + INFO + "run             ${ncons}")
    args = ["-sf", "omp", "-pk", "omp", nthreads] if nthreads else []
    rc, log = run_lmp(deck, np=np, vars=VARS, cwd=name, args=args)
    m = re.search(r"^SHEARED .*$", log, re.M)
    csv = open(os.path.join(name, "triaxial.csv")).read() if os.path.exists(
        os.path.join(name, "triaxial.csv")) else ""
    return (m.group(0) if m else None), csv, log


def threaded(log):
    return ("style = membrane/lsdem/omp" in log and "style = lsdem/membrane/omp" in log
            and "Last active /omp style is pair_style lsdem/omp" in log)


ref = run("serial", 1, 0)
check(ref[0] is not None and ref[1].count("\n") == 6, "the serial run sheared: %s" % ref[0])
for np, nthreads, base in ((1, 2, ref), (1, 3, ref)):
    name = "np%d-omp%d" % (np, nthreads)
    got = run(name, np, nthreads)
    check(threaded(got[2]), "%s: the log does not name the /omp membrane styles" % name)
    check(got[0] == base[0], "%s: %s\nserial: %s" % (name, got[0], base[0]))
    check(got[1] == base[1], "%s: the CSV differs from the serial run's" % name)
ranks = run("np2", 2, 0)
got = run("np2-omp2", 2, 2)
check(threaded(got[2]), "np2-omp2: the log does not name the /omp membrane styles")
check(got[0] == ranks[0] and got[1] == ranks[1],
      "2 ranks x 2 threads differ from 2 ranks:\n%s\n%s" % (got[0], ranks[0]))
finish()
