#!/usr/bin/env bash
# Shear cell: make the scene, compress and shear the periodic box, plot.
# Called by `./lsdem example shear_cell` (which sets LSDEM_LMP and LSDEM_SHAPE_TOOL).
# Environment: NP (2), RATE (0.2 per time unit), GAMMA (1.2, the final shear strain).
#   run.sh [prepare]   (prepare: make grains.lslib and packed.data only)
# The scene: 300 angular grains (equivalent diameters 0.8 and 1.0, six random shapes each,
# 100 surface nodes) of density 1 placed at random, without overlap, in a cube of side 9
# (solid fraction 0.17; in.shear_cell compresses it).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$here/../common.sh"
rate=${RATE:-0.2} gamma=${GAMMA:-1.2}
enter_out "${OUT:-$here/out}"
sand_shapes small.lslib 0.8 0.04 21 d0.8
sand_shapes large.lslib 1.0 0.05 22 d1.0
"$shape" merge grains.lslib small.lslib large.lslib >/dev/null
rm -f small.lslib large.lslib
"$shape" pack grains.lslib packed.data --count 300 --box 9 9 9 --density 1.0 --seed 7 --gap 0.02
[ "${1:-}" = prepare ] && exit 0
mpi_for "${NP:-2}"
echo "running lmp on ${NP:-2} rank(s): compression, then shear to gamma $gamma" \
  "(progress in $PWD/log.lammps)"
start=$SECONDS
rm -rf fields vtk
"${mpi[@]}" "$lmp" -in "$here/in.shear_cell" -var rate "$rate" -var gamma "$gamma" \
  -log log.lammps -screen none
echo "lmp took $((SECONDS - start)) s"
grep "^Loop time" log.lammps
/usr/bin/python3 "$here/plot.py" shear.csv fields/shear.pvd shear.png
echo "results: $PWD/log.lammps, shear.csv, shear.png, fields/shear.pvd and vtk/grains.pvd" \
  "(ParaView 5.10 or later: the fields' grid is skewed with the box)"
