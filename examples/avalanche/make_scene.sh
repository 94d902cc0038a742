#!/usr/bin/env bash
# The avalanche scene: the valley (make_terrain.py -> valley.asc, lsdem-shape terrain ->
# valley.band) and the source, angular grains of three sizes (equivalent diameters 0.6, 0.8
# and 1.1, four random shapes each, 120 surface nodes, number fractions 40/35/25 %: mean
# 0.8) packed loosely in a box (lsdem-shape random, merge, pack) laid as a slab on the
# upper slope (place_source.py).
#   make_scene.sh OUTDIR [NGRAINS] [RUNOUT] [SEED]
# NGRAINS (default 400), RUNOUT (run-out plane's inclination, 0 or 3 degrees; default 0),
# SEED (the packing's, default 7); the environment's VALLEY (U or V, default U) the valley's
# cross-section; lsdem-shape from LSDEM_SHAPE_TOOL. The band's spacing is 0.2 (a quarter
# of the mean grain size), its half-width 0.5 (2.5 spacings). Other scenes (the timing
# scene of bench/avalanche/timing.sh): TERRAIN_ARGS (more make_terrain.py options), SLAB
# (the pack's box A B C instead of 11 7 and the thickness below), PLACE_ARGS (more
# place_source.py options), each overriding what it repeats.
# Writes OUTDIR/valley.asc, valley.band, grains.lslib, source.data; prints the
# tools' reports (band.txt holds lsdem-shape terrain's).
set -euo pipefail
# shellcheck disable=SC2086 # TERRAIN_ARGS, SLAB, PLACE_ARGS: words on purpose
out=$1
n=${2:-400}
runout=${3:-0}
seed=${4:-7}
valley=${VALLEY:-U}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
shape=${LSDEM_SHAPE_TOOL:-$here/../../build/lsdem-shape}
py=/usr/bin/python3
[[ "$n" =~ ^[1-9][0-9]*$ ]] || { echo "make_scene.sh: NGRAINS must be a positive integer, not '$n'" >&2; exit 2; }
mkdir -p "$out"
cd "$out"
# the valley: 52 x 22 (68 x 24 for an inclined run-out, on which the grains run farther and
# spread wider), cell 0.5 (of the order of the grains), 25 deg slope onto the run-out
read -r x0 yw < <("$py" -c "print('-38 11' if float('$runout') == 0 else '-54 12')")
"$py" "$here/make_terrain.py" valley.asc --runout "$runout" --x0 "$x0" --ywidth "$yw" --shape "$valley" \
  ${TERRAIN_ARGS:-}
"$shape" terrain valley.asc valley.band --spacing 0.2 --width 0.5 > band.txt
grep -E "surface:|band:|stored bricks|surface check" band.txt
# the grains: grid spacing D/20, 120 surface nodes
parts=()
s=21
for d in 0.6 0.8 1.1; do
  h=$("$py" -c "print($d / 20)")
  "$shape" random "size$d.lslib" --count 4 --size "$d" --elongation 0.75 --flatness 0.75 \
    --angularity 0.15 --roughness 0.02 --nodes 120 --spacing "$h" --seed "$s" \
    --name "d$d" >/dev/null 2>&1
  parts+=("size$d.lslib")
  s=$((s + 1))
done
"$shape" merge grains.lslib "${parts[@]}" >/dev/null
rm -f "${parts[@]}"
# number fractions 40/35/25 % from the smallest size up (weights per shape, 4 per size);
# the box (11 along the slope, 7 across, 5.8 thick) holds 400 grains at a solid fraction of
# about 0.27: its thickness grows with NGRAINS
thick=$("$py" -c "print(round(5.8 * $n / 400, 3))")
"$shape" pack grains.lslib box.data --count "$n" --box ${SLAB:-11 7 $thick} --density 2.65 \
  --weights 8,8,8,8,7,7,7,7,5,5,5,5 --seed "$seed" --max-tries 5000 --strict
# the slab on the slope: its downhill base edge at x = 3.5, its uphill end near the top
# (14); the simulation box holds the terrain's extent and more (its faces stop no grain: a
# grain that left it would be lost)
"$py" "$here/place_source.py" box.data source.data --x0 3.5 --shape "$valley" --box $((x0 - 4)) 18 -16 16 -6 18 \
  ${PLACE_ARGS:-}
rm -f box.data
