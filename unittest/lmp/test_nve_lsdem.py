"""fix nve/lsdem and compute erotate/lsdem against analytic solutions and conservation laws:
steady spin about a principal axis, constant force, global damping, a torque-free
asymmetric top (energy, |L| and the world angular momentum vector), instability errors and
the time-step warning."""
import math
import re

from lsdemtest import run_lmp, thermo, check, near, finish
import grain_decks as gd

LIB = gd.library()
HEAD = "units lj\natom_style lsdem library %s\n" % LIB


def deck(grains, body, dt, data="grains.data"):
    gd.write_data(data, grains)
    return HEAD + "read_data %s\n%stimestep %r\n%s" % (data, gd.PROPS, dt, body)


# ---- steady spin about the largest principal axis: q(t) = q0 * rot(e_z, w t) -----------
q0 = gd.qaxis((1.0, 2.0, 3.0), 0.8)
w = 3.0
axis = gd.rotate(q0, (0.0, 0.0, 1.0))
dt, n = 0.001, 2000
run_lmp(deck([dict(id=1, shape=1, density=1.7, x=(0.0, 0.0, 0.0), q=q0,
                   w=tuple(w * c for c in axis))],
             "fix 1 all nve/lsdem\n" + gd.dump_line("d", 500, "spin.dump") + "run %d\n" % n, dt))
frames = gd.read_dump("spin.dump")
check(len(frames) == n // 500 + 1, "spin dump frames")
for step, atoms in frames:
    a = atoms[1]
    expect = gd.qmul(q0, gd.qaxis((0.0, 0.0, 1.0), w * step * dt))
    check(gd.quat_distance(gd.quat(a), expect) < 1e-12,
          "spin quaternion at step %d: %r vs %r" % (step, gd.quat(a), expect))
    for k, c in enumerate("xyz"):
        near(a["omega" + c], w * axis[k], atol=1e-12, msg="spin omega%s step %d" % (c, step))

# ---- constant force: leapfrog v_n = v0 + n dt F/m, x_n = x0 + n dt v0 + dt^2 F/m n(n+1)/2 --
F = (0.3, -0.2, 0.5)
grains = [dict(id=1, shape=3, density=2.0, x=(1.0, 2.0, 3.0), q=gd.qaxis((1, 0, 1), 0.3),
               v=(0.1, 0.0, -0.2)),
          dict(id=2, shape=2, density=0.8, x=(-4.0, -2.0, 0.5), q=(1.0, 0.0, 0.0, 0.0),
               v=(0.0, 0.3, 0.0), w=(1.0, 2.0, 3.0))]
dt, n = 0.002, 1000
run_lmp(deck(grains, "fix f all addforce %r %r %r\nfix 1 all nve/lsdem\n" % F
             + gd.dump_line("d", n, "force.dump") + "run %d\n" % n, dt))
final = gd.read_dump("force.dump")[-1][1]
for g in grains:
    a = final[g["id"]]
    m = g["density"] * gd.closed_form(g["shape"])[0]
    for k, c in enumerate("xyz"):
        near(a["v" + c], g["v"][k] + n * dt * F[k] / m, rtol=1e-12, atol=1e-14,
             msg="constant force: v%s of grain %d" % (c, g["id"]))
        near(a[c], g["x"][k] + n * dt * g["v"][k] + dt * dt * F[k] / m * n * (n + 1) / 2,
             rtol=1e-12, atol=1e-12, msg="constant force: %s of grain %d" % (c, g["id"]))
# the analytic ball (kind sphere) turns freely with the spin the data file gives it: no
# torque, so omega stays and the orientation is rot(w/|w|, |w| t) from the start
wb = grains[1]["w"]
for k, c in enumerate("xyz"):
    near(final[2]["omega" + c], wb[k], rtol=1e-13, msg="free ball: omega%s kept" % c)
expect = gd.qaxis(wb, gd.norm(wb) * n * dt)
check(gd.quat_distance(gd.quat(final[2]), expect) < 1e-10,
      "free ball: orientation %r vs %r" % (gd.quat(final[2]), expect))
# with 'spheres fixed' it keeps 3 degrees of freedom (as membrane balls do): the orientation
# is untouched and the spin given in the data file is held at zero
run_lmp(deck(grains, "fix f all addforce %r %r %r\nfix 1 all nve/lsdem spheres fixed\n" % F
             + gd.dump_line("d", n, "fixed.dump") + "run %d\n" % n, dt, data="fixed.data"))
fixed = gd.read_dump("fixed.dump")[-1][1]
check(gd.quat(fixed[2]) == (1.0, 0.0, 0.0, 0.0), "fixed ball: orientation must not change")
check((fixed[2]["omegax"], fixed[2]["omegay"], fixed[2]["omegaz"]) == (0.0, 0.0, 0.0),
      "fixed ball: omega must be held at zero")

# ---- global damping: v_n = v0 r^n, r = (1 - xi dt/2)/(1 + xi dt/2); omega ~ exp(-xi t) ---
xi, dt, n = 5.0, 0.002, 500
v0, wz = (1.0, -2.0, 0.5), 1.5
q1 = gd.qaxis((0.0, 1.0, 1.0), 1.1)
run_lmp(deck([dict(id=1, shape=1, density=1.0, x=(0.0, 0.0, 0.0), q=q1, v=v0,
                   w=tuple(wz * c for c in gd.rotate(q1, (0.0, 0.0, 1.0))))],
             "fix 1 all nve/lsdem damping %r\n" % xi + gd.dump_line("d", n, "damp.dump")
             + "run %d\n" % n, dt))
a = gd.read_dump("damp.dump")[-1][1][1]
r = (1 - xi * dt / 2) / (1 + xi * dt / 2)
for k, c in enumerate("xyz"):
    near(a["v" + c], v0[k] * r ** n, rtol=1e-12, msg="damped v%s" % c)
    near(a[c], dt * v0[k] * sum(r ** j for j in range(1, n + 1)), rtol=1e-12, atol=1e-14,
         msg="damped %s" % c)
wnorm = gd.norm([a["omegax"], a["omegay"], a["omegaz"]])
near(wnorm, wz * math.exp(-xi * n * dt), rtol=1e-3, msg="damped |omega| vs exp(-xi t)")

# ---- torque-free asymmetric top: E_rot, |L| and L_world conserved over 1e4 steps ------
qt = gd.qnormalize((0.9, 0.2, -0.3, 0.4))
wt = (0.7, -1.1, 1.9)
rho = 1.3
dt, n = 0.001, 10000
rc, log = run_lmp(deck([dict(id=1, shape=1, density=rho, x=(0.0, 0.0, 0.0), q=qt, w=wt)],
                       "compute er all erotate/lsdem\nfix 1 all nve/lsdem\n"
                       "thermo_style custom step c_er c_er[1] c_er[2] c_er[3]\n"
                       "thermo_modify format float %.17g\nthermo 100\n"
                       + gd.dump_line("d", 500, "top.dump") + "run %d\n" % n, dt))
rows = thermo(log)
check(len(rows) == n // 100 + 1, "thermo rows of the top run")
inertia = [rho * i for i in gd.closed_form(1)[1]]
wb0 = gd.rotate_inv(qt, wt)
e0 = 0.5 * sum(inertia[k] * wb0[k] ** 2 for k in range(3))
l0 = gd.norm([inertia[k] * wb0[k] for k in range(3)])
check(abs(wb0[0]) > 0.3 and abs(wb0[1]) > 0.3 and abs(wb0[2]) > 0.3,
      "the top must spin about no principal axis")
near(rows[0]["c_er"], e0, rtol=1e-13, msg="initial rotational energy vs 1/2 sum I_k w_k^2")
near(gd.norm([rows[0]["c_er[%d]" % k] for k in (1, 2, 3)]), l0, rtol=1e-13,
     msg="initial |L|")
de = max(abs(row["c_er"] - e0) / e0 for row in rows)
dl = max(abs(gd.norm([row["c_er[%d]" % k] for k in (1, 2, 3)]) - l0) / l0 for row in rows)
check(de < 1e-6, "rotational energy drift %.3g over %d steps" % (de, n))
check(dl < 1e-6, "|L| drift %.3g over %d steps" % (dl, n))
print("torque-free top, %d steps, dt %g: max rel. drift E_rot %.3g, |L| %.3g" % (n, dt, de, dl))
# body motion really happened: omega_body moved far from its start
frames = gd.read_dump("top.dump")
wb_end = gd.rotate_inv(gd.quat(frames[-1][1][1]),
                       [frames[-1][1][1]["omega" + c] for c in "xyz"])
check(gd.norm([wb_end[k] - wb0[k] for k in range(3)]) > 0.3, "the top should tumble")
# world angular momentum: omega is at n-1/2, so pair it with q^{n-1/2} = q^n rot(-omega dt/2)
lw = []
for step, atoms in frames:
    a = atoms[1]
    q = gd.quat(a)
    wb = gd.rotate_inv(q, [a["omega" + c] for c in "xyz"])
    qh = gd.qmul(q, gd.qaxis(wb, -0.5 * dt * gd.norm(wb)))
    lw.append(gd.rotate(qh, [a["c_p[%d]" % (6 + k)] * wb[k] for k in range(3)]))
dlw = max(gd.norm([l[k] - lw[0][k] for k in range(3)]) for l in lw) / l0
check(dlw < 1e-6, "world angular momentum drift %.3g over %d steps" % (dlw, n))
print("torque-free top: max rel. change of the world angular momentum %.3g" % dlw)

# ---- instability: non-finite force, runaway speed (dumps and log are flushed) ---------
rc, log = run_lmp(deck([dict(id=7, shape=1, density=1.0, x=(0.0, 0.0, 0.0), q=qt)],
                       "variable big equal 1e308*10\nfix f all addforce v_big 0 0\n"
                       "fix 1 all nve/lsdem\nrun 10\n", 0.005), expect_fail=True)
check(rc != 0 and "Fix nve/lsdem: grain 7 became unstable at step 1 with a non-finite" in log
      and "Likely causes: initial overlap" in log, "non-finite error message:\n" + log[-800:])

dt, accel = 0.005, 1.1e3       # ball radius 0.5: |v| dt > 0.25 first at step 10
m = gd.closed_form(2)[0]
nfail = next(k for k in range(1, 100) if k * dt * accel * dt > 0.5 * gd.BALL)
rc, log = run_lmp(deck([dict(id=3, shape=2, density=1.0, x=(0.0, 0.0, 0.0), q=qt)],
                       "fix f all addforce %r 0 0\nfix 1 all nve/lsdem\n" % (accel * m)
                       + "dump d all custom 1 run.dump id x vx\ndump_modify d flush no\n"
                       "thermo 1\nrun 50\n", dt), expect_fail=True)
check(rc != 0 and "grain 3 became unstable at step %d with a runaway speed" % nfail in log,
      "runaway error message at step %d:\n%s" % (nfail, log[-800:]))
check(open("run.dump").read().count("ITEM: TIMESTEP") == nfail,
      "dump frames before the error must be flushed")
check(re.search(r"^\s+%d\s" % (nfail - 1), log, re.M), "log thermo rows must be flushed")

# ---- time-step warning from the stiffest contact a grain can form ----------------------
# An analytic ball presses one contact point: k = kn. A box presses a whole face of nodes
# on a flat partner: k = kn x (its face's nodes), which the warning names and bases the
# bound on, so a time step that passes 0.2 sqrt(m/kn) for the box is still flagged.
kn = 1e5
WARN = re.compile(r"timestep (\S+) > 0\.2\*sqrt\(m/k\) = (\S+) for grain (\d+) \(mass m = "
                  r"(\S+); k = (\S+): the pair style's kn (\S+) times the (\S+) nodes one flat "
                  r"contact of its shape presses\); suggest timestep (\S+)")


def pair_deck(grains, timestep):
    gd.write_data("pair.data", grains)
    return (HEAD + "atom_modify map array\nnewton on\ncomm_modify vel yes\n"
            "read_data pair.data\ntimestep %r\npair_style lsdem\npair_coeff * * %r %r 0.0\n"
            "fix 1 all nve/lsdem\nrun 1\n" % (timestep, kn, kn))


def warning(log):
    m = WARN.search(log)
    return m and [float(v) for v in m.groups()]


def close(a, b):  # the warning prints 6 significant digits
    return abs(a - b) <= 1e-5 * abs(b)


ball = dict(id=1, shape=2, density=1.0, x=(0.0, 0.0, 0.0), q=(1, 0, 0, 0))
ell = dict(id=2, shape=1, density=1.0, x=(5.0, 5.0, 5.0), q=(1, 0, 0, 0))
m = gd.closed_form(2)[0]
dtmax = 0.2 * math.sqrt(m / kn)
rc, log = run_lmp(pair_deck([ball, ell], 0.005))
w = warning(log)
check(w and w[2] == 1 and close(w[1], dtmax) and close(w[3], m)
      and close(w[4], kn) and w[6] == 1,
      "time-step warning for the ball (one node, dt %.6g): %s\n%s" % (dtmax, w, log[-1500:]))
decade = 10.0 ** (math.floor(math.log10(dtmax)) - 1)
suggest = math.floor(dtmax / decade) * decade
check(w and close(w[7], suggest) and suggest <= dtmax,
      "suggested time step %.2g (<= %.6g): %s" % (suggest, dtmax, w))
rc, log = run_lmp(pair_deck([ball, ell], 0.5 * dtmax))
check("Fix nve/lsdem: timestep" not in log, "no time-step warning for a small time step")

# the box (half-extents 1 x 0.5 x 0.3, 30 nodes asked): its largest face, 2 x 1 of the
# 7.6 surface, holds about a quarter of its nodes
box = dict(id=3, shape=3, density=1.0, x=(0.0, 0.0, 0.0), q=(1, 0, 0, 0))
mbox = gd.closed_form(3)[0]
one_node = 0.2 * math.sqrt(mbox / kn)
rc, log = run_lmp(pair_deck([box], 0.6 * one_node))
w = warning(log)
check(w and w[2] == 3 and 3 <= w[6] <= 20 and close(w[4], kn * w[6])
      and close(w[1], 0.2 * math.sqrt(mbox / (kn * w[6]))) and w[1] < 0.6 * one_node,
      "a box's flat face presses several nodes: dt below 0.2 sqrt(m/kn) = %.6g flagged: %s\n%s"
      % (one_node, w, log[-1500:]))

finish()
