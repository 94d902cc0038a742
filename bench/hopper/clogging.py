#!/usr/bin/env python3
"""Clogging statistics of angular grains in the example hopper (issue 32's goal): for each
small orifice D, RUNS independent packings (lsdem-shape pack seeds 1..RUNS) of the grains of
angular.py discharge through the hopper; a run clogged when no grain left over its last 5
time units with grains still above the orifice (angular.py's rule). Prints per D the runs,
the fraction clogged (with its binomial standard error) and the grains discharged before
the arch formed (mean, spread, the sizes), and writes OUTDIR/clogging.txt.

Usage: clogging.py [OUTDIR] [--orifices 3 4] [--runs 6] [--grains 600] [--nsettle 10000]
                   [--ndischarge 30000] [--jobs 2]
Each run is `angular.py OUTDIR/seed<S> --orifices D --seed S --np 1` (the shapes are the same
for every run; a run whose result exists is not run again); JOBS runs at a time."""
import argparse
import concurrent.futures
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def one(out, D, seed, a):
    d = os.path.join(out, "seed%d" % seed)
    res = os.path.join(d, "D%g" % D, "result.txt")
    if not os.path.exists(res):
        with open(os.path.join(out, "seed%d_D%g.log" % (seed, D)), "w") as f:
            subprocess.run([sys.executable, os.path.join(HERE, "angular.py"), d, "--orifices",
                            str(D), "--seed", str(seed), "--np", "1", "--grains", str(a.grains),
                            "--nsettle", str(a.nsettle), "--ndischarge", str(a.ndischarge)],
                           check=True, stdout=f, stderr=subprocess.STDOUT)
    kv = dict(l.split(" ", 1) for l in open(res).read().splitlines() if " " in l)
    return D, seed, kv["clogged"].strip() == "True", int(kv["out"]), int(kv["left"])


def main(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("out", nargs="?", default="clogging_out")
    ap.add_argument("--orifices", type=float, nargs="+", default=[3.0, 4.0])
    ap.add_argument("--runs", type=int, default=6)
    ap.add_argument("--grains", type=int, default=600)
    ap.add_argument("--nsettle", type=int, default=10000)
    ap.add_argument("--ndischarge", type=int, default=30000)
    ap.add_argument("--jobs", type=int, default=2)
    a = ap.parse_args(argv)
    out = os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    jobs = [(D, s) for D in a.orifices for s in range(1, a.runs + 1)]
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as ex:
        results = list(ex.map(lambda j: one(out, j[0], j[1], a), jobs))
    lines = ["angular grains (angular.py's 6 shapes), %d per run, hopper 60 deg, bin R = 7 d; "
             "%d packings per orifice" % (a.grains, a.runs)]
    for D in a.orifices:
        rs = [r for r in results if r[0] == D]
        clog = [r for r in rs if r[2]]
        p = len(clog) / len(rs)
        sizes = [r[3] for r in clog]
        mean = sum(sizes) / len(sizes) if sizes else float("nan")
        sd = math.sqrt(sum((x - mean) ** 2 for x in sizes) / (len(sizes) - 1)) if len(sizes) > 1 else float("nan")
        lines.append("D = %g d: %d of %d runs clogged (p = %.2f +- %.2f); grains out before "
                     "the arch: mean %.0f, sd %.0f, %s; unclogged runs discharged %s"
                     % (D, len(clog), len(rs), p, math.sqrt(p * (1 - p) / len(rs)), mean, sd,
                        sorted(sizes), sorted(r[3] for r in rs if not r[2])))
    text = "\n".join(lines)
    print(text)
    open(os.path.join(out, "clogging.txt"), "w").write(text + "\n")


if __name__ == "__main__":
    main(sys.argv[1:])
