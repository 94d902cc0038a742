#!/usr/bin/env bash
# The avalanche's penalty time step for a shape library, printed: 0.2 sqrt(m_min / (5 kn)),
# below fix nve/lsdem's bound for a flat contact of five nodes (eq 4.47's 0.1 sqrt(m_min / kn)
# is just above it); m_min the smallest grain's mass (density 2.65), kn = 3e4. Used by
# run.sh and the benchmarks under bench/avalanche.
#   bash examples/avalanche/penalty_step.sh GRAINS.lslib    (LSDEM_SHAPE_TOOL: lsdem-shape)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$here/../common.sh"
vmin=$(smallest_volume "$1")
/usr/bin/python3 -c "print('%.2g' % (0.2 * (2.65 * $vmin / (5 * 3.0e4)) ** 0.5))"
