#!/usr/bin/env bash
# TAPMC setup helper: install missing Debian packages, fetch the LAMMPS headers (through CMake),
# configure and build everything into build/ (incremental when build/ exists).
set -euo pipefail
top=$(cd "$(dirname "$0")/../.." && pwd)
"$top/tools/setup/install-deps.sh"
cmake -S "$top" -B "$top/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$top/build" -j "$(nproc)"
