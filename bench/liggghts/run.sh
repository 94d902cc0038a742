#!/bin/bash
# LSDEM against LIGGGHTS on spheres (bench/README.md, "liggghts/run.sh"): the same binary
# collisions and the same settling run in both codes, with contact laws that coincide.
# Usage: bench/liggghts/run.sh [OUTDIR] [--grains N] [--time T] [--seed S]
#   OUTDIR   where scenes, logs, comparison.csv and comparison.png go (default bench-liggghts)
#   --grains settling spheres (default 500), --time simulated settling time in s (default
#   0.3), --seed the settling scene's random seed (default 1)
# Installs Debian's liggghts package when it is missing (sudo when not root). Environment:
# LSDEM_BUILD_DIR (default ../../build: lmp and lsdem-shape), LIGGGHTS (default liggghts).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${LSDEM_BUILD_DIR:-$here/../../build}
out=bench-liggghts
if [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; then out=$1; shift; fi
grains=500 time=0.3 seed=1
while [ $# -gt 0 ]; do
  case "$1" in
    --grains) grains=${2:?--grains needs a value}; shift 2 ;;
    --time) time=${2:?--time needs a value}; shift 2 ;;
    --seed) seed=${2:?--seed needs a value}; shift 2 ;;
    *) echo "run.sh: unknown option '$1' (--grains N, --time T, --seed S)" >&2; exit 2 ;;
  esac
done
case "$grains" in ''|*[!0-9]*|0) echo "run.sh: --grains must be a positive integer, not '$grains'" >&2; exit 2 ;; esac
awk -v t="$time" 'BEGIN { exit !(t + 0 > 0) }' || { echo "run.sh: --time must be > 0, not '$time'" >&2; exit 2; }
case "$seed" in ''|*[!0-9]*) echo "run.sh: --seed must be a non-negative integer, not '$seed'" >&2; exit 2 ;; esac

lmp=$build/lmp tool=$build/lsdem-shape
for f in "$lmp" "$tool"; do
  [ -x "$f" ] || { echo "run.sh: $f not found: build first (./lsdem build)" >&2; exit 1; }
done
liggghts=${LIGGGHTS:-liggghts}
if ! command -v "$liggghts" >/dev/null 2>&1; then
  echo "run.sh: installing Debian's liggghts package" >&2
  sudo=""; [ "$(id -u)" = 0 ] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends liggghts >/dev/null
fi

mkdir -p "$out"
out=$(cd "$out" && pwd)
/usr/bin/python3 "$here/scenes.py" "$out" "$tool" --grains "$grains" --seed "$seed"
param() { awk -v k="$1" '$1 == k { print $2 }' "$out/params.txt"; }
common=(-var kn "$(param kn)" -var ks "$(param ks)" -log none -screen none)
# in_out LOG CMD...: run CMD in $out, its CPU time into LOG.cpu (bash's `times` in the
# subshell that ran it: its own, then its child's user and system time); when it fails, say
# so with the end of its log
in_out() {
  local log=$1; shift
  (cd "$out" && "$@" -log "$log" && times > "$log.cpu") && return 0
  echo "run.sh: $(basename "$1") failed; the end of $out/$log:" >&2
  tail -n 15 "$out/$log" >&2 2>/dev/null || echo "(no log written)" >&2
  exit 1
}
# run_both DECK STEM DATA LGDATA -var ...: in.DECK.lsdem on DATA and in.DECK.liggghts on LGDATA,
# logs STEM.lsdem.log and STEM.liggghts.log
run_both() {
  local deck=$1 stem=$2 data=$3 lgdata=$4; shift 4
  in_out "$stem.lsdem.log" "$lmp" -in "$here/in.$deck.lsdem" -var lib spheres.lslib \
    -var data "$data" "${common[@]}" "$@"
  in_out "$stem.liggghts.log" "$liggghts" -in "$here/in.$deck.liggghts" -var data "$lgdata" \
    "${common[@]}" "$@"
}
# binary collisions: 4,000 steps of dt_collide (a contact lasts about 200)
while read -r _ case cn mu _; do
  run_both collide "collide_$case" "collide_$case.data" "collide_$case.lg.data" \
    -var mu "$mu" -var cn "$cn" -var dt "$(param dt_collide)" -var steps 4000
done < <(grep '^case ' "$out/params.txt")
steps=$(awk -v t="$time" -v dt="$(param dt)" 'BEGIN { printf "%d", t / dt + 0.5 }')
every=$(( steps / 60 > 0 ? steps / 60 : 1 ))
run_both settle settle settle.data settle.lg.data -var mu "$(param mu)" -var cn "$(param cn)" \
  -var dt "$(param dt)" -var box "$(param box)" -var gravity "$(param gravity)" \
  -var steps "$steps" -var every "$every"
/usr/bin/python3 "$here/compare.py" "$out"
