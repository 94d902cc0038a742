#!/usr/bin/env bash
# Hopper discharge example: a conical hopper as a closed STL mesh (make_hopper.py) turned into
# a band file (lsdem-shape wall), an analytic sphere (lsdem-shape analytic), spheres on a
# lattice in the hopper (fill_hopper.py); in.hopper settles them on a plug, removes it and
# records the discharge; plot.py measures the bed and the rate and draws hopper.png.
#   run.sh [prepare|run|plot|all]     (default all; `prepare` makes the inputs only, `run`
#                                      makes them and runs lmp, `plot` analyses out/)
# Called by `./lsdem example hopper` (which sets LSDEM_LMP and LSDEM_SHAPE_TOOL).
# Environment: D (orifice diameter in grain diameters, 6), ANGLE (cone half-angle from the
# vertical in degrees, 60; 90 = flat bottom), RADIUS (bin radius, 7), HEIGHT (top of the
# wall, 16), NGRAINS (1500), SPACING and WIDTH of the band (0.25, 1.0), NP (MPI ranks, 2),
# NSETTLE (8000), NSTEPS (discharge steps, 60000; the run stops earlier when fewer than 5
# grains are left above the orifice), NVTK (ParaView frames every NVTK steps, 20000; 0 =
# none), OUT (output folder, out/).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$here/../common.sh"
py=/usr/bin/python3
stage=${1:-all}
case "$stage" in prepare|run|plot|all) ;; *) echo "run.sh: unknown stage '$stage' (prepare, run, plot, all)" >&2; exit 2 ;; esac
D=${D:-6} angle=${ANGLE:-60} radius=${RADIUS:-7} height=${HEIGHT:-16} n=${NGRAINS:-1500}
spacing=${SPACING:-0.25} width=${WIDTH:-1.0} np=${NP:-2}
nsettle=${NSETTLE:-8000} nsteps=${NSTEPS:-60000} nvtk=${NVTK:-20000}
out=${OUT:-$here/out}
enter_out "$out"
geo=(--orifice "$D" --half-angle "$angle" --radius "$radius" --height "$height")

prepare() {
  echo "prepare: hopper D = $D, half-angle $angle deg, bin radius $radius, wall top $height; $n spheres (in $out)"
  "$py" "$here/make_hopper.py" hopper.stl "${geo[@]}" > hopper.txt
  "$shape" wall hopper.stl hopper.band --spacing "$spacing" --width "$width" > band.txt
  grep -E "triangles|stored bricks|bytes" band.txt
  "$shape" analytic sphere.lslib sphere 0.5 --analytic --nodes 400 --name ball > /dev/null
  "$py" "$here/fill_hopper.py" hopper.data --count "$n" --pitch 1.06 "${geo[@]}" | tr '\n' ' '
  echo
}

run() {
  for f in hopper.band sphere.lslib hopper.data hopper.txt; do [ -f "$f" ] || prepare; done
  mpi_for "$np"
  echo "running lmp on $np rank(s): settle $nsettle steps, discharge up to $nsteps (log in $out/log.lammps)"
  start=$SECONDS
  "${mpi[@]}" "$lmp" -in "$here/in.hopper" -var nsettle "$nsettle" -var ndischarge "$nsteps" \
    -var nvtk "$nvtk" -log log.lammps -echo none -screen none
  echo "lmp took $((SECONDS - start)) s"
  grep "^Loop time" log.lammps
}

plot() {
  "$py" "$here/plot.py" hopper.csv hopper_settled.dump hopper.txt hopper.png | tee hopper_result.txt
  echo "results: $out/log.lammps, hopper.csv, hopper.png, hopper_result.txt, hopper_settled.dump," \
    "vtk/hopper.pvd (ParaView; open hopper.stl with it for the wall)"
}

case "$stage" in
  prepare) prepare ;;
  run) run ;;
  plot) plot ;;
  all) prepare; run; plot ;;
esac
