"""A small triaxial specimen for the tests of examples/triaxial/in.triaxial: 80 random
grains of d ~ 16 px (4 shapes, 150 nodes), packed loose in a mould of radius 32 px by the
example's in.prepare, in a double-layer membrane from lsdem-shape membrane (spheres of 4 and
4.4 px). make() builds it in the current folder (about 5 s) and returns the variables that
in.triaxial needs for it."""
import math
import os
import re

from lsdemtest import run_lmp, shape_tool

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.join(HERE, "..", "..", "examples", "triaxial")
DECK = os.path.join(EXAMPLE, "in.triaxial")
R, RHO, RB = 32.0, 2.65e-3, 4.0


def shear_strain(steps, erate=5.0e-4, dt=0.006):
    """in.triaxial's epsmax for `steps` shearing steps (nshear = ceil((1 - e^-eps)/(erate dt)))."""
    return "%.12g" % -math.log(1 - steps * erate * dt)


def make():
    shape_tool("random", "g.lslib", "--count", 4, "--size", 16, "--size-spread", 0.1,
               "--elongation", 0.75, "--flatness", 0.75, "--angularity", 0.12, "--seed", 3,
               "--nodes", 150, "--spacing", 1.0)
    shape_tool("pack", "g.lslib", "packed.data", "--count", 80, "--cylinder", R - 1, 280,
               "--density", RHO, "--seed", 5)
    rc, log = run_lmp(os.path.join(EXAMPLE, "in.prepare"), vars={
        "lib": "g.lslib", "data": "packed.data", "R": R, "sigma_prep": 0.2, "nprep": 1500,
        "nround": 500, "maxround": 2, "mu_prep": 0.6, "densify": 0, "mu_final": 0.6,
        "nrelax": 500,
        "rho": RHO}, log="log.prepare")
    H = float(re.search(r"^PREPARED height (\S+)", log, re.M).group(1))
    text = open("sample.data").read().split("\nVelocities")[0]
    open("sample_grains.data", "w").write(text + "\n")
    shape_tool("analytic", "in.lslib", "sphere", RB, "--analytic")
    shape_tool("analytic", "out.lslib", "sphere", 1.1 * RB, "--analytic")
    shape_tool("merge", "all.lslib", "g.lslib", "in.lslib", "out.lslib")
    shape_tool("membrane", "mem", "--radius", R, "--height", H, "--z0", 0, "--rb", RB,
               "--library", "all.lslib", "--shapes", 5, 6, "--types", 2, 3, "--grains",
               "sample_grains.data", "--density", RHO, "--knbb", 4, "--ksbb", 4, "--kouter", 1, 1)
    return {"lib": os.path.abspath("all.lslib"), "data": os.path.abspath("mem.data"),
            "memin": os.path.abspath("mem.in"), "memtri": os.path.abspath("mem.tri"),
            "R": R, "rho": RHO}
