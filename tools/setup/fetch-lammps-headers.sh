#!/usr/bin/env bash
# TAPMC setup helper: extract the LAMMPS source headers that Debian's liblammps-dev does not
# install (fmt/, neigh_request.h, irregular.h, ...) from Debian's *source package* of the
# installed LAMMPS version. Nothing from LAMMPS is committed to this repository: the headers are
# fetched here, at setup time, into a cache directory outside the work tree.
#
# usage: fetch-lammps-headers.sh [--source-tree] DEST_DIR
# DEST_DIR ends up holding DEST_DIR/src/*.h and DEST_DIR/src/fmt/*.h; a stamp file
# DEST_DIR/.tapmc-headers-<source version> makes the script a no-op when the headers are already
# there. With --source-tree, DEST_DIR receives the whole LAMMPS source tree instead (src/, cmake/,
# python/, ...; stamp .tapmc-source-<source version>), for tools/setup/build-lammps-plugin.sh.
# environment:
#   TAPMC_LAMMPS_SRC_VERSION  Debian source version to fetch (default: the source version of the
#                             installed liblammps-dev, else liblammps0, else lammps)
#   TAPMC_LAMMPS_SRC_SUITE    Debian suite whose deb-src holds that version (default: this
#                             system's release, VERSION_CODENAME of /etc/os-release)
set -euo pipefail

# The Debian source version of the first installed package among the arguments.
installed_source_version() {
  local pkg status version
  for pkg in "$@"; do
    read -r status version < <(dpkg-query -W -f='${db:Status-Abbrev} ${source:Version}\n' "$pkg" 2>/dev/null \
                               | head -n 1) || continue
    if [ "$status" = ii ] && [ -n "$version" ]; then
      echo "$version"
      return 0
    fi
  done
  return 1
}

mode=headers
if [ "${1:-}" = "--source-tree" ]; then
  mode=source
  shift
fi
dest=${1:?usage: fetch-lammps-headers.sh [--source-tree] DEST_DIR}
# The headers must be those of the LAMMPS that TAPMC compiles against and links with.
pkg_version=${TAPMC_LAMMPS_SRC_VERSION:-}
if [ -z "$pkg_version" ] && ! pkg_version=$(installed_source_version liblammps-dev liblammps0 lammps); then
  echo "fetch-lammps-headers.sh: none of liblammps-dev, liblammps0, lammps is installed, so the" \
       "LAMMPS version is unknown; install them (tools/setup/install-deps.sh) or set" \
       "TAPMC_LAMMPS_SRC_VERSION" >&2
  exit 1
fi
suite=${TAPMC_LAMMPS_SRC_SUITE:-}
if [ -z "$suite" ] && [ -r /etc/os-release ]; then
  suite=$(. /etc/os-release && echo "${VERSION_CODENAME:-}")
fi
if [ -z "$suite" ]; then
  echo "fetch-lammps-headers.sh: no VERSION_CODENAME in /etc/os-release; set TAPMC_LAMMPS_SRC_SUITE" \
       "(e.g. bookworm)" >&2
  exit 1
fi
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
(cd "$work" && apt-get "${apt_opts[@]}" source --download-only -qq "lammps=$pkg_version") || {
  echo "fetch-lammps-headers.sh: Debian's $suite deb-src has no lammps=$pkg_version; set" \
       "TAPMC_LAMMPS_SRC_SUITE to the suite that has it" >&2
  exit 1
}

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
