#!/usr/bin/env bash
# TAPMC quick start, step 1: install what is missing (Debian packages, LAMMPS headers), build
# everything into build/, then show the physics: examples/quickstart taps 1024 spheres 300 times
# (about a minute on one core) and draws the compaction curve into build/quickstart/.
# TAPMC_QUICKSTART_TAPS sets the taps (0: build only).
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
"$top/tools/setup/build.sh"
taps=${TAPMC_QUICKSTART_TAPS:-300}
if [ "$taps" = 0 ]; then
  echo "tapmc: built $top/build/lmp_tapmc (quick-start run skipped: TAPMC_QUICKSTART_TAPS=0)"
  exit 0
fi
run="$top/build/quickstart"
mkdir -p "$run"
cd "$run"
echo "tapmc: tapping 1024 spheres $taps times (examples/quickstart/in.quickstart, eps = 0.0225) ..."
"$top/build/lmp_tapmc" -in "$top/examples/quickstart/in.quickstart" -var taps "$taps" \
  -log log.lammps
PYTHONPATH="$top/tools/python" /usr/bin/python3 "$top/examples/quickstart/plot_compaction.py"
echo "tapmc: built $top/build/lmp_tapmc; the quick-start run, its log and its figure are in $run"
