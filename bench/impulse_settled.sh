#!/usr/bin/env bash
# The settled mound's step: impulse against penalty at the penalty's own step (issue 33's
# goal: an impulse grain-step at dt x1 costs at most 2 penalty grain-steps).
#
#   bench/impulse_settled.sh DIR [--from TAG] [--steps N] [--rounds R] [--opts "KEYWORDS"]
#
# DIR is an output folder of bench/impulse.sh (its seed<S>/ packings, or DIR itself with one
# packing). From each packing's final mound of run TAG (default impulse_x16: mound_TAG.data,
# 8 s after the release, still creeping), both methods run N steps (default 1000) at the
# penalty step dt = 0.1 sqrt(m_min/kn) of examples/container_release/in.release, in turn on
# one core (AB_CORE, default 1), R rounds (default 2); --opts: fix impulse/lsdem keywords
# (default the deck's "method split"). Prints per packing and round the loop times and their
# ratio, then the least and the median ratio over all runs. Writes into each packing's
# folder log.settled_<method> and the deck's end files mound_settled_<method>.dump/.data.
# Environment: LSDEM_LMP, LSDEM_BUILD_DIR.
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
[ $# -ge 1 ] || { sed -n '2,16p' "$0"; exit 2; }
dir=$1
shift
from=impulse_x16 steps=1000 rounds=2 opts="method split"
while [ $# -gt 0 ]; do
  [ $# -ge 2 ] || { echo "impulse_settled.sh: $1 needs a value" >&2; exit 2; }
  case $1 in
    --from) from=$2 ;;
    --steps) steps=$2 ;;
    --rounds) rounds=$2 ;;
    --opts) opts=$2 ;;
    *) echo "impulse_settled.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift 2
done
for v in "--steps $steps" "--rounds $rounds"; do
  [[ ${v#* } =~ ^[1-9][0-9]*$ ]] || { echo "impulse_settled.sh: ${v% *} needs a positive integer, not ${v#* }" >&2; exit 2; }
done
[ -d "$dir" ] || { echo "impulse_settled.sh: $dir is not a folder (bench/impulse.sh's OUTDIR)" >&2; exit 2; }
dir=$(cd "$dir" && pwd)
lmp=${LSDEM_LMP:-${LSDEM_BUILD_DIR:-$top/build}/lmp}
[ -x "$lmp" ] || { echo "impulse_settled.sh: no lmp at $lmp (./lsdem build first)" >&2; exit 2; }
deck=$top/examples/container_release/in.release
core=${AB_CORE:-1}
# the penalty step: the packing's penalty run's (log.penalty), else the deck's default / 16
penalty_dt() {
  local d
  d=$(sed -n 's/^timestep *\([0-9][0-9.e-]*\)$/\1/p' "$1/log.penalty" 2>/dev/null | head -1)
  [ -n "$d" ] || d=$(sed -n 's/^variable *dt index \([0-9.e-]*\).*/\1/p' "$deck" |
    python3 -c "import sys; print('%.6g' % (float(sys.stdin.read()) / 16))")
  echo "$d"
}

packings=()
for p in "$dir"/seed* "$dir"; do [ -f "$p/mound_$from.data" ] && packings+=("$p"); done
[ ${#packings[@]} -gt 0 ] || { echo "impulse_settled.sh: no mound_$from.data under $dir" >&2; exit 2; }

loop_time() { sed -n 's/^Loop time of \([0-9.e+-]*\) .*/\1/p' "$1"; }
run() { # packing method -> loop seconds
  (cd "$1" && taskset -c "$core" "$lmp" -in "$deck" -var method "$2" -var dt "$(penalty_dt "$1")" \
    -var nsteps "$steps" -var data "mound_$from.data" -var tag "settled_$2" \
    -var impulse_opts "$opts" -log "log.settled_$2" -screen none >/dev/null)
  loop_time "$1/log.settled_$2"
}
ratios=()
echo "== $steps steps at the penalty step from mound_$from.data; impulse: $opts; core $core"
for p in "${packings[@]}"; do
  echo "$(basename "$p"): dt = $(penalty_dt "$p")"
  for r in $(seq "$rounds"); do
    tp=$(run "$p" penalty)
    ti=$(run "$p" impulse)
    ratio=$(python3 -c "print('%.2f' % ($ti / $tp))")
    ratios+=("$ratio")
    echo "$(basename "$p") round $r: penalty $tp s, impulse $ti s, impulse/penalty $ratio"
  done
done
python3 - "${ratios[*]}" <<'PY'
import statistics, sys
r = [float(x) for x in sys.argv[1].split()]
print("impulse/penalty grain-step: least %.2f median %.2f max %.2f over %d runs (goal <= 2)"
      % (min(r), statistics.median(r), max(r), len(r)))
PY
