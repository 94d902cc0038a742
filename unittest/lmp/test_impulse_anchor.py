"""fix impulse/lsdem: the impulses the grains give the atoms no fix integrates (clamped net
balls: anchors) enter those atoms' f as impulse / dt, so fix net/lsdem's anchor reaction
(outputs 1-3, -sum f over the clamped balls; 9 its peak) reads the load the grains put on
the anchors. A small net of four balls (radius 0.1, spacing 0.25), all clamped (no free
ball, so no bond pulls), and one spherical grain (radius 0.3) over the middle of the square:
1. impact, no gravity: the grain thrown down at 5 bounces off the four balls, stopped by
   the ball guard (keyword balls), by ETM (method split) or by the report's method (ETM on
   each pass's copies of the contacts), and as a level-set grain with nodes (the ball is
   then the pairs' master, side a of the contacts); the anchor reaction summed over the steps times dt equals
   the grain's momentum change m (v_end - v_start), each component, to 1e-9 of m |v_start|
   (momentum balance; the reaction was 0 before: the impulses never entered f);
2. resting, gravity 1: the grain settled on the four balls (resting contacts, method
   split) gives an anchor force of its weight m g, within 1 %, at the last step and on
   average over the last 100; with the report's method (method etm: the grain chatters,
   ETM's impulses come in some steps and not others) on average over the last 100;
   Balls that another fix integrates (fix nve/lsdem) are left alone: their f stays the
   bonds' (here 0);
3. every run gives the same bits on 1 and 2 ranks (the ranks split the square between its
   balls: the grain's contacts reach ghost balls, whose share goes to their owners)."""
import os

from lsdemtest import run_lmp, shape_tool, check, thermo, finish

shape_tool("analytic", "ball.lslib", "sphere", 0.1, "--analytic")
shape_tool("analytic", "grain.lslib", "sphere", 0.3, "--analytic")
shape_tool("merge", "lib.lslib", "ball.lslib", "grain.lslib")
# the same grain as a level set with surface nodes: then the ball is the pair's master
# (it tests its centre in the grain's level set), contact a = the clamped ball
shape_tool("analytic", "noded.lslib", "sphere", 0.3)
shape_tool("merge", "libn.lslib", "ball.lslib", "noded.lslib")
for name, z in (("impact", 0.5), ("rest", 0.37)):
    open(name + ".data", "w").write("""one grain

1 atoms
1 atom types

-0.4 0.6 xlo xhi
-0.4 0.6 ylo yhi
-0.5 1.0 zlo zhi

Atoms # lsdem

1 1 2 1.0 0.125 0.125 {z} 1 0 0 0
""".format(z=z))
    shape_tool("net", name + "net", "--library", "lib.lslib", "--shape", 1, "--rb", 0.1,
               "--lattice", "square", "--spacing", 0.25, "--size", 0.25, 0.25, "--clamp",
               "all", "--mass", 0.01, "--k", 1.0, "--grains", name + ".data")

HERE = os.getcwd()
DT = 0.002
DECK = """units lj
atom_style hybrid lsdem library {here}/{lib} bond
atom_modify map array
boundary f f f
newton on
processors * 1 1
read_data {here}/{name}net.data
include {here}/{name}net.in
neighbor 0.1 bin
neigh_modify delay 0 every 1 check yes
pair_style lsdem/impulse
pair_coeff * *
{extra}
fix move grains impulse/lsdem 0.5 0.3 {keys}
fix net net net/lsdem {here}/{name}net.net clamp net_clamp
timestep {dt}
variable m equal mass[1]
variable vx equal vx[1]
variable vy equal vy[1]
variable vz equal vz[1]
thermo 1
thermo_style custom step v_m v_vx v_vy v_vz f_net[1] f_net[2] f_net[3] f_net[9]
thermo_modify format float %.17g
run {steps}
"""


def run(name, extra, keys, steps, np, case):
    lib = "libn.lslib" if case == "noded" else "lib.lslib"
    rc, log = run_lmp(DECK.format(here=HERE, name=name, extra=extra, keys=keys, dt=DT,
                                  steps=steps, lib=lib), np=np, cwd="%s_%s%d" % (name, case, np),
                      log="log." + name)
    rows = thermo(log)
    check(len(rows) == steps + 1, "%s on %d ranks: %d thermo rows" % (name, np, len(rows)))
    return rows


THROW = "velocity grains set 0 0 -5"
GRAVITY = "fix grav grains gravity 1.0 vector 0 0 -1"
G = 1.0
# (name, deck's run, fix keywords, steps): the impact resolved by the ball guard (it
# corrects all four pairs in one step), by ETM (collisions, method split) and by the
# report's method (ETM on each pass's copies of the contacts); the grain at rest with
# resting contacts (split) and with the report's method (ETM every step); "noded": the
# grain with surface nodes, the clamped ball the contacts' side a (split)
CASES = [("impact", "guard", THROW, "balls net", 150), ("impact", "split", THROW, "", 150),
         ("impact", "etm", THROW, "method etm", 150), ("impact", "noded", THROW, "", 150),
         ("rest", "split", GRAVITY, "", 400), ("rest", "noded", GRAVITY, "", 400),
         ("rest", "etm", GRAVITY, "method etm", 400)]
ones = {}
for name, case, extra, keys, steps in CASES:
    rows = run(name, extra, keys, steps, 1, case)
    ones[case + name] = rows
    m = rows[0]["v_m"]
    if name == "impact":  # 1. momentum balance
        v0 = [rows[0]["v_v" + c] for c in "xyz"]
        v1 = [rows[-1]["v_v" + c] for c in "xyz"]
        load = [sum(r["f_net[%d]" % (d + 1)] for r in rows[1:]) * DT for d in range(3)]
        dp = [m * (v1[d] - v0[d]) for d in range(3)]
        scale = m * abs(v0[2])
        print("impact %s: grain's momentum change %s, anchor reaction x dt summed %s (scale "
              "%.4g); peak anchor force %.6g" % (case, dp, load, scale, rows[-1]["f_net[9]"]))
        check(v1[2] > 0.0, "impact %s: the grain did not bounce (vz %g)" % (case, v1[2]))
        check(abs(dp[2]) > scale, "impact %s: momentum change %g, expected more than %g"
              % (case, dp[2], scale))
        for d in range(3):
            check(abs(load[d] - dp[d]) <= 1e-9 * scale, "impact %s: component %d: anchor "
                  "impulse %.17g, grain's momentum change %.17g" % (case, d, load[d], dp[d]))
    else:  # 2. the anchor force of a grain at rest is its weight
        weight = m * G
        last = rows[-1]["f_net[3]"]
        mean = sum(r["f_net[3]"] for r in rows[-100:]) / 100.0
        print("rest %s: weight %.6g, anchor force at the end %.6g, over the last 100 steps "
              "%.6g (x, y %.3g %.3g)" % (case, weight, last, mean, rows[-1]["f_net[1]"],
                                         rows[-1]["f_net[2]"]))
        if case != "etm":  # the report's method chatters: the ETM impulses skip steps
            check(abs(last - weight) <= 0.01 * weight, "rest %s: anchor force %g, weight %g"
                  % (case, last, weight))
        check(abs(mean - weight) <= 0.01 * weight, "rest %s: mean anchor force %g, weight %g"
              % (case, mean, weight))

# 2b. an atom another fix integrates keeps its f (its next half-kick would read a force
# added here): the clamped balls held by fix nve/lsdem (no force moves them) read nothing
held = run("rest", GRAVITY + "\nfix hold net_clamp nve/lsdem", "", 100, 1, "held")
seen = max(abs(r["f_net[%d]" % d]) for r in held for d in (1, 2, 3))
print("rest held by fix nve/lsdem: largest anchor force component %g" % seen)
check(seen == 0.0, "held: the balls fix nve/lsdem integrates got forces (%g)" % seen)

# 3. the same bits on 2 ranks
for name, case, extra, keys, steps in CASES:
    two = run(name, extra, keys, steps, 2, case)
    diff = [(a["Step"], k) for a, b in zip(ones[case + name], two) for k in a if a[k] != b[k]]
    check(not diff, "%s %s: 1 and 2 ranks differ, first at %s" % (name, case, diff[:3]))

finish()
