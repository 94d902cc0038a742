"""pair_style lsdem / fix wall/lsdem: a run restarted mid-way continues as if
uninterrupted, on the same and on a different rank count.

The reference runs 400 steps in one go and writes a restart file at step 200. Reading
that file (which holds the per-node shear history of every grain, for the pair and for
each wall, and the position of the moving wall) and running 200 more steps must give
the reference's step-400 state to round-off (1e-8 relative). Without the history the
frictional contacts would restart with relaxed shear springs; without the wall position
the moving floor would jump back."""
import os
import random

from lsdemtest import run_lmp, thermo, check, near, finish
from contact_decks import Grain, box_library, write_data, head, quat_axis_angle, THERMO_FULL

lib = box_library("cube.lslib", 0.5, 0.05, 600)
rng = random.Random(3)
SP = 1.05
grains = []
for k in range(2):
    for j in range(3):
        for i in range(3):
            axis = (rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))
            q = quat_axis_angle(axis, rng.uniform(-0.1, 0.1)) if k else (1, 0, 0, 0)
            v = (rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), -0.3 * k)
            grains.append(Grain((SP * (i + 0.5), SP * (j + 0.5), 0.4995 + 1.02 * k), q=q, v=v))
write_data("cubes.data", (0, 3 * SP, 0, 3 * SP, 0, 6), grains)

# fixes and output shared by the reference and the restarted runs (same fix IDs)
FIXES = """fix grav all gravity 1.0 vector 0 0 -1
fix 1 all nve/lsdem
fix floor all wall/lsdem plane 0 0 0 0 0 1 1000 1000 0.6 cn 1.0 velocity 0 0 0.2
compute er all erotate/lsdem
compute w all pair lsdem
variable zfloor equal 0.2*time
thermo_style custom step ke c_er f_floor[1] f_floor[2] f_floor[3] c_w[2]
%s
thermo 100
timestep 5e-4
""" % THERMO_FULL

reference = head(lib, "cubes.data", boundary="p p f") + """
pair_style lsdem
pair_coeff * * 1000 1000 0.6 cn 1.0
%s
restart 200 mid.*
run 400
""" % FIXES

restarted = """read_restart %s
%s
run 200
""" % (os.path.abspath("ref/mid.200"), FIXES)

rc, log = run_lmp(reference, cwd=os.path.abspath("ref"))
ref = thermo(log)
check(os.path.exists("ref/mid.200"), "the reference run wrote no restart file")
if check(len(ref) == 5, "reference: thermo output missing"):
    final = ref[-1]
    check(final["c_w[2]"] >= 5, "reference: only %d contacts at the end" % final["c_w[2]"])
    check(final["f_floor[3]"] < 0, "reference: nothing presses on the floor")
    for np in (1, 2):
        rc, log = run_lmp(restarted, np=np, cwd=os.path.abspath("restart-np%d" % np))
        rows = thermo(log)
        if not check(len(rows) == 3, "restart np=%d: thermo output missing" % np):
            continue
        check("Resetting peratom fix info from restart file" in log,
              "restart np=%d: the history was not read back" % np)
        near(rows[0]["Step"], 200, atol=0, msg="restart np=%d: first step" % np)
        for key in ("KinEng", "c_er", "f_floor[3]"):
            near(rows[0][key], ref[2][key], rtol=1e-10,
                 msg="restart np=%d, step 200 (setup): %s" % (np, key))
            near(rows[-1][key], final[key], rtol=1e-8, msg="restart np=%d, step 400: %s"
                 % (np, key))
        check(rows[-1]["c_w[2]"] == final["c_w[2]"], "restart np=%d: %d contacts, reference %d"
              % (np, rows[-1]["c_w[2]"], final["c_w[2]"]))

finish()
