"""Impulse mode, bad input: each stops with an error naming the keyword (or the offending
fix, grain, step) and the allowed range, and the CFL check warns or stops by keyword."""
import os

from impulse_decks import header, library
from lsdemtest import run_lmp, check, finish

BALL = library("ball.lslib", "sphere", 0.1, nodes=20, analytic=True)
with open("ball.data", "w") as f:
    f.write("ball\n\n2 atoms\n1 atom types\n\n-1 1 xlo xhi\n-1 1 ylo yhi\n-0.5 2 zlo zhi\n\n"
            "Atoms # lsdem\n\n1 1 1 1.0 0 0 0.5 1 0 0 0\n2 1 1 1.0 0.5 0 0.5 1 0 0 0\n\n"
            "Velocities\n\n1 0 0 -3 0 0 0\n2 0 0 0 0 0 0\n")
BASE = header(BALL, "ball.data")
FLOOR = "fix floor all wall/lsdem plane 0 0 0 0 0 1 1.0e4 0 0\n"
RUN = "timestep 1e-3\nthermo 10\nrun 20\n"


def refuses(name, fix_line, expect, pre="", base=BASE, extra=FLOOR):
    rc, log = run_lmp(base + pre + extra + fix_line + RUN, cwd=os.path.abspath(name),
                      expect_fail=True)
    msgs = [ln for ln in log.splitlines() if "ERROR" in ln]
    check(rc != 0 and any(all(e in m for e in expect) for m in msgs),
          "%s: expected an error with %s, got rc %d, %s" % (name, expect, rc, msgs[:2]))


refuses("e_high", "fix imp all impulse/lsdem 1.2 0.3\n", ["restitution e = 1.2", "[0, 1]"])
refuses("e_low", "fix imp all impulse/lsdem -0.1 0.3\n", ["restitution e = -0.1", "[0, 1]"])
refuses("mu", "fix imp all impulse/lsdem 0.5 -1\n", ["friction mu = -1", ">= 0"])
refuses("alpha0", "fix imp all impulse/lsdem 0.5 0.3 alpha 0\n", ["alpha = 0", ">= 1"])
refuses("alpha_neg", "fix imp all impulse/lsdem 0.5 0.3 alpha -2\n", ["alpha = -2", ">= 1"])
refuses("beta_neg", "fix imp all impulse/lsdem 0.5 0.3 beta -0.1\n", ["beta = -0.1", "[0, 1)"])
refuses("beta_one", "fix imp all impulse/lsdem 0.5 0.3 beta 1\n", ["beta = 1", "[0, 1)"])
refuses("damping", "fix imp all impulse/lsdem 0.5 0.3 damping -1\n", ["damping xi = -1", ">= 0"])
refuses("damping_dt", "fix imp all impulse/lsdem 0.5 0.3 damping 2000\n",
        ["damping xi * timestep", "<= 1", "eq 4.46"])
refuses("passes", "fix imp all impulse/lsdem 0.5 0.3 passes 0\n", ["passes = 0", ">= 1"])
refuses("iterations", "fix imp all impulse/lsdem 0.5 0.3 iterations 0\n",
        ["iterations = 0", ">= 1"])
refuses("cfl_action", "fix imp all impulse/lsdem 0.5 0.3 cfl 0.5 maybe\n",
        ["cfl action", "warn or stop"])
refuses("keyword", "fix imp all impulse/lsdem 0.5 0.3 bogus 1\n", ["unknown keyword bogus"])
refuses("method", "fix imp all impulse/lsdem 0.5 0.3 method penalty\n",
        ["method must be split", "or etm", "not penalty"])
refuses("points", "fix imp all impulse/lsdem 0.5 0.3 points 0\n", ["points = 0", "all or >= 1"])
refuses("sweeps", "fix imp all impulse/lsdem 0.5 0.3 sweeps 0\n", ["sweeps = 0", ">= 1"])
refuses("rest_steps", "fix imp all impulse/lsdem 0.5 0.3 rest_steps 0\n",
        ["rest_steps = 0", "> 0"])
refuses("residual", "fix imp all impulse/lsdem 0.5 0.3 residual 1.5\n",
        ["residual = 1.5", "[0, 1]"])
refuses("sleep_speed", "fix imp all impulse/lsdem 0.5 0.3 sleep 0 0.1\n",
        ["sleep 0 0.1", "speed > 0"])
refuses("sleep_time", "fix imp all impulse/lsdem 0.5 0.3 sleep 0.1\n",
        ["keyword sleep needs 2 values"])
refuses("bias", "fix imp all impulse/lsdem 0.5 0.3 bias 1.5\n", ["bias = 1.5", "[0, 1]"])
refuses("twice", "fix imp all impulse/lsdem 0.5 0.3\n",
        ["fix nve (nve/lsdem, group all) also integrates 2 of its grains", "one time integrator"],
        pre="fix nve all nve/lsdem\n")
refuses("penalty_pair", "fix imp all impulse/lsdem 0.5 0.3\n",
        ["requires pair_style lsdem/impulse", "pair_style lsdem is set"],
        base=BASE.replace("pair_style lsdem/impulse\npair_coeff * *",
                          "pair_style lsdem\npair_coeff * * 1e4 0 0"))
refuses("periodic", "fix imp all impulse/lsdem 0.5 0.3\n",
        ["periodic boundaries are not supported"],
        base=BASE.replace("boundary f f f", "boundary p p f"))
refuses("pivot", "fix imp all impulse/lsdem 0.5 0.3\n", ["pivots", "not support"],
        extra="fix floor all wall/lsdem plane 0 0 0 0 0 1 1.0e4 0 0 pivot 0.1 1.0\n")
refuses("pair_coeff", "fix imp all impulse/lsdem 0.5 0.3\n",
        ["pair_coeff for lsdem/impulse", "restitution and friction are fix impulse/lsdem"],
        base=BASE.replace("pair_coeff * *", "pair_coeff * * 1e4 0 0.5"))

# CFL: grain 1 falls at 3 per step of 0.1 = 3 radii per step
rc, log = run_lmp(BASE + FLOOR + "fix imp all impulse/lsdem 0.5 0.3 cfl 0.5 stop\n"
                  + RUN.replace("1e-3", "0.1"), cwd=os.path.abspath("cfl_stop"), expect_fail=True)
check(rc != 0 and "grain 1 moves |v| dt" in log and "Use a timestep below" in log,
      "cfl stop: %s" % [ln for ln in log.splitlines() if "ERROR" in ln][:1])
rc, log = run_lmp(BASE + FLOOR + "fix imp all impulse/lsdem 0.5 0.3 cfl 0.5 warn\n"
                  + "timestep 0.1\nthermo 10\nrun 3\n", cwd=os.path.abspath("cfl_warn"))
check(rc == 0 and log.count("WARNING: Fix impulse/lsdem: step") == 1 and "grain 1" in log,
      "cfl warn: one warning naming grain 1")
finish()
