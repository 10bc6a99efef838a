# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.paper.front: the paired bias of each setting against the reference, its 95 % bound,
the recommended settings and the page, on synthetic runs whose answers are known; and the
committed page equals what its committed runs give."""

import csv
import gzip
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
SOURCE = HERE.parents[1]
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.paper import front  # noqa: E402
from tapmc.paper.front import page  # noqa: E402

#: the title line of examples/paper/in.constant_eps's taps.dat
TAPS_TITLE = "# step phi_b phi_c Z z_top lateral central h_s sweeps accept capped\n"

# setting -> (offset of every observable against the reference, CPU s per tap)
SYNTHETIC = {
    front.REFERENCE: (0.0, 1.0),
    # cheap, far off and more so at the larger eps: smoke test only
    "change 1e-5": ({0.0225: -0.01, 0.1: -0.02}, 0.02),
    # off by more than publication allows, alike at every eps and tap: exploration
    "change 1e-6": (-0.002, 0.05),
    front.DEFAULT: (-0.0002, 0.1),      # within publication
    "drift 3e-8": (0.0, 2.0),           # tighter than the reference: agrees
    "dmax R/10": (-0.0005, 0.15),       # d_max: dearer and farther than R/5 (the default) ...
    "dmax R/2": (-0.0001, 0.12),        # ... dearer and not closer by two standard errors
}
# per-seed scatter of the offsets (paired differences): known standard error
JITTER = (-0.0001, 0.0, 0.0001)


def _write_run(data, name, N, eps, seed, k, offset, cpu, drift=0.0):
    """One synthetic run: the setting's offset (a number, or eps -> number) plus `drift` x t /
    TAPS (a bias that grows with the tap count)."""
    offset = offset[eps] if isinstance(offset, dict) else offset
    path = front.taps_path(str(data), name, N, eps, seed)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with gzip.open(path, "wt") as f:
        f.write(TAPS_TITLE)
        for t in range(front.TAPS + 1):
            # a packing that compacts with t, differs from seed to seed, and is shifted by the
            # setting's offset (+ its per-seed jitter, except for the reference)
            base = 0.58 + 0.02 * (1 - math.exp(-t / 200.0)) + 0.003 * k
            shift = offset + drift * t / front.TAPS + (JITTER[k] if name != front.REFERENCE else 0.0)
            phi_c = base + shift
            f.write(f"{t} {phi_c - 0.03} {phi_c} {7.0 + 10 * shift} 13 0.57 0.58 14 {1000} 0.02 0\n")
    return {"setting": name, "N": N, "eps": "%g" % eps, "seed": seed, "taps": front.TAPS,
            "eta": front.SETTINGS[name]["eta"], "settle_keys": front.settle_keys(name, N),
            "cpu_s": cpu * front.TAPS, "wall_s": cpu * front.TAPS, "cpu_per_tap": cpu,
            "sweeps_per_tap": 1000 * cpu, "capped_taps": 0}


@pytest.fixture
def data(tmp_path):
    rows = []
    for eps in front.EPS:
        for k, seed in enumerate(front.seeds(3)):
            for name, (offset, cpu) in SYNTHETIC.items():
                rows.append(_write_run(tmp_path, name, 1024, eps, seed, k, offset, cpu))
    with open(tmp_path / "runs.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=front.RUN_FIELDS)
        w.writeheader()
        w.writerows(rows)
    return tmp_path


def test_paired_bias_and_its_bound(data):
    fr = front.Front(data).compute()
    row = fr.rows(N=1024, eps=0.0225, setting="change 1e-6")[0]
    se = 0.0001 / math.sqrt(3)  # standard error of the mean of the jitter (sd 1e-4, 3 seeds)
    for q in ("phi_c_t1", "phi_c_t1000", "phi_b_steady"):
        assert row.biases[q].mean == pytest.approx(-0.002, abs=1e-12)
        assert row.biases[q].se == pytest.approx(se, rel=1e-6)
        assert row.biases[q].bound == pytest.approx(0.002 + 4.302653 * se, rel=1e-5)
    assert row.biases["Z_steady"].mean == pytest.approx(-0.02, abs=1e-9)
    # the per-seed spread of the packings (0.003 per seed) is in the values, not in the bias
    assert row.values["phi_c_t1000"].se > 10 * row.biases["phi_c_t1000"].se
    assert row.cpu_per_tap.mean == pytest.approx(0.05) and row.seeds == 3
    ref = fr.rows(N=1024, eps=0.1, setting=front.REFERENCE)[0]
    assert ref.biases["phi_c_steady"].mean == 0.0 and ref.biases["phi_c_steady"].se == 0.0


def test_recommendations_take_the_cheapest_setting_within_each_tolerance(data):
    recs = front.Front(data).compute().recommendations(1024)
    assert recs["publication"].setting == front.DEFAULT
    assert recs["exploration"].setting == "change 1e-6"
    assert recs["smoke test"].setting == "change 1e-5"
    assert recs["exploration"].worst_bound <= 0.003 < 0.0032


def test_exploration_bounds_the_change_of_the_bias_not_the_bias(data):
    """A bias alike at every eps and tap passes exploration however large (it shifts every
    curve alike) and is stated; one that changes with eps or grows with the taps does not."""
    fr = front.Front(data).compute()
    same = fr.rows(N=1024, setting="change 1e-6")
    se = 0.0001 / math.sqrt(3)
    assert all(r.trend_bounds["phi_c_steady"] < 4.31 * 2 * se for r in same)
    recs = fr.recommendations(1024)
    assert recs["exploration"].worst_bias == pytest.approx(-0.002, abs=1e-9)
    assert recs["exploration"].criterion == "trend"
    # change 1e-5 is -0.01 at eps 0.0225 and -0.02 at 0.1: its change is 0.01 at least
    assert front.worst_trend("change 1e-5", fr.rows(N=1024, setting="change 1e-5")) >= 0.01
    # a bias that grows by 0.01 over the run moves between tap 100 and the steady window
    rows = []
    for eps in front.EPS:
        for k, seed in enumerate(front.seeds(3)):
            rows.append(_write_run(data, "change 1e-8", 1024, eps, seed, k, 0.0, 0.04, drift=-0.01))
    with open(data / "runs.csv", "a", newline="") as f:
        csv.DictWriter(f, fieldnames=front.RUN_FIELDS).writerows(rows)
    fr = front.Front(data).compute()
    drifting = fr.rows(N=1024, setting="change 1e-8")
    assert front.worst_trend("change 1e-8", drifting) > 0.006
    assert fr.recommendations(1024)["exploration"].setting == "change 1e-6"


def test_lammps_line_of_each_setting():
    assert front.lammps_line(front.REFERENCE) == "fix settle all mc/settle SEED floor 0.0 stop drift"
    assert front.lammps_line(front.DEFAULT) == "fix settle all mc/settle SEED floor 0.0"
    assert front.lammps_line("change 1e-5") == "fix settle all mc/settle SEED floor 0.0 eta 1e-5"
    assert front.lammps_line("check 10 sweeps, 1e-6", 1024) == \
        "fix settle all mc/settle SEED floor 0.0 check 10240 eta 1e-6"


def test_reference_check_names_what_differs(data):
    fr = front.Front(data).compute()
    checks = fr.reference_check(1024)
    assert {(c.setting, c.eps) for c in checks} == {("drift 3e-8", e) for e in front.EPS}
    assert all(c.differing == [] and c.paired_seeds == 3 for c in checks)  # zero offset: every quantity agrees


def test_page_figure_summary_and_the_reports_sentence(data, tmp_path):
    root = tmp_path / "repo"
    (root / "doc").mkdir(parents=True)
    (root / "tools" / "python" / "tapmc" / "paper").mkdir(parents=True)
    written = page.write_page(root, data_dir=str(data))
    text = Path(written).read_text()
    assert "change 1e-6" in text and "-0.0020 +- 0.0001" in text
    assert "all 15 agree with the reference" in text
    assert "neither is both cheaper and closer to the reference" in text
    assert "R/10 costs 1.50 times its CPU time per tap" in text
    assert (data / "front.png").stat().st_size > 10000
    summary = root / "tools" / "python" / "tapmc" / "paper" / "front_summary.csv"
    sentence = front.bias_sentence(1e-6, path=str(summary))
    assert "-0.0020 +- 0.0001 over taps 900-1000" in sentence and "eps = 0.1" in sentence
    assert "has not measured" in front.bias_sentence(3e-6, path=str(summary))


def test_a_second_N_has_its_figure_and_the_presets_are_judged_at_their_own_N(data, tmp_path):
    # N = 4096: the reference, the default (biased 0.0005, inside publication) and eta = 1e-5
    rows = []
    for eps in front.EPS:
        for k, seed in enumerate(front.seeds(3)):
            for name in (front.REFERENCE, front.DEFAULT, "change 1e-5"):
                offset, cpu = SYNTHETIC[name]
                rows.append(_write_run(data, name, 4096, eps, seed, k, offset, 4 * cpu))
    with open(data / "runs.csv", "a", newline="") as f:
        csv.DictWriter(f, fieldnames=front.RUN_FIELDS).writerows(rows)
    root = tmp_path / "repo"
    (root / "doc").mkdir(parents=True)
    (root / "tools" / "python" / "tapmc" / "paper").mkdir(parents=True)
    text = Path(page.write_page(root, data_dir=str(data))).read_text()
    assert (data / "front.png").stat().st_size > 10000
    assert (data / "front_N4096.png").stat().st_size > 10000
    assert "validation/front/front_N4096.png" in text and "N = 4096 (box 32R x 32R)" in text
    assert "not measured yet" not in text
    presets = {line.split()[0]: line for line in text.splitlines()
               if line.split() and line.split()[0] in front.PRESET_PURPOSE}
    # full (N = 4096, eta 1e-7) is judged on the N = 4096 rows; medium (N = 1024) on N = 1024,
    # quick (N = 512) on the nearest N measured, 1024
    assert "N = 4096, 4000 taps  N = 4096" in presets["full"]
    assert "N = 1024, 1000 taps  N = 1024" in presets["medium"]
    assert "N = 512, 100 taps    N = 1024" in presets["quick"]
    # the same setting (ratio 1); medium's recommended change 1e-6 costs 0.05 / 0.02 CPU s per tap
    assert presets["full"].split()[-2:] == ["yes", "1.0"]
    # a setting run where the reference has not: no bias stated for it
    with open(data / "runs.csv", "a", newline="") as f:
        csv.DictWriter(f, fieldnames=front.RUN_FIELDS).writerow(
            _write_run(data, "change 1e-6", 2048, 0.0225, front.seeds(1)[0], 0, -0.002, 0.3))
    page.write_page(root, data_dir=str(data))
    sentence = front.bias_sentence(1e-6, path=str(root / "tools" / "python" / "tapmc" / "paper"
                                                   / "front_summary.csv"))
    assert "N = 2048" not in sentence and "N = 1024, eps = 0.0225" in sentence
    assert presets["medium"].split()[-2:] == ["no", "2.5"]


def test_bad_data_is_refused_with_its_reason(tmp_path):
    with pytest.raises(front.FrontDataError, match="runs.csv: no such file"):
        front.Front(tmp_path)
    (tmp_path / "runs.csv").write_text(",".join(front.RUN_FIELDS) + "\n"
                                       + "no such setting,1024,0.1,1,1000,1e-7,,1,1,1,1,0\n")
    with pytest.raises(ValueError, match="runs.csv:2: setting 'no such setting'"):
        front.Front(tmp_path)


def test_committed_page_is_what_the_committed_runs_give(tmp_path):
    """doc/front.rst and front_summary.csv are `tapmc-paper front` of doc/validation/front."""
    data = SOURCE / front.DATA_DIR
    if not (data / "runs.csv").is_file():
        pytest.skip("no committed front data")
    root = tmp_path / "repo"
    shutil.copytree(data, root / front.DATA_DIR)
    (root / "tools" / "python" / "tapmc" / "paper").mkdir(parents=True)
    env = dict(os.environ, PYTHONPATH=str(SOURCE / "tools" / "python"))
    done = subprocess.run([sys.executable, "-m", "tapmc.paper", "front", "--root", str(root)],
                          env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    hint = "run 'build/tapmc-paper front' and commit the result"
    assert (root / page.PAGE).read_text() == (SOURCE / page.PAGE).read_text(), hint
    name = os.path.basename(front.SUMMARY)
    assert ((root / "tools" / "python" / "tapmc" / "paper" / name).read_text()
            == Path(front.SUMMARY).read_text()), hint
    for csv_path in sorted(data.glob("front*.csv")):
        assert (root / front.DATA_DIR / csv_path.name).read_text() == csv_path.read_text(), hint


def test_every_preset_has_its_setting_on_the_front():
    """The reports state the measured bias of their eta: each preset's must be a front setting,
    and each preset is made for one of the front's purposes."""
    from tapmc.paper.scales import SCALES

    assert set(front.PRESET_PURPOSE) == set(SCALES)
    assert set(front.PRESET_PURPOSE.values()) == {p for p, _, _ in front.PURPOSES}
    for name, scale in SCALES.items():
        assert front.setting_named(scale.eta) in front.SETTINGS, name


# ---- bad input: `tapmc-paper front` names the file (and line), exits 2, writes nothing ----------

def _repo_with_front(data, tmp_path):
    """A repository whose doc/validation/front is `data`, with a committed page and summary."""
    root = tmp_path / "repo"
    shutil.copytree(data, root / front.DATA_DIR)
    (root / "doc" / "front.rst").write_text("committed page\n")
    package = root / "tools" / "python" / "tapmc" / "paper"
    package.mkdir(parents=True)
    (package / "front_summary.csv").write_text("committed summary\n")
    return root


def _front_fails(root, capsys, *where):
    from tapmc.paper import cli

    assert cli.main(["front", "--root", str(root)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("tapmc-paper front: ") and "Traceback" not in err
    for text in where:
        assert text in err, err
    assert (root / "doc" / "front.rst").read_text() == "committed page\n"
    assert (root / "tools" / "python" / "tapmc" / "paper" / "front_summary.csv").read_text() \
        == "committed summary\n"
    assert not list((root / front.DATA_DIR).glob("front*"))  # no figure either
    return err


def test_a_runs_csv_cut_mid_row_is_named_with_its_line(data, tmp_path, capsys):
    root = _repo_with_front(data, tmp_path)
    runs_csv = root / front.DATA_DIR / "runs.csv"
    text = runs_csv.read_text()
    lines = text.splitlines(keepends=True)
    runs_csv.write_text("".join(lines[:5]) + lines[5][:20])
    _front_fails(root, capsys, f"{runs_csv}:6: ", "cut short")
    runs_csv.write_text("".join(lines[:5]) + lines[5][:20] + "\n" + "".join(lines[6:]))
    _front_fails(root, capsys, f"{runs_csv}:6: ", "fields, expected 12 (a row cut short?)")
    runs_csv.write_text("".join(lines[:5]) + lines[5].rstrip("\r\n") + ",1,2\r\n")
    _front_fails(root, capsys, f"{runs_csv}:6: 14 fields, expected 12")


def test_a_runs_csv_missing_a_column_is_named(data, tmp_path, capsys):
    root = _repo_with_front(data, tmp_path)
    runs_csv = root / front.DATA_DIR / "runs.csv"
    with open(runs_csv, newline="") as f:
        rows = list(csv.DictReader(f))
    with open(runs_csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=[c for c in front.RUN_FIELDS if c != "cpu_per_tap"],
                           extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    _front_fails(root, capsys, f"{runs_csv}:1: no column cpu_per_tap")
    runs_csv.write_text("")
    _front_fails(root, capsys, f"{runs_csv}:1: no column setting")
    (root / front.DATA_DIR / "runs.csv").unlink()
    _front_fails(root, capsys, f"{runs_csv}: no such file")


def test_a_meta_json_without_its_keys_is_named(data, tmp_path, capsys):
    root = _repo_with_front(data, tmp_path)
    meta = root / front.DATA_DIR / "meta.json"
    for text, what in (("{}", "no commit, machine"), ("[1]", "expected a JSON object"),
                       ('{"commit": ', "not readable JSON")):
        meta.write_text(text)
        _front_fails(root, capsys, f"{meta}: {what}")


def test_a_cut_or_short_taps_file_is_named(data, tmp_path, capsys):
    root = _repo_with_front(data, tmp_path)
    taps = Path(front.taps_path(str(root / front.DATA_DIR), "change 1e-6", 1024, 0.1,
                                front.seeds(1)[0]))
    whole = taps.read_bytes()
    taps.write_bytes(whole[:len(whole) // 2])
    _front_fails(root, capsys, f"{taps}: damaged gzip file")
    with gzip.open(taps, "wt") as f:
        f.write(TAPS_TITLE + "0 0.55 0.58 7 13 0.57 0.58 14 0 0 0\n1 0.55 0.58 7 13 0.57 0.58 14 9 0 0\n")
    _front_fails(root, capsys, f"{taps}: 1 taps (steps 1 to 1), expected steps 1 to {front.TAPS}")
    taps.unlink()
    _front_fails(root, capsys, f"{taps}")


def test_front_run_refuses_a_damaged_runs_csv_before_running(data, capsys):
    from tapmc.paper import cli

    runs_csv = data / "runs.csv"
    runs_csv.write_text(runs_csv.read_text()[:-3])
    assert cli.main(["front", "run", "--list", "--out", str(data)]) == 2
    assert f"{runs_csv}:" in capsys.readouterr().err
