# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""What a figure's settings line states (tapmc.paper._plotting.settings_text): the stop rule
of the redeposition beside eta, the campaign, the taps of the figure's own runs; and the
counts that a figure's legend states surviving a redraw from its CSV (Figs. 6, 7, 9)."""

import dataclasses
import os
import sys
from pathlib import Path
from types import SimpleNamespace

import matplotlib
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from tapmc.paper import _plotting as P  # noqa: E402
from tapmc.paper import fig2, fig4, fig6, fig7, fig9, redraw  # noqa: E402

SMOKE = SOURCE / "doc" / "validation"
PAPER_SCALE = SOURCE / "doc" / "paper_scale" / "validation"
INPUTS = SOURCE / "examples" / "paper"


def run(name, input_name, taps=None, **variables):
    """A stand-in of a campaign's RunSpec: what run_settings reads of one."""
    base = {"N": 1024, "L": 16.0, "eta": 1e-7}
    return SimpleNamespace(name=name, input=INPUTS / input_name, taps=taps,
                           variables=dict(base, **variables))


@pytest.mark.parametrize("keys, stated", [
    ("", "stop change"), ("check 0", "stop change"),
    ("dmax 0.05 stop drift window 20", "stop drift window 20 dmax 0.05"),
    ("stop change check 4096", "stop change check 4096")])
def test_stop_rule_states_the_rule_and_the_keywords_a_run_sets(keys, stated):
    assert P.stop_rule(keys) == stated


def test_settle_keys_count_only_where_the_input_passes_them_to_the_fix():
    drift = run("const_pbc_eps0.01_s1", "in.constant_eps", 100, settle_keys="stop drift")
    ignored = run("ramp_pbc_s1", "in.ramp", 300, settle_keys="stop drift", P=100, dsqrt=0.05)
    assert P.stop_rule(P.settle_keys(drift)) == "stop drift"
    assert P.stop_rule(P.settle_keys(ignored)) == "stop change"


def test_a_drift_campaign_is_not_labelled_as_a_change_one():
    runs = {rule: [run(f"const_pbc_eps0.01_s{s}", "in.constant_eps", 1000,
                       settle_keys=f"stop {rule}") for s in (1, 2)]
            for rule in ("change", "drift")}
    lines = {rule: P.settings_text(P.run_settings(specs)) for rule, specs in runs.items()}
    assert "eta = 1e-07, stop change;" in lines["change"]
    assert "eta = 1e-07, stop drift;" in lines["drift"]


def test_a_figure_states_its_own_runs_taps_and_its_ramps_levels():
    constant = [run(f"const_pbc_eps0.01_s{s}", "in.constant_eps", 1000) for s in (1, 2)]
    ramps = [run("ramp_pbc_s1", "in.ramp", 2600, P=200, dsqrt=0.05)]
    every = constant + ramps + [run("ageing_pbc_eps0.01_s1", "in.ageing", 3000)]
    own = P.settings_text(P.run_settings(every, constant))
    assert "1000 taps per run;" in own and "ramp" not in own and "3000" not in own
    both = P.settings_text(P.run_settings(every, constant + ramps))
    assert "1000 taps per run (ramps: 200 taps per level, steps of 0.05 in sqrt(eps))" in both


def test_the_campaign_is_named_by_its_preset_else_its_folder():
    assert P.campaign_text({"scale": "full", "preset": True}) == "campaign: full preset"
    assert P.campaign_text({"scale": "mine", "preset": False}) == "campaign: scale mine"
    assert P.campaign_text({"scale": None, "campaign": "trial"}) == "campaign: trial"
    assert P.campaign_text({"scale": None}) is None


def test_committed_figures_state_stop_rule_campaign_and_own_taps():
    """The committed report.json files predate the per-figure settings: the preset's plan
    gives them (smoke: medium preset, 1000 taps, ramps of 200 per level)."""
    summary = redraw.committed_settings(SMOKE)
    fig2_line = P.settings_text(redraw.figure_settings("fig2", summary))
    assert "stop change" in fig2_line and "campaign: medium preset" in fig2_line
    assert "1000 taps per run;" in fig2_line and "2600" not in fig2_line
    fig4_line = P.settings_text(redraw.figure_settings("fig4", summary))
    assert "ramps: 200 taps per level, steps of 0.05 in sqrt(eps)" in fig4_line
    full = redraw.committed_settings(PAPER_SCALE)
    assert "ramps: 1000 taps per level" in P.settings_text(redraw.figure_settings("fig4", full))
    recorded = dict(summary, figures={"fig2": {"taps": [77], "stop": ["stop drift"]}})
    assert "77 taps per run; " in P.settings_text(redraw.figure_settings("fig2", recorded))


def test_fig2_counts_the_seeds_of_its_drawn_curves_only():
    result = fig2.Fig2Result.load(SMOKE / "fig2.csv")
    assert P.plotted_seeds(result) == (2, 2)       # panel B (n = 1) is not drawn


def suptitle_and_labels(fig):
    fig.canvas.draw()
    labels = [t.get_text() for ax in fig.axes if ax.get_legend() is not None
              for t in ax.get_legend().get_texts()]
    plt.close(fig)
    return labels


@pytest.mark.parametrize("module, cls", [(fig6, fig6.Fig6Result), (fig7, fig7.Fig7Result)])
def test_fig6_fig7_keep_after_n_taps_through_their_csv(module, cls, tmp_path):
    result = cls.load(PAPER_SCALE / f"{module.NAME}.csv")
    if module is fig6:
        result = dataclasses.replace(result, profiles=dataclasses.replace(result.profiles,
                                                                          taps=4000))
    else:
        result = dataclasses.replace(result, taps=4000)
    back = cls.load(result.save(tmp_path / f"{module.NAME}.csv"))
    assert "after 4000 taps" in suptitle_and_labels(module.plot(back))
    # a CSV written before the row (the committed one without it): the count of the runs'
    # settings, as a redraw gives it
    lines = (PAPER_SCALE / f"{module.NAME}.csv").read_text().splitlines(keepends=True)
    before_row = tmp_path / f"old_{module.NAME}.csv"
    before_row.write_text("".join(line for line in lines if not line.startswith("params,taps,")))
    old = cls.load(before_row)
    assert "after 123 taps" in suptitle_and_labels(module.plot(old, {"taps": [123],
                                                                    "sizes": []}))


def test_fig9_states_its_taps_and_keeps_them_through_its_csv(tmp_path):
    result = fig9.Fig9Result.load(PAPER_SCALE / "fig9.csv")
    result = dataclasses.replace(result, taps=fig9.Value(0.0, 4000.0, float("nan"), 3))
    back = fig9.Fig9Result.load(result.save(tmp_path / "fig9.csv"))
    assert any(label.startswith("after 4000 taps") for label in
               suptitle_and_labels(fig9.plot(back)))


def test_fig4_names_where_each_ramp_turns():
    labels = suptitle_and_labels(fig4.plot(fig4.Fig4Result.load(PAPER_SCALE / "fig4.csv")))
    turns = {label.split(":")[0] for label in labels if label.startswith("ramp to")}
    assert {t.split(" (")[0] for t in turns} == {"ramp to 0.3", "ramp to 0.125",
                                                  "ramp to 0.175"}
