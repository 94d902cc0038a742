#!/usr/bin/env bash
# Benchmark LSDEM on a scene in the Kawamoto/Tan layout (the report code's input format).
#
#   bench/run.sh [SCENE_DIR] [--steps N] [--np N] [--mode oneway|twoway] [--instructions]
#                [--compare OTHER_LMP [--pairs K]] [--keep]
#
# Without SCENE_DIR it uses the reference scene of ../shared/bench (2,197 ellipsoids, 250
# nodes each), generated once (about 30 s) and kept in $LSDEM_HOME/bench (default
# ~/.cache/lsdem/bench) for later runs. The run's files (shape library, data file, logs) go
# to a temporary folder under $TMPDIR (default /tmp), removed at the end unless --keep is
# given. Prints the LAMMPS time split (pair, neighbour, comm, modify), the workload per
# grain-step, and as its last line
#   us_per_grain_step=<x> node_tests_per_s=<y>
# --instructions: instead of timing, count the CPU instructions of one grain-step under
# valgrind (callgrind): runs of N and 2N steps (N = --steps, at most 20), one rank, the
# difference divided by N * grains.
# A figure that does not depend on machine load (it leaves out memory stalls), for
# comparing code changes; last line `instructions_per_grain_step=<x>`. Needs valgrind.
# --compare OTHER_LMP: time this build's lmp (A) against another lmp binary (B, say one built
# from an earlier commit) under the same conditions: K pairs (default 3) of runs, each pair
# running A and B at once, one per core, then again with the cores swapped; prints B's time
# over A's per pair and their mean, last line `time_ratio_B_over_A=<x>`. (One run after the
# other varies by up to +-15 % on a shared machine; two at once see the same conditions.)
# Needs 2 cores and taskset (Debian: util-linux); one rank each.
# Environment: LSDEM_LMP (lmp binary), LSDEM_BUILD_DIR (for lsdem-import-tan).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=${LSDEM_BUILD_DIR:-$here/../build}
lmp=${LSDEM_LMP:-$build/lmp}
scene="" steps=500 np=1 mode=oneway instructions=0 other="" pairs=3 keep=0
while [ $# -gt 0 ]; do
  case "$1" in
    --steps) steps=$2; shift 2 ;;
    --compare) other=$2; shift 2 ;;
    --pairs) pairs=$2; shift 2 ;;
    --np) np=$2; shift 2 ;;
    --mode) mode=$2; shift 2 ;;
    --instructions) instructions=1; shift ;;
    --keep) keep=1; shift ;;
    -*) echo "unknown option $1" >&2; exit 2 ;;
    *) scene=$1; shift ;;
  esac
done

if [ -n "$other" ]; then
  [ -x "$other" ] || { echo "--compare: $other is not an executable" >&2; exit 2; }
  [ "$(nproc)" -ge 2 ] || { echo "--compare needs 2 cores" >&2; exit 2; }
  command -v taskset >/dev/null || { echo "--compare needs taskset (apt-get install util-linux)" >&2; exit 2; }
fi
# the deck's command-line arguments for a run of $1 steps, in the array `deck`
deck_args() { deck=(-in "$here/in.bench" -var steps "$1" -var mode "$mode" -var seed 2197); }
work=$(mktemp -d "${TMPDIR:-/tmp}/lsdem-bench.XXXXXX")
if [ "$keep" = 1 ]; then
  trap 'echo "files of this run kept in $work" >&2' EXIT
else
  trap 'rm -rf "$work"' EXIT
fi
if [ -z "$scene" ]; then
  gen=$here/../../shared/bench/gen_morph.py
  [ -f "$gen" ] || { echo "no SCENE_DIR given and no $gen to make the reference scene" >&2; exit 2; }
  # kept per version of the generator; made in the run's folder, then moved in whole
  cache=${LSDEM_HOME:-$HOME/.cache/lsdem}/bench/sc2197-$(sha256sum "$gen" | cut -c1-12)
  if [ ! -d "$cache" ]; then
    echo "generating the reference scene (2197 grains, about 30 s) into $cache ..."
    /usr/bin/python3 "$gen" --n 2197 --test sc2197 --spacing 19 --seed 2197 --root "$work/ref" >/dev/null
    mkdir -p "$(dirname "$cache")"
    mv "$work/ref/sc2197" "$cache.$$" && mv -T "$cache.$$" "$cache" 2>/dev/null || rm -rf "$cache.$$"
  fi
  scene=$cache
fi
# density 2650 kg/m^3 at 0.1 um per voxel: rho k^3 (report Table 3.1)
"$build/lsdem-import-tan" "$scene" "$work/scene" --density 2.65e-18
cd "$work"
if [ "$instructions" = 1 ]; then
  command -v valgrind >/dev/null || { echo "--instructions needs valgrind (Debian: apt-get install valgrind)" >&2; exit 2; }
  count() { # instructions of a run of $1 steps
    deck_args "$1"
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$lmp" "${deck[@]}" \
      -log none -screen none 2>&1 |
      awk '/refs:/ { gsub(",", "", $NF); print $NF }'
  }
  n=$((steps < 20 ? steps : 20))
  i1=$(count "$n") i2=$(count $((2 * n)))
  grains=$(awk '/ atoms$/ { print $1; exit }' scene.data)
  echo "instructions: $i1 for $n steps, $i2 for $((2 * n)) steps, $grains grains, mode $mode"
  echo "instructions_per_grain_step=$(( (i2 - i1) / (n * grains) ))"
  exit 0
fi
if [ -n "$other" ]; then
  loop_time() { # binary core log: pinned run, prints its loop time
    taskset -c "$2" "$1" "${deck[@]}" -log "$3" -screen none >/dev/null
    awk '/^Loop time/ { t = $4 } END { print t }' "$3"
  }
  deck_args "$steps"
  ratios=()
  for k in $(seq "$pairs"); do
    loop_time "$lmp" 0 a0.log >a0.t & loop_time "$other" 1 b1.log >b1.t; wait
    loop_time "$other" 0 b0.log >b0.t & loop_time "$lmp" 1 a1.log >a1.t; wait
    r=$(awk -v a0="$(cat a0.t)" -v a1="$(cat a1.t)" -v b0="$(cat b0.t)" -v b1="$(cat b1.t)" \
      'BEGIN { printf "%.4f", (b0 + b1) / (a0 + a1) }')
    echo "pair $k: A $(cat a0.t) $(cat a1.t) s, B $(cat b0.t) $(cat b1.t) s, B/A $r"
    ratios+=("$r")
  done
  echo "A: $lmp"
  echo "B: $other"
  echo "time_ratio_B_over_A=$(printf '%s\n' "${ratios[@]}" | awk '{ s += $1 } END { printf "%.4f", s / NR }')"
  exit 0
fi
mpi=()
[ "$np" -gt 1 ] && mpi=(mpirun --allow-run-as-root --oversubscribe -np "$np")
deck_args "$steps"
"${mpi[@]}" "$lmp" "${deck[@]}" -log log.bench -screen none
/usr/bin/python3 "$here/report.py" log.bench --np "$np" --mode "$mode"
