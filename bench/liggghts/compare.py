"""Figures of the LSDEM-LIGGGHTS comparison (bench/liggghts/run.sh) from the runs' logs.

Usage: compare.py OUTDIR

Reads OUTDIR/params.txt, OUTDIR/settle.data and the logs run.sh wrote
(collide_<case>.<code>.log, settle.<code>.log, code = lsdem or liggghts) and the settling
runs' CPU times (settle.<code>.log.cpu); prints a table, writes OUTDIR/comparison.csv and
OUTDIR/comparison.png, and prints last, on one line,
  collision_max_rel_diff=<a> settle_zcm_rel_diff=<b> us_per_grain_step_lsdem=<c> us_per_grain_step_liggghts=<d>
  cpu_us_per_grain_step_lsdem=<e> cpu_us_per_grain_step_liggghts=<f>
(c, d: per grain-step from the run loop's wall time; e, f: from the whole process's CPU
time, setup included)

Independent references: each collision is integrated here from the contact law alone, with
time steps 50 times shorter than the codes' (reference_collision; the elastic case must give
e = 1, the sliding oblique one an impulse ratio close to mu); the vertical force on the walls
(floor and sides) of the bed at rest must equal its weight."""
import csv
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from figures import save_panels  # noqa: E402  (bench/figures.py)
from scenes import RADII  # noqa: E402  (the radii the scenes were written with)

CODES = ("lsdem", "liggghts")


def read_params(path):
    p, cases = {}, {}
    for line in open(path):
        w = line.split()
        if w[0] == "case":
            cases[w[1]] = dict(zip(("cn", "mu", "vn", "vt"), map(float, w[2:6])))
        else:
            p[w[0]] = float(w[1])
    return p, cases


def thermo_rows(path):
    """The thermo rows of a LAMMPS or LIGGGHTS log, as dicts keyed by column name (names as
    printed: LIGGGHTS drops the v_ prefix of variables)."""
    rows, keys = [], None
    for line in open(path):
        w = line.split()
        if w and w[0] == "Step":
            keys = [k[2:] if k.startswith("v_") else k for k in w]
            continue
        if keys and w and w[0].startswith("Loop"):
            keys = None
            continue
        if keys and len(w) == len(keys):
            try:
                rows.append(dict(zip(keys, map(float, w))))
            except ValueError:
                keys = None
    return rows


def loop_seconds(path):
    for line in open(path):
        if line.startswith("Loop time of"):
            return float(line.split()[3])
    raise SystemExit("compare.py: no 'Loop time' in %s (did the run finish?)" % path)


def cpu_seconds(path):
    """User + system CPU seconds of a run, from the second line of bash's `times` that run.sh
    writes beside its log ("0m12.345s 0m0.067s": the run's user and system time). On a
    machine shared with other work a run's wall time counts the time it waited for a core,
    its CPU time does not."""
    line = open(path).read().splitlines()[1]
    seconds = 0.0
    for field in line.split():
        minutes, rest = field.rstrip("s").split("m")
        seconds += 60.0 * float(minutes) + float(rest)
    return seconds


def reference_collision(p, c, substeps=50):
    """Thermo-like rows of an independent integration of the two-sphere collision: the
    relative motion of two equal masses in the x-y plane (reduced mass m/2), normal force
    kn d - cn v_n never attractive, tangential spring decremented by ks v_t h, turned into
    each new tangent plane with its length kept and capped at mu times the normal force;
    the spheres turn about z, each with the torque -cr n x f of the force f on sphere 2
    applied cr = R - d/2 from either centre (the same on both, so both keep one spin w,
    which slows the contact point's tangential velocity by 2 cr w); semi-implicit Euler
    with `substeps` steps per time step of the codes' collision runs (10,000 per contact),
    so its own time error is negligible against theirs. Sphere 1 starts at (-R, 0) with
    velocity (vn, vt) / 2, sphere 2 opposite (scenes.py), neither spinning."""
    R, m = RADII[0], p["mass1"]
    inertia = 0.4 * m * R * R
    h = p["dt_collide"] / substeps
    rx, ry = 2 * R, 0.0  # x2 - x1
    ux, uy = -c["vn"], -c["vt"]  # v2 - v1
    w = 0.0  # spin of each sphere about z
    sx = sy = 0.0  # tangential spring, force on sphere 2
    rows, t = [], 0
    while True:
        dist = math.hypot(rx, ry)
        fx = fy = 0.0
        if dist < 2 * R:
            nx, ny = rx / dist, ry / dist
            cr = R - 0.5 * (2 * R - dist)
            un = ux * nx + uy * ny
            fn = max(p["kn"] * (2 * R - dist) - c["cn"] * un, 0.0)
            # contact point of 2 relative to 1: u - cr (w1 + w2) z x n
            tx, ty = ux - un * nx + 2 * cr * w * ny, uy - un * ny - 2 * cr * w * nx
            s_len = math.hypot(sx, sy)
            sn = sx * nx + sy * ny  # turn the spring into the tangent plane, length kept
            px, py = sx - sn * nx, sy - sn * ny
            p_len = math.hypot(px, py)
            if p_len > 0:
                sx, sy = px * s_len / p_len, py * s_len / p_len
            sx -= p["ks"] * tx * h
            sy -= p["ks"] * ty * h
            s_len = math.hypot(sx, sy)
            if s_len > c["mu"] * fn:
                scale = c["mu"] * fn / s_len if s_len > 0 else 0.0
                sx, sy = sx * scale, sy * scale
            fx, fy = fn * nx + sx, fn * ny + sy
            w += -cr * (nx * fy - ny * fx) / inertia * h
        else:
            sx = sy = 0.0
        ux += 2 * fx / m * h  # force f on sphere 2, -f on sphere 1
        uy += 2 * fy / m * h
        rx += ux * h
        ry += uy * h
        t += 1
        if t % substeps == 0:
            rows.append({"x1": -rx / 2, "y1": -ry / 2, "x2": rx / 2, "y2": ry / 2,
                         "v1x": -ux / 2, "v1y": -uy / 2, "v2x": ux / 2, "v2y": uy / 2})
            if len(rows) == 4000:
                return [{"x1": -R, "y1": 0.0, "x2": R, "y2": 0.0, "v1x": c["vn"] / 2,
                         "v1y": c["vt"] / 2, "v2x": -c["vn"] / 2, "v2y": -c["vt"] / 2}] + rows


def contact_normal_at_end(rows, radius):
    """Unit vector from sphere 1 to sphere 2 (the contact normal, in the x-y plane) at the
    last thermo row where the two still overlap."""
    touching = [r for r in rows if math.hypot(r["x2"] - r["x1"], r["y2"] - r["y1"]) < 2 * radius]
    if not touching:
        raise SystemExit("compare.py: the spheres never touched")
    r = touching[-1]
    d = (r["x2"] - r["x1"], r["y2"] - r["y1"])
    n = math.hypot(*d)
    return d[0] / n, d[1] / n


def collision_measures(rows, c):
    """The restitution e (relative normal velocity after, along the normal at separation,
    over before, along x where the spheres first touch) and, with friction, the ratio of the
    tangential to the normal impulse in the frame of the mean of the first and last normal
    (the normal turns while the spheres slide)."""
    first, last = rows[0], rows[-1]
    n = contact_normal_at_end(rows, RADII[0])
    rel = (last["v2x"] - last["v1x"], last["v2y"] - last["v1y"])
    out = {"restitution": (rel[0] * n[0] + rel[1] * n[1]) / c["vn"]}
    if c["mu"] > 0:
        mid = (1.0 + n[0], n[1])  # first normal (1, 0) plus the last
        m = math.hypot(*mid)
        mid = (mid[0] / m, mid[1] / m)
        j = (last["v2x"] - first["v2x"], last["v2y"] - first["v2y"])  # impulse on 2 / mass
        jn = j[0] * mid[0] + j[1] * mid[1]
        out["slip_ratio"] = abs(-j[0] * mid[1] + j[1] * mid[0]) / jn
    return out


def collision_figures(outdir, params, cases):
    """Per case and code: collision_measures of the code's run, and of the reference."""
    out = []
    for name, c in cases.items():
        ref = collision_measures(reference_collision(params, c), c)
        for code in CODES:
            rows = thermo_rows(os.path.join(outdir, "collide_%s.%s.log" % (name, code)))
            row = {"case": name, "code": code}
            for key, value in collision_measures(rows, c).items():
                row[key], row[key + "_ref"] = value, ref[key]
            out.append(row)
    return out


def total_weight(data_path, params):
    """Weight of the settling spheres (from the LSDEM data file's shape-IDs and densities)."""
    w, atoms = 0.0, False
    for line in open(data_path):
        s = line.split()
        if line.startswith("Atoms"):
            atoms = True
            continue
        if atoms and line.startswith("Velocities"):
            break
        if atoms and len(s) == 11:
            r = RADII[int(s[2]) - 1]
            w += float(s[3]) * 4.0 / 3.0 * math.pi * r ** 3 * params["gravity"]
    return w


def plot(outdir, series, params):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    style = {"lsdem": ("C0", "-", "LSDEM (pair_style lsdem, analytic spheres)"),
             "liggghts": ("C3", "--", "LIGGGHTS 3.8 (hooke/stiffness)")}
    for code, rows in series.items():
        t = [r["Step"] * params["dt"] for r in rows]
        colour, ls, label = style[code]
        ax[0].semilogy(t, [max(r["KinEng"], 1e-16) for r in rows], ls, color=colour, label=label)
        ax[1].plot(t, [1e3 * r["zcm"] for r in rows], ls, color=colour, label=label)
    ax[0].set(xlabel="time (s)", ylabel="kinetic energy (J)", title="settling: kinetic energy")
    ax[1].set(xlabel="time (s)", ylabel="centre of mass height (mm)",
              title="settling: centre of mass")
    save_panels(fig, ax, os.path.join(outdir, "comparison.png"))


def main(outdir):
    params, cases = read_params(os.path.join(outdir, "params.txt"))
    coll = collision_figures(outdir, params, cases)
    print("binary collisions (two R = 1 mm spheres, relative velocity %g m/s):" % params["v0"])
    print("  %-8s %-9s %12s %12s %12s %12s" % ("case", "code", "e", "e ref", "slip", "slip ref"))
    for r in coll:
        print("  %-8s %-9s %12.6f %12.6f %12s %12s" % (
            r["case"], r["code"], r["restitution"], r["restitution_ref"],
            "%.6f" % r["slip_ratio"] if "slip_ratio" in r else "-",
            "%.6f" % r["slip_ratio_ref"] if "slip_ratio_ref" in r else "-"))
    by = {(r["case"], r["code"]): r for r in coll}
    coll_diff = 0.0
    for name in cases:
        a, b = by[(name, "lsdem")], by[(name, "liggghts")]
        for key in ("restitution", "slip_ratio"):
            if key in a:
                coll_diff = max(coll_diff, abs(a[key] - b[key]) / abs(b[key]))

    series = {code: thermo_rows(os.path.join(outdir, "settle.%s.log" % code)) for code in CODES}
    n = int(params["grains"])
    us, us_cpu = {}, {}
    for code in CODES:
        steps = series[code][-1]["Step"] - series[code][0]["Step"]
        us[code] = 1e6 * loop_seconds(os.path.join(outdir, "settle.%s.log" % code)) / (steps * n)
        us_cpu[code] = 1e6 * cpu_seconds(os.path.join(outdir, "settle.%s.log.cpu" % code)) / (
            steps * n)
    zcm = {code: series[code][-1]["zcm"] for code in CODES}
    zmax = {code: series[code][-1]["zmax"] for code in CODES}
    ke = {code: series[code][-1]["KinEng"] for code in CODES}
    zdiff = abs(zcm["lsdem"] - zcm["liggghts"]) / zcm["liggghts"]
    weight = total_weight(os.path.join(outdir, "settle.data"), params)
    # the walls report the force the spheres exert on them: at rest, their z sum is the weight
    walls = -series["lsdem"][-1]["wallz"]
    floor = -series["lsdem"][-1]["f_floor[3]"]
    t_end = series["lsdem"][-1]["Step"] * params["dt"]
    print("settling (%d spheres, %.3f s):" % (n, t_end))
    print("  %-9s %14s %14s %14s %16s %16s" % ("code", "zcm (mm)", "top (mm)", "KE (J)",
                                                "us/grain-step", "CPU us/gr-step"))
    for code in CODES:
        print("  %-9s %14.4f %14.4f %14.3e %16.4f %16.4f" % (
            code, 1e3 * zcm[code], 1e3 * zmax[code], ke[code], us[code], us_cpu[code]))
    print("  LSDEM walls' vertical force %.6g N (floor %.6g N) against the spheres' weight"
          " %.6g N: ratio %.6f" % (walls, floor, weight, walls / weight))

    with open(os.path.join(outdir, "comparison.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run", "code", "quantity", "value", "reference"])
        for r in coll:
            w.writerow(["collide_" + r["case"], r["code"], "restitution", r["restitution"],
                        r["restitution_ref"]])
            if "slip_ratio" in r:
                w.writerow(["collide_" + r["case"], r["code"], "slip_ratio", r["slip_ratio"],
                            r["slip_ratio_ref"]])
        for code in CODES:
            w.writerow(["settle", code, "zcm", zcm[code], ""])
            w.writerow(["settle", code, "zmax", zmax[code], ""])
            w.writerow(["settle", code, "ke_end", ke[code], ""])
            w.writerow(["settle", code, "us_per_grain_step", us[code], ""])
            w.writerow(["settle", code, "cpu_us_per_grain_step", us_cpu[code], ""])
        w.writerow(["settle", "lsdem", "walls_vertical_force", walls, weight])
    plot(outdir, series, params)
    print("collision_max_rel_diff=%.3g settle_zcm_rel_diff=%.3g us_per_grain_step_lsdem=%.4g "
          "us_per_grain_step_liggghts=%.4g cpu_us_per_grain_step_lsdem=%.4g "
          "cpu_us_per_grain_step_liggghts=%.4g" % (coll_diff, zdiff, us["lsdem"], us["liggghts"],
                                                   us_cpu["lsdem"], us_cpu["liggghts"]))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
