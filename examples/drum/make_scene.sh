#!/usr/bin/env bash
# The drum scene: 200 angular grains (equivalent diameters 0.6 and 0.9, six random shapes
# each, 100 surface nodes) packed loosely in a box that fits inside the drum of radius 6
# (axis y, length 2.6), centred on the drum's axis by in.drum.
#   make_scene.sh OUTDIR [NGRAINS] [SEED]   (lsdem-shape from LSDEM_SHAPE_TOOL)
# Writes OUTDIR/grains.lslib and OUTDIR/packed.data.
set -euo pipefail
out=$1
n=${2:-200}
seed=${3:-5}
shape=${LSDEM_SHAPE_TOOL:-$(dirname "$0")/../../build/lsdem-shape}
mkdir -p "$out"
cd "$out"
"$shape" random small.lslib --count 6 --size 0.6 --elongation 0.75 --flatness 0.75 \
  --angularity 0.15 --roughness 0.02 --nodes 100 --spacing 0.03 --seed 11 --name d0.6 >/dev/null 2>&1
"$shape" random large.lslib --count 6 --size 0.9 --elongation 0.75 --flatness 0.75 \
  --angularity 0.15 --roughness 0.02 --nodes 100 --spacing 0.045 --seed 12 --name d0.9 >/dev/null 2>&1
"$shape" merge grains.lslib small.lslib large.lslib >/dev/null
rm -f small.lslib large.lslib
# box 7 x 2.4 x 8: its corners 5.3 from the axis once centred, inside the radius 6
"$shape" pack grains.lslib packed.data --count "$n" --box 7 2.4 8 --seed "$seed" --gap 0.02
