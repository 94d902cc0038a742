#!/usr/bin/env bash
# A triaxial specimen's figures over several packings: examples/triaxial/run.sh once per
# packing seed (PACK_SEED; the same grain shapes, another random loose packing, so another
# dense specimen), then examples/triaxial/compare.py --spread on all the CSVs: each run's
# row (peak phi, strain at peak, largest dilatancy angle, critical-state phi, ...) and each
# figure's mean +- sd (min - max), in OUTDIR/scatter.png and OUTDIR/scatter.json.
#
#   bench/scatter.sh OUTDIR [--seeds "1 2 3 4 5 6"] [--jobs 2] [--extend EPS]  (after ./lsdem build)
#   Environment: run.sh's knobs (NGRAINS, NSHAPES, DENSITY, EPSMAX, ...); NP (ranks per run,
#   default 1: with --jobs 2 two packings run side by side on a 2-core machine).
#
# The main example (run.sh's defaults, 300 grains) takes about 10 min per packing on one
# core; 2,000 grains (NGRAINS=2000 NSHAPES=100) about an hour. A run whose triaxial.csv
# already reaches its final strain is kept (re-running the script finishes the rest).
# --extend EPS shears each finished run on from its end state to axial strain EPS (run.sh
# resume: log.2.lammps, triaxial.2.csv), so that a set run to EPSMAX=0.06 for its peaks can
# be taken to the critical state later; the figures then join the two parts.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
top=$here/..
build=${LSDEM_BUILD_DIR:-$top/build}
export LSDEM_LMP=${LSDEM_LMP:-$build/lmp} LSDEM_SHAPE_TOOL=${LSDEM_SHAPE_TOOL:-$build/lsdem-shape}
export NP=${NP:-1}
out=${1:?usage: bench/scatter.sh OUTDIR [--seeds LIST] [--jobs N]}
shift
seeds="1 2 3 4 5 6" jobs=2 extend=
while [ $# -gt 0 ]; do
  case "$1" in
    --seeds) seeds=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --extend) extend=$2; shift 2 ;;
    *) echo "scatter.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
mkdir -p "$out"
out=$(cd "$out" && pwd)

finished() { grep -q '^SHEARED' "$1/log.lammps" 2>/dev/null; }
extended() { grep -q '^SHEARED' "$1/log.2.lammps" 2>/dev/null; }
run_seed() {
  local dir=$out/seed$1
  finished "$dir" && return 0
  mkdir -p "$dir"
  local t0=$SECONDS
  OUT=$dir PACK_SEED=$1 bash "$top/examples/triaxial/run.sh" >"$dir/run.log" 2>&1 \
    || { echo "seed $1 failed: see $dir/run.log" >&2; return 1; }
  echo "seed $1: $((SECONDS - t0)) s on $NP rank(s), $(date -u +%F)" | tee "$dir/time.txt"
}
extend_seed() {
  local dir=$out/seed$1
  [ -n "$extend" ] && ! extended "$dir" || return 0
  rm -f "$dir/triaxial.2.csv" "$dir/log.2.lammps"   # an interrupted extension starts again
  local t0=$SECONDS
  OUT=$dir PACK_SEED=$1 EPSMAX=$extend bash "$top/examples/triaxial/run.sh" resume >>"$dir/run.log" 2>&1 \
    || { echo "seed $1: extension failed: see $dir/run.log" >&2; return 1; }
  echo "seed $1: extended to $extend in $((SECONDS - t0)) s on $NP rank(s), $(date -u +%F)" | tee -a "$dir/time.txt"
}

running=0
for s in $seeds; do
  { run_seed "$s" && extend_seed "$s"; } &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then wait -n || true; running=$((running - 1)); fi
done
wait || true

args=()
for s in $seeds; do
  d=$out/seed$s
  if [ -n "$extend" ] && extended "$d"; then
    args+=("packing seed $s=$d/triaxial.csv+$d/triaxial.2.csv")
  elif finished "$d"; then
    args+=("packing seed $s=$d/triaxial.csv")
  fi
done
[ ${#args[@]} -gt 0 ] || { echo "scatter.sh: no run finished" >&2; exit 1; }
/usr/bin/python3 "$top/examples/triaxial/compare.py" "$out/scatter.png" "${args[@]}" --spread \
  --title "LSDEM triaxial, ${NGRAINS:-300} grains, ${#args[@]} packings, against PEER 2022/06" \
  | tee "$out/scatter.txt"
