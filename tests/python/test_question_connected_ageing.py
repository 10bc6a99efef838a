# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# tapmc-paper question connected-ageing on synthetic campaigns with a known answer: realizations
# that age simply (increments of variance ln(s / (s - 1)): C = ln(1 + t / t_W), mu = 1) and a
# control that does not (stationary increments, mu = 0), both under a drift shared by every
# realization that makes the paper's A almost all drift; the CSV, its reading back, the page's
# finding, the figure, a run resumed mid-way (taps printed twice) and a damaged run.
import json
import os
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tools", "python"))
sys.path.insert(0, os.path.dirname(__file__))

from tapmc.paper import cli, questions, validation  # noqa: E402
from tapmc.paper.questions import connected_ageing  # noqa: E402

TAPS = 1000
REALIZATIONS = 60
SETTINGS = {"N": 256, "L": 8.0, "eta": 1e-07, "eps": 0.01, "taps": TAPS, "bc": "pbc"}


def walks(step_variance, seed):
    """<Z> of every realization: a random walk with step variances ``step_variance(s)`` (s
    the tap, 1 ..) under a drift shared by all, 20 times the walks' own spread at the end."""
    rng = np.random.default_rng(seed)
    s = np.arange(1, TAPS + 1)
    steps = rng.normal(size=(REALIZATIONS, TAPS)) * np.sqrt(step_variance(s))
    z = np.concatenate([np.zeros((REALIZATIONS, 1)), np.cumsum(steps, axis=1)], axis=1)
    return 5.0 + 1e-3 * (z - 20.0 * np.log1p(np.arange(TAPS + 1)))


def simple_ageing(s):
    v = np.ones(len(s))
    v[1:] = np.log(s[1:] / (s[1:] - 1.0))
    return v


def stationary(s):
    return np.ones(len(s))


def write_campaign(root, z, resumed=None):
    """A finished ageing run per row of ``z`` (taps.dat: step Z phi_b phi_c; DONE.json with
    the run's variables); ``resumed``: the index of one whose taps 500-600 were printed twice
    (a resume from restart.500), the first print wrong."""
    for k, series in enumerate(z):
        folder = root / "runs" / f"ageing_pbc_eps0.01_s{k + 1}"
        folder.mkdir(parents=True)
        rows = [f"{t} {v:.10f} 0.55 0.58" for t, v in enumerate(series)]
        if k == resumed:   # the killed attempt's taps 500-600, then the resume's from 500
            rows = (rows[:500] + [f"{t} {series[t] + 1.0:.10f} 0.55 0.58"
                                  for t in range(500, 601)] + rows[500:])
        (folder / "taps.dat").write_text("# step Z phi_b phi_c\n" + "\n".join(rows) + "\n")
        done = {"run": {"name": folder.name, "input": "in.ageing", "variables": SETTINGS,
                        "seed": k + 1, "nprocs": 1, "taps": len(series) - 1}}
        (folder / "DONE.json").write_text(json.dumps(done))
    return root


def measured(tmp_path, step_variance, seed=3, resumed=None):
    campaign = write_campaign(tmp_path / "campaign", walks(step_variance, seed), resumed)
    out = tmp_path / "questions"
    assert cli.main(["question", "connected-ageing", "--campaign", str(campaign),
                     "--out", str(out)]) == 0
    return out, connected_ageing.results(connected_ageing.load(out / connected_ageing.CSV))


def test_simple_ageing_is_found_under_a_drift_that_is_almost_all_of_A(tmp_path, capsys):
    """Realizations that age simply: mu within its errors of 1, 0 excluded, the sentence says
    so; A is almost all drift at every t_W; the CSV's C follows ln(1 + t / t_W)."""
    out, (res,) = measured(tmp_path, simple_ageing)
    assert res.eps == 0.01 and res.settings["realizations"] == REALIZATIONS
    assert (res.settings["taps"], res.settings["N"], res.settings["eta"]) == (TAPS, 256, 1e-7)
    assert sorted(res.drift_share) == [2, 8, 25, 75, 250]   # Fig. 5's, scaled to 1000 taps
    assert min(res.drift_share.values()) > 0.9
    assert res.excluded_by(1.0) < 2.0 < res.excluded_by(0.0)
    t, c, err = res.curves["C"][25]
    expected = 1e-6 * np.log1p(t / 25)
    assert np.all(np.abs(c - expected) < 4 * err + 1e-9)
    assert set([10, 100]) <= set(t.astype(int))             # the page's table reads them
    text = connected_ageing.finding_text(connected_ageing.load(out / connected_ageing.CSV))
    assert "simple ageing (mu = 1 within" in text and "no ageing (mu = 0) excluded by" in text
    assert f"P.B.C., eps = 0.01, {REALIZATIONS} realizations of {TAPS} taps" in text
    assert (out / connected_ageing.PNG).stat().st_size > 10_000


def test_the_control_without_ageing_fails_simple_ageing(tmp_path, capsys):
    """Stationary increments: mu within its errors of 0, simple ageing excluded; the paper's
    A still separates the waiting times (the drift), the connected curves do not."""
    out, (res,) = measured(tmp_path, stationary)
    assert res.excluded_by(0.0) < 2.0 < res.excluded_by(1.0)
    text = connected_ageing.finding_text(connected_ageing.load(out / connected_ageing.CSV))
    assert "no ageing at this precision (mu = 0 within" in text
    assert "simple ageing (mu = 1) excluded by" in text
    mu, err = res.mu
    assert f"any ageing with mu above {mu + 2 * err:.2f} by 2" in text
    a_early, a_late = res.curves["A"][2][1], res.curves["A"][250][1]
    assert a_early[-1] > 3 * a_late[-1]                       # A: the drift's ln ages it
    assert res.dispersions["dispersion_unscaled"] < res.dispersions["dispersion_simple"]


def test_a_resumed_run_counts_each_tap_once_with_its_last_print(tmp_path, capsys):
    """Taps 500-600 printed twice (the first print off by 1): the answer is the one of the
    same campaign printed once."""
    z = walks(stationary, 5)
    once = write_campaign(tmp_path / "a", z)
    twice = write_campaign(tmp_path / "b", z, resumed=2)
    read_once, _ = connected_ageing.realizations(sorted((once / "runs").iterdir()))
    read_twice, _ = connected_ageing.realizations(sorted((twice / "runs").iterdir()))
    np.testing.assert_array_equal(read_once, read_twice)


def test_a_damaged_run_is_named_and_the_committed_csv_kept(tmp_path, capsys):
    campaign = write_campaign(tmp_path / "campaign", walks(stationary, 1)[:4])
    taps = campaign / "runs" / "ageing_pbc_eps0.01_s2" / "taps.dat"
    lines = taps.read_text().splitlines()
    taps.write_text("\n".join(lines[:300] + lines[400:]) + "\n")   # taps 299-398 lost
    out = tmp_path / "out"
    out.mkdir()
    (out / connected_ageing.CSV).write_text("eps,quantity\ncommitted,1\n")
    status = cli.main(["question", "connected-ageing", "--campaign", str(campaign),
                       "--out", str(out)])
    err = capsys.readouterr().err
    assert status == 2 and "Traceback" not in err and err.count("\n") == 1
    assert f"{taps}: taps missing" in err
    assert (out / connected_ageing.CSV).read_text() == "eps,quantity\ncommitted,1\n"
    assert sorted(p.name for p in out.iterdir()) == [connected_ageing.CSV]
    # runs too short for Fig. 5's waiting times, a DONE.json without variables: named
    short = write_campaign(tmp_path / "short", walks(stationary, 1)[:4, :6])
    (short / "runs" / "ageing_pbc_eps0.01_s1" / "DONE.json").write_text("{}")
    assert cli.main(["question", "connected-ageing", "--campaign", str(short), "--out",
                     str(out)]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and "eps = 0.01: a collapse needs at least 2 waiting" in err
    # a finished run whose taps.dat stops before its last tap (cut short): named, not analysed
    lines = taps.read_text().splitlines()
    taps.write_text("\n".join(lines[:200]) + "\n")
    assert cli.main(["question", "connected-ageing", "--campaign", str(campaign), "--out",
                     str(out)]) == 2
    err = capsys.readouterr().err
    assert f"{taps}: cut short: it ends at step 198, before the last tap 1000" in err, err


def test_the_page_states_the_finding_with_its_figure(tmp_path, capsys):
    """The appendix section and the main page's open question, from the CSV alone."""
    out, _ = measured(tmp_path, simple_ageing)
    section = "\n".join(questions.render_section(out))
    assert "Ageing with the drift removed (connected-ageing)" in section
    assert "     - C(t = 100)" in section and "``connected-ageing``" in section
    # the report's figures sit beside the questions' folder (here: ``out``)
    assert out.name == questions.FOLDER
    files = {"fig5": (str(tmp_path / "fig5.png"), str(tmp_path / "fig5.csv"))}
    text, (png, alt) = validation._connected_ageing_finding(files)
    assert text.startswith("Ageing as ageing (section III.C, Fig. 5; N = 256, L = 8R")
    assert text.endswith("(``tapmc-paper question connected-ageing``).")
    assert png == str(Path("validation") / "questions" / connected_ageing.PNG)
    (out / connected_ageing.PNG).unlink()
    assert isinstance(validation._connected_ageing_finding(files), str)
