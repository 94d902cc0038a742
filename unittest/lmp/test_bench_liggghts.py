"""bench/liggghts/run.sh on a small case: LSDEM against LIGGGHTS 3.8 (Debian's package,
installed by the script when missing) with contact laws that coincide on rotating spheres.
Independent expectations: the binary collisions of the two codes agree to round-off, and
each is within 0.5 % (the codes' own time error at 200 steps per contact) of compare.py's
reference integration of the contact law with 50 times shorter steps; an elastic collision
keeps e = 1; the settled bed is at rest, the vertical force on LSDEM's walls equals the
spheres' weight (computed from the data file, and checked against LAMMPS's mass(all)), and
the two codes' beds settle to the same centre-of-mass height within 3 %; the plot is
written; --instructions resumes both settled beds and prints their instructions per
grain-step; a bad option is refused."""
import csv
import os
import subprocess

from lsdemtest import SHAPE_TOOL, check, finish, near, script_refuses, thermo

RUN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench", "liggghts",
                   "run.sh")
env = dict(os.environ, LSDEM_BUILD_DIR=os.path.dirname(SHAPE_TOOL))
# 0.4 s: rotating spheres with no rolling resistance still creep at 0.2 s (kinetic energy
# ~3e-8 J in both codes, the walls 0.3 % off the weight); at 0.4 s the bed is at rest
p = subprocess.run(["bash", RUN, "out", "--grains", "200", "--time", "0.4", "--instructions", "40"],
                   env=env,
                   stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=900)
check(p.returncode == 0, "run.sh failed (%d): %s%s" % (p.returncode, p.stdout[-2000:],
                                                       p.stderr[-2000:]))
rows = list(csv.DictReader(open("out/comparison.csv")))
val = {(r["run"], r["code"], r["quantity"]): r for r in rows}

for case in ("elastic", "damped", "oblique"):
    quantities = ("restitution", "slip_ratio") if case == "oblique" else ("restitution",)
    for q in quantities:
        a = val[("collide_" + case, "lsdem", q)]
        b = val[("collide_" + case, "liggghts", q)]
        near(float(a["value"]), float(b["value"]), rtol=1e-9,
             msg="%s %s: LSDEM against LIGGGHTS" % (case, q))
        for r in (a, b):
            near(float(r["value"]), float(r["reference"]), rtol=0.005,
                 msg="%s %s (%s) against the reference integration" % (case, q, r["code"]))
near(float(val[("collide_elastic", "lsdem", "restitution")]["value"]), 1.0, atol=1e-4,
     msg="elastic collision: e = 1")
check(float(val[("collide_damped", "lsdem", "restitution")]["reference"]) < 0.6,
      "the damped case dissipates (e %s)" % val[("collide_damped", "lsdem", "restitution")])

walls = val[("settle", "lsdem", "walls_vertical_force")]
near(float(walls["value"]), float(walls["reference"]), rtol=1e-3,
     msg="vertical force on the walls against the weight")
last = thermo(open("out/settle.lsdem.log").read())[-1]
near(last["v_mg"], float(walls["reference"]), rtol=1e-9,
     msg="compare.py's weight against LAMMPS's mass(all) g")
for code in ("lsdem", "liggghts"):
    check(float(val[("settle", code, "ke_end")]["value"]) < 1e-9,
          "%s: the bed is at rest at the end (KE %s J)" % (code, val[("settle", code, "ke_end")]))
    check(float(val[("settle", code, "us_per_grain_step")]["value"]) > 0, "%s: a time" % code)
near(float(val[("settle", "lsdem", "zcm")]["value"]),
     float(val[("settle", "liggghts", "zcm")]["value"]), rtol=0.03,
     msg="settled centre of mass, LSDEM against LIGGGHTS")
check(os.path.getsize("out/comparison.png") > 10000, "the plot is written")
check(p.stdout.strip().splitlines()[-1].startswith("collision_max_rel_diff="),
      "the last line gives the headline figures")
for code in ("lsdem", "liggghts"):
    check(float(val[("settle", code, "cpu_us_per_grain_step")]["value"]) > 0,
          "%s: a CPU time" % code)

# --instructions: each code's settled bed run on from its restart file under callgrind, the
# instructions of 40 steps less those of 0 steps per grain-step; both resumed runs go on
# from the settled state (the restart files keep it: the same kinetic energy as the end of
# the settling, to its printed digits)
line = [l for l in p.stdout.splitlines() if l.startswith("instructions per grain-step")]
check(len(line) == 1, "the instructions line is printed")
if line:
    words = line[0].split()
    a, b, ratio = int(words[-5]), int(words[-3]), float(words[-1])
    check(a > 100 and b > 100, "instructions per grain-step: lsdem %d liggghts %d" % (a, b))
    near(ratio, a / b, rtol=2e-3, msg="the printed ratio")
for code in ("lsdem", "liggghts"):
    settled = thermo(open("out/settle.%s.log" % code).read())[-1]["KinEng"]
    resumed = thermo(open("out/resume.%s.0.log" % code).read())[0]["KinEng"]
    near(resumed, settled, rtol=1e-6, msg="%s resumes from the settled bed" % code)
script_refuses(RUN, ["--grains", "0"], env, "--grains must be a positive integer", "bad")
script_refuses(RUN, ["--instructions", "x"], env, "--instructions must be a non-negative integer",
               "bad2")
finish()
