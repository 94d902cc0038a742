"""atom_style lsdem: shape library report, data file input/output, restart, migration
between ranks, replicate, compute property/atom names, input errors (bad libraries, data
lines with a value too many or too few, fewer Atoms lines than the header declares, repeated
atom IDs), hybrid use.

Expected masses and moments come from closed forms (grain_decks.closed_form); restart and
migration are checked by continuing a run through a restart file and on 2 ranks, which must
reproduce an uninterrupted single-rank run (this needs the integrator state dwprev too)."""
import math
import re
import struct
import subprocess

from lsdemtest import LAMMPS_VERSION, SHAPE_TOOL, run_lmp, shape_tool, check, near, finish
import grain_decks as gd

LIB = gd.library()

# 1-based shape IDs, non-normalised quaternions on purpose; speeds carry grains across
# the periodic box and between ranks within the runs below
GRAINS = [
    dict(id=1, shape=1, density=2.5, x=(0.5, -1.0, 2.0), q=(0.9, 0.2, -0.3, 0.4),
         v=(0.3, -0.2, 0.1), w=(0.7, -1.1, 1.9)),
    dict(id=2, shape=2, density=1.0, x=(5.0, 0.0, 0.0), q=(2.0, 0.0, 0.0, 0.0),
         v=(-0.5, 0.0, 0.2), w=(0.0, 0.0, 0.0)),
    dict(id=3, shape=3, density=3.0, x=(-5.0, 3.0, -4.0), q=(0.5, 0.5, 0.5, 0.5),
         v=(0.1, 0.4, -0.3), w=(2.0, -1.0, 0.5)),
    dict(id=4, shape=1, density=0.7, x=(8.0, 8.0, -8.0), q=(0.0, 1.0, 0.0, 0.0),
         v=(1.5, 1.2, -0.9), w=(-0.4, 0.3, 1.2)),
    dict(id=5, shape=3, density=1.3, x=(-8.0, -8.0, 8.0), q=(0.1, -0.7, 0.2, 0.3),
         v=(-1.3, -1.1, 0.8), w=(0.9, 0.9, -0.9)),
]
gd.write_data("grains.data", GRAINS)

HEAD = "units lj\natom_style lsdem library %s\n" % LIB


def fnv1a(data, h=0xcbf29ce484222325):
    """FNV-1a 64 (the library's checksum, doc/shape_library.rst) from its definition."""
    for b in data:
        h = ((h ^ b) * 0x100000001b3) & 0xffffffffffffffff
    return h


def section(path, name):
    """The lines of one data file section (without the title)."""
    text = open(path).read()
    body = text.split("\n" + name)[1].split("\n\n", 2)[1]
    return body.strip().splitlines()


# ---- library report and data input --------------------------------------------------
rc, log = run_lmp(HEAD + "read_data grains.data\n" + gd.PROPS + gd.dump_line("d", 1, "a.dump")
                  + "run 0\nwrite_data a.data\n")
check("LSDEM shape library: 3 shapes" in log, "library summary line missing")
for sid, name, kind in ((1, "ellipsoid", "grid"), (2, "sphere", "sphere"), (3, "box", "grid")):
    vol = gd.closed_form(sid)[0]
    check(re.search(r"^\s+%d\s+%s\s+%s\s+\d+\s+\S+\s+%s\s*$" % (sid, name, kind, "%.6g" % vol),
                    log, re.M), "shape line %d %s %s %.6g not in the log" % (sid, name, kind, vol))
# coarse grids: spacing > R/10 with R the equivalent-volume radius; the ball has no grid
for sid, name, h in ((1, "ellipsoid", 0.2), (3, "box", 0.25)):
    req = (3 * gd.closed_form(sid)[0] / (4 * math.pi)) ** (1 / 3)
    want = "shape %d (%s) has grid spacing %g, coarser than R/10 = %.6g" % (sid, name, h, 0.1 * req)
    check(want in log, "coarse-grid warning missing: %s" % want)
check("shape 2 (" not in log, "the analytic ball must not get a grid warning")

# more than 20 shapes: one summary line instead of a table; coarse-grid warnings name at
# most 10 shapes and count the rest
shape_tool("merge", "many.lslib", *(["ball.lslib"] * 8 + ["box.lslib"] * 13))
rc, log = run_lmp("units lj\natom_style lsdem library many.lslib\n")
check("LSDEM shape library: 21 shapes" in log and "bounding radius 0.5 to " in log
      and not re.search(r"^\s+21\s+box", log, re.M), "summary for 21 shapes:\n" + log[-800:])
named = re.findall(r"shape (\d+) \(box\) has grid spacing", log)
check(named == [str(k) for k in range(9, 19)] and "3 more shapes have grid spacings" in log,
      "coarse warnings for shapes 9..18 and a count of 3 more: %r" % named)

frame = gd.read_dump("a.dump")[0][1]
for g in GRAINS:
    a = frame[g["id"]]
    vol, inertia = gd.closed_form(g["shape"])
    near(a["mass"], g["density"] * vol, rtol=1e-13, msg="mass of grain %d" % g["id"])
    for k in range(3):
        near(a["c_p[%d]" % (6 + k)], g["density"] * inertia[k], rtol=1e-13,
             msg="inertia%d of grain %d" % (k + 1, g["id"]))
    check(a["c_p[5]"] == g["shape"], "shape-ID of grain %d: %g" % (g["id"], a["c_p[5]"]))
    qn = gd.qnormalize(g["q"])
    for k in range(4):
        near(gd.quat(a)[k], qn[k], atol=1e-15, msg="normalised quat of grain %d" % g["id"])
    for k, c in enumerate("xyz"):
        check(a[c] == g["x"][k], "position of grain %d" % g["id"])
        check(a["omega" + c] == g["w"][k], "omega of grain %d" % g["id"])
near(frame[2]["radius"], gd.BALL, rtol=1e-15, msg="bounding radius of the analytic ball")
check(frame[1]["radius"] >= gd.ELL[0] and frame[3]["radius"] >= gd.norm(gd.BOX),
      "bounding radii must contain the solids")

# ---- write_data -> read_data round trip ---------------------------------------------
atoms_a = section("a.data", "Atoms")
for line, g in zip(atoms_a, GRAINS):
    w = line.split()
    check(int(w[0]) == g["id"] and int(w[2]) == g["shape"], "write_data id/shape: " + line)
    near(float(w[3]), g["density"], rtol=1e-15, msg="write_data density of grain %d" % g["id"])
    check(tuple(map(float, w[4:7])) == g["x"], "write_data position: " + line)
rc, log = run_lmp(HEAD + "read_data a.data\nwrite_data b.data\n")
check(section("a.data", "Atoms") == section("b.data", "Atoms"),
      "Atoms section changed in a write_data/read_data round trip")
check(section("a.data", "Velocities") == section("b.data", "Velocities"),
      "Velocities section changed in a write_data/read_data round trip")

# ---- restart and migration: every path must reproduce one uninterrupted run ----------
RUN = gd.PROPS + "fix 1 all nve/lsdem\ntimestep 0.005\n"
run_lmp(HEAD + "read_data grains.data\n" + RUN + gd.dump_line("d", 1200, "ref.dump")
        + "run 1200\n")
run_lmp(HEAD + "read_data grains.data\n" + RUN + gd.dump_line("d", 1200, "np2.dump")
        + "run 600\nwrite_restart mid.restart\nrun 600\n", np=2)
run_lmp("read_restart mid.restart\n" + RUN + gd.dump_line("d", 1200, "rst1.dump")
        + "run 600\n")
run_lmp("read_restart mid.restart\n" + RUN + gd.dump_line("d", 1200, "rst2.dump")
        + "run 600\n", np=2)
ref = gd.read_dump("ref.dump")[-1]
check(ref[0] == 1200, "reference run ends at step 1200")
moved = sum(1 for g in GRAINS if any(abs(ref[1][g["id"]][c] - g["x"][k]) > 3.0
                                     for k, c in enumerate("xyz")))
check(moved >= 3, "grains should travel across the box in the reference run")
for name in ("np2.dump", "rst1.dump", "rst2.dump"):
    step, atoms = gd.read_dump(name)[-1]
    check(step == 1200 and len(atoms) == len(GRAINS), "%s: final frame" % name)
    for i, a in atoms.items():
        r = ref[1][i]
        for c in ("x", "y", "z"):  # wrapping at different steps changes the last bits
            near(a[c], r[c], atol=1e-11, msg="%s grain %d %s" % (name, i, c))
        for c in ("vx", "vy", "vz", "omegax", "omegay", "omegaz", "mass", "c_p[5]", "c_p[6]",
                  "c_p[7]", "c_p[8]", "c_p[1]", "c_p[2]", "c_p[3]", "c_p[4]"):
            near(a[c], r[c], rtol=1e-13, atol=1e-15, msg="%s grain %d %s" % (name, i, c))

# ---- ghosts: quat/omega forward, torque reverse; contacts across ranks match one rank --
CHAIN = []
for i, (x, y) in enumerate([(x, y) for x in (-3.0, -1.0, 1.0, 3.0) for y in (-1.3, 1.3)]):
    s = 0.37 * (i + 1)
    CHAIN.append(dict(id=i + 1, shape=1 if i % 2 == 0 else 3, density=1.0,
                      x=(x + 0.05 * math.sin(7 * s), y, 0.05 * i),
                      q=gd.qnormalize((math.cos(s), math.sin(2 * s), math.cos(3 * s), 0.3)),
                      v=(0.4 * math.sin(5 * s), 0.3 * math.cos(3 * s), 0.2 * math.sin(s)),
                      w=(math.cos(2 * s), math.sin(3 * s), math.cos(5 * s))))
gd.write_data("chain.data", CHAIN, box=(-6.0, 6.0, -4.0, 4.0, -4.0, 4.0))
CONTACT = (HEAD + "atom_modify map array\nnewton on\ncomm_modify vel yes\nread_data chain.data\n"
           + gd.PROPS + "pair_style lsdem\npair_coeff * * 1000 1000 0.5\n"
           "fix 1 all nve/lsdem\ntimestep 0.001\n")
run_lmp(CONTACT + gd.dump_line("d", 2000, "chain1.dump") + "run 2000\n")
run_lmp(CONTACT + gd.dump_line("d", 2000, "chain2.dump") + "run 2000\n", np=2)
c0, c1 = gd.read_dump("chain1.dump")[0][1], gd.read_dump("chain1.dump")[-1][1]
c2 = gd.read_dump("chain2.dump")[-1][1]
check(max(abs(c1[i][c] - c0[i][c]) for i in c0 for c in ("vx", "omegax", "omegay")) > 0.1,
      "the chain grains should collide")
for i in c1:
    for c in c1[i]:
        near(c2[i][c], c1[i][c], atol=1e-9, msg="chain grain %d %s on 2 ranks vs 1" % (i, c))

# ---- replicate keeps shapes, orientations and masses ---------------------------------
run_lmp(HEAD + "read_data grains.data\nreplicate 2 1 1\n" + gd.PROPS
        + gd.dump_line("d", 1, "rep.dump") + "run 0\n")
rep = gd.read_dump("rep.dump")[0][1]
check(len(rep) == 2 * len(GRAINS), "replicate 2 1 1 doubles the grains")
for g in GRAINS:
    a, b = rep[g["id"]], rep[g["id"] + len(GRAINS)]
    for c in ("mass", "radius", "c_p[1]", "c_p[2]", "c_p[3]", "c_p[4]", "c_p[5]", "c_p[6]",
              "omegax", "omegay", "omegaz", "y", "z"):
        check(a[c] == b[c], "replicated grain %d: %s %r vs %r" % (g["id"], c, a[c], b[c]))

# ---- input errors name the offending atom and the valid range ------------------------
bad = [dict(g) for g in GRAINS]
bad[1]["shape"] = 4
gd.write_data("badshape.data", bad)
rc, log = run_lmp(HEAD + "read_data badshape.data\n", expect_fail=True)
check(rc != 0 and "Atom 2 in Atoms section has shape-ID 4; the shape library has shapes 1 to 3"
      in log, "out-of-range shape-ID error:\n" + log[-600:])

# a restart re-opens its library by path: one that lost shapes, or whose shapes were
# reordered (ball, box, ellipsoid), is refused naming the atom, instead of a crash
shape_tool("merge", "swap.lslib", "ell.lslib", "ball.lslib", "box.lslib")
run_lmp(HEAD.replace(LIB, "swap.lslib") + "read_data grains.data\n" + RUN
        + "run 10\nwrite_restart swap.restart\n")
for parts, expect in ((["ell.lslib"], "atom 2 has shape-ID 2, but the shape library "
                       "swap.lslib has shapes 1 to 1"),
                      (["ball.lslib", "box.lslib", "ell.lslib"], "atom 1 has bounding radius")):
    shape_tool("merge", "swap.lslib", *parts)
    rc, log = run_lmp("read_restart swap.restart\n" + RUN + "run 10\n", expect_fail=True)
    check(rc != 0 and expect in log and "written with another library" in log,
          "restart with library %s: expected %r:\n%s" % (parts, expect, log[-600:]))

bad = [dict(g) for g in GRAINS]
bad[2]["q"] = (0.0, 0.0, 0.0, 0.0)
gd.write_data("badquat.data", bad)
rc, log = run_lmp(HEAD + "read_data badquat.data\n", expect_fail=True)
check(rc != 0 and "Atom 3 in Atoms section has invalid quaternion" in log,
      "zero quaternion error:\n" + log[-600:])
rc, log = run_lmp("atom_style lsdem library no-such-file.lslib\n", expect_fail=True)
check(rc != 0 and "cannot open shape library no-such-file.lslib" in log,
      "missing library error:\n" + log[-600:])
# a byte changed inside a shape's section (the header and its checksum intact): open alone
# would not see it, the atom style's check of every section does
raw = bytearray(open(LIB, "rb").read())
raw[len(raw) // 2] ^= 0x40
open("damaged.lslib", "wb").write(bytes(raw))
rc, log = run_lmp("atom_style lsdem library damaged.lslib\n", expect_fail=True)
check(rc != 0 and "shape library damaged.lslib is damaged" in log
      and "section checksum mismatch" in log, "damaged library section:\n" + log[-600:])
# a library whose TOC (resealed: its checksum matches) gives the ball a bounding radius of
# 0.05 while its nodes lie at 0.5: lsdem-shape verify and the atom style refuse it, naming
# the shape (the grains would pass through each other)
raw = bytearray(open("ball.lslib", "rb").read())
raw[64 + 88:64 + 96] = struct.pack("<d", 0.05)               # TOC entry 0: radius
count = struct.unpack("<I", raw[20:24])[0]
raw[56:64] = struct.pack("<Q", fnv1a(raw[64:64 + 360 * count], fnv1a(raw[:56])))
open("shrunk.lslib", "wb").write(bytes(raw))
p = subprocess.run([SHAPE_TOOL, "verify", "shrunk.lslib"], stdout=subprocess.PIPE,
                   stderr=subprocess.STDOUT, text=True)
want = "lies 0.5 from the centroid, beyond the bounding radius 0.05"
check(p.returncode == 1 and "shape 0 ('sphere'): node " in p.stdout and want in p.stdout
      and "1 bad" in p.stdout,
      "lsdem-shape verify of a too small radius:\n" + p.stdout)
rc, log = run_lmp("atom_style lsdem library shrunk.lslib\n", expect_fail=True)
check(rc != 0 and want in log, "atom style with a too small radius:\n" + log[-600:])
# lsdem-shape list shows the table and refuses it as verify does (it listed it as sound)
p = subprocess.run([SHAPE_TOOL, "list", "shrunk.lslib"], stdout=subprocess.PIPE,
                   stderr=subprocess.STDOUT, text=True)
check(p.returncode == 1 and "shrunk.lslib: 1 shape" in p.stdout
      and "lsdem-shape: list: shape library: shape 0 ('sphere'): node " in p.stdout
      and want in p.stdout and "lsdem-shape: list: shrunk.lslib: 1 of 1 shapes bad (above): "
      "atom_style lsdem refuses this library; make it again" in p.stdout,
      "lsdem-shape list of a too small radius:\n" + p.stdout)

# every Atoms and Velocities line must have the values of the section's first line: LAMMPS
# checks only that one, passes over extra values and shifts the values after a line with
# one missing (its reader crashes two lines later). The check cannot tell whether the
# text after a line's values is its own or the next line's, and names both; when lines end
# in their last value it is the whole next line, here the bad one, that is shown.
def data_with(name, section, k, edit):
    lines = open("grains.data").read().split("\n")
    i = lines.index(section) + 2 + k
    lines[i] = edit(lines[i])
    open(name, "w").write("\n".join(lines))
    return lines[i]


drop = lambda line: line.rsplit(" ", 1)[0]
# LAMMPS since 2022 checks every line's values itself ("Incorrect format in Atoms section of
# data file: <the line>"); atom_style lsdem's own check is for 29 Sep 2021 (compat header)
LAMMPS_CHECKS_LINES = LAMMPS_VERSION >= 20220000


def bad_line(log, section, n, line=None):
    """log refuses the `section` line `line` (n values wanted), LAMMPS's way or LSDEM's."""
    if LAMMPS_CHECKS_LINES:
        return "Incorrect format in %s section of data file: %s" % (section, line or "") in log
    return ("each %s line needs %d values" % (section, n) in log
            and (line is None or "'%s' (%d values)" % (line, len(line.split())) in log))


cases = [("short.data", "Atoms # lsdem", 2, drop, 11),          # atom 3 lacks qz
         ("extra.data", "Atoms # lsdem", 3, lambda l: l + " 7", 11),
         ("vshort.data", "Velocities", 1, drop, 7),              # atom 2 lacks wz
         ("vextra.data", "Velocities", 4, lambda l: l + " 1", 7)]  # the last line, atom 5
for name, section, k, edit, n in cases:
    line = data_with(name, section, k, edit)
    rc, log = run_lmp(HEAD + "read_data %s\nrun 0\n" % name, expect_fail=True)
    check(rc != 0 and bad_line(log, section.split()[0], n, line),
          "%s: refused showing the line:\n%s" % (name, log[-700:]))
# image flags on all lines but one (atom 3's)
lines = open("grains.data").read().split("\n")
first = lines.index("Atoms # lsdem") + 2
for i in (0, 1, 3, 4):
    lines[first + i] += " 0 0 0"
open("flags.data", "w").write("\n".join(lines))
rc, log = run_lmp(HEAD + "read_data flags.data\nrun 0\n", expect_fail=True)
check(rc != 0 and bad_line(log, "Atoms", 14, lines[first + 2]),
      "a line without image flags:\n" + log[-700:])
# a comment after the values is no value (as on the first line, where LAMMPS strips it)
data_with("comment.data", "Atoms # lsdem", 2, lambda l: l + "   # the box")
rc, log = run_lmp(HEAD + "read_data comment.data\nrun 0\n")
check(rc == 0, "a comment after an Atoms line's values")
# on 2 ranks the rank that owns the line stops the run (extra value on atom 4's line,
# rank 1's: x = 8 on a 2 by 1 by 1 grid)
rc, log = run_lmp(HEAD + "processors 2 1 1\nread_data extra.data\nrun 0\n", np=2,
                  expect_fail=True)
check(rc != 0 and bad_line(log, "Atoms", 11), "np 2 extra value:\n" + log[-700:])

# a header that declares more atoms than the Atoms section holds: LAMMPS reads on into the
# blank line and says only "Incorrect atom format"; the message names the count, the lines
# and what follows them. Lines numbered from 1 as in an editor (write_data's layout: the
# Atoms keyword, a blank line, the 5 atoms, a blank line, Velocities).
text = open("grains.data").read()
lines = text.split("\n")
first = lines.index("Atoms # lsdem") + 3
atoms_lines = "5 lines (lines %d-%d)" % (first, first + 4)
open("more.data", "w").write(text.replace("5 atoms", "7 atoms"))
open("eof.data", "w").write(text.replace("5 atoms", "6 atoms").split("\nVelocities")[0])
gap = lines[:first + 1] + [""] + lines[first + 1:]          # a blank line after atom 2
open("gap.data", "w").write("\n".join(gap))
fix = "; fix the atoms count in the header or add the %d missing Atoms line%s"
for name, np, tail in (
        ("more.data", 1, ": line %d starts section 'Velocities'" % (lines.index("Velocities") + 1)
         + fix % (2, "s")),
        ("eof.data", 2, " at the end of the file" + fix % (1, "")),
        ("gap.data", 1, None)):
    rc, log = run_lmp(HEAD + "processors %d 1 1\nread_data %s\nrun 0\n" % (np, name), np=np,
                      log="count.log", expect_fail=True)
    log = open("count.log").read()
    want = ("read_data: data file %s: the header declares %d atoms but the Atoms section ends "
            "after " % (name, {"more.data": 7, "eof.data": 6, "gap.data": 5}[name])
            + (atoms_lines + tail if tail else "2 lines (lines %d-%d): line %d is blank, and "
               "Atoms lines go on at line %d; remove the blank line (an Atoms section has "
               "none)" % (first, first + 1, first + 2, first + 3)))
    if name == "eof.data" and LAMMPS_CHECKS_LINES:
        # LAMMPS 2025 reads the declared count of lines before any reaches the atom style
        want = "ERROR: Unexpected end of data file"
    check(rc != 0 and want in log and "Incorrect atom format" not in log,
          "%s, np %d: expected %r:\n%s" % (name, np, want, log[-700:]))
rc, log = run_lmp(HEAD + "processors 2 1 1\nread_data grains.data\nrun 0\n", np=2)
check(rc == 0 and "5 atoms" in log, "grains.data still reads on 2 ranks")

# an atom ID given to two grains (not seen by LAMMPS's read_data when the largest ID is not
# below the atom count) stops the run naming it, also when the two are on different ranks:
# IDs 1 3 3 4 7, the two 3s at x = 5 (rank 1) and x = -5 (rank 0); ID 3 is sorted on rank 1
dup = [dict(g) for g in GRAINS]
for g, new_id in zip(dup, (1, 3, 3, 4, 7)):
    g["id"] = new_id
gd.write_data("dup.data", dup)
for np in (1, 2):
    rc, log = run_lmp(HEAD + "processors %d 1 1\nread_data dup.data\nrun 0\n" % np, np=np,
                      log="dup.log", expect_fail=True)
    log = open("dup.log").read()
    check(rc != 0 and "1 atom ID is given to more than one atom: 3 (2 atoms)" in log
          and ("(found on rank 1)" in log) == (np == 2),
          "np %d: repeated atom ID:\n%s" % (np, log[-700:]))

# LAMMPS's set diameter/mass/density would change a grain's radius or mass apart from its
# shape and moments: refused at the run, naming the atom, on all ranks (atom 4, at x = 8, is
# rank 1's on a 2 by 1 by 1 grid)
for cmd, expect in (("set atom 4 diameter 3.0", "atom 4 has radius 1.5 but its shape 1 has "
                     "bounding radius"),
                    ("set atom 4 mass 5.0", "atom 4 has mass 5 but moments of inertia"),
                    ("set atom 4 density 5.0", "atom 4 has mass ")):
    for np in (1, 2):
        rc, log = run_lmp(HEAD + "processors %d 1 1\nread_data grains.data\n" % np + cmd
                          + "\n" + RUN + "run 0\n", np=np, log="set.log", expect_fail=True)
        log = open("set.log").read()
        check(rc != 0 and expect in log and "set diameter, set mass and set density do not "
              "apply" in log and ("(found on rank 1)" in log) == (np == 2),
              "%s, np %d: expected %r:\n%s" % (cmd, np, expect, log[-600:]))
rc, log = run_lmp(HEAD + "read_data grains.data\nset atom 4 type 1\n" + RUN + "run 0\n")
check(rc == 0, "other set commands still work")
rc, log = run_lmp("atom_style lsdem grains.lslib\n", expect_fail=True)
check(rc != 0 and "Illegal atom_style lsdem command" in log, "bad syntax error")

# ---- hybrid with bonds (membranes): create, run, restart, run again -------------------
rc, log = run_lmp("""units lj
atom_style hybrid lsdem library %s bond
region b block -5 5 -5 5 -5 5
create_box 1 b bond/types 1 extra/bond/per/atom 2
mass 1 1.0
create_atoms 1 single 0 0 0
create_atoms 1 single 3 0 0
velocity all set 0.1 0 0
fix 1 all nve/lsdem
run 10
write_restart hybrid.restart
clear
read_restart hybrid.restart
fix 1 all nve/lsdem
%s
run 10
""" % (LIB, gd.PROPS + gd.dump_line("d", 20, "hyb.dump")))
hyb = gd.read_dump("hyb.dump")[-1][1]
vol = gd.closed_form(1)[0]
check(rc == 0 and len(hyb) == 2, "hybrid lsdem/bond run through a restart")
for i, x0 in ((1, 0.0), (2, 3.0)):
    near(hyb[i]["x"], x0 + 0.1 * 20 * 0.005, atol=1e-12, msg="hybrid grain %d moved" % i)
    near(hyb[i]["mass"], vol, rtol=1e-13, msg="create_atoms grain: shape 1 at density 1")

finish()
