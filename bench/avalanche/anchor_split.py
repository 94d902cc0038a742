#!/usr/bin/env python3
"""The anchors' reaction of each net in an avalanche run, split at every step into the bonds'
pull on the clamped balls and the grains' contacts on them (bench/README.md, "The avalanche,
impulse against penalty"). fix net/lsdem's anchor force is -sum f over the clamped balls
(doc/fix_net_lsdem.rst): with the penalty method f holds the bond forces and the grains'
contact forces on those balls; with the impulse method the contacts are impulses, which
fix impulse/lsdem adds to the clamped balls' f as impulse / dt (before branch anchor they
never entered f, and only the bonds' part was counted). This script recomputes the bonds' part from the
balls' positions and velocities as bond_style lsdem/net does (core/specimen/net.c,
lsdem_net_bond_force: k (L - r0) + c (v_j - v_i).u along u) and reads the total from f.
    anchor_split.py RUNDIR NETS [M...]
RUNDIR holds nets_steps.dump (in.avalanche -var netsteps N -var netfrom T), netK.in and
netNETS.data; M: also the peaks of the series sampled every M steps (every offset). Prints
per net the peak of the total and of the bonds' part with their steps; writes
RUNDIR/anchor_split.csv (step, then per net total and bonds)."""
import os
import sys

import numpy as np

run, nets = sys.argv[1], int(sys.argv[2])
samples = [int(a) for a in sys.argv[3:]]


def net_setup(k):
    btype = clamp_type = None
    for line in open(os.path.join(run, "net%d.in" % k)):
        w = line.split()
        if w[:1] == ["bond_coeff"]:
            btype, kk, r0 = int(w[1]), float(w[2]), float(w[3])
            c = float(w[w.index("damp") + 1]) if "damp" in w else 0.0
        if w[:2] == ["group", "net%d_clamp" % k]:
            clamp_type = int(w[3])
    return btype, kk, r0, c, clamp_type


types, bonds, sec = {}, [], None
for line in open(os.path.join(run, "net%d.data" % nets)):
    s = line.split("#")[0].strip()
    if not s:
        continue
    if s[0].isalpha():
        sec = s
        continue
    w = s.split()
    if sec == "Atoms":
        types[int(w[0])] = int(w[1])
    elif sec == "Bonds":
        bonds.append((int(w[1]), int(w[2]), int(w[3])))

lines = open(os.path.join(run, "nets_steps.dump")).read().split("\n")
n = int(lines[3])
frames = (len(lines) - 1) // (9 + n)
steps = np.empty(frames, int)
data = np.empty((frames, n, 11))
for f in range(frames):
    o = f * (9 + n)
    steps[f] = int(lines[o + 1])
    data[f] = np.array(" ".join(lines[o + 9:o + 9 + n]).split(), float).reshape(n, 11)
ids = data[0, :, 0].astype(int)
row = {a: r for r, a in enumerate(ids)}
assert all((data[f, :, 0].astype(int) == ids).all() for f in range(frames))

cols = [steps]
for k in range(1, nets + 1):
    btype, kk, r0, c, ctype = net_setup(k)
    clamped = np.array([row[a] for a in ids if types[a] == ctype])
    # bonds of this net with one clamped end: i the clamped ball, j the free one
    pairs = []
    for t, a, b in bonds:
        if t != btype or (types[a] == ctype) == (types[b] == ctype):
            continue
        pairs.append((row[a], row[b]) if types[a] == ctype else (row[b], row[a]))
    i, j = np.array(pairs).T
    x, v, force = data[:, :, 2:5], data[:, :, 5:8], data[:, :, 8:11]  # id type x v f
    total = np.linalg.norm(-force[:, clamped].sum(axis=1), axis=1)
    d = x[:, j] - x[:, i]
    length = np.linalg.norm(d, axis=2)
    u = d / length[..., None]
    pull = kk * (length - r0) + c * np.einsum("fbk,fbk->fb", v[:, j] - v[:, i], u)
    # the force on the clamped ball i is +pull u; the reaction is minus its sum
    bonds_only = np.linalg.norm(-(pull[..., None] * u).sum(axis=1), axis=1)
    a, b = total.argmax(), bonds_only.argmax()
    print("net %d: %d clamped balls, %d bonds to them, steps %d-%d: peak total %.1f at step %d "
          "(bonds %.1f there), peak of the bonds' part %.1f at step %d"
          % (k, len(clamped), len(i), steps[0], steps[-1], total[a], steps[a], bonds_only[a],
             bonds_only[b], steps[b]))
    for m in samples:
        print("  sampled every %d steps: peak total %.1f-%.1f, bonds' part %.1f-%.1f (over the %d offsets)"
              % (m, min(total[s::m].max() for s in range(m)), max(total[s::m].max() for s in range(m)),
                 min(bonds_only[s::m].max() for s in range(m)),
                 max(bonds_only[s::m].max() for s in range(m)), m))
    cols += [total, bonds_only]
head = "step " + " ".join("total_%d bonds_%d" % (k, k) for k in range(1, nets + 1))
np.savetxt(os.path.join(run, "anchor_split.csv"), np.column_stack(cols), fmt="%.10g", header=head,
           comments="")
