#!/usr/bin/env bash
# The avalanche timing goal of issue 34: 20,000 steps with at least 5,000 angular grains,
# without nets and with two (bench/README.md, "avalanche/timing.sh"). The example's valley
# made longer and wider (make_terrain.py: x from -60 to 40, y from -14 to 14, the U 11
# wide) and a slab of 5,000 grains (the example's three sizes and twelve shapes, 120
# nodes; pack box 34 x 16 x 10.3 laid on the slope from x = 3.5), the example's nets
# (make_nets.sh defaults); then in.avalanche for 20,000 steps on NP ranks, penalty, no
# ParaView frames after the first.
#   bench/avalanche/timing.sh OUT [NETS...]     (default NETS: 0 2; NP from the environment, 2)
# Writes OUT/scene (the inputs) and OUT/rN (log.lammps and took.txt of each run).
set -euo pipefail
out=$(mkdir -p "$1" && cd "$1" && pwd)
shift
runs=(0 2)
[ $# -gt 0 ] && runs=("$@")
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
ex=$top/examples/avalanche
build=${LSDEM_BUILD_DIR:-$top/build}
shape=$build/lsdem-shape
np=${NP:-2}
mkdir -p "$out/scene"
cd "$out/scene"
if [ ! -f source.data ]; then
  TERRAIN_ARGS="--x0 -60 --xtop 40 --ywidth 14 --yhalf 11" SLAB="34 16 10.3" \
    PLACE_ARGS="--yhalf 11 --box -64 44 -30 30 -6 40" LSDEM_SHAPE_TOOL=$shape \
    bash "$ex/make_scene.sh" . 5000
  LSDEM_SHAPE_TOOL=$shape bash "$ex/make_nets.sh" . 2 >/dev/null
fi
mpi=()
[ "$np" -gt 1 ] && mpi=(mpirun --allow-run-as-root --oversubscribe -np "$np")
for n in "${runs[@]}"; do
  mkdir -p "$out/r$n"
  cd "$out/r$n"
  for f in "$out"/scene/*; do ln -sf "$f" .; done
  start=$SECONDS
  "${mpi[@]}" "$build/lmp" -in "$ex/in.avalanche" -var nets "$n" -var dt 0.00028 \
    -var nsteps 20000 -var vtkevery 100 -var edge_x -60 -var edge_y 14 -screen none \
    -log log.lammps
  echo "nets $n: lmp took $((SECONDS - start)) s on $np rank(s)" | tee took.txt
  grep -E "^Loop time|^end:|^net [12]:" log.lammps
done
