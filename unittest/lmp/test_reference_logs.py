"""Reference logs: every example with a run.sh ships log.<date>.<name>.g++.1 and .g++.2
(examples/make_reference_logs.sh makes them), each a complete lmp log of that example; and a
run of the short avatars example on 1 rank matches its .g++.1 log.

Tolerance: the same build on the same kind of machine gives the same bits, but another CPU
(libm code paths) or compiler changes the last bits, and a settling pack amplifies them
until individual grains take other paths. So the rows while the grains are still falling
apart (steps <= 3000: first contacts, no pile yet) must agree to 1e-6 relative, and the
settled state only as a pile: the same step count and, at the last row, the floor carrying
the weight in both (floor load / weight within 0.1 of each other)."""
import glob
import os
import re
import subprocess

from lsdemtest import HERE, LMP, SHAPE_TOOL, check, finish, thermo

EXAMPLES = os.path.normpath(os.path.join(HERE, "..", "..", "examples"))
names = sorted(os.path.basename(os.path.dirname(p))
               for p in glob.glob(os.path.join(EXAMPLES, "*", "run.sh")))
check(len(names) >= 5, "examples found: %s" % names)
for name in names:
    for np_ in (1, 2):
        logs = glob.glob(os.path.join(EXAMPLES, name, "log.*.%s.g++.%d" % (name, np_)))
        check(len(logs) == 1, "%s: %d reference logs for %d rank(s) (expected one log.<date>."
              "%s.g++.%d; make them with examples/make_reference_logs.sh)"
              % (name, len(logs), np_, name, np_))
        if len(logs) == 1:
            text = open(logs[0]).read()
            check(text.startswith("LAMMPS (") and "Total wall time" in text,
                  "%s: not a complete lmp log" % logs[0])
            procs = re.findall(r"on (\d+) procs? for", text)
            check(procs and all(int(p) == np_ for p in procs),
                  "%s: Loop lines say %s ranks" % (logs[0], procs))

# a fresh run of examples/avatars on 1 rank, into this test's folder (not the example's out/)
work = os.path.abspath("avatars")
p = subprocess.run(["bash", os.path.join(EXAMPLES, "avatars", "run.sh")], stdout=subprocess.PIPE,
                   stderr=subprocess.STDOUT, text=True,
                   env=dict(os.environ, NP="1", OUT=work, LSDEM_LMP=LMP,
                            LSDEM_SHAPE_TOOL=SHAPE_TOOL))
check(p.returncode == 0, "avatars run.sh failed:\n" + p.stdout[-2000:])
mine = thermo(open(os.path.join(work, "log.lammps")).read())
ref_path = glob.glob(os.path.join(EXAMPLES, "avatars", "log.*.avatars.g++.1"))
ref = thermo(open(ref_path[0]).read()) if ref_path else []
check(len(mine) == len(ref) and len(ref) > 5,
      "thermo rows: %d in this run, %d in the reference" % (len(mine), len(ref)))
early = 0
for a, b in zip(mine, ref):
    if a["Step"] > 3000:
        break
    early += 1
    for k, v in b.items():
        check(abs(a[k] - v) <= 1e-6 * max(abs(v), 1e-300) or a[k] == v,
              "step %d %s: %r here, %r in the reference" % (b["Step"], k, a[k], v))
check(early >= 3, "only %d early rows compared" % early)
if mine and ref:
    check(mine[-1]["Step"] == ref[-1]["Step"], "last step %d vs %d" % (mine[-1]["Step"],
                                                                    ref[-1]["Step"]))
    check(abs(mine[-1]["v_floorload"] - ref[-1]["v_floorload"]) < 0.1,
          "floor load / weight at the end: %.3f here, %.3f in the reference"
          % (mine[-1]["v_floorload"], ref[-1]["v_floorload"]))
finish()
