#!/usr/bin/env python3
"""The example hopper (examples/hopper: 1,500 grains, 60-degree cone, bin R = 7 d, wall top
16 d) with angular grains instead of analytic spheres, at one or more orifice diameters D.

Usage: angular.py [OUTDIR] [--orifices 6 8] [--grains 1500] [--nsettle 15000]
                  [--ndischarge 50000] [--np 2] [--nodes 100] [--seed 5] [--twoway]
                  [--report-only]
  (OUTDIR default angular_out; a D whose hopper.csv exists is not run again; --report-only
  analyses what is there.) Prints per D: rho_b, fill height, W with its error and window,
  C at k = 1.4, the discharged and remaining grains, whether the flow clogged (no grain out
  over the last 5 time units with more than 5 left above the orifice; the deck's halt stops
  an emptied hopper), and the loop time per particle-step of the settling and discharge
  (particle-steps from the thermo's atom count); with 2 orifices, Beverloo's C and k through
  the 2 points (exact: no error).

Per D it writes OUTDIR/D<value>/: make_hopper.py (radius 7 at every D, as run.sh) + `lsdem-shape wall` (spacing 0.25,
half-width 1.0, as run.sh), then examples/hopper/in.hopper with -var lib/data/band and
nvtk 0, then plot.py's analysis (bulk density, steady rate W over 10-60 % of the bed, from
t = 3 on) to result.txt. The grains (shared by every D): `lsdem-shape random` (6 shapes,
volume-equivalent diameter 1, elongation 0.75, flatness 0.75, angularity 0.15, roughness
0.02, 100 nodes, grid spacing 0.05, seed 3). They are not on fill_hopper.py's lattice:
their bounding radius is up to 0.82 d, so a lattice that keeps randomly turned grains apart
(pitch >= 1.7) is 60 d tall in this bin. Instead `lsdem-shape pack` places them without
overlap (random shape 1..6, random orientation) in a cylinder of radius 5.9 (clear of the
bin wall's inner radius 7 by the bounding radius) and height 28, which is then lifted to
start 1 d above the cone's top (z = 3.3); grains above the wall's top (16) fall into the bin.
The contact law, time step and stages are in.hopper's defaults (kn = 1000 per contact node).
"""
import argparse
import math
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
EX = os.path.join(ROOT, "examples", "hopper")
SHAPE = os.path.join(ROOT, "build", "lsdem-shape")
LMP = os.path.join(ROOT, "build", "lmp")
sys.path.insert(0, EX)
import plot  # noqa: E402


def sh(cmd, cwd, log=None):
    with open(os.path.join(cwd, log), "w") if log else open(os.devnull, "w") as f:
        subprocess.run(cmd, cwd=cwd, check=True, stdout=f, stderr=subprocess.STDOUT)


def grains(out, n, nodes, seed=5):
    lib = os.path.join(out, "ang.lslib")
    if not os.path.exists(lib):
        sh([SHAPE, "random", "ang.lslib", "--count", "6", "--size", "1.0", "--elongation",
            "0.75", "--flatness", "0.75", "--angularity", "0.15", "--roughness", "0.02",
            "--nodes", str(nodes), "--spacing", "0.05", "--seed", "3", "--name", "ang"],
           out, "shapes.txt")
    data = os.path.join(out, "ang_%d.data" % n)
    if not os.path.exists(data):
        sh([SHAPE, "pack", "ang.lslib", "packed.data", "--count", str(n), "--cylinder", "5.9",
            "28", "--density", "1", "--weights", "1,1,1,1,1,1", "--seed", str(seed),
            "--max-tries", "5000", "--strict"], out, "pack.txt")
        lift = 3.3
        lines = open(os.path.join(out, "packed.data")).read().split("\n")
        res, sec = [], None
        for l in lines:
            p = l.split()
            if l.strip().startswith("Atoms"):
                sec = "atoms"
            elif l.strip().startswith("Velocities"):
                sec = "vel"
            if l.endswith("xlo xhi"):
                l = "-9.0 9.0 xlo xhi"
            elif l.endswith("ylo yhi"):
                l = "-9.0 9.0 ylo yhi"
            elif l.endswith("zlo zhi"):
                l = "-10.0 %r zlo zhi" % (28 + lift + 2.0)
            elif sec == "atoms" and len(p) == 11:
                p[6] = repr(float(p[6]) + lift)
                l = " ".join(p)
            res.append(l)
        open(data, "w").write("\n".join(res))
    return lib, data


def run_one(out, D, lib, data, a):
    d = os.path.join(out, "D%g" % D)
    os.makedirs(d, exist_ok=True)
    geo = ["--orifice", str(D), "--half-angle", "60", "--radius", "7",
           "--height", "16"]
    if not os.path.exists(os.path.join(d, "hopper.band")):
        with open(os.path.join(d, "hopper.txt"), "w") as f:
            subprocess.run([sys.executable, os.path.join(EX, "make_hopper.py"), "hopper.stl"]
                           + geo, cwd=d, check=True, stdout=f)
        sh([SHAPE, "wall", "hopper.stl", "hopper.band", "--spacing", "0.25", "--width", "1.0"],
           d, "band.txt")
    deck = os.path.join(EX, "in.hopper")
    if a.twoway:  # the example's deck with pair_style lsdem mode twoway (a copy in OUTDIR)
        txt = open(deck).read()
        assert "\npair_style      lsdem\n" in txt
        deck = os.path.join(out, "in.hopper.twoway")
        open(deck, "w").write(txt.replace("\npair_style      lsdem\n",
                                          "\npair_style      lsdem mode twoway\n"))
    cmd = [LMP, "-in", deck, "-var", "lib", lib, "-var", "data", data,
           "-var", "band", "hopper.band", "-var", "nsettle", str(a.nsettle), "-var",
           "ndischarge", str(a.ndischarge), "-var", "nvtk", "0", "-var", "prefix", "hopper",
           "-log", "log.lammps", "-screen", "none"]
    if a.np > 1:
        cmd = ["mpirun", "--allow-run-as-root", "-np", str(a.np)] + cmd
    t0 = time.time()
    subprocess.run(cmd, cwd=d, check=True)
    wall = time.time() - t0
    open(os.path.join(d, "wall.txt"), "w").write("%.1f\n" % wall)
    return d


def cpu_per_pstep(d):
    """Loop time / sum over steps of the atoms (thermo's atoms column), settling and discharge."""
    log = os.path.join(d, "log.lammps")
    runs, cur, head = [], [], None
    for l in open(log):
        p = l.split()
        if p and p[0] == "Step":
            head, cur = p, []
            continue
        if head and l.startswith("Loop time of"):
            runs.append((float(p[3]), int(p[8]), cur))
            head = None
            continue
        if head and len(p) == len(head):
            try:
                cur.append((int(p[0]), int(p[head.index("Atoms")])))
            except (ValueError, IndexError):
                pass
    res = []
    for sec, steps, rows in runs:
        # trapezoid of the atom count over the steps
        ps = sum((rows[i + 1][0] - rows[i][0]) * 0.5 * (rows[i][1] + rows[i + 1][1])
                 for i in range(len(rows) - 1)) if len(rows) > 1 else steps * rows[0][1]
        res.append((sec, steps, ps))
    return res


def report(out, Ds):
    rows = []
    for D in Ds:
        d = os.path.join(out, "D%g" % D)
        if not os.path.exists(os.path.join(d, "hopper.csv")):
            continue
        geo = plot.read_kv(os.path.join(d, "hopper.txt"))
        r = plot.analyse(os.path.join(d, "hopper.csv"), os.path.join(d, "hopper_settled.dump"),
                         geo, (0.1, 0.6), 1.0, 3.0)
        csv = r["rows"]
        last = csv[-1]
        # clogging: no grain leaves over the last 5 time units while grains remain above
        tail = [x for x in csv if x["time"] >= last["time"] - 5.0]
        clog = (last["grains_above_orifice"] > 5 and last["time"] >= 10.0 and
                tail[-1]["discharged_grains"] - tail[0]["discharged_grains"] == 0)
        cpu = cpu_per_pstep(d)
        try:
            plot.draw(r, geo, os.path.join(d, "hopper.png"),
                      "angular grains, hopper D = %g d: %d grains, rho_b = %.3f"
                      % (D, r["grains"], r["bulk_density"]))
        except Exception as e:  # noqa: BLE001
            print("no plot: %s" % e)
        res = dict(D=D, grains=r["grains"], rho_b=r["bulk_density"], fill=r["fill_height"],
                   W=r.get("rate"), W_err=r.get("rate_err"), t0=r.get("t0"), t1=r.get("t1"),
                   C14=r.get("C_fixed_k"), t_end=last["time"],
                   out=int(last["discharged_grains"]), left=int(last["grains_above_orifice"]),
                   clogged=clog, cpu=cpu)
        with open(os.path.join(d, "result.txt"), "w") as f:
            for k, v in res.items():
                f.write("%s %s\n" % (k, v))
        rows.append(res)
    for r in rows:
        print("D %g: grains %d rho_b %.3f fill %.1f W %s +- %s (t %s-%s) C(k=1.4) %s; "
              "t_end %.1f discharged %d left %d clogged %s" % (
                  r["D"], r["grains"], r["rho_b"], r["fill"],
                  "%.2f" % r["W"] if r["W"] else "-", "%.2f" % r["W_err"] if r["W_err"] else "-",
                  "%.1f" % r["t0"] if r["t0"] else "-", "%.1f" % r["t1"] if r["t1"] else "-",
                  "%.3f" % r["C14"] if r["C14"] else "-", r["t_end"], r["out"], r["left"],
                  r["clogged"]))
        for sec, steps, ps in r["cpu"]:
            print("   run: %d steps %.1f s, %.3g particle-steps, %.3g us/particle-step"
                  % (steps, sec, ps, 1e6 * sec / ps if ps else float("nan")))
    ok = [r for r in rows if r["W"]]
    if len(ok) == 2:
        (D1, W1, r1), (D2, W2, r2) = [(r["D"], r["W"], r["rho_b"]) for r in ok]
        y1, y2 = (W1 / r1) ** 0.4, (W2 / r2) ** 0.4
        s = (y2 - y1) / (D2 - D1)
        k = D1 - y1 / s
        print("Beverloo through the 2 points (exact, no error): C = %.3f, k = %.2f"
              % (s ** 2.5, k))
    return rows


def main(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("out", nargs="?", default="angular_out")
    ap.add_argument("--orifices", type=float, nargs="+", default=[6.0, 8.0])
    ap.add_argument("--grains", type=int, default=1500)
    ap.add_argument("--nodes", type=int, default=100)
    ap.add_argument("--nsettle", type=int, default=15000)
    ap.add_argument("--ndischarge", type=int, default=50000)
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--seed", type=int, default=5, help="the packing's seed (lsdem-shape pack)")
    ap.add_argument("--twoway", action="store_true",
                    help="pair_style lsdem mode twoway (both grains test their nodes)")
    ap.add_argument("--report-only", action="store_true")
    a = ap.parse_args(argv)
    out = os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    if not a.report_only:
        lib, data = grains(out, a.grains, a.nodes, a.seed)
        for D in a.orifices:
            d = os.path.join(out, "D%g" % D)
            if os.path.exists(os.path.join(d, "hopper.csv")):
                continue
            run_one(out, D, lib, data, a)
    report(out, a.orifices)


if __name__ == "__main__":
    main(sys.argv[1:])
