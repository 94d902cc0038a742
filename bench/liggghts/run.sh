#!/bin/bash
# LSDEM against LIGGGHTS on spheres (bench/README.md, "liggghts/run.sh"): the same binary
# collisions and the same settling run in both codes, with contact laws that coincide.
# Usage: bench/liggghts/run.sh [OUTDIR] [--grains N] [--time T] [--seed S] [--instructions K]
#   OUTDIR   where scenes, logs, comparison.csv and comparison.png go (default bench-liggghts)
#   --grains settling spheres (default 500), --time simulated settling time in s (default
#   0.3), --seed the settling scene's random seed (default 1), --instructions K: then K more
#   steps of each code's settled bed (in.resume.*) under valgrind's callgrind, printed as
#   instructions per grain-step (a figure a busy machine does not blur; about 1 min at
#   K = 3000)
# Installs Debian's liggghts package (and valgrind for --instructions) when missing (sudo
# when not root). Environment:
# LSDEM_BUILD_DIR (default ../../build: lmp and lsdem-shape), LIGGGHTS (default liggghts).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${LSDEM_BUILD_DIR:-$here/../../build}
out=bench-liggghts
if [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; then out=$1; shift; fi
grains=500 time=0.3 seed=1 instructions=0
while [ $# -gt 0 ]; do
  case "$1" in
    --grains) grains=${2:?--grains needs a value}; shift 2 ;;
    --time) time=${2:?--time needs a value}; shift 2 ;;
    --seed) seed=${2:?--seed needs a value}; shift 2 ;;
    --instructions) instructions=${2:?--instructions needs a value}; shift 2 ;;
    *) echo "run.sh: unknown option '$1' (--grains N, --time T, --seed S, --instructions K)" >&2
       exit 2 ;;
  esac
done
case "$instructions" in ''|*[!0-9]*) echo "run.sh: --instructions must be a non-negative integer, not '$instructions'" >&2; exit 2 ;; esac
case "$grains" in ''|*[!0-9]*|0) echo "run.sh: --grains must be a positive integer, not '$grains'" >&2; exit 2 ;; esac
awk -v t="$time" 'BEGIN { exit !(t + 0 > 0) }' || { echo "run.sh: --time must be > 0, not '$time'" >&2; exit 2; }
case "$seed" in ''|*[!0-9]*) echo "run.sh: --seed must be a non-negative integer, not '$seed'" >&2; exit 2 ;; esac

lmp=$build/lmp tool=$build/lsdem-shape
for f in "$lmp" "$tool"; do
  [ -x "$f" ] || { echo "run.sh: $f not found: build first (./lsdem build)" >&2; exit 1; }
done
liggghts=${LIGGGHTS:-liggghts}
# need_package PACKAGE COMMAND: Debian's PACKAGE installed when COMMAND is missing
need_package() {
  command -v "$2" >/dev/null 2>&1 && return 0
  echo "run.sh: installing Debian's $1 package" >&2
  local sudo=""; [ "$(id -u)" = 0 ] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "$1" >/dev/null
}
need_package liggghts "$liggghts"
[ "$instructions" -eq 0 ] || need_package valgrind valgrind

mkdir -p "$out"
out=$(cd "$out" && pwd)
/usr/bin/python3 "$here/scenes.py" "$out" "$tool" --grains "$grains" --seed "$seed"
param() { awk -v k="$1" '$1 == k { print $2 }' "$out/params.txt"; }
stiff=(-var kn "$(param kn)" -var ks "$(param ks)")
common=("${stiff[@]}" -log none -screen none)
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
# instructions CODE BINARY K -var ...: instructions (valgrind's callgrind) of K steps of
# CODE's settled bed, less those of 0 steps (start-up, reading, the setup's force call)
instructions_of() {
  local code=$1 bin=$2 k=$3 total=()
  shift 3
  for n in 0 "$k"; do
    (cd "$out" && valgrind --tool=callgrind --callgrind-out-file="resume.$code.$n.callgrind" \
      "$bin" -in "$here/in.resume.$code" "${stiff[@]}" -screen none -log "resume.$code.$n.log" \
      -var steps "$n" "$@" > "resume.$code.$n.valgrind" 2>&1) ||
      { echo "run.sh: $code under valgrind failed: $out/resume.$code.$n.valgrind" >&2; exit 1; }
    total+=("$(sed -n 's/^summary: *//p' "$out/resume.$code.$n.callgrind")")
  done
  awk -v a="${total[0]}" -v b="${total[1]}" -v k="$k" -v n="$grains" 'BEGIN { printf "%.0f", (b - a) / (k * n) }'
}
# binary collisions: 4,000 steps of dt_collide (a contact lasts about 200)
while read -r _ case cn mu _; do
  run_both collide "collide_$case" "collide_$case.data" "collide_$case.lg.data" \
    -var mu "$mu" -var cn "$cn" -var dt "$(param dt_collide)" -var steps 4000
done < <(grep '^case ' "$out/params.txt")
steps=$(awk -v t="$time" -v dt="$(param dt)" 'BEGIN { printf "%d", t / dt + 0.5 }')
every=$(( steps / 60 > 0 ? steps / 60 : 1 ))
laws=(-var mu "$(param mu)" -var cn "$(param cn)" -var dt "$(param dt)" -var box "$(param box)"
  -var gravity "$(param gravity)" -var here "$here")
run_both settle settle settle.data settle.lg.data "${laws[@]}" -var steps "$steps" \
  -var every "$every"
if [ "$instructions" -gt 0 ]; then
  a=$(instructions_of lsdem "$lmp" "$instructions" "${laws[@]}")
  b=$(instructions_of liggghts "$liggghts" "$instructions" "${laws[@]}")
  awk -v a="$a" -v b="$b" -v k="$instructions" 'BEGIN { printf "instructions per grain-step of the settled bed (%d steps, callgrind): lsdem %d liggghts %d ratio %.3f\n", k, a, b, a / b }'
fi
/usr/bin/python3 "$here/compare.py" "$out"
