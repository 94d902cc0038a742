"""bench/impulse.sh on a small container release (40 grains, 0.03 s, impulse at dt x 1 and
x 2 and at x 2 on two ranks). Independent expectations: each CSV row is what the run's own
files say (steps and loop time of its log, mound height and spread recomputed here from its
dump, speed-up = the penalty run's loop time over the run's); the impulse runs take 1 and
1/2 of the penalty run's steps; the two-rank run is the one-rank run, bit for bit; the plots
are written; a bad option is refused."""
import csv
import math
import os
import re
import subprocess

from lsdemtest import SHAPE_TOOL, check, finish, near, script_refuses

RUN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench", "impulse.sh")
env = dict(os.environ, LSDEM_BUILD_DIR=os.path.dirname(SHAPE_TOOL))
p = subprocess.run(["bash", RUN, "out", "--grains", "40", "--time", "0.03", "--fill-time",
                    "0.02", "--muls", "1 2", "--np2", "2"], env=env, stdout=subprocess.PIPE,
                   stderr=subprocess.PIPE, text=True, timeout=900)
check(p.returncode == 0, "impulse.sh failed (%d): %s%s" % (p.returncode, p.stdout[-2000:],
                                                           p.stderr[-2000:]))


def last_frame(path):
    text = open(path).read().split("ITEM: ATOMS")[-1].splitlines()
    cols = text[0].split()
    return [dict(zip(cols, map(float, ln.split()))) for ln in text[1:] if ln.strip()]


def pct(vals, q):
    v = sorted(vals)
    pos = (len(v) - 1) * q / 100.0
    lo = int(pos)
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (pos - lo)


rows = {r["run"]: r for r in csv.DictReader(open("out/impulse.csv"))}
tags = ["penalty", "impulse_x1", "impulse_x2", "impulse_x2_np2"]
check(sorted(rows) == sorted(tags), "one row per run: %s" % sorted(rows))
loops = {}
for t in tags:
    m = re.search(r"Loop time of ([\d.e+-]+) on (\d+) procs for (\d+) steps",
                  open("out/log.%s" % t).read())
    loops[t] = (float(m.group(1)), int(m.group(2)), int(m.group(3)))
    check(int(rows[t]["steps"]) == loops[t][2] and int(rows[t]["ranks"]) == loops[t][1],
          "%s: steps and ranks from its log" % t)
    near(float(rows[t]["loop s"]), loops[t][0], rtol=1e-3, msg="%s: loop time from its log" % t)
    use = re.search(r"([\d.]+)% CPU use", open("out/log.%s" % t).read()).group(1)
    near(float(rows[t]["CPU use %"]), float(use), atol=0.5, msg="%s: CPU use from its log" % t)
    grains = last_frame("out/mound_%s.dump" % t)
    near(float(rows[t]["height"]), pct([g["z"] for g in grains], 99), atol=1e-3,
         msg="%s: height from its dump" % t)
    near(float(rows[t]["spread"]), pct([math.hypot(g["x"], g["y"]) for g in grains], 95),
         atol=1e-3, msg="%s: spread from its dump" % t)
    near(float(rows[t]["speed-up"]), loops["penalty"][0] / loops[t][0], rtol=0.02, atol=0.01,
         msg="%s: speed-up" % t)
check(loops["impulse_x1"][2] == loops["penalty"][2] and
      abs(2 * loops["impulse_x2"][2] - loops["penalty"][2]) <= 1, "steps at dt x 1 and x 2")
check(open("out/mound_impulse_x2.dump").read() == open("out/mound_impulse_x2_np2.dump").read(),
      "two ranks give the one-rank run's grains")
check(os.path.getsize("out/impulse_error.png") > 10000, "the error plot is written")
check(os.path.getsize("out/impulse_mounds.png") > 10000, "the renderings are written")

script_refuses(RUN, ["--muls", "1 0"], env, "--muls needs positive integers", "bad")

# bench/impulse_settled.sh from the x2 run's mound: both methods 5 steps at the penalty run's
# step; its figures are its logs' loop times and their ratio
SETTLED = os.path.join(os.path.dirname(RUN), "impulse_settled.sh")
p = subprocess.run(["bash", SETTLED, "out", "--from", "impulse_x2", "--steps", "5", "--rounds",
                    "1"], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                   timeout=300)
check(p.returncode == 0, "impulse_settled.sh failed (%d): %s%s" % (p.returncode,
                                                                   p.stdout[-2000:],
                                                                   p.stderr[-2000:]))
dt_penalty = re.search(r"^timestep\s+([\d.e+-]+)$", open("out/log.penalty").read(), re.M).group(1)
settled = {}
for method in ("penalty", "impulse"):
    log = open("out/log.settled_%s" % method).read()
    check(re.search(r"^read_data\s+mound_impulse_x2\.data$", log, re.M) is not None,
          "%s: starts from the x2 run's mound" % method)
    check(re.search(r"^timestep\s+%s$" % re.escape(dt_penalty), log, re.M) is not None,
          "%s: at the penalty run's step %s" % (method, dt_penalty))
    m = re.search(r"Loop time of ([\d.e+-]+) on 1 procs for 5 steps", log)
    check(m is not None, "%s: 5 steps on one rank" % method)
    settled[method] = float(m.group(1))
line = [ln for ln in p.stdout.splitlines() if "round 1:" in ln]
m = re.search(r"penalty ([\d.e+-]+) s, impulse ([\d.e+-]+) s, impulse/penalty ([\d.]+)",
              line[0] if line else "")
check(m is not None, "a line per round: %s" % p.stdout[-500:])
if m:
    near(float(m.group(1)), settled["penalty"], rtol=1e-6, msg="penalty time from its log")
    near(float(m.group(2)), settled["impulse"], rtol=1e-6, msg="impulse time from its log")
    near(float(m.group(3)), settled["impulse"] / settled["penalty"], atol=0.006,
         msg="the ratio of the two")
script_refuses(SETTLED, ["--steps", "0"], env, "--steps needs a positive integer", "bad")
finish()
