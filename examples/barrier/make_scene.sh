#!/usr/bin/env bash
# The barrier-test scene (ETAG 027-style, issue 34 item 4): a level-set cube (half-size H,
# 2000 surface nodes, mass M) above a horizontal hexagonal net (balls of radius 0.08, mass
# 1e-4, spacing 0.2, rest length 0.19: 5 % pretension, K, axial damping C) of L x L whose
# four edges are clamped; the net lies in z = 0, the cube's centre above its middle.
#   make_scene.sh OUTDIR [L] [M] [K] [C] [H]    (defaults 3 0.1 5 0.03 0.3)
# lsdem-shape from LSDEM_SHAPE_TOOL. Writes OUTDIR/all.lslib (shape 1 the cube, 2 the
# ball), net.data (the cube is atom 1, group grains), net.in, net.net and cube.in (the
# cube's half-size, for the deck).
set -euo pipefail
out=$1
size=${2:-3}
mass=${3:-0.1}
k=${4:-5}
damp=${5:-0.03}
half=${6:-0.3}
shape=${LSDEM_SHAPE_TOOL:-$(cd "$(dirname "$0")" && pwd)/../../build/lsdem-shape}
mkdir -p "$out"
cd "$out"
"$shape" analytic block.lslib box "$half" "$half" "$half" --nodes 2000 --name cube >/dev/null
"$shape" analytic ball.lslib sphere 0.08 --analytic >/dev/null
"$shape" merge all.lslib block.lslib ball.lslib >/dev/null
rm -f block.lslib ball.lslib
# the cube, unrotated, over the net's middle (the deck moves it to the footprint's centre):
# density = M / (2H)^3
density=$(awk -v m="$mass" -v h="$half" 'BEGIN { printf "%.17g", m / (8 * h * h * h) }')
mid=$(awk -v l="$size" 'BEGIN { printf "%.17g", l / 2 }')
cat > block.data <<DATA
LSDEM barrier block (make_scene.sh)

1 atoms
1 atom types

-$size $size xlo xhi
-$size $size ylo yhi
-$size $size zlo zhi

Atoms # lsdem

1 1 1 $density 0 0 1 1 0 0 0
DATA
"$shape" net net --library all.lslib --shape 2 --rb 0.08 --spacing 0.2 --size "$size" "$size" \
  --rest 0.19 --k "$k" --damp "$damp" --mass 1e-4 --origin "-$mid" "-$mid" 0 \
  --grains block.data >/dev/null
rm -f block.data
echo "variable half equal $half    # the cube's half-size (make_scene.sh)" > cube.in
