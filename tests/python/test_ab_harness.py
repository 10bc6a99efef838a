# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The A/B harness of bench/ (ab_mc_settle.py): it reads every kernel row of bench_mc_settle
--kernel, and its speed-ups are new / ref for rates and ref / new for times."""
import importlib.util
import os
import subprocess
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BUILD = Path(os.environ.get("TAPMC_BUILD_DIR", SOURCE / "build"))


def harness():
    spec = importlib.util.spec_from_file_location("ab_mc_settle", SOURCE / "bench" / "ab_mc_settle.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_speedups_are_oriented_by_the_kind_of_row():
    ab = harness()
    rate = ab.summarize("N = 4096, Random order (paper)", [10.0, 12.0, 11.0], [15.0, 12.0, 22.0])
    assert rate["speedup_of_medians"] == pytest.approx(15.0 / 11.0)
    assert rate["pair_speedup_min"] == pytest.approx(1.0)
    assert rate["pair_speedup_max"] == pytest.approx(2.0)
    time = ab.summarize("s per tap (loop)", [2.0, 2.0, 3.0], [1.0, 2.0, 1.5])
    assert time["speedup_of_medians"] == pytest.approx(2.0 / 1.5)
    assert time["pair_speedup_median"] == pytest.approx(2.0)
    assert time["pair_speedup_min"] == pytest.approx(1.0)


def test_every_kernel_row_of_the_benchmark_is_read():
    binary = BUILD / "bench" / "bench_mc_settle"
    if not binary.exists():
        pytest.skip(f"{binary} not built (TAPMC_BUILD_BENCH=OFF)")
    out = subprocess.run([str(binary), "--kernel"], capture_output=True, text=True, check=True,
                         timeout=120).stdout
    printed = [line for line in out.splitlines() if "M moves/s" in line]
    rows = harness().kernel_rows(str(binary), False, False)
    assert len(rows) == len(printed) >= 6
    assert all(v > 0 for v in rows.values())
    assert "N = 4096, Random order (paper)" in rows
    bad = subprocess.run([str(binary), "--bogus"], capture_output=True, text=True)
    assert bad.returncode == 2 and "--kernel" in bad.stderr
