#!/usr/bin/env python3
"""Summarise an LSDEM benchmark log: time split, workload per grain-step, headline figures.

The deck's thermo output has `c_work[1..4]` from `compute pair lsdem` (per-step counters of
pair_style lsdem): pairs within bounding spheres, contacting pairs, node lookups (nodes that
reached the trilinear level-set lookup) and penetrating nodes. Their mean over the thermo rows
is divided by the grain count."""
import argparse
import re
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("log")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--mode", default="oneway")
    ap.add_argument("--membw", default="", help="bench/membw.c's output line")
    a = ap.parse_args()
    text = open(a.log).read()
    loops = re.findall(r"Loop time of ([\d.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms", text)
    if not loops:
        sys.exit("no 'Loop time' line in %s: the run did not finish" % a.log)
    loop, procs, steps, atoms = float(loops[-1][0]), int(loops[-1][1]), int(loops[-1][2]), int(loops[-1][3])
    # the last run's timing table
    tail = text[text.rfind("Loop time of"):]
    print("LSDEM benchmark: %d grains, %d steps, %d rank(s), mode %s" % (atoms, steps, procs, a.mode))
    print("time split (avg seconds over ranks, % of total):")
    for name in ("Pair", "Neigh", "Comm", "Modify", "Output", "Other"):
        m = re.search(r"^%s\s+\|\s*([\d.eE+-]+)\s*\|\s*([\d.eE+-]+)\s*\|\s*([\d.eE+-]+)\s*\|\s*([\d.]+|)\s*\|\s*([\d.]+)" % name, tail, re.M)
        if m:
            print("  %-7s %10.3f s  %6.2f %%" % (name, float(m.group(2)), float(m.group(5))))
    # workload from the thermo rows of the last run
    rows = []
    header = None
    for line in tail_before(text).splitlines():
        parts = line.split()
        if parts[:1] == ["Step"]:
            header, rows = parts, []
        elif header and len(parts) == len(header):
            try:
                rows.append(dict(zip(header, map(float, parts))))
            except ValueError:
                header = None
    per = {}
    labels = ["pairs within bounding spheres", "contacting pairs", "node lookups", "penetrating nodes"]
    for k, label in enumerate(labels, start=1):
        key = "c_work[%d]" % k
        vals = [r[key] for r in rows if key in r]
        if vals:
            per[label] = sum(vals) / len(vals) / atoms
    if per:
        print("workload per grain-step (mean of thermo rows):")
        for label in labels:
            if label in per:
                print("  %-30s %8.2f" % (label, per[label]))
    stretches = by_stretch(rows, atoms)
    if stretches:
        print("wall time per grain-step by stretch (thermo 'cpu' column):")
        for label, us in stretches:
            print("  %-30s %8.3f us" % (label, us))
    print("wall time per grain-step: %.3f us (loop %.2f s; core-us per grain-step %.3f)"
          % (loop / (atoms * steps) * 1e6, loop, loop * procs / (atoms * steps) * 1e6))
    lookups = per.get("node lookups", float("nan")) * atoms * steps
    memory_line(lookups / loop, a.membw)
    print("us_per_grain_step=%.3f node_tests_per_s=%.4g" % (loop / (atoms * steps) * 1e6, lookups / loop))


# Cache lines a lookup reads from a grid (levelset.c, dense floats x fastest): its cell's 8
# samples are 2 neighbours on each of 4 rows (2 rows in each of 2 planes), a line per row
# (a pair straddles two lines in 1 cell of 16, which this leaves out).
LINES_PER_LOOKUP = 4


def memory_line(rate, membw):
    """Node lookups per second against the memory system: the bytes a lookup moves at most,
    estimated as LINES_PER_LOOKUP x 64 bytes, the traffic that rate makes, and this core's
    measured speed (bench/membw.c's output line `read_GBps=.. copy_GBps=.. latency_ns=..`)."""
    need = rate * LINES_PER_LOOKUP * 64
    print("memory: %.4g node lookups/s x %d cache lines x 64 B = %d B per lookup at most "
          "(lookups served by a node list's kept cell move none): %.3f GB/s"
          % (rate, LINES_PER_LOOKUP, LINES_PER_LOOKUP * 64, need * 1e-9))
    f = dict(kv.split("=") for kv in membw.split())
    if f:
        print("memory: this core streams %s GB/s read, %s GB/s copy (read + write); one "
              "dependent miss %s ns (bench/membw.c): the lookups use %.1f %% of the read "
              "bandwidth" % (f["read_GBps"], f["copy_GBps"], f["latency_ns"],
                             100 * need * 1e-9 / float(f["read_GBps"])))


def by_stretch(rows, atoms, settle=300):
    """Wall time per grain-step before and after step `settle` (the reference pack rattles
    at first: its lists are rebuilt at most steps), from the thermo rows' elapsed time."""
    rows = [r for r in rows if "CPU" in r and "Step" in r]
    if len(rows) < 3:
        return []
    first, last = rows[0], rows[-1]
    mid = next((r for r in rows if r["Step"] >= first["Step"] + settle), None)
    if mid is None or mid is last:
        return []
    def us(a, b):
        return (b["CPU"] - a["CPU"]) / (atoms * (b["Step"] - a["Step"])) * 1e6
    return [("steps %d-%d" % (first["Step"], mid["Step"]), us(first, mid)),
            ("steps %d-%d" % (mid["Step"], last["Step"]), us(mid, last))]


def tail_before(text):
    """The log text up to the last 'Loop time' line (the last run's thermo rows)."""
    i = text.rfind("Loop time of")
    return text[:i]


if __name__ == "__main__":
    main()
