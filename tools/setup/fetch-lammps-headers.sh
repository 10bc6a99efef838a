#!/usr/bin/env bash
# TAPMC setup helper: extract the LAMMPS source headers that Debian's liblammps-dev does not
# install (fmt/, neigh_request.h, irregular.h, ...) from Debian's *source package* of the same
# LAMMPS version. Nothing from LAMMPS is committed to this repository: the headers are fetched
# here, at setup time, into a cache directory outside the work tree.
#
# usage: fetch-lammps-headers.sh [--source-tree] DEST_DIR
# DEST_DIR ends up holding DEST_DIR/src/*.h and DEST_DIR/src/fmt/*.h; a stamp file makes the
# script a no-op when the headers are already there. With --source-tree, DEST_DIR receives the
# whole LAMMPS source tree instead (src/, cmake/, python/, ...), for
# tools/setup/build-lammps-plugin.sh.
set -euo pipefail

mode=headers
if [ "${1:-}" = "--source-tree" ]; then
  mode=source
  shift
fi
dest=${1:?usage: fetch-lammps-headers.sh [--source-tree] DEST_DIR}
# Debian bookworm's lammps source package; its LAMMPS version is 29 Sep 2021 (update 2), the
# version of the binary liblammps0 / liblammps-dev packages we link against.
suite=${TAPMC_LAMMPS_SRC_SUITE:-bookworm}
pkg_version=${TAPMC_LAMMPS_SRC_VERSION:-20220106.git7586adbb6a+ds1-2}
stamp="$dest/.tapmc-$mode-$pkg_version"

if [ -f "$stamp" ]; then
  exit 0
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# A private apt configuration with a deb-src entry, so the machine's own sources stay untouched.
mkdir -p "$work/apt/lists/partial" "$work/apt/cache/archives/partial"
cat > "$work/apt/sources.list" <<SRC
deb-src [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://deb.debian.org/debian $suite main
SRC
apt_opts=(-o "Dir::Etc::SourceList=$work/apt/sources.list" -o "Dir::Etc::SourceParts=/dev/null"
          -o "Dir::State::Lists=$work/apt/lists" -o "Dir::Cache=$work/apt/cache"
          -o "APT::Sandbox::User=root")
echo "tapmc: fetching Debian source package lammps=$pkg_version ($suite) for $mode" >&2
apt-get "${apt_opts[@]}" update -qq
(cd "$work" && apt-get "${apt_opts[@]}" source --download-only -qq "lammps=$pkg_version")

orig=$(ls "$work"/lammps_*.orig.tar.* | head -n 1)
mkdir -p "$work/x"
if [ "$mode" = source ]; then
  tar -xf "$orig" -C "$work/x"
  top=$(find "$work/x" -maxdepth 1 -mindepth 1 -type d | head -n 1)
  [ -f "$top/cmake/CMakeLists.txt" ] || { echo "tapmc: cmake/CMakeLists.txt not found in $orig" >&2; exit 1; }
  rm -rf "$dest"
  mkdir -p "$(dirname "$dest")"
  mv "$top" "$dest"
  echo "$pkg_version" > "$stamp"
  echo "tapmc: LAMMPS source tree ready in $dest" >&2
  exit 0
fi
# Only the top-level src/ headers and the bundled fmt library are needed.
tar -xf "$orig" -C "$work/x" --wildcards '*/src/*.h' '*/src/fmt/*' 2>/dev/null || \
  tar -xf "$orig" -C "$work/x"
top=$(find "$work/x" -maxdepth 1 -mindepth 1 -type d | head -n 1)
[ -f "$top/src/neigh_request.h" ] || { echo "tapmc: neigh_request.h not found in $orig" >&2; exit 1; }

rm -rf "$dest"
mkdir -p "$dest/src"
cp "$top"/src/*.h "$dest/src/"
cp -r "$top/src/fmt" "$dest/src/fmt"
echo "$pkg_version" > "$stamp"
echo "tapmc: LAMMPS headers ready in $dest/src" >&2
