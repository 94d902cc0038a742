#!/usr/bin/python3
"""Drive the settle scene (examples/settle/in.settle) from Python through LAMMPS's own
Python module, and read every grain's position and orientation into numpy as it settles.

  PYTHONPATH=build/python [mpirun -np N] python3 settle.py [IN_SETTLE NSTEPS CHUNK OUT.npz]

Runs in the folder that holds grains.lslib and data.settle: as shipped, this folder (links
to examples/settle's inputs; `cd examples/python && PYTHONPATH=../../build/python mpirun
-np 2 python3 settle.py`), or run.sh's out/ (examples/settle/run.sh prepare makes them).
Defaults: examples/settle/in.settle, 10000 steps, chunks of 1000, grains.npz. The deck is read with nsteps = 0, then Python runs CHUNK steps at a
time; after each chunk it gathers the positions (gather_atoms "x") and the quaternions and
shape indices (gather "c_orient": the deck's compute property/atom) of all grains in
atom-ID order from all ranks, prints a line of what they say, and at the end saves them to
OUT.npz (arrays id, x, quat, shape, step, mean_z). Under mpirun every rank runs this
script; rank 0 prints and saves."""
import os
import sys

import numpy as np
from lammps import lammps


DEFAULTS = [os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "settle", "in.settle"),
            "10000", "1000", "grains.npz"]


def grains(lmp):
    """ids, positions (n x 3) and quaternions qw qx qy qz + shape (n x 5), gathered from all
    ranks in atom-ID order (the compute is evaluated on demand)."""
    n = lmp.get_natoms()
    x = np.ctypeslib.as_array(lmp.gather_atoms("x", 1, 3)).reshape(n, 3).copy()
    orient = np.ctypeslib.as_array(lmp.gather("c_orient", 1, 5)).reshape(n, 5).copy()
    return np.arange(1, n + 1), x, orient


def main():
    args = sys.argv[1:] + DEFAULTS[len(sys.argv) - 1:]
    deck, nsteps, chunk, out = args[0], int(args[1]), int(args[2]), args[3]
    lmp = lammps(cmdargs=["-log", "log.lammps", "-echo", "none", "-screen", "none",
                          "-var", "nsteps", "0"])
    lmp.file(deck)
    me = lmp.extract_setting("world_rank")
    say = print if me == 0 else (lambda *a, **k: None)
    ids, x, orient = grains(lmp)
    say("%d grains read from the deck; mean height %.5f m" % (len(ids), x[:, 2].mean()))
    steps, mean_z = [0], [x[:, 2].mean()]
    done = 0
    while done < nsteps:
        lmp.command("run %d" % min(chunk, nsteps - done))
        done += min(chunk, nsteps - done)
        ids, x, orient = grains(lmp)
        norm = np.linalg.norm(orient[:, :4], axis=1)
        steps.append(done)
        mean_z.append(x[:, 2].mean())
        say("step %6d: mean height %.5f m, lowest %.5f m, |q| - 1 within %.1e, kinetic "
            "energy %.3e J" % (done, x[:, 2].mean(), x[:, 2].min(), np.abs(norm - 1).max(),
                               lmp.get_thermo("ke")), flush=True)
    if me == 0:
        np.savez(out, id=ids, x=x, quat=orient[:, :4], shape=orient[:, 4].astype(int),
                 step=np.array(steps), mean_z=np.array(mean_z))
    say("%s: positions and quaternions of %d grains" % (out, len(ids)))
    lmp.close()
    lmp.finalize()  # MPI_Finalize: mpirun expects it of every rank


if __name__ == "__main__":
    main()
