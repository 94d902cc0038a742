#!/usr/bin/env bash
# The avalanche, impulse against penalty (issue 34; bench/README.md, "The avalanche, impulse
# against penalty"): examples/avalanche's flat run-out with 400 grains over several packings
# (make_scene.sh's SEED), without nets and with the example's two (make_nets.sh defaults),
# by the penalty method at its step and by the impulse method at MULTS times it. One rank
# each, one run at a time, under nice; the user time of every run is kept (time.txt), so
# that the speed-up is one of CPU time on a shared machine. Then table.py prints the table.
#   bench/avalanche/impulse.sh OUT [SEEDS] [MULTS] [NETS]
# defaults: SEEDS "7 8 9", MULTS "16 32 64", NETS "0 2". Writes OUT/sSEED/scene (the
# inputs) and OUT/sSEED/nN_penalty, OUT/sSEED/nN_xM (log.lammps, avalanche.csv,
# deposit.dump, nets.csv, time.txt, plot.txt: plot.py's summary); a run whose log ended is
# not run again. LSDEM_BUILD_DIR: the
# build with lmp and lsdem-shape (default build/).
set -euo pipefail
out=$(mkdir -p "$1" && cd "$1" && pwd)
seeds=${2:-7 8 9}
mults=${3:-16 32 64}
nets_list=${4:-0 2}
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
ex=$top/examples/avalanche
build=${LSDEM_BUILD_DIR:-$top/build}
py=/usr/bin/python3
for s in $seeds; do
  scene=$out/s$s/scene
  mkdir -p "$scene"
  if [ ! -f "$scene/net2.data" ]; then
    (cd "$scene" && LSDEM_SHAPE_TOOL=$build/lsdem-shape bash "$ex/make_scene.sh" . 400 0 "$s" >/dev/null &&
       LSDEM_SHAPE_TOOL=$build/lsdem-shape bash "$ex/make_nets.sh" . 2 >/dev/null)
  fi
  # run.sh's step and the terrain's edges
  dt=$(LSDEM_SHAPE_TOOL=$build/lsdem-shape bash "$ex/penalty_step.sh" "$scene/grains.lslib")
  edge_x=$(awk 'tolower($1) == "xllcenter" { print $2 }' "$scene/valley.asc")
  edge_y=$(awk 'tolower($1) == "yllcenter" { print -$2 }' "$scene/valley.asc")
  for n in $nets_list; do
    for m in penalty $mults; do
      if [ "$m" = penalty ]; then run=$out/s$s/n${n}_penalty args=(-var method penalty)
      else run=$out/s$s/n${n}_x$m args=(-var method impulse -var mult "$m"); fi
      mkdir -p "$run"
      cd "$run"
      # a run that ended is kept (run the script again with more MULTS or SEEDS)
      if [ -f log.lammps ] && tail -1 log.lammps | grep -q "^Total wall time"; then continue; fi
      for f in "$scene"/*; do ln -sf "$f" .; done
      rm -rf vtk
      nice /usr/bin/time -f "user %U sys %S wall %e" -o time.txt "$build/lmp" -in "$ex/in.avalanche" \
        "${args[@]}" -var dt "$dt" -var nets "$n" -var vtkevery 100 -var edge_x "$edge_x" \
        -var edge_y "$edge_y" -log log.lammps -screen none || echo "lmp failed" >> time.txt
      rm -rf vtk
      "$py" "$ex/plot.py" avalanche.csv deposit.dump valley.asc source.data avalanche.png \
        deposit.png > plot.txt 2>&1 || true
      echo "seed $s nets $n $m: $(tr '\n' ' ' < time.txt)"
    done
  done
done
"$py" "$top/bench/avalanche/table.py" "$out"
