#!/bin/bash
# Contact-force error of level-set grains against the cost of a contact test (bench/README.md,
# "accuracy.sh"). Usage: bench/accuracy.sh [OUTDIR] [lsdem-bench-accuracy options]
# Writes OUTDIR/accuracy.csv and OUTDIR/accuracy.png (default OUTDIR: bench-accuracy in the
# current folder) and prints the CSV. Environment: LSDEM_BUILD_DIR (default ../build).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${LSDEM_BUILD_DIR:-$here/../build}
out=bench-accuracy
if [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; then out=$1; shift; fi
prog=$build/lsdem-bench-accuracy
[ -x "$prog" ] || { echo "accuracy.sh: $prog not found: build first (./lsdem build)" >&2; exit 1; }
mkdir -p "$out"
"$prog" "$@" | tee "$out/accuracy.csv"
/usr/bin/python3 "$here/accuracy_plot.py" "$out/accuracy.csv" "$out/accuracy.png"
echo "plot: $out/accuracy.png" >&2
