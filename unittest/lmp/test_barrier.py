"""The barrier test (examples/barrier: make_scene.sh, in.barrier, barrier.py), short decks.

A 0.1-mass level-set cube strikes a clamped hexagonal net (2 x 2, K = 5) with kinetic
energy 0.45 and rebounds. The energy is E = kinetic (translation + rotation, cube and free
balls) + bond energy (compute pe bond) + gravitational energy (fix gravity); W is the work
of the bonds' damping forces, measured by fix net/lsdem (output 8: the integral of the
damping power). Contact spring energy is not computed by pair_style lsdem, so the balance
is checked at the samples at which the cube touches nothing (before contact and after it
left the net: contacts = 0); the contacts are elastic here (cn 0, mu 0).
1. No damping at all, no gravity: E(t) = E(0) within 1 % of the impact energy at every
   sample without contact, after the net has taken up more than half of it (the check
   sees the energy go through the net and come back).
2. Bond damping (C = 0.1), no gravity: E(t) + W(t) = E(0) within 1 %, with W more than
   5 % of the impact energy (leaving W out would fail the 1 %); on 2 ranks W is the same
   within 1e-9 (the bond energy too: sums over ranks), the cube's motion, the anchors'
   reaction and the net's deflection and strain the same bits as printed.
3. No damping, gravity 9.81 (ETAG's vertical drop, the net unsettled): the same with the
   gravitational energy, within 1 %.
4. Momentum: the anchors' reaction (fix net/lsdem outputs 1-3) integrated over time equals
   the change of the momentum of the cube and the free balls along z within 1 % (the
   anchors are the only external force without gravity).
5. Figures (barrier.py): first contact from the cube's velocity, braking time ends within
   10 % of the time of the net's largest deflection (the cube stops when the net does),
   no bond broken.
6. Impulse method (fix impulse/lsdem, 5 times the step, restitution 0.5): the cube is
   braked and rebounds, the figures are those of the penalty run within 15 % (braking
   time, largest deflection), and the energy the collisions took (the residual) is >= 0
   and below the impact energy.
7. Statics (ETAG's drop as the example runs it: the net settled under its weight first,
   contact damping and friction, then quieted down): at rest the anchors carry the weight
   of the cube and of the free balls within 0.5 %, horizontally less than 0.5 % of it (the
   cube still creeps: kinetic energy ~1e-6 of the impact's); the cube rests on
   the net (residual deflection > 0)."""
import os
import sys

from lsdemtest import run_lmp, check, near, finish, HERE

EX = os.path.normpath(os.path.join(HERE, os.pardir, os.pardir, "examples", "barrier"))
sys.path.insert(0, EX)
import barrier  # noqa: E402

import subprocess  # noqa: E402

DECK = os.path.join(EX, "in.barrier")
BASE = {"g": 0, "settle": 0, "cn": 0, "mu": 0, "every": 1, "nsteps": 4000, "nrest": 0}


def scene(name, damp):
    env = dict(os.environ)
    p = subprocess.run(["bash", os.path.join(EX, "make_scene.sh"), name, "2", "0.1", "5",
                        str(damp)], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True)
    check(p.returncode == 0, "make_scene.sh failed: %s" % p.stdout)
    return os.path.abspath(name)


def run(folder, np=1, **vars):
    v = dict(BASE)
    v.update(vars)
    run_lmp(DECK, np=np, vars=v, cwd=folder)
    rows = barrier.read(os.path.join(folder, "barrier.csv"))
    return rows, barrier.figures(rows)


def balance(rows, f, what, rebound=True):
    """worst |E + W - E(0)| / E_impact over the samples without contact"""
    e0 = barrier.energy(rows[0])
    n0 = barrier.first_contact(rows)
    free = [r for r in rows if r["contacts"] == 0]
    after = [r for r in rows[n0:] if r["contacts"] == 0]
    check(len(after) > 100, "%s: the cube should have left the net (%d samples without "
          "contact after the first contact)" % (what, len(after)))
    check(not rebound or rows[-1]["vz"] > 0, "%s: the cube should rebound, vz %g" % (what, rows[-1]["vz"]))
    worst = max(abs(barrier.energy(r) + r["w_bond_damping"] - e0) for r in free)
    rel = worst / f["E_impact"]
    print("%s: balance within %.4f %% over %d samples without contact" % (what, 100 * rel,
                                                                        len(free)))
    check(rel < 0.01, "%s: energy balance off by %.3f %% of the impact energy" % (what,
                                                                                 100 * rel))
    return rel


# 1. conservative
plain = scene("plain", 0)
rows, f = run(plain)
near(f["E_impact"], 0.45, 0.01, msg="impact energy")
check(f["energy"]["peak_bond"] > 0.5 * f["E_impact"], "the net took up only %g of %g"
      % (f["energy"]["peak_bond"], f["E_impact"]))
check(rows[-1]["w_bond_damping"] == 0.0, "damping work %g without damping"
      % rows[-1]["w_bond_damping"])
balance(rows, f, "no damping")

# 4. momentum: integral of R_z dt against the change of momentum (trapezoid, every step)
imp = sum(0.5 * (a["rz"] + b["rz"]) * (b["time"] - a["time"]) for a, b in zip(rows, rows[1:]))
M = 0.1
dp = (M * rows[-1]["vz"] + rows[-1]["pz_net"]) - (M * rows[0]["vz"] + rows[0]["pz_net"])
print("momentum: integral of R_z %.6f, change of momentum %.6f" % (imp, dp))
check(abs(imp - dp) < 0.01 * abs(dp), "anchor impulse %g against momentum change %g"
      % (imp, dp))

# 5. figures
check(f["t_contact"] is not None and 0 < f["t_contact"] < 0.01,
      "first contact at %s (the cube starts 0.01 above the net at speed 3)" % f["t_contact"])
check(f["braking_time"] is not None and f["braking_time"] > 0, "no braking time")
check(abs(f["t_stop"] - f["t_max_deflection"]) < 0.1 * f["braking_time"],
      "the cube stops at %g, the net deflects most at %g" % (f["t_stop"],
                                                             f["t_max_deflection"]))
check(f["bonds_broken"] == 0, "bonds broke")
check(f["anchor_peak"] > 0 and f["max_strain"] > 0.0526, "anchor peak %g, strain %g"
      % (f["anchor_peak"], f["max_strain"]))
penalty = f

# 2. bond damping
damped = scene("damped", 0.1)
rows, f = run(damped)
w = rows[-1]["w_bond_damping"]
check(w > 0.05 * f["E_impact"], "damping work %g is not > 5 %% of %g" % (w, f["E_impact"]))
balance(rows, f, "bond damping")
# the same on 2 ranks (the bonds across the ranks' boundary counted once): the work within
# round-off, the rest to the bit
rows2, f2 = run(damped, np=2)
w2 = rows2[-1]["w_bond_damping"]
near(w2, w, 1e-9, msg="damping work on 2 ranks against 1")
check(len(rows2) == len(rows) and all(a[k] == b[k] for a, b in zip(rows, rows2)
                                      for k in ("z", "vz", "rz", "height", "max_strain")),
      "the 2-rank run differs from the 1-rank run")
check(all(abs(a["ebond"] - b["ebond"]) <= 1e-9 * a["ebond"] for a, b in zip(rows, rows2)),
      "bond energy on 2 ranks (a sum over ranks: round-off only)")

# 3. gravity
rows, f = run(plain, g=9.81, nsteps=5000)
check(rows[-1]["egrav"] != rows[0]["egrav"], "gravity did no work")
balance(rows, f, "gravity", rebound=False)    # it flew up and falls back

# 6. impulse
rows, f = run(plain, method="impulse", dt=1e-3, nsteps=800, mu=0.3)
check(f["braking_time"] is not None, "impulse: the cube was not braked")
if f["braking_time"] is not None:
    for key in ("braking_time", "max_deflection"):
        check(abs(f[key] - penalty[key]) < 0.15 * penalty[key], "impulse %s %g, penalty %g"
              % (key, f[key], penalty[key]))
    d = f["energy"]["other_dissipated_residual"]
    check(-0.01 * f["E_impact"] < d < f["E_impact"], "impulse: collisions took %g of %g"
          % (d, f["E_impact"]))
print("impulse:", barrier.report(f))

# 7. statics after the drop
rows, f = run(plain, g=9.81, settle=3000, cn=0.01, mu=0.3, every=50, nsteps=3000,
              nrest=12000)
nfree = sum(1 for l in open(os.path.join(plain, "net.data")).read().split("Atoms")[1]
            .split("Bonds")[0].strip().splitlines() if len(l.split()) > 3 and l.split()[1] == "2")
weight = (0.1 + nfree * 1e-4) * 9.81
print("statics: %d free balls, weight %.6f, anchors %s, kinetic %.2g" % (nfree, weight,
                                                                          f["anchor_final"],
                                                                          f["ke_last"]))
check(f["quieted"] and f["ke_last"] < 1e-5 * f["E_impact"], "not at rest: kinetic %g" % f["ke_last"])
near(f["anchor_final"][2], weight, 0.005, msg="anchors' vertical reaction against the weight")
check(abs(f["anchor_final"][0]) + abs(f["anchor_final"][1]) < 0.005 * weight,
      "horizontal reaction %s" % f["anchor_final"][:2])
check(f["residual_deflection"] > 0.01, "residual deflection %g" % f["residual_deflection"])

finish()
