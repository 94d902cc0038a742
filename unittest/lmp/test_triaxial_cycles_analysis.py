"""examples/triaxial/cycles.py (the loops of a cyclic run: secant modulus, loop energy,
damping ratio, residual volumetric strain) and plot.py --cycles on loops whose measures are
known in closed form.

1. An elliptic loop sampled at n = 2000 equal steps of t: eps = e0 + a cos t, qz = q0 +
   E a cos t - eta a sin t, eps_v = v0 + b (1 - cos t) ... unloading for t in (0, pi], the
   reload for t in (pi, 2 pi], then loading on beyond. The rows make a polygon inscribed in
   the ellipse by an affine map of the regular n-gon, so the loop energy is exactly
   (n/2) sin(2 pi/n) eta a^2 (the n-gon's area times |det|); the tips are at t = 0 and pi,
   so E_sec = E, W_e = E a^2 / 2 and D = (n/2) sin(2 pi/n) eta / (2 pi E) (eta / 2E as
   n grows, the linear viscoelastic damping ratio). To 1e-12 relative.
2. A polygon with holds: peak (1, 2.2), held to (1, 2), unloaded to (0.5, 0.5), held to
   (0.5, 0.7), reloaded in a straight line to (1.2, 2.3), which crosses eps = 1 at q = 0.7 +
   1.6 (0.5/0.7): loop energy = -(2 + 0.5)/2 0.5 + (0.7 + q_C)/2 0.5 = 0.075/7 exactly,
   E_sec = 1.5/0.5 = 3, residual eps_v interpolated the same way. To 1e-12.
3. The parts of a resumed run joined by step ("a.csv+b.csv"), an open last loop reported as
   open, plot.py --cycles writing cycles.png and loops.csv with one row per closed loop."""
import math
import os
import subprocess
import sys

from lsdemtest import HERE, check, finish, near

EXAMPLE = os.path.join(HERE, "..", "..", "examples", "triaxial")
sys.path.insert(0, EXAMPLE)
import cycles  # noqa: E402

HEADER = "step,cycle,phase,eps_a,eps_v,qz,p,sigma1,sigma3,phi_deg\n"


def write(path, rows):
    with open(path, "w") as f:
        f.write(HEADER)
        for step, k, phase, e, v, q in rows:
            f.write("%d,%d,%s,%.17g,%.17g,%.17g,1,1,1,0\n" % (step, k, phase, e, v, q))


# 1. the ellipse
n, e0, a, q0, E, eta, v0, b = 2000, 0.03, 0.004, 1.5, 120.0, 9.0, 0.01, 0.002
rows = [(0, 1, "load", e0 + a, v0, q0 + E * a)]   # the peak: t = 0
for i in range(1, 2 * n):
    t = 2 * math.pi * i / n
    e = e0 + a * math.cos(t) + (a * (t - 2 * math.pi) if t > 2 * math.pi else 0)
    q = q0 + E * a * math.cos(t) - eta * a * math.sin(t)
    phase, k = ("unload", 1) if i <= n // 2 else ("load", 2)
    rows.append((i, k, phase, e, v0 + b * (1 - math.cos(t)), q))
write("ellipse.csv", rows)
lp = cycles.loops(cycles.read("ellipse.csv"))
check(len(lp) == 1 and lp[0]["closed"], "one closed loop: %s" % [(x["cycle"], x["closed"]) for x in lp])
lp = lp[0]
w = 0.5 * n * math.sin(2 * math.pi / n) * eta * a * a
near(lp["loop_energy"], w, rtol=1e-12, msg="ellipse: loop energy")
near(lp["secant_modulus"], E, rtol=1e-12, msg="ellipse: secant modulus")
near(lp["elastic_energy"], 0.5 * E * a * a, rtol=1e-12, msg="ellipse: elastic energy")
near(lp["damping_ratio"], w / (2 * math.pi * E * a * a), rtol=1e-12, msg="ellipse: damping ratio")
near(lp["damping_ratio"], eta / (2 * E), rtol=1e-5, msg="ellipse: damping ratio ~ eta / 2E")
near(lp["residual_eps_v"], 0.0, atol=1e-15, msg="ellipse: closes at its own eps_v")
check(lp["step_top"] == 0 and lp["step_turn"] == n // 2 and lp["step_close"] == n,
      "ellipse: U, T, C at steps 0, %d, %d: %s" % (n // 2, n, (lp["step_top"], lp["step_turn"],
                                                              lp["step_close"])))

# 2. the polygon with holds (a second, open loop after it)
qc = 0.7 + 1.6 * 0.5 / 0.7
rows = [(10, 1, "load", 0.2, 0.0, 0.3), (20, 1, "load", 1.0, 0.004, 2.2),
        (30, 1, "hold", 1.0, 0.004, 2.0), (40, 1, "unload", 0.5, 0.006, 0.5),
        (50, 1, "hold", 0.5, 0.006, 0.7), (60, 2, "load", 1.2, 0.013, 2.3),
        (70, 2, "hold", 1.2, 0.013, 2.25), (80, 2, "unload", 1.0, 0.014, 1.0),
        (90, 2, "hold", 1.0, 0.014, 1.1), (100, 3, "load", 1.1, 0.015, 1.4)]
write("poly_a.csv", rows[:6])
write("poly_b.csv", [(45, 1, "unload", 0.5, 0.006, 0.5)] + rows[4:])   # resumed at step 45
joined = cycles.read("poly_a.csv+poly_b.csv")
check([r["step"] for r in joined] == [10, 20, 30, 40, 45, 50, 60, 70, 80, 90, 100],
      "parts joined by step: %s" % [r["step"] for r in joined])
lp = cycles.loops(joined)
check([(x["cycle"], x["closed"]) for x in lp] == [(1, True), (2, False)],
      "loops: %s" % [(x["cycle"], x["closed"]) for x in lp])
near(lp[0]["loop_energy"], 0.075 / 7, rtol=1e-12, msg="polygon: loop energy")
near(lp[0]["secant_modulus"], 3.0, rtol=1e-12, msg="polygon: secant modulus")
near(lp[0]["damping_ratio"], (0.075 / 7) / (4 * math.pi * 1.5 * 0.5 / 8), rtol=1e-12,
     msg="polygon: damping ratio")
near(lp[0]["residual_eps_v"], 0.006 + 0.007 * 0.5 / 0.7 - 0.004, rtol=1e-12,
     msg="polygon: residual eps_v")
check(lp[0]["step_top"] == 30 and lp[0]["step_turn"] == 45 and lp[0]["step_close"] == 60,
      "polygon: U after the hold, T the last unloading row, C on the reload")

# 3. plot.py --cycles
write("cycles.csv", rows)
p = subprocess.run(["/usr/bin/python3", os.path.join(EXAMPLE, "plot.py"), "--cycles", "cycles.csv"],
                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
check(p.returncode == 0 and "loop open" in p.stdout, "plot.py --cycles: %s" % p.stdout)
check(os.path.getsize("cycles.png") > 10000, "cycles.png written")
table = open("loops.csv").read().splitlines()
check(len(table) == 2 and table[0].startswith("cycle,eps_top,q_top"), "loops.csv: %s" % table)
near(float(table[1].split(",")[6]), 0.075 / 7, rtol=1e-9, msg="loops.csv loop energy")
finish()
