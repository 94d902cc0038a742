#!/usr/bin/env bash
# bench/band/run.sh -- wall storage: our narrow band (lsdem_band) against OpenVDB.
#
#   bench/band/run.sh                  # N = 1000 terrain, 10^6 lookups
#   bench/band/run.sh --n 4000         # the large terrain (about 5 GB while building ours)
#   bench/band/run.sh --signed-test    # also OpenVDB's signed conversion of the open sheet
#
# Arguments go to band_vs_openvdb (--help lists them). Installs libopenvdb-dev from Debian
# when it is missing (root, apt-get) and says what it installed; configures a core-only
# build of the repository in $BUILD_DIR (default /tmp/band-core) and builds lsdem_prep;
# compiles the benchmark into $OUT_DIR (default /tmp/band-bench) with g++ -O2, timing the
# compile (OpenVDB's weight as a dependency); runs it on one thread. Prints figures; never
# pass/fail. See bench/README.md, "Wall storage: own band vs OpenVDB".
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
BUILD_DIR="${BUILD_DIR:-/tmp/band-core}"
OUT_DIR="${OUT_DIR:-/tmp/band-bench}"
JOBS="${JOBS:-2}"
CORE="$REPO/src/PKG-LSDEM/core"
mkdir -p "$OUT_DIR"

echo "== machine"
echo "nproc: $(nproc)"
lscpu | head -n 15
echo

# ---------------------------------------------------------------- OpenVDB ----
echo "== OpenVDB (Debian libopenvdb-dev)"
pkgs_file="$OUT_DIR/openvdb-packages.txt"
if ! dpkg-query -W -f='${Status}' libopenvdb-dev 2>/dev/null | grep -q "install ok installed"; then
  if [ "$(id -u)" != 0 ]; then
    echo "libopenvdb-dev is missing: run as root, or: sudo apt-get install libopenvdb-dev" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y --no-install-recommends libopenvdb-dev > "$OUT_DIR/apt-install.log"
  awk '/NEW packages will be installed/ {on = 1; print; next} on && /^  / {print; next}
       {on = 0} /newly installed|Need to get|After this operation/ {print}' "$OUT_DIR/apt-install.log"
  # the packages apt added: the lines after "The following NEW packages will be installed:"
  awk '/NEW packages will be installed/ {on = 1; next} on && /^  / {print; next} {on = 0}' \
    "$OUT_DIR/apt-install.log" | tr -s ' ' '\n' | sed '/^$/d' > "$pkgs_file"
fi
if [ ! -s "$pkgs_file" ]; then # installed earlier: libopenvdb-dev and what it depends on
  { echo libopenvdb-dev; dpkg-query -W -f='${Depends}\n' libopenvdb-dev libopenvdb10.0 2>/dev/null |
      tr ',' '\n' | sed 's/(.*)//; s/|.*//; s/:any//; s/ //g' | sed '/^$/d' |
      grep -v -x -E 'libc6|libgcc-s1|libstdc\+\+6|zlib1g'; } | sort -u > "$pkgs_file.all"
  : > "$pkgs_file"
  while read -r p; do
    dpkg-query -W "$p" >/dev/null 2>&1 && echo "$p" >> "$pkgs_file"
  done < "$pkgs_file.all"
  rm -f "$pkgs_file.all"
  echo "(already installed; the sizes below are of libopenvdb-dev and its direct dependencies,"
  echo " some of which other packages may have brought)"
fi
total_kb=0
total_deb=0
printf "%-24s %-22s %12s %12s\n" package version "deb (kB)" "installed (KiB)"
while read -r p; do
  v=$(dpkg-query -W -f='${Version}' "$p")
  s=$(dpkg-query -W -f='${Installed-Size}' "$p")
  d=$(apt-cache show "$p=$v" 2>/dev/null | awk '/^Size:/ {print $2; exit}')
  printf "%-24s %-22s %12s %12s\n" "$p" "$v" "$(( ${d:-0} / 1000 ))" "$s"
  total_kb=$((total_kb + s))
  total_deb=$((total_deb + ${d:-0}))
done < "$pkgs_file"
echo "$(wc -l < "$pkgs_file") packages, download $((total_deb / 1000)) kB (.deb sizes), installed ${total_kb} KiB"
echo "licence: $(grep -m1 '^License:' /usr/share/doc/libopenvdb10.0/copyright 2>/dev/null |
  sed 's/License: //') (/usr/share/doc/libopenvdb10.0/copyright)"
echo "libopenvdb.so needs: $(ldd /usr/lib/x86_64-linux-gnu/libopenvdb.so | awk '{print $1}' |
  grep -v -E 'linux-vdso|ld-linux|libc.so|libm.so|libgcc_s|libstdc' | tr '\n' ' ')"
echo

# ------------------------------------------------------------- the core ----
echo "== core-only build in $BUILD_DIR"
if [ ! -f "$BUILD_DIR/build.ninja" ]; then
  cmake -S "$REPO" -B "$BUILD_DIR" -G Ninja -DLSDEM_CORE_ONLY=ON -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
ninja -C "$BUILD_DIR" -j "$JOBS" lsdem_prep | tail -n 1
LIBDIR="$(dirname "$(find "$BUILD_DIR" -name liblsdem_prep.a | head -n 1)")"
echo

# ----------------------------------------------------------- the benchmark ----
echo "== compile (g++ -O2, one translation unit each; wall seconds)"
TIMEFORMAT=%R
CXXFLAGS=(-std=c++17 -O2 -Wall -Wextra -I"$CORE")
printf '#include <openvdb/openvdb.h>\nint main() { openvdb::initialize(); return 0; }\n' \
  > "$OUT_DIR/vdb_minimal.cpp"
t_min=$( { time g++ "${CXXFLAGS[@]}" -c "$OUT_DIR/vdb_minimal.cpp" -o "$OUT_DIR/vdb_minimal.o"; } 2>&1 )
t_bench=$( { time g++ "${CXXFLAGS[@]}" -c "$HERE/band_vs_openvdb.cpp" -o "$OUT_DIR/band_vs_openvdb.o"; } 2>&1 )
t_ours=$( { time gcc -std=c11 -O2 -I"$CORE" -c "$CORE/prep/band_build.c" -o "$OUT_DIR/band_build.o"; } 2>&1 )
echo "#include <openvdb/openvdb.h> alone:                    ${t_min} s"
echo "band_vs_openvdb.cpp (MeshToVolume, Interpolation):     ${t_bench} s"
echo "ours, prep/band_build.c (gcc -O2, for comparison):     ${t_ours} s"
VDB_LIBS=(-lopenvdb -ltbb -lImath-3_1)
echo "extra link libraries: ${VDB_LIBS[*]}"
g++ "$OUT_DIR/band_vs_openvdb.o" -o "$OUT_DIR/band_vs_openvdb" \
  "$LIBDIR/liblsdem_prep.a" "$LIBDIR/liblsdem_kernel.a" "${VDB_LIBS[@]}" -ltiff -lpng -lm
echo

echo "== run: $OUT_DIR/band_vs_openvdb $*"
"$OUT_DIR/band_vs_openvdb" "$@"
