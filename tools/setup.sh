#!/usr/bin/env bash
# TAPMC quick start, step 1: install what is missing (Debian packages, LAMMPS headers), build
# everything into build/, and run the default example (a short tapping run of the paper's set-up).
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
"$top/tools/setup/build.sh"
cd "$top/examples/tapping"
"$top/build/lmp_tapmc" -in in.tapping_pbc -log "$top/build/log.quickstart" 
echo "tapmc: built $top/build/lmp_tapmc and ran examples/tapping/in.tapping_pbc (log: build/log.quickstart)"
