"""Every example runs as shipped: a copy of examples/ (as a fresh clone has it, with the
inputs that ship beside each deck), and in each example's folder `lmp -in in.NAME` on 1 and
2 ranks for a few steps, with only the step counts shortened on the command line. Checked:
lmp exits 0, reads the shipped grains (the atom count of the shipped data file), runs the
steps asked for, and writes what the deck writes; the Python example runs from its folder
through LAMMPS's Python module, the C driver on the shipped scene; in.ct_scan names a grain
lost from its box instead of failing in write_data."""
import os
import re
import shutil
import subprocess

from lsdemtest import LMP, check, finish, mpi_prefix, run_lmp

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.normpath(os.path.join(HERE, "..", "..", "examples"))
BUILD = os.path.dirname(LMP)

# (folder, deck, -var overrides that only shorten the run, files the run must write)
DECKS = [
    ("settle", "in.settle", {"nsteps": 40}, ["settle.csv", "dump.settle"]),
    ("avatars", "in.avatars", {"nsteps": 40}, ["dump.avatars", "settled.data"]),
    ("ct_scan", "in.ct_scan", {"nsteps": 40}, ["settled.data"]),
    ("container_release", "in.fill", {"nsteps": 20}, ["filled.data"]),
    ("container_release", "in.release", {"nsteps": 3}, ["mound_impulse.data"]),
    ("triaxial", "in.prepare", {"nprep": 30, "nround": 20, "maxround": 1, "nrelax": 20},
     ["sample.data"]),
    ("triaxial", "in.triaxial", {"ncons": 30, "epsmax": 1.0e-4, "every": 10},
     ["triaxial.csv"]),
    ("drum", "in.drum", {"nsteps": 40}, ["drum.csv", "drum_end.data"]),
    ("hopper", "in.hopper", {"nsettle": 40, "ndischarge": 20, "nvtk": 0},
     ["hopper.csv", "hopper_settled.dump"]),
    ("avalanche", "in.avalanche", {"nsteps": 40},
     ["avalanche.csv", "deposit.dump", "avalanche_end.data", "vtk/grains.pvd", "vtk/terrain.pvd"]),
    ("net_drop", "in.net_drop", {"nsteps": 40, "vtk": 20},
     ["net_drop.csv", "vtk/net_drop.pvd", "vtk/net_drop_net.pvd"]),
    ("barrier", "in.barrier", {"settle": 20, "nsteps": 40, "nrest": 20}, ["barrier.csv"]),
    ("shear_cell", "in.shear_cell", {"ncomp": 20, "nrelax": 20, "nshear": 40, "every": 20},
     ["shear.csv", "fields/shear.pvd", "vtk/grains.pvd", "sheared.data"]),
]


def declared_atoms(path):
    """The atom count in a data file's header."""
    with open(path) as f:
        for line in f:
            m = re.match(r"\s*(\d+)\s+atoms\s*$", line)
            if m:
                return int(m.group(1))
    return None


def read_data_file(deck_path):
    """The file the deck's read_data reads by default (a literal or an index variable)."""
    text = open(deck_path).read()
    name = re.search(r'read_data\s+([^\s"]+)', text).group(1)
    m = re.match(r"\$\{(\w+)\}", name)
    if m:
        name = re.search(r"^variable\s+%s\s+index\s+(\S+)" % m.group(1), text, re.M).group(1)
    return name


def fresh_copy(tag):
    """examples/ as shipped (links followed), without run.sh's out/ folders."""
    dst = os.path.abspath("examples_%s" % tag)
    shutil.rmtree(dst, ignore_errors=True)
    shutil.copytree(EXAMPLES, dst, symlinks=False, ignore=shutil.ignore_patterns("out"))
    return dst


for np_ in (1, 2):
    root = fresh_copy(np_)
    for folder, deck, short, outputs in DECKS:
        cwd = os.path.join(root, folder)
        data = os.path.join(cwd, read_data_file(os.path.join(cwd, deck)))
        check(os.path.exists(data), "%s/%s: its data file %s ships with it" % (folder, deck, data))
        natoms = declared_atoms(data) if os.path.exists(data) else None
        rc, log = run_lmp(os.path.join(cwd, deck), np=np_, vars=short, cwd=cwd,
                          log="log.%s" % deck[3:], timeout=900)
        what = "%s/%s on %d rank(s)" % (folder, deck, np_)
        check(rc == 0, "%s exits 0" % what)
        m = re.search(r"^\s*(\d+) atoms\s*$", log, re.M)
        check(m is not None and int(m.group(1)) == natoms,
              "%s read the shipped data file's %s atoms (log: %s)"
              % (what, natoms, m.group(1) if m else None))
        check("Loop time of" in log and "on %d procs" % np_ in log,
              "%s ran its steps on %d rank(s)" % (what, np_))
        for f in outputs:
            check(os.path.exists(os.path.join(cwd, f)), "%s wrote %s" % (what, f))

    # the C driver on the shipped scene, and the Python example from its own folder
    driver = os.path.join(BUILD, "lsdem-c-driver")
    p = subprocess.run(mpi_prefix(np_) + [driver, "in.driver", "10"], cwd=os.path.join(root, "c_driver"),
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    rows = [l for l in p.stdout.splitlines() if len(l.split()) == 9]
    check(p.returncode == 0 and len(rows) == declared_atoms(os.path.join(root, "c_driver", "data.driver")),
          "c_driver on %d rank(s): exit %d, %d grains printed:\n%s"
          % (np_, p.returncode, len(rows), p.stdout[-1500:]))
    env = dict(os.environ, PYTHONPATH=os.path.join(BUILD, "python"))
    mpi = mpi_prefix(np_) + (["-x", "PYTHONPATH"] if np_ > 1 else [])
    p = subprocess.run(mpi + ["/usr/bin/python3", "settle.py", "../settle/in.settle", "20", "10",
                              "grains.npz"], cwd=os.path.join(root, "python"), env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    check(p.returncode == 0 and os.path.exists(os.path.join(root, "python", "grains.npz")),
          "python example on %d rank(s) from its folder: exit %d\n%s"
          % (np_, p.returncode, p.stdout[-1500:]))

# in.ct_scan stops with a named error, not write_data's "Atom count is inconsistent", when a
# grain left the box (forced here: the deck with one grain deleted after its run)
ct = os.path.join(root, "ct_scan")
text = open(os.path.join(ct, "in.ct_scan")).read()
assert "\nrun             ${nsteps}\n" in text
open(os.path.join(ct, "in.lost"), "w").write(text.replace(
    "\nrun             ${nsteps}\n", "\nrun             ${nsteps}\ngroup gone id 1\ndelete_atoms group gone\n"))
if os.path.exists(os.path.join(ct, "settled.data")):
    os.remove(os.path.join(ct, "settled.data"))
rc, log = run_lmp(os.path.join(ct, "in.lost"), vars={"nsteps": 10}, cwd=ct, expect_fail=True)
check(rc != 0 and "1 of 21 grains left the box" in log and not os.path.exists(os.path.join(ct, "settled.data")),
      "ct_scan: a lost grain is named before write_data (exit %d):\n%s" % (rc, log[-800:]))

finish()
