"""pair_style lsdem: elastic head-on collision of two level-set (grid) spheres.

mu = 0 and no damping, so the contact is a conservative spring: the kinetic energy after
separation must equal the energy before (within 1%), linear momentum is conserved
exactly (action = reaction), and two equal masses in a head-on collision exchange their
velocities. Run in both one-way (report) and two-way modes."""
import os

from lsdemtest import run_lmp, thermo, check, near, finish
from contact_decks import Grain, sphere_library, write_data, head, THERMO_FULL

R = 0.5
V0 = 1.0
lib = sphere_library("sphere.lslib", R, 0.05, 300)
# equal masses approaching along x; a small lateral offset keeps the test honest
# (the normal is not exactly along x, so energy moves into rotation too)
grains = [Grain((-0.7, 0.0, 0.0), v=(V0, 0, 0)),
          Grain((0.7, 0.02, 0.0), q=(0.92387953, 0.38268343, 0.0, 0.0), v=(-V0, 0, 0))]
write_data("data.two", (-4, 4, -4, 4, -4, 4), grains)

for mode in ("oneway", "twoway"):
    deck = head(lib, "data.two", boundary="f f f") + """
pair_style lsdem mode %s
pair_coeff * * 2000 0 0
fix 1 all nve/lsdem
compute er all erotate/lsdem
compute w all pair lsdem
variable px equal mass(all)*vcm(all,x)
variable py equal mass(all)*vcm(all,y)
variable v1 equal vx[1]
variable v2 equal vx[2]
variable etot equal ke+c_er
thermo_style custom step ke c_er v_etot v_px v_py v_v1 v_v2 c_w[2]
%s
thermo 50
timestep 2e-4
run 3000
""" % (mode, THERMO_FULL)
    rc, log = run_lmp(deck, cwd=os.path.abspath(mode))
    rows = thermo(log)
    if not check(len(rows) > 10, "%s: no thermo output" % mode):
        continue
    first, last = rows[0], rows[-1]
    check(any(r["c_w[2]"] > 0 for r in rows), "%s: the grains never touched" % mode)
    check(last["c_w[2]"] == 0, "%s: the grains are still in contact at the end" % mode)
    near(last["v_etot"], first["v_etot"], rtol=0.01, msg="%s: kinetic energy after/before" % mode)
    for r in rows:
        near(r["v_px"], 0.0, atol=1e-12, msg="%s: x momentum at step %d" % (mode, r["Step"]))
        near(r["v_py"], 0.0, atol=1e-12, msg="%s: y momentum at step %d" % (mode, r["Step"]))
    # equal masses, head-on: velocities are exchanged (a little energy went into rotation
    # and the lateral offset deflects them slightly)
    near(last["v_v1"], -V0, rtol=0.02, msg="%s: grain 1 bounced back" % mode)
    near(last["v_v2"], V0, rtol=0.02, msg="%s: grain 2 bounced back" % mode)

finish()
