#!/bin/bash
# Node density against run time and result on the triaxial example (report §3.4.1, Figure
# 3.7): the same specimen sheared with grain contacts that test every N-th node, forces times
# N (pair_style lsdem stride N). Usage: bench/node_stride.sh [OUTDIR] [--strides 1,2,3,4]
# Writes OUTDIR/strideN/ (each run's example output), OUTDIR/node_stride.csv and
# OUTDIR/node_stride.png, and prints the table (default OUTDIR: bench-node-stride).
# Environment: LSDEM_BUILD_DIR (default ../build), NP (ranks, default 2), NGRAINS, EPSMAX,
# NPREP as for examples/triaxial/run.sh. About 40 s per stride on 2 cores (2026-11-23).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${LSDEM_BUILD_DIR:-$here/../build}
out=bench-node-stride
if [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; then out=$1; shift; fi
strides=1,2,3,4
while [ $# -gt 0 ]; do
  case "$1" in
    --strides) strides=${2:?--strides needs a value}; shift 2 ;;
    *) echo "node_stride.sh: unknown option '$1' (--strides N,N,...)" >&2; exit 2 ;;
  esac
done
case ",$strides," in
  *,,*|*[!0-9,]*|*,0,*) echo "node_stride.sh: --strides must be positive integers separated by commas, not '$strides'" >&2; exit 2 ;;
esac
for f in "$build/lmp" "$build/lsdem-shape"; do
  [ -x "$f" ] || { echo "node_stride.sh: $f not found: build first (./lsdem build)" >&2; exit 1; }
done
mkdir -p "$out"
out=$(cd "$out" && pwd)
runs=()
for n in ${strides//,/ }; do
  echo "stride $n ..." >&2
  OUT="$out/stride$n" STRIDE=$n LSDEM_LMP="$build/lmp" LSDEM_SHAPE_TOOL="$build/lsdem-shape" \
    bash "$here/../examples/triaxial/run.sh" > "$out/stride$n.txt"
  runs+=("$n" "$out/stride$n")
done
/usr/bin/python3 "$here/node_stride_plot.py" "$out" "${runs[@]}"
