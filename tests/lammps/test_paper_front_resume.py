# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# bench/paper_front.py resumes a stopped run from its latest restart file: the taps are the same,
# bit for bit, as those of a run never stopped, the rows a killed attempt wrote past its restart
# (and half a row) are dropped, and the run's CPU time counts each attempt for the taps it kept.
import gzip
import importlib.util
import os
import subprocess
from pathlib import Path

import pytest

from lmprun import LMP

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
_spec = importlib.util.spec_from_file_location("paper_front", SOURCE / "bench" / "paper_front.py")
paper_front = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(paper_front)
front = paper_front.front

# a tiny run of the paper's protocol: 64 spheres (box 4R), the loosest eta, 6 taps
SETTING, N, EPS, TAPS, SEED = "change 1e-5", 64, 0.05, 6, 4928


def _taps_text(out):
    with gzip.open(front.taps_path(str(out), SETTING, N, EPS, SEED), "rt") as f:
        return f.read()


def test_a_stopped_run_resumes_to_the_same_taps(tmp_path):
    whole = paper_front.run_one(LMP, SETTING, N, EPS, TAPS, SEED, str(tmp_path / "a"), 0)
    assert whole is not None and int(whole["taps"]) == TAPS

    # an attempt stopped after tap 4 whose latest restart is tap 2, with half of row 5 written
    out = tmp_path / "b"
    work = paper_front.work_dir(str(out), SETTING, N, EPS, SEED)
    os.makedirs(work)
    assert paper_front.restart_every(TAPS) == 1
    subprocess.run(paper_front.lmp_command(LMP, SETTING, N, EPS, 4, SEED, 0), cwd=work, check=True,
                   stdout=subprocess.DEVNULL, timeout=300)
    for step in (3, 4):
        os.remove(os.path.join(work, "restart.%d" % step))
    taps_dat = os.path.join(work, "taps.dat")
    with open(taps_dat, "a") as f:
        f.write("5 0.55 0.5")
    swept = paper_front.sweeps_between(taps_dat, 0, 4)
    kept = paper_front.sweeps_between(taps_dat, 0, 2)
    assert 0 < kept < swept
    paper_front.save_attempts(work, [{"start": 0, "end": 4, "cpu": 100.0, "wall": 1.0,
                                      "sweeps": swept, "rc": -15}])

    resumed = paper_front.run_one(LMP, SETTING, N, EPS, TAPS, SEED, str(out), 0)
    assert resumed is not None
    assert _taps_text(out) == _taps_text(tmp_path / "a")
    assert resumed["sweeps_per_tap"] == whole["sweeps_per_tap"]
    assert not os.path.exists(work)  # a finished run leaves only its gzipped taps
    # the stopped attempt counts 100 s for taps 1-2 only, by their share of its sweeps
    assert float(resumed["cpu_s"]) > 100.0 * kept / swept
    assert float(resumed["cpu_s"]) < 100.0 * kept / swept + 10 * float(whole["cpu_s"]) + 5


def test_cpu_of_a_run_from_its_attempts():
    # two attempts, the first cut to the taps it kept: their CPU adds up
    attempts = [{"start": 0, "end": 40, "cpu": 10.0, "sweeps": 400.0, "kept_cpu": 5.0,
                 "kept_sweeps": 200.0},
                {"start": 20, "end": 100, "cpu": 20.0, "sweeps": 800.0}]
    assert paper_front.run_cpu_seconds(attempts, 1000.0) == pytest.approx(25.0)
    # an attempt without a record (a hard kill) is priced at the others' CPU per sweep
    assert paper_front.run_cpu_seconds(attempts[1:], 1000.0) == pytest.approx(25.0)


def test_trim_taps_keeps_the_rows_up_to_the_restart(tmp_path):
    path = tmp_path / "taps.dat"
    width = len(front.TAPS_COLUMNS)
    rows = ["%d %s\n" % (t, " ".join(["1"] * (width - 1))) for t in range(0, 6)]
    # a resumed attempt wrote the header and the row of its restart (step 2) again
    path.write_text("# header\n" + "".join(rows[:3]) + "# header\n" + "".join(rows[2:]) + "6 1 1")
    paper_front.trim_taps(str(path), 3)
    assert path.read_text() == "# header\n" + "".join(rows[:4])
    assert paper_front.latest_restart(str(tmp_path)) == (None, None)
    # the restart a run resumes from: the latest that is not empty (a kill mid-write)
    (tmp_path / "restart.50").write_bytes(b"written")
    (tmp_path / "restart.100").touch()
    assert paper_front.latest_restart(str(tmp_path)) == (50, tmp_path / "restart.50")
