# common.sh -- the start every example's run.sh shares; sourced after the script sets `here`
# (its own folder). Sets lmp and shape (the binaries ./lsdem example passes in LSDEM_LMP and
# LSDEM_SHAPE_TOOL, else those of ../../build) and defines:
#   enter_out DIR          make the output folder and work in it
#   mpi_for NP             the array mpi: empty for one rank, else mpirun's words for NP ranks
#   smallest_volume LIB    the smallest grain volume of a shape library (lsdem-shape list)
# shellcheck shell=bash
lmp=${LSDEM_LMP:-$here/../../build/lmp}
shape=${LSDEM_SHAPE_TOOL:-$here/../../build/lsdem-shape}

enter_out() { mkdir -p "$1" && cd "$1"; }

mpi_for() {
  mpi=()
  if [ "$1" -gt 1 ]; then mpi=(mpirun --allow-run-as-root --oversubscribe -np "$1"); fi
}

smallest_volume() {
  "$shape" list "$1" | awk 'NR > 2 && NF { v = $(NF - 3); if (m == "" || v < m) m = v } END { print m }'
}
