"""examples/avalanche with two nets across the channel (in.avalanche -var nets 2, inputs by
make_nets.sh), on a small scene: the 100 lowest grains of the shipped source, two nets
close below them (x = -1, 0.6 high, which the flow overtops; x = -3.5, 2.5 high), 7,854
steps (t = 2.2) on 2 ranks.

The deck's nets.csv (fix net/lsdem outputs 10, 7, 1-3 and 9 of each net) against an
independent count from its end dumps (deposit.dump: the grains; nets_end.dump: the balls
with their forces; netK.net: each net's frame, footprint and ball IDs):
  - retained (grains upslope of the net) and through, recounted in numpy from the rule
    (over the footprint: below or above the ball nearest in the net's plane; beside it: the
    side of the initial plane), exactly;
  - the anchor force |R|: minus the sum of the dumped forces on the net's clamped balls
    (its own atom type), to the CSV's 6 digits;
  - the peak anchor force is at least every sampled |R| and the final one;
and the scene does what it is built for: the flow reaches both nets, net 1 lets grains
past, and every grain is upslope of net 2 or through it (none past it around or over it)."""
import os

import numpy as np

from lsdemtest import check, near, finish, run_lmp
from avalanche_scene import EX, make_scene

NGRAINS, EVERY, ROWS = 100, 357, 22
print(make_scene(NGRAINS))
rc, log = run_lmp(os.path.join(EX, "in.avalanche"), np=2,
                  vars={"nets": 2, "nsteps": EVERY * ROWS, "vtkevery": 10})
for f in ("nets.csv", "nets_end.dump", "vtk/nets.pvd", "vtk/nets_end.pvd", "deposit.dump"):
    check(os.path.exists(f), "the deck did not write %s" % f)


def read_csv(path):
    text = [l.split() for l in open(path) if l.strip() and not l.startswith("#")]
    return [dict(zip(text[0], map(float, r))) for r in text[1:]]


def read_dump(path):
    lines = open(path).read().splitlines()
    i = next(k for k, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[i].split()[2:]
    return {int(l.split()[0]): dict(zip(cols, map(float, l.split()))) for l in lines[i + 1:]
            if l.strip()}


def read_net(path):
    """frame, footprint and [(ID, clamp)] of a net file"""
    net, balls, it = {}, [], iter(open(path).read().splitlines())
    for line in it:
        w = line.split("#")[0].split()
        if w and w[0] in ("origin", "e1", "e2", "size"):
            net[w[0]] = np.array(list(map(float, w[1:])))
        if w and w[0] == "balls":
            balls = [tuple(map(int, next(it).split())) for _ in range(int(w[1]))]
            break
    net["n"] = np.cross(net["e1"], net["e2"])
    net["balls"] = balls
    return net


def sides(net, balls, grains):
    """(before, through) by the rule, written out again"""
    ids = [b for b, _ in net["balls"]]
    xb = np.array([[balls[i][c] for c in "xyz"] for i in ids]) - net["origin"]
    ub, vb, hb = xb @ net["e1"], xb @ net["e2"], xb @ net["n"]
    before = through = 0
    for g in grains.values():
        d = np.array([g["x"], g["y"], g["z"]]) - net["origin"]
        u, v, h = d @ net["e1"], d @ net["e2"], d @ net["n"]
        if 0 <= u <= net["size"][0] and 0 <= v <= net["size"][1]:
            k = int(np.argmin((ub - u) ** 2 + (vb - v) ** 2))
            through += h < hb[k]
            before += h >= hb[k]
        else:
            before += h >= 0
    return before, through


csv = read_csv("nets.csv")
check(len(csv) == ROWS + 1, "nets.csv has %d rows, expected %d" % (len(csv), ROWS + 1))
end = csv[-1]
grains, balls = read_dump("deposit.dump"), read_dump("nets_end.dump")
check(len(grains) == NGRAINS, "deposit.dump: %d grains" % len(grains))
counts = {}
for n, clamp_type in ((1, 3), (2, 5)):
    net = read_net("net%d.net" % n)
    before, through = sides(net, balls, grains)
    counts[n] = (before, through)
    near(end["retained_%d" % n] * NGRAINS, before, atol=1e-6,
         msg="net %d: retained fraction x grains = the recount of grains upslope" % n)
    near(end["through_%d" % n], through, atol=0, msg="net %d: grains through = the recount" % n)
    clamped = [i for i, c in net["balls"] if c]
    check(all(int(balls[i]["type"]) == clamp_type for i in clamped),
          "net %d: its clamped balls are not all of type %d" % (n, clamp_type))
    r = -np.array([sum(balls[i][c] for i in clamped) for c in ("fx", "fy", "fz")])
    near(end["anchor_%d" % n], np.linalg.norm(r), rtol=1e-5,
         msg="net %d: anchor force = |sum of the dumped forces on its clamped balls|" % n)
    sampled = max(row["anchor_%d" % n] for row in csv)
    check(end["peak_anchor_%d" % n] >= sampled * (1 - 1e-6) > 0,
          "net %d: peak %g below the largest sampled |R| %g" % (n, end["peak_anchor_%d" % n],
                                                                sampled))
    print("net %d: %d grains upslope, %d through, anchor force %.6g (peak %.6g, largest sampled "
          "%.6g)" % (n, before, through, end["anchor_%d" % n], end["peak_anchor_%d" % n],
                     sampled))
check(sum(counts[2]) == NGRAINS, "grains past net 2 beside or over it: %s" % counts)
check(counts[1][0] < NGRAINS and end["peak_anchor_1"] > 0 and end["peak_anchor_2"] > 0,
      "the flow did not reach both nets: %s, peaks %g %g" % (counts, end["peak_anchor_1"],
                                                          end["peak_anchor_2"]))
finish()
