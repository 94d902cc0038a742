#!/usr/bin/env bash
# Protection nets across the avalanche's channel (issue 34): NETS (1 or 2) vertical
# hexagonal nets of bonded balls across the channel, their four edges clamped (posts at
# the sides, a ground anchor line and a top cable), each added to the data file before it
# by lsdem-shape net --grains (its own atom IDs, types, molecule, bond type and groups
# netK, netK_free, netK_clamp). Net K stands at x = XK, spans y from -10 to 10 and HK up
# from the channel floor's height at (XK, 0) (valley.asc, bilinear: where the valley's
# sides rise the net's lower corners lie in the ground, which the balls do not feel), its
# normal e1 x e2 = +x pointing upslope. Balls of radius 0.1 and mass 0.3 (not below the
# lightest grain's, so the grains' step holds for the balls' contacts) at spacing 0.35
# (gaps of 0.15, below the smallest grain), bonds of stiffness K and axial damping C.
#   make_nets.sh OUTDIR NETS [X1] [X2] [H1] [H2] [K] [C]
# defaults: X1 -5 (in the fan), X2 -13 (on the run-out), H1 1 (low: the flow overtops it),
# H2 2.5, K 5000, C 5 (the rows cover HK to the nearest row: 0.91 and 2.42 high). Reads
# OUTDIR/grains.lslib, source.data, valley.asc (make_scene.sh); writes OUTDIR/nets.lslib
# (the grains' shapes and the ball), netK.data, netK.in, netK.net: the deck (-var nets
# NETS) reads net${NETS}.data (the grains and every net) and includes net1.in, net2.in.
# lsdem-shape from LSDEM_SHAPE_TOOL.
set -euo pipefail
out=$1
nets=$2
xs=("${3:--5}" "${4:--13}")
hs=("${5:-1}" "${6:-2.5}")
k=${7:-5000}
damp=${8:-5}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
shape=${LSDEM_SHAPE_TOOL:-$here/../../build/lsdem-shape}
case "$nets" in 1|2) ;; *) echo "make_nets.sh: NETS must be 1 or 2, not '$nets'" >&2; exit 2 ;; esac
cd "$out"
"$shape" analytic ball.lslib sphere 0.1 --analytic >/dev/null
"$shape" merge nets.lslib grains.lslib ball.lslib >/dev/null
rm -f ball.lslib
ball=$("$shape" list nets.lslib | awk 'NR == 1 { print $2 }')    # the last shape, 1-based
prev=source.data
for n in $(seq 1 "$nets"); do
  x=${xs[$((n - 1))]}
  z=$(/usr/bin/python3 "$here/terrain.py" valley.asc "$x")
  "$shape" net "net$n" --library nets.lslib --shape "$ball" --rb 0.1 --spacing 0.35 \
    --size 20 "${hs[$((n - 1))]}" --e1 0 1 0 --e2 0 0 1 --origin "$x" -10 "$z" --mass 0.3 \
    --k "$k" --damp "$damp" --grains "$prev" --name "net$n" --margin 0
  prev=net$n.data
done
