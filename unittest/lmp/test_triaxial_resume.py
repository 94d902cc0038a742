"""Checkpointed shearing and resume of examples/triaxial/in.triaxial (-var checkpoint N,
-var resume FILE, -var part SUFFIX), the long runs' safety net (bench/specimen.sh --full).

A small specimen (80 random grains of d ~ 16 px, packed loose by in.prepare, a double-layer
membrane from lsdem-shape membrane) is consolidated (300 steps) and sheared (900 steps) on 2
ranks with a restart every 300 shearing steps. Independent expectation: the uninterrupted run
itself. A second run resumes from the checkpoint at step 900 on 1 rank (a different rank count
as well) and must end in the same state: the SHEARED line and every CSV row after the resumed
step agree to 1e-6 (contact sums are order-free; the membrane's bond forces are not: 1e-13 at
the step of the restart, ~1e-8 in q after 300 steps on another rank count),
psi_deg of the first row excepted (compute dilatancy/lsdem differences the strains of the
previous row, which the resumed run did not see), nan and nan alike in the band columns (no
plane). The band columns: no plane at the first row (no grain has turned since shearing
began: the band's indicator is the rotation since then, not since the deck's start), a dip
in [0, 90] deg and a thickness >= 0 where there is one. The resumed run writes triaxial.2.csv and
dump.triaxial.2 and leaves the first run's files as they were; its first CSV row repeats the
checkpoint's step. A resume from a missing file stops with a message before anything is
written. Runs in about 15 s."""
import csv
import math
import os
import re

from lsdemtest import run_lmp, check, near, finish
from triaxial_specimen import make, shear_strain, DECK

VARS = dict(make(), ncons=300, epsmax=shear_strain(900), every=100, checkpoint=300)


def sheared(log):
    m = re.search(r"^SHEARED (.*)$", log, re.M)
    w = m.group(1).split() if m else []
    return {w[i]: float(w[i + 1]) for i in range(0, len(w) - 1, 2)}


def rows(path):
    return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(path))]


rc, log1 = run_lmp(DECK, np=2, vars=VARS, log="log.full")
full = rows("triaxial.csv")
end1 = sheared(log1)
check(len(full) == 10 and end1, "uninterrupted run: %d CSV rows, SHEARED %s" % (len(full), end1))
check(os.path.exists("shear.a.restart") and os.path.exists("shear.b.restart"),
      "checkpoints written")
state = open("shear_state.in").read()
check("variable step0 equal 300" in state, "shear_state.in: %r" % state)
before = {f: os.path.getmtime(f) for f in ("triaxial.csv", "dump.triaxial", "consolidated.restart")}

# resume from the checkpoint of step 900 (shear.b: steps 600 a, 900 b, 1200 a) on 1 rank
rc, log2 = run_lmp(DECK, np=1, vars=dict(VARS, resume="shear.b.restart", part=".2"), log="log.2")
check(re.search(r"^RESUMED at step 900, shearing to step 1200", log2, re.M) is not None,
      "RESUMED line: %s" % re.findall(r"^RESUMED.*", log2, re.M))
end2 = sheared(log2)
for k in ("eps_a", "eps_v", "q", "phi"):
    near(end2.get(k, float("nan")), end1[k], rtol=1e-6, atol=1e-12, msg="SHEARED %s" % k)
part = rows("triaxial.2.csv")
check(len(part) == 4, "resumed CSV rows: %d (steps 900..1200)" % len(part))
near(part[0]["eps_a"], full[6]["eps_a"], rtol=1e-8, msg="first resumed row at the checkpoint")
for i, (a, b) in enumerate(zip(part[1:], full[7:])):
    for k in a:
        if k == "psi_deg" and i == 0:
            continue
        if math.isnan(a[k]) and math.isnan(b[k]):   # the band columns without a plane
            continue
        near(a[k], b[k], rtol=1e-6, atol=1e-9, msg="row %d, %s: resumed vs uninterrupted" % (7 + i, k))
# the band columns: grains rotated since shearing began (none at its first row: no plane)
check(math.isnan(full[0]["band_dip"]) and math.isnan(full[0]["band_thickness"]),
      "no band at the start of shearing: %s" % full[0])
planes = [r for r in full if not math.isnan(r["band_dip"])]
check(planes and all(0 <= r["band_dip"] <= 90 and r["band_thickness"] >= 0 for r in planes),
      "band dip and thickness once grains turn: %s" % [(r["band_dip"], r["band_thickness"])
                                                       for r in full])
check(os.path.exists("dump.triaxial.2"), "the resumed run's dump")
check(all(os.path.getmtime(f) == t for f, t in before.items()),
      "the first run's CSV, dump and consolidated.restart untouched")

# a missing restart file: a message, nothing written
rc, log3 = run_lmp(DECK, np=1, vars=dict(VARS, resume="nofile", part=".3"), log="log.3",
                   expect_fail=True)
check(rc != 0 and "-var resume nofile: no such restart file" in log3, "missing file: %s" % log3[-400:])
check(not os.path.exists("triaxial.3.csv"), "nothing written by the refused resume")
finish()
