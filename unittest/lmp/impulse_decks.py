"""impulse_decks -- shared pieces of the impulse-mode tests (fix impulse/lsdem,
pair_style lsdem/impulse): a deck header, shape libraries, dumps of whole grain states and
the energies and momenta computed here from them (mass, principal moments, quaternion),
independently of the code under test."""
import math
import os

from grain_decks import read_dump, rotate, rotate_inv
from lsdemtest import shape_tool

HEADER = """units lj
atom_style lsdem library {lib}
atom_modify map array
boundary f f f
newton on
comm_modify vel yes
read_data {data}
pair_style lsdem/impulse
pair_coeff * *
neighbor {skin} bin
neigh_modify delay 0 every 1 check yes
"""

PROPS = "compute p all property/atom qw qx qy qz inertia1 inertia2 inertia3\n"
COLUMNS = ("id x y z vx vy vz omegax omegay omegaz mass radius c_p[1] c_p[2] c_p[3] c_p[4] "
           "c_p[5] c_p[6] c_p[7]")


def header(lib, data, skin=0.1):
    return HEADER.format(lib=os.path.abspath(lib), data=os.path.abspath(data), skin=skin)


def floor_drop(lib, data, e, dt, steps, g=None, opts="", setup=""):
    """A deck: the grains of data over the floor z = 0 (fix wall/lsdem plane, kn 1e4), setup
    commands first, gravity g down (None: none), fix imp impulse/lsdem e 0 opts, run steps
    of dt with thermo every step: Step, v_z and v_vz of atom 1 at full precision."""
    return (header(lib, data) + setup
            + "fix floor all wall/lsdem plane 0 0 0 0 0 1 1.0e4 0 0\n"
            + ("fix grav all gravity %r vector 0 0 -1\n" % g if g else "")
            + "fix imp all impulse/lsdem %r 0.0 %s\ntimestep %r\n" % (e, opts, dt)
            + "variable z equal z[1]\nvariable vz equal vz[1]\n"
            + "thermo_style custom step v_z v_vz\nthermo_modify format float %.15g\n"
            + "thermo 1\nrun %d\n" % steps)


def dump(every, fname, name="d"):
    """A dump of every grain's whole state at full precision (read with states())."""
    return (PROPS + "dump %s all custom %d %s %s\ndump_modify %s format float %%.17g sort id\n"
            % (name, every, fname, COLUMNS, name))


def states(path):
    """Frames of a dump() file: list of (step, {id: row})."""
    return read_dump(path)


def library(path, kind, *params, nodes=100, spacing=None, analytic=False):
    """A one-shape library made by lsdem-shape analytic (once)."""
    if not os.path.exists(path):
        args = ["analytic", path, kind] + list(params) + ["--nodes", nodes]
        if spacing:
            args += ["--spacing", spacing]
        if analytic:
            args.append("--analytic")
        shape_tool(*args)
    return path


def quat(a):
    return tuple(a["c_p[%d]" % k] for k in (1, 2, 3, 4))


def kinetic(a):
    """1/2 m v^2 + 1/2 w.I w of one dump row (I from the principal moments and q)."""
    v = (a["vx"], a["vy"], a["vz"])
    wb = rotate_inv(quat(a), (a["omegax"], a["omegay"], a["omegaz"]))
    inertia = (a["c_p[5]"], a["c_p[6]"], a["c_p[7]"])
    return 0.5 * a["mass"] * sum(c * c for c in v) + 0.5 * sum(
        i * w * w for i, w in zip(inertia, wb))


def momenta(atoms):
    """Linear momentum and angular momentum about the origin of a frame's grains."""
    p = [0.0, 0.0, 0.0]
    L = [0.0, 0.0, 0.0]
    for a in atoms.values():
        m = a["mass"]
        x = (a["x"], a["y"], a["z"])
        v = (a["vx"], a["vy"], a["vz"])
        q = quat(a)
        wb = rotate_inv(q, (a["omegax"], a["omegay"], a["omegaz"]))
        Iw = rotate(q, tuple(i * w for i, w in zip((a["c_p[5]"], a["c_p[6]"], a["c_p[7]"]), wb)))
        xv = (x[1] * v[2] - x[2] * v[1], x[2] * v[0] - x[0] * v[2], x[0] * v[1] - x[1] * v[0])
        for k in range(3):
            p[k] += m * v[k]
            L[k] += m * xv[k] + Iw[k]
    return p, L


def energy(atoms):
    return sum(kinetic(a) for a in atoms.values())


def norm(v):
    return math.sqrt(sum(c * c for c in v))


NET_HEAD = """units lj
atom_style hybrid lsdem library {here}/netlib.lslib bond
atom_modify map array
boundary f f f
newton on
read_data {here}/net.data
include {here}/net.in
neighbor 0.1 bin
neigh_modify delay 0 every 1 check yes
pair_style lsdem/impulse
pair_coeff * *
"""


def net_scene():
    """A spherical grain (radius 0.3, group grains) at (1.06, 0.97, 0.5) above a free square
    net of 81 balls (radius 0.1, spacing 0.25, mass 0.01, k 1, no clamps; groups net,
    net_free), made in the current folder by lsdem-shape net. Returns the deck's head: up
    to the pair style, nothing moving yet."""
    shape_tool("analytic", "netball.lslib", "sphere", 0.1, "--analytic")
    shape_tool("analytic", "netgrain.lslib", "sphere", 0.3, "--analytic")
    shape_tool("merge", "netlib.lslib", "netball.lslib", "netgrain.lslib")
    with open("one.data", "w") as f:
        f.write("one grain\n\n1 atoms\n1 atom types\n\n-1 3 xlo xhi\n-1 3 ylo yhi\n"
                "-6 3 zlo zhi\n\nAtoms # lsdem\n\n1 1 2 1.0 1.06 0.97 0.5 1 0 0 0\n")
    shape_tool("net", "net", "--library", "netlib.lslib", "--shape", 1, "--rb", 0.1,
               "--lattice", "square", "--spacing", 0.25, "--size", 2, 2, "--clamp", "none",
               "--mass", 0.01, "--k", 1.0, "--grains", "one.data")
    return NET_HEAD.format(here=os.getcwd())
