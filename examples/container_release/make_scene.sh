#!/usr/bin/env bash
# The container-release scene (report §4.6.1 analog): angular grains of four sizes
# (equivalent diameters 0.4 to 1.25, mass ratio (1.25/0.4)^3 = 30.5), six random shapes per
# size, packed loosely in a cylinder of radius 4.5 (lsdem-shape random, merge, pack).
#   make_scene.sh OUTDIR [NGRAINS]   (default 1600; lsdem-shape from LSDEM_SHAPE_TOOL)
# Writes OUTDIR/grains.lslib and OUTDIR/packed.data; prints the pack tool's line.
set -euo pipefail
out=$1
n=${2:-1600}
shape=${LSDEM_SHAPE_TOOL:-$(dirname "$0")/../../build/lsdem-shape}
mkdir -p "$out"
cd "$out"
parts=()
seed=1
for d in 0.4 0.6 0.85 1.25; do
  h=$(/usr/bin/python3 -c "print($d / 15)")
  "$shape" random "size$d.lslib" --count 6 --size "$d" --elongation 0.75 --flatness 0.75 \
    --angularity 0.15 --roughness 0.02 --nodes 120 --spacing "$h" --seed "$seed" \
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
  --weights "$w" --seed 7 --max-tries 5000 --strict
