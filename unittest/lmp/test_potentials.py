"""potentials/: make.sh writes every library README.md lists (2 grains per sand library to
keep the test short), each verifies and holds what its row says (the sphere's volume is
4/3 pi 15^3 to the grid's accuracy, the ellipsoids' are 4/3 pi abc, the three sand libraries
hold the same grains: equal volumes within 1 % at the three resolutions, node counts as
named); the snippets give lmp the values of the report's Tables 3.2 and 4.1 as typed here
from the report; every library runs in lmp with a snippet's contact parameters."""
import math
import os
import re
import subprocess

from grain_decks import write_data
from lsdemtest import HERE, SHAPE_TOOL, check, finish, near, run_lmp, shape_tool

POT = os.path.normpath(os.path.join(HERE, "..", "..", "potentials"))
out = os.path.abspath("pot")
p = subprocess.run(["bash", os.path.join(POT, "make.sh"), out], stdout=subprocess.PIPE,
                   stderr=subprocess.STDOUT, text=True,
                   env=dict(os.environ, COUNT="2", LSDEM_SHAPE_TOOL=SHAPE_TOOL))
check(p.returncode == 0, "make.sh failed:\n" + p.stdout[-2000:])

readme = open(os.path.join(POT, "README.md")).read()
listed = re.findall(r"^\| `([^`]+\.lslib)`", readme, re.M)
made = sorted(f for f in os.listdir(out) if f.endswith(".lslib"))
check(sorted(listed) == made, "README lists %s, make.sh made %s" % (sorted(listed), made))
for snippet in re.findall(r"^\| `([^`]+\.lsdem)`", readme, re.M):
    check(os.path.exists(os.path.join(POT, snippet)), "README lists %s, not in potentials/" % snippet)


def shapes(lib):
    """(name, nodes, volume) per shape from lsdem-shape list."""
    rows = []
    for line in shape_tool("list", os.path.join(out, lib)).splitlines()[2:]:
        f = line.split()
        rows.append((f[1], int(f[-7]), float(f[-4])))  # grid/params may be two words
    return rows


sand = {n: shapes("sand_%d.lslib" % n) for n in (100, 250, 750)}
for n, rows in sand.items():
    check(len(rows) == 2 and all(r[1] == n for r in rows), "sand_%d: %s" % (n, rows))
for i in range(2):
    v = [sand[n][i][2] for n in (100, 250, 750)]
    check(max(v) / min(v) < 1.01, "grain %d: volumes %s at the three resolutions" % (i, v))
    d = (6 * v[2] / math.pi) ** (1 / 3)
    check(20 < d < 45, "grain %d: equivalent diameter %.1f voxels (median 30)" % (i, d))
near(shapes("sphere.lslib")[0][2], 4 / 3 * math.pi * 15 ** 3, rtol=1e-5, msg="analytic sphere (6 digits listed)")
near(shapes("sphere_grid.lslib")[0][2], 4 / 3 * math.pi * 15 ** 3, rtol=0.01, msg="grid sphere")
ell = shapes("ellipsoids.lslib")
near(ell[0][2], 4 / 3 * math.pi * 18 * 15 * 12, rtol=0.01, msg="ellipsoid 18 15 12")
near(ell[1][2], 4 / 3 * math.pi * 20 * 14 * 10, rtol=0.01, msg="ellipsoid 20 14 10")

# the snippets against the report's tables (values typed from the report)
table32 = {"xi": 1.0, "Rp": 500, "Hp": 800, "Knp": 3e4, "Ksp": 2.7e4, "mup": 0.5, "rb": 10,
           "Knbb": 50, "Ksbb": 50, "Knb": 3e4, "Kn": 3e4, "Ks": 2.7e4, "mu": 0.6,
           "rho": 2500 * 4.3e-6 ** 3, "rho_p": 2500 * 4.3e-6 ** 3}
table41 = {"Gs": 2.65, "mu": 0.55, "xi": 0.5, "Kn": 3e4, "Ks": 2.7e4, "dt": 2.5e-4, "Rn": 0.65,
           "Rt": 0.0, "rho": 2650 * 3.4e-6 ** 3}
for snippet, table in (("table3_2.lsdem", table32), ("table4_1.lsdem", table41)):
    deck = "include %s\n" % os.path.join(POT, snippet)
    deck += "".join('print "%s = $(v_%s:%%.10g)"\n' % (k, k) for k in table)
    rc, log = run_lmp(deck, log="log.%s" % snippet)
    for k, v in table.items():
        m = re.search(r"^%s = (\S+)$" % k, log, re.M)
        check(m is not None and math.isclose(float(m.group(1)), v, rel_tol=1e-9),
              "%s: %s = %s, the report has %g" % (snippet, k, m and m.group(1), v))

# every library in lmp: two grains of it fall onto a floor with Table 3.2's parameters
rho = 2500 * 4.3e-6 ** 3
for lib in made:
    second = min(2, len(shapes(lib)))
    write_data("two.data", [dict(id=1, shape=1, density=rho, x=(0, 0, 30), q=(1, 0, 0, 0)),
                            dict(id=2, shape=second, density=rho, x=(0, 0, 75),
                                 q=(0.8, 0.6, 0, 0))], box=(-60, 60, -60, 60, -10, 110))
    deck = """units si
atom_style lsdem library %s
boundary f f f
newton on
comm_modify vel yes
read_data two.data
include %s
pair_style lsdem
pair_coeff * * ${Kn} ${Ks} ${mu}
fix floor all wall/lsdem plane 0 0 0 0 0 1 ${Knp} ${Ksp} ${mup}
fix g all gravity 1e4 vector 0 0 -1
fix nve all nve/lsdem damping ${xi}
timestep 2e-9
thermo 100
run 200
""" % (os.path.join(out, lib), os.path.join(POT, "table3_2.lsdem"))
    rc, log = run_lmp(deck, log="log.%s" % lib)
    check(rc == 0 and "Loop time" in log and "2 atoms" in log, "%s did not run in lmp" % lib)
finish()
