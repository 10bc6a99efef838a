#!/usr/bin/env bash
# TAPMC setup helper: build a LAMMPS that can `plugin load` TAPMC and that turns errors into C++
# exceptions (so the Python module raises instead of ending the process). Debian's binary LAMMPS
# has neither the PLUGIN package nor LAMMPS_EXCEPTIONS; this script builds the same LAMMPS
# version, or another one (the current 4 Jul 2026 release: see below), from Debian's *source
# package* (its original tarball, fetched and checked by fetch-lammps-headers.sh --source-tree)
# with only what TAPMC's inputs need: the core styles (atom_style sphere is core), PLUGIN, MPI, a
# shared library and exceptions. Everything goes into the user's cache, never into the
# repository. See doc/lammps_plugin.rst.
#
# usage: build-lammps-plugin.sh [--print-prefix] [--keep-build]
#   --print-prefix  print the install directory and exit (nothing is built)
#   --keep-build    keep the source and build trees after a successful install
# environment:
#   TAPMC_LAMMPS_SRC_VERSION  Debian source version to build (default: that of the installed
#                             liblammps0, so the plugin LAMMPS is the version TAPMC targets)
#   TAPMC_LAMMPS_SRC_SUITE    Debian suite that has it (default: this system's release); LAMMPS
#                             4 Jul 2026 is TAPMC_LAMMPS_SRC_VERSION=20260704+dfsg-2
#                             TAPMC_LAMMPS_SRC_SUITE=unstable
#   TAPMC_JOBS                parallel compile jobs (default: nproc)
#   XDG_CACHE_HOME            cache root (default ~/.cache); the install is
#                             $XDG_CACHE_HOME/tapmc/lammps-plugin-<source version>
#
# The install holds bin/lmp, lib/liblammps.so, lib/cmake/LAMMPS (for TAPMC's
# -DLAMMPS_DIR=<prefix>/lib/cmake/LAMMPS) and python/lammps (the Python module with the library
# beside it: PYTHONPATH=<prefix>/python); the LAMMPS source headers TAPMC compiles with go to
# $XDG_CACHE_HOME/tapmc/lammps-<version, e.g. 20260704>, where TAPMC's CMake looks for them. A
# stamp file records the version and the options; the script does nothing when the install is
# present and matches.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
print_prefix=0
keep_build=0
for arg in "$@"; do
  case "$arg" in
    --print-prefix) print_prefix=1 ;;
    --keep-build) keep_build=1 ;;
    *) echo "build-lammps-plugin.sh: unknown argument '$arg'" \
            "(allowed: --print-prefix, --keep-build)" >&2
       exit 2 ;;
  esac
done

pkg_version=${TAPMC_LAMMPS_SRC_VERSION:-}
if [ -z "$pkg_version" ]; then
  pkg_version=$(dpkg-query -W -f='${source:Version}' liblammps0 2>/dev/null || true)
fi
if [ -z "$pkg_version" ]; then
  echo "build-lammps-plugin.sh: Debian's liblammps0 is not installed, so the LAMMPS version" \
       "to build is unknown; install it (tools/setup/install-deps.sh) or set" \
       "TAPMC_LAMMPS_SRC_VERSION" >&2
  exit 1
fi

cache=${XDG_CACHE_HOME:-$HOME/.cache}/tapmc
prefix="$cache/lammps-plugin-$pkg_version"
work="$prefix.work"
if [ "$print_prefix" = 1 ]; then
  echo "$prefix"
  exit 0
fi

python=/usr/bin/python3
# Core only: every command of TAPMC's examples and tests (units lj, atom_style sphere, region,
# create_box, thermo, run, ...) is a core style. PLUGIN for `plugin load`; exceptions for the
# library interface; MPI as in Debian's build (Open MPI). No OpenMP, images, movies or tools.
cmake_options=(
  -D CMAKE_BUILD_TYPE=Release
  -D "CMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG"
  -D "CMAKE_INSTALL_PREFIX=$prefix"
  -D CMAKE_INSTALL_LIBDIR=lib
  -D "CMAKE_INSTALL_RPATH=$prefix/lib"
  -D BUILD_SHARED_LIBS=on
  -D BUILD_MPI=on
  -D BUILD_OMP=off
  -D PKG_PLUGIN=on
  -D LAMMPS_EXCEPTIONS=on
  -D WITH_JPEG=off -D WITH_PNG=off -D WITH_FFMPEG=off -D WITH_GZIP=on
  -D BUILD_TOOLS=off -D BUILD_DOC=off -D ENABLE_TESTING=off
)
stamp="$prefix/.tapmc-lammps-plugin"
stamp_text="$pkg_version ${cmake_options[*]}"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$stamp_text" ] && [ -x "$prefix/bin/lmp" ] \
   && [ -f "$prefix/python/lammps/liblammps.so" ]; then
  echo "tapmc: plugin LAMMPS already installed in $prefix" >&2
  exit 0
fi

for tool in cmake make mpicxx; do
  command -v "$tool" > /dev/null || {
    echo "build-lammps-plugin.sh: '$tool' not found; install the build dependencies" \
         "(tools/setup/install-deps.sh)" >&2; exit 1; }
done

jobs=${TAPMC_JOBS:-$(nproc)}
if ! [[ "$jobs" =~ ^[1-9][0-9]*$ ]]; then
  echo "build-lammps-plugin.sh: TAPMC_JOBS = '$jobs' must be a positive integer" >&2
  exit 2
fi

TAPMC_LAMMPS_SRC_VERSION=$pkg_version \
  bash "$here/fetch-lammps-headers.sh" --source-tree "$work/source"

# The Python module is installed below, by hand, next to its library. LAMMPS up to 2022 would
# also install it with the library when CMake finds Python, so Python is hidden from it; newer
# LAMMPS (2026) refuses to configure without Python >= 3.6 and uses it only for its
# install-python target, so it gets Debian's interpreter.
if grep -q 'LAMMPS requires Python' "$work/source/cmake/CMakeLists.txt"; then
  python_options=(-D "Python_EXECUTABLE=$python")
else
  python_options=(-D CMAKE_DISABLE_FIND_PACKAGE_Python=on
                  -D CMAKE_DISABLE_FIND_PACKAGE_PythonInterp=on)
fi
lammps_version=$(sed -n 's/^#define LAMMPS_VERSION "\(.*\)"$/\1/p' "$work/source/src/version.h")

start=$(date +%s)
echo "tapmc: building LAMMPS $lammps_version ($pkg_version) with PLUGIN and exceptions," \
     "$jobs jobs, into $prefix" >&2
cmake -S "$work/source/cmake" -B "$work/build" "${cmake_options[@]}" "${python_options[@]}" \
  > "$work/configure.log" || {
  echo "build-lammps-plugin.sh: configuring LAMMPS failed; see $work/configure.log" >&2
  exit 1; }
# nice: the build is long and must not starve interactive work on a shared machine
nice -n 19 cmake --build "$work/build" -j "$jobs"
rm -rf "$prefix"
cmake --install "$work/build" > "$work/install.log"
# LAMMPS installs its potential files (53 MB) and, from 2023 on, its benchmark inputs (37 MB);
# no core-only input of TAPMC reads them
rm -rf "$prefix/share/lammps/potentials" "$prefix/share/lammps/bench"

# Python module: LAMMPS's python/lammps package with the library beside it, where
# lammps.lammps() looks first (before the system's liblammps.so).
mkdir -p "$prefix/python"
cp -r "$work/source/python/lammps" "$prefix/python/lammps"
ln -sf ../../lib/liblammps.so "$prefix/python/lammps/liblammps.so"
# Package metadata with the library's version: newer modules compare the version of the
# installed 'lammps' distribution with the library's and would otherwise find Debian's
# python3-lammps (2021.9.29) and refuse to start.
dist_version=$(date -d "$lammps_version" +%Y.%-m.%-d)
mkdir -p "$prefix/python/lammps-$dist_version.dist-info"
printf 'Metadata-Version: 2.1\nName: lammps\nVersion: %s\n' "$dist_version" \
  > "$prefix/python/lammps-$dist_version.dist-info/METADATA"
"$python" -c "import sys; sys.path.insert(0, '$prefix/python'); import lammps; \
L = lammps.lammps(cmdargs=['-log', 'none', '-screen', 'none']); \
assert L.has_exceptions, 'built without exceptions'; \
assert 'PLUGIN' in L.installed_packages, 'built without PLUGIN'; L.close()"

# The source headers for TAPMC's build (cmake/LAMMPSHeaders.cmake), from the tree just built.
TAPMC_LAMMPS_SRC_VERSION=$pkg_version bash "$here/fetch-lammps-headers.sh" \
  --from-tree "$work/source" "$cache/lammps-$(date -d "$lammps_version" +%Y%m%d)"

echo "$stamp_text" > "$stamp"
end=$(date +%s)
echo "tapmc: plugin LAMMPS ready in $prefix (build and install: $((end - start)) s)" >&2
if [ "$keep_build" = 0 ]; then
  rm -rf "$work"
fi
