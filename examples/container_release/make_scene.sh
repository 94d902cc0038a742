#!/usr/bin/env bash
# The container-release scene (report §4.6.1 analog): angular grains of four sizes
# (equivalent diameters 0.4 to 1.25, mass ratio (1.25/0.4)^3 = 30.5), six random shapes per
# size, packed loosely in a cylinder of radius 4.5 (lsdem-shape random, merge, pack).
#   make_scene.sh OUTDIR [NGRAINS] [NODES] [SEED]   (default 1600; lsdem-shape from
#   LSDEM_SHAPE_TOOL)
# NODES (default 120, or LSDEM_SCENE_NODES): surface nodes per grain; the level-set grid
# spacing is D/15, finer when the nodes need it: D/max(15, round(0.8 sqrt(NODES))), about
# two thirds of the mean node spacing (D/40 for the report's ~2,500 nodes). The shapes (their
# random seeds) are the same at every node count. SEED (default 7, or LSDEM_SCENE_SEED):
# the packing's random seed.
# Writes OUTDIR/grains.lslib and OUTDIR/packed.data; prints the pack tool's line.
set -euo pipefail
out=$1
n=${2:-1600}
nodes=${3:-${LSDEM_SCENE_NODES:-120}}
pack_seed=${4:-${LSDEM_SCENE_SEED:-7}}
[[ "$nodes" =~ ^[1-9][0-9]*$ ]] || { echo "make_scene.sh: NODES must be a positive integer, not '$nodes'" >&2; exit 2; }
[[ "$pack_seed" =~ ^[0-9]+$ ]] || { echo "make_scene.sh: SEED must be an integer >= 0, not '$pack_seed'" >&2; exit 2; }
shape=${LSDEM_SHAPE_TOOL:-$(dirname "$0")/../../build/lsdem-shape}
# grid spacing D/div: 15 up to ~350 nodes, then about 2/3 of the node spacing sqrt(area/N)
div=$(/usr/bin/python3 -c "print(max(15, round(0.8 * $nodes ** 0.5)))")
mkdir -p "$out"
cd "$out"
parts=()
seed=1
for d in 0.4 0.6 0.85 1.25; do
  h=$(/usr/bin/python3 -c "print($d / $div)")
  "$shape" random "size$d.lslib" --count 6 --size "$d" --elongation 0.75 --flatness 0.75 \
    --angularity 0.15 --roughness 0.02 --nodes "$nodes" --spacing "$h" --seed "$seed" \
    --name "d$d" >/dev/null 2>&1
  parts+=("size$d.lslib")
  seed=$((seed + 1))
done
"$shape" merge grains.lslib "${parts[@]}" >/dev/null
rm -f "${parts[@]}"
# number fractions 40/30/20/10 % from the smallest size up (weights per shape, 6 per size)
w=$(/usr/bin/python3 -c "print(','.join(str(x) for x in [4]*6 + [3]*6 + [2]*6 + [1]*6))")
# the height holds the grains at a solid fraction of about 0.34
hgt=$(/usr/bin/python3 -c "print(round(max(3.0, 15 * $n / 1600), 3))")
"$shape" pack grains.lslib packed.data --count "$n" --cylinder 4.5 "$hgt" --density 2.65 \
  --weights "$w" --seed "$pack_seed" --max-tries 5000 --strict
