#!/usr/bin/env python3
"""The figures of a barrier test (in.barrier) from its barrier.csv, as ETAG 027 asks them,
and the energy balance.

    python3 barrier.py [barrier.csv] [--json]

Impact direction: -z, the net's normal is +z (deflections are positive downward).
  first contact   the first sample at which the cube's vz leaves free flight (vz0 - g t
                  with g from the change of vz before contact; relative 1e-7): both methods
  braking time    from first contact until vz first reaches 0 (linear between samples)
  max elongation  largest bond strain (fix net/lsdem output 4) and largest deflection of the
                  net from its state at release, the fall of its lowest ball (output 5)
  residual        the net's deflection at the last sample (after the deck's quieting down,
                  phase 1, if it ran one), from its state at release
Times are from the release of the cube (the first sample); the work W from there too.
  anchor force    |R| of the anchors' reaction (outputs 1-3), peak and last
Energy: E(t) = kinetic (translation + rotation of the cube and the free balls) + bond energy
+ gravitational energy. With W the work of the bond damping (output 8, the integral of the
damping power, measured), the rest D(t) = E(0) - E(t) - W(t) is what the contacts took:
contact damping and friction (penalty), collisions (impulse), global damping, plus the
contact spring energy stored at t (zero when nothing touches). D is the residual, not
measured."""
import json
import sys


def read(path):
    rows = []
    with open(path) as f:
        cols = f.readline().lstrip("#").split()
        for line in f:
            if line.strip():
                rows.append(dict(zip(cols, map(float, line.split()))))
    w0, t0 = rows[0]["w_bond_damping"], rows[0]["time"]
    for r in rows:    # the impact run's own: time and damping work from its start
        r["w_bond_damping"] -= w0
        r["time"] -= t0
    return rows


def energy(r):
    return r["ke_block"] + r["ke_net"] + r["ebond"] + r["egrav"]


def first_contact(rows):
    """index of the first sample off free flight (the contact happened since the one before)"""
    r0, r1 = rows[0], rows[1]
    acc = (r1["vz"] - r0["vz"]) / (r1["time"] - r0["time"])    # free flight: -g
    for n, r in enumerate(rows):
        free = r0["vz"] + acc * (r["time"] - r0["time"])
        if abs(r["vz"] - free) > 1e-7 * max(1.0, abs(free)):
            return n
    return None


def figures(all_rows):
    """the figures of the impact (phase 0) and the residual ones of the last sample (after
    the quieting down, phase 1, if the deck ran one)"""
    rows = [r for r in all_rows if r.get("phase", 0) == 0]
    last = all_rows[-1]
    out = {}
    n0 = first_contact(rows)
    out["t_contact"] = rows[n0]["time"] if n0 is not None else None
    # the cube's kinetic energy at first contact (the sample before: still in free flight)
    out["E_impact"] = rows[max(n0 - 1, 0)]["ke_block"] if n0 is not None else None
    t_stop = None
    if n0 is not None:
        for a, b in zip(rows[n0 - 1:], rows[n0:]):
            if b["vz"] >= 0.0 > a["vz"]:
                t_stop = a["time"] + (b["time"] - a["time"]) * (-a["vz"]) / (b["vz"] - a["vz"])
                break
    out["t_stop"] = t_stop
    out["braking_time"] = t_stop - rows[n0]["time"] if t_stop is not None else None
    out["max_strain"] = max(r["max_strain"] for r in rows)
    low = min(rows, key=lambda r: r["height"])
    out["sag_before"] = -rows[0]["height"]
    out["max_deflection"] = rows[0]["height"] - low["height"]
    out["t_max_deflection"] = low["time"]
    out["residual_deflection"] = rows[0]["height"] - last["height"]
    out["quieted"] = last.get("phase", 0) == 1
    out["ke_last"] = last["ke_block"] + last["ke_net"]
    mag = lambda r: (r["rx"] ** 2 + r["ry"] ** 2 + r["rz"] ** 2) ** 0.5
    peak = max(rows, key=mag)
    out["anchor_peak"] = mag(peak)
    out["t_anchor_peak"] = peak["time"]
    out["anchor_final"] = [last["rx"], last["ry"], last["rz"]]
    out["bonds_broken"] = last["bonds_broken"]
    out["vz_final"] = last["vz"]
    e0, e1 = energy(rows[0]), energy(rows[-1])
    out["energy"] = {
        "E0": e0, "kinetic_end": rows[-1]["ke_block"] + rows[-1]["ke_net"],
        "bond_end": rows[-1]["ebond"], "bond_start": rows[0]["ebond"],
        "gravity_change": rows[-1]["egrav"] - rows[0]["egrav"],
        "bond_damping_work": rows[-1]["w_bond_damping"],
        "other_dissipated_residual": e0 - e1 - rows[-1]["w_bond_damping"],
        "peak_bond": max(r["ebond"] for r in rows) - rows[0]["ebond"],
    }
    # the balance where nothing touches (penalty: contacts 0): E(t) + W(t) against E(0)
    free = [r for r in rows if r["contacts"] == 0]
    if free and free is not rows:
        worst = max(free, key=lambda r: abs(energy(r) + r["w_bond_damping"] - e0))
        out["energy"]["balance_no_contact_worst"] = (energy(worst) + worst["w_bond_damping"]
                                                     - e0) / (out["E_impact"] or e0)
        out["energy"]["balance_no_contact_samples"] = len(free)
    return out


def report(f):
    e = f["energy"]
    lines = [
        "first contact        t = %.4f, kinetic energy then %.5g" % (f["t_contact"], f["E_impact"]),
        "braking time         %.4f (block's vz first 0 at t = %.4f)" % (f["braking_time"], f["t_stop"])
        if f["braking_time"] is not None else "braking time         - (vz never reached 0)",
        "max elongation       bond strain %.4f; net deflection %.4f (t = %.4f)"
        % (f["max_strain"], f["max_deflection"], f["t_max_deflection"]),
        "residual deflection  %.4f (last sample%s, kinetic energy then %.2g; the net sagged %.4f "
        "under its weight before)" % (f["residual_deflection"], ", after quieting down"
                                      if f["quieted"] else "", f["ke_last"], f["sag_before"]),
        "anchor force         peak |R| %.4g (t = %.4f); last R = (%.3g, %.3g, %.4g)"
        % ((f["anchor_peak"], f["t_anchor_peak"]) + tuple(f["anchor_final"])),
        "bonds broken         %d" % f["bonds_broken"],
        "energy over the impact (of E(0) = %.5g): kinetic left %.4g, bond %.4g (start %.4g, peak rise %.4g), "
        "gravity change %.4g, bond damping work %.4g, other dissipation (residual) %.4g"
        % (e["E0"], e["kinetic_end"], e["bond_end"], e["bond_start"], e["peak_bond"],
           e["gravity_change"], e["bond_damping_work"], e["other_dissipated_residual"]),
    ]
    if "balance_no_contact_worst" in e:
        lines.append("without contact: worst |E + W - E(0)| = %.3g %% of the impact energy "
                     "over %d samples (what the contacts took so far; 0 if they are elastic)"
                     % (100 * abs(e["balance_no_contact_worst"]),
                        e["balance_no_contact_samples"]))
    return "\n".join(lines)


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    f = figures(read(args[0] if args else "barrier.csv"))
    print(json.dumps(f, indent=1) if "--json" in sys.argv else report(f))
