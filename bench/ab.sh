#!/usr/bin/env bash
# Two lmp binaries on any deck, in turn on one core: the ratio B/A of their user CPU times,
# the least and the median over the rounds (a shared machine's noise only ever adds time, so
# the minima are the fairest pair; the median says how often). For the reference scene
# bench/run.sh --compare runs both at once on two cores instead.
#
#   bench/ab.sh DIR INPUT ROUNDS LMP_A LMP_B [lmp arguments ...]
#     run in DIR (where INPUT's data files are), e.g.
#     bench/ab.sh /tmp/mound in.release 3 /old/lmp build/lmp -var nsteps 200
# Environment: AB_CORE (the core to pin to with taskset, default 1).
set -euo pipefail
[ $# -ge 5 ] || { sed -n '2,10p' "$0"; exit 2; }
dir=$1 in=$2 rounds=$3 a=$4 b=$5
shift 5
core=${AB_CORE:-1}
for bin in "$a" "$b"; do [ -x "$bin" ] || { echo "ab.sh: $bin is not an executable" >&2; exit 2; }; done
a=$(realpath "$a") b=$(realpath "$b")
cd "$dir"
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
user_seconds() {
  /usr/bin/time -f "%U" -o "$tmp" taskset -c "$core" "$1" -in "$in" -log none -screen none "${@:2}" \
    >/dev/null || { echo "ab.sh: $1 failed on $in" >&2; exit 1; }
  cat "$tmp"
}
ta=() tb=()
for r in $(seq "$rounds"); do
  ta+=("$(user_seconds "$a" "$@")")
  tb+=("$(user_seconds "$b" "$@")")
  echo "round $r: A ${ta[-1]} s, B ${tb[-1]} s"
done
python3 - "${ta[*]}" "${tb[*]}" <<'PY'
import statistics, sys
a = [float(x) for x in sys.argv[1].split()]
b = [float(x) for x in sys.argv[2].split()]
print("B/A least %.3f median %.3f (A least %.2f s, B least %.2f s)"
      % (min(b) / min(a), statistics.median(b) / statistics.median(a), min(a), min(b)))
PY
