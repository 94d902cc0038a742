"""fix network/lsdem: the contact network of three cubes at rest on a floor wall (cube 3
across cubes 1 and 2; g = 1, unit masses).

Expected from statics: four lines, (1,3) and (2,3) carrying normal forces that sum to
cube 3's weight 1 (about 1/2 each: how it splits depends on the cubes' small tilts),
(1,floor) and (2,floor) each 1 plus what that cube carries (about 3/2); mean normal force 1, so the two floor
contacts are strong: strong fraction 1/2, their share of the load 3/4; the grain contacts'
normals are vertical, so their fabric deviator has Dzz = 5, Dxx = -5/2 and anisotropy 7.5
(Kanatani's, as compute fabric/lsdem's). Cubes 1 and 2 do not touch. The same in two-way mode (two tests per pair merged into one line). The .vtp holds
polylines centre - point - centre (3 points) and centre - point (2 for a wall); 1 and 2
ranks write the same bytes. The .vtp's normal array holds unit vectors along which the
force gives the normal force (one-way: to 1e-12; a merged two-way line keeps its first test's
normal: 1e-5), vertical here (down onto cubes 1 and 2, up from the floor). With band v_name the grain lines split into inside (both grains
flagged) and outside, each with its count and fabric, on 1 and 2 ranks."""
import os
import re

from contact_decks import Grain, box_library, write_data, head, THERMO_FULL
from lsdemtest import check, finish, near, run_lmp, thermo

lib = box_library("cube.lslib", 0.5, 0.05, 600)
write_data("wall.data", (-3, 3, -3, 3, 0, 4),
           [Grain((-0.55, 0, 0.5)), Grain((0.55, 0, 0.5)), Grain((0, 0, 1.5))])


def deck(pair_args):
    return head(lib, "wall.data", boundary="f f f") + """
pair_style lsdem %s
pair_coeff * * 1000 1000 0.5 cn 2.0
fix grav all gravity 1.0 vector 0 0 -1
fix 1 all nve/lsdem damping 4.0
fix floor all wall/lsdem plane 0 0 0 0 0 1 1000 1000 0.5 cn 2.0
fix net all network/lsdem 2000 net wall floor
thermo_style custom step f_net[1] f_net[2] f_net[3] f_net[4] f_net[5] f_net[7] f_net[11]
%s
thermo 2000
timestep 1e-3
run 4000
""" % (pair_args, THERMO_FULL)


def read_vtp(path):
    text = open(path).read()
    arrays = dict(re.findall(r'Name="(\w+)"[^>]*>\n([^<]*)</DataArray>', text))
    num = lambda name: [float(v) for v in arrays[name].split()]
    nlines = int(re.search(r'NumberOfLines="(\d+)"', text).group(1))
    vec = lambda name: list(zip(*[iter(num(name))] * 3))
    return (nlines, num("id_a"), num("id_b"), num("normal_force"), num("offsets"), num("strong"),
            vec("force"), vec("normal"))


def check_network(name, wd, log):
    row = thermo(log)[-1]
    check(row.get("f_net[1]") == 4, "%s: 4 contacts, got %r" % (name, row.get("f_net[1]")))
    near(row.get("f_net[2]", 0), 1.0, rtol=1e-6, msg=name + " mean normal force")
    near(row.get("f_net[3]", 0), 0.5, atol=1e-12, msg=name + " strong fraction")
    near(row.get("f_net[4]", 0), 0.75, rtol=1e-6, msg=name + " strong share")
    # both grain contacts are cube 3's flat face on the top faces of 1 and 2: vertical
    # normals, F = e_z e_z, D = 15/2 (F - I/3): Dzz = 5, Dxx = -5/2, anisotropy 7.5
    near(row.get("f_net[7]", 0), 5.0, rtol=1e-3, msg=name + " contact-normal fabric Dzz")
    near(row.get("f_net[5]", 0), -2.5, rtol=1e-3, msg=name + " contact-normal fabric Dxx")
    near(row.get("f_net[11]", 0), 7.5, rtol=1e-3, msg=name + " contact-normal anisotropy")
    path = os.path.join(wd, "net_4000.vtp")
    if not os.path.exists(path):
        check(False, name + ": no net_4000.vtp")
        return b""
    nlines, ida, idb, fn, offsets, strong, force, normal = read_vtp(path)
    check(nlines == 4, "%s: %d lines" % (name, nlines))
    got = {(int(a), int(b)): f for a, b, f in zip(ida, idb, fn)}
    check(sorted(got) == [(1, -1), (1, 3), (2, -1), (2, 3)], "%s: lines %r" % (name, sorted(got)))
    near(got.get((1, 3), 0.0) + got.get((2, 3), 0.0), 1.0, rtol=1e-6,
         msg=name + " normal forces on cube 3")
    for key in ((1, 3), (2, 3)):
        check(0.45 < got.get(key, 0.0) < 0.55, "%s normal force %r: %r"
              % (name, key, got.get(key)))
    # each bottom cube stands on the floor with its own weight and what cube 3 puts on it
    for a in (1, 2):
        near(got.get((a, -1), 0.0), 1.0 + got.get((a, 3), 0.0), rtol=1e-6,
             msg="%s floor under cube %d" % (name, a))
    # grain-grain lines have 3 points (centre, point, centre), wall lines 2
    widths = [int(b - a) for a, b in zip([0.0] + offsets[:-1], offsets)]
    check(widths == [3 if b > 0 else 2 for b in idb], "%s: points per line %r" % (name, widths))
    check(strong == [1.0 if b < 0 else 0.0 for b in idb], "%s: strong flags %r" % (name, strong))
    # the normal array: unit vectors, the normal force the force along them (a merged
    # two-way line keeps its first test's normal, its normal force sums each test's own);
    # the partner's outward normal points to grain a: down from cube 3 onto 1 and 2, up
    # from the floor
    for b, f, fv, n in zip(idb, fn, force, normal):
        near(sum(c * c for c in n), 1.0, rtol=1e-12, msg="%s: |normal| of line to %d" % (name, b))
        near(sum(x * y for x, y in zip(fv, n)), f, rtol=1e-12 if "oneway" in name else 1e-5,
             msg="%s: force . normal" % name)
        check(n[2] * (1 if b < 0 else -1) > 0.99, "%s: normal %r of the line to %d" % (name, n, b))
    pvd = open(os.path.join(wd, "net.pvd")).read()
    check(all('file="net_%d.vtp"' % s in pvd for s in (0, 2000, 4000)), name + ": .pvd")
    return open(path, "rb").read()


outs = {}
for name, args, np_ in (("oneway", "", 1), ("oneway", "", 2), ("twoway", "mode twoway", 1)):
    wd = os.path.abspath("%s_np%d" % (name, np_))
    rc, log = run_lmp(deck(args), np=np_, cwd=wd)
    if rc == 0:
        outs[(name, np_)] = check_network("%s np=%d" % (name, np_), wd, log)
check(outs.get(("oneway", 1)) and outs.get(("oneway", 1)) == outs.get(("oneway", 2)),
      "1 and 2 ranks write different networks")

# band v_name: a line is inside when both its grains are flagged. Cubes 2 and 3 flagged:
# (2,3) inside, (1,3) outside; cube 3 alone: both outside. Each side's fabric is vertical.
for flag, inside, outside in (("id>=2", 1, 1), ("id==3", 0, 2)):
    for np_ in (1, 2):
        band = deck("").replace("fix net all network/lsdem 2000 net wall floor",
                                "variable inband atom %s\nfix net all network/lsdem 2000 net band "
                                "v_inband wall floor" % flag)
        band = band.replace("f_net[5] f_net[7] f_net[11]", "f_net[12] f_net[15] f_net[19] "
                            "f_net[20] f_net[23] f_net[27]")
        rc, log = run_lmp(band, np=np_, cwd=os.path.abspath("band_%s_np%d" % (inside, np_)))
        row = thermo(log)[-1] if rc == 0 else {}
        what = "band %s on %d rank(s)" % (flag, np_)
        check(row.get("f_net[12]") == inside and row.get("f_net[20]") == outside,
              "%s: %r lines inside, %r outside (expected %d, %d)"
              % (what, row.get("f_net[12]"), row.get("f_net[20]"), inside, outside))
        for count, dzz, a in (("f_net[12]", "f_net[15]", "f_net[19]"),
                              ("f_net[20]", "f_net[23]", "f_net[27]")):
            if row.get(count):
                near(row.get(dzz, 0), 5.0, rtol=1e-3, msg="%s: %s" % (what, dzz))
                near(row.get(a, 0), 7.5, rtol=1e-3, msg="%s: %s" % (what, a))
            else:
                check(row.get(a) == 0.0, "%s: no line, anisotropy %r" % (what, row.get(a)))
rc, log = run_lmp(deck("").replace("network/lsdem 2000 net wall", "network/lsdem 2000 net band "
                                   "c_x wall"), cwd=os.path.abspath("band_bad"), expect_fail=True)
check(rc != 0 and "band takes an atom-style variable" in log, "band c_x: %s" % log[-600:])
finish()
