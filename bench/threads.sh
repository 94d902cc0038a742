#!/usr/bin/env bash
# Threads against ranks on the benchmark scene: bench/run.sh's run (default: the reference
# scene of ../shared/bench, 2,197 grains) as
#   1 rank without threads, 1 rank with 2 threads (-sf omp -pk omp 2: pair_style lsdem/omp,
#   fix nve/lsdem/omp), 2 ranks without threads,
# ROUNDS times (default 3) in turn, so that the machine's load drifts over all three alike;
# prints each run's time per grain-step and, per setup, the median and the speed-up over one
# rank. Every setup uses both cores but the first: they cannot run side by side, so the
# ratios carry the machine's noise (run again on a quiet machine).
#
#   bench/threads.sh [--rounds N] [run.sh options, e.g. --steps 300]
# Environment: as bench/run.sh (LSDEM_LMP, LSDEM_BUILD_DIR).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=${LSDEM_BUILD_DIR:-$here/../build}
lmp=${LSDEM_LMP:-$build/lmp}
rounds=3
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --rounds) rounds=$2; shift 2 ;;
    *) args+=("$1"); shift ;;
  esac
done
work=$(mktemp -d "${TMPDIR:-/tmp}/lsdem-threads.XXXXXX")
trap 'rm -rf "$work"' EXIT
# the threaded lmp: the same binary with the OPENMP suffix and 2 threads per rank
printf '#!/bin/sh\nexec "%s" "$@" -sf omp -pk omp 2\n' "$lmp" >"$work/lmp-omp2"
chmod +x "$work/lmp-omp2"

one() { # label lmp np: one run, prints its microseconds per grain-step
  local t
  t=$(LSDEM_LMP=$2 LSDEM_BUILD_DIR=$build "$here/run.sh" "${args[@]}" --np "$3" |
    awk -F'[= ]' '/^us_per_grain_step=/ { print $2 }')
  echo "$1 $t" | tee -a "$work/times"
}
for r in $(seq "$rounds"); do
  one "1rank" "$lmp" 1
  one "1rank_2threads" "$work/lmp-omp2" 1
  one "2ranks" "$lmp" 2
done
awk '{ t[$1] = t[$1] " " $2 }
  END {
    n = split("1rank 1rank_2threads 2ranks", order, " ")
    for (k = 1; k <= n; k++) {
      m = split(substr(t[order[k]], 2), v, " ")
      for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (v[j] < v[i]) { x = v[i]; v[i] = v[j]; v[j] = x }
      med[order[k]] = (m % 2) ? v[(m + 1) / 2] : (v[m / 2] + v[m / 2 + 1]) / 2
    }
    for (k = 1; k <= n; k++)
      printf "%-15s median %.4g us/grain-step, speed-up over 1 rank %.3f\n", order[k],
        med[order[k]], med["1rank"] / med[order[k]]
    printf "speedup_2threads=%.3f speedup_2ranks=%.3f\n", med["1rank"] / med["1rank_2threads"],
      med["1rank"] / med["2ranks"]
  }' "$work/times"
