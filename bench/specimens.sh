#!/usr/bin/env bash
# The report's three kinds of specimen side by side (PEER 2022/06 §3.4.5, Figures 3.12-3.13):
# a dense and a loose specimen of random angular grains and a dense specimen of equal-volume
# spheres, each prepared by examples/triaxial/in.prepare (frictionless compaction for the dense
# ones, compaction at the test's friction for the loose one), consolidated to sigma_c and
# sheared to 16 % axial strain (in.triaxial), then compared with the report's figures
# (examples/triaxial/compare.py: specimens.png, specimens.json, and a table on stdout).
#
#   bench/specimens.sh [OUTDIR]          (default bench/out/specimens; after ./lsdem build)
#   NGRAINS=2000 NSHAPES=100 NP=1 MU=0.6 ONLY="dense loose spheres" (which runs) EPSMAX=0.16
#   ONLY may also name the like-for-like controls: spheres_loose (equal-volume spheres packed
#   from friction 0.6 to the mould void ratio E_SPHERES, default 0.75, so that e0 in the
#   membrane is near the report's 0.60) and loose_round (loose, rounder shapes of 250 nodes,
#   ANGULARITY 0.05, like the report's eroded low-resolution avatars)
#
# A benchmark, not a test: about an hour per specimen of 2,000 grains on one core. Each run's
# folder keeps run.sh's outputs (triaxial.csv, logs, voids.txt, plots) and time.txt.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
top=$here/..
build=${LSDEM_BUILD_DIR:-$top/build}
export LSDEM_LMP=${LSDEM_LMP:-$build/lmp} LSDEM_SHAPE_TOOL=${LSDEM_SHAPE_TOOL:-$build/lsdem-shape}
out=$(mkdir -p "${1:-$here/out/specimens}" && cd "${1:-$here/out/specimens}" && pwd)
export NGRAINS=${NGRAINS:-2000} NSHAPES=${NSHAPES:-100} NP=${NP:-1}
only=${ONLY:-dense loose spheres}
for name in $only; do
  case "$name" in
    dense) env=(DENSITY=dense SHAPES=angular) ;;
    loose) env=(DENSITY=loose SHAPES=angular) ;;
    spheres) env=(DENSITY=dense SHAPES=spheres) ;;
    spheres_loose) env=(SHAPES=spheres E_TARGET="${E_SPHERES:-0.75}") ;;
    loose_round) env=(DENSITY=loose SHAPES=angular ANGULARITY=0.05 NODES=250) ;;
    *) echo "specimens.sh: ONLY takes dense, loose, spheres, spheres_loose, loose_round" >&2; exit 2 ;;
  esac
  echo "== $name: ${env[*]} NGRAINS=$NGRAINS NSHAPES=$NSHAPES NP=$NP (log $out/$name/run.log)"
  mkdir -p "$out/$name"
  t0=$(date +%s)
  env "${env[@]}" OUT="$out/$name" bash "$top/examples/triaxial/run.sh" >"$out/$name/run.log" 2>&1
  t1=$(date +%s)
  echo "wall $((t1 - t0)) s on $NP rank(s), $(date -u +%F)" > "$out/$name/time.txt"
  grep -E '^(packed|void ratio|CONSOLIDATED|SHEARED|peak)' "$out/$name/run.log" || true
  cat "$out/$name/time.txt"
done
args=()
for name in dense loose spheres spheres_loose loose_round; do
  [ -f "$out/$name/triaxial.csv" ] || continue
  case "$name" in
    dense) label="dense angular" ;;
    loose) label="loose angular" ;;
    spheres) label="dense spheres" ;;
    spheres_loose) label="loose spheres" ;;
    loose_round) label="loose rounder (250 nodes)" ;;
  esac
  args+=("$label=$out/$name/triaxial.csv")
done
/usr/bin/python3 "$top/examples/triaxial/compare.py" "$out/specimens.png" "${args[@]}" \
  --title "LSDEM triaxial specimens, $NGRAINS grains, mu ${MU:-0.6}, against PEER 2022/06 Figs 3.12-3.13"
