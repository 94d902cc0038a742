"""bench/node_stride.sh on a small specimen (100 grains, 2 % axial strain, strides 1 and 2):
the report's node-density study (§3.4.1) on the triaxial example. Independent expectations:
both strides shear the same specimen (identical sample.data), yet their curves differ (the
stride reached the pair style); each CSV row is what the run's own files say (the peak of
triaxial.csv's phi_deg and the volumetric strain of its last row, LAMMPS's 'Total wall time'
of log.lammps); the plot is written; a bad stride list is refused."""
import csv
import filecmp
import os
import re
import subprocess

from lsdemtest import SHAPE_TOOL, check, finish, near, script_refuses

RUN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "bench",
                   "node_stride.sh")
env = dict(os.environ, LSDEM_BUILD_DIR=os.path.dirname(SHAPE_TOOL), NGRAINS="100",
           EPSMAX="0.02", NPREP="2000", NP="2")
p = subprocess.run(["bash", RUN, "out", "--strides", "1,2"], env=env, stdout=subprocess.PIPE,
                   stderr=subprocess.PIPE, text=True, timeout=900)
check(p.returncode == 0, "node_stride.sh failed (%d): %s%s" % (p.returncode, p.stdout[-2000:],
                                                               p.stderr[-2000:]))
rows = {int(r["stride"]): r for r in csv.DictReader(open("out/node_stride.csv"))}
check(sorted(rows) == [1, 2], "one row per stride: %s" % sorted(rows))
check(filecmp.cmp("out/stride1/sample.data", "out/stride2/sample.data", shallow=False),
      "both strides shear the same specimen")
curves = {}
for n in (1, 2):
    run = list(csv.DictReader(open("out/stride%d/triaxial.csv" % n)))
    curves[n] = [r["q"] for r in run]
    near(float(rows[n]["phi_peak_deg"]), max(float(r["phi_deg"]) for r in run), rtol=1e-12,
         msg="stride %d: peak friction angle from triaxial.csv" % n)
    near(float(rows[n]["eps_v_end"]), float(run[-1]["eps_v"]), rtol=1e-12,
         msg="stride %d: final volumetric strain from triaxial.csv" % n)
    h, m, s = map(int, re.findall(r"^Total wall time: (\d+):(\d+):(\d+)",
                                  open("out/stride%d/log.lammps" % n).read(), re.M)[-1])
    check(int(rows[n]["seconds"]) == 3600 * h + 60 * m + s,
          "stride %d: seconds from log.lammps" % n)
check(curves[1] != curves[2], "stride 2 changes the contact forces, hence the curve")
check(os.path.getsize("out/node_stride.png") > 10000, "the plot is written")
check(p.stdout.strip().splitlines()[-1].startswith("stride=1:time_ratio=1.000"),
      "the last line gives the figures relative to stride 1")

script_refuses(RUN, ["--strides", "1,0"], env, "--strides must be positive integers", "bad")
finish()
