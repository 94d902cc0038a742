#!/usr/bin/env bash
# The barrier test (ETAG 027-style vertical drop): make the scene, run it by the penalty
# and by the impulse method, print the figures of each (barrier.py) and plot them. Called
# by `./lsdem example barrier` (which sets LSDEM_LMP and LSDEM_SHAPE_TOOL).
# Environment: NP (1: the scene is small), OUT (out/).
#   run.sh [prepare]   (prepare: make all.lslib, net.data, net.in, net.net, cube.in only)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$here/../common.sh"
np=${NP:-1}
out=${OUT:-$here/out}
enter_out "$out"
LSDEM_SHAPE_TOOL=$shape bash "$here/make_scene.sh" .
[ "${1:-}" = prepare ] && exit 0
mpi_for "$np"
# penalty: dt 2e-4, 15,000 steps of impact then 20,000 of quieting down (the deck's
# defaults); impulse: 5 times the step (the balls' bond damping bounds it), same times
for method in penalty impulse; do
  vars=(-var method "$method")
  [ "$method" = impulse ] && vars+=(-var dt 1e-3 -var settle 1000 -var nsteps 3000 -var nrest 4000 -var every 2)
  start=$SECONDS
  "${mpi[@]}" "$lmp" -in "$here/in.barrier" "${vars[@]}" -log "log.$method" -screen none
  mv barrier.csv "barrier_$method.csv"
  echo "== $method ($((SECONDS - start)) s; $(grep '^barrier:' "log.$method" | tail -1))"
  /usr/bin/python3 "$here/barrier.py" "barrier_$method.csv" | tee "figures_$method.txt"
done
cp log.penalty log.lammps    # the example's own run (the deck's defaults)
/usr/bin/python3 "$here/plot.py" barrier_penalty.csv barrier_impulse.csv barrier.png
echo "results: $out/figures_*.txt, $out/barrier_*.csv, $out/log.*, $out/barrier.png"
