#!/usr/bin/env bash
# Label-exchange rounds of fix impulse/lsdem's islands on a settled pile (report §4.5): the
# settled mound that bench/impulse.sh left (OUTDIR/mound_<tag>.data) runs STEPS steps
# (default 20) on each rank count of RANKS (default "2 3 4"), with the benchmark's impulse
# settings; prints per rank count the islands spanning ranks and the rounds per pass (the
# largest and the mean over the steps) and the grains of the largest island.
#   bench/impulse_rounds.sh OUTDIR [TAG] [--steps N] [--ranks "2 3 4"] [--impulse-opts "..."]
# TAG: the run whose mound to use (default impulse_x16). Environment: LSDEM_LMP, LSDEM_BUILD_DIR.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
ex=$here/../examples/container_release
build=${LSDEM_BUILD_DIR:-$here/../build}
lmp=${LSDEM_LMP:-$build/lmp}
bad() { echo "bench/impulse_rounds.sh: $*" >&2; exit 2; }
out="" tag=impulse_x16 steps=20 ranks="2 3 4" opts="tolerance 1e-2 passes 3"
while [ $# -gt 0 ]; do
  case "$1" in
    --steps) [[ "${2:-}" =~ ^[1-9][0-9]*$ ]] || bad "--steps needs a positive integer"; steps=$2; shift 2 ;;
    --ranks) ranks=${2:-}; shift 2 ;;
    --impulse-opts) opts=${2:-}; shift 2 ;;
    -*) bad "unknown option $1" ;;
    *) if [ -z "$out" ]; then out=$1; else tag=$1; fi; shift ;;
  esac
done
[ -n "$out" ] || bad "OUTDIR is required"
cd "$out"
[ -f "mound_$tag.data" ] || bad "no mound_$tag.data in $out (run bench/impulse.sh first)"
dt=$(grep "^timestep" "log.$tag" | tail -1 | awk '{print $2}')  # the line with the value
sed -e "s/^read_data .*/read_data mound_$tag.data/" -e '/^dump/d' -e '/^write_data/d' \
    -e 's/^variable        every equal .*/variable        every equal 1/' "$ex/in.release" > in.rounds
echo "settled mound of $tag, dt $dt, $steps steps"
echo "ranks | spanning islands (mean) | rounds per pass (max, mean) | largest island"
for np in $ranks; do
  mpirun --allow-run-as-root --oversubscribe -np "$np" "$lmp" -in in.rounds -var method impulse \
    -var dt "$dt" -var nsteps "$steps" -var tag "rounds$np" -var impulse_opts "$opts" \
    -log "log.rounds$np" -screen none
  awk -v np="$np" '/^Step/ { for (i = 1; i <= NF; i++) c[$i] = i; on = 1; next }
    on && NF > 10 && $1 + 0 > 0 { n++; s += $c["f_integrate[3]"]; r += $c["f_integrate[8]"];
      if ($c["f_integrate[8]"] > m) m = $c["f_integrate[8]"];
      if ($c["f_integrate[2]"] > l) l = $c["f_integrate[2]"] }
    /^Loop time/ { on = 0 }
    END { printf "%d | %.1f | %d, %.1f | %d\n", np, s / n, m, r / n, l }' "log.rounds$np"
done
