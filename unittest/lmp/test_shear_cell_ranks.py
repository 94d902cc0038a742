"""A sheared triclinic periodic box is the same on any rank count (the examples' shear
cell, shortened): examples/shear_cell/in.shear_cell with its shipped grains, compressed in
200 steps, relaxed in 50, then sheared at a rate that takes the tilt past half the length
(the box flips) within 70 steps, on 1, 2 and 4 ranks. Checked: the box flipped (the final
tilt lies within half a length, though the shear strain 0.84 put it beyond); contacts
carried load (pressure > 0); the final data file (positions, orientations, velocities,
box; its Atoms and Velocities lines by atom ID, as write_data writes each rank's atoms in
turn) and the last fields file are the same bytes on every rank count."""
import os
import re
import shutil

from lsdemtest import check, finish, run_lmp, thermo

EXAMPLE = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                        "examples", "shear_cell"))
RATE, NSHEAR, DT = 60.0, 70, 2.0e-4  # shear strain RATE * NSHEAR * DT = 0.84 at step 320
VARS = {"ncomp": 200, "nrelax": 50, "nshear": NSHEAR, "rate": RATE, "every": 40, "thermo": 40}

def sorted_sections(data):
    """the data file with each section's lines sorted (atom IDs lead them)"""
    parts = re.split(r"\n(Atoms[^\n]*|Velocities)\n\n", data)
    out = [parts[0]]
    for name, body in zip(parts[1::2], parts[2::2]):
        rows, rest = body.split("\n\n", 1) if "\n\n" in body else (body, "")
        out += [name, "\n".join(sorted(rows.splitlines(), key=lambda l: int(l.split()[0]))),
                rest]
    return "\n".join(out)


outs = {}
for np_ in (1, 2, 4):
    wd = os.path.abspath("np%d" % np_)
    shutil.rmtree(wd, ignore_errors=True)
    os.makedirs(wd)
    for f in ("in.shear_cell", "grains.lslib", "packed.data"):
        shutil.copy(os.path.join(EXAMPLE, f), wd)
    rc, log = run_lmp(os.path.join(wd, "in.shear_cell"), np=np_, vars=VARS, cwd=wd)
    if rc != 0:
        continue
    data = open(os.path.join(wd, "sheared.data")).read()
    vti = open(os.path.join(wd, "fields", "shear_%d.vti" % (250 + NSHEAR)), "rb").read()
    outs[np_] = (sorted_sections(data), vti)
    if np_ == 1:
        row = thermo(log)[-1]
        m = re.search(r"^\s*(\S+)\s+(\S+)\s+(\S+)\s+xy xz yz", data, re.M)
        xy, ly = float(m.group(1)), float(re.search(r"(\S+)\s+(\S+)\s+ylo yhi", data).group(2))
        gamma = RATE * NSHEAR * DT
        check(abs(xy) <= 0.5 * ly + 1e-12 and abs(xy - gamma * ly) > 0.4 * ly,
              "the box did not flip: xy %g, ly %g, shear strain %g" % (xy, ly, gamma))
        check(row["v_p"] > 0.0, "no contact pressure at the end (%r)" % row["v_p"])
        print("1 rank: flipped to xy %.4f (shear strain %.2f), p %.4g" % (xy, gamma, row["v_p"]))
check(len(outs) == 3, "runs that finished: %s" % sorted(outs))
if len(outs) == 3:
    check(outs[1][0] == outs[2][0] == outs[4][0],
          "the final data file differs between 1, 2 and 4 ranks")
    check(outs[1][1] == outs[2][1] == outs[4][1],
          "the last fields file differs between 1, 2 and 4 ranks")
    print("1, 2, 4 ranks: the same data file (%d bytes) and fields file (%d bytes)"
          % (len(outs[1][0]), len(outs[1][1])))
finish()
