"""dump lsdem/vtk: posed grain surfaces per dump step (.vtp) and the ParaView index (.pvd),
on 1 and 2 ranks; and lsdem-shape render of the same run's dump frame (PNG checked with
python's zlib).

Expectations are independent of the dump code: the triangle count of each shape's mesh
comes from `lsdem-shape surface`; grain poses come from a dump custom of the same run; a
vertex mapped back to its grain's frame (R(q)^T (p - x), quaternion algebra here) must lie
on the analytic ball (radius 0.5) or inside the box (half-extents BOX) and reach its faces,
and every vertex lies within the grain's bounding radius of its centre."""
import math
import os
import struct
import subprocess
import xml.etree.ElementTree as ET
import zlib

from lsdemtest import SHAPE_TOOL, run_lmp, shape_tool, check, near, finish
import grain_decks as gd

LIB = gd.library()
GRAINS = [
    dict(id=1, shape=1, density=1.0, x=(-6.0, -5.0, 1.0), q=(0.9, 0.2, -0.3, 0.4),
         v=(0.4, 0.1, 0.0), w=(0.3, -0.5, 0.8)),
    dict(id=2, shape=2, density=1.0, x=(5.0, 0.0, 0.0), q=(1.0, 0.0, 0.0, 0.0),
         v=(-0.5, 0.0, 0.2)),
    dict(id=3, shape=3, density=1.0, x=(-5.0, 3.0, -4.0), q=(0.5, 0.5, 0.5, 0.5),
         v=(0.1, 0.4, -0.3), w=(2.0, -1.0, 0.5)),
    dict(id=4, shape=3, density=1.0, x=(6.0, 6.0, 5.0), q=(0.1, -0.7, 0.2, 0.3),
         v=(-0.3, 0.2, 0.1), w=(0.9, 0.9, -0.9)),
    dict(id=5, shape=1, density=1.0, x=(0.5, -6.0, -6.0), q=(0.0, 1.0, 0.0, 0.0)),
]
gd.write_data("grains.data", GRAINS)
STEPS, EVERY, DT = 20, 10, 0.005

# triangles of each shape's mesh, by the command-line tool
ntri = {}
for s in (1, 2, 3):
    shape_tool("surface", LIB, s - 1, "shape%d.vtk" % s)
    for line in open("shape%d.vtk" % s):
        if line.startswith("POLYGONS"):
            ntri[s] = int(line.split()[1])
check(len(ntri) == 3 and min(ntri.values()) > 100, "mesh triangle counts: %r" % ntri)

# bounding radii from the shapes' geometry (+ one grid spacing for the sampled shapes)
RADIUS = {1: max(gd.ELL) + 0.2, 2: gd.BALL * 1.001, 3: math.sqrt(sum(h * h for h in gd.BOX)) + 0.25}


def deck(extra=""):
    return ("units lj\natom_style lsdem library %s\natom_modify map array\nnewton on\n"
            "comm_modify vel yes\nread_data grains.data\ntimestep %r\n" % (LIB, DT)
            + gd.PROPS + gd.dump_line("c", EVERY, "grains.dump")
            + "dump v all lsdem/vtk %d out/grains\n" % EVERY + extra
            + "fix 1 all nve/lsdem\nrun %d\n" % STEPS)


def floats(node):
    return [float(t) for t in node.text.split()]


def read_vtp(path):
    root = ET.parse(path).getroot()
    pieces = root.findall("./PolyData/Piece")
    check(len(pieces) == 1, "%s: %d pieces" % (path, len(pieces)))
    p = pieces[0]
    npts, npolys = int(p.get("NumberOfPoints")), int(p.get("NumberOfPolys"))
    pts = floats(p.find("./Points/DataArray"))
    arrays = {a.get("Name"): [int(t) for t in a.text.split()]
              for a in p.findall("./Polys/DataArray") + p.findall("./CellData/DataArray")}
    check(len(pts) == 3 * npts and len(arrays["connectivity"]) == 3 * npolys
          and arrays["offsets"] == [3 * (t + 1) for t in range(npolys)]
          and len(arrays["id"]) == npolys and len(arrays["shape"]) == npolys,
          "%s: array sizes disagree with the piece header" % path)
    return npts, npolys, pts, arrays


def rotate_inv(q, v):
    """R(q)^T v for a unit quaternion q = (w, x, y, z): q* v q."""
    r = gd.qmul(gd.qmul(gd.qconj(q), (0.0,) + tuple(v)), q)
    return r[1:]


def check_frame(path, atoms, tag):
    npts, npolys, pts, a = read_vtp(path)
    want = sum(ntri[int(at["c_p[5]"])] for at in atoms.values())
    check(npolys == want, "%s: %d triangles, expected %d" % (tag, npolys, want))
    verts_of = {}
    for t in range(npolys):
        verts_of.setdefault(a["id"][t], set()).update(a["connectivity"][3 * t:3 * t + 3])
    check(set(verts_of) == set(atoms), "%s: grains %r, expected %r"
          % (tag, sorted(verts_of), sorted(atoms)))
    for gid, at in atoms.items():
        s = int(at["c_p[5]"])
        cells = [t for t in range(npolys) if a["id"][t] == gid]
        check(len(cells) == ntri[s] and all(a["shape"][t] == s for t in cells),
              "%s: grain %d has %d triangles of shapes %r, expected %d of shape %d"
              % (tag, gid, len(cells), sorted({a["shape"][t] for t in cells}), ntri[s], s))
        x, q = (at["x"], at["y"], at["z"]), gd.qnormalize(gd.quat(at))
        body = [rotate_inv(q, [pts[3 * v + k] - x[k] for k in range(3)])
                for v in verts_of.get(gid, ())]
        far = max(math.sqrt(sum(c * c for c in b)) for b in body)
        check(far <= RADIUS[s], "%s: grain %d vertex %.4f from its centre > %.4f"
              % (tag, gid, far, RADIUS[s]))
        if s == 2:   # analytic ball on a lattice of R/20: vertices on the sphere
            dev = max(abs(math.sqrt(sum(c * c for c in b)) - gd.BALL) for b in body)
            check(dev < 0.01 * gd.BALL, "%s: ball vertex off the sphere by %g" % (tag, dev))
        if s == 3:   # box grid: inside the box in its own frame, touching every face
            hi = [max(abs(b[k]) for b in body) for k in range(3)]
            check(all(gd.BOX[k] - 0.25 <= hi[k] <= gd.BOX[k] + 1e-6 for k in range(3)),
                  "%s: grain %d box extents %r, half-extents %r (wrong pose?)"
                  % (tag, gid, hi, gd.BOX))


os.makedirs("out", exist_ok=True)
texts = {}
for np_ in (1, 2):
    for f in os.listdir("out"):
        os.remove(os.path.join("out", f))
    run_lmp(deck("dump_modify v sort id\n"), np=np_)
    frames = dict(gd.read_dump("grains.dump"))
    steps = list(range(0, STEPS + 1, EVERY))
    check(sorted(frames) == steps, "np %d: custom dump steps %r" % (np_, sorted(frames)))
    for step in steps:
        path = "out/grains_%d.vtp" % step
        if check(os.path.exists(path), "np %d: %s missing" % (np_, path)):
            check_frame(path, frames[step], "np %d step %d" % (np_, step))
            texts.setdefault(step, []).append(open(path).read())
    # the index lists every step, with its time, relative to its own folder
    root = ET.parse("out/grains.pvd").getroot()
    sets = root.findall("./Collection/DataSet")
    check([d.get("file") for d in sets] == ["grains_%d.vtp" % s for s in steps],
          "np %d: pvd files %r" % (np_, [d.get("file") for d in sets]))
    for d, s in zip(sets, steps):
        near(float(d.get("timestep")), s * DT, atol=1e-12, msg="pvd time of step %d" % s)
for step, t in texts.items():
    check(len(t) == 2 and t[0] == t[1], "step %d: 1-rank and 2-rank files differ (sort id)" % step)

# unsorted on 2 ranks: every grain still there once
for f in os.listdir("out"):
    os.remove(os.path.join("out", f))
run_lmp(deck(), np=2)
frames = dict(gd.read_dump("grains.dump"))
check_frame("out/grains_%d.vtp" % STEPS, frames[STEPS], "np 2 unsorted")

# files already written survive a run that fails later
for f in os.listdir("out"):
    os.remove(os.path.join("out", f))
rc, log = run_lmp(deck() + "variable bad equal 1/0\nprint ${bad}\n", expect_fail=True)
check(rc != 0, "the failing deck did not fail")
check(len(ET.parse("out/grains.pvd").getroot().findall("./Collection/DataSet")) == 3
      and os.path.exists("out/grains_20.vtp"), "files lost after a failing command")
ET.parse("out/grains_20.vtp")

# spacing 2: coarser lattices, about 4 times fewer triangles, grains still complete
for f in os.listdir("out"):
    os.remove(os.path.join("out", f))
run_lmp(deck().replace("out/grains\n", "out/grains spacing 2.0\n"))
n2, t2, pts2, a2 = read_vtp("out/grains_0.vtp")
t1 = sum(ntri[g["shape"]] for g in GRAINS)
check(0.15 * t1 < t2 < 0.4 * t1 and set(a2["id"]) == {g["id"] for g in GRAINS},
      "spacing 2: %d triangles vs %d at spacing 1" % (t2, t1))
check("no surface triangles" not in open("log.lammps").read(), "spacing 2: no shape lost")

# spacing 30: the ball's lattice (radius / 20 x 30) is coarser than the ball, which has no
# triangles left; its grain is left out of the files, and a warning says so
run_lmp(deck().replace("out/grains\n", "out/grains spacing 30\n"))
n30, t30, pts30, a30 = read_vtp("out/grains_0.vtp")
logged = open("log.lammps").read()
check(2 not in set(a30["id"]) and "shape 2 has no surface triangles at spacing 30" in logged,
      "spacing 30: grain 2 missing (%s) without the warning" % sorted(set(a30["id"])))

# input errors
rc, log = run_lmp("units lj\natom_style lsdem library %s\nread_data grains.data\n"
                  "dump v all lsdem/vtk 10 out/g*\n" % LIB, expect_fail=True)
check("without * or %" in log, "prefix with * not rejected: %s" % log[-300:])
rc, log = run_lmp("units lj\natom_style lsdem library %s\nread_data grains.data\n"
                  "dump v all lsdem/vtk 10 nofolder/g\nrun 0\n" % LIB, expect_fail=True)
check("cannot open nofolder/g_0.vtp" in log and "shell mkdir nofolder" in log,
      "missing dump folder not named: %s" % log[-300:])
rc, log = run_lmp("units lj\natom_style sphere\nregion b block 0 1 0 1 0 1\ncreate_box 1 b\n"
                  "dump v all lsdem/vtk 10 g\n", expect_fail=True)
check("requires atom_style lsdem" in log, "atom style not checked: %s" % log[-300:])

# ---- lsdem-shape render of the last dump frame and of the data file -----------------
def read_png(path):
    """(width, height, rows of RGB bytes) of an 8-bit RGB PNG, every chunk CRC checked
    (read here with zlib, independently of libpng, which wrote it)."""
    png = open(path, "rb").read()
    check(png[:8] == b"\x89PNG\r\n\x1a\n", "%s: PNG signature" % path)
    pos, idat, chunks, size = 8, b"", [], (0, 0)
    while pos < len(png):
        n, kind = struct.unpack(">I4s", png[pos:pos + 8])
        data = png[pos + 8:pos + 8 + n]
        crc, = struct.unpack(">I", png[pos + 8 + n:pos + 12 + n])
        check(zlib.crc32(kind + data) == crc, "%s: CRC of chunk %r" % (path, kind))
        chunks.append(kind)
        if kind == b"IHDR":
            size = struct.unpack(">II", data[:8])
            check(data[8:10] == b"\x08\x02", "%s: not 8-bit RGB" % path)
        idat += data if kind == b"IDAT" else b""
        pos += 12 + n
    check(chunks[0] == b"IHDR" and chunks[-1] == b"IEND", "%s: chunks %r" % (path, chunks))
    w, h = size
    raw = zlib.decompress(idat)
    check(len(raw) == h * (1 + 3 * w), "%s: decompressed %d bytes" % (path, len(raw)))
    return w, h, unfilter(raw, w, h)


def unfilter(raw, w, h):
    """Scanlines of 3-byte pixels from PNG's filtered rows (filter types 0-4, RFC 2083 §6):
    libpng chooses a filter per row."""
    rows, prev, n = [], bytearray(3 * w), 3 * w
    for r in range(h):
        kind, line = raw[r * (n + 1)], bytearray(raw[r * (n + 1) + 1:(r + 1) * (n + 1)])
        for i in range(n):
            a = line[i - 3] if i >= 3 else 0
            b, c = prev[i], prev[i - 3] if i >= 3 else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        check(kind <= 4, "PNG filter type %d" % kind)
        rows.append(bytes(line))
        prev = line
    return rows


def covered(rows, w):
    return sum(1 for row in rows for c in range(w) if row[3 * c:3 * c + 3] != b"\xff\xff\xff")


shape_tool("render", LIB, "grains.dump", "frame.png", "--size", 160, 120, "--view", "z")
w, h, rows = read_png("frame.png")
check((w, h) == (160, 120), "frame.png is %dx%d" % (w, h))
check(0.01 * w * h < covered(rows, w) < 0.9 * w * h, "grain pixels: %d of %d" % (covered(rows, w), w * h))
shape_tool("render", LIB, "grains.data", "data.png", "--size", 90, 70, "--view", "y")
w, h, rows = read_png("data.png")
check((w, h) == (90, 70) and covered(rows, w) > 0.01 * w * h, "data.png: %dx%d" % (w, h))

# readers reject what they cannot use, naming the problem
bad = open("grains.data").read().replace("\n2 1 2 1.0 ", "\n2 1 9 1.0 ", 1)
open("bad.data", "w").write(bad)
open("bad.dump", "w").write(open("grains.dump").read().replace("c_p[2]", "c_q[2]"))
for path, want in (("bad.data", "shape-ID in 1..3"), ("bad.dump", "c_NAME[1..5]")):
    p = subprocess.run([SHAPE_TOOL, "render", LIB, path, "x.png"], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True)
    check(p.returncode == 1 and want in p.stdout, "%s: exit %d, %s" % (path, p.returncode, p.stdout))
finish()
