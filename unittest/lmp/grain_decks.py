"""grain_decks -- shared pieces of the atom style / integrator tests (atom_style lsdem,
fix nve/lsdem, compute erotate/lsdem): a three-shape library with closed-form mass
properties, data files, dump parsing and independent quaternion algebra."""
import math
import os

from lsdemtest import shape_tool

# Library shapes (1-based IDs as in data files) and their closed-form volume and principal
# moments per unit density, computed here independently of the code under test.
ELL = (2.0, 1.2, 0.8)      # ellipsoid semi-axes, grid spacing 0.2 (coarser than R/10)
BALL = 0.5                 # analytic sphere radius (kind "sphere": no rotation)
BOX = (1.0, 0.5, 0.3)      # box half-extents, grid spacing 0.25 (coarser than R/10)


def closed_form(shape_id):
    """(volume, (I1, I2, I3)) at density 1 for shape 1, 2 or 3 of library()."""
    if shape_id == 1:
        a, b, c = ELL
        v = 4.0 / 3.0 * math.pi * a * b * c
        return v, (v * (b * b + c * c) / 5, v * (a * a + c * c) / 5, v * (a * a + b * b) / 5)
    if shape_id == 2:
        v = 4.0 / 3.0 * math.pi * BALL ** 3
        return v, (0.4 * v * BALL ** 2,) * 3
    hx, hy, hz = BOX
    v = 8.0 * hx * hy * hz
    return v, (v * (hy * hy + hz * hz) / 3, v * (hx * hx + hz * hz) / 3,
               v * (hx * hx + hy * hy) / 3)


def library(path="grains.lslib"):
    """Shapes 1 ellipsoid, 2 analytic ball, 3 box, merged into one library."""
    if not os.path.exists(path):
        shape_tool("analytic", "ell.lslib", "ellipsoid", *ELL, "--nodes", 50,
                   "--spacing", 0.2)
        shape_tool("analytic", "ball.lslib", "sphere", BALL, "--analytic", "--nodes", 20)
        shape_tool("analytic", "box.lslib", "box", *BOX, "--spacing", 0.25, "--nodes", 30)
        shape_tool("merge", path, "ell.lslib", "ball.lslib", "box.lslib")
    return path


def pile(lib="pile.lslib", data="pile.data"):
    """The angular pile of the rank, thread, balance and impulse tests: six random shapes
    (100 nodes) and the 140 of 200 grains that fit loosely in a 6 x 6 x 9 box (made once).
    Returns both paths."""
    if not os.path.exists(lib):
        shape_tool("random", lib, "--count", 6, "--size", 1.0, "--size-spread", 0.2,
                   "--elongation", 0.7, "--flatness", 0.7, "--angularity", 0.15,
                   "--roughness", 0.02, "--seed", 11, "--nodes", 100, "--spacing", 0.06)
    if not os.path.exists(data):
        shape_tool("pack", lib, data, "--count", 200, "--box", 6, 6, 9, "--density", 1.0,
                   "--seed", 5)
    return os.path.abspath(lib), os.path.abspath(data)


def write_data(path, grains, box=(-10.0, 10.0, -10.0, 10.0, -10.0, 10.0)):
    """grains: list of dicts with id, shape, density, x, q (and optional v, w, type)."""
    lines = ["LAMMPS data file (grain tests)", "", "%d atoms" % len(grains), "1 atom types",
             "", "%r %r xlo xhi" % box[0:2], "%r %r ylo yhi" % box[2:4],
             "%r %r zlo zhi" % box[4:6], "", "Atoms # lsdem", ""]
    for g in grains:
        lines.append("%d %d %d %r %r %r %r %r %r %r %r" % (
            (g["id"], g.get("type", 1), g["shape"], g["density"]) + tuple(g["x"])
            + tuple(g["q"])))
    lines += ["", "Velocities", ""]
    for g in grains:
        lines.append("%d %r %r %r %r %r %r" % ((g["id"],) + tuple(g.get("v", (0, 0, 0)))
                                               + tuple(g.get("w", (0, 0, 0)))))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


# dump columns used by the tests: c_p[1..8] = qw qx qy qz shape inertia1 inertia2 inertia3
PROPS = "compute p all property/atom qw qx qy qz shape inertia1 inertia2 inertia3\n"
COLUMNS = ("id x y z vx vy vz omegax omegay omegaz mass radius "
           "c_p[1] c_p[2] c_p[3] c_p[4] c_p[5] c_p[6] c_p[7] c_p[8]")


def dump_line(name, every, fname, group="all"):
    """A dump custom line with full precision for the standard columns."""
    return ("dump %s %s custom %d %s %s\ndump_modify %s format float %%.17g sort id\n"
            % (name, group, every, fname, COLUMNS, name))


def read_dump(path):
    """Frames of a dump custom file: list of (step, {id: {column: value}})."""
    frames = []
    lines = open(path).read().splitlines()
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: TIMESTEP"):
            step = int(lines[i + 1])
            n = int(lines[i + 3])
            cols = lines[i + 8].split()[2:]
            atoms = {}
            for line in lines[i + 9:i + 9 + n]:
                vals = dict(zip(cols, map(float, line.split())))
                atoms[int(vals["id"])] = vals
            frames.append((step, atoms))
            i += 9 + n
        else:
            i += 1
    return frames


def quat(a):
    """(w, x, y, z) of a dump row."""
    return tuple(a["c_p[%d]" % k] for k in (1, 2, 3, 4))


# ------------------------------------------------------------ quaternion algebra ----

def qmul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return (w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)


def qconj(q):
    return (q[0], -q[1], -q[2], -q[3])


def qnormalize(q):
    n = math.sqrt(sum(c * c for c in q))
    return tuple(c / n for c in q)


def qaxis(axis, angle):
    """Rotation by angle about axis."""
    n = math.sqrt(sum(c * c for c in axis))
    s = math.sin(angle / 2) / n
    return (math.cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s)


def rotate(q, v):
    """R(q) v (body -> world)."""
    return qmul(qmul(q, (0.0,) + tuple(v)), qconj(q))[1:]


def rotate_inv(q, v):
    """R(q)^T v (world -> body)."""
    return rotate(qconj(q), v)


def quat_distance(q1, q2):
    """min(|q1 - q2|, |q1 + q2|): about half the angle between the two rotations
    (q and -q are the same rotation)."""
    return min(norm([a - b for a, b in zip(q1, q2)]), norm([a + b for a, b in zip(q1, q2)]))


def norm(v):
    return math.sqrt(sum(c * c for c in v))
