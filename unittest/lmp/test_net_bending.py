"""Bending joints of a net (lsdem-shape net --bending KB, angle_style lsdem/net).

1. A cantilever: a straight ball chain, its first two balls held, a small load P across it
   at the free end, run to rest with damping. Each joint j (arms of length a) takes the
   moment P (x_tip - x_j) = Kb delta_j (E = Kb (1 + cos theta) ~ Kb delta^2 / 2), so the tip
   deflects by sum_j delta_j (x_tip - x_j) = P a^2 / Kb sum_{m=1}^{N-1} m^2 (the discrete
   Euler-Bernoulli cantilever, independent of the code): within 0.3 % (the deflection is
   2.9 % of the length, the geometric nonlinearity of order its square). Without
   --bending the same chain has no bending stiffness and falls much further.
2. The same run on 1 and 2 ranks (the chain split between them) ends with the same bits:
   the joints' forces are rounded to the bonds' quantum before they are summed.
3. The files: a hexagonal net's data file holds its joints as Angles (3 per row ball with
   both row neighbours, 2 per diagonal), atom_style hybrid lsdem angle; a second net
   added with --grains keeps the first net's angles and gets the next angle type, its .in
   leaving angle_style to the first.
4. Bad input: a negative Kb, and angle_style lsdem/net without bond_style lsdem/net, stop
   with messages that say what is wrong."""
from lsdemtest import run_lmp, check, near, finish
from net_common import HERE, make_ball, make_net, head, read_dump

make_ball()
N, A, KB, P = 10, 1.0, 1.0, 1e-3    # segments, spacing, joint stiffness, tip load


def cantilever(prefix, np=1, bending=True):
    """Tip deflection (down) of the loaded chain at rest; the rest dump's path."""
    args = ["--lattice", "square", "--spacing", A, "--size", N * A, 0, "--clamp", "none",
            "--k", 100]
    make_net(prefix, *(args + (["--bending", KB] if bending else [])))
    deck = head(prefix, style="angle" if bending else "bond") + """
group held id 1 2
group moving subtract all held
group tip id {tip}
fix int moving nve/lsdem damping 0.3
fix load tip addforce 0 0 -{P}
timestep 0.005
variable w equal -z[{tip}]
thermo 5000
thermo_style custom step ke v_w
thermo_modify format float %.17g
run 40000
write_dump all custom rest.dump id x y z modify format float %.17g
""".format(tip=N + 1, P=P)
    run_lmp(deck, np=np, cwd="%s_np%d" % (prefix, np))
    rest = read_dump("%s_np%d/rest.dump" % (prefix, np))
    return -rest[N + 1]["z"], "%s_np%d/rest.dump" % (prefix, np)


# ---- 1. the discrete cantilever ---------------------------------------------------------
expect = P * A * A / KB * sum(m * m for m in range(1, N))
w1, dump1 = cantilever("beam")
near(w1, expect, rtol=3e-3, msg="tip deflection against P a^2/Kb sum m^2")
print("cantilever: tip deflection %.9f, discrete beam %.9f (%.3g %%)"
      % (w1, expect, 100 * (w1 / expect - 1)))
w0, _ = cantilever("limp", bending=False)
check(w0 > 10 * expect, "without --bending the chain should sag much further: %g vs %g"
      % (w0, expect))

# ---- 2. the same bits on 2 ranks --------------------------------------------------------
w2, dump2 = cantilever("beam", np=2)
same = open(dump1).read().split("ITEM: ATOMS")[1] == open(dump2).read().split("ITEM: ATOMS")[1]
check(same, "1 and 2 ranks: the rest positions differ (tip %.17g vs %.17g)" % (w1, w2))

# ---- 3. the files -----------------------------------------------------------------------
make_net("hexa", "--spacing", 1, "--size", 2, 3 ** 0.5, "--bending", 0.5)    # 3 x 3 balls
text = open("hexa.data").read()
check("atom_style hybrid lsdem angle" in text.splitlines()[0], "header names the angle style")
angles = [l.split() for l in text.split("\nAngles\n")[1].strip().splitlines()]
check(len(angles) == 7 and "7 angles" in text and "1 angle types" in text,
      "3 x 3 hexagonal net: %d joints, expected 3 along rows + 4 across" % len(angles))
inc = open("hexa.in").read()
check("angle_style lsdem/net" in inc and "angle_coeff 1 0.5" in inc, "first net's .in:\n" + inc)
make_net("hexb", "--spacing", 1, "--size", 2, 3 ** 0.5, "--bending", 0.25, "--origin", 0, 0,
         -3, "--grains", "hexa.data", "--name", "netb")
text = open("hexb.data").read()
angles_b = [l.split() for l in text.split("\nAngles\n")[1].strip().splitlines()]
check(angles_b[:7] == angles and len(angles_b) == 14 and "2 angle types" in text,
      "second net: the first's 7 angles kept, 7 more of type 2 (%d angles)" % len(angles_b))
check(all(a[1] == "2" for a in angles_b[7:]), "second net's joints: angle type 2")
inc = open("hexb.in").read()
check(not any(l.startswith("angle_style") for l in inc.splitlines()) and
      "angle_coeff 2 0.25" in inc, "second net's .in sets only its angle type:\n" + inc)
two_nets = head("hexb", style="angle").replace("include", "include %s/hexa.in\ninclude" % HERE)
rc, log = run_lmp(two_nets + "run 0\n", cwd="hexb_run")
check(rc == 0, "two bending nets read and run")

# ---- 4. bad input -----------------------------------------------------------------------
rc, log = run_lmp(head("hexa", style="angle") + "angle_coeff 1 -1\nrun 0\n", cwd="bad_kb",
                  expect_fail=True)
check(rc != 0 and "Kb (-1) must be >= 0" in log, "negative Kb:\n" + log[-600:])
rc, log = run_lmp(head("hexa", style="angle") + "bond_style zero\nbond_coeff *\nrun 0\n",
                  cwd="bad_bond", expect_fail=True)
check(rc != 0 and "needs bond_style lsdem/net" in log, "no net bonds:\n" + log[-600:])
finish()
