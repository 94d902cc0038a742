"""lmp -h of this build lists the LSDEM package and every style it defines, and names the
LAMMPS version it was built against (the tree's src/version.h, given by CMake as
LSDEM_LAMMPS_VERSION, YYYYMMDD). The expected styles are read from the package's own headers
(the AtomStyle(...)/PairStyle(...) lines of src/PKG-LSDEM and its OPENMP folder), so a new
style is checked without editing this test; internal styles (upper-case names such as
LSDEM_HISTORY) are hidden by lmp -h and skipped."""
import glob
import os
import re
import subprocess
import time

from lsdemtest import LAMMPS_VERSION, LMP, check, finish

HERE = os.path.dirname(os.path.abspath(__file__))
PKG = os.path.join(HERE, "..", "..", "src", "PKG-LSDEM")
# style macro -> the heading of its list in lmp -h
SECTIONS = {"AtomStyle": "Atom styles", "PairStyle": "Pair styles", "BondStyle": "Bond styles",
            "FixStyle": "Fix styles", "ComputeStyle": "Compute styles",
            "DumpStyle": "Dump styles", "CommandStyle": "Command styles"}

p = subprocess.run([LMP, "-h"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                   timeout=60)
out = p.stdout
check(p.returncode == 0, "lmp -h exited %d: %s" % (p.returncode, out[-2000:]))

# the version line: "Large-scale Atomic/Molecular Massively Parallel Simulator - 4 Feb 2025"
m = re.search(r"Massively Parallel Simulator - (\d+ \w+ \d{4})(?: - (.*))?", out)
version = m.group(1) if m else None
print("lmp -h: built against LAMMPS %s%s" % (version, " (%s)" % m.group(2) if m and m.group(2)
                                                  else ""))
check(version is not None, "lmp -h names a LAMMPS version: %s" % out[:500])
if version:
    number = int(time.strftime("%Y%m%d", time.strptime(version, "%d %b %Y")))
    check(number == LAMMPS_VERSION, "lmp -h says LAMMPS %s, the tree built is %d"
          % (version, LAMMPS_VERSION))

# installed packages: the paragraph after "Installed packages:"
m = re.search(r"Installed packages:\s*\n\s*\n(.*?)\n\s*\n", out, re.S)
packages = m.group(1).split() if m else []
print("installed packages:", " ".join(packages))
check("LSDEM" in packages, "LSDEM among the installed packages: %r" % packages)


def listed(heading):
    """The names under '* <heading>' (up to the next '* ' heading)."""
    m = re.search(r"^\* %s:?\s*\n(.*?)(?=^\* |\Z)" % re.escape(heading), out, re.S | re.M)
    return set(m.group(1).split()) if m else set()


expected = {}
for h in glob.glob(os.path.join(PKG, "*.h")) + glob.glob(os.path.join(PKG, "OPENMP", "*.h")):
    for macro, name in re.findall(r"^(\w+Style)\(([^,]+),", open(h).read(), re.M):
        if macro in SECTIONS and not name[0].isupper():
            expected.setdefault(SECTIONS[macro], set()).add(name)
check(len(expected.get("Pair styles", ())) >= 1, "style macros found in %s" % PKG)
for heading, names in sorted(expected.items()):
    have = listed(heading)
    missing = sorted(names - have)
    check(not missing, "lmp -h %s lacks %s" % (heading.lower(), " ".join(missing)))
    print("%s: %s" % (heading.lower(), " ".join(sorted(names))))
# the styles the README and the examples lean on, by name
for heading, name in (("Atom styles", "lsdem"), ("Pair styles", "lsdem"),
                      ("Fix styles", "nve/lsdem"), ("Fix styles", "wall/lsdem"),
                      ("Compute styles", "stress/lsdem"), ("Dump styles", "lsdem/vtk")):
    check(name in listed(heading), "lmp -h %s lists %s" % (heading.lower(), name))
finish()
