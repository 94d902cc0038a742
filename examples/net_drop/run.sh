#!/usr/bin/env bash
# Grains falling into a flexible net: make the scene, run it and plot the net's kinetic
# energy. Called by `./lsdem example net_drop` (which sets LSDEM_LMP and LSDEM_SHAPE_TOOL).
# Environment: NP (2).
#   run.sh [prepare]   (prepare: make all.lslib and net.data, net.in, net.net only)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$here/../common.sh"
np=${NP:-2}
out=${OUT:-$here/out}
enter_out "$out"
LSDEM_SHAPE_TOOL=$shape bash "$here/make_scene.sh" .
[ "${1:-}" = prepare ] && exit 0
mpi_for "$np"
start=$SECONDS
"${mpi[@]}" "$lmp" -in "$here/in.net_drop" -log log.lammps -screen none
echo "lmp took $((SECONDS - start)) s"
grep "^Loop time" log.lammps
/usr/bin/python3 "$here/plot.py" net_drop.csv net_drop.png
echo "results: $out/log.lammps, $out/net_drop.csv, $out/net_drop.png, $out/vtk/net_drop.pvd (ParaView)"
