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
    # an instruction count is lower-is-better, as a time
    count = ab.summarize(ab.INSTRUCTIONS_ROW, [200], [100])
    assert count["speedup_of_medians"] == count["pair_speedup_max"] == pytest.approx(2.0)


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


ANNOTATE = """--------------------------------------------------------------------------------
Ir
--------------------------------------------------------------------------------
1,000,000 (100.0%)  PROGRAM TOTALS

--------------------------------------------------------------------------------
Ir                      file:function
--------------------------------------------------------------------------------
  600,000 (60.00%)  ???:tapmc::TrialMoveSampler::draw_trials(tapmc::CounterRandom const&, int) const [{binary}]
  300,000 (30.00%)  ???:void tapmc::run_trials<true, false>(tapmc::SphereMover::State&) [{binary}]
   {atan2:>6,d} ( 9.00%)  ./math/../sysdeps/ieee754/dbl-64/e_atan2.c:__ieee754_atan2_fma [/usr/lib/libm.so.6]
"""


def test_callgrind_counts_are_read_per_function_whatever_the_build():
    ab = harness()
    ref = ab.parse_annotate(ANNOTATE.format(binary="ref-build/bench/bench_mc_settle", atan2=90000))
    new = ab.parse_annotate(ANNOTATE.format(binary="build/bench/bench_mc_settle", atan2=80000))
    assert ref[0] == new[0] == 1_000_000
    # the same function of two builds has one name: no source file, no binary
    assert set(ref[1]) == set(new[1]) == {
        "tapmc::TrialMoveSampler::draw_trials(tapmc::CounterRandom const&, int) const",
        "void tapmc::run_trials<true, false>(tapmc::SphereMover::State&)",
        "__ieee754_atan2_fma"}
    table = ab.instruction_table(ref, new, 8)
    assert "new / ref 1.00000" in table[0]
    assert len(table) == 3 and "-10,000" in table[2] and "__ieee754_atan2_fma" in table[2]
    # control: the same counts list no change
    assert ab.instruction_table(ref, ref, 8)[-1] == "no function's count changed"
    with pytest.raises(SystemExit, match="PROGRAM TOTALS"):
        ab.parse_annotate("nothing here")


def test_pairs_zero_needs_the_instruction_count():
    script = SOURCE / "bench" / "ab_mc_settle.py"
    out = subprocess.run(["/usr/bin/python3", str(script), "--pairs", "0", "--build", "/nonexistent"],
                         capture_output=True, text=True)
    assert out.returncode != 0 and "--pairs = 0" in out.stderr and "--instructions" in out.stderr
