#!/usr/bin/env python3
"""Beverloo's law from LSDEM hopper discharges (issue 32 item 5; bench/README.md, "Hopper
discharge (Beverloo)"). For each orifice diameter D (in grain diameters d = 1): a hopper
mesh (examples/hopper/make_hopper.py), its band (lsdem-shape wall), spheres on a lattice
(fill_hopper.py), and examples/hopper/in.hopper: settle on the plug, remove it, discharge.
The steady rate W is the slope of the discharged mass from t = TMIN on until FMAX of the
bed has left (examples/hopper/plot.py); rho_b is measured in the settled bed. The fit is the
straight line of Beverloo's law,

    (W / (rho_b sqrt(g)))^(2/5) = C^(2/5) (D - k d),

weighted by the rates' errors: C = slope^(5/2), k = -intercept / slope, their errors from
the fit's covariance (scaled by sqrt(chi^2/dof) when that exceeds 1).

Usage: beverloo.py [OUTDIR] [--diameters 5,6,7,8.5,10] [--radius 12.5] [--half-angle 90]
                   [--fill 20] [--tmax 25] [--tmin 3] [--fmax 0.4] [--np 1] [--redo]
                   [--report-only]
  OUTDIR      default bench-hopper; one folder per D (D<value>/) with the run's inputs, log,
              CSV and result.txt (the checkpoint: a D whose result.txt exists is not run
              again unless --redo), then beverloo.csv, beverloo.png and summary.txt
  --radius    inner radius of the bin (the same for every D), default 12.5 (2.5 D at D = 10)
  --half-angle  cone half-angle from the vertical, default 90: a flat-bottomed silo (the
              geometry Beverloo's C = 0.58, k = 1.4 are for); 60 for the example's cone
  --fill      bed height above the orifice aimed at (the grain count is chosen for it at a
              solid fraction of 0.57), default 20 (2 D at D = 10)
  --tmax      discharge time at most (sqrt(d/g) units), default 25; a run also stops when
              FMAX + 0.05 of the grains have left
  --np        MPI ranks per lmp run (default 1)
  --report-only  fit and plot the runs that have a result.txt, run nothing
Environment: LSDEM_BUILD_DIR (default ../../build: lmp and lsdem-shape)."""
import argparse
import math
import os
import resource
import subprocess
import sys
import time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.normpath(os.path.join(HERE, "..", "..", "examples", "hopper"))
sys.path.insert(0, EXAMPLE)
import plot as hp  # noqa: E402  (examples/hopper/plot.py)

BUILD = os.environ.get("LSDEM_BUILD_DIR", os.path.join(HERE, "..", "..", "build"))
LMP = os.path.join(BUILD, "lmp")
TOOL = os.path.join(BUILD, "lsdem-shape")
PY = "/usr/bin/python3"
DT = 1.0e-3
GRAIN_MASS = math.pi / 6.0   # d = 1, density 1
PHI_GUESS = 0.57             # solid fraction assumed when choosing the grain count
C_REF, K_REF = 0.58, 1.4


def sh(cmd, cwd, log=None):
    """Run cmd in cwd; its output to log (or captured); stop with its tail on failure."""
    out = open(os.path.join(cwd, log), "w") if log else subprocess.PIPE
    p = subprocess.run([str(c) for c in cmd], cwd=cwd, stdout=out, stderr=subprocess.STDOUT,
                       universal_newlines=True)
    if p.returncode != 0:
        text = open(os.path.join(cwd, log)).read() if log else p.stdout
        sys.exit("beverloo.py: %s failed (exit %d) in %s:\n%s"
                 % (os.path.basename(str(cmd[0])), p.returncode, cwd, text[-2500:]))
    return p.stdout if not log else None


def kv(text):
    out = {}
    for line in text.splitlines():
        p = line.split()
        if len(p) == 2:
            try:
                out[p[0]] = float(p[1])
            except ValueError:
                out[p[0]] = p[1]
    return out


def grain_count(D, R, A, fill):
    """Grains for a bed of height `fill` above the orifice at solid fraction PHI_GUESS."""
    zc = 0.0 if A >= 90.0 else (R - D / 2.0) / math.tan(math.radians(A))
    vol = hp.frustum(D, R, zc, min(fill, zc)) + math.pi * R * R * max(0.0, fill - zc)
    return int(round(PHI_GUESS * vol / GRAIN_MASS))


def one_run(D, a, out):
    """Run (or reuse) the discharge at orifice D; its result as a dict."""
    wd = os.path.join(out, "D%g" % D)
    res_path = os.path.join(wd, "result.txt")
    if os.path.exists(res_path) and not a.redo:
        res = kv(open(res_path).read())
        print("D = %g: reusing %s" % (D, res_path))
        return res
    if a.report_only:
        return None
    os.makedirs(wd, exist_ok=True)
    R, A = a.radius, a.half_angle
    n = grain_count(D, R, A, a.fill)
    # the lattice (pitch 1.06, solid fraction 0.44) stands about 1.35 times the bed
    zc = 0.0 if A >= 90.0 else (R - D / 2.0) / math.tan(math.radians(A))
    H = math.ceil(zc + 1.45 * (a.fill - zc) + 3.0)
    geo_args = ["--orifice", D, "--half-angle", A, "--radius", R, "--height", H]
    geo_text = sh([PY, os.path.join(EXAMPLE, "make_hopper.py"), "hopper.stl"] + geo_args, wd)
    open(os.path.join(wd, "hopper.txt"), "w").write(geo_text)
    sh([TOOL, "wall", "hopper.stl", "hopper.band", "--spacing", 0.2, "--width", 0.8], wd,
       log="band.txt")
    sh([TOOL, "analytic", "sphere.lslib", "sphere", 0.5, "--analytic", "--nodes", 400,
        "--name", "ball"], wd, log="shape.txt")
    fill_text = sh([PY, os.path.join(EXAMPLE, "fill_hopper.py"), "hopper.data", "--count", n,
                    "--pitch", 1.06] + geo_args, wd)
    nsettle = 10000
    ndis = int(round(a.tmax / DT))
    halt = int(round((1.0 - a.fmax - 0.05) * n))
    mpi = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", a.np] if a.np > 1 else []
    print("D = %g: %d grains, bin R = %g, half-angle %g, wall height %g; settling %d steps, "
          "discharge up to %d steps" % (D, n, R, A, H, nsettle, ndis), flush=True)
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.time()
    sh(mpi + [LMP, "-in", os.path.join(EXAMPLE, "in.hopper"), "-var", "nsettle", nsettle,
              "-var", "ndischarge", ndis, "-var", "nvtk", 0, "-var", "halt", halt,
              "-var", "every", 100, "-log", "log.lammps", "-screen", "none"], wd,
       log="lmp.out")
    wall = time.time() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    geo = hp.read_kv(os.path.join(wd, "hopper.txt"))
    res = hp.analyse(os.path.join(wd, "hopper.csv"), os.path.join(wd, "hopper_settled.dump"),
                     geo, window=(0.0, a.fmax), tmin=a.tmin)
    if "rate" not in res:
        sys.exit("beverloo.py: D = %g: too few CSV rows in the window (see %s)" % (D, wd))
    steps = sum(int(l.split()[8]) for l in open(os.path.join(wd, "log.lammps"))
                if l.startswith("Loop time of"))
    hp.draw(res, geo, os.path.join(wd, "hopper.png"))
    keep = dict(D=D, grains=n, radius=R, half_angle=A, bulk_density=res["bulk_density"],
                fill_height=res["fill_height"], surface=res["surface"],
                bed_mass=res["bed_mass"], rate=res["rate"], rate_err=res["rate_err"],
                t0=res["t0"], t1=res["t1"],
                discharged=res["rows"][-1]["discharged_grains"],
                steps=steps, wall_s=wall, cpu_s=cpu)
    with open(res_path, "w") as f:
        for k, v in keep.items():
            f.write("%s %r\n" % (k, v))
    print("D = %g: W = %.4g +- %.2g (t %.3g..%.3g), rho_b = %.4f, bed %.1f d; %d steps, "
          "%.0f s wall, %.0f s CPU" % (D, res["rate"], res["rate_err"], res["t0"], res["t1"],
                                       res["bulk_density"], res["fill_height"], steps, wall,
                                       cpu), flush=True)
    return keep


def wfit(x, y, s):
    """Weighted straight line y = a + b x: a, b, their covariance, chi^2."""
    w = [1.0 / (e * e) for e in s]
    S = sum(w)
    Sx = sum(wi * xi for wi, xi in zip(w, x))
    Sy = sum(wi * yi for wi, yi in zip(w, y))
    Sxx = sum(wi * xi * xi for wi, xi in zip(w, x))
    Sxy = sum(wi * xi * yi for wi, xi, yi in zip(w, x, y))
    det = S * Sxx - Sx * Sx
    a = (Sxx * Sy - Sx * Sxy) / det
    b = (S * Sxy - Sx * Sy) / det
    chi2 = sum(wi * (yi - a - b * xi) ** 2 for wi, xi, yi in zip(w, x, y))
    return a, b, (Sxx / det, S / det, -Sx / det), chi2


def beverloo_fit(runs, g=1.0):
    """C, k and their errors from the straight line of (W / (rho_b sqrt g))^(2/5) vs D
    (W ~ (D - k)^(5/2) in 3-D: the power 2/5 makes it straight; 2/3 is the 2-D law's)."""
    x = [r["D"] for r in runs]
    y = [(r["rate"] / (r["bulk_density"] * math.sqrt(g))) ** 0.4 for r in runs]
    # error of y from the rate's; at least 0.4 % of y (1 % of W: the rate's windows are few)
    s = [max(0.4 * yi * r["rate_err"] / r["rate"], 0.004 * yi) for yi, r in zip(y, runs)]
    a, b, (vaa, vbb, vab), chi2 = wfit(x, y, s)
    dof = len(x) - 2
    scale = max(1.0, chi2 / dof) if dof > 0 else 1.0
    vaa, vbb, vab = vaa * scale, vbb * scale, vab * scale
    C = b ** 2.5
    k = -a / b
    dC = 2.5 * b ** 1.5 * math.sqrt(vbb)
    # k = -a/b: dk^2 = (1/b)^2 vaa + (a/b^2)^2 vbb + 2 (-1/b)(a/b^2) vab
    dk = math.sqrt(vaa / b ** 2 + (a / b ** 2) ** 2 * vbb - 2 * a / b ** 3 * vab)
    return dict(C=C, dC=dC, k=k, dk=dk, a=a, b=b, chi2=chi2, dof=dof, x=x, y=y, s=s)


def draw(runs, fit, png, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.4))
    a1.errorbar(fit["x"], fit["y"], yerr=fit["s"], fmt="ko", capsize=3, label="LSDEM runs")
    xs = [min(fit["x"] + [fit["k"], K_REF]) - 0.3, max(fit["x"]) + 0.5]
    a1.plot(xs, [fit["a"] + fit["b"] * v for v in xs], "r-",
            label="fit: C = %.3f $\\pm$ %.3f, k = %.2f $\\pm$ %.2f" % (fit["C"], fit["dC"],
                                                                 fit["k"], fit["dk"]))
    a1.plot(xs, [C_REF ** 0.4 * (v - K_REF) for v in xs], "b:",
            label="Beverloo C = %.2f, k = %.1f" % (C_REF, K_REF))
    a1.axhline(0.0, color="grey", lw=0.5)
    a1.set_xlabel("orifice diameter D / d")
    a1.set_ylabel("$(W / \\rho_b \\sqrt{g})^{2/5}$  [$d$]")
    a1.legend(loc="upper left", fontsize=8)
    a1.grid(alpha=0.3)
    a1.set_title("Beverloo: a straight line through (k d, 0)", fontsize=10)
    for r in runs:
        csv = r.get("_csv")
        if not csv or not os.path.exists(csv):
            continue
        rows = hp.read_csv(csv)
        a2.plot([q["time"] for q in rows], [q["discharged_mass"] for q in rows], lw=1,
                label="D = %g d" % r["D"])
        a2.plot([r["t0"], r["t1"]], [0, 0], alpha=0)  # keep limits
    a2.set_xlabel("time since the plug was removed [$\\sqrt{d/g}$]")
    a2.set_ylabel("discharged mass [$\\rho_s d^3$]")
    a2.legend(fontsize=8)
    a2.grid(alpha=0.3)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="?", default="bench-hopper")
    ap.add_argument("--diameters", default="5,6,7,8.5,10")
    ap.add_argument("--radius", type=float, default=12.5)
    ap.add_argument("--half-angle", type=float, default=90.0)
    ap.add_argument("--fill", type=float, default=20.0)
    ap.add_argument("--tmax", type=float, default=25.0)
    ap.add_argument("--tmin", type=float, default=3.0)
    ap.add_argument("--fmax", type=float, default=0.4)
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--redo", action="store_true")
    ap.add_argument("--report-only", action="store_true")
    a = ap.parse_args(argv)
    out = os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    for f in (LMP, TOOL):
        if not a.report_only and not os.access(f, os.X_OK):
            sys.exit("beverloo.py: %s not found: build first (./lsdem build)" % f)
    diameters = [float(v) for v in a.diameters.split(",")]
    runs = []
    for D in diameters:
        r = one_run(D, a, out)
        if r is not None:
            r["_csv"] = os.path.join(out, "D%g" % D, "hopper.csv")
            runs.append(r)
    if len(runs) < 2:
        sys.exit("beverloo.py: %d run(s) done: nothing to fit" % len(runs))
    fit = beverloo_fit(runs)
    lines = []
    lines.append("| D/d | grains | bed height [d] | rho_b | W [rho_s d^3/sqrt(d/g)] | "
                 "W/(rho_b sqrt(g) D^2.5)... C at k = 1.4 | fit window [t] | steps | CPU [s] |")
    lines.append("|---|---|---|---|---|---|---|---|---|")
    for r in runs:
        c14 = r["rate"] / (r["bulk_density"] * (r["D"] - K_REF) ** 2.5)
        lines.append("| %g | %d | %.1f | %.3f | %.2f +- %.2f | %.3f | %.1f-%.1f | %d | %.0f |"
                     % (r["D"], r["grains"], r["fill_height"], r["bulk_density"], r["rate"],
                        r["rate_err"], c14, r["t0"], r["t1"], r["steps"], r["cpu_s"]))
    lines[0] = lines[0].replace("W/(rho_b sqrt(g) D^2.5)... C at k = 1.4", "C at k = 1.4")
    lines.append("")
    lines.append("Beverloo fit (%d orifices): C = %.3f +- %.3f, k = %.2f +- %.2f "
                 "(chi^2 = %.2f for %d dof; issue's goal C = 0.58 +- 0.06, k = 1.4 +- 0.4)"
                 % (len(runs), fit["C"], fit["dC"], fit["k"], fit["dk"], fit["chi2"], fit["dof"]))
    if len(runs) >= 4:  # leave-one-out: how much one orifice moves the fit
        loo = [beverloo_fit(runs[:i] + runs[i + 1:]) for i in range(len(runs))]
        lines.append("leave one orifice out: C %.3f..%.3f, k %.2f..%.2f"
                     % (min(f["C"] for f in loo), max(f["C"] for f in loo),
                        min(f["k"] for f in loo), max(f["k"] for f in loo)))
    c14 = [r["rate"] / (r["bulk_density"] * (r["D"] - K_REF) ** 2.5) for r in runs]
    m = sum(c14) / len(c14)
    sd = math.sqrt(sum((c - m) ** 2 for c in c14) / max(1, len(c14) - 1))
    lines.append("C with k fixed at 1.4: %.3f (spread over D: %.3f)" % (m, sd))
    total_cpu = sum(r["cpu_s"] for r in runs)
    lines.append("CPU time of the lmp runs: %.0f s (half-angle %g, bin radius %g, %d rank(s))"
                 % (total_cpu, runs[0]["half_angle"], runs[0]["radius"], a.np))
    text = "\n".join(lines)
    print(text)
    open(os.path.join(out, "summary.txt"), "w").write(text + "\n")
    with open(os.path.join(out, "beverloo.csv"), "w") as f:
        keys = ["D", "grains", "fill_height", "bulk_density", "rate", "rate_err", "t0", "t1",
                "discharged", "steps", "wall_s", "cpu_s"]
        f.write(",".join(keys) + "\n")
        for r in runs:
            f.write(",".join("%g" % r[k] for k in keys) + "\n")
    draw(runs, fit, os.path.join(out, "beverloo.png"),
         "LSDEM hopper, spheres d = 1, mu = 0.5, e = 0.5: %s, bin R = %g d, bed ~%g d"
         % ("flat bottom" if runs[0]["half_angle"] >= 90 else
            "cone half-angle %g deg" % runs[0]["half_angle"], runs[0]["radius"], a.fill))
    print("wrote %s/summary.txt, beverloo.csv, beverloo.png" % out)


if __name__ == "__main__":
    main(sys.argv[1:])
