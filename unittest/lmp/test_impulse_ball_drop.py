"""Impulse mode, a ball dropped on a plane (fix impulse/lsdem, fix wall/lsdem).

A sphere of radius 0.1 released from rest with its lowest point h0 = 1 above a plane
(gravity 9.81) rebounds to e^2 h0 (Stronge's hypothesis, report eq 4.1: the energy released
is e^2 times the energy absorbed) within 1 % for e = 1, 0.65 and 0.3; the impact is one ETM
collision with the wall (approach far above the resting speed). With e = 0.3 and a coarse
time step the bounces die out and the ball then rests on the plane: it neither sinks into it
nor jitters (the wall correction of resting contact, report §4.4.1). A ball placed 0.01 deep
into the plane (a start from a penalty run's overlaps) is lifted out no faster than a fall
through the overlap, sqrt(2 g 0.01), not thrown off at 0.01 / dt, and is out within a few
hundred steps."""
import math
import os

from impulse_decks import floor_drop, header, library
from lsdemtest import run_lmp, thermo, check, near, finish

R, H0, G = 0.1, 1.0, 9.81
LIB = library("ball.lslib", "sphere", R, nodes=20, analytic=True)
with open("ball.data", "w") as f:
    f.write("ball\n\n1 atoms\n1 atom types\n\n-1 1 xlo xhi\n-1 1 ylo yhi\n-0.5 2 zlo zhi\n\n"
            "Atoms # lsdem\n\n1 1 1 1.0 0 0 %r 1 0 0 0\n" % (R + H0))


def deck(e, dt, steps, every):
    return (header(LIB, "ball.data")
            + "fix floor all wall/lsdem plane 0 0 0 0 0 1 1.0e4 0 0\n"
            + "fix grav all gravity %r vector 0 0 -1\n" % G
            + "fix imp all impulse/lsdem %r 0.0\n" % e
            + "timestep %r\nvariable z equal z[1]\nvariable vz equal vz[1]\n" % dt
            + "thermo_style custom step v_z v_vz f_imp[1] f_imp[7]\n"
            + "thermo_modify format float %%.15g\nthermo %d\nrun %d\n" % (every, steps))


for e in (1.0, 0.65, 0.3):
    _, log = run_lmp(deck(e, 5e-5, 20000, 10), cwd=os.path.abspath("e%g" % e))
    rows = thermo(log)
    bounce = next((k for k in range(1, len(rows))
                   if rows[k - 1]["v_vz"] < 0 and rows[k]["v_vz"] > 0), None)
    if not check(bounce is not None, "e = %g: the ball never bounced" % e):
        continue
    top = next((k for k in range(bounce, len(rows)) if rows[k]["v_vz"] <= 0), len(rows) - 1)
    apex = max(r["v_z"] for r in rows[top - 1:top + 2]) - R  # the apex row and its neighbours
    print("e = %.2f: rebound %.6f, e^2 h0 = %.6f (ratio %.5f)" % (e, apex, e * e * H0,
                                                                   apex / (e * e * H0)))
    near(apex, e * e * H0, rtol=0.01, msg="e = %g: rebound height against e^2 h0" % e)

# comes to rest: after 2000 steps of 1e-3 the ball sits on the plane within the depth a
# resting grain sinks by in one step, g dt^2, and stays there
_, log = run_lmp(deck(0.3, 1e-3, 3000, 10), cwd=os.path.abspath("rest"))
late = [r for r in thermo(log) if r["Step"] >= 2000]
zs = [r["v_z"] for r in late]
check(late and min(zs) > R - 2 * G * 1e-6 and max(zs) < R + 2 * G * 1e-6,
      "the ball at rest stays on the plane: z in [%.9g, %.9g], expected %g +- %g"
      % (min(zs), max(zs), R, 2 * G * 1e-6))
check(all(abs(r["v_vz"]) < 2 * G * 1e-3 for r in late),
      "the ball at rest does not jitter: |vz| up to %g" % max(abs(r["v_vz"]) for r in late))
# placed 0.01 into the plane, dt 1e-4: d / dt would be 100, the resting speed is 2 g dt
with open("sunk.data", "w") as f:
    f.write("ball\n\n1 atoms\n1 atom types\n\n-1 1 xlo xhi\n-1 1 ylo yhi\n-0.5 2 zlo zhi\n\n"
            "Atoms # lsdem\n\n1 1 1 1.0 0 0 %r 1 0 0 0\n" % (R - 0.01))
deck = floor_drop(LIB, "sunk.data", 0.3, 1e-4, 3000, g=G)
_, log = run_lmp(deck, cwd=os.path.abspath("sunk"))
rows = thermo(log)
if check(rows, "sunk ball ran"):
    fastest = max(r["v_vz"] for r in rows)
    out = next((r["Step"] for r in rows if r["v_z"] >= R - 1e-6), None)
    cap = math.sqrt(2 * G * 0.01)
    print("sunk ball: fastest lift %.4g (sqrt(2 g d) %.4g, d / dt 100), out at step %s"
          % (fastest, cap, out))
    check(fastest <= cap * (1 + 1e-6), "lifted out no faster than a fall through the overlap")
    check(out is not None and out < 1000, "out of the plane within 1000 steps")
finish()
