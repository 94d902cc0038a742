"""Unload-reload cycles of examples/triaxial/in.triaxial (-var cycles N, report §3.5.5) on the
small test specimen of triaxial_specimen.py (consolidated 600 steps, sheared ten times faster
than the example, erate 5e-3: 3e-5 axial strain a step), 2 ranks, about 25 s.

Independent expectations, from the deck's definition of the bounds (the platen moves erate H0
dt a step, so axial strain eps_a = -ln(1 - D erate dt) after D steps down):
1. strain bounds (2 cycles at 0.6 % and 1.0 %, unloading by 0.2 %, holds of 20 steps, to
   1.2 %): the segments come in the order load, hold, unload, hold per cycle, then the final
   load; each peak is the first step at or beyond its strain (eps_a >= bound, less than one
   step's strain beyond), each turn the last step at or before peak - 0.2 %, each hold 20
   steps at constant strain; the run ends at epsmax; the rows' phi_deg is
   asin((sigma1 - sigma3)/(sigma1 + sigma3)) of their sigma1, sigma3 (the formula that gives
   45 deg at sigma1/sigma3 = 5.83; the core test test_measure checks 45 deg exactly at
   3 + 2 sqrt 2);
2. q bound (1 cycle at 1.0 %, unloading to cyc_q = 0.5 of the deviator at the peak, checked
   every 10 steps, holds of 40): unloading stops at the first check with qz <= the bound (the
   check before was above it), at a smaller strain, and the bound in cycles_state.in is 0.5
   times the peak's qz;
3. resume mid-cycle: the same q-bounded run with a checkpoint every 470 steps has one at step
   940, inside the hold after the peak (steps 932-972: the peak is 332 steps after the start
   of shearing at step 600). Resumed from it (-var resume shear.a.restart -var part .2, 2
   ranks), the run takes the peak's qz from cycles_state.in, turns at the uninterrupted run's
   step and ends at its step; every row of cycles.2.csv agrees with the uninterrupted run's
   row of that step to 1e-6 relative (measured: 9 digits equal for 100 steps after the
   restart, then ~1e-9; not bits: the restart re-sorts the atoms and the membrane's bond
   sums are not order-free, as lmp.triaxial_resume states)."""
import csv
import math
import os
import re

from lsdemtest import run_lmp, check, near, finish
from triaxial_specimen import make, DECK

ERATE, DT = 5.0e-3, 0.006
STEP = ERATE * DT
BASE = dict(make(), ncons=600, every=10, erate=ERATE, cyc_every=10)


def rows(path):
    return [{k: (v if k == "phase" else float(v)) for k, v in r.items()}
            for r in csv.DictReader(open(path))]


def segments(rs):
    """[(cycle, phase, first row, last row)] of consecutive rows."""
    out = []
    for r in rs:
        key = (int(r["cycle"]), r["phase"])
        if out and tuple(out[-1][:2]) == key:
            out[-1][3] = r
        else:
            out.append([key[0], key[1], r, r])
    return out


def step_strain(eps):
    """One platen step's axial strain at eps: d eps = STEP / (1 - D STEP) = STEP e^eps."""
    return STEP * math.exp(eps)


# 1. strain bounds
os.makedirs("strain", exist_ok=True)
rc, log = run_lmp(DECK, np=2, cwd="strain", vars=dict(
    BASE, epsmax=0.012, cycles=2, cyc_at=0.006, cyc_step=0.004, cyc_amp=0.002, cyc_hold=20))
step0 = int(re.search(r"variable step0 equal (\d+)", open("strain/shear_state.in").read()).group(1))
rs = rows("strain/cycles.csv")
seg = segments(rs)
check([(s[0], s[1]) for s in seg] == [(1, "load"), (1, "hold"), (1, "unload"), (1, "hold"),
                                      (2, "load"), (2, "hold"), (2, "unload"), (2, "hold"),
                                      (3, "load")], "segments: %s" % [(s[0], s[1]) for s in seg])
check(rs[0]["step"] == step0 + 10 and all(b["step"] > a["step"] for a, b in zip(rs, rs[1:])),
      "rows from the first check after step %d, steps increasing" % step0)
prev_end = step0
for k, peak in ((1, 0.006), (2, 0.010)):
    load, top, unload, bottom = [s for s in seg if s[0] == k]
    e = load[3]["eps_a"]
    check(peak <= e < peak + step_strain(e), "cycle %d peak at eps_a %.9g: bound %g" % (k, e, peak))
    t = unload[3]["eps_a"]
    check(peak - 0.002 - step_strain(t) < t <= peak - 0.002,
          "cycle %d turn at eps_a %.9g: bound %g" % (k, t, peak - 0.002))
    for hold, at in ((top, e), (bottom, t)):
        check(hold[3]["step"] - (load[3] if hold is top else unload[3])["step"] == 20,
              "cycle %d hold of 20 steps" % k)
        near(hold[3]["eps_a"], at, rtol=1e-8, msg="cycle %d hold at constant strain" % k)
    check(load[2]["step"] > prev_end and unload[3]["eps_a"] < top[3]["eps_a"],
          "cycle %d unloads after its peak" % k)
    prev_end = bottom[3]["step"]
near(rs[-1]["eps_a"], 0.012, atol=step_strain(0.012), msg="the final load ends at epsmax")
for r in rs:
    s1, s3 = r["sigma1"], r["sigma3"]
    near(r["phi_deg"], math.degrees(math.asin((s1 - s3) / (s1 + s3))), atol=2e-6,
         msg="step %d: phi_deg from sigma1, sigma3" % r["step"])
check(re.search(r"^SHEARED eps_a 0\.0120", log, re.M) is not None, "SHEARED line")

# 2. q bound, with checkpoints; 3. resumed from the one inside the hold after the peak
os.makedirs("q", exist_ok=True)
QVARS = dict(BASE, epsmax=0.012, cycles=1, cyc_at=0.01, cyc_q=0.5, cyc_hold=40, checkpoint=470)
rc, log = run_lmp(DECK, np=2, cwd="q", vars=QVARS)
full = rows("q/cycles.csv")
seg = segments(full)
check([(s[0], s[1]) for s in seg] == [(1, "load"), (1, "hold"), (1, "unload"), (1, "hold"),
                                      (2, "load")], "q segments: %s" % [(s[0], s[1]) for s in seg])
state = open("q/cycles_state.in").read()
peak_qz = float(re.search(r"variable cyc_peak1 equal (\S+)", state).group(1))
load, top, unload, bottom, reload = seg
near(peak_qz, load[3]["qz"], rtol=1e-8, msg="peak qz recorded")
bound = 0.5 * peak_qz
check(peak_qz > 0, "loaded before unloading: qz %g" % peak_qz)
checks = [r for r in full if r["phase"] == "unload"]
check(len(checks) >= 2 and checks[-1]["qz"] <= bound
      and all(r["qz"] > bound for r in [top[3]] + checks[:-1]),
      "unloading stops at the first check below %g: %s" % (bound, [r["qz"] for r in checks]))
check(unload[3]["eps_a"] < load[3]["eps_a"], "the platen went back up")
check(load[3]["step"] == 932 and top[3]["step"] == 972, "peak at 932, hold to 972: %d, %d"
      % (load[3]["step"], top[3]["step"]))
turn = int(re.search(r"variable cyc_turn1 equal (\d+)", state).group(1))
check(turn == unload[3]["step"], "turn recorded: %d" % turn)

rc, log2 = run_lmp(DECK, np=2, cwd="q", vars=dict(QVARS, resume="shear.a.restart", part=".2"),
                   log="log.2")
check(re.search(r"^RESUMED at step 940,", log2, re.M) is not None,
      "RESUMED line: %s" % re.findall(r"^RESUMED.*", log2, re.M))
part = rows("q/cycles.2.csv")
by_step = {r["step"]: r for r in full}
check(part and part[0]["step"] == 950 and part[-1]["step"] == full[-1]["step"],
      "resumed rows from step 950 to the uninterrupted run's end %d" % full[-1]["step"])
m = re.search(r"^CYCLE 1 unload to step (\d+)", log2, re.M)
check(m is not None and int(m.group(1)) == turn, "resumed turn at step %s" % (m and m.group(1)))
worst = 0.0
for r in part:
    ref = by_step.get(r["step"])
    if not check(ref is not None and ref["phase"] == r["phase"] and ref["cycle"] == r["cycle"],
                 "step %d: row and segment in the uninterrupted run" % r["step"]):
        continue
    for k, v in r.items():
        if k != "phase":
            near(v, ref[k], rtol=1e-6, atol=1e-9, msg="step %d %s: resumed" % (r["step"], k))
            if ref[k]:
                worst = max(worst, abs(v - ref[k]) / abs(ref[k]))
print("resumed vs uninterrupted: largest relative difference %.3g over %d rows" % (worst, len(part)))
finish()
