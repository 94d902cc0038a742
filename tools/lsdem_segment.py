#!/usr/bin/python3
"""lsdem-segment -- a grey-level CT scan to grain labels, a shape library and the in-situ
LAMMPS data file, in one command (doc/lsdem_segment.rst).

  lsdem-segment SCAN.tif OUT.lslib --voxel S [--data OUT.data --density RHO] [options]

The scan is read by `lsdem-shape to-raw` (libtiff: compressed, tiled, BigTIFF, 8/16/32-bit
or float, one page per slice), segmented here with scikit-image and SciPy (Debian
python3-skimage, python3-scipy) the usual way for sand scans, and the labels go to
`lsdem-shape from-labels`, which builds one level-set shape per grain:

  0. region of interest (--roi auto, the default): the zero-filled corners outside a
     reconstruction's circular field of view (warned about) and the air around the specimen
     are left out; the threshold, the fits and the grains are found inside it (--roi none:
     the whole scan; --roi cylinder CX CY R: a cylinder along z, in voxels; --mask FILE: a
     scan of the same size, nonzero in the specimen);
  1. denoising: none by default (at 8-25 voxels per grain any smoothing closes the 1-2
     voxel gaps between grains more than it helps against noise at SNR 5 or more);
     --denoise median (3x3x3) or gaussian (--sigma voxels) on request;
  2. shading: the grey levels of the pore and the grain phase are fitted across the scan on
     their pure voxels (away from the other phase): a linear trend in x, y, z, cupping
     (rho^2, rho^4 about the axis) and ring artifacts (an offset per half-voxel ring);
     the scan is normalised to 0 in the pore and 1 in the grains everywhere (--no-detrend:
     two constant levels);
  3. threshold: half way, 0.5 of the normalised scan (--threshold midpoint, the default):
     a partial-volume voxel is solid when more than half of it is; 'otsu' takes Otsu's
     threshold of the normalised scan, a number a grey level of the scan itself (no
     normalisation); grains are the brighter phase (--dark-grains for the other way round);
     warnings when one phase dominates the region or the phases overlap; a pore voxel
     enclosed alone in the solid (6-connected) is filled: noise at the threshold, and each
     one is a pit in the distance map that splits a grain;
  4. Euclidean distance transform of the solid phase, lowered by --grey-weight (4) voxels
     times 1 - the normalised grey level (smoothed over 0.7 voxel, clipped to 0..1): the
     darker voxels of a gap the threshold closed lower the map where two grains meet;
  5. markers: the h-maxima of that map, h = 0.0015 D^2 voxels, at most 0.5 (--h), D the grain size
     (--d50, or 6 V / S of the solid phase, V its volume, S 2/3 of its voxel faces);
  6. marker-controlled watershed of the negated map, inside the solid phase;
  7. regions whose common saddle reaches --merge-ratio of the smaller peak are joined;
  8. small fragments (fewer than --min-voxels, default 5 % of a sphere of diameter D) are
     merged into the neighbour they share most faces with, or dropped when they touch none;
  9. check: a label that is not one convex body is named in a warning (its id in --labels
     and in the shape's name, label_<L>): one whose convex hull leaves a hollow of more
     than 4 % of its volume, at least 1.5 voxels and 0.2 times its inscribed radius deep
     (the crease about the contact of two grains; a grain alone is nearly convex); larger
     than the median label it likely holds two grains, smaller it is likely a piece of a
     grain split in two.

--report DIR writes report.txt (the progress lines and warnings), histogram.png (the scan
and the normalised scan in the region, the phases' levels and the threshold) and the middle
z slice after each stage as PNG.

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
from scipy.spatial import ConvexHull, QhullError
from skimage import filters, morphology, segmentation

TYPES = {"u8": "<u1", "u16": "<u2", "u32": "<u4", "i8": "<i1", "i16": "<i2", "i32": "<i4",
         "f32": "<f4", "f64": "<f8"}
CORNERS = ([0, 0, -1, -1], [0, -1, 0, -1])  # [y], [x] of a slice's four corners
SPECK_VOXELS = 27     # coarse foreground specks smaller than this are noise in the air
DENOISE = "none"      # the default denoising (doc/lsdem_segment.rst, "How well it segments")
H_PER_SIZE2 = 0.0015  # h-maxima height over the square of the grain size,
H_MAX = 0.5           # voxels, at most
MIN_VOLUME_SHARE = 0.05  # smallest grain over the volume of a sphere of the grain size
PURE_DEPTH = 2        # voxels: a pure voxel is this far inside its phase, if there are
MIN_PURE = 100        # this many sampled per fitted coefficient (else nearer the surface)
RING_WINDOW = 9       # half-voxel bins: rings are narrower than a median over 4.5 voxels
GREY_WEIGHT = 4.0     # voxels: the distance map lowered by this times 1 - normalised grey
WEIGHT_SIGMA = 0.7    # voxels: the Gaussian that takes the noise out of that weight
HOLLOW_DEPTH = 1.5    # voxels: a hollow of a label's convex hull counts this deep or more
HOLLOW_DEPTH_SHARE = 0.2  # and this share of the label's inscribed radius,
HOLLOW_SHARE = 0.04   # when it holds more than this share of the label's volume
CORNERS8 = np.array([[a, b, c] for a in (-0.5, 0.5) for b in (-0.5, 0.5) for c in (-0.5, 0.5)])


def fail(msg):
    sys.exit("lsdem-segment: " + msg)


class Progress:
    """One line per stage with the time it took, on the screen as it happens; all of them
    kept for the report."""

    def __init__(self, quiet):
        self.quiet, self.t0, self.lines = quiet, time.time(), []

    def __call__(self, what):
        line = "[%6.1f s] %s" % (time.time() - self.t0, what)
        self.lines.append(line)
        if not self.quiet:
            print("lsdem-segment: " + line, flush=True)


def warn(say, msg):
    """A warning: on stderr whatever --quiet says, and in the report."""
    say.lines.append("warning: " + msg)
    print("lsdem-segment: warning: " + msg, file=sys.stderr, flush=True)


class Report:
    """--report DIR: the histogram with the chosen threshold and the middle z slice after
    each stage, as PNG (matplotlib, Debian python3-matplotlib), and report.txt."""

    def __init__(self, folder):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        self.plt, self.folder, self.count = plt, folder, 0
        os.makedirs(folder, exist_ok=True)

    def slice(self, name, volume):
        self.count += 1
        img = np.asarray(volume[volume.shape[0] // 2], dtype=np.float64)
        fig, ax = self.plt.subplots(figsize=(5, 5))
        if name in ("markers", "labels"):
            shown = np.where(img > 0, (img * 0.618034) % 1 + 0.05, np.nan)
            ax.imshow(shown, cmap="hsv", vmin=0, vmax=1.05, interpolation="nearest")
        else:
            span = (-0.25, 1.25) if name == "normalised" else (None, None)
            ax.imshow(img, cmap="gray", vmin=span[0], vmax=span[1], interpolation="nearest")
        ax.set_title("%d. %s (slice z = %d)" % (self.count, name, volume.shape[0] // 2))
        ax.axis("off")
        fig.savefig(os.path.join(self.folder, "%d_%s.png" % (self.count, name)), dpi=80,
                    bbox_inches="tight")
        self.plt.close(fig)

    def histogram(self, raw, norm, t, levels):
        fig, ax = self.plt.subplots(1, 2, figsize=(10, 3.5))
        ax[0].hist(raw, bins=256, color="0.4")
        for v, c in zip(levels, ("b", "r")):
            ax[0].axvline(v, color=c, lw=1)
        ax[0].set_title("scan in the region (pore, grain level on the axis)")
        ax[1].hist(norm, bins=256, range=(-0.5, 1.5), color="0.4")
        ax[1].axvline(0, color="b", lw=1)
        ax[1].axvline(1, color="r", lw=1)
        ax[1].axvline(t, color="k", ls="--", lw=1)
        ax[1].set_title("normalised (pore 0, grain 1), threshold %.3g" % t)
        fig.savefig(os.path.join(self.folder, "histogram.png"), dpi=80, bbox_inches="tight")
        self.plt.close(fig)

    def text(self, lines):
        with open(os.path.join(self.folder, "report.txt"), "w") as f:
            f.write("\n".join(lines) + "\n")


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


def region_of_interest(grey, args, say, mask=None):
    """The specimen: the voxels the threshold is chosen over and grains are looked for in
    (--mask or --roi), or None for the whole scan."""
    if mask is not None:
        if mask.shape != grey.shape:
            fail("the mask %s is %s voxels, the scan %s" % (args.mask, mask.shape[::-1],
                                                           grey.shape[::-1]))
        roi, kind = mask != 0, "mask " + args.mask
    elif args.roi[0] == "none":
        return None
    elif args.roi[0] == "cylinder":
        roi, kind = cylinder_region(grey.shape, *args.roi[1:]), "cylinder"
    else:
        outside, value = fill_region(grey)
        say("field of view: " + ("%.3f of the voxels outside it, filled with %g"
                                 % (outside.mean(), value) if outside is not None
                                 else "no constant fill in the slice corners"))
        if outside is not None and value == 0:
            warn(say, "the corners outside the field of view are filled with 0 (%.1f %% of "
                 "the scan): left out of the region; a threshold over the whole scan would be "
                 "pulled down by them" % (100 * outside.mean()))
        roi, kind = specimen_region(grey, outside, SPECK_VOXELS), "auto"
    if not roi.any():
        fail("the region of interest (%s) holds no voxel" % kind)
    say("region of interest (%s): %.3f of the voxels" % (kind, roi.mean()))
    return roi


def axis_radius(shape):
    """Distance [y, x] of each voxel centre from the slices' centre line (the scanner's
    rotation axis in a reconstruction), and the field of view's radius."""
    _, ny, nx = shape
    y, x = np.ogrid[0:ny, 0:nx]
    return np.hypot(x - (nx - 1) / 2, y - (ny - 1) / 2), min(nx, ny) / 2


class Shading:
    """The grey levels of the two phases across the scan: for each phase, pore and grain, a
    least-squares fit of its pure voxels (those PURE_DEPTH voxels or more inside the phase
    in every direction, 26-neighbour erosion: no partial volume, no blur; less deep when the
    pores of small grains leave fewer than MIN_PURE per coefficient) to 1, x, y, z (a linear trend) and rho^2, rho^4 (cupping:
    beam hardening darkens the middle of the field of view; rho the distance from the axis
    over the field of view's radius), both plus one offset per half-voxel ring about the
    axis that the two phases share (ring artifacts: the mean residual of the pure voxels at
    that radius, less its running median over RING_WINDOW rings, which is trend, not ring).
    With trend False only the two mean levels."""

    def __init__(self, grey, roi, solid, step, trend):
        nz, ny, nx = grey.shape
        z, y, x = np.mgrid[0:nz:step, 0:ny:step, 0:nx:step]
        rad, self.rfov = axis_radius(grey.shape)
        keep = subsample(roi, step)
        g = sample(grey, roi, step).astype(np.float64)
        rho = rad[::step, ::step][None].repeat(z.shape[0], 0)[keep].ravel() / self.rfov
        cols = [np.ones(g.size)]
        if trend:
            cols += [c[keep].ravel() / m - 0.5 for c, m in ((x, nx), (y, ny), (z, nz))]
            cols += [rho ** 2, rho ** 4]
        basis = np.stack(cols, axis=1)
        full = np.ones((3, 3, 3), bool)
        phases = (~solid & roi if roi is not None else ~solid, solid)
        for depth in range(PURE_DEPTH, -1, -1):  # narrow pores of small grains: less deep
            pure = [(ndi.binary_erosion(m, full, depth) if depth else m)[::step, ::step, ::step]
                    [keep].ravel() for m in phases]
            if min(m.sum() for m in pure) >= MIN_PURE * basis.shape[1]:
                break
        else:
            fail("one phase has almost no voxels (%d): the scan does not look like grains and "
                 "pores; give --threshold" % min(m.sum() for m in pure))
        self.trend, self.redge = trend, float(rho.max())
        self.bins = np.floor(rho * self.rfov * 2).astype(np.int64)
        self.ring = np.zeros(int(rad.max() * 2) + 2)
        for _ in range(2 if trend else 1):
            gr = g - self.ring[self.bins]
            self.coef = [np.linalg.lstsq(basis[m], gr[m], rcond=None)[0] for m in pure]
            if not trend:
                break
            res = np.concatenate([g[m] - basis[m] @ c for m, c in zip(pure, self.coef)])
            where = np.concatenate([self.bins[m] for m in pure])
            cnt = np.bincount(where, minlength=self.ring.size)
            tot = np.bincount(where, res, minlength=self.ring.size)
            mean = np.where(cnt >= 20, tot / np.maximum(cnt, 1), 0.0)
            self.ring = mean - ndi.median_filter(mean, RING_WINDOW)  # rings, not the trend
        gr = g - self.ring[self.bins]
        self.noise = [float(np.std(gr[m] - basis[m] @ c)) for m, c in zip(pure, self.coef)]

    def levels(self, shape, zs=slice(None)):
        """The pore and grain levels (ring offsets included) over the slices zs."""
        nz, ny, nx = shape
        z = (np.arange(nz)[zs] / nz - 0.5)[:, None, None]
        y = (np.arange(ny) / ny - 0.5)[None, :, None]
        x = (np.arange(nx) / nx - 0.5)[None, None, :]
        rad, _ = axis_radius(shape)
        rho = (rad / self.rfov)[None]
        ring = self.ring[np.floor(rad * 2).astype(np.int64)][None]
        out = []
        for c in self.coef:
            lv = c[0] + ring
            if self.trend:
                lv = lv + c[1] * x + c[2] * y + c[3] * z + c[4] * rho ** 2 + c[5] * rho ** 4
            out.append(lv)
        return out

    def normalise(self, grey):
        """The scan mapped so that the pore phase is 0 and the grain phase 1 everywhere,
        slice by slice (float32)."""
        out = np.empty(grey.shape, np.float32)
        for k in range(grey.shape[0]):
            pore, grain = self.levels(grey.shape, slice(k, k + 1))
            out[k] = (grey[k] - pore[0]) / np.maximum(grain[0] - pore[0], 1e-6)
        return out

    def centre(self):
        """Pore and grain level on the axis, in the middle slice; and at the region's largest
        distance from the axis (cupping)."""
        lv = [c[0] for c in self.coef]
        if not self.trend:
            return lv, lv
        return lv, [c[0] + c[4] * self.redge ** 2 + c[5] * self.redge ** 4 for c in self.coef]


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


def hollow(mine):
    """The largest hollow of a region (bool array with a background voxel on every side):
    the 6-connected voxels inside its convex hull (of the voxels as cubes) but not in it
    that lie at least HOLLOW_DEPTH voxels and HOLLOW_DEPTH_SHARE times its inscribed radius
    inside the hull. Returns its size over the region's."""
    rin = ndi.distance_transform_edt(mine).max()
    centres = np.argwhere(mine & ~ndi.binary_erosion(mine)).astype(np.float64)
    try:  # the hull's corners are those of the voxels at the corners of the centres' hull
        centres = centres[ConvexHull(centres).vertices]
    except QhullError:  # the centres lie in a plane or a line: all of them
        pass
    eq = ConvexHull((centres[:, None, :] + CORNERS8[None]).reshape(-1, 3)).equations
    # the hull row by row along x: eq[:, 2] x <= -(eq[:, 0] z + eq[:, 1] y + eq[:, 3])
    nz, ny, nx = mine.shape
    z, y = (c.ravel().astype(np.float64) for c in np.indices((nz, ny)))
    rhs = 1e-9 - (np.outer(z, eq[:, 0]) + np.outer(y, eq[:, 1]) + eq[:, 3])
    a = eq[:, 2]
    with np.errstate(divide="ignore"):
        hi = np.where(a > 0, rhs / a, np.inf).min(axis=1)
        lo = np.where(a < 0, rhs / a, -np.inf).max(axis=1)
    lo[(rhs[:, a == 0] < 0).any(axis=1)] = np.inf  # a facet parallel to x excludes the row
    x = np.arange(nx)
    hull = ((x >= lo[:, None]) & (x <= hi[:, None])).reshape(mine.shape)
    deep = hull & ~mine & (ndi.distance_transform_edt(hull) >=
                           max(HOLLOW_DEPTH, HOLLOW_DEPTH_SHARE * rin))
    parts, n = ndi.label(deep)
    return (np.bincount(parts.ravel())[1:].max() if n else 0) / np.count_nonzero(mine)


def check_labels(labels, say):
    """Step 9: the labels that are not one convex body, in two lists of label ids: larger
    than the median label (likely two grains joined) and smaller (likely a piece of a split
    grain); both named in a warning."""
    sizes = np.bincount(labels.ravel())
    joined, pieces = [], []
    if sizes.size < 2:
        return joined, pieces
    median = np.median(sizes[1:])
    for l, box in enumerate(ndi.find_objects(labels), start=1):
        if box is None:
            continue
        sl = tuple(slice(max(b.start - 1, 0), b.stop + 1) for b in box)
        if hollow(np.pad(labels[sl] == l, 1)) > HOLLOW_SHARE:
            (joined if sizes[l] >= median else pieces).append(l)
    for ids, what in ((joined, "larger than the median label: likely two grains joined"),
                      (pieces, "smaller than the median label: likely a piece of a grain "
                               "split in two")):
        if ids:
            warn(say, "%d label%s not one convex body (a hollow of the convex hull over %g %% "
                 "of the volume), %s: %s" % (len(ids), "s are" if len(ids) > 1 else " is",
                                             100 * HOLLOW_SHARE, what,
                                             " ".join(map(str, ids))))
    say("check: %d labels look like two grains joined, %d like pieces of a split grain"
        % (len(joined), len(pieces)))
    return joined, pieces


def denoise(grey, args, say):
    """Edge-preserving denoising (--denoise): a median of the 3x3x3 neighbourhood, or a
    Gaussian of --sigma voxels, or none."""
    if args.denoise == "median":
        grey = ndi.median_filter(grey, size=3)
        say("denoised (median, 3x3x3)")
    elif args.denoise == "gaussian" and args.sigma > 0:
        grey = filters.gaussian(grey, sigma=args.sigma, preserve_range=True).astype(np.float32)
        say("denoised (Gaussian, sigma %g voxels)" % args.sigma)
    return grey


def grain_size(solid):
    """The grains' mean size from the solid's volume V and surface S: 6 V / S (a sphere's
    diameter; the Sauter mean of a size distribution), S taken as 2/3 of the count of voxel
    faces between solid and pore (the mean projection of a randomly oriented surface onto
    the voxel faces)."""
    faces = sum(np.count_nonzero(np.diff(solid, axis=a)) for a in range(3))
    return 9.0 * np.count_nonzero(solid) / max(faces, 1)


def threshold(grey, roi, args, say, report):
    """The solid phase (inside the region of interest) and what the threshold stage found."""
    info = {}
    inside = roi if roi is not None else np.ones(grey.shape, bool)
    step = sample_step(grey)
    if args.threshold not in ("midpoint", "otsu"):
        t = float(args.threshold)
        info["threshold"] = t
        say("threshold %.6g (given)" % t)
        return (grey > t) & inside, info
    solid = (grey > otsu(sample(grey, roi, step))) & inside
    for _ in range(2):  # split, fit the phases, split the normalised scan again
        shade = Shading(grey, roi, solid, step, args.detrend)
        norm = shade.normalise(grey)
        t = 0.5 if args.threshold == "midpoint" else otsu(sample(norm, roi, step))
        solid = (norm > t) & inside
    (p0, g0), (p1, g1) = shade.centre()
    grey_t = p0 + t * (g0 - p0)
    info.update(threshold=grey_t, pore=p0, grain=g0, snr=(g0 - p0) / max(shade.noise),
                cupping=(1 - g0 / g1) if shade.trend else 0.0,
                rings=float(np.abs(shade.ring).max()) / (g0 - p0) if shade.trend else 0.0)
    if shade.trend:
        say("grey levels: pore %.6g, grain %.6g on the axis; %.6g and %.6g at %.0f voxels "
            "from it (cupping %.1f %%); rings up to %.1f %% of the contrast removed"
            % (p0, g0, p1, g1, shade.redge * shade.rfov, 100 * info["cupping"],
               100 * info["rings"]))
    else:
        say("grey levels: pore %.6g, grain %.6g" % (p0, g0))
    say("threshold %.6g (%s: %.3g of the way from pore to grain, wherever the phases' "
        "levels are); noise: contrast / %.1f" % (grey_t, args.threshold, t, info["snr"]))
    if report:
        report.histogram(sample(grey, roi, step), sample(norm, roi, step), t, (p0, g0))
        report.slice("normalised", norm)
    info["norm"] = norm
    return solid, info


def segment(grey, args, say, mask=None, report=None):
    """The pipeline of the module docstring; returns labels (uint32, [z, y, x]) and a dict of
    what each stage found."""
    if args.dark_grains:
        grey = grey.max() - grey
    if report:
        report.slice("scan", grey)
    chosen = args.threshold in ("midpoint", "otsu")
    roi = region_of_interest(grey, args, say, mask) if chosen or args.roi[0] != "auto" or \
        mask is not None else None  # a given threshold needs no automatic region
    if report and roi is not None:
        report.slice("region", np.where(roi, grey, np.nan))
    grey = denoise(grey, args, say)
    if report and args.denoise != "none":
        report.slice("denoised", grey)
    solid, info = threshold(grey, roi, args, say, report)
    del grey
    holes = np.count_nonzero(solid)
    solid = morphology.remove_small_holes(solid, 2)  # single enclosed pore voxels: noise
    say("pore voxels enclosed alone in the solid filled: %d" % (np.count_nonzero(solid) - holes))
    info["solid_fraction"] = float(solid[roi].mean() if roi is not None else solid.mean())
    if not 0.2 <= info["solid_fraction"] <= 0.8:
        warn(say, "one phase dominates the region: solid fraction %.3f; the defaults assume a "
             "packing of grains and pores (check --roi or --mask for air counted as pore, "
             "--dark-grains, --threshold)" % info["solid_fraction"])
    if info.get("snr", np.inf) < 4:
        warn(say, "the two phases overlap: contrast / noise %.1f (the defaults assume 5 or "
             "more); --denoise median may help" % info["snr"])
    if report:
        report.slice("solid", solid)
    if not solid.any():
        info.update(markers=0, merged=0, dropped=0, grains=0)
        return np.zeros(solid.shape, np.uint32), info
    size = args.d50 or grain_size(solid)
    h = args.h or min(H_PER_SIZE2 * size ** 2, H_MAX)
    min_voxels = args.min_voxels or max(8, round(MIN_VOLUME_SHARE * np.pi / 6 * size ** 3))
    info.update(size=size, h=h, min_voxels=min_voxels)
    say("solid fraction %.3f in the region; grain size %.3g voxels (%s)"
        % (info["solid_fraction"], size, "given" if args.d50 else "6 V / S of the solid"))
    dist = ndi.distance_transform_edt(solid)
    say("distance transform: largest inscribed radius %.1f voxels" % dist.max())
    norm = info.pop("norm", None)
    if norm is not None and args.grey_weight > 0:
        dist += args.grey_weight * (np.clip(ndi.gaussian_filter(norm, WEIGHT_SIGMA), 0, 1) - 1)
        np.maximum(dist, 0, out=dist)
        say("distance lowered by %g voxels times 1 - the normalised grey level"
            % args.grey_weight)
    del norm
    if report:
        report.slice("distance", dist)
    markers, nmark = ndi.label(morphology.h_maxima(dist, h))
    say("markers (h-maxima, h = %.3g voxels): %d" % (h, nmark))
    if report:
        report.slice("markers", np.where(dist > 0, markers, 0))
    labels = segmentation.watershed(-dist, markers, mask=solid)
    say("watershed: %d regions" % labels.max())
    labels, joins = merge_oversplit(labels, dist, args.merge_ratio)
    info["joined"] = joins
    say("regions joined across saddles above %g of their peak distance: %d"
        % (args.merge_ratio, joins))
    labels, merged, dropped = merge_fragments(labels, min_voxels)
    info.update(markers=nmark, merged=merged, dropped=dropped, grains=int(labels.max()))
    say("fragments below %d voxels: %d merged into a neighbour, %d dropped; %d grains"
        % (min_voxels, merged, dropped, labels.max()))
    info["joined_grains"], info["pieces"] = check_labels(labels, say)
    if report:
        report.slice("labels", labels)
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
    p.add_argument("--threshold", default="midpoint",
                   help="'midpoint' (default: half way between the two phases' fitted grey "
                        "levels), 'otsu' (Otsu's of the normalised scan) or a grey level")
    p.add_argument("--mask", help="the specimen: a TIFF of the scan's size, nonzero inside "
                                  "(instead of --roi)")
    p.add_argument("--roi", nargs="+", default=["auto"], metavar="KIND",
                   help="where the threshold is chosen and grains are looked for: auto "
                        "(default: the specimen, without "
                        "a zero-filled field of view or the air around it), none (the whole "
                        "scan) or cylinder CX CY R (voxels)")
    p.add_argument("--no-detrend", dest="detrend", action="store_false",
                   help="keep the scan's grey-level trend, cupping and rings")
    p.add_argument("--denoise", choices=("median", "gaussian", "none"), default=DENOISE,
                   help="edge-preserving median (3x3x3), Gaussian of --sigma, or none (%s)"
                        % DENOISE)
    p.add_argument("--dark-grains", action="store_true", help="grains are darker than pores")
    p.add_argument("--sigma", type=float, default=1.0,
                   help="--denoise gaussian's sigma, voxels (1)")
    p.add_argument("--d50", type=float,
                   help="grain size, voxels (default: 6 V / S of the solid phase)")
    p.add_argument("--h", type=float,
                   help="h-maxima height, voxels (default %g x the grain size squared, at "
                        "most %g)" % (H_PER_SIZE2, H_MAX))
    p.add_argument("--grey-weight", type=float, default=GREY_WEIGHT,
                   help="lower the distance map by this many voxels times 1 - the normalised "
                        "grey level, so that the darker voxels of a gap the threshold closed "
                        "part the grains (%g; 0: the plain distance)" % GREY_WEIGHT)
    p.add_argument("--merge-ratio", type=float, default=0.9,
                   help="join regions whose saddle reaches this share of their peak distance "
                        "(0.9; 1 joins none)")
    p.add_argument("--min-voxels", type=int,
                   help="smallest grain, voxels (default %g of a sphere of the grain size, at "
                        "least 8)" % MIN_VOLUME_SHARE)
    p.add_argument("--labels", help="keep the labels: raw uint32 or .tif")
    p.add_argument("--report", metavar="DIR",
                   help="write report.txt, the histogram and a slice after each stage (PNG)")
    p.add_argument("--quiet", action="store_true", help="no progress lines")
    for opt in ("--nodes", "--node-spacing", "--smooth", "--margin", "--seed"):
        p.add_argument(opt, help="passed to lsdem-shape from-labels")
    a = p.parse_args(argv)
    if a.voxel <= 0 or (a.density is not None and a.density <= 0):
        p.error("--voxel and --density must be positive")
    if a.data and a.density is None:
        p.error("--data needs --density RHO")
    if a.threshold not in ("midpoint", "otsu"):
        try:
            float(a.threshold)
        except ValueError:
            p.error("--threshold takes 'midpoint', 'otsu' or a number, not '%s'" % a.threshold)
    a.roi = parse_roi(p, a.roi)
    if a.sigma < 0 or (a.h is not None and a.h <= 0) or (a.min_voxels is not None and
                                                         a.min_voxels < 1):
        p.error("--sigma >= 0, --h > 0 and --min-voxels >= 1")
    if a.d50 is not None and a.d50 <= 0:
        p.error("--d50 must be positive")
    if a.grey_weight < 0:
        p.error("--grey-weight must be >= 0")
    return a


def main(argv=None):
    args = parse(sys.argv[1:] if argv is None else argv)
    say = Progress(args.quiet)
    with tempfile.TemporaryDirectory(prefix="lsdem-segment.") as tmp:
        grey, kind = read_scan(args.scan, tmp)
        nz, ny, nx = grey.shape
        say("%s: %d x %d x %d voxels, %s" % (args.scan, nx, ny, nz, kind))
        mask = read_scan(args.mask, tmp)[0] if args.mask else None
        report = Report(args.report) if args.report else None
        labels, info = segment(grey, args, say, mask, report)
        del grey, mask
        if report:
            report.text(say.lines)
            say("report written to %s" % args.report)
        if info["grains"] == 0:
            fail("%s: no grain found (threshold %.6g, solid fraction %.3f): check --threshold "
                 "and --dark-grains" % (args.scan, info["threshold"], info["solid_fraction"]))
        if args.labels:
            write_labels(args.labels, labels)
            say("labels written to %s" % args.labels)
        raw = os.path.join(tmp, "labels.raw")
        labels.astype("<u4").tofile(raw)
        cmd = [shape_tool(), "from-labels", raw, args.library, "--raw", str(nx), str(ny), str(nz),
               "u32", "--voxel", repr(args.voxel), "--min-voxels", str(info["min_voxels"])]
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
