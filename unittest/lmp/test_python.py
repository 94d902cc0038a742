"""Python: LAMMPS's own module (build/python/lammps, with this build's liblammps.so) imports,
reports the LSDEM package, and examples/python drives the settle scene from Python. Its
gathered positions and quaternions (read into numpy) are checked against independent
expectations: lmp itself running the same deck and data for the same steps in one go
(write_data), the free fall of a damped body for grains still in the air (the integrator's
recurrence, itself within 1.5/N of z0 - z = g/xi (t - (1 - exp(-xi t))/xi)), unit
quaternions, and the same numbers on 2 ranks."""
import math
import os
import shutil
import subprocess

import numpy as np

from lsdemtest import HERE, LAMMPS_VERSION, LMP, SHAPE_TOOL, check, finish, near, run_lmp

BUILD = os.path.dirname(SHAPE_TOOL)
EXAMPLES = os.path.normpath(os.path.join(HERE, "..", "..", "examples"))
env = dict(os.environ, PYTHONPATH=os.path.join(BUILD, "python"))

p = subprocess.run(["/usr/bin/python3", "-c",
                    "from lammps import lammps; l = lammps(cmdargs=['-log', 'none', '-screen', "
                    "'none']); print(l.version(), 'LSDEM' in l.installed_packages, "
                    "l.has_style('pair', 'lsdem'))"],
                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
check(p.returncode == 0 and p.stdout.split()[-3:] == [str(LAMMPS_VERSION), "True", "True"],
      "from lammps import lammps: %s" % p.stdout[-1500:])

NSTEPS, NGRAINS = 2000, 40
results = {}
for np_ in (1, 2):
    out = os.path.abspath("python%d" % np_)
    os.makedirs(out, exist_ok=True)
    for f in ("run.sh", "settle.py"):
        with open(os.path.join(EXAMPLES, "python", f)) as src, open(os.path.join(out, f), "w") as dst:
            dst.write(src.read().replace('"$here/../settle/', '"%s/settle/' % EXAMPLES))
    p = subprocess.run(["bash", os.path.join(out, "run.sh")], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True,
                       env=dict(env, NP=str(np_), NGRAINS=str(NGRAINS), NSTEPS=str(NSTEPS),
                                CHUNK="500", LSDEM_BUILD_DIR=BUILD, LSDEM_SHAPE_TOOL=SHAPE_TOOL))
    check(p.returncode == 0 and "positions and quaternions of %d grains" % NGRAINS in p.stdout,
          "python example on %d rank(s):\n%s" % (np_, p.stdout[-2500:]))
    check(p.stdout.count("step ") == NSTEPS // 500, "one line per chunk expected:\n" + p.stdout)
    if p.returncode == 0:
        results[np_] = np.load(os.path.join(out, "out", "grains.npz"))

r = results.get(1)
check(r is not None, "no results from the 1-rank run")
if r is not None:
    check(list(r["id"]) == list(range(1, NGRAINS + 1)), "ids %s" % r["id"])
    check(np.abs(np.linalg.norm(r["quat"], axis=1) - 1).max() < 1e-12, "quaternions not unit")
    check(set(r["shape"]) <= {1, 2, 3, 4}, "shape indices %s" % set(r["shape"]))
    # lmp on the same deck and data, the same steps in one run
    ref = os.path.abspath("lmp1")
    os.makedirs(ref, exist_ok=True)
    for f in ("grains.lslib", "data.settle"):
        shutil.copy(os.path.join("python1", "out", f), ref)
    run_lmp(os.path.join(EXAMPLES, "settle", "in.settle"), cwd=ref, vars={"nsteps": NSTEPS})
    rows = {}
    lines = open(os.path.join(ref, "settle.data")).read().splitlines()
    at = lines.index(next(l for l in lines if l.startswith("Atoms")))
    for l in lines[at + 2:at + 2 + NGRAINS]:
        f = l.split()
        rows[int(f[0])] = [float(v) for v in f[4:11]]
    x_lmp = np.array([rows[i][0:3] for i in range(1, NGRAINS + 1)])
    q_lmp = np.array([rows[i][3:7] for i in range(1, NGRAINS + 1)])
    check(np.abs(r["x"] - x_lmp).max() < 1e-12, "positions differ from lmp's by %.3g m"
          % np.abs(r["x"] - x_lmp).max())
    check(np.abs(r["quat"] - q_lmp).max() < 1e-9, "quaternions differ from lmp's by %.3g"
          % np.abs(r["quat"] - q_lmp).max())
    # grains still in the air fell as a damped body does (xi = 2 /s, g = 9.81, t = steps dt)
    lines0 = open(os.path.join("python1", "out", "data.settle")).read().splitlines()
    at0 = lines0.index(next(l for l in lines0 if l.startswith("Atoms")))
    z0 = np.array(sorted((int(l.split()[0]), float(l.split()[6]))
                         for l in lines0[at0 + 2:at0 + 2 + NGRAINS]))[:, 1]
    # the integrator's own recurrence (fix nve/lsdem, report eq 2.18): from rest,
    # v+ = ((1 - xi dt/2) v- + g dt) / (1 + xi dt/2), z -= v+ dt each step
    dt, xi, g = 5e-6, 2.0, 9.81
    v = fall = 0.0
    for _ in range(NSTEPS):
        v = ((1 - xi * dt / 2) * v + g * dt) / (1 + xi * dt / 2)
        fall += v * dt
    t = NSTEPS * dt
    near(fall, g / xi * (t - (1 - math.exp(-xi * t)) / xi), rtol=1.5 / NSTEPS,
         msg="discrete against continuous damped fall")
    drop = z0 - r["x"][:, 2]
    free = np.abs(drop - fall) < 0.01 * fall
    check(free.sum() >= NGRAINS // 2, "only %d of %d grains fell freely (drop %s, expected %.4g)"
          % (free.sum(), NGRAINS, np.round(drop, 6), fall))
    near(np.median(drop), fall, rtol=1e-9, msg="median free-fall drop")
if 1 in results and 2 in results:
    check(np.abs(results[2]["x"] - results[1]["x"]).max() < 1e-12 and
          np.abs(results[2]["quat"] - results[1]["quat"]).max() < 1e-9,
          "2 ranks differ from 1 rank: %.3g m" % np.abs(results[2]["x"] - results[1]["x"]).max())
finish()
