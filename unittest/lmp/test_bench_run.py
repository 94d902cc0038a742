"""bench/run.sh on a small scene folder in the Kawamoto/Tan layout (the benchmark a user points
at their own data). Independent expectations: its last line's us_per_grain_step is the run's
'Loop time' divided by steps x grains and node_tests_per_s the thermo rows' mean node lookups
(c_work[3]) times steps over the loop time, both recomputed here from the kept log; the
memory line's traffic is the same rate times its bytes per lookup (lines x 64), beside a
measured bandwidth and latency; the run leaves nothing in $TMPDIR unless --keep is given, and then says where its files are."""
import os
import re
import shutil
import subprocess

from lsdemtest import LMP, SHAPE_TOOL, check, finish, near, tan_scene, thermo

RUN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench", "run.sh")
STEPS, GRAINS = 40, 8

# eight grains (two shapes) on a 2x2x2 lattice of spacing 10 in a 20^3 box (voxel units):
# neighbours and walls overlap them at the start
tan_scene("scene", "ab" * (GRAINS // 2),
          [(5 + 10 * (k % 2), 5 + 10 * (k // 2 % 2), 5 + 10 * (k // 4)) for k in range(GRAINS)],
          [(0, 0, 0, 1), (0.6, 0, 0, 0.8), (0, 0.6, 0, 0.8), (0, 0, 0.6, 0.8)] * 2,
          box=(20, 20, 20))

shutil.rmtree("tmp", ignore_errors=True)  # an earlier run's kept files
os.makedirs("tmp")
env = dict(os.environ, TMPDIR=os.path.abspath("tmp"), LSDEM_LMP=LMP,
           LSDEM_BUILD_DIR=os.path.dirname(SHAPE_TOOL))


def bench(*extra):
    p = subprocess.run(["bash", RUN, "scene", "--steps", str(STEPS)] + list(extra), env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=300)
    check(p.returncode == 0, "bench/run.sh %s failed (%d): %s%s"
          % (" ".join(extra), p.returncode, p.stdout[-2000:], p.stderr[-2000:]))
    return p


p = bench()
check(os.listdir("tmp") == [], "a run without --keep leaves nothing in $TMPDIR: %s"
      % os.listdir("tmp"))

p = bench("--keep")
last = p.stdout.strip().splitlines()[-1]
m = re.fullmatch(r"us_per_grain_step=([\d.]+) node_tests_per_s=([\d.eE+-]+)", last)
check(m is not None, "last line is the headline figures: %r" % last)
k = re.search(r"files of this run kept in (\S+)", p.stderr)
check(k is not None and os.path.isdir(k.group(1)), "--keep says where the files are: %r"
      % p.stderr)
if m and k:
    log = open(os.path.join(k.group(1), "log.bench")).read()
    loop = re.findall(r"Loop time of ([\d.eE+-]+) on 1 procs for (\d+) steps with (\d+) atoms",
                      log)[-1]
    check(int(loop[1]) == STEPS and int(loop[2]) == GRAINS, "the run: %s" % (loop,))
    near(float(m.group(1)), float(loop[0]) / (STEPS * GRAINS) * 1e6, atol=0.0015,
         msg="us_per_grain_step = loop time / (steps x grains)")
    rows = thermo(log)
    lookups = sum(r["c_work[3]"] for r in rows) / len(rows)
    check(lookups > 0, "the scene's grains touch: %g node lookups per step" % lookups)
    near(float(m.group(2)), lookups * STEPS / float(loop[0]), rtol=1e-3,
         msg="node_tests_per_s = mean lookups per step x steps / loop time")
    t = re.search(r"memory: ([\d.eE+-]+) node lookups/s x (\d+) cache lines x 64 B = (\d+) B "
                  r"per lookup .*: ([\d.]+) GB/s", p.stdout)
    check(t is not None, "the lookups' memory traffic is printed: %r" % p.stdout[-800:])
    if t:
        near(float(t.group(1)), float(m.group(2)), rtol=1e-3, msg="the same lookup rate")
        check(int(t.group(3)) == 64 * int(t.group(2)), "bytes per lookup = lines x 64")
        near(float(t.group(4)), float(t.group(1)) * int(t.group(3)) * 1e-9, rtol=2e-3,
             atol=1e-3, msg="GB/s = lookups/s x bytes per lookup")
    b = re.search(r"streams ([\d.]+) GB/s read, ([\d.]+) GB/s copy .*one dependent miss "
                  r"([\d.]+) ns", p.stdout)
    check(b is not None and min(map(float, b.groups())) > 0,
          "this core's measured memory speed (bench/membw.c) is printed: %r" % p.stdout[-800:])
finish()
