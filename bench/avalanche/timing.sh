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
py=/usr/bin/python3
np=${NP:-2}
mkdir -p "$out/scene"
cd "$out/scene"
if [ ! -f source.data ]; then
  "$py" "$ex/make_terrain.py" valley.asc --x0 -60 --xtop 40 --ywidth 14 --yhalf 11
  "$shape" terrain valley.asc valley.band --spacing 0.2 --width 0.5 > band.txt
  parts=()
  s=21
  for d in 0.6 0.8 1.1; do
    h=$("$py" -c "print($d / 20)")
    "$shape" random "size$d.lslib" --count 4 --size "$d" --elongation 0.75 --flatness 0.75 \
      --angularity 0.15 --roughness 0.02 --nodes 120 --spacing "$h" --seed "$s" \
      --name "d$d" >/dev/null 2>&1
    parts+=("size$d.lslib")
    s=$((s + 1))
  done
  "$shape" merge grains.lslib "${parts[@]}" >/dev/null
  rm -f "${parts[@]}"
  "$shape" pack grains.lslib box.data --count 5000 --box 34 16 10.3 --density 2.65 \
    --weights 8,8,8,8,7,7,7,7,5,5,5,5 --seed 7 --max-tries 5000 --strict
  "$py" "$ex/place_source.py" box.data source.data --x0 3.5 --yhalf 11 --box -64 44 -30 30 -6 40
  rm -f box.data
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
