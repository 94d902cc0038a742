"""examples/triaxial/compare.py (specimens side by side against the report) on curves whose
figures are known in closed form.

A synthetic triaxial.csv (eps_a 0 to 16 % in steps of 0.1 %): phi = 48 - 2 (eps_a - 3)^2 deg
up to eps_a = 5 % and 40 deg after (peak 48 deg at 3.0 %, first within 0.5 deg of it at
2.5 %, 40 deg over the critical-state window 13-16 %, softening 8 deg); eps_v = 0.5 eps_a up
to 1 % (contraction) and 0.5 - 0.2 (eps_a - 1) after, so the largest dilatancy angle of
eq 3.10 over 1 % windows is asin(0.2 / 2.2) = 5.22 deg and the specimen dilates; a voids.txt
next to it gives the mould and core void ratios. A second CSV that only contracts and
hardens (phi rising to 30 deg at the end, eps_v = 0.1 eps_a) has its peak at the end, no
dilation and no softening. Checks the printed table, the JSON and that the PNG is written."""
import json
import math
import os
import subprocess
import sys

from lsdemtest import HERE, check, finish, near

SCRIPT = os.path.join(HERE, "..", "..", "examples", "triaxial", "compare.py")
COLS = ["eps_a", "eps_v", "q", "p", "phi_deg", "Z", "e"]


def write(folder, phi, epsv, voids=None):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "triaxial.csv"), "w") as f:
        f.write(",".join(COLS) + "\n")
        for i in range(161):
            ea = 0.1 * i  # percent
            f.write("%.6g,%.9g,1,1,%.9g,8,%.4g\n" % (ea / 100, epsv(ea) / 100, phi(ea),
                                                     0.6 - 0.001 * i))
    if voids:
        with open(os.path.join(folder, "voids.txt"), "w") as f:
            for name, e in voids:
                f.write("%s voids: points 1000 solid 600 solid_fraction %.5f void_ratio %.5f "
                        "volume 1000\n" % (name, 1 / (1 + e), e))
    return os.path.join(folder, "triaxial.csv")


dense = write("dense", lambda ea: 48 - 2 * (ea - 3) ** 2 if ea <= 5 else 40.0,
              lambda ea: 0.5 * ea if ea <= 1 else 0.5 - 0.2 * (ea - 1),
              voids=[("mould", 0.55), ("core", 0.48)])
loose = write("loose", lambda ea: 30 * (1 - math.exp(-ea)) / (1 - math.exp(-16)),
              lambda ea: 0.1 * ea)
p = subprocess.run([sys.executable, SCRIPT, "cmp.png", "dense=" + dense, "loose=" + loose,
                    "--title", "synthetic"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                   text=True, timeout=120)
print(p.stdout)
check(p.returncode == 0, "compare.py failed (%d)" % p.returncode)
check(os.path.getsize("cmp.png") > 10000 if os.path.exists("cmp.png") else False, "PNG written")
s = json.load(open("cmp.json"))
d, l = s["dense"], s["loose"]
near(d["peak_phi"], 48.0, atol=1e-6, msg="dense peak phi")
near(d["eps_peak"], 3.0, atol=1e-6, msg="dense strain at peak")
near(d["eps_peak_within_05"], 2.5, atol=1e-6, msg="dense: first strain within 0.5 deg of the peak")
near(d["crit_phi"], 40.0, atol=1e-6, msg="dense critical-state phi (13-16 %)")
near(d["crit_window"][0], 13.0, atol=1e-6, msg="critical-state window from 13 %")
near(d["softening"], 8.0, atol=1e-6, msg="dense softening")
near(d["psi_max"], math.degrees(math.asin(0.2 / 2.2)), atol=1e-6, msg="dense max dilatancy angle")
near(d["epsv_max_contraction"], 0.5, atol=1e-6, msg="dense largest contraction")
near(d["epsv_end"], 0.5 - 0.2 * 15, atol=1e-6, msg="dense eps_v at the end")
check(d["dilates"] is True, "dense dilates")
near(d["e_mould"], 0.55, atol=1e-9, msg="mould void ratio from voids.txt")
near(d["e_core"], 0.48, atol=1e-9, msg="core void ratio from voids.txt")
near(d["e0"], 0.6, atol=1e-9, msg="e0 from the CSV's first row")
near(l["eps_peak"], 16.0, atol=1e-6, msg="loose: peak at the end (hardening)")
near(l["peak_phi"], 30.0, atol=1e-6, msg="loose peak phi")
check(l["dilates"] is False, "loose does not dilate")
near(l["psi_max"], math.degrees(math.asin(-0.1 / 1.9)), atol=1e-6, msg="loose dilatancy (contraction)")
check(l["e_mould"] is None, "no voids.txt: no mould void ratio")
rows = [r for r in p.stdout.splitlines() if r.startswith(("dense ", "loose "))]
check(len(rows) == 2 and "48.0°" in rows[0] and "3.0%" in rows[0] and "2.5%" in rows[0]
      and rows[0].rstrip().endswith("yes") and rows[1].rstrip().endswith("no"), "table rows")

# --spread: each figure's mean, sample sd and range over the runs (here the two curves)
p = subprocess.run([sys.executable, SCRIPT, "spread.png", "dense=" + dense, "loose=" + loose,
                    "--spread"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                   timeout=120)
check(p.returncode == 0, "compare.py --spread failed (%d): %s" % (p.returncode, p.stdout))
sp = json.load(open("spread.json"))["spread"]
near(sp["peak_phi"]["mean"], 39.0, atol=1e-6, msg="mean peak phi of 48 and 30")
near(sp["peak_phi"]["sd"], 18.0 / math.sqrt(2.0), atol=1e-6, msg="sample sd of 48 and 30")
check(sp["peak_phi"]["min"] == 30.0 and sp["peak_phi"]["max"] == 48.0 and sp["peak_phi"]["n"] == 2,
      "peak phi range and count")
check(sp["e_mould"]["n"] == 1, "a figure only one run has counts one run")

# --join / PART+PART: a run's parts joined back into the whole CSV, with the resumed part
# repeating the row it resumed from (a checkpoint) or starting at a new row (an extension)
lines = open(dense).read().splitlines()
with open("a.csv", "w") as f:
    f.write("\n".join(lines[:51]) + "\n")          # rows 0-49: eps_a 0 to 4.9 %
with open("b_repeat.csv", "w") as f:
    f.write("\n".join(lines[:1] + ["%s,9,9,9,99,8,0.5" % lines[50].split(",")[0]] + lines[51:]) + "\n")
with open("b_next.csv", "w") as f:
    f.write("\n".join(lines[:1] + lines[51:]) + "\n")
for b in ("b_repeat.csv", "b_next.csv"):
    p = subprocess.run([sys.executable, SCRIPT, "--join", "a.csv", b], stdout=subprocess.PIPE,
                       text=True, timeout=60)
    check(p.stdout.splitlines() == lines, "--join a.csv %s gives the whole CSV back" % b)
p = subprocess.run([sys.executable, SCRIPT, "parts.png", "parts=a.csv+b_next.csv"],
                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
near(json.load(open("parts.json"))["parts"]["crit_phi"], 40.0, atol=1e-6,
     msg="a CSV given as PART+PART is read joined (critical state from the second part)")
finish()
