# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.paper.paper_ramp: the paper-protocol ramps judged from their taps.dat (a frozen
descending branch, a compacting one, a run still going up), the CSV round trip and the finding
of the report's first screen."""
import os
import shutil
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from tapmc.hysteresis import BranchStatistic
from tapmc.paper import paper_ramp, paper_ramp_figure, validation
from tapmc.paper.scales import QUICK

SOURCE = Path(__file__).resolve().parents[2]

LEVELS = [0.025, 0.05, 0.075, 0.1, 0.125, 0.1, 0.075, 0.05, 0.025]


def write_run(campaign, name, phi_of_level, levels=LEVELS, taps_per_level=4000, seed=1,
              done=False, repeat_from=None, noise=1e-3, window_offset=None):
    """A synthetic ramp: <Phi^c> = phi_of_level[k] + white noise (sigma ``noise``) in level
    k, plus ``window_offset(k, w)`` in its 1000-tap window w (0-3) when given; a resumed run
    (repeat_from) writes the taps after that step twice, the first copy wrong."""
    rng = np.random.default_rng(seed)
    offsets = {} if window_offset is None else {
        (k, w): window_offset(k, w) for k in range(len(levels)) for w in range(4)}
    run = campaign / "runs" / name
    run.mkdir(parents=True)
    rows = ["# step level branch sqrt_eps phi_b phi_c Z", "0 -1 0 0.0 0.5 0.58 7.3"]
    for k, (sq, phi) in enumerate(zip(levels, phi_of_level)):
        for t in range(taps_per_level):
            step = k * taps_per_level + t + 1
            value = phi + offsets.get((k, t // 1000), 0.0) + noise * rng.standard_normal()
            if repeat_from is not None and step > repeat_from and k == len(levels) - 1:
                rows.append(f"{step} {k} 0 {sq} 0.5 {value + 0.01:.8f} 7.0")
            rows.append(f"{step} {k} 0 {sq} 0.5 {value:.8f} 7.0")
    (run / "taps.dat").write_text("\n".join(rows) + "\n")
    if done:
        (run / "DONE.json").write_text("{}\n")
    return run


def test_frozen_compacting_and_running_ramps(tmp_path):
    up = [0.590, 0.595, 0.598, 0.600, 0.600]
    write_run(tmp_path, "paperramp0.125_pbc_s1", up + [0.600] * 4, done=True)
    write_run(tmp_path, "paperramp0.125_pbc_eta1e-05_s1",
              up + [0.601, 0.602, 0.603, 0.604], seed=2, repeat_from=34000)
    write_run(tmp_path, "paperramp0.125_pbc_eta1e-06_s2", up[:3], levels=LEVELS[:3], seed=3)
    # a run just started: fewer taps than one level (no level mean yet) is running, no error
    write_run(tmp_path, "paperramp0.125_pbc_s2", up[:1], levels=LEVELS[:1], taps_per_level=161)
    rows = {r.run: r for r in paper_ramp.analyse(tmp_path, 1e-7)}
    frozen = rows["paperramp0.125_pbc_s1"]
    assert frozen.verdict == "frozen" and frozen.eta == 1e-7 and frozen.finished
    assert abs(frozen.down_change) < 3 * frozen.down_change_sem
    compacting = rows["paperramp0.125_pbc_eta1e-05_s1"]
    assert compacting.verdict == "compacts" and compacting.eta == 1e-5
    assert compacting.down_change == pytest.approx(0.0025, abs=2e-4)
    assert compacting.down_rise == pytest.approx(0.003, abs=2e-4)  # the repeated taps count once
    assert compacting.taps_done == 36000
    running = rows["paperramp0.125_pbc_eta1e-06_s2"]
    assert running.verdict == "running" and running.taps_done == 12000
    started = rows["paperramp0.125_pbc_s2"]
    assert started.verdict == "running" and started.taps_done == 161 and started.down_levels == 0

    # the CSV keeps every field, and the finding names each eta's verdict
    back = paper_ramp.read_csv(paper_ramp.write_csv(list(rows.values()), tmp_path / "p.csv"))
    assert [r.run for r in back] == list(rows)
    assert back[0] == list(rows.values())[0]
    text = paper_ramp.finding_text(back, 1e-7, source=" Per run: here.")
    assert "At eta = 1e-7 (the default), the model has an irreversible (frozen) branch" in text
    # a sentence closed by where the numbers are, then one nested list item per eta
    intro, blank, *items = text.split("\n")
    assert intro.endswith("answered per redeposition threshold eta. Per run: here.")
    assert blank == "" and [i[:12] for i in items] == ["  - At eta ="] * 3
    # a seed still on its way is named beside the decided one, not counted
    assert "; not counted yet: seed 2 at tap 161, still going up." in text
    assert "At eta = 1e-5, the model has no irreversible branch: the descending branch compacts" in text
    progress = paper_ramp.progress_text(2, 12000, running.down_levels)
    assert f"At eta = 1e-6 the ramp has not come down two levels yet ({progress}): undecided." \
        in text
    assert paper_ramp.progress_text(1, 23737, 1) == \
        "seed 1 at tap 23737, 1 descending level of the 2 needed"
    # past the turn (tap 20000 for 0.125) without a whole descending level: not "going up"
    past = tmp_path / "past"
    run = write_run(past, "paperramp0.125_pbc_s4", up + [0.601], levels=LEVELS[:6], seed=4)
    taps = (run / "taps.dat").read_text().splitlines()
    (run / "taps.dat").write_text("\n".join(taps[:2 + 21000]) + "\n")   # 1000 taps down
    (turning,) = paper_ramp.analyse(past, 1e-7)
    assert turning.verdict == "running" and paper_ramp.turned(turning)
    assert "seed 4 at tap 21000, on its first descending level" in \
        paper_ramp.finding_text([turning], 1e-7)
    assert not paper_ramp.turned(rows["paperramp0.125_pbc_eta1e-06_s2"])

    # the first screen's sentence: one answer per eta, the decided seeds' changes, how far the
    # running ones got
    headline = paper_ramp.headline_text(back, 1e-7)
    assert "eta = 1e-5: no irreversible branch (1 seed; the descending levels lie +0.00" \
        in headline
    assert ("eta = 1e-6: undecided, the ramp has not come down two levels yet (seed 2 at tap "
            "12000, ") in headline
    assert "seed 2 at tap 161, still going up" in paper_ramp.finding_text(
        [started], 1e-7)
    assert "eta = 1e-7 (the default): an irreversible (frozen) branch (1 seed;" in headline
    assert paper_ramp.headline_text([], 1e-7) == ""


def test_a_ramp_beyond_the_critical_level_is_told_apart(tmp_path):
    """A ramp turning at 0.2 (beyond (sqrt eps)* = 0.15) comes down the reversible branch: it
    is no evidence about the branch below, so the headline's answer counts only the ramp
    turning at 0.125 (frozen here), and the headline's last bullet and the finding name the
    one beyond after it, for comparison; the first increase's
    whole levels (all 4000 taps) are kept for the claims, the level still running is not."""
    up = [0.590, 0.595, 0.598, 0.600, 0.600]
    write_run(tmp_path, "paperramp0.125_pbc_s1", up + [0.600] * 4, done=True)
    high = [0.025 * k for k in range(1, 9)]
    write_run(tmp_path, "paperramp0.2_pbc_s2", [0.59 + 0.001 * k for k in range(8)]
              + [0.61, 0.612], levels=high + [0.175, 0.15], seed=2)
    rows = {r.run: r for r in paper_ramp.analyse(tmp_path, 1e-7)}
    beyond = rows["paperramp0.2_pbc_s2"]
    assert beyond.verdict == "compacts" and beyond.top == 0.2
    x, mean, _ = beyond.branch("up1")
    np.testing.assert_allclose(x, high)
    np.testing.assert_allclose(mean, [0.59 + 0.001 * k for k in range(8)], atol=2e-4)
    np.testing.assert_allclose(beyond.branch("down")[0], [0.175, 0.15])
    assert len(beyond.branch("up2")[0]) == 0
    headline = paper_ramp.headline_text(list(rows.values()), 1e-7)
    assert "eta = 1e-7 (the default): an irreversible (frozen) branch (1 seed;" in headline
    lines = headline.split("\n")
    assert lines[0].endswith("an irreversible (frozen) branch at the redeposition threshold "
                             "eta measured.") and len(lines) == 4
    assert "0.2" not in "\n".join(lines[:3])
    assert lines[3] == ("- For comparison, beyond (sqrt eps)* (the branch the paper calls "
                        "reversible): at eta = 1e-7 (the default), turning at 0.2 (1 seed): the "
                        f"descending levels lie {beyond.down_change:+.4f} in <Phi^c> from the "
                        "turning level on average (the descent's move).")
    finding = paper_ramp.finding_text(list(rows.values()), 1e-7)
    assert "Beyond (sqrt eps)* (the reversible branch of the paper), the descending branch " \
        "from the turning level: at eta = 1e-7 (the default), seed 2, turning at 0.2: +0.0" \
        in finding and finding.endswith("(compacts).")
    assert finding.split("\n")[-1].startswith("  - Beyond (sqrt eps)*")
    assert "then beyond (sqrt eps)*." in finding.split("\n")[0]
    alone = paper_ramp.finding_text([beyond], 1e-7)
    assert alone.startswith("Beyond (sqrt eps)*") and "Section III.B" not in alone
    assert "second increase" not in alone   # not going up again yet
    # back up again: the second increase against the descent, the paper's test of its branch
    write_run(tmp_path, "paperramp0.2_pbc_s3", [0.59 + 0.001 * k for k in range(8)]
              + [0.61, 0.612, 0.612], levels=high + [0.175, 0.15, 0.175], seed=3)
    again = paper_ramp.analyse_run(tmp_path / "runs" / "paperramp0.2_pbc_s3", 1e-7)
    text = paper_ramp.finding_text([again], 1e-7)
    assert ", second increase minus descent +0.0020 +- 0.0000 over 1 level (above)" in text
    assert paper_ramp.headline_text([beyond], 1e-7) == ""
    compared = paper_ramp.headline_text([rows["paperramp0.125_pbc_s1"], again], 1e-7)
    assert compared.split("\n")[-1].endswith(
        "the second increase minus the descent: +0.0020 (mean of 1 level; "
        f"{100 * 0.002 / again.down_change:.0f} % of the descent's move), it lies above the "
        "descent: still compacting.")
    # a ramp beyond still going up: nothing to compare yet
    write_run(tmp_path, "paperramp0.2_pbc_s4", [0.59, 0.591, 0.592], levels=high[:3], seed=4)
    running = paper_ramp.analyse_run(tmp_path / "runs" / "paperramp0.2_pbc_s4", 1e-7)
    assert running.verdict == "running"
    assert len(paper_ramp.headline_text([rows["paperramp0.125_pbc_s1"], running],
                                        1e-7).split("\n")) == 3
    # a run in its first increase: the level in progress is not a whole level
    run = write_run(tmp_path, "paperramp0.125_pbc_s3", up[:3], levels=LEVELS[:3], seed=3)
    taps = (run / "taps.dat").read_text().splitlines()
    (run / "taps.dat").write_text("\n".join(taps[:2 + 9000]) + "\n")   # 1000 taps into 0.075
    going = paper_ramp.analyse_run(run, 1e-7)
    assert going.verdict == "running" and going.taps_done == 9000
    np.testing.assert_allclose(going.branch("up1")[0], [0.025, 0.05])
    # the whole levels survive the CSV
    back = paper_ramp.read_csv(paper_ramp.write_csv([going, beyond], tmp_path / "p.csv"))
    assert list(map(repr, back)) == list(map(repr, [going, beyond]))   # nan != nan


def test_a_level_in_progress_is_not_a_level_yet(tmp_path):
    """The paper's level is the mean of the last 1000 of its 4000 taps: a descending level
    2000 taps in (here far above the others) is neither counted nor averaged until it ends."""
    up = [0.590, 0.595, 0.598, 0.600, 0.600]
    run = write_run(tmp_path, "paperramp0.125_pbc_s1", up + [0.601, 0.601, 0.640])
    taps = (run / "taps.dat").read_text().splitlines()
    (run / "taps.dat").write_text("\n".join(taps[:2 + 7 * 4000 + 2000]) + "\n")
    r = paper_ramp.analyse_run(run, 1e-7)
    assert r.taps_done == 30000 and r.down_levels == 2 and r.down_last == 0.075
    assert r.down_change == pytest.approx(0.001, abs=1e-4) and r.verdict == "compacts"
    np.testing.assert_allclose(r.branch("down")[0], [0.1, 0.075])


def test_seeds_that_disagree_are_said_to_disagree(tmp_path):
    up = [0.590, 0.595, 0.598, 0.600, 0.600]
    write_run(tmp_path, "paperramp0.125_pbc_s1", up + [0.600] * 4, done=True)
    write_run(tmp_path, "paperramp0.125_pbc_s2", up + [0.601, 0.602, 0.603, 0.604], seed=2,
              done=True)
    headline = paper_ramp.headline_text(paper_ramp.analyse(tmp_path, 1e-7), 1e-7)
    assert "eta = 1e-7 (the default): the seeds disagree (2 seeds;" in headline


def test_a_directory_that_is_not_a_paper_ramp_is_refused(tmp_path):
    run = write_run(tmp_path, "ramp_pbc_s1", [0.6] * 9)
    with pytest.raises(ValueError, match="ramp_pbc_s1"):
        paper_ramp.analyse_run(run, 1e-7)
    assert paper_ramp.analyse(tmp_path, 1e-7) == []


LOOP = LEVELS + [0.05, 0.075, 0.1, 0.125]


def test_back_at_the_turning_level_the_loop_splits_into_given_back_and_kept(tmp_path):
    """A ramp that goes up again: back at the turning level, what the packing gives back of the
    descent's compaction (a reversible response) and what the loop keeps, with a known answer;
    controls: a frozen second increase gives back nothing, and one not yet back at the top
    says nothing."""
    up, down = [0.590, 0.595, 0.598, 0.600, 0.600], [0.601, 0.602, 0.603, 0.604]
    write_run(tmp_path, "paperramp0.125_pbc_s1", up + down + [0.6035, 0.603, 0.6025, 0.602],
              levels=LOOP)
    write_run(tmp_path, "paperramp0.125_pbc_s2", up + down + [0.604] * 4, levels=LOOP, seed=2)
    write_run(tmp_path, "paperramp0.125_pbc_s3", up + down + [0.6035, 0.603], levels=LOOP[:11],
              seed=3)
    rows = {r.run: r for r in paper_ramp.analyse(tmp_path, 1e-7)}
    loosens = rows["paperramp0.125_pbc_s1"].return_to_top()
    assert loosens.sqrt_eps == 0.125 and loosens.verdict == "loosens"
    assert loosens.given_back.value == pytest.approx(-0.002, abs=2e-4)
    assert loosens.kept.value == pytest.approx(0.002, abs=2e-4)
    assert 0 < loosens.given_back.sem < 1e-4   # two level means of 1000 taps, sigma 1e-3
    frozen = rows["paperramp0.125_pbc_s2"].return_to_top()
    assert frozen.verdict == "frozen" and frozen.kept.value == pytest.approx(0.004, abs=2e-4)
    assert rows["paperramp0.125_pbc_s3"].return_to_top() is None

    one = [rows["paperramp0.125_pbc_s1"], rows["paperramp0.125_pbc_s3"]]
    text = paper_ramp.finding_text(one, 1e-7)
    assert ("Back up at the turning level (1 of 2 seeds), it loosens as the taps grow again (a "
            "frozen branch would not) (seed 1: of the +0.0040 gained from the turning level "
            "down to the bottom of the loop it gives back -0.0020 +- 0.0000 and keeps +0.0020 "
            "+- 0.0000 over its first visit, on the first increase).") in text
    both = paper_ramp.finding_text([rows["paperramp0.125_pbc_s1"],
                                    rows["paperramp0.125_pbc_s2"]], 1e-7)
    assert ("Back up at the turning level (2 of 2 seeds), the seeds disagree beyond their "
            "errors (seed 1 loosens, seed 2 stays (frozen); chi2 = ") in both
    assert "p < 1e-4): one answer per seed (seed 1:" in both
    alone = paper_ramp.finding_text([rows["paperramp0.125_pbc_s2"]], 1e-7)
    assert "it stays where the descent left it (frozen) (seed 2:" in alone
    # a ramp still on its way up again adds nothing to the sentence
    assert "Back up" not in paper_ramp.finding_text([rows["paperramp0.125_pbc_s3"]], 1e-7)


def test_the_second_increase_against_the_descent_is_the_papers_test_of_reversibility(tmp_path):
    """The second increase against the descent at the sqrt(eps) both visited, with known
    answers: one that comes across the same values (reversible), one that lies 0.002 above
    them (still compacting); controls: one level of the second increase compares that level
    only, and a ramp not yet going up again has no answer."""
    up, down = [0.590, 0.595, 0.598, 0.600, 0.600], [0.601, 0.602, 0.603, 0.604]
    back = [0.603, 0.602, 0.601, 0.6005]  # the descent's values at 0.05, 0.075, 0.1, then 0.125
    write_run(tmp_path, "paperramp0.125_pbc_s1", up + down + back, levels=LOOP)
    write_run(tmp_path, "paperramp0.125_pbc_s2", up + down + [v + 0.002 for v in back],
              levels=LOOP, seed=2)
    write_run(tmp_path, "paperramp0.125_pbc_s3", up + down + back[:1], levels=LOOP[:10],
              seed=3)
    write_run(tmp_path, "paperramp0.125_pbc_s4", up + down, seed=4)
    rows = {r.run: r for r in paper_ramp.analyse(tmp_path, 1e-7)}
    same = rows["paperramp0.125_pbc_s1"].retrace()
    assert same.verdict == "retraces" and same.levels == (0.05, 0.075, 0.1)
    assert same.differences == pytest.approx((0.0, 0.0, 0.0), abs=2e-4)
    assert all(0 < e < 1e-4 for e in same.sems) and same.mean.n == 3
    above = rows["paperramp0.125_pbc_s2"].retrace()
    assert above.verdict == "above" and above.mean.value == pytest.approx(0.002, abs=2e-4)
    assert above.differences == pytest.approx((0.002,) * 3, abs=2e-4)
    first = rows["paperramp0.125_pbc_s3"].retrace()
    assert first.levels == (0.05,) and first.mean.n == 1 and first.verdict == "retraces"
    assert rows["paperramp0.125_pbc_s4"].retrace() is None

    text = paper_ramp.finding_text([rows["paperramp0.125_pbc_s1"]], 1e-7)
    levels = ", ".join(f"{paper_ramp._signed(d)} +- 0.0000 at {x:g}"
                       for x, d in zip(same.levels, same.differences))
    assert ("The second increase against the descent at the sqrt(eps) both visited (1 of 1 "
            "seed; the paper's test of its reversible branch, 'we approximately come across the "
            "same values'): it comes across the same values within its errors (how close: the "
            "register's reversible-retraced row) (second increase minus "
            f"descent, seed 1: {levels}; mean {paper_ramp._signed(same.mean.value)} +- "
            "0.0000).") in text
    headline = paper_ramp.headline_text([rows["paperramp0.125_pbc_s2"]], 1e-7)
    share = 100 * above.mean.value / rows["paperramp0.125_pbc_s2"].down_change
    assert (f"; the second increase minus the descent: +0.0020 (mean of 3 levels; {share:.0f} % "
            "of the descent's move), it lies above the descent: still compacting)") in headline
    both = paper_ramp.headline_text([rows["paperramp0.125_pbc_s1"],
                                     rows["paperramp0.125_pbc_s2"]], 1e-7)
    assert "+0.0000 and +0.0020 (mean of 3 levels;" in both
    assert ("the seeds disagree beyond their errors (seed 1 lies on the descent, seed 2 lies "
            "above; chi2 = ") in both and "p < 1e-4): one answer per seed)" in both
    # seeds that reached different numbers of levels: the counts follow the seeds' order
    uneven = paper_ramp.headline_text([rows["paperramp0.125_pbc_s2"],
                                       rows["paperramp0.125_pbc_s3"]], 1e-7)
    assert f"+0.0020 and {paper_ramp._signed(first.mean.value)} (mean of 3 and 1 levels;" \
        in uneven
    assert "the second increase" not in paper_ramp.headline_text(
        [rows["paperramp0.125_pbc_s4"]], 1e-7)


def test_the_figure_draws_every_whole_level_one_panel_per_eta(tmp_path):
    """paper_ramp.png: a panel per eta (the default first, then the loosest), per run a line
    through its whole levels in the ramp's order and a marker series per branch; shared
    <Phi^c> range; the settings on top; too few axes refused."""
    up, down = [0.590, 0.595, 0.598, 0.600, 0.600], [0.601, 0.602, 0.603, 0.604]
    write_run(tmp_path, "paperramp0.125_pbc_s1", up + down + [0.6035, 0.603], levels=LOOP[:11])
    write_run(tmp_path, "paperramp0.125_pbc_eta1e-05_s2", up + [0.61] * 4, seed=2)
    write_run(tmp_path, "paperramp0.125_pbc_eta1e-06_s3", up[:3], levels=LEVELS[:3], seed=3)
    # a run just started (no whole level yet) draws nothing and breaks nothing
    write_run(tmp_path, "paperramp0.2_pbc_s1", up[:1], levels=LEVELS[:1], taps_per_level=161)
    rows = paper_ramp.analyse(tmp_path, 1e-7)
    started = next(r for r in rows if r.top == 0.2)
    assert [len(v) for v in started.branch("up1")] == [0, 0, 0]
    axes = paper_ramp_figure.plot(rows, 1e-7)
    assert [ax.get_title() for ax in axes] == ["eta = 1e-7 (the default)", "eta = 1e-5",
                                               "eta = 1e-6"]
    loop = axes[0].get_lines()[0]
    assert list(loop.get_xdata()) == LOOP[:11]     # the whole loop, in the ramp's order
    labels = axes[0].get_legend_handles_labels()[1]
    assert labels == ["$(\\varepsilon^{1/2})^* = 0.15$", "seed 1, to 0.125: increase",
                      "seed 1, to 0.125: decrease", "seed 1, to 0.125: increase again"]
    assert axes[2].get_legend_handles_labels()[1][1:] == ["seed 3, to 0.125: increase"]
    assert axes[0].get_ylim() == axes[1].get_ylim() and axes[1].get_ylim()[1] > 0.61
    with pytest.raises(ValueError, match="axes: 1 given, the rows have 3 etas"):
        paper_ramp_figure.plot(rows, 1e-7, axes[:1])
    png = paper_ramp_figure.write_figure(rows, 1e-7, tmp_path / "out" / paper_ramp.PNG_NAME)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "4000 taps per level" in paper_ramp_figure.settings_line(rows)
    assert paper_ramp_figure.settings_line(rows).endswith("seeds 1, 2, 3; campaign: full preset")
    assert "stop change" in paper_ramp_figure.settings_line(rows)
    assert "error bars their batch-means errors;" in paper_ramp_figure.settings_line(rows)
    assert "error bars their batch-means errors x 2.1 (the realizations' spread);" in \
        paper_ramp_figure.settings_line(rows, 2.1)
    # a campaign of another scale (tier 7 keeps its N, box and ramp grid): the figure states it
    small = QUICK.replace(ramp_sqrt0=0.025, ramp_dsqrt=0.025)
    stated = paper_ramp_figure.settings_line(rows, scale=small)
    assert stated.startswith(f"N = {QUICK.N}, box {QUICK.L:g}R x {QUICK.L:g}R, P.B.C.")
    assert "steps of 0.025 in sqrt(eps)" in stated and stated.endswith("campaign: scale quick")
    wide = paper_ramp_figure.plot(paper_ramp.calibrated(rows, 3.0), 1e-7)
    seg = lambda c: np.ptp(c.lines[2][0].get_segments()[0][:, 1])   # noqa: E731
    first = lambda axs: next(c for c in axs[0].containers if c.has_yerr)   # noqa: E731
    assert seg(first(wide)) == pytest.approx(3 * seg(first(axes)))
    png = paper_ramp_figure.write_figure(rows, 1e-7, tmp_path / "out" / "b.png", 2.1)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # beside it, every number it draws, the error bars as drawn (x 2.1)
    from tapmc.paper._plotting import figure_csv_path, figure_csv_rows
    csv_rows = figure_csv_rows(figure_csv_path(png))
    run = next(r for r in rows if r.seed == 1 and r.eta == 1e-7)
    x, mean, sem = run.branch("up1")
    drawn = [r for r in csv_rows if r[1:3] == ("eta = 1e-7 (the default)",
                                               "seed 1, to 0.125: increase")]
    assert [r[3] for r in drawn] == pytest.approx(list(x))
    assert [r[4] for r in drawn] == pytest.approx(list(mean))
    assert [r[5] for r in drawn] == pytest.approx([2.1 * s for s in sem])


def test_verdicts_take_the_realizations_error_when_given_its_factor(tmp_path):
    """calibrated(): every error times the realizations' factor and the descent's verdict
    decided again: a second increase 3 of its own errors above the descent lies above it with
    the run's errors and retraces it at a factor of 2; a factor below 1 is refused."""
    up, down = [0.590, 0.595, 0.598, 0.600, 0.600], [0.601, 0.602, 0.603, 0.604]
    write_run(tmp_path, "paperramp0.125_pbc_s1", up + down + [0.603, 0.602, 0.601, 0.6005],
              levels=LOOP)
    raw = paper_ramp.analyse(tmp_path, 1e-7)[0]
    trace = raw.retrace()
    # shift the second increase by 3 of its mean's errors: above with the run's own errors
    shift = 3 * trace.mean.sem
    branches = raw.level_branches.split()
    shifted = replace(raw, level_mean=tuple(
        m + (shift if b == "up2" else 0.0) for m, b in zip(raw.level_mean, branches)))
    assert shifted.retrace().verdict == "above"
    [wide] = paper_ramp.calibrated([shifted], 2.0)
    assert wide.retrace().verdict == "retraces"
    assert wide.retrace().mean.sem == pytest.approx(2 * shifted.retrace().mean.sem)
    assert wide.down_change_sem == pytest.approx(2 * raw.down_change_sem)
    assert wide.level_sem == pytest.approx(tuple(2 * s for s in raw.level_sem))
    # the descent's verdict is decided again: a change of 3 raw errors is frozen at 2
    marginal = replace(raw, down_change=3 * raw.down_change_sem)
    assert paper_ramp.calibrated([marginal], 2.0)[0].verdict == "frozen"
    assert paper_ramp.calibrated([marginal], 1.0)[0] == marginal
    assert paper_ramp.calibrated([marginal], None) == [marginal]   # no report: as measured
    text = paper_ramp.finding_text([shifted], 1e-7, error_factor=2.0)
    assert "errors: the levels' batch-means errors x 2.0, the spread of the campaign's " \
        "realizations" in text and "it comes across the same values within its errors" in text
    assert "errors: the levels' batch-means errors)" in paper_ramp.finding_text([shifted], 1e-7)
    with pytest.raises(ValueError, match="error factor: 0.5, must be >= 1"):
        paper_ramp.calibrated([raw], 0.5)


def _paper_ramp_cli(*args):
    env = dict(os.environ, PYTHONPATH=str(SOURCE / "tools" / "python"))
    return subprocess.run([sys.executable, "-m", "tapmc.paper", "paper-ramp", *map(str, args)],
                          capture_output=True, text=True, env=env, timeout=120)


def test_the_command_decides_with_the_errors_of_the_report_in_out(tmp_path):
    """tapmc-paper paper-ramp prints the finding with the errors the page in --out decides it
    with (the committed paper-scale report: x 2.1), and says so when --out holds no report."""
    write_run(tmp_path / "c", "paperramp0.125_pbc_s1", [0.590, 0.595, 0.598, 0.600, 0.600,
                                                        0.601, 0.602, 0.603, 0.604])
    bare = _paper_ramp_cli("--campaign", tmp_path / "c", "--out", tmp_path / "bare")
    assert bare.returncode == 0, bare.stderr
    assert "errors: the levels' batch-means errors)" in bare.stdout
    assert "holds no report: the verdicts take the runs' own batch-means errors" in bare.stdout
    page = tmp_path / "page"
    shutil.copytree(SOURCE / "doc" / "paper_scale" / "validation", page / "validation",
                    ignore=shutil.ignore_patterns("*.png", "partial"))
    done = _paper_ramp_cli("--campaign", tmp_path / "c", "--out", page)
    assert done.returncode == 0, done.stderr
    factor = validation.report_errors(SOURCE / "doc" / "paper_scale", paper_ramp)
    assert factor > 1 and f"errors: the levels' batch-means errors x {factor:.1f}," in done.stdout
    assert "holds no report" not in done.stdout
    assert validation.report_errors(tmp_path / "bare", paper_ramp) is None
    # a damaged report in --out: named, exit 2, nothing written
    (page / "validation" / "report.json").write_text("{broken")
    (page / "validation" / "questions" / paper_ramp.CSV_NAME).unlink()
    damaged = _paper_ramp_cli("--campaign", tmp_path / "c", "--out", page)
    assert damaged.returncode == 2 and "Traceback" not in damaged.stderr
    assert "holds a damaged report" in damaged.stderr and "report.json:1:" in damaged.stderr
    assert not (page / "validation" / "questions" / paper_ramp.CSV_NAME).exists()


def test_the_headline_gives_one_answer_then_a_bullet_per_eta(tmp_path):
    """The headline: a sentence with the answer when every eta gives the same one, then a
    blank line and one "- " line per eta (default first); when the etas differ or one is
    undecided, the sentence gives no answer of its own."""
    up = [0.590, 0.595, 0.598, 0.600, 0.600]
    write_run(tmp_path, "paperramp0.125_pbc_s1", up + [0.602, 0.603, 0.604, 0.605])
    write_run(tmp_path, "paperramp0.125_pbc_eta1e-05_s1", up + [0.601, 0.602, 0.603, 0.604],
              seed=2)
    write_run(tmp_path, "paperramp0.125_pbc_eta1e-06_s1", up + [0.600] * 4, seed=3)
    write_run(tmp_path, "paperramp0.125_pbc_eta1e-08_s1", up[:3], levels=LEVELS[:3], seed=4)
    rows = {r.eta: r for r in paper_ramp.analyse(tmp_path, 1e-7)}
    agree = paper_ramp.headline_text([rows[1e-7], rows[1e-5]], 1e-7).split("\n")
    assert agree[0].endswith("P.B.C.): no irreversible branch at any of the 2 redeposition "
                             "thresholds eta measured.")
    assert agree[1] == "" and len(agree) == 4
    assert agree[2].startswith("- eta = 1e-7 (the default): no irreversible branch (1 seed;")
    assert agree[3].startswith("- eta = 1e-5: no irreversible branch (1 seed;")
    one = paper_ramp.headline_text([rows[1e-6]], 1e-7).split("\n")
    assert one[0].endswith("an irreversible (frozen) branch at the redeposition threshold eta "
                           "measured.")
    differ = paper_ramp.headline_text([rows[1e-7], rows[1e-6]], 1e-7).split("\n")
    assert differ[0].endswith("P.B.C.): per redeposition threshold eta.")
    assert differ[3].startswith("- eta = 1e-6: an irreversible (frozen) branch (1 seed;")
    pending = paper_ramp.headline_text([rows[1e-7], rows[1e-8]], 1e-7).split("\n")
    assert pending[0].endswith("per redeposition threshold eta.")
    assert pending[3] == ("- eta = 1e-8: undecided, the ramp has not come down two levels yet "
                          "(seed 1 at tap 12000, still going up).")


def test_the_level_errors_take_the_ramps_own_windows_when_they_reject_the_report(tmp_path):
    """level_previous is the mean of the 1000 taps before a level's last 1000; white noise
    calibrates a factor near 1 that rejects nothing (the report's factor, or 1, stays); slow
    fluctuations of the 1000-tap means (an offset per window, 9 batch-means errors) reject
    the report's factor of 2 and set the errors; rows without level_previous (a CSV written
    before it) count for nothing."""
    up, down = [0.590, 0.595, 0.598, 0.600, 0.600], [0.601, 0.602, 0.603, 0.604]
    loop = up + down + [0.603, 0.602, 0.601, 0.6005]
    write_run(tmp_path / "exact", "paperramp0.125_pbc_s1", loop, levels=LOOP, noise=1e-6,
              window_offset=lambda k, w: 1e-4 * w)
    [exact] = paper_ramp.analyse(tmp_path / "exact", 1e-7)
    assert exact.level_previous == pytest.approx([m + 2e-4 for m in loop], abs=1e-6)
    assert exact.level_mean == pytest.approx([m + 3e-4 for m in loop], abs=1e-6)
    for seed in (1, 2):
        write_run(tmp_path / "white", f"paperramp0.125_pbc_s{seed}", loop, levels=LOOP,
                  seed=seed)
    white = paper_ramp.analyse(tmp_path / "white", 1e-7)
    factor, levels = paper_ramp.window_factor(white)
    assert levels == 16 and 0.6 < factor < 1.5
    assert not paper_ramp.level_errors(white, 2.0).from_window
    assert paper_ramp.level_errors(white, 2.0).value == 2.0
    assert paper_ramp.level_errors(white).value == 1.0
    assert paper_ramp.window_factor([replace(r, level_previous=()) for r in white]) == (None, 0)
    rng = np.random.default_rng(7)
    shifts = rng.standard_normal((len(LOOP), 4)) * 3e-4     # batch-means error ~ 3.3e-5
    for seed in (1, 2):
        write_run(tmp_path / "slow", f"paperramp0.125_pbc_s{seed}", loop, levels=LOOP,
                  seed=seed, window_offset=lambda k, w: shifts[k, w] * (1 if seed == 1 else -1))
    slow = paper_ramp.analyse(tmp_path / "slow", 1e-7)
    errors = paper_ramp.level_errors(slow, 2.0)
    assert errors.from_window and errors.window_p_value < 1e-6 and errors.value > 4.0
    [scaled] = paper_ramp.calibrated(slow[:1], errors.value)
    assert scaled.level_sem == pytest.approx([s * errors.value for s in slow[0].level_sem])
    text = paper_ramp.finding_text(slow, 1e-7, error_factor=2.0)
    assert (f"errors: the levels' batch-means errors x {errors.value:.1f}, the spread of one "
            "1000-tap mean to the next within a level over the ramps' 16 levels after their "
            "turn; the campaign's realizations give x 2.0)") in text
    assert f"x {errors.value:.1f} (one 1000-tap mean to the next)" in \
        paper_ramp_figure.settings_line(slow, 2.0)


def test_seeds_whose_verdicts_differ_within_their_errors_are_answered_together():
    """Two seeds' second increases, one within noise of its descent (+0.0001 +- 0.0004), one
    beyond (+0.0013 +- 0.0004): their difference is 2.1 errors (chi2 = 4.5, p = 0.034, not
    below CALIBRATION_ALPHA), so the answer is their mean, whose error 0.00028 of two
    independent seeds widens by their scatter, sqrt(4.5) = 2.1, to 0.0006: +0.0007 is within
    noise of the descent, reversible (unwidened it read 2.5 errors above: still compacting,
    a verdict the seeds' own disagreement does not support). The control, +0.0030 for the
    second: 5 errors apart, one answer per seed."""
    def trace(mean):
        return paper_ramp.Retrace((0.05,), (mean,), (0.0004,),
                                  BranchStatistic(mean, 0.0004, 3))

    def seed(k):
        return type("Run", (), {"seed": k})()

    traces = [(seed(1), trace(0.0001)), (seed(2), trace(0.0013))]
    assert [t.verdict for _, t in traces] == ["retraces", "above"]
    long = paper_ramp._retrace_answer(traces)
    assert long == ("the seeds' verdicts differ (seed 1 lies on the descent, seed 2 lies above) "
                    "within their errors (chi2 = 4.5 for 1 dof, p = 0.034); over the 2 seeds, "
                    "+0.0007 +- 0.0006 (their errors' mean widened x 2.1 by their scatter): it "
                    "comes across the same values within its errors (how close: the register's "
                    "reversible-retraced row)")
    assert paper_ramp._retrace_answer(traces, short=True) == (
        "together +0.0007 +- 0.0006: within its errors of the descent (seed 1 lies on the "
        "descent, seed 2 lies above, within their errors)")
    apart = [(seed(1), trace(0.0001)), (seed(2), trace(0.0030))]
    assert paper_ramp._retrace_answer(apart, short=True) == (
        "the seeds disagree beyond their errors (seed 1 lies on the descent, seed 2 lies "
        "above; chi2 = "
        "26.3 for 1 dof, p < 1e-4): one answer per seed")
