#!/usr/bin/env bash
# How well lsdem-segment finds the grains of synthetic scans made from known grains
# (tools/synthetic_scan.py: touching bumpy ellipsoids, blur 1 voxel, noise 0.1 and a
# grey-level gradient of 0.3 of the contrast along z), for the default pipeline and with
# one step left out. Prints one row per scan and variant: recovered one-to-one, grains
# found, mean |volume error| and mean volume error of the recovered grains.
#   bash bench/segment.sh [OUTDIR]     (SIZE=128 GRAINS=260 SEEDS="1 2 3")
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${LSDEM_BUILD_DIR:-$top/build}
out=${1:-bench-segment}
size=${SIZE:-128}
mkdir -p "$out"
cd "$out"
export LSDEM_SHAPE_TOOL=$build/lsdem-shape
printf '%-5s %-22s %s\n' seed variant score
for seed in ${SEEDS:-1 2 3}; do
  /usr/bin/python3 "$top/tools/synthetic_scan.py" make scan$seed --size "$size" \
    --grains "${GRAINS:-260}" --seed "$seed" >/dev/null
  tiffcp -c lzw scan$seed.tif scan$seed.lzw.tif
  for variant in default no-detrend merge-ratio=1 h=1; do
    case $variant in
      default) opts=() ;;
      no-detrend) opts=(--no-detrend) ;;
      merge-ratio=1) opts=(--merge-ratio 1) ;;
      h=1) opts=(--h 1) ;;
    esac
    "$build/lsdem-segment" scan$seed.lzw.tif s.lslib --voxel 1e-4 --nodes 50 --quiet \
      --labels found.raw "${opts[@]}" 2>/dev/null >/dev/null
    printf '%-5s %-22s %s\n' "$seed" "$variant" \
      "$(/usr/bin/python3 "$top/tools/synthetic_scan.py" score scan$seed.truth.raw found.raw "$size")"
  done
done
