#!/usr/bin/env bash
# Impulse against penalty LS-DEM on the container release (report §4.6.1, Table 4.1/4.2).
#
#   bench/impulse.sh [OUTDIR] [--grains N] [--nodes K] [--seeds "7 8 9"] [--time T]
#                    [--muls "1 4 8 16"] [--np2 M|none] [--fill-time T] [--reuse]
#                    [--impulse-opts "keyword value ..." | --variants "NAME:OPTS;NAME:OPTS"]
#
# examples/container_release makes the scene (N angular grains, default 1600, four sizes,
# mass ratio 30, K surface nodes per grain, default 120), settles it in a smooth cylinder
# (penalty, --fill-time s, default 2.5) and releases it: the penalty method at
# dt = 0.1 sqrt(m_min/kn) (kn = 3e4 per node), then the impulse method at dt times each of
# --muls, each for --time s (default 8) on one rank; and the impulse run at dt x M (--np2,
# default the largest multiple; none: skip) on two ranks.
# --seeds: one packing per pack seed, each in OUTDIR/seed<S>/ (scene, fill and every run);
# without --seeds one packing, seed 7, in OUTDIR itself.
# --variants: impulse settings side by side, "NAME:fix impulse/lsdem keywords" separated by
# ';' (NAME: letters, digits, '.', '-'), each run at every multiple (and at --np2), runs
# impulse_NAME_x<m>; without it one setting, --impulse-opts (default none: the fix's
# defaults), runs impulse_x<m>.
# Prints the tables of bench/impulse_report.py (per run: CPU time, speed-up over the
# packing's penalty run, mound height and spread and their difference from it, islands, ETM
# iterations, passes, label rounds, penetration; per run over the packings: mean, sample std
# and min..max of height and spread, the verdicts against the penalty mounds; the fix's
# counters) and writes into OUTDIR (default bench/out/impulse): impulse.csv,
# impulse_summary.csv, impulse_counters.csv, impulse_error.png (error against run time, one
# series per variant), impulse_mounds.png (renderings of the first packing), and per
# packing the logs and the final dumps. Timings on a shared machine vary by +-20 %.
# --reuse continues an interrupted benchmark in OUTDIR: a packing's scene and fill are kept
# when its filled.data exists (and its scene.txt says the same grains, nodes and seed), and
# every run whose log has its "Loop time" is kept.
# Environment: LSDEM_LMP, LSDEM_SHAPE_TOOL, LSDEM_BUILD_DIR.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
ex=$here/../examples/container_release
build=${LSDEM_BUILD_DIR:-$here/../build}
lmp=${LSDEM_LMP:-$build/lmp}
shape=${LSDEM_SHAPE_TOOL:-$build/lsdem-shape}
out="" grains=1600 nodes=120 seeds="" t_end=8 muls="1 4 8 16" np2="" opts="" t_fill=2.5 reuse=0
variants="" opts_given=0
bad() { echo "bench/impulse.sh: $*" >&2; exit 2; }
number() { [[ "$2" =~ ^[0-9]+([.][0-9]+)?([eE][-+]?[0-9]+)?$ ]] || bad "$1 needs a positive number, not '$2'"; }
while [ $# -gt 0 ]; do
  case "$1" in
    --grains) [[ "${2:-}" =~ ^[1-9][0-9]*$ ]] || bad "--grains needs a positive integer, not '${2:-}'"
              grains=$2; shift 2 ;;
    --nodes) [[ "${2:-}" =~ ^[1-9][0-9]*$ ]] || bad "--nodes needs a positive integer, not '${2:-}'"
             nodes=$2; shift 2 ;;
    --seeds) for s in ${2:-}; do [[ "$s" =~ ^[0-9]+$ ]] || bad "--seeds needs integers >= 0, not '$s'"; done
             [ -n "${2// /}" ] || bad "--seeds needs a list"
             [ "$(echo ${2} | tr ' ' '\n' | sort | uniq -d)" = "" ] || bad "--seeds: a seed twice in '$2'"
             seeds=$2; shift 2 ;;
    --time) number --time "${2:-}"; t_end=$2; shift 2 ;;
    --fill-time) number --fill-time "${2:-}"; t_fill=$2; shift 2 ;;
    --muls) for m in ${2:-}; do [[ "$m" =~ ^[1-9][0-9]*$ ]] || bad "--muls needs positive integers, not '$m'"; done
            [ -n "${2:-}" ] || bad "--muls needs a list"; muls=$2; shift 2 ;;
    --np2) [[ "${2:-}" =~ ^([1-9][0-9]*|none)$ ]] || bad "--np2 needs a multiple or none, not '${2:-}'"
           np2=$2; shift 2 ;;
    --impulse-opts) opts=${2:-}; opts_given=1; shift 2 ;;
    --variants) [ -n "${2:-}" ] || bad "--variants needs 'NAME:OPTS;NAME:OPTS'"
                variants=$2; shift 2 ;;
    --reuse) reuse=1; shift ;;
    -*) bad "unknown option $1" ;;
    *) [ -z "$out" ] || bad "one OUTDIR only ($out, $1)"; out=$1; shift ;;
  esac
done
# the impulse settings: vnames[i] ("" for the single unnamed one) with vopts[i]
vnames=() vopts=()
if [ -n "$variants" ]; then
  [ "$opts_given" = 0 ] || bad "give --impulse-opts or --variants, not both (a variant holds its options)"
  IFS=';' read -r -a items <<< "$variants"
  for it in "${items[@]}"; do
    [ -n "${it//[[:space:]]/}" ] || continue
    [[ "$it" == *:* ]] || bad "--variants: '$it' is not NAME:OPTS"
    name=${it%%:*} name=${name//[[:space:]]/}
    [[ "$name" =~ ^[A-Za-z0-9][A-Za-z0-9.-]*$ ]] || bad "--variants: a name is letters, digits, '.' and '-', not '$name'"
    for v in "${vnames[@]}"; do [ "$v" != "$name" ] || bad "--variants: the name $name twice"; done
    read -r -a words <<< "${it#*:}"
    o="${words[*]}"  # the keywords, separated by single spaces
    vnames+=("$name") vopts+=("$o")
  done
  [ "${#vnames[@]}" -gt 0 ] || bad "--variants needs 'NAME:OPTS;NAME:OPTS'"
else
  vnames=("") vopts=("$opts")
fi
out=${out:-$here/out/impulse}
[ -z "$np2" ] && np2=$(echo "$muls" | tr ' ' '\n' | sort -n | tail -1)
[ -x "$lmp" ] || bad "no lmp at $lmp (./lsdem build first)"
# the packings: folder and pack seed
if [ -n "$seeds" ]; then
  pdirs=() pseeds=()
  for s in $seeds; do pdirs+=("seed$s") pseeds+=("$s"); done
else
  pdirs=(.) pseeds=(7)
fi
mkdir -p "$out"
cd "$out"
out=$(pwd)
vtag() { if [ -n "$1" ]; then echo "impulse_$1"; else echo impulse; fi; }
echo "== $grains grains, $nodes nodes per grain; packings (seeds): ${pseeds[*]}; release $t_end s"
for i in "${!vnames[@]}"; do
  echo "== impulse setting $(vtag "${vnames[$i]}"): ${vopts[$i]:-(none: the defaults of the fix)}"
done

kept() { [ "$reuse" = 1 ] && [ -f "$1" ] && { [ -z "${2:-}" ] || grep -q "$2" "$1"; }; }
mpi2=(mpirun --allow-run-as-root --oversubscribe -np 2)
steps() { /usr/bin/python3 -c "print(round($1 / $2))"; }

release() {  # tag method dt-multiple ranks opts
  local tag=$1 method=$2 m=$3 np=$4 o=$5 mpi=()
  [ "$np" -gt 1 ] && mpi=("${mpi2[@]}")
  local d
  d=$(/usr/bin/python3 -c "print('%.6g' % ($dt * $m))")
  echo "== $tag: $method, dt = $d, $(steps "$t_end" "$d") steps, $np rank(s)"
  if kept "log.$tag" "^Loop time"; then
    echo "(kept: log.$tag)"
  else
    "${mpi[@]}" "$lmp" -in "$ex/in.release" -var method "$method" -var dt "$d" \
      -var nsteps "$(steps "$t_end" "$d")" -var tag "$tag" -var impulse_opts "$o" \
      -log "log.$tag" -screen none
  fi
  grep "^Loop time" "log.$tag"
  "$shape" render grains.lslib "mound_$tag.dump" "render_$tag.png" --view y --size 480 300 \
    >/dev/null 2>&1 || true
}

tags=(penalty)
for i in "${!vnames[@]}"; do
  for m in $muls; do tags+=("$(vtag "${vnames[$i]}")_x$m"); done
done
if [ "$np2" != none ]; then
  for i in "${!vnames[@]}"; do tags+=("$(vtag "${vnames[$i]}")_x${np2}_np2"); done
fi

for k in "${!pdirs[@]}"; do
  pdir=${pdirs[$k]} pseed=${pseeds[$k]}
  mkdir -p "$out/$pdir"
  cd "$out/$pdir"
  [ "$pdir" = . ] || echo "==== packing $pdir (pack seed $pseed): $out/$pdir"
  scene="grains $grains nodes $nodes seed $pseed"
  if kept filled.data; then
    if [ -f scene.txt ] && [ "$(cat scene.txt)" != "$scene" ]; then
      bad "--reuse: $out/$pdir holds the scene '$(cat scene.txt)', not '$scene'"
    fi
    echo "== scene and fill: kept ($out/$pdir/filled.data)"
  else
    echo "== scene: $grains grains, $nodes nodes, pack seed $pseed (examples/container_release/make_scene.sh)"
    rm -f scene.txt
    LSDEM_SHAPE_TOOL=$shape bash "$ex/make_scene.sh" . "$grains" "$nodes" "$pseed"
  fi
  # dt = 0.1 sqrt(m_min / kn) (report eq 4.47), m_min from the smallest shape at density
  # 2.65; and its equivalent diameter d_min (the penetration's yardstick)
  dd=$(/usr/bin/python3 - "$shape" <<'EOF'
import math, subprocess, sys
rows = subprocess.run([sys.argv[1], "list", "grains.lslib"], capture_output=True, text=True,
                      check=True).stdout.splitlines()
vol = min(float(r.split()[-4]) for r in rows[2:] if r.strip())  # ... volume I1 I2 I3
print("%.4g %.4g" % (0.1 * (2.65 * vol / 3.0e4) ** 0.5, (6 * vol / math.pi) ** (1 / 3)))
EOF
)
  dt=${dd% *} dmin=${dd#* }
  echo "dt = $dt (0.1 sqrt(m_min/kn)); release $t_end s = $(steps "$t_end" "$dt") penalty steps"
  if ! kept filled.data; then
    echo "== fill: $t_fill s in the container (penalty, 2 ranks)"
    "${mpi2[@]}" "$lmp" -in "$ex/in.fill" -var dt "$dt" -var nsteps "$(steps "$t_fill" "$dt")" \
      -log log.fill -screen none
    echo "$scene" > scene.txt
  fi
  release penalty penalty 1 1 ""
  for i in "${!vnames[@]}"; do
    for m in $muls; do
      release "$(vtag "${vnames[$i]}")_x$m" impulse "$m" 1 "${vopts[$i]}"
    done
  done
  if [ "$np2" != none ]; then
    for i in "${!vnames[@]}"; do
      release "$(vtag "${vnames[$i]}")_x${np2}_np2" impulse "$np2" 2 "${vopts[$i]}"
    done
  fi
done
cd "$out"
echo "== figures ($out)"
rargs=("--dmin=$dmin")
packs=()
for k in "${!pdirs[@]}"; do packs+=("${pdirs[$k]}=${pseeds[$k]}"); done
rargs+=("--packings=${packs[*]}")
for i in "${!vnames[@]}"; do rargs+=("--variant=${vnames[$i]}:${vopts[$i]}"); done
/usr/bin/python3 "$here/impulse_report.py" "${rargs[@]}" . "$grains" "${tags[@]}"
