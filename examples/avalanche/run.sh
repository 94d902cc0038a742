#!/usr/bin/env bash
# Rock avalanche down a synthetic valley: make the valley and the source, run the avalanche
# until it is at rest, and plot it (front, centroid, speed, H/L, deposit thickness).
# Called by `./lsdem example avalanche` (which sets LSDEM_LMP and LSDEM_SHAPE_TOOL).
# Environment: NGRAINS (400), RUNOUT (inclination of the run-out plane, 0 or 3 degrees; 0),
# VALLEY (the valley's cross-section, U or V; U), SEED (the packing's, 7), METHOD (penalty
# or impulse: MULT times the penalty step, 16), NP (2),
# TIME (simulated time at most, 10: the run stops once the grains are at rest), VTK
# (simulated time between ParaView frames of the grains, 1.0), OUT (output folder, out/),
# NETS (0; 1 or 2: protection nets across the run-out, make_nets.sh, whose optional
# arguments X1 X2 H1 H2 K C NET_ARGS passes on).
#   run.sh [prepare]   (prepare: make valley.asc, valley.band, grains.lslib, source.data only)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$here/../common.sh"
py=/usr/bin/python3
n=${NGRAINS:-400} runout=${RUNOUT:-0} seed=${SEED:-7} method=${METHOD:-penalty} np=${NP:-2}
t_end=${TIME:-10} vtk=${VTK:-1.0} nets=${NETS:-0} mult=${MULT:-16}
out=${OUT:-$here/out}
case "$method" in penalty|impulse) ;; *) echo "run.sh: METHOD must be penalty or impulse, not '$method'" >&2; exit 2 ;; esac
enter_out "$out"
LSDEM_SHAPE_TOOL=$shape bash "$here/make_scene.sh" . "$n" "$runout" "$seed"
# shellcheck disable=SC2086 # NET_ARGS: words on purpose
[ "$nets" != 0 ] && LSDEM_SHAPE_TOOL=$shape bash "$here/make_nets.sh" . "$nets" ${NET_ARGS:-}
# the penalty step (penalty_step.sh: 0.2 sqrt(m_min / (5 kn)))
dt=$(LSDEM_SHAPE_TOOL=$shape bash "$here/penalty_step.sh" grains.lslib)
echo "dt $dt"
[ "${1:-}" = prepare ] && exit 0
# the terrain's west end and half-width, for the deck's count of grains near its edges
edge_x=$(awk 'tolower($1) == "xllcenter" { print $2 }' valley.asc)
edge_y=$(awk 'tolower($1) == "yllcenter" { print -$2 }' valley.asc)
mpi_for "$np"
echo "avalanche: $method, up to $t_end time units, $np rank(s) (log in $out/log.lammps)"
rm -rf vtk
start=$SECONDS
"${mpi[@]}" "$lmp" -in "$here/in.avalanche" -var method "$method" -var dt "$dt" \
  -var time "$t_end" -var vtkevery "$vtk" -var edge_x "$edge_x" -var edge_y "$edge_y" \
  -var nets "$nets" -var mult "$mult" \
  -log log.lammps -screen none
echo "lmp took $((SECONDS - start)) s"
grep -E "^Loop time|^end:|^net [12]:" log.lammps
"$py" "$here/plot.py" avalanche.csv deposit.dump valley.asc source.data avalanche.png deposit.png
echo "results: $out/log.lammps, avalanche.csv, avalanche.png, deposit.png, deposit.dump," \
  "avalanche_end.data, vtk/grains.pvd, vtk/deposit.pvd, vtk/terrain.pvd (ParaView)" \
  "$([ "$nets" != 0 ] && echo ", nets.csv, nets.png, nets_end.dump, vtk/nets.pvd, vtk/nets_end.pvd")"
