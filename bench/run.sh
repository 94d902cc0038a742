#!/usr/bin/env bash
# Benchmark LSDEM on a scene in the Kawamoto/Tan layout (the report code's input format), with
# the physics of the report code's benchmark driver (bench/in.bench says how each parameter
# converts).
#
#   bench/run.sh [SCENE_DIR] [--steps N] [--np N] [--mode oneway|twoway] [--nodelist auto|off]
#                [--instructions] [--compare OTHER_LMP] [--report REPORT_BIN]... [--pairs K]
#                [--keep]
#
# Without SCENE_DIR it uses the reference scene of ../shared/bench (2,197 ellipsoids, 250
# nodes each), generated once (about 30 s) and kept in $LSDEM_HOME/bench (default
# ~/.cache/lsdem/bench) for later runs. The run's files (shape library, data file, body
# accelerations, logs) go to a temporary folder under $TMPDIR (default /tmp), removed at the
# end unless --keep is given. Default 200 steps (the report benchmark's first 200). Prints the
# LAMMPS time split (pair, neighbour, comm, modify), the workload per grain-step, the node
# lookups' memory traffic (4 cache lines per lookup x 64 B x lookups per second) beside this
# core's memory speed (bench/membw.c, compiled with cc: read and copy bandwidth, latency of a
# dependent miss), and as its last line
#   us_per_grain_step=<x> node_tests_per_s=<y>
# --nodelist off: every node of a master screened at every step (the report's algorithm;
# same forces), so that "node lookups" counts the nodes inside the partner's bounding sphere,
# the report code's "node tests".
# --instructions: instead of timing, count the CPU instructions of one grain-step under
# valgrind (callgrind): runs of N and 2N steps (N = --steps, at most 20), one rank, the
# difference divided by N * grains.
# A figure that does not depend on machine load (it leaves out memory stalls), for
# comparing code changes; last line `instructions_per_grain_step=<x>`. Needs valgrind.
# --compare OTHER_LMP: time this build's lmp (A) against another lmp binary (B, say one built
# from an earlier commit) under the same conditions: K pairs (default 3) of runs, each pair
# running A and B at once, one per core, then again with the cores swapped; prints B's CPU
# time over A's per pair and their mean, last line `time_ratio_B_over_A=<x>`. (One run after
# the other varies by up to +-15 % on a shared machine; two at once see the same conditions.)
# --report REPORT_BIN (repeatable): the same side by side against the report code's own
# benchmark driver, built outside this repository (bench/README.md says how): its input
# folder and parameter file are written into the run's folder, it runs on one core and this
# build's lmp on the other, LSDEM repeated until the report code's step loop ends, then the
# cores swapped, K pairs per binary; CPU time of the step loops (LAMMPS's loop time x its CPU
# use; the driver's `cpu_loop_seconds=` line, else its wall-clock "Simulation Time"); prints
# microseconds per grain-step of both and their ratio per pair, last line
# `report_over_lsdem=<r1>[,<r2>...]` (one mean ratio per binary, in the order given).
# --compare and --report need 2 cores and taskset (Debian: util-linux); one rank each.
# Environment: LSDEM_LMP (lmp binary), LSDEM_BUILD_DIR (for lsdem-import-tan).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=${LSDEM_BUILD_DIR:-$here/../build}
lmp=${LSDEM_LMP:-$build/lmp}
scene="" steps=200 np=1 mode=oneway nodelist=auto instructions=0 other="" reports=() pairs=3 keep=0
while [ $# -gt 0 ]; do
  case "$1" in
    --steps) steps=$2; shift 2 ;;
    --compare) other=$2; shift 2 ;;
    --report) reports+=("$2"); shift 2 ;;
    --nodelist) nodelist=$2; shift 2 ;;
    --pairs) pairs=$2; shift 2 ;;
    --np) np=$2; shift 2 ;;
    --mode) mode=$2; shift 2 ;;
    --instructions) instructions=1; shift ;;
    --keep) keep=1; shift ;;
    -*) echo "unknown option $1" >&2; exit 2 ;;
    *) scene=$1; shift ;;
  esac
done

for b in ${other:+"$other"} ${reports[@]+"${reports[@]}"}; do
  [ -x "$b" ] || { echo "--compare/--report: $b is not an executable" >&2; exit 2; }
done
if [ -n "$other" ] || [ ${#reports[@]} -gt 0 ]; then
  [ "$(nproc)" -ge 2 ] || { echo "--compare needs 2 cores" >&2; exit 2; }
  command -v taskset >/dev/null || { echo "--compare needs taskset (apt-get install util-linux)" >&2; exit 2; }
fi
# the deck's command-line arguments for a run of $1 steps, in the array `deck`
# (thermo about every 1 % of the run: the workload is the mean of the thermo rows)
deck_args() {
  deck=(-in "$here/in.bench" -var steps "$1" -var mode "$mode" -var nodelist "$nodelist"
        -var thermo $(($1 >= 200 ? $1 / 100 : 1)))
}
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
scene=$(cd "$scene" && pwd)
# the report code's masses: 2650 x (0.1 x 0.1 um per voxel)^3 per voxel^3 (see in.bench)
"$build/lsdem-import-tan" "$scene" "$work/scene" --density 2.65e-3
cd "$work"
grains=$(awk '/ atoms$/ { print $1; exit }' scene.data)
/usr/bin/python3 "$here/report_accel.py" "$grains" .
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
  echo "instructions: $i1 for $n steps, $i2 for $((2 * n)) steps, $grains grains, mode $mode"
  echo "instructions_per_grain_step=$(( (i2 - i1) / (n * grains) ))"
  exit 0
fi
# CPU seconds of a LAMMPS log's last loop: its loop time times its CPU use
lmp_cpu() { awk '/^Loop time/ { t = $4 } /% CPU use/ { c = $1 + 0 } END { printf "%.6f", t * c / 100 }' "$1"; }
# microseconds per grain-step of $1 CPU seconds
us_of() { awk -v t="$1" -v n="$((steps * grains))" 'BEGIN { printf "%.3f", t / n * 1e6 }'; }
mean() { printf '%s\n' "$@" | awk '{ s += $1 } END { printf "%.4f", s / NR }'; }
if [ -n "$other" ]; then
  cpu_time() { # binary core log: pinned run, prints its loop's CPU time
    taskset -c "$2" "$1" "${deck[@]}" -log "$3" -screen none >/dev/null
    lmp_cpu "$3"
  }
  deck_args "$steps"
  ratios=()
  for k in $(seq "$pairs"); do
    cpu_time "$lmp" 0 a0.log >a0.t & cpu_time "$other" 1 b1.log >b1.t; wait
    cpu_time "$other" 0 b0.log >b0.t & cpu_time "$lmp" 1 a1.log >a1.t; wait
    r=$(awk -v a0="$(cat a0.t)" -v a1="$(cat a1.t)" -v b0="$(cat b0.t)" -v b1="$(cat b1.t)" \
      'BEGIN { printf "%.4f", (b0 + b1) / (a0 + a1) }')
    echo "pair $k: A $(cat a0.t) $(cat a1.t) s, B $(cat b0.t) $(cat b1.t) s (CPU), B/A $r"
    ratios+=("$r")
  done
  echo "A: $lmp"
  echo "B: $other"
  echo "time_ratio_B_over_A=$(mean "${ratios[@]}")"
  exit 0
fi
if [ ${#reports[@]} -gt 0 ]; then
  # The report code's input: its Input/<test>/ layout is the scene folder itself; its
  # parameter file (format of its Parameters_LSDEM.txt, read by readParametersTrueUnit) with
  # the benchmark's values, this run's steps and grains, and the box of scene.data (its
  # walls: x = 0 and worldLength, y = 0 and worldWidth, z = 0 and worldHeight).
  pos=$(ls "$scene"/InitState/positions_*.dat | head -n 1)
  test=$(basename "$pos" .dat); test=${test#positions_}
  mkdir -p report/Input report/Output/"$test"
  ln -s "$(cd "$scene" && pwd)" report/Input/"$test"
  read -r bx by bz < <(awk '/xlo xhi/ { x = $2 - $1 } /ylo yhi/ { y = $2 - $1 }
    /zlo zhi/ { z = $2 - $1 } END { print x, y, z }' scene.data)
  cat >report/Parameters_LSDEM.txt <<PARAMS
## INPUT PARAMETERS BEGIN HERE ##
Test Name: "$test"
Restart: 0
Time-steps: $steps
Time-Step Multiplier: 0.1
Output Frequency: 100
Microns per voxel: 0.1
Maximum Grain ID: $grains
Grain Density: 2650
kn: 30000
ks: 27000
mu: 0.65
gdamping: 1.5
worldWidth: $by
worldLength: $bx
worldHeight: $bz
Dynamic Binning: 0
Re-binning Frequency: 1000
Plane Walls to Grains Friction: 0.8
PARAMS
  export TAN_PARAMS=$work/report/Parameters_LSDEM.txt TAN_ROOT=$work/report
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  deck_args "$steps"
  # side REPORT_BIN REPORT_CORE LSDEM_CORE TAG: the report binary on one core; once its step
  # loop has begun, LSDEM's deck again and again on the other core until it ends; prints
  # "report_us lsdem_us lsdem_runs"
  side() {
    taskset -c "$2" "$1" >"rep_$4.out" 2>&1 &
    local pid=$! n=0 t=()
    until grep -q "Begin Simulation" "rep_$4.out" 2>/dev/null || ! kill -0 "$pid" 2>/dev/null; do
      sleep 0.05
    done
    while kill -0 "$pid" 2>/dev/null || [ "$n" = 0 ]; do
      taskset -c "$3" "$lmp" "${deck[@]}" -log "lmp_$4.$n.log" -screen none >/dev/null
      t+=("$(lmp_cpu "lmp_$4.$n.log")"); n=$((n + 1))
    done
    wait "$pid" || { echo "the report binary $1 failed: $(tail -n 5 "rep_$4.out")" >&2; exit 1; }
    local rt
    rt=$(awk -F= '/^cpu_loop_seconds=/ { c = $2 } /Simulation Time =/ { w = $(NF - 1) }
      END { print (c != "" ? c : w) }' "rep_$4.out")
    [ -n "$rt" ] || { echo "no step-loop time in the output of $1" >&2; exit 1; }
    echo "$(us_of "$rt") $(us_of "$(mean "${t[@]}")") $n"
  }
  means=()
  for b in "${reports[@]}"; do
    ratios=()
    for k in $(seq "$pairs"); do
      read -r r1 l0 n0 < <(side "$b" 1 0 "$k.a")
      read -r r0 l1 n1 < <(side "$b" 0 1 "$k.b")
      r=$(awk -v a="$r1" -v b="$r0" -v c="$l0" -v d="$l1" 'BEGIN { printf "%.3f", (a + b) / (c + d) }')
      echo "pair $k: report $r1 $r0 us, LSDEM $l0 $l1 us per grain-step (CPU; LSDEM mean of $n0 and $n1 runs), report/LSDEM $r"
      ratios+=("$r")
    done
    echo "report binary: $b: report/LSDEM $(mean "${ratios[@]}") (${ratios[*]})"
    means+=("$(mean "${ratios[@]}")")
  done
  echo "LSDEM: $lmp, $steps steps, $grains grains, mode $mode"
  echo "report_over_lsdem=$(IFS=,; echo "${means[*]}")"
  exit 0
fi
mpi=()
[ "$np" -gt 1 ] && mpi=(mpirun --allow-run-as-root --oversubscribe -np "$np")
deck_args "$steps"
"${mpi[@]}" "$lmp" "${deck[@]}" -log log.bench -screen none
# this core's memory speed beside the lookups' traffic (bench/membw.c)
membw=""
if command -v cc >/dev/null && cc -O2 -o membw "$here/membw.c" 2>/dev/null; then
  membw=$(./membw 256)
fi
/usr/bin/python3 "$here/report.py" log.bench --np "$np" --mode "$mode" --membw "$membw"
