"""The membrane is a net (issue #34): bond_style lsdem/membrane is bond_style lsdem/net's
force call with a tangential spring added, so with its tangential stiffness Ksbb = 0 a
membrane bond acts as the net bond of the same K and r0. Eight dimers in arbitrary
directions, twice: one copy bonded by lsdem/membrane (Ksbb 0, rest offsets far from the
geometry), the other, 64 higher (exact: the coordinates are dyadic), by lsdem/net, both
through bond_style hybrid in one run 0:
1. each atom's bond energy (compute pe/atom bond) is the same in both copies, bit for bit;
2. each atom's force is the same once the membrane's is rounded to the net's quantum
   (the net rounds every bond force to 2^(ilogb(K r0) + 1 - 40), ties to even; the
   membrane keeps its forces unrounded, as it always did), bit for bit;
3. with Ksbb = 3 the membrane copy's forces differ from the net's by more than the quantum
   (the deck does compare a membrane with a net: the tangential spring is there)."""
import math
import random

from lsdemtest import run_lmp, check, finish

K, R0, SHIFT = 2.5, 1.1, 64.0
rng = random.Random(7)


def dyadic(lo, hi):
    """A number in [lo, hi) with 10 bits after the point (sums and shifts stay exact)."""
    return math.floor(rng.uniform(lo, hi) * 1024) / 1024


pairs = []
for n in range(8):
    a = [dyadic(-6, 6), dyadic(-6, 6), dyadic(0, 8)]
    pairs.append((a, [a[k] + dyadic(-1, 1) for k in range(3)]))

atoms, bonds = [], []
for copy in range(2):    # bond type 1: membrane, 2: net
    for a, b in pairs:
        for p in (a, b):
            atoms.append((p[0], p[1], p[2] + copy * SHIFT))
        bonds.append((copy + 1, len(atoms) - 1, len(atoms)))
data = ["membrane and net dimers", "", "%d atoms" % len(atoms), "1 atom types",
        "%d bonds" % len(bonds), "2 bond types", "", "-20 20 xlo xhi", "-20 20 ylo yhi",
        "-10 90 zlo zhi", "", "Masses", "", "1 1.0", "", "Atoms # bond", ""]
data += ["%d %d 1 %.17g %.17g %.17g" % (i + 1, i // 2 + 1, *x) for i, x in enumerate(atoms)]
data += ["", "Bonds", ""]
data += ["%d %d %d %d" % (n + 1, *b) for n, b in enumerate(bonds)]
open("dimers.data", "w").write("\n".join(data) + "\n")

DECK = """units lj
atom_style bond
boundary f f f
read_data ../dimers.data
pair_style zero 1.0
pair_coeff * *
bond_style hybrid lsdem/membrane lsdem/net
bond_coeff 1 lsdem/membrane %g ${ks} %g 0.3 -0.7
bond_coeff 2 lsdem/net %g %g
compute eb all pe/atom bond
dump d all custom 1 forces.dump id fx fy fz c_eb
dump_modify d format float %%.17g sort id
run 0
""" % (K, R0, K, R0)


def forces(ks):
    """{id: (fx, fy, fz, bond energy)} of run 0 with the membrane's Ksbb = ks."""
    run_lmp(DECK, vars={"ks": ks}, cwd="ks%g" % ks)
    lines = open("ks%g/forces.dump" % ks).read().split("ITEM: ATOMS")[1].splitlines()[1:]
    return {int(l.split()[0]): tuple(map(float, l.split()[1:])) for l in lines}


def quantize(x, q):
    return round(x / q) * q    # x / q and back are exact (q a power of two); round: to even


q = math.ldexp(1.0, math.frexp(K * R0)[1] - 1 + 1 - 40)    # ilogb(F) = frexp exponent - 1
n = len(atoms) // 2
same = forces(0)
for i in range(1, n + 1):
    m, net = same[i], same[i + n]
    check(m[3] == net[3], "atom %d: membrane bond energy %r, net %r" % (i, m[3], net[3]))
    check(all(quantize(m[k], q) == net[k] for k in range(3)),
          "atom %d: membrane force %r (rounded to %g: %r), net force %r"
          % (i, m[:3], q, [quantize(m[k], q) for k in range(3)], net[:3]))
    check(any(m[k] != 0.0 for k in range(3)), "atom %d: no force (dimer at rest?)" % i)
shear = forces(3)
apart = sum(max(abs(shear[i][k] - shear[i + n][k]) for k in range(3)) > q
            for i in range(1, n + 1))
check(apart == n, "Ksbb = 3: %d of %d membrane atoms differ from the net's" % (apart, n))
finish()
