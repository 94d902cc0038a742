#!/usr/bin/python3
"""lsdem-segment -- a grey-level CT scan to grain labels, a shape library and the in-situ
LAMMPS data file, in one command (doc/lsdem_segment.rst).

  lsdem-segment SCAN.tif OUT.lslib --voxel S [--data OUT.data --density RHO] [options]

The scan is read by `lsdem-shape to-raw` (libtiff: compressed, tiled, BigTIFF, 8/16/32-bit
or float, one page per slice), segmented here with scikit-image and SciPy (Debian
python3-skimage, python3-scipy) the usual way for sand scans, and the labels go to
`lsdem-shape from-labels`, which builds one level-set shape per grain:

  0. region of interest (--roi auto, the default): the zero-filled corners outside a
     reconstruction's circular field of view and the air around the specimen are left out of
     the threshold's and the trend's statistics (--roi none: the whole scan; --roi cylinder
     CX CY R: a cylinder along z, in voxels);
  1. smoothing: Gaussian filter, --sigma voxels (noise);
  2. grey-level trend: a linear trend in x, y, z of the grain and pore grey levels is fitted
     and removed (--no-detrend to keep the scan as it is): beam hardening or uneven
     illumination shift the grey level across a scan, and one global threshold then cuts
     grains at one end and merges pores at the other;
  3. threshold: Otsu's (--threshold otsu, the default) or a given grey level; grains are the
     brighter phase (--dark-grains for the other way round);
  4. Euclidean distance transform of the solid phase;
  5. markers: the h-maxima of the distance (--h voxels: a maximum must rise h above the
     saddle to its neighbour's to seed a grain of its own; larger h merges more);
  6. marker-controlled watershed of the negated distance, inside the solid phase;
  7. small fragments (fewer than --min-voxels) are merged into the neighbour they share most
     faces with, or dropped when they touch none.

Options passed on to from-labels: --nodes N | --node-spacing S, --smooth K, --margin M,
--seed S, --min-voxels N (also its threshold). --labels FILE keeps the label volume (raw
little-endian uint32, or TIFF when FILE ends in .tif). Progress goes to the screen.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy import ndimage as ndi
from skimage import filters, morphology, segmentation

TYPES = {"u8": "<u1", "u16": "<u2", "u32": "<u4", "i8": "<i1", "i16": "<i2", "i32": "<i4",
         "f32": "<f4", "f64": "<f8"}
CORNERS = ([0, 0, -1, -1], [0, -1, 0, -1])  # [y], [x] of a slice's four corners


def fail(msg):
    sys.exit("lsdem-segment: " + msg)


class Progress:
    """One line per stage with the time it took, on the screen as it happens."""

    def __init__(self, quiet):
        self.quiet, self.t0 = quiet, time.time()

    def __call__(self, what):
        if not self.quiet:
            print("lsdem-segment: [%6.1f s] %s" % (time.time() - self.t0, what), flush=True)


def shape_tool():
    tool = os.environ.get("LSDEM_SHAPE_TOOL")
    if tool:
        return tool
    here = os.path.dirname(os.path.realpath(sys.argv[0]))
    for cand in (os.path.join(here, "lsdem-shape"), os.path.join(here, "..", "build", "lsdem-shape")):
        if os.access(cand, os.X_OK):
            return cand
    fail("cannot find lsdem-shape next to this script; set LSDEM_SHAPE_TOOL")


def read_scan(path, tmp):
    """The scan as a float32 array indexed [z, y, x], read through lsdem-shape to-raw."""
    if not os.path.exists(path):
        fail("%s: no such file" % path)
    raw = os.path.join(tmp, "scan.raw")
    p = subprocess.run([shape_tool(), "to-raw", path, raw], stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        fail(p.stderr.strip().replace("lsdem-shape: to-raw: ", "") or "cannot read " + path)
    nx, ny, nz, kind = p.stdout.split()[-4:]
    a = np.fromfile(raw, dtype=TYPES[kind]).reshape(int(nz), int(ny), int(nx))
    os.unlink(raw)
    return a.astype(np.float32), kind


def sample_step(grey):
    """The stride that leaves about two million voxels for the threshold and the fits."""
    return max(1, round((grey.size / 2e6) ** (1 / 3)))


def subsample(roi, step):
    """Which voxels of the every-step-th subsample lie in the region (all when roi is None)."""
    if roi is None:
        return slice(None)
    return roi[::step, ::step, ::step]


def sample(grey, roi, step):
    """Every step-th voxel's grey level inside the region, flat."""
    return grey[::step, ::step, ::step][subsample(roi, step)].ravel()


def otsu(values):
    if values.min() == values.max():
        fail("the scan has one grey level (%g) only: nothing to segment" % values.min())
    return float(filters.threshold_otsu(values))


def fill_region(grey):
    """The voxels outside a reconstruction's field of view: where the four corners of every
    slice hold one and the same value, the voxels of that exact value connected to the
    corners. Returns the mask (None when there is no such fill) and the fill value."""
    corners = grey[(slice(None),) + CORNERS]
    if corners.min() != corners.max():
        return None, None
    value = corners.flat[0]
    parts, _ = ndi.label(grey == value)
    return np.isin(parts, np.unique(parts[(slice(None),) + CORNERS])), float(value)


def specimen_region(grey, outside, min_voxels):
    """The specimen, taken to stand along z: the convex hull of the coarse foreground seen
    along z, in every slice. The coarse foreground is the voxels above Otsu's threshold of
    everything but `outside` (the fill), without specks smaller than min_voxels (noise in the
    air)."""
    inside = ~outside if outside is not None else np.ones(grey.shape, bool)
    coarse = grey > otsu(sample(grey, inside, sample_step(grey)))
    coarse = morphology.remove_small_objects(coarse, min_size=min_voxels)
    if not coarse.any():
        return coarse
    return morphology.convex_hull_image(coarse.any(axis=0))[None] & inside


def cylinder_region(shape, cx, cy, r):
    _, ny, nx = shape
    y, x = np.ogrid[0:ny, 0:nx]
    return np.broadcast_to(np.hypot(x - cx, y - cy) <= r, shape)


def region_of_interest(grey, args, say):
    """The voxels the threshold is chosen over (--roi), or None for the whole scan."""
    if args.roi[0] == "none":
        return None
    if args.roi[0] == "cylinder":
        roi = cylinder_region(grey.shape, *args.roi[1:])
    else:
        outside, value = fill_region(grey)
        say("field of view: " + ("%.3f of the voxels outside it, filled with %g"
                                 % (outside.mean(), value) if outside is not None
                                 else "no constant fill in the slice corners"))
        roi = specimen_region(grey, outside, args.min_voxels)
    if not roi.any():
        fail("the region of interest (--roi %s) holds no voxel" % " ".join(map(str, args.roi)))
    say("region of interest (%s): %.3f of the voxels" % (args.roi[0], roi.mean()))
    return roi


def detrend(grey, roi, t, step):
    """Remove the linear trend of the two phases' grey levels: fit a + b.x to each phase
    (on every step-th voxel of the region of interest, split at the threshold t), subtract the
    mean of the two fits' slopes. Returns the corrected scan and the grey-level change the
    trend made across it."""
    nz, ny, nx = grey.shape
    z, y, x = np.mgrid[0:nz:step, 0:ny:step, 0:nx:step]
    keep = subsample(roi, step)
    g = sample(grey, roi, step)
    coords = [c[keep].ravel() / m for c, m in ((x, nx), (y, ny), (z, nz))]
    pts = np.stack([np.ones(g.size)] + coords, axis=1)
    slopes = []
    for phase in (g > t, g <= t):
        if phase.sum() < 10:
            return grey, 0.0
        coef, *_ = np.linalg.lstsq(pts[phase], g[phase], rcond=None)
        slopes.append(coef[1:])
    b = 0.5 * (slopes[0] + slopes[1])
    zz, yy, xx = np.ogrid[0:nz, 0:ny, 0:nx]
    trend = b[0] * (xx / nx - 0.5) + b[1] * (yy / ny - 0.5) + b[2] * (zz / nz - 0.5)
    return (grey - trend).astype(np.float32), float(np.abs(b).sum())


def merge_oversplit(labels, dist, ratio):
    """Join neighbouring regions whose common boundary is no neck: where the distance on
    the boundary (its saddle) reaches `ratio` times the smaller of the two regions' largest
    distances, the two are one grain split at a shallow dip of an elongated or bumpy
    grain's distance map; at a contact between two grains the saddle is far lower. A
    relative test, so it treats small and large grains alike, where h is absolute.
    Returns the labels and the number of joins."""
    n = int(labels.max())
    if n < 2 or ratio >= 1.0:
        return labels, 0
    peak = np.zeros(n + 1)
    peak[1:] = ndi.maximum(dist, labels, index=np.arange(1, n + 1))
    keys, vals = [], []
    for ax in range(3):
        a, b = np.moveaxis(labels, ax, 0), np.moveaxis(dist, ax, 0)
        la, lb = a[:-1].ravel(), a[1:].ravel()
        m = (la > 0) & (lb > 0) & (la != lb)
        lo, hi = np.minimum(la[m], lb[m]).astype(np.int64), np.maximum(la[m], lb[m])
        keys.append(lo * (n + 1) + hi)
        vals.append(np.minimum(b[:-1].ravel()[m], b[1:].ravel()[m]))
    keys, vals = np.concatenate(keys), np.concatenate(vals)
    if keys.size == 0:
        return labels, 0
    order = np.lexsort((vals, keys))  # per pair, the largest boundary distance comes last
    keys, vals = keys[order], vals[order]
    last = np.r_[keys[1:] != keys[:-1], True]
    pa, pb, saddle = keys[last] // (n + 1), keys[last] % (n + 1), vals[last]
    parent = np.arange(n + 1)

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    joins = 0
    for a, b, s_ab in zip(pa, pb, saddle):
        if s_ab >= ratio * min(peak[a], peak[b]):
            ra, rb = root(a), root(b)
            if ra != rb:
                parent[max(ra, rb)] = min(ra, rb)
                joins += 1
    roots = np.array([root(i) for i in range(n + 1)])
    return roots[labels], joins


def merge_fragments(labels, min_voxels):
    """Labels below min_voxels join the neighbour they share most faces with; fragments that
    touch no other label are dropped. Returns the relabelled volume (1..n), merged, dropped."""
    sizes = np.bincount(labels.ravel())
    small = [l for l in np.nonzero(sizes)[0] if l > 0 and sizes[l] < min_voxels]
    boxes = ndi.find_objects(labels)
    merged = dropped = 0
    for l in sorted(small, key=lambda l: sizes[l]):
        sl = tuple(slice(max(s.start - 1, 0), s.stop + 1) for s in boxes[l - 1])
        sub = labels[sl]
        mine = sub == l
        if not mine.any():  # already absorbed into another
            continue
        ring = ndi.binary_dilation(mine) & ~mine
        around = sub[ring]
        around = around[(around > 0) & (around != l)]
        if around.size:
            target = np.bincount(around).argmax()
            sub[mine] = target
            merged += 1
        else:
            sub[mine] = 0
            dropped += 1
    out, _, _ = segmentation.relabel_sequential(labels)
    return out, merged, dropped


def segment(grey, args, say):
    """The pipeline of the module docstring; returns labels (uint32, [z, y, x]) and a dict of
    what each stage found."""
    info = {}
    if args.dark_grains:
        grey = grey.max() - grey
    roi = region_of_interest(grey, args, say) if args.threshold == "otsu" else None
    if args.sigma > 0:
        grey = filters.gaussian(grey, sigma=args.sigma, preserve_range=True).astype(np.float32)
        say("smoothed (Gaussian, sigma %g voxels)" % args.sigma)
    step = sample_step(grey)
    t = otsu(sample(grey, roi, step)) if args.threshold == "otsu" else float(args.threshold)
    if args.detrend and args.threshold == "otsu":
        grey, change = detrend(grey, roi, t, step)
        t = otsu(sample(grey, roi, step))
        info["trend"] = change
        say("grey-level trend removed (%.4g across the scan)" % change)
    solid = grey > t
    info["threshold"], info["solid_fraction"] = t, float(solid.mean())
    say("threshold %.6g (%s): solid fraction %.3f" % (t, args.threshold, solid.mean()))
    if not solid.any():
        info.update(markers=0, merged=0, dropped=0, grains=0)
        return np.zeros(grey.shape, np.uint32), info
    dist = ndi.distance_transform_edt(solid)
    say("distance transform: largest inscribed radius %.1f voxels" % dist.max())
    markers, nmark = ndi.label(morphology.h_maxima(dist, args.h))
    say("markers (h-maxima, h = %g voxels): %d" % (args.h, nmark))
    labels = segmentation.watershed(-dist, markers, mask=solid)
    say("watershed: %d regions" % labels.max())
    labels, joins = merge_oversplit(labels, dist, args.merge_ratio)
    info["joined"] = joins
    say("regions joined across saddles above %g of their peak distance: %d"
        % (args.merge_ratio, joins))
    labels, merged, dropped = merge_fragments(labels, args.min_voxels)
    info.update(markers=nmark, merged=merged, dropped=dropped, grains=int(labels.max()))
    say("fragments below %d voxels: %d merged into a neighbour, %d dropped; %d grains"
        % (args.min_voxels, merged, dropped, labels.max()))
    return labels.astype(np.uint32), info


def write_labels(path, labels):
    if path.endswith((".tif", ".tiff")):
        import tifffile
        tifffile.imwrite(path, labels, photometric="minisblack")
    else:
        labels.astype("<u4").tofile(path)


def parse_roi(p, words):
    if words in (["auto"], ["none"]):
        return words
    try:
        if words[0] == "cylinder" and len(words) == 4 and float(words[3]) > 0:
            return ["cylinder"] + [float(w) for w in words[1:]]
    except ValueError:
        pass
    p.error("--roi takes auto, none or cylinder CX CY R (R > 0), not '%s'" % " ".join(words))


def parse(argv):
    p = argparse.ArgumentParser(prog="lsdem-segment", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scan", help="grey-level scan: TIFF (any libtiff reads)")
    p.add_argument("library", help="output shape library (.lslib)")
    p.add_argument("--voxel", type=float, required=True, help="voxel size (length units)")
    p.add_argument("--data", help="in-situ LAMMPS data file (needs --density)")
    p.add_argument("--density", type=float)
    p.add_argument("--threshold", default="otsu", help="'otsu' (default) or a grey level")
    p.add_argument("--roi", nargs="+", default=["auto"], metavar="KIND",
                   help="where the threshold is chosen: auto (default: the specimen, without "
                        "a zero-filled field of view or the air around it), none (the whole "
                        "scan) or cylinder CX CY R (voxels)")
    p.add_argument("--no-detrend", dest="detrend", action="store_false",
                   help="keep the scan's grey-level trend")
    p.add_argument("--dark-grains", action="store_true", help="grains are darker than pores")
    p.add_argument("--sigma", type=float, default=1.0, help="Gaussian smoothing, voxels (1)")
    p.add_argument("--h", type=float, default=0.5, help="h-maxima height, voxels (0.5)")
    p.add_argument("--merge-ratio", type=float, default=0.9,
                   help="join regions whose saddle reaches this share of their peak distance "
                        "(0.9; 1 joins none)")
    p.add_argument("--min-voxels", type=int, default=100, help="smallest grain, voxels (100)")
    p.add_argument("--labels", help="keep the labels: raw uint32 or .tif")
    p.add_argument("--quiet", action="store_true", help="no progress lines")
    for opt in ("--nodes", "--node-spacing", "--smooth", "--margin", "--seed"):
        p.add_argument(opt, help="passed to lsdem-shape from-labels")
    a = p.parse_args(argv)
    if a.voxel <= 0 or (a.density is not None and a.density <= 0):
        p.error("--voxel and --density must be positive")
    if a.data and a.density is None:
        p.error("--data needs --density RHO")
    if a.threshold != "otsu":
        try:
            float(a.threshold)
        except ValueError:
            p.error("--threshold takes 'otsu' or a number, not '%s'" % a.threshold)
    a.roi = parse_roi(p, a.roi)
    if a.sigma < 0 or a.h <= 0 or a.min_voxels < 1:
        p.error("--sigma >= 0, --h > 0 and --min-voxels >= 1")
    return a


def main(argv=None):
    args = parse(sys.argv[1:] if argv is None else argv)
    say = Progress(args.quiet)
    with tempfile.TemporaryDirectory(prefix="lsdem-segment.") as tmp:
        grey, kind = read_scan(args.scan, tmp)
        nz, ny, nx = grey.shape
        say("%s: %d x %d x %d voxels, %s" % (args.scan, nx, ny, nz, kind))
        labels, info = segment(grey, args, say)
        del grey
        if info["grains"] == 0:
            fail("%s: no grain found (threshold %.6g, solid fraction %.3f): check --threshold "
                 "and --dark-grains" % (args.scan, info["threshold"], info["solid_fraction"]))
        if args.labels:
            write_labels(args.labels, labels)
            say("labels written to %s" % args.labels)
        raw = os.path.join(tmp, "labels.raw")
        labels.astype("<u4").tofile(raw)
        cmd = [shape_tool(), "from-labels", raw, args.library, "--raw", str(nx), str(ny), str(nz),
               "u32", "--voxel", repr(args.voxel), "--min-voxels", str(args.min_voxels)]
        for opt in ("nodes", "node_spacing", "smooth", "margin", "seed"):
            if getattr(args, opt) is not None:
                cmd += ["--" + opt.replace("_", "-"), getattr(args, opt)]
        if args.data:
            cmd += ["--data", args.data, "--density", repr(args.density)]
        say("building %d shapes (lsdem-shape from-labels)" % info["grains"])
        p = subprocess.run(cmd)
        if p.returncode != 0:
            fail("lsdem-shape from-labels failed (exit %d)" % p.returncode)
        say("done: %s%s" % (args.library, ", " + args.data if args.data else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
