#!/usr/bin/env bash
# TAPMC setup helper: extract the LAMMPS source headers that Debian's liblammps-dev does not
# install (fmt/, neigh_request.h, irregular.h, ...) from Debian's *source package* of the
# installed LAMMPS version. Nothing from LAMMPS is committed to this repository: the headers are
# fetched here, at setup time, into a cache directory outside the work tree.
#
# usage: fetch-lammps-headers.sh [--source-tree | --from-tree TREE] DEST_DIR
# DEST_DIR ends up holding DEST_DIR/src/*.h and DEST_DIR/src/fmt/*.h; a stamp file
# DEST_DIR/.tapmc-headers-<source version> makes the script a no-op when the headers are already
# there. With --source-tree, DEST_DIR receives the whole LAMMPS source tree instead (src/, cmake/,
# python/, ...; stamp .tapmc-source-<source version>), for tools/setup/build-lammps-plugin.sh.
# With --from-tree, the headers are copied from the LAMMPS source tree TREE (nothing is
# downloaded); build-lammps-plugin.sh leaves the headers of the LAMMPS it builds this way.
# The original tarball is checked against the SHA-256 and size in the suite's Sources index. A
# version whose .dsc or Debian patches are missing from the archive (lammps 20260704+dfsg-2 in
# unstable) still works: only the original tarball is used.
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

# Copy the headers TAPMC needs from the LAMMPS source tree $1 into $dest/src, with the stamp.
install_headers() {
  local top=$1
  rm -rf "$dest"
  mkdir -p "$dest/src"
  cp "$top"/src/*.h "$dest/src/"
  cp -r "$top/src/fmt" "$dest/src/fmt"
  # LAMMPS from 2023 on: json_fwd.h, included by atom.h, needs the bundled JSON library
  if [ -d "$top/src/nlohmann" ]; then
    cp -r "$top/src/nlohmann" "$dest/src/nlohmann"
  fi
  echo "$pkg_version" > "$stamp"
  echo "tapmc: LAMMPS headers ready in $dest/src" >&2
}

usage="usage: fetch-lammps-headers.sh [--source-tree | --from-tree TREE] DEST_DIR"
mode=headers
tree=
case "${1:-}" in
  --source-tree) mode=source; shift ;;
  --from-tree) tree=${2:?$usage}; shift 2 ;;
esac
dest=${1:?$usage}
# The headers must be those of the LAMMPS that TAPMC compiles against and links with.
pkg_version=${TAPMC_LAMMPS_SRC_VERSION:-}
if [ -z "$pkg_version" ] && ! pkg_version=$(installed_source_version liblammps-dev liblammps0 lammps); then
  echo "fetch-lammps-headers.sh: none of liblammps-dev, liblammps0, lammps is installed, so the" \
       "LAMMPS version is unknown; install them (tools/setup/install-deps.sh) or set" \
       "TAPMC_LAMMPS_SRC_VERSION" >&2
  exit 1
fi
stamp="$dest/.tapmc-$mode-$pkg_version"
if [ -f "$stamp" ]; then
  exit 0
fi
if [ -n "$tree" ]; then
  if [ ! -f "$tree/src/neigh_request.h" ] || [ ! -d "$tree/src/fmt" ]; then
    echo "fetch-lammps-headers.sh: $tree is not a LAMMPS source tree (no src/neigh_request.h" \
         "or src/fmt/); give the top directory of the tree" >&2
    exit 1
  fi
  install_headers "$tree"
  exit 0
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
# When apt's log $1 says that Debian's archive was out of reach: say so, and how to go on
# offline, and stop.
stop_if_unreachable() {
  grep -qE 'Could not (connect|resolve)|Temporary failure resolving|Connection (failed|timed out)' \
    "$1" || return 0
  echo "fetch-lammps-headers.sh: Debian's archive is out of reach (apt's message is above): no" \
       "network, or a proxy in the way (http_proxy=${http_proxy:-<not set>}), so lammps=$pkg_version" \
       "cannot be fetched. Run this again once the archive is reachable, or go on offline with a" \
       "LAMMPS source tree of that version: doc/install.rst, 'Without network'" >&2
  exit 1
}

echo "tapmc: fetching Debian source package lammps=$pkg_version ($suite) for $mode" >&2
# apt-get update only warns when it cannot download an index; --error-on=any makes that an error.
if ! apt-get "${apt_opts[@]}" update -qq --error-on=any 2> "$work/apt-update.log"; then
  cat "$work/apt-update.log" >&2
  stop_if_unreachable "$work/apt-update.log"
  echo "fetch-lammps-headers.sh: apt-get update of Debian's $suite deb-src failed (above); is" \
       "'$suite' (TAPMC_LAMMPS_SRC_SUITE, default this system's release) a Debian suite?" >&2
  exit 1
fi
# The original tarball is the whole upstream source; Debian's .dsc and patches are not needed.
# apt fetches the tarball first, so when the archive lacks the .dsc (lammps 20260704+dfsg-2 in
# unstable) the download fails after the tarball is in hand; the checksum test below decides.
(cd "$work" && apt-get "${apt_opts[@]}" source --download-only -qq "lammps=$pkg_version") \
  > "$work/apt-source.log" 2>&1 || true
orig=$(ls "$work"/lammps_*.orig.tar.* 2> /dev/null | head -n 1 || true)
if [ -z "$orig" ]; then
  cat "$work/apt-source.log" >&2
  stop_if_unreachable "$work/apt-source.log"
  echo "fetch-lammps-headers.sh: Debian's $suite deb-src has no lammps=$pkg_version; set" \
       "TAPMC_LAMMPS_SRC_SUITE to the suite that has it (e.g. unstable for 20260704+dfsg-2)" >&2
  exit 1
fi
if grep -q '^E: ' "$work/apt-source.log"; then
  echo "tapmc: apt could not fetch all of lammps=$pkg_version (below); the original tarball" \
       "is here and is used if its checksum matches the archive's Sources index" >&2
  grep '^E: ' "$work/apt-source.log" | sed 's/^/  /' >&2
fi

# Check the tarball against the SHA-256 and size of the Sources index apt just downloaded
# (signed through the suite's InRelease), whether or not apt finished.
name=$(basename "$orig")
read -r want_sha want_size < <(apt-cache "${apt_opts[@]}" showsrc lammps 2> /dev/null \
  | awk -v v="$pkg_version" -v f="$name" '
      /^Package: / { pkg = $2 } /^Version: / { ver = $2 }
      /^[^ ]/ { sha = ($1 == "Checksums-Sha256:") }
      sha && pkg == "lammps" && ver == v && $3 == f { print $1, $2; exit }') || true
if [ -z "${want_sha:-}" ]; then
  echo "fetch-lammps-headers.sh: the Sources index of $suite lists no SHA-256 for $name, so" \
       "the tarball cannot be checked; not using it" >&2
  exit 1
fi
have_sha=$(sha256sum "$orig" | cut -d ' ' -f 1)
have_size=$(stat -c %s "$orig")
if [ "$have_sha" != "$want_sha" ] || [ "$have_size" != "$want_size" ]; then
  echo "fetch-lammps-headers.sh: $name does not match the Sources index of $suite" \
       "(SHA-256 $have_sha, $have_size bytes; expected $want_sha, $want_size bytes);" \
       "a broken download or mirror: run the script again later" >&2
  exit 1
fi
echo "tapmc: $name matches the Sources index of $suite (SHA-256 $want_sha)" >&2

# The top of the source tree: one directory (lammps-29Sep2021/) in older tarballs, the
# tarball's root in newer ones (20260704+dfsg: cmake/, src/, python/ at the top).
source_top() {
  local marker=$1 dir
  if [ -e "$work/x/$marker" ]; then
    echo "$work/x"
    return 0
  fi
  for dir in "$work"/x/*/; do
    if [ -e "$dir$marker" ]; then
      echo "${dir%/}"
      return 0
    fi
  done
  echo "tapmc: $marker not found in $orig" >&2
  return 1
}

mkdir -p "$work/x"
if [ "$mode" = source ]; then
  tar -xf "$orig" -C "$work/x"
  top=$(source_top cmake/CMakeLists.txt)
  rm -rf "$dest"
  mkdir -p "$(dirname "$dest")"
  if [ "$top" = "$work/x" ]; then
    mv "$work/x" "$dest"
  else
    mv "$top" "$dest"
  fi
  echo "$pkg_version" > "$stamp"
  echo "tapmc: LAMMPS source tree ready in $dest" >&2
  exit 0
fi
# Only the top-level src/ headers and the bundled fmt library are needed.
# ('*' also matches the empty string and '/', so this covers both layouts; tar complains about
# the patterns that match nothing, such as nlohmann/ before 2023.)
tar -xf "$orig" -C "$work/x" --wildcards '*src/*.h' '*src/fmt/*' '*src/nlohmann/*' \
  2> /dev/null || true
if ! source_top src/neigh_request.h > /dev/null 2>&1; then
  tar -xf "$orig" -C "$work/x"
fi
install_headers "$(source_top src/neigh_request.h)"
