#!/usr/bin/env bash
# How well lsdem-segment finds the grains of synthetic scans made from known grains.
#   bash bench/segment.sh [OUTDIR]            both parts below
#   PART=scan | PART=sand bash bench/segment.sh [OUTDIR]
# scan: tools/synthetic_scan.py (touching bumpy ellipsoids, blur 1 voxel, noise 0.1, a grey
#   gradient of 0.3 of the contrast along z; SIZE=128 GRAINS=260 SEEDS="1 2 3"), the default
#   pipeline and with one step changed; one row per scan and variant.
# sand: tools/synthetic_sand.py (angular rough grains, lognormal sizes, 0.58 solid, partial
#   volume, blur 0.8, and the artifacts of a sand scan) at D50 = D50S (default "8 14 25"
#   voxels) x artifacts (clean: partial volume and blur only; all: cupping 15 %, rings,
#   inclusions, noise SNR 8, air around the specimen; zero: all, and the corners outside the
#   field of view 0) x SEEDS, the default pipeline; one row per scan into sand.txt, then the
#   mean per D50 and artifacts and recovery.png (bench/segment_summary.py), and how well the
#   check's warning "likely two grains joined" names the labels that hold two true grains.
# Rows: key=value figures of synthetic_scan.py score (one-to-one = IoU >= 0.5).
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${LSDEM_BUILD_DIR:-$top/build}
out=${1:-bench-segment}
py=/usr/bin/python3
mkdir -p "$out"
cd "$out"
export LSDEM_SHAPE_TOOL=$build/lsdem-shape
seeds=${SEEDS:-1 2 3}

if [ "${PART:-scan}" = scan ]; then
  size=${SIZE:-128}
  printf '%-5s %-22s %s\n' seed variant score
  for seed in $seeds; do
    $py "$top/tools/synthetic_scan.py" make scan$seed --size "$size" \
      --grains "${GRAINS:-260}" --seed "$seed" >/dev/null
    tiffcp -c lzw scan$seed.tif scan$seed.lzw.tif
    for variant in default no-detrend merge-ratio=1 grey-weight=0; do
      case $variant in
        default) opts=() ;;
        no-detrend) opts=(--no-detrend) ;;
        merge-ratio=1) opts=(--merge-ratio 1) ;;
        grey-weight=0) opts=(--grey-weight 0) ;;
      esac
      "$build/lsdem-segment" scan$seed.lzw.tif s.lslib --voxel 1e-4 --nodes 50 --quiet \
        --labels found.raw "${opts[@]}" 2>/dev/null >/dev/null
      printf '%-5s %-22s %s\n' "$seed" "$variant" \
        "$($py "$top/tools/synthetic_scan.py" score scan$seed.truth.raw found.raw "$size")"
    done
  done
fi

if [ "${PART:-sand}" = sand ]; then
  : >sand.txt
  for d50 in ${D50S:-8 14 25}; do
    size=$($py -c "print(max(80, 16 * round($d50 * 0.4)))")  # ~120-470 grains
    for art in clean all zero; do
      case $art in
        clean) opts=(--clean) ;;
        all) opts=() ;;
        zero) opts=(--zero-corners) ;;
      esac
      for seed in $seeds; do
        $py "$top/tools/synthetic_sand.py" make sand --size "$size" --d50 "$d50" \
          --seed "$seed" "${opts[@]}" >/dev/null
        "$build/lsdem-segment" sand.tif s.lslib --voxel 1e-4 --nodes 50 --quiet \
          --labels found.raw 2>warnings.txt >/dev/null
        named=$(sed -n 's/.*likely two grains joined: //p' warnings.txt)
        line="d50=$d50 artifacts=$art seed=$seed size=$size $($py "$top/tools/synthetic_scan.py" \
          score sand.truth.raw found.raw "$size" --named "$named")"
        echo "$line" | tee -a sand.txt
      done
    done
  done
  $py "$top/bench/segment_summary.py" sand.txt recovery.png
fi
