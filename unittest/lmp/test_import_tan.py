"""lsdem-import-tan: a Kawamoto/Tan scene folder -> shape library + data file.
Independent expectations: the rotation matrix of each imported (scalar-first) quaternion equals
the report's eq 2.26 evaluated on the file's quaternion as printed; morphology files that are
symlinks to one file share one shape; positions are copied; lmp reads the data file; a
morphology with no solid (said first, naming the grain) or its centroid outside its grid is
refused."""
import math
import os
import subprocess

from lsdemtest import SHAPE_TOOL, check, finish, near, run_lmp, tan_scene

IMPORT = os.path.join(os.path.dirname(SHAPE_TOOL), "lsdem-import-tan")


def eq226(q):
    """Report eq 2.26 with Evans' (q1, q2, q3, q4) = the file's (q0, q1, q2, q3)."""
    q1, q2, q3, q4 = q
    return [[-q1*q1 + q2*q2 - q3*q3 + q4*q4, -2*(q1*q2 - q3*q4), 2*(q2*q3 + q1*q4)],
            [-2*(q1*q2 + q3*q4), q1*q1 - q2*q2 - q3*q3 + q4*q4, -2*(q1*q3 - q2*q4)],
            [2*(q2*q3 - q1*q4), -2*(q1*q3 + q2*q4), -q1*q1 - q2*q2 + q3*q3 + q4*q4]]


def textbook(w, x, y, z):
    """Body -> world matrix of a scalar-first unit quaternion."""
    return [[1 - 2*(y*y + z*z), 2*(x*y - w*z), 2*(x*z + w*y)],
            [2*(x*y + w*z), 1 - 2*(x*x + z*z), 2*(y*z - w*x)],
            [2*(x*z - w*y), 2*(y*z + w*x), 1 - 2*(x*x + y*y)]]


# grains 1, 3, 4 share one morphology file (a: an ellipsoid), grain 2 has the other (a sphere)
which = ["a", "b", "a", "a"]
pos = [(15.0, 15.0, 15.0), (35.0, 15.0, 15.0), (15.0, 35.0, 15.0), (35.0, 35.0, 35.0)]
rots = []
for i in range(4):                      # unit quaternions in the file's (x y z w) order
    a, b = 0.3 + 0.7 * i, 1.1 * i + 0.2
    v = (math.sin(a) * math.cos(b), math.sin(a) * math.sin(b), math.cos(a))
    h = 0.4 + 0.5 * i
    rots.append((v[0] * math.sin(h), v[1] * math.sin(h), v[2] * math.sin(h), math.cos(h)))
tan_scene("scene", which, pos, rots)

p = subprocess.run([IMPORT, "scene", "out", "--density", "2.0", "--box", "50", "50", "50"],
                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
check(p.returncode == 0, "lsdem-import-tan failed: %s" % p.stdout)
check("4 grains, 2 distinct shapes" in p.stdout, "two distinct shapes: %s" % p.stdout)

lines = open("out.data").read().splitlines()
atoms = [l.split() for l in lines[lines.index("Atoms # lsdem") + 2:] if l.strip()]
check(len(atoms) == 4, "four Atoms lines")
ids = {}
for row, w, x, qf in zip(atoms, which, pos, rots):
    ids.setdefault(w, set()).add(int(row[2]))
    near(float(row[3]), 2.0, msg="density")
    for k in range(3):
        near(float(row[4 + k]), x[k], atol=1e-6, msg="position")
    R, E = textbook(*map(float, row[7:11])), eq226(qf)
    for r in range(3):
        for c in range(3):
            near(R[r][c], E[r][c], atol=1e-9, msg="grain %s: R[%d][%d] vs eq 2.26" % (row[0], r, c))
check(len(ids["a"]) == 1 and len(ids["b"]) == 1 and ids["a"] != ids["b"],
      "shared files share a shape id: %r" % ids)

rc, log = run_lmp("units si\natom_style lsdem library out.lslib\nboundary f f f\n"
                  "read_data out.data\nrun 0\n")
check("4 atoms" in log, "lmp reads the imported data file")

# a morphology a grain cannot use is refused naming the grain, its file and its shape: grain
# 2's a 3 x 3 x 3 grid with no negative value (no solid; said before anything else: its mass
# of 0 on line 1 is not what is reported), grain 1's one whose centroid (line 3) lies outside
# the grid. Shapes are numbered by the sorted file paths: morph_2.dat (a file) is shape 0.
for name, grain, line1, centroid, values in (
        ("nosolid", 2, "0", "1 1 1", ["1"] * 27),
        ("offgrid", 1, "1", "1 1 -4", ["1"] * 13 + ["-1"] + ["1"] * 13)):
    tan_scene(name, ["a", "a"], pos[:2], rots[:2])
    morph = os.path.join(name, "Morphologies", "morph_%d.dat" % grain)
    os.remove(morph)
    with open(morph, "w") as f:
        f.write("%s\n0.4 0.4 0.4\n%s\n1\n0.5 0 0\n1\n3 3 3\n%s\n"
                % (line1, centroid, " ".join(values)))
    p = subprocess.run([IMPORT, name, name + "_out", "--box", "50", "50", "50"],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    want = (["lsdem-import-tan: grain 2 (nosolid/Morphologies/morph_2.dat, shape 0): ",
             "morph_2.dat: line 8: no level-set value is negative: the grid has no solid "
             "voxel, so the file describes no grain"] if name == "nosolid" else
            ["shape 0 ('morph_1.dat'): its centroid (the origin of its principal frame) is "
             "at grid coordinates (1, 1, -4), outside the grid"])
    check(p.returncode == 1 and all(w in p.stdout for w in want) and "line 1" not in p.stdout
          and not os.path.exists(name + "_out.lslib"), "%s refused: %s" % (name, p.stdout))
finish()
