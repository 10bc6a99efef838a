# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc-paper question alpha-window (issue 46, item 5): alpha of Fig. 6's bell in a window
5-18R below the packing's loose top, on synthetic profiles of a known gradient with a loose
top above 18R, its CSV, its page section, and the register's reading rows of gradient-bell
on fake data: a bell in the narrow window agrees, a rise disagrees (the control)."""

import os
import sys
from pathlib import Path

import numpy as np
import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from claims_fakes import BELL, BY_ID, X, Table, fig4, report  # noqa: E402
from tapmc.paper import claims, cli, questions  # noqa: E402
from tapmc.paper.questions import alpha_window  # noqa: E402

#: the synthetic packing: sphere radius (the inputs' default), its known gradient alpha in
#: the bulk, where its loose top starts and how steeply Phi falls there (per R)
RADIUS, ALPHA, PHI0, TOP_START, TOP_FALL = 0.5, 0.002, 0.62, 19.0, 0.06
#: the packing's height (z/R where Phi reaches 0): Fig. 6's window ends at 22/28 of it
HEIGHT = TOP_START + (PHI0 - ALPHA * TOP_START) / (ALPHA + TOP_FALL)
ZB = np.arange(0.1, 40.0, 0.2)          # bins of R/5, as compute stereo/profile


def profile(zb=ZB, alpha=ALPHA, top=TOP_START):
    """Phi0 - alpha z/R in the bulk, falling TOP_FALL per R faster from ``top`` up."""
    phi = PHI0 - alpha * zb - TOP_FALL * np.clip(zb - top, 0.0, None)
    return np.clip(phi, 0.0, None)


def write_run(root, eps, seed, alpha=ALPHA, with_profile=True):
    """A finished P.B.C. constant-eps run (DONE.json without variables: R = 0.5) whose
    profile_z.dat has :func:`profile` at t = 0 and after its 20 taps; no dump, so alpha's
    error is the straight line's own."""
    folder = root / "runs" / f"const_pbc_eps{eps:g}_s{seed}"
    folder.mkdir(parents=True)
    rows = ["# step phi_b phi_c Z z_top lateral central h_s sweeps accept capped"]
    rows += [f"{t} 0.55 0.58 5.0 14.0 0.56 0.57 {HEIGHT * RADIUS:.6f} 100 0.1 0"
             for t in range(21)]
    (folder / "taps.dat").write_text("\n".join(rows) + "\n")
    if with_profile:
        text = ["# Time-averaged data for fix zprof", "# TimeStep Number-of-rows",
                "# Row c_phi[1] c_phi[2] c_phi[3]"]
        phi = profile(alpha=alpha)
        for step in (0, 20):
            text.append(f"{step} {len(ZB)}")
            text += [f"{i + 1} {z * RADIUS:.4f} {p:.8f} {p:.8f}"
                     for i, (z, p) in enumerate(zip(ZB, phi))]
        (folder / "profile_z.dat").write_text("\n".join(text) + "\n")
    (folder / "DONE.json").write_text("{}")
    return folder


def test_loose_top_and_the_upper_departure_of_a_known_profile():
    """The straight line of 5-18R extrapolated: the first 2R block that falls 0.02 below it
    starts at 19R; Fig. 6's window top, 22.8R, holds the loose top's fall (negative); a fall
    from 15R is found inside the window itself (the window reaches the top); a profile
    without a top has none."""
    assert alpha_window.loose_top(ZB, profile()) == pytest.approx(TOP_START)
    default_top = 22.0 / 28.0 * HEIGHT
    assert 22.0 < default_top < 23.5
    departure = alpha_window.upper_departure(ZB, profile(), (5.0, default_top))
    # the 5-18R line is the bulk's own: the departure is the loose top's fall, -TOP_FALL
    # (z - 19) above 19R, averaged over the bins 18 < z/R <= 22.8 (about -0.08)
    upper = ZB[(ZB > 18.0) & (ZB <= default_top)]
    expected = float(np.mean(-TOP_FALL * np.clip(upper - TOP_START, 0.0, None)))
    assert expected < -0.05 and departure == pytest.approx(expected, abs=1e-6)
    assert alpha_window.loose_top(ZB, profile(top=15.0)) <= 15.0
    assert alpha_window.loose_top(ZB, PHI0 - ALPHA * ZB) is None


def test_alpha_window_recovers_the_gradient_below_the_loose_top(tmp_path, capsys):
    """Two eps (one of two seeds): in 5-18R every run's alpha is the profile's known
    gradient; Fig. 6's window (cut at 22/28 of the height) reaches the loose top and
    steepens it (the control: the default window does not recover it); the CSV reads back
    as written and the page's table averages the seeds."""
    for eps, seed, alpha in ((0.01, 1, ALPHA), (0.01, 2, ALPHA), (0.04, 1, 2 * ALPHA)):
        write_run(tmp_path / "campaign", eps, seed, alpha)
    out = tmp_path / "questions"
    assert cli.main(["question", "alpha-window", "--campaign", str(tmp_path / "campaign"),
                     "--out", str(out)]) == 0
    rows = alpha_window.load(out / alpha_window.CSV)
    assert list(rows[0]) == alpha_window.HEADER
    assert [(r["eps"], r["seed"]) for r in rows] == [("0.01", "1"), ("0.01", "2"),
                                                      ("0.04", "1")]
    for r, alpha in zip(rows, (ALPHA, ALPHA, 2 * ALPHA)):
        assert (r["bc"], r["window_lo"], r["window_hi"]) == ("pbc", "5", "18")
        assert float(r["alpha"]) == pytest.approx(alpha, rel=1e-4)
        assert float(r["alpha_err"]) < 1e-5                     # an exact straight line
        assert float(r["default_window_hi"]) == pytest.approx(22.0 / 28.0 * HEIGHT, rel=1e-4)
        assert float(r["alpha_default"]) > alpha + 0.002        # the loose top steepens it
        assert float(r["loose_top"]) == pytest.approx(TOP_START)
        assert float(r["sqrt_eps"]) == pytest.approx(np.sqrt(float(r["eps"])))
    # the round trip: saved again from what was read, the same file
    again = tmp_path / "again.csv"
    alpha_window.save(again, [[r[k] for k in alpha_window.HEADER] for r in rows])
    assert alpha_window.load(again) == rows
    text = "\n".join(questions.render_section(out))
    assert "alpha in a window below the loose top (alpha-window)" in text
    assert "``alpha-window``" in text
    assert "   * - 0.1\n     - 2\n     - 0.002 ± 0" in text
    assert "from 19R at the lowest, 19R at the highest (3 of 3 runs)" in text
    assert "agrees" not in text and "disagrees" not in text     # no verdict of its own


def test_a_run_without_its_profile_is_named_and_keeps_the_committed_csv(tmp_path, capsys):
    write_run(tmp_path / "campaign", 0.01, 1)
    folder = write_run(tmp_path / "campaign", 0.04, 1, with_profile=False)
    out = tmp_path / "out"
    out.mkdir()
    (out / alpha_window.CSV).write_text("run,eps\ncommitted,0.05\n")
    status = cli.main(["question", "alpha-window", "--campaign", str(tmp_path / "campaign"),
                       "--out", str(out)])
    err = capsys.readouterr().err
    assert status == 2 and "Traceback" not in err and err.count("\n") == 1
    assert f"{folder / 'profile_z.dat'}: no such file" in err
    assert (out / alpha_window.CSV).read_text() == "run,eps\ncommitted,0.05\n"
    assert sorted(p.name for p in out.iterdir()) == [alpha_window.CSV]


def window_rows(alphas, err=0.0002, two_seeds_at=None):
    """alpha_window.csv rows of one seed per sqrt(eps) of X with the narrow window's alphas
    ``alphas``; at index ``two_seeds_at`` two seeds, +-err/2 about the value."""
    rows = []
    for k, (x, a) in enumerate(zip(X, alphas)):
        seeds = [a] if k != two_seeds_at else [a - err / 2, a + err / 2]
        for seed, value in enumerate(seeds, 1):
            rows.append({"run": f"const_pbc_eps{x * x:g}_s{seed}", "bc": "pbc",
                         "eps": f"{x * x:.10g}", "sqrt_eps": f"{x:g}", "seed": str(seed),
                         "window_lo": "5", "window_hi": "18", "alpha": f"{value:.10g}",
                         "alpha_err": f"{err:g}", "default_window_hi": "22.8",
                         "alpha_default": f"{0.001 + 0.01 * x:.10g}",
                         "alpha_default_err": f"{err:g}", "loose_top": "27",
                         "upper_departure": "0.01"})
    return rows


def bell_report(rows):
    """Fig. 6's bell rising (the default window's alphas), Fig. 4's steady bell, and the
    question's ``rows``."""
    base = report(fig6=Table().add("b", "bell:alpha", X, 0.001 + 0.01 * X, 0.0002),
                  fig4=fig4(BELL))
    return claims.ReportData(base.summary, base.written, questions={"alpha_window": rows})


def test_register_reading_rows_agree_for_a_bell_and_disagree_for_a_rise():
    """gradient-bell keeps its rows and their numbers, and adds the same two readings in the
    narrow window: a bell there (one eps of two seeds, averaged as Fig. 6 does) agrees with
    both; a monotonic rise there disagrees (the control that must fail)."""
    claim = BY_ID["gradient-bell"]
    alone = claims.alpha_bell(bell_report([]), claim)
    bell = claims.alpha_bell(bell_report(window_rows(0.004 - 0.1 * (X - 0.15) ** 2,
                                                     two_seeds_at=4)), claim)
    assert [m.label for m in alone] == ["about its own largest value",
                                        claims.ALPHA_ABOVE_STEADY]
    assert [m.text() for m in bell[:2]] == [m.text() for m in alone]
    assert [str(claims.verdict(claim, m)) for m in bell[:2]] == \
        [str(claims.verdict(claim, m)) for m in alone]
    reading = bell[2:]
    assert [m.label for m in reading] == [
        "window 5-18R (reading): about its own largest value",
        f"window 5-18R (reading): {claims.ALPHA_ABOVE_STEADY}"]
    assert [str(claims.verdict(claim, m)) for m in reading] == ["agrees", "agrees"]
    rise = claims.alpha_bell(bell_report(window_rows(0.001 + 0.01 * X)), claim)[2:]
    assert rise[0].undecided.startswith("fewer than three alphas above the largest")
    assert str(claims.verdict(claim, rise[1])) == "disagrees"
    few = claims.alpha_bell(bell_report(window_rows((0.001, 0.002))), claim)[2:]
    assert len(few) == 1 and few[0].undecided.startswith("alpha of 2 eps")


def test_reading_rows_average_seeds_as_fig6_does():
    """Two seeds at one eps: the point is their mean, its error their sem (the report has no
    groups of realizations to floor it with), as Fig. 6's bell:alpha; with groups, Fig. 6's
    calibration."""
    rows = window_rows(0.004 - 0.1 * (X - 0.15) ** 2, err=0.0002, two_seeds_at=4)
    data = bell_report(rows)
    seeds = claims.bell.alpha_window_seeds(rows)
    assert len(seeds) == len(X) and len(seeds[float(rows[4]["eps"])]) == 2
    errors = claims.bell._calibrated_alpha_errors(data, seeds)
    assert errors[4] == pytest.approx(0.0001)      # the sem of a -+ 0.0001
    assert np.allclose(np.delete(errors, 4), 0.0002)
    # with groups of realizations: one seed's jackknife times their factor, a mean of
    # seeds no more precise than their realization error of such a mean (Fig. 6's rules)
    data.run_error = lambda quantity, bc: (2.0, 10)
    data.realization_floor = lambda quantity, errors, bc: 0.0005
    errors = claims.bell._calibrated_alpha_errors(data, seeds)
    assert errors[4] == pytest.approx(0.0005)
    assert np.allclose(np.delete(errors, 4), 0.0004)
