#!/usr/bin/env python3
"""The table of bench/avalanche/impulse.sh: per run (OUT/sSEED/nN_METHOD) the steps, the user
time, the time at rest, the front, the front of the bulk and the centroid, H/L, the deposit's
area and thickness, the nets' retained fraction and peak anchor force, and the warnings; then
per variant the mean over the seeds with its spread (min..max), and the CPU-time speed-up
against the penalty run of the same seed and nets.
    table.py OUT"""
import glob
import os
import re
import sys

out = sys.argv[1]
FLOAT = r"(-?[0-9.]+(?:e[-+]?[0-9]+)?)"


def grab(pattern, text, n=1, cast=float):
    m = re.search(pattern, text)
    if not m:
        return None
    return cast(m.group(n))


def read_run(d):
    log = open(os.path.join(d, "log.lammps")).read()
    took = open(os.path.join(d, "time.txt")).read()
    plot = open(os.path.join(d, "plot.txt")).read() if os.path.exists(os.path.join(d, "plot.txt")) else ""
    r = {"failed": "ERROR" in log or "lmp failed" in took}
    r["user"] = grab(r"user " + FLOAT, took)
    r["steps"] = grab(r"Loop time of \S+ on \d+ procs for (\d+) steps", log, cast=int)
    r["t"] = grab(r"end: t = " + FLOAT, log)
    r["front"] = grab(r"end: .*?front x " + FLOAT, log)
    r["centroid"] = grab(r"end: .*?centroid x " + FLOAT, log)
    r["hl"] = grab(r"end: .*?H/L " + FLOAT, log)
    r["hl_c"] = grab(r"end: .*?\(centroid " + FLOAT, log)
    r["bulk"] = grab(r"of the bulk, 2 % beyond: " + FLOAT, plot)
    r["hl_b"] = grab(r"H/L = \S+ \(front\), " + FLOAT, plot)
    r["area"] = grab(r"area " + FLOAT, plot)
    r["thick_max"] = grab(r"thickness max " + FLOAT, plot)
    r["thick_mean"] = grab(r"thickness max \S+ mean " + FLOAT, plot)
    for k in (1, 2):
        r["ret%d" % k] = grab(r"net %d: retained fraction " % k + FLOAT, log)
        r["through%d" % k] = grab(r"net %d: retained fraction \S+ grains through (\d+)" % k, log, cast=int)
        r["peak%d" % k] = grab(r"net %d: .*?peak anchor force " % k + FLOAT, log)
    # the warnings but the two every nets run prints (hybrid masses, the comm cutoff)
    warns = sorted(set(l.strip()[:90] for l in log.splitlines() if l.startswith("WARNING") and
                       "per-type and per-atom masses" not in l and "cutoff adjusted" not in l))
    r["warnings"] = warns
    return r


runs = {}
for d in sorted(glob.glob(os.path.join(out, "s*", "n*_*"))):
    seed = os.path.basename(os.path.dirname(d))[1:]
    nets, method = os.path.basename(d).split("_", 1)
    if not os.path.exists(os.path.join(d, "log.lammps")):
        continue
    runs[(nets, method, seed)] = read_run(d)

cols = [("steps", "%d"), ("user", "%.1f"), ("t", "%.2f"), ("front", "%.2f"), ("bulk", "%.2f"),
        ("centroid", "%.2f"), ("hl", "%.3f"), ("hl_b", "%.3f"), ("hl_c", "%.3f"),
        ("area", "%.1f"), ("thick_max", "%.2f"), ("thick_mean", "%.2f"),
        ("ret1", "%.3f"), ("through1", "%d"), ("peak1", "%.0f"), ("ret2", "%.3f"), ("peak2", "%.0f")]


def fmt(f, v):
    return "-" if v is None else f % v


print("| nets | method | seed | speed-up | " + " | ".join(c for c, _ in cols) + " | warnings |")
print("|" + "---|" * (len(cols) + 5))
def order(nets, method):
    """the nets, then penalty before the impulse runs by their multiple"""
    return (nets, 0 if method == "penalty" else int(method[1:]))


for (nets, method, seed), r in sorted(runs.items(), key=lambda kv: order(kv[0][0], kv[0][1]) + (kv[0][2],)):
    pen = runs.get((nets, "penalty", seed))
    sp = pen["user"] / r["user"] if pen and pen["user"] and r["user"] and not r["failed"] else None
    print("| %s | %s | %s | %s | " % (nets[1:], method, seed, fmt("%.1f", sp)) +
          " | ".join(fmt(f, r[c]) for c, f in cols) + " | %s%s |" % ("FAILED; " if r["failed"] else "",
                                                                  "; ".join(r["warnings"]) or "-"))

print()
print("mean over the seeds [min..max]")
print("| nets | method | seeds | failed | speed-up | " + " | ".join(c for c, _ in cols) + " |")
print("|" + "---|" * (len(cols) + 5))
for nets, method in sorted(set((k[0], k[1]) for k in runs), key=lambda k: order(*k)):
    mine = [(s, runs[(n, m, s)]) for (n, m, s) in runs if n == nets and m == method]
    rs = [(s, r) for s, r in mine if not r["failed"]]
    cells = []
    sps = [runs[(nets, "penalty", s)]["user"] / r["user"] for s, r in rs
           if (nets, "penalty", s) in runs and r["user"]]
    for c, f in [("speed-up", "%.1f")] + cols:
        vals = sps if c == "speed-up" else [r[c] for _, r in rs if r[c] is not None]
        if not vals:
            cells.append("-")
        elif len(vals) == 1:
            cells.append(fmt(f, vals[0]))
        else:
            mean = sum(vals) / len(vals)
            cells.append("%s [%s..%s]" % (fmt("%.0f" if f == "%d" else f, mean), fmt(f, min(vals)),
                                          fmt(f, max(vals))))
    print("| %s | %s | %d | %d | " % (nets[1:], method, len(rs), len(mine) - len(rs)) +
          " | ".join(cells) + " |")
