#!/usr/bin/env bash
# TAPMC quick start, step 2: the whole fast test suite (installs/builds whatever is missing
# first). TAPMC_SLOW=1 runs the slow statistical validation too (GoogleTest suites named Slow*,
# pytest files tests/*/test_slow_*.py).
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
"$top/tools/setup/build.sh"
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
exclude=()
[ "${TAPMC_SLOW:-0}" = 1 ] || exclude=(-E '(^|\.)Slow' -LE slow)
ctest --test-dir "$top/build" --output-on-failure -j "$(nproc)" "${exclude[@]}"
