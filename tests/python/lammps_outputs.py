# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""For the reader tests: find lmp_tapmc and run a small input in a folder, whose outputs
(log, dumps, fix print and fix ave/time files) the tests then read."""

import os
import subprocess
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))


def find_lmp():
    """$TAPMC_LMP, else lmp_tapmc of $TAPMC_BUILD_DIR or build/; skips the test without one."""
    lmp = os.environ.get("TAPMC_LMP")
    if lmp:
        return lmp
    for cand in (Path(os.environ.get("TAPMC_BUILD_DIR", SOURCE / "build")) / "lmp_tapmc",
                 SOURCE / "build" / "lmp_tapmc"):
        if cand.exists():
            return str(cand)
    pytest.skip("lmp_tapmc not found (set TAPMC_LMP)")


def run_input(directory, text, name):
    """Write ``text`` as ``directory/name`` and run it there (log.lammps, no screen output);
    the run must succeed. Returns ``directory``."""
    directory = Path(directory)
    (directory / name).write_text(text)
    proc = subprocess.run([find_lmp(), "-in", name, "-log", "log.lammps", "-screen", "none"],
                          cwd=directory, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return directory
