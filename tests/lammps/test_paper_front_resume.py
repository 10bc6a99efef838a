# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# `tapmc-paper front run` (tapmc.paper.front.runs, through tapmc.campaign) resumes a stopped run
# from its latest restart file: the taps are the same, bit for bit, as those of a run never
# stopped, the rows a killed attempt wrote past its restart (and half a row) are dropped, and
# the run's CPU time counts each attempt for the taps it kept.
import gzip
import io
import os
import subprocess
import sys
from pathlib import Path

import pytest

from lmprun import LMP

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.campaign import MANIFEST_FORMAT, launch, run_folder  # noqa: E402
from tapmc.campaign.provenance import write_manifest  # noqa: E402
from tapmc.paper.front import data, runs  # noqa: E402

# a tiny run of the paper's protocol: 64 spheres (box 4R), the loosest eta, 6 taps
SETTING, N, EPS, TAPS, SEED = "change 1e-5", 64, 0.05, 6, 4928
RUN = runs.FrontRun(SETTING, N, EPS, SEED, TAPS)


def _taps_text(out):
    with gzip.open(data.taps_path(str(out), SETTING, N, EPS, SEED), "rt") as f:
        return f.read()


def _sweeps(table, last):
    return sum(s for step, s in zip(table.step, table.sweeps) if step <= last)


def test_a_stopped_run_resumes_to_the_same_taps(tmp_path):
    (whole,) = runs.run_front(str(tmp_path / "a"), [RUN], lmp=LMP, stream=io.StringIO())
    assert whole.taps == TAPS

    # an attempt stopped after tap 4 whose latest restart is tap 2, with half of row 5 written
    out = tmp_path / "b"
    work = out / runs.WORK
    run_dir = work / "runs" / RUN.name
    run_dir.mkdir(parents=True)
    assert runs.restart_every(TAPS) == 1
    short = runs.run_spec(runs.FrontRun(SETTING, N, EPS, SEED, 4))
    subprocess.run(launch.lammps_command(LMP, short, short.input,
                                         {"resume": "no", "resume_file": "restart.*"}),
                   cwd=run_dir, check=True, stdout=subprocess.DEVNULL, timeout=300)
    for step in (3, 4):
        os.remove(run_dir / ("restart.%d" % step))
    with open(run_dir / "taps.dat", "a") as f:
        f.write("5 0.55 0.5")
    table = data.read_taps(run_dir / "taps.dat")
    swept, kept = _sweeps(table, 4), _sweeps(table, 2)
    assert 0 < kept < swept
    # the campaign's record of that attempt: 100 CPU s for taps 1-4, stopped by SIGTERM
    record = dict(runs.run_spec(RUN).describe(), attempts=[
        {"resumed_from_step": None, "end_step": 4, "cpu_s": 100.0, "wall_s": 1.0,
         "returncode": -15}])
    write_manifest(work, {"format": MANIFEST_FORMAT, "runs": [record]})

    (resumed,) = runs.run_front(str(out), [RUN], lmp=LMP, stream=io.StringIO())
    assert _taps_text(out) == _taps_text(tmp_path / "a")
    assert resumed.sweeps_per_tap == whole.sweeps_per_tap
    assert not run_dir.exists()  # a finished run leaves only its gzipped taps and its row
    assert [r.key for r in data.read_runs(out / data.RUNS_CSV)] == [RUN.key]
    # the stopped attempt counts 100 s for taps 1-2 only, by their share of its sweeps
    assert float(resumed.cpu_s) > 100.0 * kept / swept
    assert float(resumed.cpu_s) < 100.0 * kept / swept + 10 * float(whole.cpu_s) + 5


def test_cpu_of_a_run_from_its_attempts():
    # 100 taps of 10 sweeps each
    table = data.TapsTable(step=list(range(1, 101)), phi_b=[0.0] * 100, phi_c=[0.0] * 100,
                           Z=[0.0] * 100, sweeps=[10.0] * 100, capped=[0.0] * 100)
    # two attempts, the first cut to the taps it kept (1-20 of 1-40): their CPU adds up
    attempts = [{"resumed_from_step": None, "end_step": 40, "cpu_s": 10.0},
                {"interrupted": True, "log": "log.attempt1.lammps", "taps_done": 40},
                {"resumed_from_step": 20, "end_step": 100, "cpu_s": 20.0}]
    assert runs.run_cpu_seconds(attempts, table) == pytest.approx(25.0)
    # an attempt without a record (a hard kill) is priced at the others' CPU per sweep
    assert runs.run_cpu_seconds(attempts[1:], table) == pytest.approx(25.0)


def test_the_campaign_trims_the_rows_after_the_restart(tmp_path):
    path = tmp_path / "taps.dat"
    rows = ["%d %s\n" % (t, " ".join(["1"] * 10)) for t in range(0, 6)]
    # a killed attempt wrote rows past its restart (step 3) and half a row
    path.write_text("# header\n" + "".join(rows) + "6 1 1")
    run_folder.trim_rows(path, 3)
    assert path.read_text() == "# header\n" + "".join(rows[:3])
    # the resumed attempt appends its title line again, and the row of its restart step
    with open(path, "a") as f:
        f.write("# header\n" + "".join(rows[3:]))
    run_folder.drop_repeated_titles(path)
    assert path.read_text() == "# header\n" + "".join(rows)
    assert run_folder.latest_restart(str(tmp_path)) == (None, None)
    # the restart a run resumes from: the latest that is not empty (a kill mid-write)
    (tmp_path / "restart.50").write_bytes(b"written")
    (tmp_path / "restart.100").touch()
    assert run_folder.latest_restart(str(tmp_path)) == (50, tmp_path / "restart.50")


def test_front_run_adds_the_missing_runs_once(tmp_path):
    """`tapmc-paper front run` runs what runs.csv lacks, records it, and has nothing left to do
    the second time; --list runs nothing."""
    out = tmp_path / "front"
    args = [sys.executable, "-m", "tapmc.paper", "front", "run", "--lmp", str(LMP), "--N", str(N),
            "--taps", "3", "--seeds", "1", "--settings", SETTING, "--eps", "%g" % EPS,
            "--out", str(out)]
    env = dict(os.environ, PYTHONPATH=str(SOURCE / "tools" / "python"))
    listed = subprocess.run(args + ["--list"], env=env, capture_output=True, text=True, timeout=60)
    assert listed.returncode == 0 and "1 runs to do" in listed.stdout and not out.exists()
    first = subprocess.run(args, env=env, capture_output=True, text=True, timeout=300)
    assert first.returncode == 0, first.stderr
    assert "1 runs added" in first.stdout
    (row,) = data.read_runs(out / data.RUNS_CSV)
    assert row.key == (SETTING, N, "%g" % EPS, SEED, 3) and float(row.cpu_s) > 0
    assert data.read_meta(str(out))["lmp"] == os.path.basename(LMP)
    again = subprocess.run(args, env=env, capture_output=True, text=True, timeout=60)
    assert again.returncode == 0 and "0 runs to do" in again.stdout
