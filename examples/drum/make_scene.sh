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
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$here/../common.sh"
mkdir -p "$out"
cd "$out"
sand_shapes small.lslib 0.6 0.03 11 d0.6
sand_shapes large.lslib 0.9 0.045 12 d0.9
"$shape" merge grains.lslib small.lslib large.lslib >/dev/null
rm -f small.lslib large.lslib
# box 7 x 2.4 x 8: its corners 5.3 from the axis once centred, inside the radius 6
"$shape" pack grains.lslib packed.data --count "$n" --box 7 2.4 8 --seed "$seed" --gap 0.02
