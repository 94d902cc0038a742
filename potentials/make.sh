#!/usr/bin/env bash
# Make the shape libraries of potentials/ (README.md lists them): reproducible, the same
# bytes for the same lsdem-shape. Lengths are in voxels (pixels), the report's units
# (Table 3.1): scale with the include snippets' voxel size k.
#   bash potentials/make.sh [OUTDIR]     (default: this folder; ./lsdem potentials)
#   COUNT=N  grains per sand library (default 8)
# Takes about 20 s (the 750-node library most of it).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
shape=${LSDEM_SHAPE_TOOL:-$here/../build/lsdem-shape}
out=${1:-$here}
count=${COUNT:-8}
[ -x "$shape" ] || { echo "make.sh: no lsdem-shape at $shape (build first: ./lsdem build)" >&2; exit 1; }
mkdir -p "$out"
cd "$out"
say() { printf 'potentials: %-18s %s\n' "$1" "$2"; }

# sand-like random grains, equivalent diameter 30 voxels (median, lognormal spread 0.15),
# Zingg elongation 0.75 and flatness 0.8, angularity 0.12: one set of grains (one seed) at
# three resolutions. 250 and 750 nodes are the report's low- and high-resolution avatars
# (report chapter 3: 9-10 and 4.3 um/voxel scans); 100 nodes is for quick tests.
sand() { # NAME NODES SPACING
  "$shape" random "$1.lslib" --count "$count" --size 30 --size-spread 0.15 --elongation 0.75 \
    --flatness 0.8 --angularity 0.12 --seed 2022 --nodes "$2" --spacing "$3" --name sand \
    >/dev/null 2>"$1.log"
  say "$1.lslib" "$count sand grains, $2 nodes, grid spacing $3 voxel"
}
sand sand_100 100 2.0
sand sand_250 250 1.0
sand sand_750 750 0.6

# a sphere of diameter 30 voxels: analytic (exact level set, cheapest contact) and as a grid
"$shape" analytic sphere.lslib sphere 15 --nodes 400 --analytic --name sphere >/dev/null 2>sphere.log
say sphere.lslib "analytic sphere R 15, 400 nodes"
"$shape" analytic sphere_grid.lslib sphere 15 --nodes 400 --spacing 1 --name sphere_grid \
  >/dev/null 2>sphere_grid.log
say sphere_grid.lslib "sphere R 15 as a grid (spacing 1), 400 nodes"
# ellipsoids of aspect ratios 1.5 and 2 (semi-axes in voxels), grids
"$shape" analytic ell_a.lslib ellipsoid 18 15 12 --nodes 400 --spacing 1 --name ellipsoid_18_15_12 \
  >/dev/null 2>ellipsoids.log
"$shape" analytic ell_b.lslib ellipsoid 20 14 10 --nodes 400 --spacing 1 --name ellipsoid_20_14_10 \
  >/dev/null 2>>ellipsoids.log
"$shape" merge ellipsoids.lslib ell_a.lslib ell_b.lslib >/dev/null
rm -f ell_a.lslib ell_b.lslib
say ellipsoids.lslib "ellipsoids 18x15x12 and 20x14x10, 400 nodes each"
for f in sand_100 sand_250 sand_750 sphere sphere_grid ellipsoids; do
  "$shape" verify "$f.lslib" >/dev/null || { echo "make.sh: $f.lslib does not verify" >&2; exit 1; }
done
