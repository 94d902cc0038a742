#!/usr/bin/env bash
# CT scan example: a grey-level, LZW-compressed CT stack (synthetic, of known grains) ->
# segmentation (lsdem-segment) -> shape library + in-situ data file -> settling in lmp.
# Called by `./lsdem example ct_scan` (which sets LSDEM_LMP and LSDEM_SHAPE_TOOL); NP=2 by
# default. SIZE, GRAINS, SEED change the scan, NSTEPS the run.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$here/../common.sh"
segment=$(dirname "$shape")/lsdem-segment
np=${NP:-2}
size=${SIZE:-128}
out=${OUT:-$here/out}
enter_out "$out"

# 1. the scan as it leaves a lab: 16-bit grey levels, one page per slice, LZW-compressed
#    (compressed by libtiff's own tiffcp); the grains it was made from go to scan.truth.raw
/usr/bin/python3 "$here/../../tools/synthetic_scan.py" make scan --size "$size" \
  --grains "${GRAINS:-260}" --seed "${SEED:-7}"
tiffcp -c lzw scan.tif scan_lzw.tif
rm scan.tif

# 2. one command from the grey-level stack to shapes and the in-situ data file
#    (voxel 0.1 mm: grains of about 1.8 mm); shape quality warnings go to segment.log
"$segment" scan_lzw.tif grains.lslib --voxel 1e-4 --labels labels.raw --nodes 200 \
  --data insitu.data --density 2650 2> segment.log

# 3. how well the segmentation found the grains the scan was made from
/usr/bin/python3 "$here/../../tools/synthetic_scan.py" score scan.truth.raw labels.raw "$size" \
  | tee score.txt

# 4. look at it, then let the in-situ sample settle under gravity between walls
"$shape" render grains.lslib insitu.data insitu.png
[ "${1:-}" = prepare ] && exit 0
mpi_for "$np"
echo "running lmp on $np rank(s): ${NSTEPS:-4000} steps (progress on screen, log in $out/log.lammps)"
start=$SECONDS
"${mpi[@]}" "$lmp" -in "$here/in.ct_scan" -var nsteps "${NSTEPS:-4000}" -log log.lammps -echo none
echo "lmp took $((SECONDS - start)) s"
"$shape" render grains.lslib settled.data settled.png
echo "results: $out/score.txt, $out/insitu.png, $out/settled.png, $out/log.lammps"
