# common.sh -- the start every example's run.sh shares; sourced after the script sets `here`
# (its own folder). Sets lmp and shape (the binaries ./lsdem example passes in LSDEM_LMP and
# LSDEM_SHAPE_TOOL, else those of ../../build) and defines:
#   enter_out DIR          make the output folder and work in it
#   mpi_for NP             the array mpi: empty for one rank, else mpirun's words for NP ranks
#   smallest_volume LIB    the smallest grain volume of a shape library (lsdem-shape list)
#   sand_shapes OUT.lslib SIZE SPACING SEED NAME
#                          six random sand-like shapes of equivalent diameter SIZE, 100
#                          surface nodes, grid spacing SPACING (lsdem-shape random)
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

sand_shapes() {
  "$shape" random "$1" --count 6 --size "$2" --elongation 0.75 --flatness 0.75 \
    --angularity 0.15 --roughness 0.02 --nodes 100 --spacing "$3" --seed "$4" --name "$5" \
    >/dev/null 2>&1
}
