"""The reader of fix field/lsdem's VTK ImageData files (tools/lsdem_vti.py, which the
examples' plots use too), and the runs of one deck on several rank counts that compare them."""
import os
import sys

from lsdemtest import run_lmp

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from lsdem_vti import read_vti  # noqa: E402,F401  (the tests import it from here)


def runs_on_ranks(deck, name, out, ranks=(1, 2, 4)):
    """deck run on each rank count N of ranks in folder <name>_np<N>: ({N: the bytes of the
    file out written there, for the runs that wrote it}, (out's path, the log) of the first
    rank count's run, or None when it wrote nothing)."""
    outs, first = {}, None
    for np_ in ranks:
        wd = os.path.abspath("%s_np%d" % (name, np_))
        rc, log = run_lmp(deck, np=np_, cwd=wd)
        path = os.path.join(wd, out)
        if rc != 0 or not os.path.exists(path):
            continue
        outs[np_] = open(path, "rb").read()
        if np_ == ranks[0]:
            first = (path, log)
    return outs, first
