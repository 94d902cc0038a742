"""contact_decks -- small building blocks shared by the contact-style tests
(pair_style lsdem, fix wall/lsdem, compute contact/lsdem): shape libraries, data files
and the common head of an input deck."""
import math
import os

from lsdemtest import shape_tool, run_lmp, check


def sphere_library(path, radius, spacing, nodes):
    """A level-set (grid) sphere; one shape."""
    if not os.path.exists(path):
        shape_tool("analytic", path, "sphere", radius, "--spacing", spacing, "--nodes", nodes)
    return path


def ball_library(path, radius):
    """An analytic sphere (one contact point per pair); one shape."""
    if not os.path.exists(path):
        shape_tool("analytic", path, "sphere", radius, "--analytic")
    return path


def box_library(path, half, spacing, nodes):
    """A level-set (grid) cube of half-side `half`; one shape."""
    if not os.path.exists(path):
        shape_tool("analytic", path, "box", half, half, half, "--spacing", spacing,
                   "--nodes", nodes)
    return path


def quat_axis_angle(axis, angle):
    """Scalar-first unit quaternion of a rotation by `angle` about `axis`."""
    n = math.sqrt(sum(a * a for a in axis))
    s = math.sin(angle / 2) / n
    return (math.cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s)


class Grain:
    def __init__(self, x, q=(1, 0, 0, 0), v=(0, 0, 0), w=(0, 0, 0), shape=1, type=1,
                 density=1.0):
        self.x, self.q, self.v, self.w = x, q, v, w
        self.shape, self.type, self.density = shape, type, density


def write_data(path, box, grains, ids=None, ntypes=1):
    """A data file for atom_style lsdem. box = (xlo, xhi, ylo, yhi, zlo, zhi);
    ids = the atom ID of each grain (default 1..N, in order)."""
    ids = ids or list(range(1, len(grains) + 1))
    lines = ["LAMMPS data file (contact tests)", "",
             "%d atoms" % len(grains), "%d atom types" % ntypes, "",
             "%r %r xlo xhi" % box[0:2], "%r %r ylo yhi" % box[2:4], "%r %r zlo zhi" % box[4:6],
             "", "Atoms # lsdem", ""]
    for i, g in zip(ids, grains):
        lines.append("%d %d %d %r %r %r %r %r %r %r %r" % ((i, g.type, g.shape, g.density)
                                                             + tuple(g.x) + tuple(g.q)))
    lines += ["", "Velocities", ""]
    for i, g in zip(ids, grains):
        lines.append("%d %r %r %r %r %r %r" % ((i,) + tuple(g.v) + tuple(g.w)))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def head(library, data, boundary="p p f", extra=""):
    """The lines every contact deck starts with."""
    return """units lj
atom_style lsdem library %s
atom_modify map array
boundary %s
newton on
comm_modify vel yes
%s
read_data %s
""" % (os.path.abspath(library), boundary, extra, os.path.abspath(data))


THERMO_FULL = "thermo_modify norm no format float %.17g\n"
# grain 1's position and velocity as equal-style variables for thermo_style custom
# (v_px v_py v_pz v_vx v_vy v_vz): thermo keywords cannot name an atom's x[1] in LAMMPS 2021
GRAIN1 = """variable px equal x[1]
variable py equal y[1]
variable pz equal z[1]
variable vx equal vx[1]
variable vy equal vy[1]
variable vz equal vz[1]
"""


def write_stl(path, tris, name="mesh"):
    """Triangles (three (x, y, z) corners each, in their orientation) as ASCII STL."""
    lines = ["solid %s" % name]
    for t in tris:
        lines.append(" facet normal 0 0 0\n  outer loop")
        lines += ["   vertex %r %r %r" % tuple(v) for v in t]
        lines.append("  endloop\n endfacet")
    lines.append("endsolid %s" % name)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def write_cube_stl(path, lo, hi):
    """A closed, outward-oriented box as ASCII STL."""
    c = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return write_stl(path, [(c[a], c[t1], c[t2]) for a, b, cc, d in quads
                            for t1, t2 in ((b, cc), (cc, d))], "box")


def write_ridges_stl(path, xs, half_y, half_base=0.3, height=0.5):
    """Closed triangular prisms along y as ASCII STL, one per x in xs: the sharp top edge
    at (x, z = 0) from y = -half_y to half_y, the base 2 half_base wide at z = -height;
    triangles oriented outwards."""
    tris = []
    for xc in xs:
        a, b = ([(xc - half_base, y, -height), (xc + half_base, y, -height), (xc, y, 0.0)]
                for y in (-half_y, half_y))
        quads = [(a[0], a[1], b[1], b[0]), (a[1], a[2], b[2], b[1]), (a[2], a[0], b[0], b[2])]
        prism = [t for q in quads for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]
        prism += [tuple(a), tuple(b)]
        centre = (xc, 0.0, -height / 3)
        for t in prism:
            e1 = [t[1][i] - t[0][i] for i in range(3)]
            e2 = [t[2][i] - t[0][i] for i in range(3)]
            n = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                 e1[0] * e2[1] - e1[1] * e2[0])
            outward = sum(n[i] * (t[0][i] - centre[i]) for i in range(3)) > 0
            tris.append(t if outward else (t[0], t[2], t[1]))
    return write_stl(path, tris, "ridges")


def atoms_of(path):
    """The Atoms and Velocities lines of a data file, each section sorted by atom ID (ranks
    write their atoms in their own order); empty when the file is missing."""
    text = open(path).read() if os.path.exists(path) else ""
    atoms, _, vels = text[text.find("Atoms"):].partition("Velocities")
    return [sorted((l for l in s.splitlines() if l.split() and l.split()[0].isdigit()),
                   key=lambda l: int(l.split()[0]))
            for s in (atoms, vels)]


def largest_move(a, b):
    """The largest difference of a coordinate between two Atoms sections (atoms_of);
    1.0 when either is empty."""
    return max([abs(float(p) - float(q)) for la, lb in zip(a, b)
                for p, q in zip(la.split()[4:7], lb.split()[4:7])] or [1.0])


def lattice(rng, layers, z0, dz, velocity):
    """4 x 4 analytic-sphere grains per layer on a 1.2 lattice (jittered by up to 0.1 in x and
    y), layer k at z0 + k dz, each with velocity(rng)."""
    grains = []
    for k in range(layers):
        for j in range(4):
            for i in range(4):
                g = Grain((0.6 + 1.2 * i + 0.1 * rng.random(),
                           0.6 + 1.2 * j + 0.1 * rng.random(), z0 + dz * k))
                g.v = velocity(rng)
                grains.append(g)
    return grains


def final_state(deck, name, np=1, args=None):
    """deck run in folder `name` on np ranks, then its atoms written: (atoms_of, log)."""
    where = os.path.abspath(name)
    rc, log = run_lmp(deck + "write_data final.data nocoeff\n", np=np, cwd=where, args=args)
    return atoms_of(os.path.join(where, "final.data")), log


def check_ranks_threads(make_deck, body, serial, name):
    """make_deck(np) + body ends with the serial run's bits on 2 ranks and on 2 threads (in
    folders name-ranks and name-threads)."""
    ranks, _ = final_state(make_deck(2) + body, name + "-ranks", np=2)
    check(ranks == serial, "%s, 2 ranks: the serial bits" % name)
    threads, _ = final_state(make_deck(1) + body, name + "-threads",
                             args=["-sf", "omp", "-pk", "omp", "2"])
    check(threads == serial, "%s, 2 threads: the serial bits" % name)

