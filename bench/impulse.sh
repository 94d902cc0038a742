#!/usr/bin/env bash
# Impulse against penalty LS-DEM on the container release (report §4.6.1, Table 4.1/4.2).
#
#   bench/impulse.sh [OUTDIR] [--grains N] [--time T] [--muls "1 4 8 16"] [--np2 M|none]
#                    [--impulse-opts "keyword value ..."] [--fill-time T] [--reuse]
#
# examples/container_release makes the scene (N angular grains, default 1600, four sizes,
# mass ratio 30), settles it in a smooth cylinder (penalty, --fill-time s, default 2.5) and
# releases it: the penalty method at dt = 0.1 sqrt(m_min/kn) (kn = 3e4 per node), then the
# impulse method at dt times each of --muls, each for --time s (default 8) on one rank; and
# the impulse run at dt x M (--np2, default the largest multiple; none: skip) on two ranks.
# Prints the table of bench/impulse_report.py (CPU time, speed-up over the penalty run,
# mound height and spread and their difference from the penalty run, islands, ETM
# iterations, passes, label rounds, penetration) and writes into OUTDIR (default
# bench/out/impulse): impulse.csv, impulse_error.png (error against run time),
# impulse_mounds.png (renderings), the logs, the final dumps. Timings on a shared machine
# vary by +-20 %. --reuse continues an interrupted benchmark in OUTDIR: the scene and fill
# are kept when filled.data exists, and every run whose log has its "Loop time" is kept.
# Environment: LSDEM_LMP, LSDEM_SHAPE_TOOL, LSDEM_BUILD_DIR.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
ex=$here/../examples/container_release
build=${LSDEM_BUILD_DIR:-$here/../build}
lmp=${LSDEM_LMP:-$build/lmp}
shape=${LSDEM_SHAPE_TOOL:-$build/lsdem-shape}
out="" grains=1600 t_end=8 muls="1 4 8 16" np2="" opts="" t_fill=2.5 reuse=0
bad() { echo "bench/impulse.sh: $*" >&2; exit 2; }
number() { [[ "$2" =~ ^[0-9]+([.][0-9]+)?([eE][-+]?[0-9]+)?$ ]] || bad "$1 needs a positive number, not '$2'"; }
while [ $# -gt 0 ]; do
  case "$1" in
    --grains) [[ "${2:-}" =~ ^[1-9][0-9]*$ ]] || bad "--grains needs a positive integer, not '${2:-}'"
              grains=$2; shift 2 ;;
    --time) number --time "${2:-}"; t_end=$2; shift 2 ;;
    --fill-time) number --fill-time "${2:-}"; t_fill=$2; shift 2 ;;
    --muls) for m in ${2:-}; do [[ "$m" =~ ^[1-9][0-9]*$ ]] || bad "--muls needs positive integers, not '$m'"; done
            [ -n "${2:-}" ] || bad "--muls needs a list"; muls=$2; shift 2 ;;
    --np2) [[ "${2:-}" =~ ^([1-9][0-9]*|none)$ ]] || bad "--np2 needs a multiple or none, not '${2:-}'"
           np2=$2; shift 2 ;;
    --impulse-opts) opts=${2:-}; shift 2 ;;
    --reuse) reuse=1; shift ;;
    -*) bad "unknown option $1" ;;
    *) [ -z "$out" ] || bad "one OUTDIR only ($out, $1)"; out=$1; shift ;;
  esac
done
out=${out:-$here/out/impulse}
[ -z "$np2" ] && np2=$(echo "$muls" | tr ' ' '\n' | sort -n | tail -1)
[ -x "$lmp" ] || bad "no lmp at $lmp (./lsdem build first)"
mkdir -p "$out"
cd "$out"

kept() { [ "$reuse" = 1 ] && [ -f "$1" ] && { [ -z "${2:-}" ] || grep -q "$2" "$1"; }; }
if kept filled.data; then
  echo "== scene and fill: kept ($out/filled.data)"
else
  echo "== scene: $grains grains (examples/container_release/make_scene.sh)"
  LSDEM_SHAPE_TOOL=$shape bash "$ex/make_scene.sh" . "$grains"
fi
# dt = 0.1 sqrt(m_min / kn) (report eq 4.47), m_min from the smallest shape at density 2.65
dt=$(/usr/bin/python3 - "$shape" <<'EOF'
import subprocess, sys
rows = subprocess.run([sys.argv[1], "list", "grains.lslib"], capture_output=True, text=True,
                      check=True).stdout.splitlines()
vol = min(float(r.split()[-4]) for r in rows[2:] if r.strip())  # ... volume I1 I2 I3
print("%.4g" % (0.1 * (2.65 * vol / 3.0e4) ** 0.5))
EOF
)
steps() { /usr/bin/python3 -c "print(round($1 / $2))"; }
echo "dt = $dt (0.1 sqrt(m_min/kn)); release $t_end s = $(steps "$t_end" "$dt") penalty steps"

mpi2=(mpirun --allow-run-as-root --oversubscribe -np 2)
if ! kept filled.data; then
  echo "== fill: $t_fill s in the container (penalty, 2 ranks)"
  "${mpi2[@]}" "$lmp" -in "$ex/in.fill" -var dt "$dt" -var nsteps "$(steps "$t_fill" "$dt")" \
    -log log.fill -screen none
fi

release() {  # tag method dt-multiple ranks
  local tag=$1 method=$2 m=$3 np=$4 mpi=()
  [ "$np" -gt 1 ] && mpi=("${mpi2[@]}")
  local d
  d=$(/usr/bin/python3 -c "print('%.6g' % ($dt * $m))")
  echo "== $tag: $method, dt = $d, $(steps "$t_end" "$d") steps, $np rank(s)"
  if kept "log.$tag" "^Loop time"; then
    echo "(kept: log.$tag)"
  else
    "${mpi[@]}" "$lmp" -in "$ex/in.release" -var method "$method" -var dt "$d" \
      -var nsteps "$(steps "$t_end" "$d")" -var tag "$tag" -var impulse_opts "$opts" \
      -log "log.$tag" -screen none
  fi
  grep "^Loop time" "log.$tag"
  "$shape" render grains.lslib "mound_$tag.dump" "render_$tag.png" --view y --size 480 300 \
    >/dev/null 2>&1 || true
}
tags=(penalty)
release penalty penalty 1 1
for m in $muls; do
  release "impulse_x$m" impulse "$m" 1
  tags+=("impulse_x$m")
done
if [ "$np2" != none ]; then
  release "impulse_x${np2}_np2" impulse "$np2" 2
  tags+=("impulse_x${np2}_np2")
fi
echo "== figures ($out)"
/usr/bin/python3 "$here/impulse_report.py" . "$grains" "${tags[@]}"
