#!/usr/bin/env bash
# What the in-run analysis of in.triaxial costs on a specimen of bench/specimen.sh --full
# (issue 35's goal: at most 5 % of the run's time at one evaluation per 1 % of strain).
#
#   bench/analysis_cost.sh RUN_DIR [--steps N] [--np P]
#
# From RUN_DIR's newest shearing checkpoint (shear.a/b.restart), four resumed runs of N
# shearing steps (default 1000) in RUN_DIR/cost/: B, A, A, B (drift cancels), where A takes
# one snapshot half-way (fix field/lsdem's fields, fix network/lsdem's contact network, the
# band grains' dump, the snapshots.csv row) and B none (-var snap_at 10); everything else
# (thermo, the band's dip and thickness in every CSV row) the same. Prints each run's loop
# time (the sum of its LAMMPS "Loop time" lines: set-up and reading excluded) and its Modify
# time (the timer breakdown's average over ranks: the fixes, the snapshot's among them; the
# field's reduction and FFT on rank 0 keep the other ranks waiting inside the fix, so
# Modify is even across ranks), the cost of one snapshot (A - B in Modify, each the mean of
# its two runs: on a shared machine the loop times of equal runs differ by more than a
# snapshot costs, Modify much less), the fields' own times as fix field/lsdem logs them
# (gathering and computing, writing the .vti) and that cost as a share of 1 % of axial strain's
# shearing (B's loop time per step x the steps of 1 %: 0.01 / (erate dt), the deck's erate
# and timestep as bench/triaxial_rate.sh reads them):
#   snapshot_s=<x> loop_diff_s=<A - B in loop time> shearing_s_per_pct=<y> share_at_one_per_pct=<z>
# Environment: LSDEM_BUILD_DIR (default ./build) or LSDEM_LMP.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
ex=$here/../examples/triaxial
lmp=${LSDEM_LMP:-${LSDEM_BUILD_DIR:-$here/../build}/lmp}
run=${1:?usage: bench/analysis_cost.sh RUN_DIR [--steps N] [--np P]}; shift
steps=1000 np=2
while [ $# -gt 0 ]; do
  case $1 in
    --steps) steps=$2; shift ;;
    --np) np=$2; shift ;;
    *) echo "analysis_cost.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
run=$(cd "$run" && pwd)
for f in mem.data mem.in mem.tri all.lslib shear_state.in summary.txt; do
  [ -e "$run/$f" ] || { echo "analysis_cost.sh: $run has no $f (not a specimen.sh --full run)" >&2; exit 1; }
done
ckpt=$(ls -t "$run"/shear.a.restart "$run"/shear.b.restart 2>/dev/null | head -1)
[ -n "$ckpt" ] || { echo "analysis_cost.sh: $run has no shearing checkpoint" >&2; exit 1; }
R=$(sed -n 's/.* R \([0-9]*\) px.*/\1/p' "$run/summary.txt" | head -1)
[ -n "$R" ] || { echo "analysis_cost.sh: no radius in $run/summary.txt" >&2; exit 1; }
mpi=()
[ "$np" -gt 1 ] && mpi=(mpirun --allow-run-as-root --oversubscribe -np "$np")
source "$here/triaxial_rate.sh"  # erate, dt and shear_strain, from the deck
work=$run/cost
mkdir -p "$work"
cd "$work"
for f in mem.data mem.in mem.tri all.lslib; do ln -sf "$run/$f" .; done
cp "$run/shear_state.in" .
printf 'read_restart %s\nprint "CKPT_STEP $(step)"\n' "$ckpt" > in.step
s_c=$("$lmp" -in in.step -log none -echo none -screen /dev/stdout | sed -n 's/^CKPT_STEP //p')
step0=$(sed -n 's/^variable step0 equal //p' shear_state.in)
strain() { shear_strain $(($1 - step0)); }  # eps_a at step $1 of the run
epsmax=$(strain $((s_c + steps)))
snap_mid=$(strain $((s_c + steps / 2)))
echo "checkpoint $(basename "$ckpt") at step $s_c (eps_a $(strain "$s_c")); $steps steps to eps_a $epsmax, $np rank(s)"
loop_time() { awk '/^Loop time of/ { t += $4 } END { printf "%.3f", t }' "$1"; }
modify_time() { awk '/^Modify +\|/ { t += $5 } END { printf "%.3f", t }' "$1"; }
declare -A total=([A]=0 [B]=0) modify=([A]=0 [B]=0)
k=0
for variant in B A A B; do
  k=$((k + 1))
  snap=10; [ "$variant" = A ] && snap=$snap_mid
  rm -f fields_*.vti chains_*.vtp
  "${mpi[@]}" "$lmp" -in "$ex/in.triaxial" -var lib all.lslib -var data mem.data \
    -var memin mem.in -var memtri mem.tri -var mu 0.6 -var rho 2.65e-3 -var R "$R" \
    -var epsmax "$epsmax" -var snap_at "$snap" -var resume "$ckpt" -var part ".cost$k" \
    -log "log.$k.$variant" -echo none -screen none
  t=$(loop_time "log.$k.$variant") m=$(modify_time "log.$k.$variant")
  written=$(find . -maxdepth 1 -name 'fields_*.vti' | wc -l)
  echo "run $k ($variant): loop time $t s, Modify $m s, fields files written $written"
  sed -n 's/^fix field\/lsdem [^:]*: \(step .*\): [^ ]*$/  fields: \1/p' "log.$k.$variant"
  total[$variant]=$(awk -v a="${total[$variant]}" -v b="$t" 'BEGIN { print a + b }')
  modify[$variant]=$(awk -v a="${modify[$variant]}" -v b="$m" 'BEGIN { print a + b }')
done
rm -f fields_*.vti chains_*.vtp
awk -v a="${total[A]}" -v b="${total[B]}" -v ma="${modify[A]}" -v mb="${modify[B]}" \
  -v n="$steps" -v r="$erate" -v dt="$dt" 'BEGIN {
  snap = (ma - mb) / 2; per_pct = b / 2 / n * 0.01 / (r * dt)
  printf "snapshot_s=%.2f loop_diff_s=%.2f shearing_s_per_pct=%.1f share_at_one_per_pct=%.4f\n",
         snap, (a - b) / 2, per_pct, snap / per_pct }'
