#!/usr/bin/env bash
# Make anew the inputs that ship with the examples, so that every deck runs as shipped
# (`cd examples/NAME && mpirun -np 2 lmp -in in.NAME`). Each example's run.sh makes its
# inputs in a scratch folder (`run.sh prepare` stops before the main run) and the files the
# decks read are copied into the example's folder. The runs are deterministic on one
# machine; another CPU may give other last bits (libm) and so another packing.
#
#   bash examples/make_inputs.sh [NAME...]     (default: every example; after ./lsdem build)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=${LSDEM_BUILD_DIR:-$here/../build}
export LSDEM_LMP=${LSDEM_LMP:-$build/lmp} LSDEM_SHAPE_TOOL=${LSDEM_SHAPE_TOOL:-$build/lsdem-shape}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# the files each example's decks read, as run.sh makes them
inputs() {
  case "$1" in
    settle) echo grains.lslib data.settle ;;
    avatars) echo grains.lslib packed.data ;;
    ct_scan) echo grains.lslib insitu.data ;;
    container_release) echo grains.lslib packed.data filled.data ;;
    triaxial) echo all.lslib packed.data mem.data mem.in mem.tri ;;
    c_driver) echo grains.lslib data.driver ;;
    drum) echo grains.lslib packed.data ;;
    hopper) echo hopper.stl hopper.band hopper.txt sphere.lslib hopper.data ;;
    avalanche) echo grains.lslib source.data valley.asc valley.band ;;
    net_drop) echo all.lslib net.data net.in net.net ;;
    barrier) echo all.lslib net.data net.in net.net cube.in ;;
    shear_cell) echo grains.lslib packed.data ;;
  esac
}

# c_driver has no run.sh: five grains of three shapes dropped on a floor (the test's scene)
make_c_driver() {
  (cd "$1" && LSDEM_SHAPE_TOOL=$LSDEM_SHAPE_TOOL PYTHONPATH=$here/../unittest/lmp /usr/bin/python3 - <<'EOF'
import grain_decks as gd
gd.library()
grains = [dict(id=i + 1, shape=(1, 3, 1, 2, 3)[i], density=2.0,
               x=(-9.0 + 4.5 * i, 0.3 * (i % 2), 2.5 + 0.5 * i),
               q=gd.qaxis((1, i, 2), 0.4 * i)) for i in range(5)]
gd.write_data("data.driver", grains, box=(-12.0, 12.0, -4.0, 4.0, -1.0, 8.0))
EOF
  )
}

names=("$@")
[ ${#names[@]} -gt 0 ] || names=(settle avatars ct_scan container_release triaxial c_driver drum hopper avalanche net_drop barrier shear_cell)
for name in "${names[@]}"; do
  files=$(inputs "$name")
  [ -n "$files" ] || { echo "make_inputs.sh: no example '$name'" >&2; exit 2; }
  out=$scratch/$name
  mkdir -p "$out"
  echo "== $name"
  if [ "$name" = c_driver ]; then
    make_c_driver "$out"
  else
    # the CT example ships a 64^3 crop-sized scan (33 grains, ~2 MB of shapes) instead of
    # run.sh's 128^3 scan of 260 grains (20 MB)
    scene=()
    [ "$name" = ct_scan ] && scene=(SIZE=64 GRAINS=33)
    env "${scene[@]}" OUT="$out" bash "$here/$name/run.sh" prepare >"$out/prepare.log" 2>&1 \
      || { tail -n 20 "$out/prepare.log"; exit 1; }
  fi
  for f in $files; do cp "$out/$f" "$here/$name/$f"; done
  (cd "$here/$name" && du -ch $files | tail -n 1 | sed "s/total/$name inputs/")
done
