"""Density-controlled specimen preparation: examples/triaxial/in.prepare.

80 small random sand-like grains (lsdem-shape random, d ~ 16 px) are packed in a rigid
cylindrical mould three ways:
1. loose: jammed at the test's friction (mu_prep 0.6, densify 0);
2. to a requested void ratio halfway between the loose state and the densest: the friction
   is lowered from 0.6 step by step until e <= e_target (densify 1, e_target);
3. densest: frictionless from the start (mu_prep 0, densify 1).
Checks: the loose, targeted and dense void ratios come in that order, far enough apart; the
target is reached (PREPARED ... reached 1) within 0.03 below it; every PREPARED solid
fraction (solids from the masses over the mould volume pi R^2 H, H the platen height) agrees
within 2 % with an independent measure, lsdem-shape voids (a lattice at 0.5 px tested against
each grain's level set at its written pose, over the same cylinder; at these grains' R/h ~ 8
the level set's zero contour holds 0.8 % less volume than the mass properties, and contact
overlaps count once), and every grain is inside the mould. Runs in about 10 s."""
import os
import re

from lsdemtest import run_lmp, check, near, finish, shape_tool

HERE = os.path.dirname(os.path.abspath(__file__))
DECK = os.path.join(HERE, "..", "..", "examples", "triaxial", "in.prepare")
R = 32.0
RHO = 2.65e-3

shape_tool("random", "g.lslib", "--count", 4, "--size", 16, "--size-spread", 0.1,
           "--elongation", 0.75, "--flatness", 0.75, "--angularity", 0.12, "--seed", 3,
           "--nodes", 150, "--spacing", 1.0)
out = shape_tool("pack", "g.lslib", "packed.data", "--count", 80, "--cylinder", R - 1, 280,
                 "--density", RHO, "--seed", 5)
check("80 of 80" in out, "pack placed all grains: %s" % out)


def prepare(tag, **v):
    """Run in.prepare in folder tag; returns the PREPARED fields and the lattice measure."""
    os.makedirs(tag, exist_ok=True)
    for f in ("g.lslib", "packed.data"):
        if not os.path.exists(os.path.join(tag, f)):
            os.symlink(os.path.abspath(f), os.path.join(tag, f))
    vars = {"lib": "g.lslib", "data": "packed.data", "R": R, "sigma_prep": 0.2,
            "nprep": 2000, "nround": 500, "rho": RHO}
    vars.update(v)
    rc, log = run_lmp(DECK, vars=vars, cwd=tag)
    m = re.search(r"^PREPARED (.*)$", log, re.M)
    if not check(m is not None, "%s: no PREPARED line" % tag):
        return None
    w = m.group(1).split()
    p = {w[i]: float(w[i + 1]) for i in range(0, len(w) - 1, 2)}
    # grains only (no velocities) for the lattice measure, as run.sh does
    text = open(os.path.join(tag, "sample.data")).read().split("\nVelocities")[0]
    open(os.path.join(tag, "grains.data"), "w").write(text + "\n")
    lat = shape_tool("voids", "g.lslib", "grains.data", "--cylinder", R, 0, p["height"],
                     "--spacing", 0.5, cwd=tag)
    mm = re.search(r"solid_fraction (\S+) void_ratio (\S+)", lat)
    check(mm is not None, "%s: voids printed %r" % (tag, lat))
    p["e_lattice"] = float(mm.group(2)) if mm else float("nan")
    # every grain centre inside the mould
    atoms = text.split("Atoms")[1].strip().splitlines()[1:]
    bad = [a for a in atoms if a.split() and (float(a.split()[4]) ** 2 + float(a.split()[5]) ** 2
                                              > R * R or not 0 < float(a.split()[6]) < p["height"])]
    check(not bad, "%s: %d grain centres outside the mould" % (tag, len(bad)))
    print("%s: e %.4f (lattice %.4f) mu_reached %g reached %d rounds %d" %
          (tag, p["void_ratio"], p["e_lattice"], p["mu_reached"], p["reached"], p["rounds"]))
    return p


loose = prepare("loose", mu_prep=0.6, densify=0, mu_final=0.6)
dense = prepare("dense", mu_prep=0.0, densify=1, mu_final=0.6)
if loose and dense:
    check(loose["void_ratio"] > dense["void_ratio"] + 0.15,
          "loose e %.4f clearly above dense e %.4f" % (loose["void_ratio"], dense["void_ratio"]))
    target = round(0.5 * (loose["void_ratio"] + dense["void_ratio"]), 3)
    mid = prepare("target", mu_prep=0.6, densify=1, e_target=target, mu_final=0.6)
    if mid:
        check(mid["reached"] == 1, "target %.3f reached (mu %g)" % (target, mid["mu_reached"]))
        check(target - 0.03 <= mid["void_ratio"] <= target + 0.005,
              "e %.4f within [target - 0.03, target] = [%.3f, %.3f]"
              % (mid["void_ratio"], target - 0.03, target))
        check(0 < mid["mu_reached"] < 0.6, "target reached at a friction between 0 and 0.6: %g"
              % mid["mu_reached"])
    for p, tag in ((loose, "loose"), (dense, "dense"), (mid, "target")):
        if p:
            near(1.0 / (1.0 + p["e_lattice"]), p["solid_fraction"], rtol=0.02,
                 msg="%s: lattice solid fraction against masses over the mould volume" % tag)
finish()
