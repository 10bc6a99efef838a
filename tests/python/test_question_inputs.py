# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""``tapmc-paper question`` on bad input (issue 41): a missing, file or empty --campaign, a
campaign without finished runs, a cut dump or taps.dat, a ramp whose run folder is gone. Each
ends with one line naming the file (and line) and what is wrong, exit status 1, no traceback,
and the CSV already in --out (the committed result) left exactly as it was. And every
question answers ``--help``."""

import csv
import os
import shutil
import sys
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.paper import cli  # noqa: E402
from tapmc.paper.questions import QUESTIONS, common  # noqa: E402

#: the re-analyses of the campaign that wrote a header-only CSV from an empty campaign
REANALYSES = {"spectral-window": "spectral_window.csv", "realization-scatter":
              "realization_scatter.csv", "seed-fits": "seed_fits.csv",
              "pbc-course": "pbc_course.csv", "packing-scatter": "packing_scatter.csv",
              "fit-surrogates": "fit_surrogates.csv", "crystallinity": "crystallinity.csv",
              "alpha-window": "alpha_window.csv"}
#: what a committed result holds before a command fails
COMMITTED = "run,eps\ncommitted,0.05\n"
RUN = SOURCE / "doc" / "validation" / "data" / "full" / "runs" / "const_pbc_eps0.0225_s1"


def question(capsys, *argv):
    """(exit status, stderr) of ``tapmc-paper question ARGV`` run in this process."""
    status = cli.main(["question", *map(str, argv)])
    return status, capsys.readouterr().err


def bad_campaign(tmp_path, kind):
    """A --campaign that is missing, a file, an empty folder, or a campaign whose runs have
    not finished (taps.dat but no DONE.json)."""
    path = tmp_path / "campaign"
    if kind == "file":
        path.write_text("not a campaign\n")
    elif kind == "empty":
        path.mkdir()
    elif kind == "unfinished":
        for name in ("const_pbc_eps0.05_s1", "const_pbc_eps0.05_s2", "const_fbc_eps0.05_s1"):
            (path / "runs" / name).mkdir(parents=True)
            (path / "runs" / name / "taps.dat").write_text("# step phi_b phi_c Z\n0 0.5 0.5 6\n")
    return path


@pytest.mark.parametrize("kind", ["missing", "file", "empty", "unfinished"])
@pytest.mark.parametrize("name", sorted(REANALYSES))
def test_reanalysis_of_a_bad_campaign_keeps_the_committed_csv(capsys, tmp_path, name, kind):
    campaign = bad_campaign(tmp_path, kind)
    out = tmp_path / "out"
    out.mkdir()
    committed = out / REANALYSES[name]
    committed.write_text(COMMITTED)
    status, err = question(capsys, name, "--campaign", campaign, "--out", out)
    assert status == 2
    assert err.startswith(f"tapmc-paper question {name}: ") and err.count("\n") == 1, err
    assert str(campaign) in err and "Traceback" not in err
    assert committed.read_text() == COMMITTED
    assert sorted(p.name for p in out.iterdir()) == [committed.name]   # no partial file left


def test_no_csv_is_made_from_nothing(capsys, tmp_path):
    status, _ = question(capsys, "pbc-course", "--campaign", bad_campaign(tmp_path, "empty"),
                         "--out", tmp_path / "out")
    assert status == 2 and not (tmp_path / "out" / "pbc_course.csv").exists()


def test_write_csv_replaces_a_file_whole_or_not_at_all(tmp_path):
    path = tmp_path / "q.csv"
    path.write_text(COMMITTED)
    with pytest.raises(common.QuestionError, match="nothing to write"):
        common.write_csv(path, ["run", "eps"], [])
    with pytest.raises(csv.Error):       # a row that cannot be written half-way through
        common.write_csv(path, ["run", "eps"], [["a", 1], None])
    assert path.read_text() == COMMITTED and sorted(os.listdir(tmp_path)) == ["q.csv"]
    common.write_csv(path, ["run", "eps"], [["b", 2]])
    assert path.read_bytes() == b"run,eps\r\nb,2\r\n"


@pytest.mark.parametrize("kind", ["missing", "file", "empty"])
def test_integrity_of_a_bad_campaign(capsys, tmp_path, kind):
    campaign = bad_campaign(tmp_path, kind)
    status, err = question(capsys, "integrity", "--campaign", campaign, "--out", tmp_path)
    assert status == 2 and str(campaign) in err and "Traceback" not in err
    assert not (tmp_path / "integrity.csv").exists()


def copied_run(tmp_path, dumps):
    """A campaign with a copy of the committed run's taps.dat and ``dumps``."""
    if not all((RUN / d).is_file() for d in dumps):
        pytest.skip("campaign data absent")
    folder = tmp_path / "campaign" / "runs" / RUN.name
    folder.mkdir(parents=True)
    for name in ("taps.dat", *dumps):
        shutil.copy(RUN / name, folder / name)
    return folder


def cut(path, keep):
    data = path.read_bytes()
    path.write_bytes(data[:keep])


def test_integrity_of_a_cut_dump_names_the_file_and_line(capsys, tmp_path):
    folder = copied_run(tmp_path, ["dump.0.lammpstrj"])
    cut(folder / "dump.0.lammpstrj", 100000)
    (tmp_path / "integrity.csv").write_text(COMMITTED)
    status, err = question(capsys, "integrity", "--campaign", tmp_path / "campaign",
                           "--out", tmp_path)
    assert status == 2 and "Traceback" not in err
    assert f"{folder / 'dump.0.lammpstrj'}:" in err and "cut short" in err
    assert (tmp_path / "integrity.csv").read_text() == COMMITTED


def test_integrity_of_a_cut_taps_file_names_it(capsys, tmp_path):
    folder = copied_run(tmp_path, ["dump.0.lammpstrj", "dump.4000.lammpstrj"])
    cut(folder / "taps.dat", 3000)          # ends inside a line, long before tap 4000
    status, err = question(capsys, "integrity", "--campaign", tmp_path / "campaign",
                           "--out", tmp_path)
    assert status == 2 and "Traceback" not in err
    assert f"{folder / 'taps.dat'}: ends at step" in err and "dump.4000.lammpstrj" in err
    assert not (tmp_path / "integrity.csv").exists()
    (folder / "taps.dat").write_text("# step phi_b phi_c Z\n0 0.5 0.5\n")   # a short row
    status, err = question(capsys, "integrity", "--campaign", tmp_path / "campaign",
                           "--out", tmp_path)
    assert status == 2 and f"{folder / 'taps.dat'}:" in err and "Traceback" not in err


def ramp_campaign(tmp_path, with_run):
    """A campaign whose manifest lists ramp_pbc_s1, with or without its run folder."""
    campaign = tmp_path / "campaign"
    (campaign / "runs").mkdir(parents=True)
    (campaign / "manifest.json").write_text(
        '{"runs": [{"name": "ramp_pbc_s1", "seed": 1, "variables": {"N": 64, "L": 8, "P": 10, '
        '"nlev": 3, "sqrt0": 0.05, "dsqrt": 0.1}}]}')
    if with_run:
        (campaign / "runs" / "ramp_pbc_s1").mkdir()
    return campaign


@pytest.mark.parametrize("name", ["ramp-levels", "ramp-pores"])
def test_ramp_question_without_its_run_folder(capsys, tmp_path, name):
    campaign = ramp_campaign(tmp_path, with_run=False)
    status, err = question(capsys, name, "--campaign", campaign, "--out", tmp_path / "out")
    assert status == 2 and "Traceback" not in err
    assert f"{campaign / 'runs' / 'ramp_pbc_s1'}: no such run folder" in err
    status, err = question(capsys, name, "--campaign", campaign, "--run", "ramp_pbc_s9",
                           "--out", tmp_path / "out")
    assert status == 2 and "no run 'ramp_pbc_s9' in" in err and "manifest.json" in err
    status, err = question(capsys, name, "--campaign", tmp_path / "nothing",
                           "--out", tmp_path / "out")
    assert status == 2 and f"{tmp_path / 'nothing' / 'manifest.json'} not found" in err


def test_ramp_levels_without_taps_names_the_file(capsys, tmp_path):
    campaign = ramp_campaign(tmp_path, with_run=True)
    status, err = question(capsys, "ramp-levels", "--campaign", campaign,
                           "--out", tmp_path / "out")
    assert status == 2 and "Traceback" not in err
    assert f"{campaign / 'runs' / 'ramp_pbc_s1' / 'taps.dat'}: no such file" in err, err


def test_list_names_every_question(capsys):
    assert cli.main(["question", "--list"]) == 0
    listed = [line.split()[0] for line in capsys.readouterr().out.splitlines()]
    assert listed == list(QUESTIONS) and len(listed) == 23


def test_help_lists_every_question(capsys):
    with pytest.raises(SystemExit) as stop:
        cli.main(["question", "--help"])
    assert stop.value.code == 0
    text = capsys.readouterr().out
    assert all(name in text for name in QUESTIONS) and "58.3 % -> 57.1 %" in text


@pytest.mark.parametrize("name", list(QUESTIONS))
def test_help_of_every_question(capsys, name):
    with pytest.raises(SystemExit) as stop:
        cli.main(["question", name, "--help"])
    assert stop.value.code == 0
    text = capsys.readouterr().out
    assert f"tapmc-paper question {name}" in text and "--out" in text
    assert f"{name}:" in text            # the question, from its module's docstring


def test_exit_status_tells_a_failed_run_from_an_unusable_input(tmp_path, capsys, monkeypatch):
    """1 when a run failed (or the campaign folder is in use), 2 for a usage error, a path that
    cannot be used or a damaged input, the convention of doc/tapmc-paper.rst (every input error
    of a question exited 1)."""
    from tapmc.campaign import CampaignDirectoryError, CampaignError
    from tapmc.paper.questions import command, launch

    def failing(error):
        class Failing:
            def __init__(self, *args, **kwargs):
                raise error
        return Failing

    for error, raised in ((CampaignError("run x failed"), common.QuestionRunError),
                          (CampaignDirectoryError("folder y: not writable"), common.QuestionError),
                          (ValueError("bad spec"), common.QuestionError)):
        monkeypatch.setattr(launch, "Campaign", failing(error))
        with pytest.raises(raised) as info:
            launch.run_all(tmp_path, [], None)
        assert type(info.value) is raised and str(error) in str(info.value)
    module = command.QUESTIONS["pbc-course"]
    from tapmc.paper import _runs

    for error, status in ((common.QuestionRunError("run x failed"), 1),
                          (_runs.PoresFailed("tapmc-pores d.dump failed (2): bad"), 1),
                          (common.QuestionError("--campaign y: no such folder"), 2)):
        def measure(args, error=error):
            raise error
        monkeypatch.setattr(module, "measure", measure)
        assert cli.main(["question", "pbc-course", "--out", str(tmp_path)]) == status
        assert capsys.readouterr().err == f"tapmc-paper question pbc-course: {error}\n"


@pytest.mark.parametrize("name", ["pbc-course", "realization-scatter"])
def test_a_campaign_of_short_runs_is_named_not_a_traceback(capsys, tmp_path, name):
    """A quick campaign's runs (100 taps) are shorter than the 1000-tap steady window these
    two questions read: they ended in a traceback of SteadyState ('last = 1000 exceeds the
    series length 100'); now one line names the run and the window, exit 2."""
    import json
    if not (RUN / "DONE.json").is_file():
        pytest.skip("campaign data absent")
    lines = (RUN / "taps.dat").read_text().splitlines()
    short = [line for line in lines if line.startswith("#")] + \
        [line for line in lines if not line.startswith("#")][:101]
    for seed in (1, 2):
        folder = tmp_path / "campaign" / "runs" / f"const_pbc_eps0.0225_s{seed}"
        folder.mkdir(parents=True)
        (folder / "taps.dat").write_text("\n".join(short) + "\n")
        done = json.loads((RUN / "DONE.json").read_text())
        done["run"]["taps"] = done["run"]["variables"]["taps"] = 100
        done["run"]["name"], done["run"]["seed"] = folder.name, seed
        (folder / "DONE.json").write_text(json.dumps(done))
    status, err = question(capsys, name, "--campaign", tmp_path / "campaign", "--out",
                           tmp_path / "out")
    assert status == 2 and err.count("\n") == 1 and "Traceback" not in err, err
    assert "100 taps, fewer than the 1000-tap steady window" in err, err
