"""The unload-reload loops of a cyclic triaxial run (in.triaxial -var cycles N, report §3.5.5):
cycles.csv read, split into loops and measured. Pure functions; plot.py draws Figure 3.25.

A loop of cycle k starts where unloading starts (U: the end of the hold after the peak, or the
peak without holds), follows the unloading, the hold at the turn and the reload, and closes
where the reload first comes back to U's axial strain (C, interpolated linearly between the
two rows around it; a reload that ends before, the run's last loop cut short, leaves the loop
open). Measures, with q the axial deviator qz (sigma_zz - (sigma_xx + sigma_yy)/2):
  loop energy W = the integral of q d(eps_a) along the path U ... C and back to U (the
      trapezoid rule over the rows, exact for the polygon they make; the closing edge C-U is
      at constant strain and adds nothing): the work per unit volume dissipated in the loop,
      positive when the reload runs above the unloading;
  secant modulus E_sec = (q_U - q_T) / (eps_U - eps_T), T the turn (the last unloading row,
      before the hold's relaxation);
  elastic energy W_e = 1/2 E_sec (d_eps/2)^2 = d_q d_eps / 8, d = U - T: what a linear spring
      of the secant modulus stores at the loop's half amplitudes, the reference of the usual
      damping ratio of cyclic tests (ASTM D3999: triangle of the half amplitudes);
  damping ratio D = W / (4 pi W_e) (for a linear viscoelastic q = E eps + eta d(eps)/dt under
      harmonic strain this is eta omega / (2 E), the classical damping ratio);
  residual volumetric strain eps_v(C) - eps_v(U) (+ = contraction over the loop)."""
import csv
import math

COLUMNS = ("step", "cycle", "phase", "eps_a", "eps_v", "qz")


def read(spec):
    """Rows of cycles.csv as dicts (step and cycle int, phase str, the rest float). spec may
    join the parts of a resumed run, "cycles.csv+cycles.2.csv": each part's rows from its first
    step on replace the earlier parts'."""
    rows = []
    for path in spec.split("+"):
        part = []
        for r in csv.DictReader(open(path)):
            part.append({k: (int(v) if k in ("step", "cycle") else v if k == "phase"
                             else float(v)) for k, v in r.items()})
        if part:
            rows = [r for r in rows if r["step"] < part[0]["step"]] + part
    return rows


def loop_work(points):
    """The integral of q d(eps) along the closed polygon `points` [(eps, q), ...] (closed
    from the last point back to the first), by the trapezoid rule: exact for a polygon."""
    w = 0.0
    for i, (e0, q0) in enumerate(points):
        e1, q1 = points[(i + 1) % len(points)]
        w += 0.5 * (q0 + q1) * (e1 - e0)
    return w


def measure(path, turn):
    """Measures of one loop: path = [(eps_a, q, eps_v), ...] from U to the closing point C
    (at U's strain), turn = the index in path of the turn T. Returns a dict."""
    (eu, qu, vu), (et, qt, _), (_, _, vc) = path[0], path[turn], path[-1]
    de, dq = eu - et, qu - qt
    w = loop_work([(e, q) for e, q, _ in path])
    we = dq * de / 8.0
    return {"eps_top": eu, "q_top": qu, "eps_turn": et, "q_turn": qt,
            "secant_modulus": dq / de if de else float("nan"), "loop_energy": w,
            "elastic_energy": we, "damping_ratio": w / (4.0 * math.pi * we) if we else float("nan"),
            "residual_eps_v": vc - vu}


def loops(rows):
    """The loops of a cyclic run's rows: a list of dicts, one per cycle that unloaded, with the
    cycle, the steps of U, T and C (C None when the reload did not reach U's strain), closed
    (bool) and, for closed loops, the measures of measure()."""
    out = []
    cycles = sorted({r["cycle"] for r in rows if r["phase"] == "unload"})
    for k in cycles:
        idx = [i for i, r in enumerate(rows) if r["cycle"] == k]
        first_unload = next(i for i in idx if rows[i]["phase"] == "unload")
        u = first_unload - 1                        # the last row before unloading: U
        t = max(i for i in idx if rows[i]["phase"] == "unload")
        eu = rows[u]["eps_a"]
        path = [(rows[i]["eps_a"], rows[i]["qz"], rows[i]["eps_v"]) for i in range(u, t + 1)]
        c = None
        for i in range(t + 1, len(rows)):
            r = rows[i]
            if r["eps_a"] >= eu and r["phase"] == "load":
                p = rows[i - 1]
                f = (eu - p["eps_a"]) / (r["eps_a"] - p["eps_a"])
                path.append((eu, p["qz"] + f * (r["qz"] - p["qz"]),
                             p["eps_v"] + f * (r["eps_v"] - p["eps_v"])))
                c = i
                break
            path.append((r["eps_a"], r["qz"], r["eps_v"]))
        loop = {"cycle": k, "step_top": rows[u]["step"], "step_turn": rows[t]["step"],
                "step_close": rows[c]["step"] if c is not None else None,
                "closed": c is not None, "path": path}
        if c is not None:
            loop.update(measure(path, t - u))
        out.append(loop)
    return out


FIELDS = ("cycle", "eps_top", "q_top", "eps_turn", "q_turn", "secant_modulus", "loop_energy",
          "elastic_energy", "damping_ratio", "residual_eps_v", "step_top", "step_turn",
          "step_close")


def write(path, measured):
    """One row per closed loop: FIELDS."""
    with open(path, "w") as f:
        f.write(",".join(FIELDS) + "\n")
        for lp in measured:
            if lp["closed"]:
                f.write(",".join("%.10g" % lp[k] if isinstance(lp[k], float) else str(lp[k])
                                 for k in FIELDS) + "\n")
