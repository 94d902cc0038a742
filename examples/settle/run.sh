#!/usr/bin/env bash
# Settle example: make the shape library and the grains, run lmp, plot.
# Called by `./lsdem example settle` (which sets LSDEM_LMP and LSDEM_SHAPE_TOOL); NP=2 by default.
# `run.sh prepare` makes the shapes and grains only (examples/python drives the run itself);
# OUT sets the output folder (default out/).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$here/../common.sh"
np=${NP:-2}
n=${NGRAINS:-300}
out=${OUT:-$here/out}
enter_out "$out"

# four angular shapes, 1-2 mm: two cuboids, a plate and a short cylinder, 200 nodes each
rm -f grains.lslib part*.lslib
"$shape" analytic part1.lslib box 0.0010 0.0007 0.0005 --nodes 200 --name cuboid >/dev/null
"$shape" analytic part2.lslib box 0.0008 0.0008 0.0006 --nodes 200 --name block >/dev/null
"$shape" analytic part3.lslib box 0.0010 0.0009 0.0003 --nodes 200 --name plate >/dev/null
"$shape" analytic part4.lslib cylinder 0.0007 0.0006 --nodes 200 --name cylinder >/dev/null
"$shape" merge grains.lslib part1.lslib part2.lslib part3.lslib part4.lslib >/dev/null
rm -f part*.lslib
/usr/bin/python3 "$here/make_grains.py" "$n" 4 0.0028 8 8 0.024 0.024 0.03 2024 > data.settle
[ "${1:-}" = prepare ] && exit 0

mpi_for "$np"
echo "running lmp on $np rank(s): $n grains, ${NSTEPS:-20000} steps (progress in $out/log.lammps)"
start=$SECONDS
"${mpi[@]}" "$lmp" -in "$here/in.settle" -var nsteps "${NSTEPS:-20000}" -log log.lammps -echo none -screen none
echo "lmp took $((SECONDS - start)) s"
grep -A3 "^Loop time" log.lammps | head -n 1
/usr/bin/python3 "$here/plot.py" settle.csv settle.png "$n"
"$shape" render grains.lslib dump.settle render.png --view iso >/dev/null  # last frame, no ParaView needed
echo "results: $out/settle.csv, $out/settle.png, $out/render.png, $out/dump.settle (ParaView/OVITO), settle.restart"
