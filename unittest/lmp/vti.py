"""Reader of the VTK ImageData files fix field/lsdem writes (raw appended, UInt64 headers),
and the runs of one deck on several rank counts that compare them."""
import os
import re

import numpy as np

from lsdemtest import run_lmp

MARK = b'<AppendedData encoding="raw">\n_'


def read_vti(path):
    """{'n': (nx, ny, nz), 'origin': (...), 'spacing': (hx, hy, hz), 'h': hx (the spacing of
    an open box's grid, the same on every axis), 'direction': 3x3 (columns: the grid's unit
    axes; identity unless the file has a Direction), name: array (nodes, components)}"""
    data = open(path, "rb").read()
    base = data.index(MARK) + len(MARK)
    head = data[:base].decode()
    out = {}
    ext = [int(v) for v in re.search(r'WholeExtent="([^"]+)"', head).group(1).split()]
    out["n"] = (ext[1] + 1, ext[3] + 1, ext[5] + 1)
    out["origin"] = [float(v) for v in re.search(r'Origin="([^"]+)"', head).group(1).split()]
    out["spacing"] = [float(v) for v in re.search(r'Spacing="([^"]+)"', head).group(1).split()]
    out["h"] = out["spacing"][0]
    # a skewed grid's (a triclinic box's) Direction: row-major, columns the unit axes
    m = re.search(r'Direction="([^"]+)"', head)
    out["direction"] = (np.array([float(v) for v in m.group(1).split()]).reshape(3, 3)
                        if m else np.eye(3))
    for m in re.finditer(r'<DataArray type="(\w+)" Name="(\w+)" NumberOfComponents="(\d+)" '
                         r'format="appended" offset="(\d+)"/>', head):
        kind, name, comps, offset = m.group(1), m.group(2), int(m.group(3)), int(m.group(4))
        size = int(np.frombuffer(data, np.uint64, 1, base + offset)[0])
        dtype = np.float64 if kind == "Float64" else np.uint8
        arr = np.frombuffer(data, dtype, size // np.dtype(dtype).itemsize, base + offset + 8)
        out[name] = arr.reshape(-1, comps)
    return out


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
