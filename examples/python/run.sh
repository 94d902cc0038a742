#!/usr/bin/env bash
# Python example: the settle scene driven from Python (`from lammps import lammps`), grain
# positions and quaternions read into numpy. Called by `./lsdem example python` (which sets
# LSDEM_BUILD_DIR); NP ranks (default 1), NGRAINS (default 100), NSTEPS (10000), CHUNK (1000).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=${LSDEM_BUILD_DIR:-$here/../../build}
out=$here/out
mkdir -p "$out"
# the settle example's shapes and grains
OUT=$out NGRAINS=${NGRAINS:-100} LSDEM_SHAPE_TOOL=${LSDEM_SHAPE_TOOL:-$build/lsdem-shape} \
  bash "$here/../settle/run.sh" prepare
cd "$out"
# LAMMPS's Python module with this build's liblammps.so (doc/python.rst)
mpi=()
[ "${NP:-1}" -gt 1 ] && mpi=(mpirun --allow-run-as-root --oversubscribe -np "$NP" -x PYTHONPATH)
export PYTHONPATH=$build/python${PYTHONPATH:+:$PYTHONPATH}
"${mpi[@]}" /usr/bin/python3 "$here/settle.py" \
  "$here/../settle/in.settle" "${NSTEPS:-10000}" "${CHUNK:-1000}" grains.npz
echo "results: $out/grains.npz, $out/log.lammps"
