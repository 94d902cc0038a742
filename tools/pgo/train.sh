#!/usr/bin/env bash
# Training run for the profile-guided build of the core (./lsdem build does it; see
# src/PKG-LSDEM/core/CMakeLists.txt): an instrumented lmp runs the benchmark deck
# (bench/in.bench) on a small scene of the reference benchmark's kind, 512 ellipsoids of
# semi-axes 8-12 voxels on a lattice of spacing 19, first rattling and then packed
# (600 steps, about 5 s). Its profile goes where the instrumented build put it.
#   tools/pgo/train.sh LMP LSDEM_SHAPE
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
lmp=$1 shape=$2
work=$(mktemp -d /tmp/lsdem-pgo.XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$work"
nshapes=12
for i in $(seq "$nshapes"); do
  axes=$(/usr/bin/python3 -c "import random; r = random.Random($i); print(*('%.2f' % r.uniform(8, 12) for _ in range(3)))")
  # shellcheck disable=SC2086  # three semi-axes
  "$shape" analytic "part$i.lslib" ellipsoid $axes --spacing 1 --nodes 250 --margin 3 \
    --name "ellipsoid$i" >/dev/null 2>&1
done
"$shape" merge scene.lslib $(seq -f 'part%g.lslib' "$nshapes") >/dev/null
/usr/bin/python3 "$here/lattice.py" 8 "$nshapes" 19 7 >scene.data
"$lmp" -in "$here/../../bench/in.bench" -var steps 600 -var mode oneway -var seed 7 \
  -log log.train -screen none
grep -q '^Loop time' log.train
