#!/usr/bin/env bash
# Container release (report §4.6.1 analog): make the scene, settle it in the container
# (penalty), release it for 8 s and measure the mound.
# Called by `./lsdem example container_release` (which sets LSDEM_LMP and LSDEM_SHAPE_TOOL).
# Environment: NGRAINS (1600), METHOD (impulse or penalty), DTMUL (impulse: multiple of the
# penalty time step, 16), NP (2), TIME (8 s of release), OPTS (fix impulse/lsdem keywords,
# default "method split", the fix's defaults; "method etm" for the report's method).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$here/../common.sh"
n=${NGRAINS:-1600} method=${METHOD:-impulse} mul=${DTMUL:-16} np=${NP:-2} t_end=${TIME:-8}
opts=${OPTS:-method split}
out=${OUT:-$here/out}
enter_out "$out"
LSDEM_SHAPE_TOOL=$shape bash "$here/make_scene.sh" . "$n"
# dt = 0.1 sqrt(m_min / kn), the report's eq 4.47 (kn = 3e4 per node, density 2.65)
vmin=$(smallest_volume grains.lslib)
dt=$(/usr/bin/python3 -c "print('%.4g' % (0.1 * (2.65 * $vmin / 3.0e4) ** 0.5))")
mpi_for "$np"
steps() { /usr/bin/python3 -c "print(round($1 / $2))"; }
echo "fill: 2.5 s in the container, penalty, dt = $dt, $np rank(s) (log in $out/log.fill)"
"${mpi[@]}" "$lmp" -in "$here/in.fill" -var dt "$dt" -var nsteps "$(steps 2.5 "$dt")" \
  -log log.fill -screen none
[ "${1:-}" = prepare ] && { echo "dt $dt"; exit 0; }
[ "$method" = penalty ] && mul=1
d=$(/usr/bin/python3 -c "print('%.6g' % ($dt * $mul))")
# the release's log is the example's log.lammps (and its reference logs)
echo "release: $t_end s, $method, dt = $d ($mul x), $(steps "$t_end" "$d") steps (log in $out/log.lammps)"
start=$SECONDS
"${mpi[@]}" "$lmp" -in "$here/in.release" -var method "$method" -var dt "$d" \
  -var nsteps "$(steps "$t_end" "$d")" -var impulse_opts "$opts" -log log.lammps -screen none
echo "lmp took $((SECONDS - start)) s"
grep "^Loop time" log.lammps
/usr/bin/python3 "$here/mound.py" "mound_$method.dump"
"$shape" render grains.lslib "mound_$method.dump" "mound_$method.png" --view y --size 640 400 >/dev/null
echo "results: $out/log.lammps, $out/mound_$method.dump, $out/mound_$method.png"
