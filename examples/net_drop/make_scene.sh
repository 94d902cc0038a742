#!/usr/bin/env bash
# The net-drop scene (report §4.4.2, Figure 4.6): 10 angular grains (equivalent diameter
# 0.6, six random shapes, 100 surface nodes, density 0.01) packed loosely in a 2.4 x 2.4 x
# 1.6 box over a square hexagonal net of 21 x 24 balls (radius 0.08, mass 1e-5, spacing
# 0.2, rest length 0.16: 20 % pretension; K = 0.1, axial damping 0.001) whose four edges
# are clamped, 0.4 below the lowest grain.
#   make_scene.sh OUTDIR [SEED]   (lsdem-shape from LSDEM_SHAPE_TOOL)
# Writes OUTDIR/all.lslib (shapes 1-6 the grains, 7 the ball) and net.data, net.in, net.net.
set -euo pipefail
out=$1
seed=${2:-3}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$here/../common.sh"
mkdir -p "$out"
cd "$out"
sand_shapes grains.lslib 0.6 0.03 11 d0.6
"$shape" analytic ball.lslib sphere 0.08 --analytic >/dev/null
"$shape" merge all.lslib grains.lslib ball.lslib >/dev/null
rm -f grains.lslib ball.lslib
"$shape" pack all.lslib packed.data --count 10 --box 2.4 2.4 1.6 --seed "$seed" --gap 0.05 \
  --weights 1,1,1,1,1,1,0 --density 0.01
"$shape" net net --library all.lslib --shape 7 --rb 0.08 --spacing 0.2 --size 4 4 \
  --rest 0.16 --k 0.1 --damp 0.001 --mass 1e-5 --origin -0.8 -0.8 -0.2 --grains packed.data \
  --margin 2
rm -f packed.data
