"""Reader of the VTK ImageData files fix field/lsdem writes (raw appended, UInt64 headers)."""
import re

import numpy as np

MARK = b'<AppendedData encoding="raw">\n_'


def read_vti(path):
    """{'n': (nx, ny, nz), 'origin': (...), 'spacing': (hx, hy, hz), 'h': hx (the spacing of
    an open box's grid, the same on every axis), name: array (nodes, components)}"""
    data = open(path, "rb").read()
    base = data.index(MARK) + len(MARK)
    head = data[:base].decode()
    out = {}
    ext = [int(v) for v in re.search(r'WholeExtent="([^"]+)"', head).group(1).split()]
    out["n"] = (ext[1] + 1, ext[3] + 1, ext[5] + 1)
    out["origin"] = [float(v) for v in re.search(r'Origin="([^"]+)"', head).group(1).split()]
    out["spacing"] = [float(v) for v in re.search(r'Spacing="([^"]+)"', head).group(1).split()]
    out["h"] = out["spacing"][0]
    for m in re.finditer(r'<DataArray type="(\w+)" Name="(\w+)" NumberOfComponents="(\d+)" '
                         r'format="appended" offset="(\d+)"/>', head):
        kind, name, comps, offset = m.group(1), m.group(2), int(m.group(3)), int(m.group(4))
        size = int(np.frombuffer(data, np.uint64, 1, base + offset)[0])
        dtype = np.float64 if kind == "Float64" else np.uint8
        arr = np.frombuffer(data, dtype, size // np.dtype(dtype).itemsize, base + offset + 8)
        out[name] = arr.reshape(-1, comps)
    return out
