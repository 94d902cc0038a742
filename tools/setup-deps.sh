#!/usr/bin/env bash
# Install what building and testing LSDEM needs, from Debian's packages, when missing,
# and fetch Debian's LAMMPS source package unless the caller points LAMMPS_SOURCE_DIR at
# an existing tree:
#   LSDEM_LAMMPS=2021 (default)  bookworm's lammps (29 Sep 2021 Update 2) -> $LSDEM_HOME/lammps-src
#   LSDEM_LAMMPS=2025            trixie's lammps (4 Feb 2025) -> $LSDEM_HOME/lammps-src-2025,
#                                from a deb-src-only list for trixie (no trixie binaries)
#
# Idempotent: a second run that finds everything in place does nothing and is quick.
# Environment:
#   LSDEM_HOME         cache folder for the LAMMPS source and the build (default ~/.cache/lsdem)
#   LSDEM_LAMMPS       which Debian LAMMPS source to fetch: 2021 (default) or 2025
#   LAMMPS_SOURCE_DIR  an existing LAMMPS tree to use instead of fetching Debian's source
set -euo pipefail

LSDEM_HOME=${LSDEM_HOME:-$HOME/.cache/lsdem}
LSDEM_LAMMPS=${LSDEM_LAMMPS:-2021}
case "$LSDEM_LAMMPS" in
  2021|2025) ;;
  *) echo "setup: LSDEM_LAMMPS=$LSDEM_LAMMPS: expected 2021 or 2025" >&2; exit 1 ;;
esac
mkdir -p "$LSDEM_HOME"

need_pkgs=()
have_cmd() { command -v "$1" >/dev/null 2>&1; }
have_pkg() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q 'install ok installed'; }
for p in build-essential cmake ninja-build ccache pkg-config openmpi-bin libopenmpi-dev \
         python3 python3-numpy python3-matplotlib dpkg-dev \
         libtiff-dev libpng-dev libfftw3-dev libtiff-tools python3-scipy python3-skimage python3-tifffile python3-sphinx; do
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
         "point it at the top of a LAMMPS 29 Sep 2021 or 4 Feb 2025 tree" >&2
    exit 1
  fi
  echo "setup: using LAMMPS source at $LAMMPS_SOURCE_DIR" \
       "($(sed -n 's/^#define LAMMPS_VERSION "\(.*\)"/\1/p' "$LAMMPS_SOURCE_DIR/src/version.h"))"
  exit 0
fi

if [ "$LSDEM_LAMMPS" = 2025 ]; then
  src="$LSDEM_HOME/lammps-src-2025"
else
  src="$LSDEM_HOME/lammps-src"
fi
if [ -f "$src/cmake/CMakeLists.txt" ]; then
  exit 0
fi

# ---- LAMMPS 4 Feb 2025: Debian trixie's source package ------------------------------------
# A separate sources list with Types: deb-src only and Suites: trixie, its URI and key taken
# from the system's own bookworm entry: apt sees trixie's source packages, never its binaries,
# so no upgrade or install can pull a trixie package. The .dsc has been refused (404) while
# the tarballs came: then the orig tarball alone (checked against the hash in trixie's
# Sources index) is enough, as LSDEM applies no Debian patches to either tree.
if [ "$LSDEM_LAMMPS" = 2025 ]; then
  echo "setup: fetching Debian trixie's lammps source package (LAMMPS 4 Feb 2025) into $LSDEM_HOME"
  list=/etc/apt/sources.list.d/lsdem-trixie-src.sources
  if [ ! -f "$list" ]; then
    sys=/etc/apt/sources.list.d/debian.sources
    uri="" key=""
    if [ -f "$sys" ]; then
      # URI and key of the first deb822 stanza for the release itself (a suite without '-')
      read -r uri key < <(awk 'BEGIN { RS = "" } {
          uri = ""; key = ""; plain = 0; n = split($0, line, "\n")
          for (i = 1; i <= n; i++) {
            m = split(line[i], w, " ")
            if (w[1] == "URIs:") uri = w[2]
            if (w[1] == "Signed-By:") key = w[2]
            if (w[1] == "Suites:") for (j = 2; j <= m; j++) if (w[j] !~ /-/) plain = 1
          }
          if (plain && uri != "") { print uri, key; exit }
        }' "$sys") || true
    elif [ -f /etc/apt/sources.list ]; then
      uri=$(awk '$1 == "deb" && $3 !~ /-/ { for (i = 2; i <= NF; i++) if ($i !~ /^\[/) { print $i; exit } }' \
              /etc/apt/sources.list)
    fi
    if [ -z "$uri" ]; then
      echo "setup: found no Debian mirror in $sys or /etc/apt/sources.list to derive a" \
           "trixie deb-src entry from; set LAMMPS_SOURCE_DIR to a LAMMPS 4 Feb 2025 tree" >&2
      exit 1
    fi
    { echo "Types: deb-src"
      echo "URIs: $uri"
      echo "Suites: trixie"
      echo "Components: main"
      if [ -n "$key" ]; then echo "Signed-By: $key"; fi
    } | $SUDO tee "$list" >/dev/null
    apt_updated=0
  fi
  uris=$(apt-get source --print-uris --only-source lammps/trixie 2>/dev/null || true)
  if ! grep -q "orig.tar" <<<"$uris"; then
    apt_update
    uris=$(apt-get source --print-uris --only-source lammps/trixie)
  fi
  tmp=$(mktemp -d "$LSDEM_HOME/fetch.XXXXXX")
  # the whole source package when the archive gives it, else (404 on the .dsc) whatever
  # came; the orig tarball is fetched on its own when it did not
  ( cd "$tmp" && apt-get source -qq --download-only --only-source lammps/trixie >/dev/null 2>&1 ) || true
  read -r orig_uri orig_name _ orig_hash < <(grep "orig.tar" <<<"$uris" | tr -d "'")
  if [ ! -f "$tmp/$orig_name" ]; then
    /usr/lib/apt/apt-helper download-file "$orig_uri" "$tmp/$orig_name" "$orig_hash" >/dev/null || {
      echo "setup: could not fetch $orig_uri; set LAMMPS_SOURCE_DIR to a LAMMPS 4 Feb 2025 tree" >&2
      exit 1
    }
  fi
  [ "$(sha256sum "$tmp/$orig_name" | cut -d' ' -f1)" = "${orig_hash#SHA256:}" ] || {
    echo "setup: $orig_name does not match the SHA256 of trixie's Sources index" >&2
    exit 1
  }
  if ls "$tmp"/lammps_*.dsc >/dev/null 2>&1; then
    ( cd "$tmp" && dpkg-source -x --skip-patches lammps_*.dsc lammps >/dev/null )
  else
    mkdir "$tmp/orig" && tar -xf "$tmp/$orig_name" -C "$tmp/orig"
    mv "$tmp"/orig/* "$tmp/lammps"
  fi
  rm -rf "$src"
  mv "$tmp/lammps" "$src"
  rm -rf "$tmp"
  grep -h 'LAMMPS_VERSION' "$src/src/version.h" | sed 's/^/setup: /'
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
