#!/usr/bin/env bash
# Install what building and testing LSDEM needs, from Debian's packages, when missing,
# and fetch Debian's LAMMPS source package (29 Sep 2021 Update 2) unless the caller
# points LAMMPS_SOURCE_DIR at an existing tree of that version.
#
# Idempotent: a second run that finds everything in place does nothing and is quick.
# Environment:
#   LSDEM_HOME         cache folder for the LAMMPS source and the build (default ~/.cache/lsdem)
#   LAMMPS_SOURCE_DIR  an existing LAMMPS tree to use instead of fetching Debian's source
set -euo pipefail

LSDEM_HOME=${LSDEM_HOME:-$HOME/.cache/lsdem}
mkdir -p "$LSDEM_HOME"

need_pkgs=()
have_cmd() { command -v "$1" >/dev/null 2>&1; }
have_pkg() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q 'install ok installed'; }
for p in build-essential cmake ninja-build ccache pkg-config openmpi-bin libopenmpi-dev \
         python3 python3-numpy python3-matplotlib dpkg-dev \
         libtiff-dev libpng-dev libtiff-tools python3-skimage python3-tifffile python3-sphinx; do
  have_pkg "$p" || need_pkgs+=("$p")
done

SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
apt_updated=0
apt_update() {
  if [ $apt_updated = 0 ]; then
    $SUDO apt-get update -qq
    apt_updated=1
  fi
}

if [ ${#need_pkgs[@]} -gt 0 ]; then
  echo "setup: installing Debian packages: ${need_pkgs[*]}"
  apt_update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
    "${need_pkgs[@]}" >/dev/null
fi

# ---- LAMMPS source -----------------------------------------------------------------
if [ -n "${LAMMPS_SOURCE_DIR:-}" ]; then
  if [ ! -f "$LAMMPS_SOURCE_DIR/cmake/CMakeLists.txt" ]; then
    echo "setup: LAMMPS_SOURCE_DIR=$LAMMPS_SOURCE_DIR has no cmake/CMakeLists.txt;" \
         "point it at the top of a LAMMPS 29Sep2021 tree" >&2
    exit 1
  fi
  echo "setup: using LAMMPS source at $LAMMPS_SOURCE_DIR"
  exit 0
fi

src="$LSDEM_HOME/lammps-src"
if [ -f "$src/cmake/CMakeLists.txt" ]; then
  exit 0
fi

echo "setup: fetching Debian's lammps source package into $LSDEM_HOME"
# A fresh machine has only binary package lists: derive deb-src entries from the system's
# own sources (no mirror host is written here), then update.
if ! apt-get source --print-uris lammps >/dev/null 2>&1; then
  for f in /etc/apt/sources.list.d/debian.sources; do
    [ -f "$f" ] || continue
    sed -e 's/^Types: deb$/Types: deb-src/' "$f" | $SUDO tee /etc/apt/sources.list.d/lsdem-deb-src.sources >/dev/null
  done
  if [ -f /etc/apt/sources.list ] && grep -q '^deb ' /etc/apt/sources.list; then
    grep '^deb ' /etc/apt/sources.list | grep -v 'deb-src' | sed 's/^deb /deb-src /' \
      | $SUDO tee /etc/apt/sources.list.d/lsdem-deb-src.list >/dev/null
  fi
  apt_updated=0
  apt_update
fi
tmp=$(mktemp -d "$LSDEM_HOME/fetch.XXXXXX")
( cd "$tmp" && apt-get source -qq --download-only lammps >/dev/null && dpkg-source -x --skip-patches lammps_*.dsc lammps >/dev/null ) || {
  echo "setup: could not fetch Debian's lammps source package; set LAMMPS_SOURCE_DIR to a LAMMPS 29Sep2021 tree" >&2
  exit 1
}
rm -rf "$src"
mv "$tmp/lammps" "$src"
rm -rf "$tmp"
grep -h 'LAMMPS_VERSION' "$src/src/version.h" | sed 's/^/setup: /'
