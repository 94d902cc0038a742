#!/usr/bin/env python3
"""LSDEM against LIGGGHTS on the hopper (bench/README.md, "Hopper discharge (Beverloo)"):
the same STL hopper, the same spheres from the same lattice, the same linear contact law
(as bench/liggghts: kn, ks, mu, absolute normal damping cn, no tangential damping, rotating
spheres), the same stages (settle on a plane plug, remove it, discharge for a fixed number of
steps, delete the grains below z = -6). Compared: the steady discharge rate (fitted as in
examples/hopper/plot.py) and the CPU time per particle-step of the discharge (1 rank each).

Usage: liggghts.py [OUTDIR] [--orifices 6] [--half-angle 60] [--radius 7] [--height 16]
                   [--grains 1500] [--nsettle 8000] [--ndischarge 30000] [--tmin 3]
                   [--fmax 0.6] [--redo]
  defaults: the example's scene (examples/hopper: D = 6, cone 60 deg, 1,500 spheres).
  Per orifice OUTDIR/D<value>/: hopper.stl, hopper.band, hopper.data (LSDEM) and
  hopper.lg.data (LIGGGHTS, atom_style granular), the logs, lsdem.csv and liggghts.csv,
  result.txt (checkpoint); then OUTDIR/compare.txt and compare.png.
Installs Debian's liggghts when it is missing. LSDEM_BUILD_DIR as for beverloo.py."""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.normpath(os.path.join(HERE, "..", "..", "examples", "hopper"))
sys.path.insert(0, EXAMPLE)
sys.path.insert(0, HERE)
import plot as hp  # noqa: E402
from beverloo import sh, kv, LMP, TOOL, PY  # noqa: E402

KN, KS, MU, CN, DT, G = 1000.0, 800.0, 0.5, 6.972, 1.0e-3, 1.0
VISCOUS = 0.5 * math.pi / 6.0  # in.hopper's damping 0.5 times the grain mass


def liggghts_data(src, dst):
    """atom_style lsdem data (id type shape density x y z q) -> granular (id type d rho x y z)."""
    out, section = [], None
    for line in open(src):
        s = line.split()
        if line.startswith("Atoms"):
            section = "atoms"
            out.append("Atoms\n")
            continue
        if line.startswith("Velocities"):
            section = "vel"
        if section == "atoms" and len(s) == 11:
            out.append("%s %s 1.0 %s %s %s %s\n" % (s[0], s[1], s[3], s[4], s[5], s[6]))
        else:
            out.append(line)
    open(dst, "w").writelines(out)


def loop_stats(log):
    """(loop seconds, steps, mean atoms) of the discharge in a LAMMPS/LIGGGHTS log: every
    run after the first (the settling), summed (LIGGGHTS runs the discharge in pieces)."""
    text = open(log).read()
    parts = text.split("Loop time of")
    secs = steps = 0
    atoms = []
    for k in range(2, len(parts)):
        m = re.match(r"\s*([\d.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms",
                     parts[k])
        secs += float(m.group(1))
        steps += int(m.group(3))
        body = parts[k - 1].split("\n")
        hdr = max(i for i, l in enumerate(body) if l.strip().startswith("Step"))
        cols = body[hdr].split()
        ia = cols.index("Atoms")
        atoms += [float(l.split()[ia]) for l in body[hdr + 1:]
                  if re.match(r"^\s*\d+\s", l) and len(l.split()) == len(cols)]
    return secs, steps, sum(atoms) / len(atoms)


def read_lg_csv(path):
    """fix print output of the LIGGGHTS deck (no title): time,mout,nout,left,ke."""
    names = ["time", "discharged_mass", "discharged_grains", "grains_above_orifice", "ke"]
    rows = []
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        rows.append(dict(zip(names, map(float, line.split(",")))))
    return rows


def one(D, a, out, liggghts):
    wd = os.path.join(out, "D%g" % D)
    res_path = os.path.join(wd, "result.txt")
    if os.path.exists(res_path) and not a.redo:
        print("D = %g: reusing %s" % (D, res_path))
        return kv(open(res_path).read())
    os.makedirs(wd, exist_ok=True)
    geo_args = ["--orifice", D, "--half-angle", a.half_angle, "--radius", a.radius,
                "--height", a.height]
    open(os.path.join(wd, "hopper.txt"), "w").write(
        sh([PY, os.path.join(EXAMPLE, "make_hopper.py"), "hopper.stl"] + geo_args, wd))
    sh([TOOL, "wall", "hopper.stl", "hopper.band", "--spacing", 0.25, "--width", 1.0], wd,
       log="band.txt")
    sh([TOOL, "analytic", "sphere.lslib", "sphere", 0.5, "--analytic", "--nodes", 400,
        "--name", "ball"], wd, log="shape.txt")
    sh([PY, os.path.join(EXAMPLE, "fill_hopper.py"), "hopper.data", "--count", a.grains,
        "--pitch", 1.06] + geo_args, wd)
    liggghts_data(os.path.join(wd, "hopper.data"), os.path.join(wd, "hopper.lg.data"))
    common = ["-var", "nsettle", a.nsettle, "-var", "ndischarge", a.ndischarge,
              "-var", "every", 100, "-var", "zsink", -6.0]
    print("D = %g: LSDEM, %d grains, %d + %d steps" % (D, a.grains, a.nsettle, a.ndischarge),
          flush=True)
    sh([LMP, "-in", os.path.join(EXAMPLE, "in.hopper"), "-var", "nvtk", 0, "-var", "halt", -1,
        "-var", "prefix", "lsdem", "-log", "log.lsdem", "-screen", "none"] + common, wd,
       log="lsdem.out")
    print("D = %g: LIGGGHTS" % D, flush=True)
    sh([liggghts, "-in", os.path.join(HERE, "in.hopper.liggghts"), "-var", "data",
        "hopper.lg.data", "-var", "stl", "hopper.stl", "-var", "kn", KN, "-var", "ks", KS,
        "-var", "mu", MU, "-var", "cn", CN, "-var", "dt", DT, "-var", "g", G,
        "-var", "viscous", VISCOUS, "-var", "prefix", "liggghts", "-log", "log.liggghts"]
       + common, wd, log="liggghts.out")  # not -screen none: its mesh reader prints to it
    geo = hp.read_kv(os.path.join(wd, "hopper.txt"))
    res = dict(D=D, grains=a.grains)
    for code, rows in (("lsdem", hp.read_csv(os.path.join(wd, "lsdem.csv"))),
                       ("liggghts", read_lg_csv(os.path.join(wd, "liggghts.csv")))):
        b = hp.bed(hp.read_dump(os.path.join(wd, code + "_settled.dump")), geo)
        r = hp.rate(rows, b["bed_mass"], (0.0, a.fmax), a.tmin)
        secs, steps, atoms = loop_stats(os.path.join(wd, "log." + code))
        res.update({code + "_rate": r["rate"], code + "_rate_err": r["rate_err"],
                    code + "_t0": r["t0"], code + "_t1": r["t1"],
                    code + "_bulk_density": b["bulk_density"],
                    code + "_fill_height": b["fill_height"],
                    code + "_loop_s": secs, code + "_steps": steps, code + "_mean_atoms": atoms,
                    code + "_us_per_particle_step": 1e6 * secs / (steps * atoms)})
    with open(res_path, "w") as f:
        for k, v in res.items():
            f.write("%s %r\n" % (k, v))
    return res


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="?", default="bench-hopper-liggghts")
    ap.add_argument("--orifices", default="6")
    ap.add_argument("--half-angle", type=float, default=60.0)
    ap.add_argument("--radius", type=float, default=7.0)
    ap.add_argument("--height", type=float, default=16.0)
    ap.add_argument("--grains", type=int, default=1500)
    ap.add_argument("--nsettle", type=int, default=8000)
    ap.add_argument("--ndischarge", type=int, default=30000)
    ap.add_argument("--tmin", type=float, default=3.0)
    ap.add_argument("--fmax", type=float, default=0.6)
    ap.add_argument("--redo", action="store_true")
    a = ap.parse_args(argv)
    liggghts = os.environ.get("LIGGGHTS", "liggghts")
    if shutil.which(liggghts) is None:
        print("liggghts.py: installing Debian's liggghts package", file=sys.stderr)
        sudo = [] if os.geteuid() == 0 else ["sudo"]
        subprocess.run(sudo + ["apt-get", "update", "-qq"], check=True)
        subprocess.run(sudo + ["apt-get", "install", "-y", "-qq", "--no-install-recommends",
                               "liggghts"], check=True,
                       env=dict(os.environ, DEBIAN_FRONTEND="noninteractive"))
    out = os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    rows = [one(float(D), a, out, liggghts) for D in a.orifices.split(",")]
    lines = ["| D/d | code | rho_b | bed [d] | W | fit window [t] | mean grains | "
             "us per particle-step |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        for code, name in (("lsdem", "LSDEM"), ("liggghts", "LIGGGHTS")):
            lines.append("| %g | %s | %.3f | %.1f | %.2f +- %.2f | %.1f-%.1f | %.0f | %.3f |" % (
                r["D"], name, r[code + "_bulk_density"], r[code + "_fill_height"],
                r[code + "_rate"], r[code + "_rate_err"], r[code + "_t0"], r[code + "_t1"],
                r[code + "_mean_atoms"], r[code + "_us_per_particle_step"]))
        lines.append("")
        lines.append("D = %g: rate LSDEM/LIGGGHTS = %.3f, time per particle-step "
                     "LSDEM/LIGGGHTS = %.2f" % (
                         r["D"], r["lsdem_rate"] / r["liggghts_rate"],
                         r["lsdem_us_per_particle_step"] / r["liggghts_us_per_particle_step"]))
    text = "\n".join(lines)
    print(text)
    open(os.path.join(out, "compare.txt"), "w").write(text + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for r in rows:
        wd = os.path.join(out, "D%g" % r["D"])
        for code, rd, st in (("lsdem", hp.read_csv, "-"), ("liggghts", read_lg_csv, "--")):
            q = rd(os.path.join(wd, code + ".csv"))
            ax.plot([x["time"] for x in q], [x["discharged_mass"] for x in q], st,
                    label="%s D = %g: W = %.2f" % ("LSDEM" if code == "lsdem" else "LIGGGHTS",
                                                   r["D"], r[code + "_rate"]))
    ax.set_xlabel("time since the plug was removed [$\\sqrt{d/g}$]")
    ax.set_ylabel("discharged mass [$\\rho_s d^3$]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("hopper: LSDEM (fix wall/lsdem mesh) vs LIGGGHTS (fix mesh/surface)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "compare.png"), dpi=110)
    print("wrote %s/compare.txt, compare.png" % out)


if __name__ == "__main__":
    main(sys.argv[1:])
