"""Reader of the VTK ImageData files fix field/lsdem writes (`.vti`: raw appended data, UInt64
block headers, Float64 or UInt8 arrays), shared by the examples' plots and the tests.

    vti = read_vti(path)
    vti["n"]          (nx, ny, nz) nodes
    vti["origin"]     world position of node (0, 0, 0)
    vti["spacing"]    (hx, hy, hz) along the grid's axes; vti["h"] = hx
    vti["direction"]  3x3, columns the grid's unit axes in the world frame: the identity, or a
                      tilted (triclinic) box's skewed axes when the file has a Direction
    vti["skewed"]     whether it has one
    vti[name]         each array, shape (nodes, components), node index i + nx (j + ny k);
                      vti["names"] lists them in the file's order

node_grid(vti, name) is an array as (nz, ny, nx, components); node_positions(vti, k) the
world positions of node layer k, shape (ny, nx, 3): origin + direction (spacing * index)."""
import re

import numpy as np

_MARK = b'<AppendedData encoding="raw">'


def read_vti(path):
    """The grid and the arrays of a fix field/lsdem .vti (module docstring)."""
    raw = open(path, "rb").read()
    base = raw.index(b"_", raw.index(_MARK) + len(_MARK)) + 1
    head = raw[:base].decode()

    def numbers(key):
        return [float(v) for v in re.search(key + r'="([^"]+)"', head).group(1).split()]

    ext = [int(v) for v in numbers("WholeExtent")]
    out = {"n": (ext[1] + 1, ext[3] + 1, ext[5] + 1),
           "origin": np.array(numbers("Origin")),
           "spacing": np.array(numbers("Spacing")),
           "skewed": 'Direction="' in head, "names": []}
    out["h"] = out["spacing"][0]
    out["direction"] = (np.array(numbers("Direction")).reshape(3, 3) if out["skewed"]
                        else np.eye(3))
    for kind, name, comps, offset in re.findall(
            r'<DataArray type="(\w+)" Name="(\w+)" NumberOfComponents="(\d+)" '
            r'format="appended" offset="(\d+)"', head):
        at = base + int(offset)
        nbytes = int(np.frombuffer(raw, "<u8", 1, at)[0])
        dtype = np.dtype("<f8" if kind == "Float64" else "u1")
        out[name] = np.frombuffer(raw, dtype, nbytes // dtype.itemsize, at + 8) \
            .reshape(-1, int(comps))
        out["names"].append(name)
    return out


def node_grid(vti, name):
    """Array `name` of vti as (nz, ny, nx, components)."""
    nx, ny, nz = vti["n"]
    return vti[name].reshape(nz, ny, nx, -1)


def node_positions(vti, k):
    """World positions of node layer k (nodes (i, j, k)), shape (ny, nx, 3)."""
    nx, ny, _ = vti["n"]
    i, j = np.meshgrid(np.arange(nx), np.arange(ny))
    index = np.stack([i, j, np.full_like(i, k)], axis=-1) * vti["spacing"]
    return vti["origin"] + index @ vti["direction"].T
