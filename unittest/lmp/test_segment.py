"""lsdem-segment: a grey-level, compressed CT stack -> labels -> shape library + in-situ data
file -> a running lmp. Independent expectations:
  * the scan is made from known grains (tools/synthetic_scan.py: 92 touching, bumpy
    ellipsoids, blurred, noisy, with a grey-level gradient along z) and written uncompressed
    by tifffile; libtiff's own tiffcp compresses it (LZW, Deflate, PackBits), tiles it, turns
    it into BigTIFF or big-endian: every variant must read to the same samples as numpy
    reads from tifffile's file;
  * the segmentation is scored against the grains the scan was made from: one-to-one
    recovery and volume error within the figures of doc/lsdem_segment.rst, and removing the
    grey-level trend must reduce the volume error;
  * a scan of a cylindrical specimen with air around it and zero-filled corners outside the
    circular field of view: the threshold (the midpoint of the two phases' fitted levels)
    lies within 3 % of the contrast of the midpoint of the two phases' mean grey levels
    taken from the truth, with the default region of interest, the true cylinder and even
    the whole scan; the zero fill is warned about, and over the whole scan that one phase
    dominates; the default recovers at least as many grains as on the scan without air;
  * the in-situ data file holds one grain per shape and lmp runs it.
A damaged file and a scan without grains stop with a message naming the file and the cause."""
import os
import re
import subprocess
import sys

import numpy as np
from scipy import ndimage as ndi

from lsdemtest import HERE, SHAPE_TOOL, check, finish, run_lmp, shape_tool

TOOLS = os.path.join(HERE, "..", "..", "tools")
SEGMENT = os.path.join(os.path.dirname(SHAPE_TOOL), "lsdem-segment")
sys.path.insert(0, TOOLS)
import synthetic_scan  # noqa: E402

N = 96


def run(cmd, expect_ok=True, progress="0"):
    p = subprocess.run([str(c) for c in cmd], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, env=dict(os.environ, LSDEM_SHAPE_TOOL=SHAPE_TOOL,
                                           LSDEM_PROGRESS=progress))
    if expect_ok:
        check(p.returncode == 0, "%s failed (%d):\n%s" % (" ".join(map(str, cmd)), p.returncode,
                                                         p.stdout[-3000:]))
    return p


def score(labels_file, truth_file="scan.truth.raw"):
    truth = np.fromfile(truth_file, "<u4").reshape(N, N, N)
    found = np.fromfile(labels_file, "<u4").reshape(N, N, N)
    return synthetic_scan.score(truth, found)


# ---- the scan and its libtiff-written variants -------------------------------------------
run([sys.executable, os.path.join(TOOLS, "synthetic_scan.py"), "make", "scan", "--size", N,
     "--grains", 120, "--seed", 1])
import tifffile  # noqa: E402

reference = tifffile.imread("scan.tif")
check(reference.shape == (N, N, N) and reference.dtype == np.uint16, "scan %s %s"
      % (reference.shape, reference.dtype))
variants = {"lzw": ["-c", "lzw"], "zip": ["-c", "zip"], "packbits": ["-c", "packbits"],
            "tiled_lzw": ["-t", "-w", "32", "-l", "32", "-c", "lzw"],
            "bigtiff_zip": ["-8", "-c", "zip"], "bigendian_lzw": ["-B", "-c", "lzw:2"]}
for name, opts in variants.items():
    run(["tiffcp"] + opts + ["scan.tif", "scan_%s.tif" % name])
    out = run([SHAPE_TOOL, "to-raw", "scan_%s.tif" % name, "scan_%s.raw" % name]).stdout
    check(out.split()[-4:] == [str(N), str(N), str(N), "u16"], "%s: to-raw says %s" % (name, out))
    got = np.fromfile("scan_%s.raw" % name, "<u2")
    check(got.size == reference.size and np.array_equal(got.reshape(reference.shape), reference),
          "%s: samples differ from tifffile's reading of the uncompressed scan" % name)
check(os.path.getsize("scan_zip.tif") < os.path.getsize("scan.tif"), "Deflate did not compress")

# ---- segmentation against the known grains -----------------------------------------------
p = run([SEGMENT, "scan_lzw.tif", "grains.lslib", "--voxel", 1e-4, "--labels", "found.raw",
         "--data", "insitu.data", "--density", 2650, "--nodes", 100], progress="1")
for stage in ("no constant fill", "region of interest", "grey levels", "threshold", "grain size",
              "distance transform",
              "markers", "watershed", "joined", "fragments", "building", "shapes built"):
    check(stage in p.stdout, "no progress line for '%s':\n%s" % (stage, p.stdout[-2000:]))
built = [tuple(map(int, re.search(r"shapes built: (\d+) of (\d+)", l).groups()))
         for l in p.stdout.splitlines() if "shapes built" in l]
check(len(built) == 10 and built[-1][0] == built[-1][1] and len({t for _, t in built}) == 1,
      "from-labels progress: one line per tenth expected, got %s" % built)
r = score("found.raw")
print("segmentation of the LZW scan: %s" % r)
check(r["true"] >= 80, "the synthetic scan has only %d grains" % r["true"])
check(r["fraction"] >= 0.95, "recovered one-to-one: %.3f of the grains (expected >= 0.95)"
      % r["fraction"])
check(r["vol_err_mean_abs"] <= 0.08, "mean |volume error| %.3f (expected <= 0.08)"
      % r["vol_err_mean_abs"])
check(abs(r["vol_err_mean"]) <= 0.07, "volume bias %.3f (expected within 0.07)" % r["vol_err_mean"])
check(r["found"] <= 1.1 * r["true"], "%d grains found for %d: over-segmented" % (r["found"], r["true"]))

run([SEGMENT, "scan_lzw.tif", "trend.lslib", "--voxel", 1e-4, "--labels", "trend.raw",
     "--no-detrend", "--nodes", 50, "--quiet"])
r_trend = score("trend.raw")
print("without trend removal: %s" % r_trend)
# the trend makes grains too large at the bright end and too small at the dark one
check(r_trend["vol_err_mean_abs"] > 1.5 * r["vol_err_mean_abs"],
      "trend removal did not help: mean |volume error| %.3f without, %.3f with"
      % (r_trend["vol_err_mean_abs"], r["vol_err_mean_abs"]))

# a given threshold (the grey level half way between pore and grain, at the middle slice)
run([SEGMENT, "scan.tif", "given.lslib", "--voxel", 1e-4, "--labels", "given.raw",
     "--threshold", 20000, "--no-detrend", "--nodes", 50, "--quiet"])
check(score("given.raw")["fraction"] > 0.5, "a given threshold found too few grains")

# ---- air around the specimen, zero-filled corners: the region of interest -----------------
SPECIMEN = 0.8  # radius of the grains' cylinder, a fraction of half the size
run([sys.executable, os.path.join(TOOLS, "synthetic_scan.py"), "make", "air", "--size", N,
     "--grains", 120, "--seed", 1, "--specimen", SPECIMEN, "--zero-corners"])
air = tifffile.imread("air.tif")
air_truth = np.fromfile("air.truth.raw", "<u4").reshape(N, N, N)
yy, xx = np.ogrid[0:N, 0:N]
from_axis = np.hypot(xx - (N - 1) / 2, yy - (N - 1) / 2)
in_specimen = from_axis <= SPECIMEN * N / 2
check((air[:, from_axis > N / 2] == 0).all() and (air[:, in_specimen] > 0).mean() > 0.99,
      "the scan's corners are not zero-filled")
# the two phases' grey levels in the middle slice (where the trend along z is 0), from the
# truth: voxels more than 2 voxels inside a grain or inside the specimen's pore space
inner = [ndi.distance_transform_edt(m) > 2 for m in (air_truth == 0, air_truth > 0)]
pore_mean, grain_mean = (float(air[N // 2][m[N // 2] & in_specimen].mean()) for m in inner)
t_true = 0.5 * (pore_mean + grain_mean)


def segment_air(*roi):
    p = run([SEGMENT, "air.tif", "air.lslib", "--voxel", 1e-4, "--labels", "air.raw",
             "--nodes", 50] + list(roi), progress="1")
    t = float(re.search(r"threshold ([0-9.]+) \(midpoint", p.stdout).group(1))
    return t, score("air.raw", "air.truth.raw"), p.stdout


t_none, r_none, out_none = segment_air("--roi", "none")
t_auto, r_auto, out = segment_air()
t_cyl, _, _ = segment_air("--roi", "cylinder", (N - 1) / 2, (N - 1) / 2, SPECIMEN * N / 2)
print("air around the specimen: phases %.0f and %.0f (truth), midpoint %.0f; threshold "
      "--roi none %.0f, %s; auto %.0f, %s; cylinder %.0f" % (pore_mean, grain_mean, t_true,
                                                            t_none, r_none, t_auto, r_auto, t_cyl))
check("filled with 0" in out and "warning: the corners outside the field of view are filled "
      "with 0" in out, "zero-filled corners not reported:\n%s" % out[-2000:])
check("warning: one phase dominates" in out_none and "one phase dominates" not in out,
      "the whole scan (--roi none) is mostly air and zero fill: a warning expected there only")
for name, t in (("auto", t_auto), ("cylinder", t_cyl), ("none", t_none)):
    check(abs(t - t_true) <= 0.03 * (grain_mean - pore_mean), "--roi %s: threshold %.0f, the "
          "phases' midpoint %.0f" % (name, t, t_true))
check(r_auto["fraction"] >= r["fraction"] and abs(r_auto["vol_err_mean"]) <= 0.07,
      "--roi auto on the scan with air: %s; without air: %s" % (r_auto, r))

# ---- the shapes and the data file run in lmp ---------------------------------------------
listing = shape_tool("list", "grains.lslib")
nshapes = int(listing.split()[1])
check(nshapes == r["found"], "library has %d shapes, the labels %d grains" % (nshapes, r["found"]))
shape_tool("verify", "grains.lslib")
natoms = next(int(l.split()[0]) for l in open("insitu.data") if l.strip().endswith("atoms"))
check(natoms == nshapes, "data file has %d grains for %d shapes" % (natoms, nshapes))
deck = """units si
atom_style lsdem library grains.lslib
boundary f f f
newton on
comm_modify vel yes
read_data insitu.data
pair_style lsdem
pair_coeff * * 100 90 0.5
neighbor 0.0003 bin
fix grav all gravity 9.81 vector 0 0 -1
fix integrate all nve/lsdem damping 2.0
timestep 1e-6
thermo 10
run 20
"""
rc, log = run_lmp(deck)
check(rc == 0 and "Loop time" in log, "lmp did not run the in-situ sample")
check("%d atoms" % nshapes in log, "lmp read another grain count")

# ---- errors: a damaged file, a scan with no grain, a bad option --------------------------
data = open("scan_zip.tif", "rb").read()
open("cut.tif", "wb").write(data[: len(data) // 2])
p = run([SEGMENT, "cut.tif", "x.lslib", "--voxel", 1], expect_ok=False)
check(p.returncode != 0 and "cut.tif" in p.stdout and "Traceback" not in p.stdout,
      "damaged file: %s" % p.stdout[-800:])
tifffile.imwrite("flat.tif", np.full((8, 16, 16), 1000, np.uint16))
p = run([SEGMENT, "flat.tif", "x.lslib", "--voxel", 1, "--threshold", 5000], expect_ok=False)
check(p.returncode != 0 and "no grain found" in p.stdout, "flat scan: %s" % p.stdout[-800:])
p = run([SEGMENT, "scan.tif", "x.lslib", "--voxel", 1, "--threshold", "bright"], expect_ok=False)
check(p.returncode == 2 and "--threshold" in p.stdout, "bad threshold: %s" % p.stdout[-800:])
p = run([SEGMENT, "scan.tif", "x.lslib", "--voxel", 1, "--roi", "cylinder", 1], expect_ok=False)
check(p.returncode == 2 and "--roi" in p.stdout, "bad region: %s" % p.stdout[-800:])
finish()
