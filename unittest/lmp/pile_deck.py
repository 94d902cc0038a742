"""The pile of angular grains that the rank-count, thread-count and load-balance tests run
(test_reproducible, test_threads, test_balance): 140 grains of 6 random shapes fall into an
open box under strong gravity and pile up, with friction history, node lists and five
walls. deck() writes its input; run() runs it and returns the final frame of every grain
(bits of position, velocity, spin and orientation) and the exact sums of each output
step."""
import os

from grain_decks import pile
from lsdemtest import run_lmp, thermo

STEPS, HALF, EVERY = 1500, 750, 300
def pile_in_power_of_two_box():
    """grain_decks.pile()'s grains (they stay in 6 x 6 x 9, walls at 0 and 6) in a box whose
    edges are powers of two from 0: LAMMPS's balance shift converts positions to box
    fractions and back, which is exact only then (test_balance, doc/howto_parallel.rst)."""
    fresh = not os.path.exists("pile.data")
    lib, data = pile()
    if fresh:
        text = open(data).read()
        for old, new in (("0 6 xlo xhi", "0 8 xlo xhi"), ("0 6 ylo yhi", "0 8 ylo yhi"),
                         ("0 9 zlo zhi", "0 16 zlo zhi")):
            text = text.replace(old, new)
        open(data, "w").write(text)
    return lib, data


LIB, DATA = pile_in_power_of_two_box()

# strong gravity and a short time: the grains land within a few hundred steps
CONTACT = """pair_coeff      * * 1.0e4 0.9e4 0.5 cn 2.0
neighbor        0.1 bin
neigh_modify    delay 0 every 1 check yes
fix             floor all wall/lsdem plane 0 0 0 0 0 1 1.0e4 0.9e4 0.5 cn 2.0
fix             wx0 all wall/lsdem plane 0 0 0 1 0 0 1.0e4 0.9e4 0.5 cn 2.0
fix             wx1 all wall/lsdem plane 6 0 0 -1 0 0 1.0e4 0.9e4 0.5 cn 2.0
fix             wy0 all wall/lsdem plane 0 0 0 0 1 0 1.0e4 0.9e4 0.5 cn 2.0
fix             wy1 all wall/lsdem plane 0 6 0 0 -1 0 1.0e4 0.9e4 0.5 cn 2.0
fix             grav all gravity 100.0 vector 0 0 -1
fix             integrate all nve/lsdem damping 1.0
timestep        2.0e-4
compute         w all pair lsdem
compute         q all property/atom qw qx qy qz
thermo_style    custom step ke c_w[2] c_w[4] f_floor[3]
thermo_modify   norm no format float %.17g
thermo          {every}
"""
DUMP = ("dump            d all custom {steps} final.dump id x y z vx vy vz omegax omegay "
        "omegaz c_q[1] c_q[2] c_q[3] c_q[4]\n"
        "dump_modify     d sort id format float %.17g\n")


def deck(mode, steps, restart=None, before_run="", before_box=""):
    """The pile's input for `steps` steps; before_box, before_run: commands inserted before
    read_data and before the run"""
    return ("units lj\natom_style lsdem library %s\nboundary f f f\nnewton on\n"
            "comm_modify vel yes\n%sread_data %s\npair_style lsdem mode %s\n"
            % (LIB, before_box, DATA, mode)
            + CONTACT.format(every=EVERY) + ("" if restart else DUMP.format(steps=steps))
            + before_run + "run %d\n" % steps + ("write_restart %s\n" % restart if restart else ""))


def continued(steps):
    return ("read_restart half.restart\n" + CONTACT.format(every=EVERY)
            + DUMP.format(steps=STEPS) + "run %d\n" % steps)


def run(name, text, np, args=None):
    rc, log = run_lmp(text, np=np, cwd=os.path.abspath(name), args=args)
    dump = os.path.join(os.path.abspath(name), "final.dump")
    # the frame of the last step (a dump every STEPS steps: the run's end)
    atoms = open(dump).read().split("ITEM: ATOMS")[-1] if os.path.exists(dump) else None
    # the package's sums (the floor's load, contact counts) are exact; LAMMPS's own
    # reductions over ranks (thermo ke) sum in rank order: compared to round-off below
    rows = [(r["Step"], r["f_floor[3]"], r["c_w[2]"], r["c_w[4]"]) for r in thermo(log)]
    return atoms, rows, thermo(log)


