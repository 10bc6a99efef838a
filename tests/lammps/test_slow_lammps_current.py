# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# TAPMC on the current LAMMPS release (4 Jul 2026, label "slow"): compiled against the LAMMPS that
# tools/setup/build-lammps-plugin.sh builds from Debian unstable's original tarball (see
# lammps_builds.py), the LAMMPS-level tests (GoogleTest library tests, mpirun tests, process
# tests of tests/lammps; not the slow ones) pass there, and every example input, run with the
# small settings of test_example_switches.py, prints the same thermo output on that LAMMPS as on
# Debian's 2021 LAMMPS: the TAPMC styles compute everything they print themselves, with their
# own random streams, so the LAMMPS version must not change a digit. The version-dependent
# parts (LAMMPS's own messages, `clear` and plugins) are in the tests that check them.
import os
import re
import subprocess
from pathlib import Path

import pytest

from lammps_builds import lammps_prefix, run, tapmc_against
from lmprun import LMP
from test_example_switches import RUNS, example_command

NAME = "2026"


@pytest.fixture(scope="module")
def current():
    """The TAPMC build directory compiled against LAMMPS 2026, test suite included."""
    prefix = lammps_prefix(NAME)
    return tapmc_against(NAME, prefix, ["all"])


def test_tapmc_build_uses_the_current_lammps(current):
    cache = (Path(current) / "CMakeCache.txt").read_text()
    assert re.search(r"^LAMMPS_DIR:\w+=.*lammps-plugin-20260704", cache, re.M), cache
    rc, out = run([os.path.join(current, "lmp_tapmc"), "-h"], cwd=current)
    assert rc == 0, out
    assert "Large-scale Atomic/Molecular Massively Parallel Simulator - 4 Jul 2026" in out, out


def test_lammps_level_tests_pass_on_the_current_lammps(current):
    """The fast LAMMPS-level tests of that build (ctest names lammps.* and mpi.*), run there."""
    env = dict(os.environ, OMPI_MCA_rmaps_base_oversubscribe="1", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    rc, out = run(["ctest", "--test-dir", current, "--output-on-failure", "-R",
                   r"^(lammps|mpi)\.", "-E", r"(^|\.)(Slow|test_slow_)", "-LE", "slow"],
                  cwd=current, env=env, timeout=3 * 3600)
    assert rc == 0, out
    assert re.search(r"100% tests passed, 0 tests failed out of ([2-9][0-9]|[1-9][0-9][0-9])",
                     out), out


# LAMMPS's own report of a run (banner, set-up, memory, timings, neighbour statistics): its
# wording and fields are LAMMPS's and change with the version, and timings change run to run.
LAMMPS_REPORT = re.compile("|".join([
    r"^LAMMPS \(", r"OMP_NUM_THREADS", r"using \d+ OpenMP thread", r"^Created orthogonal box",
    r"MPI processor grid", r"create_packing CPU =", r"^Setting up Verlet run", r"^  Unit style",
    r"^  Current step", r"^  Time step", r"^Per MPI rank memory", r"^Loop time", r"^Performance:",
    r"CPU use with", r"^MPI task timing", r"^Section", r"^-----",
    r"^(Pair|Bond|Kspace|Neigh|Comm|Output|Modify|Other) *\|", r"^(Nlocal|Nghost|Neighs)",
    r"^Histogram", r"^Total # of", r"^Ave neighs", r"^Neighbor list builds",
    r"^Dangerous builds", r"^Total wall time", r"^For more information see", r"^\s*$"]))
# LAMMPS's own warnings: the same text, but the source location and the final full stop of the
# wording change with the version ("... full system init. (src/write_dump.cpp:84)" in 2021,
# "... full system init (src/write_dump.cpp:87)" in 2026).
LAMMPS_WARNING_TAIL = re.compile(r"\.? \(src/[^ ]+:\d+\)$")
# Thermo columns that are timings (thermo keywords cpu and cpuremain), different run to run.
TIMING_COLUMNS = ("CPU", "CPULeft")


def example_output(lmp, example, variables, workdir):
    """What an example prints that does not come from LAMMPS's own run report: the thermo
    output (the CPU / CPULeft columns left out), TAPMC's messages, the input's print lines and warnings."""
    proc = subprocess.run(example_command(lmp, example, variables), cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, timeout=600, stdin=subprocess.DEVNULL)
    assert proc.returncode == 0, proc.stdout
    lines, header = [], None
    for line in proc.stdout.splitlines():
        words = line.split()
        if words[:1] == ["Step"]:
            header = words
            lines.append(" ".join(w for w in words if w not in TIMING_COLUMNS))
        elif header is not None and len(words) == len(header) and words[0].isdigit():
            lines.append(" ".join(w for w, h in zip(words, header) if h not in TIMING_COLUMNS))
        else:
            header = None
            if line.startswith("WARNING:"):
                lines.append(LAMMPS_WARNING_TAIL.sub("", line))
            elif not LAMMPS_REPORT.search(line):
                lines.append(line)
    return lines


@pytest.mark.parametrize("example", sorted(RUNS))
def test_examples_print_the_same_thermo_as_on_debians_lammps(current, example, tmp_path):
    variables = RUNS[example][0]
    (tmp_path / "debian").mkdir()
    (tmp_path / "current").mkdir()
    expected = example_output(LMP, example, variables, tmp_path / "debian")
    got = example_output(os.path.join(current, "lmp_tapmc"), example, variables,
                         tmp_path / "current")
    assert any(line.startswith("Step") for line in expected) or example.startswith("deposition")
    assert got == expected
