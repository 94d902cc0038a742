"""Scenes for the LSDEM-LIGGGHTS comparison (bench/liggghts/run.sh): the same spheres, in the
same places with the same velocities, written once as an LSDEM data file (analytic spheres of
a shape library, atom_style lsdem) and once as a LIGGGHTS data file (atom_style granular).

Usage: scenes.py OUTDIR SHAPE_TOOL [--grains N] [--seed S]

Writes to OUTDIR:
  spheres.lslib                     analytic spheres of the radii below (shape-IDs 1, 2, 3)
  collide_<case>.data / .lg.data    two spheres of radius R1 about to collide (cases below)
  settle.data / settle.lg.data      N spheres of the three radii on a jittered lattice above
                                    the floor of a BOX x BOX box, random velocities
  params.txt                        the parameters both codes' decks read (-var name value)

Units: SI. The contact parameters are chosen so that the two codes' laws coincide: a linear
normal spring kn and absolute viscous damping cn (force = kn d - cn v_n, never attractive),
a tangential spring ks with history capped at mu times the normal force, no tangential
damping; the spheres rotate (LSDEM's fix nve/lsdem, LIGGGHTS's fix nve/sphere), both codes
taking the contact point in the middle of the overlap, R - d/2 from each centre."""
import math
import os
import random
import subprocess
import sys

RADII = (1.0e-3, 1.25e-3, 1.5e-3)  # m
DENSITY = 2500.0  # kg/m^3
KN, KS, MU = 2000.0, 1600.0, 0.5  # N/m, N/m, -
RESTITUTION = 0.5  # normal restitution aimed at for two R1 spheres (sets cn)
BOX = 0.02  # m: the settling box's footprint (BOX x BOX), its walls at 0 and BOX
GRAVITY = 9.81  # m/s^2


def mass(r):
    return DENSITY * 4.0 / 3.0 * math.pi * r ** 3


def damping_for_restitution(e, m_eff, kn):
    """cn of a linear spring-dashpot whose free (attractive-allowed) collision has
    restitution e: e = exp(-zeta pi / sqrt(1 - zeta^2)), cn = 2 zeta sqrt(kn m_eff)."""
    le = math.log(e)
    zeta = -le / math.sqrt(math.pi ** 2 + le ** 2)
    return 2.0 * zeta * math.sqrt(kn * m_eff)


CN = damping_for_restitution(RESTITUTION, mass(RADII[0]) / 2.0, KN)
# time step: 1/50 of the R1-R1 contact time pi sqrt(m_eff / kn); the binary collisions use
# a quarter of it (their restitution's time error is then about 0.3 %, against 1 % at DT)
DT = math.pi * math.sqrt(mass(RADII[0]) / 2.0 / KN) / 50.0
DT_COLLIDE = DT / 4.0

# Collision cases: name -> (cn, mu, relative velocity of sphere 1 towards sphere 2: normal,
# tangential). "oblique" slides from its first steps (tangential speed 5 V0, the spring reaches
# the cap mu kn d within 2 of the 50 steps of contact), so its tangential velocity change is
# mu times the normal one (to about 2 %: the normal turns by 0.04 rad while they slide).
V0 = 0.1  # m/s
CASES = {
    "elastic": (0.0, 0.0, V0, 0.0),
    "damped": (CN, 0.0, V0, 0.0),
    "oblique": (CN, MU, V0, 5.0 * V0),
}


def lsdem_atom(i, s, x):
    """An Atoms line of atom_style lsdem: id type shape-ID density x y z quaternion."""
    return "%d 1 %d %r %r %r %r 1 0 0 0" % ((i, s + 1, DENSITY) + tuple(x))


def liggghts_atom(i, s, x):
    """An Atoms line of LIGGGHTS's atom_style granular: id type diameter density x y z."""
    return "%d 1 %r %r %r %r %r" % ((i, 2.0 * RADII[s], DENSITY) + tuple(x))


def write_data(path, box, grains, title, atoms_header, atom_line):
    """grains: (shape index 0-based, x, v) -> a data file with atom_line's Atoms lines and
    Velocities lines (no spin)."""
    lines = [title, "", "%d atoms" % len(grains), "1 atom types", "",
             "%r %r xlo xhi" % box[0:2], "%r %r ylo yhi" % box[2:4],
             "%r %r zlo zhi" % box[4:6], "", atoms_header, ""]
    lines += [atom_line(i, s, x) for i, (s, x, _) in enumerate(grains, 1)]
    lines += ["", "Velocities", ""]
    lines += ["%d %r %r %r 0 0 0" % ((i,) + tuple(v)) for i, (_, _, v) in enumerate(grains, 1)]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def write_both(outdir, name, box, grains):
    write_data(os.path.join(outdir, name + ".data"), box, grains, "LSDEM " + name,
               "Atoms # lsdem", lsdem_atom)
    write_data(os.path.join(outdir, name + ".lg.data"), box, grains, "LIGGGHTS " + name,
               "Atoms", liggghts_atom)


def collision_grains(vn, vt):
    """Two R1 spheres touching along x, closing at vn (sphere 1 also moving at vt along y,
    sphere 2 against it): half of each velocity on each sphere, so the centre of mass is at
    rest; the contact normal is x when the collision starts."""
    r = RADII[0]
    return [(0, (-r, 0.0, 0.0), (vn / 2, vt / 2, 0.0)),
            (0, (r, 0.0, 0.0), (-vn / 2, -vt / 2, 0.0))]


def settle_grains(n, seed):
    """n spheres, radius drawn from RADII, on a lattice of pitch 2.2 R3 inside the box's
    footprint, each jittered by up to 0.05 R3, with random velocities up to 0.05 m/s."""
    rng = random.Random(seed)
    pitch = 2.2 * RADII[-1]
    per_row = int((BOX - 2 * RADII[-1]) / pitch) + 1
    grains = []
    k = 0
    while len(grains) < n:
        ix, iy, iz = k % per_row, (k // per_row) % per_row, k // (per_row * per_row)
        k += 1
        x = [RADII[-1] * 1.1 + pitch * ix, RADII[-1] * 1.1 + pitch * iy,
             RADII[-1] * 1.1 + pitch * iz]
        x = [c + rng.uniform(-0.05, 0.05) * RADII[-1] for c in x]
        v = [rng.uniform(-0.05, 0.05) for _ in range(3)]
        grains.append((rng.randrange(len(RADII)), tuple(x), tuple(v)))
    return grains


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    outdir, tool = argv[1], argv[2]
    opts = dict(zip(argv[3::2], argv[4::2]))
    n = int(opts.get("--grains", 500))
    seed = int(opts.get("--seed", 1))
    os.makedirs(outdir, exist_ok=True)
    parts = []
    for i, r in enumerate(RADII):
        part = os.path.join(outdir, "r%d.lslib" % i)
        subprocess.run([tool, "analytic", part, "sphere", repr(r), "--analytic",
                        "--name", "r%d" % i], check=True, stdout=subprocess.DEVNULL)
        parts.append(part)
    subprocess.run([tool, "merge", os.path.join(outdir, "spheres.lslib")] + parts, check=True,
                   stdout=subprocess.DEVNULL)
    for part in parts:
        os.remove(part)

    cbox = (-0.01, 0.01, -0.01, 0.01, -0.01, 0.01)
    for name, (_, _, vn, vt) in CASES.items():
        write_both(outdir, "collide_" + name, cbox, collision_grains(vn, vt))
    grains = settle_grains(n, seed)
    top = max(x[2] for _, x, _ in grains) + 2 * RADII[-1]
    write_both(outdir, "settle", (0.0, BOX, 0.0, BOX, 0.0, top), grains)

    with open(os.path.join(outdir, "params.txt"), "w") as f:
        f.write("kn %r\nks %r\nmu %r\ncn %r\ndt %r\ndt_collide %r\nbox %r\ngravity %r\nv0 %r\n"
                % (KN, KS, MU, CN, DT, DT_COLLIDE, BOX, GRAVITY, V0))
        for name, (cn, mu, vn, vt) in CASES.items():
            f.write("case %s %r %r %r %r\n" % (name, cn, mu, vn, vt))
        f.write("mass1 %r\ngrains %d\n" % (mass(RADII[0]), n))


if __name__ == "__main__":
    main(sys.argv)
