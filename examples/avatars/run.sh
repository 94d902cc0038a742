#!/usr/bin/env bash
# Avatars example: synthetic labelled CT volume -> shape library -> packed sample ->
# rendering -> settling run. Called by `./lsdem example avatars` (which sets LSDEM_LMP and
# LSDEM_SHAPE_TOOL); NP=2 by default, OUT the output folder (default out/).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$here/../common.sh"
np=${NP:-2}
n=${NGRAINS:-120}
out=${OUT:-$here/out}
enter_out "$out"

# 1. a labelled volume: 45 bumpy ellipsoids in 120^3 voxels (raw uint16, like a watershed
#    segmentation exported from a CT scan)
/usr/bin/python3 "$here/make_labels.py" labels.raw 120 45 7

# 2. every label becomes a grain shape (exact distance transform, principal frame); the
#    in-situ sample (grains at their scan poses) comes along as insitu.data.
#    Voxel 0.1 mm: grains of ~1.7 mm.
"$shape" from-labels labels.raw grains.lslib --raw 120 120 120 u16 --voxel 1e-4 \
  --min-voxels 100 --nodes 300 --data insitu.data --density 2650 2> from-labels.log
"$shape" list grains.lslib > list.txt
head -n 6 list.txt

# 3. a loose random packing of N grains drawn from the library in an 8 x 8 x 20 mm box
"$shape" pack grains.lslib packed.data --count "$n" --box 0.008 0.008 0.020 --seed 1 \
  --density 2650

# 4. look at it: the in-situ sample and the packing (ray-marched level sets)
"$shape" render grains.lslib insitu.data insitu.png
"$shape" render grains.lslib packed.data packed.png
[ "${1:-}" = prepare ] && exit 0

# 5. settle it under gravity (the deck sets dt = 0.05 sqrt(m_min / kn))
mpi_for "$np"
echo "running lmp on $np rank(s): $n grains, ${NSTEPS:-15000} steps (progress in $out/log.lammps)"
start=$SECONDS
"${mpi[@]}" "$lmp" -in "$here/in.avatars" -var nsteps "${NSTEPS:-15000}" -log log.lammps -echo none -screen none
echo "lmp took $((SECONDS - start)) s"
grep "^Loop time" log.lammps | tail -n 1
"$shape" render grains.lslib settled.data settled.png
echo "results: $out/packed.png, $out/settled.png, $out/insitu.png, $out/dump.avatars, $out/log.lammps"
