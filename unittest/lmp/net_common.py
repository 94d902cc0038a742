"""Shared pieces of the net tests (lsdem-shape net + bond_style lsdem/net + fix net/lsdem):
a ball library, the deck head, the data file's bonds and the dump reader."""
import os

from lsdemtest import shape_tool

RB = 0.2
HERE = os.getcwd()


def make_ball(radius=RB, name="ball.lslib"):
    shape_tool("analytic", name, "sphere", radius, "--analytic")


def make_net(prefix, *args, library="ball.lslib", shape=1, rb=RB):
    """lsdem-shape net PREFIX with args (library=None: the library, shape and radius are
    among args)."""
    if library is None:
        return shape_tool("net", prefix, *args)
    return shape_tool("net", prefix, "--library", library, "--shape", shape, "--rb", rb, *args)


def head(prefix, library="ball.lslib", kn=100.0, pre="", style="bond"):
    """Everything up to the integrators: the net (and grains) read, its .in included;
    `pre` goes before read_data (processors, ...); style: the molecular half of the atom
    style (angle for nets made with --bending)."""
    return """units lj
atom_style hybrid lsdem library {lib} {style}
boundary f f f
newton on
{pre}read_data {p}.data
include {p}.in
pair_style lsdem
pair_coeff * * {kn} 0 0
""".format(lib=os.path.join(HERE, library), p=os.path.join(HERE, prefix), kn=kn, pre=pre,
           style=style)


def bonds(prefix):
    """[(type, id1, id2)] of the data file's Bonds section."""
    text = open(prefix + ".data").read().split("\nBonds\n")[1]
    return [tuple(map(int, l.split()[1:4])) for l in text.strip().splitlines()]


def read_dump(path):
    """{id: {column: value}} of a single-frame text dump."""
    lines = open(path).read().splitlines()
    i = next(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[i].split()[2:]
    out = {}
    for l in lines[i + 1:]:
        v = dict(zip(cols, map(float, l.split())))
        out[int(v["id"])] = v
    return out
