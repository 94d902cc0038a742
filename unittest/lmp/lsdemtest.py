"""lsdemtest -- helpers for the lmp-level tests (input decks run through the real lmp).

Each test is a script test_<name>.py in this folder, run by CTest in its own empty work
folder, with these environment variables set by CMake:
  LSDEM_LMP         the lmp binary built with PKG-LSDEM
  LSDEM_SHAPE_TOOL  the lsdem-shape command-line tool
  LSDEM_MPIEXEC     mpirun (Open MPI), run as root if need be
  LSDEM_LAMMPS_VERSION  the LAMMPS release lmp was built from, YYYYMMDD (20210929 or
                    20250204): LAMMPS_VERSION, for the few checks of LAMMPS's own messages
                    that differ between the two
A test runs lmp as often as it needs, checks the results against independent expectations
with check()/near(), and ends with finish(), which prints "N passed, M failed" and exits
non-zero on any failure.
"""
import math
import os
import re
import subprocess
import sys

LMP = os.environ.get("LSDEM_LMP", "lmp")
SHAPE_TOOL = os.environ.get("LSDEM_SHAPE_TOOL", "lsdem-shape")
MPIEXEC = os.environ.get("LSDEM_MPIEXEC", "mpirun")
LAMMPS_VERSION = int(os.environ.get("LSDEM_LAMMPS_VERSION", "20210929"))
HERE = os.path.dirname(os.path.abspath(__file__))

_passed = 0
_failed = 0


def mpi_prefix(np):
    """The command prefix that starts np ranks (root-safe, oversubscription allowed)."""
    if np <= 1:
        return []
    return [MPIEXEC, "--allow-run-as-root", "--oversubscribe", "-np", str(np)]


def run_lmp(deck, np=1, vars=None, cwd=None, expect_fail=False, log="log.lammps", timeout=600,
            args=None):
    """Run lmp on `deck` (input text, or the path of an existing input file), with extra
    command-line arguments args (e.g. -sf omp -pk omp 2).

    Returns (returncode, log_text). The log is also left in cwd/log. When expect_fail is
    False a non-zero exit is recorded as a failed check (with the tail of the output)."""
    cwd = os.path.abspath(cwd or os.getcwd())
    os.makedirs(cwd, exist_ok=True)
    if "\n" not in deck and os.path.exists(deck):
        infile = os.path.abspath(deck)
    else:
        infile = os.path.join(cwd, "in.deck")
        with open(infile, "w") as f:
            f.write(deck)
    cmd = mpi_prefix(np) + [LMP, "-in", infile, "-log", log, "-screen", "none"]
    for k, v in (vars or {}).items():
        cmd += ["-var", str(k), str(v)]
    cmd += [str(a) for a in (args or [])]
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       timeout=timeout, text=True)
    logpath = os.path.join(cwd, log)
    text = open(logpath).read() if os.path.exists(logpath) else ""
    if p.returncode != 0 and not expect_fail:
        check(False, "lmp (np=%d) exited with %d:\n%s\n--- log tail ---\n%s"
              % (np, p.returncode, p.stdout[-3000:], text[-3000:]))
    if expect_fail:
        text = text + "\n" + p.stdout
    return p.returncode, text


def shape_tool(*args, cwd=None):
    """Run lsdem-shape with args; a failure is a failed check. Returns stdout."""
    p = subprocess.run([SHAPE_TOOL] + [str(a) for a in args], cwd=cwd or os.getcwd(),
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    check(p.returncode == 0, "lsdem-shape %s failed (%d): %s" % (" ".join(map(str, args)),
                                                                 p.returncode, p.stdout))
    return p.stdout


def tan_scene(root, which, positions, rotations, box=None):
    """A scene folder in the Kawamoto/Tan layout (what lsdem-import-tan and bench/run.sh
    read) from two analytic shapes in voxel units, a = ellipsoid 6 5 4 and b = sphere 5
    (100 nodes each): grain i's Morphologies/morph_<i>.dat links to shapes/<which[i-1]>.dat,
    positions and rotations (unit quaternions in the file's x y z w order) go to InitState,
    and box (X, Y, Z), when given, to geometry.txt."""
    shape_tool("analytic", "a.lslib", "ellipsoid", 6, 5, 4, "--spacing", 1, "--nodes", 100)
    shape_tool("analytic", "b.lslib", "sphere", 5, "--spacing", 1, "--nodes", 100)
    os.makedirs(os.path.join(root, "Morphologies", "shapes"), exist_ok=True)
    os.makedirs(os.path.join(root, "InitState"), exist_ok=True)
    for w in "ab":
        shape_tool("to-morph", w + ".lslib", 0, os.path.join(root, "Morphologies", "shapes",
                                                              w + ".dat"))
    for i, w in enumerate(which):
        link = os.path.join(root, "Morphologies", "morph_%d.dat" % (i + 1))
        if not os.path.lexists(link):
            os.symlink("shapes/%s.dat" % w, link)
    with open(os.path.join(root, "InitState", "positions_t.dat"), "w") as f:
        f.write("".join("%r %r %r\n" % tuple(p) for p in positions))
    with open(os.path.join(root, "InitState", "rotations_t.dat"), "w") as f:
        f.write("".join("%r %r %r %r\n" % tuple(q) for q in rotations))
    if box:
        with open(os.path.join(root, "geometry.txt"), "w") as f:
            f.write("box_x %r\nbox_y %r\nbox_z %r\n" % tuple(box))


def thermo(log_text, run_index=-1):
    """Thermo rows of one run (default: the last) as a list of dicts of floats; warnings,
    the examples' PROGRESS lines and fix field/lsdem's line per file written, printed
    between rows, are passed over."""
    runs = []
    lines = log_text.splitlines()
    i = 0
    while i < len(lines):
        if lines[i].split()[:1] == ["Step"]:
            header = lines[i].split()
            rows = []
            i += 1
            while i < len(lines):
                parts = lines[i].split()
                if parts[:1] in (["WARNING:"], ["PROGRESS"], ["fix"]):  # printed between rows
                    i += 1
                    continue
                if len(parts) != len(header):
                    break
                try:
                    rows.append(dict(zip(header, map(float, parts))))
                except ValueError:
                    break
                i += 1
            runs.append(rows)
        else:
            i += 1
    if not runs:
        return []
    return runs[run_index]


def check(cond, msg):
    """Record one assertion; print the message when it fails."""
    global _passed, _failed
    if cond:
        _passed += 1
    else:
        _failed += 1
        print("FAIL:", msg, flush=True)
    return bool(cond)


def near(a, b, rtol=0.0, atol=0.0, msg=""):
    """check |a - b| <= atol + rtol*|b|."""
    ok = (math.isfinite(a) and math.isfinite(b) and abs(a - b) <= atol + rtol * abs(b))
    return check(ok, "%s: %.17g vs %.17g (|diff| %.3g, rtol %g, atol %g)"
                 % (msg, a, b, abs(a - b) if math.isfinite(a - b) else float("nan"), rtol, atol))


def script_refuses(script, args, env, message, outdir):
    """A benchmark script given bad `args` stops with exit code 2, says `message` on standard
    error and writes nothing (no `outdir`)."""
    p = subprocess.run(["bash", script, outdir] + list(args), env=env, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True, timeout=60)
    check(p.returncode == 2 and message in p.stderr and not os.path.exists(outdir),
          "%s refused: exit %d, %s" % (" ".join(args), p.returncode, p.stderr[-500:]))


def finish():
    print("%d passed, %d failed" % (_passed, _failed))
    sys.exit(1 if _failed else 0)
