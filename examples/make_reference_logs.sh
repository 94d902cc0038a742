#!/usr/bin/env bash
# Reference logs of the examples, as LAMMPS ships them: log.<date>.<name>.g++.1 and
# log.<date>.<name>.g++.2 in each example folder, lmp's log of the example run on 1 and on
# 2 MPI ranks, so that a user can compare a run of their own (the test
# lmp.reference_logs compares a run of examples/avatars with its logs). Re-run it when
# results change: an example's old logs are replaced.
#   bash examples/make_reference_logs.sh [NAME...]     (default: every example with a run.sh)
# Uses LSDEM_BUILD_DIR (default ./build). The triaxial example takes most of the time
# (about 5 minutes for both rank counts on 2 cores).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=${LSDEM_BUILD_DIR:-$here/../build}
stamp=$(date +%-d%b%y)  # LAMMPS's style: log.1Dec26.NAME.g++.N
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  for d in "$here"/*/; do [ -f "$d/run.sh" ] && names+=("$(basename "$d")"); done
fi
for name in "${names[@]}"; do
  [ -f "$here/$name/run.sh" ] || { echo "make_reference_logs: no example $name" >&2; exit 1; }
  for np in 1 2; do
    printf 'make_reference_logs: %s on %d rank(s) ... ' "$name" "$np"
    t0=$SECONDS
    mkdir -p "$here/$name/out"
    NP=$np LSDEM_LMP=$build/lmp LSDEM_SHAPE_TOOL=$build/lsdem-shape LSDEM_BUILD_DIR=$build \
      bash "$here/$name/run.sh" >"$here/$name/out/run.sh.out" 2>&1 \
      || { echo "failed: see $here/$name/out/run.sh.out" >&2; exit 1; }
    rm -f "$here/$name"/log.*."$name".g++."$np"
    cp "$here/$name/out/log.lammps" "$here/$name/log.$stamp.$name.g++.$np"
    echo "$((SECONDS - t0)) s: log.$stamp.$name.g++.$np"
  done
done
