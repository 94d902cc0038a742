#!/usr/bin/env bash
# Rotating drum: make the scene, turn the drum and plot the dynamic angle of repose.
# Called by `./lsdem example drum` (which sets LSDEM_LMP and LSDEM_SHAPE_TOOL).
# Environment: NP (2), OMEGA (0.5 rad per time unit), SPIN (4 time units of turning).
#   run.sh [prepare]   (prepare: make grains.lslib and packed.data only)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$here/../common.sh"
np=${NP:-2} omega=${OMEGA:-0.5} spin=${SPIN:-4.0}
out=${OUT:-$here/out}
enter_out "$out"
LSDEM_SHAPE_TOOL=$shape bash "$here/make_scene.sh" .
[ "${1:-}" = prepare ] && exit 0
mpi_for "$np"
start=$SECONDS
"${mpi[@]}" "$lmp" -in "$here/in.drum" -var omega "$omega" -var spin "$spin" -log log.lammps \
  -screen none
echo "lmp took $((SECONDS - start)) s"
grep "^Loop time" log.lammps
/usr/bin/python3 "$here/plot.py" drum.csv drum.png
echo "results: $out/log.lammps, $out/drum.csv, $out/drum.png, $out/vtk/drum.pvd (ParaView)"
