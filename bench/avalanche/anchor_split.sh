#!/usr/bin/env bash
# The nets' anchor force split into the bonds' pull and the grains' contacts on the clamped
# balls (issue 34; bench/README.md, "The avalanche, impulse against penalty"): for each seed
# of impulse.sh's scenes (OUT/sSEED/scene, made by impulse.sh), the two-net run again with
# the balls dumped at every step from t = T0 to T1 (in.avalanche -var netsteps -var netfrom),
# stopped at T1, then anchor_split.py, by the penalty method (its series also sampled every
# MULTS steps) and by the impulse method at MULTS times its step.
#   bench/avalanche/anchor_split.sh OUT [SEEDS] [MULTS] [T0] [T1]
# defaults: SEEDS "7 8 9", MULTS "16", T0 1.5, T1 3.5. Writes OUT/sSEED/split_penalty,
# OUT/sSEED/split_xM (split.txt: anchor_split.py's report; the dump is deleted).
set -euo pipefail
out=$(cd "$1" && pwd)
seeds=${2:-7 8 9}
mults=${3:-16}
t0=${4:-1.5}
t1=${5:-3.5}
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
ex=$top/examples/avalanche
build=${LSDEM_BUILD_DIR:-$top/build}
py=/usr/bin/python3
for s in $seeds; do
  scene=$out/s$s/scene
  dt=$(LSDEM_SHAPE_TOOL=$build/lsdem-shape bash "$ex/penalty_step.sh" "$scene/grains.lslib")
  for m in penalty $mults; do
    if [ "$m" = penalty ]; then run=$out/s$s/split_penalty args=(-var method penalty) step=$dt
    else run=$out/s$s/split_x$m args=(-var method impulse -var mult "$m") step=$("$py" -c "print($m * $dt)"); fi
    read -r nstop nwin < <("$py" -c "a = round($t0 / $step); b = round($t1 / $step); print(b, b - a)")
    mkdir -p "$run"
    cd "$run"
    for f in "$scene"/*; do ln -sf "$f" .; done
    nice "$build/lmp" -in "$ex/in.avalanche" "${args[@]}" -var dt "$dt" -var nets 2 \
      -var vtkevery 100 -var nsteps "$nstop" -var netsteps "$nwin" -var netfrom "$t0" \
      -log log.lammps -screen none
    rm -rf vtk
    # the penalty series also sampled at each impulse step's interval
    samples=()
    [ "$m" = penalty ] && read -ra samples <<< "$mults"
    "$py" "$top/bench/avalanche/anchor_split.py" . 2 "${samples[@]}" | tee split.txt
    rm -f nets_steps.dump
  done
done
