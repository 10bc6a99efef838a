#!/usr/bin/env bash
# TAPMC quick start, step 2: the whole fast test suite (installs/builds whatever is missing
# first), then the list of the slow statistical validation it skipped. TAPMC_SLOW=1 runs the
# slow tests too (GoogleTest suites named Slow*, pytest files tests/*/test_slow_*.py, label slow).
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
"$top/tools/setup/build.sh"
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
if [ "${TAPMC_SLOW:-0}" = 1 ]; then
  exec ctest --test-dir "$top/build" --output-on-failure -j "$(nproc)"
fi
slow_name='(^|\.)Slow'
# The names of the tests left out, listed by ctest itself (-N: list only).
mapfile -t skipped < <({ ctest --test-dir "$top/build" -N -L slow
                         ctest --test-dir "$top/build" -N -R "$slow_name"; } |
                       sed -n 's/^ *Test *#[0-9]*: *//p' | sort -u)
status=0
ctest --test-dir "$top/build" --output-on-failure -j "$(nproc)" -E "$slow_name" -LE slow || status=$?
echo
if ((${#skipped[@]})); then
  echo "tapmc: skipped ${#skipped[@]} slow tests (statistical validation, minutes to hours):"
  printf '  %s\n' "${skipped[@]}"
  echo "tapmc: run them with: TAPMC_SLOW=1 tools/run-tests.sh"
fi
exit "$status"
