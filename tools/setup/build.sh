#!/usr/bin/env bash
# TAPMC setup helper: install missing Debian packages, fetch the LAMMPS headers (through CMake),
# configure and build everything into build/ (incremental when build/ exists). Without GoogleTest
# (libgtest-dev, optional) the GoogleTest suites are left out; CMake leaves out the tests of the
# other optional packages by itself.
set -euo pipefail
top=$(cd "$(dirname "$0")/../.." && pwd)
missing_optional=$("$top/tools/setup/install-deps.sh")
gtests=ON
[[ " $missing_optional " != *" libgtest-dev "* ]] || gtests=OFF
cmake -S "$top" -B "$top/build" -DCMAKE_BUILD_TYPE=Release -DTAPMC_BUILD_GTESTS=$gtests >/dev/null
cmake --build "$top/build" -j "$(nproc)"
