# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.paper.cost: the cost rule recovers known power laws and per-trial costs from a
synthetic front, borrows what a setting did not measure, refuses what it cannot price, prices
the paper's inputs (ramps level by level), predicts the committed campaign's sweeps, and
`tapmc-paper plan` / `--dry-run` print it."""

import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = HERE.parents[1]
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.paper import cost, front  # noqa: E402

TRIAL, OVERHEAD = 50e-9, 4e-6
# setting -> (S0 at N = 1024 and eps = 0.0225, a, b, the (N, eps) it was run at)
FULL = [(1024, 0.0225), (1024, 0.1), (4096, 0.0225), (4096, 0.1)]
LAWS = {"change 1e-5": (400.0, 0.15, 0.2, FULL),
        "change 1e-7 (default)": (1800.0, 0.55, 0.25, FULL),
        "change 1e-6": (900.0, None, 0.3, FULL[:2]),
        "drift 1e-7": (8000.0, 0.1, 0.3, FULL),
        "dmax R/2": (1900.0, None, None, FULL[:1])}


def sweeps(S0, a, b, N, eps, borrowed_a=0.0, borrowed_b=0.0):
    """The law; a missing exponent is the borrowed one (0 where the points do not need it)."""
    a = a if a is not None else borrowed_a
    b = b if b is not None else borrowed_b
    return S0 * (N / 1024) ** a * (eps / 0.0225) ** b


def synthetic_rows():
    rows = []
    for name, (S0, a, b, points) in LAWS.items():
        for N, eps in points:
            S = sweeps(S0, a, b, N, eps)
            rows.append({"N": N, "eps": eps, "setting": name, "sweeps_per_tap": S,
                         "cpu_per_tap": N * (OVERHEAD + TRIAL * S)})
    return rows


def test_the_rule_recovers_the_per_trial_cost_and_the_power_laws():
    rule = cost.CostRule(synthetic_rows())
    assert rule.trial == pytest.approx(TRIAL, rel=1e-9)
    assert rule.overhead == pytest.approx(OVERHEAD, rel=1e-9)
    for name in ("change 1e-5", "change 1e-7 (default)", "drift 1e-7"):
        S0, a, b, _ = LAWS[name]
        assert rule.exponents(name)[:2] == pytest.approx((a, b), rel=1e-9)
        for N, eps in ((512, 0.0025), (32768, 0.3)):  # beyond the measured range: the law
            assert rule.sweeps_per_tap(N, eps, name) == pytest.approx(sweeps(S0, a, b, N, eps), rel=1e-9)
            assert rule.cpu_hours(N, 4000, eps, name) == pytest.approx(
                4000 * N * (OVERHEAD + TRIAL * sweeps(S0, a, b, N, eps)) / 3600, rel=1e-9)


def test_a_setting_measured_at_one_N_borrows_its_N_exponent_in_log_eta():
    rule = cost.CostRule(synthetic_rows())
    # change 1e-6 sits halfway (in log eta) between change 1e-5 (a = 0.15) and 1e-7 (0.55)
    a, b, source = rule.exponents("change 1e-6")
    assert a == pytest.approx(0.35) and b == pytest.approx(0.3)
    assert source["a"] and source["b"] is None
    assert rule.sweeps_per_tap(4096, 0.1, "change 1e-6") == pytest.approx(
        sweeps(900.0, None, 0.3, 4096, 0.1, borrowed_a=0.35), rel=1e-9)
    # a d_max variant borrows both from the plain setting of its rule and eta (the default)
    assert rule.exponents("dmax R/2")[:2] == pytest.approx((0.55, 0.25))
    # an unlisted threshold between measured ones: anchor and exponents interpolated
    mid = rule.sweeps_per_tap(1024, 0.0225, "change 1e-6")
    assert 400 < rule.sweeps_per_tap(1024, 0.0225, "change 3e-6") < mid


def test_what_the_rule_cannot_price_is_refused_by_name():
    rule = cost.CostRule(synthetic_rows())
    with pytest.raises(cost.CostError, match="change 1e-9.*1e-7 .. 1e-5"):
        rule.sweeps_per_tap(1024, 0.0225, "change 1e-9")
    with pytest.raises(cost.CostError, match="allowed values are the purposes"):
        rule.sweeps_per_tap(1024, 0.0225, "fastest")
    with pytest.raises(cost.CostError, match=r"eps = 2.0: must be in \(0, 1\]"):
        rule.sweeps_per_tap(1024, 2.0, "change 1e-5")
    with pytest.raises(cost.CostError, match="N = 0"):
        rule.seconds_per_tap(0, 0.01, "change 1e-5")
    with pytest.raises(cost.CostError, match="lacks N, eps"):
        cost.CostRule([{"N": 1024, "setting": "change 1e-5"}])
    with pytest.raises(cost.CostError, match="no rows"):
        cost.CostRule([])


def test_runs_of_the_paper_inputs_are_priced_tap_by_tap():
    rule = cost.CostRule(synthetic_rows())

    class Spec:
        def __init__(self, variables, taps):
            self.variables, self.taps = variables, taps

    ramp = Spec({"N": 4096, "eta": 1e-7, "sqrt0": 0.05, "dsqrt": 0.05, "nlev": 2, "P": 10}, 40)
    eps = cost.run_eps(ramp.variables, ramp.taps)
    # up 0.05, 0.1; down 0.05; up 0.1: 10 taps each
    assert np.allclose(eps, np.repeat([0.0025, 0.01, 0.0025, 0.01], 10))
    expected = sum(10 * rule.seconds_per_tap(4096, e, front.DEFAULT)
                   for e in (0.0025, 0.01, 0.0025, 0.01)) / 3600
    assert cost.run_cost(ramp, rule) == pytest.approx(expected, rel=1e-12)
    # tap by tap, the strong levels cost more (the campaign's ETA of a ramp weighs by it)
    per_tap = cost.tap_seconds(ramp, rule)
    assert per_tap.shape == (40,) and per_tap[10] > per_tap[0] == per_tap[20]
    assert per_tap[0] == pytest.approx(rule.seconds_per_tap(4096, 0.0025, front.DEFAULT))
    constant = Spec({"N": 1024, "eta": 1e-5, "sqrteps": 0.15, "eps": 0.5}, 100)
    assert cost.run_cost(constant, rule) == pytest.approx(rule.cpu_hours(1024, 100, 0.0225, "change 1e-5"))
    drift = Spec({"N": 1024, "eta": 1e-7, "eps": 0.1, "settle_keys": "stop drift window 32"}, 10)
    assert cost.run_setting(drift.variables) == "drift 1e-7"


def test_the_front_recommendation_is_the_setting_of_a_purpose():
    rule = cost.CostRule.from_summary()
    recs = front.recommend(rule.summary_rows, 4096)
    for purpose in cost.TIERS:
        assert cost.tier_setting(purpose, rule, 3000) == recs[purpose].setting
    assert cost.tier_setting("smoke", rule, 4096) == recs["smoke test"].setting
    assert cost.tier_setting("change 1e-6", rule, 4096) == "change 1e-6"


def test_the_committed_campaign_is_predicted_within_a_tenth():
    """The rule, fitted to the front's 1000-tap runs at eps 0.0225 and 0.1, against the sweeps
    per tap of every finished run of the committed paper-scale campaign at the default setting
    (eps 0.0025 to 0.15, ramps level by level): within 10 % each, 3 % in the median. The loose
    threshold of the eta = 1e-5 ramp is extrapolated badly far below the front's eps (its
    sweeps fall much faster there: tapmc-paper.rst), but its CPU time per tap, where the
    per-tap overhead weighs more, still within 10 %, on the runs whose logs time at least
    MIN_CPU_COVERAGE of their taps."""
    campaign = SOURCE / "doc" / "validation" / "data" / "full"
    if not (campaign / "runs").is_dir():
        pytest.skip("no committed campaign")
    rows = cost.campaign_check(campaign, cost.CostRule.from_summary())
    default = [r for r in rows if r["setting"] == front.DEFAULT]
    assert len(default) >= 30
    ratios = np.array([r["sweeps_predicted"] / r["sweeps"] for r in default])
    assert np.all(np.abs(ratios - 1) < 0.10), [(r["run"], round(x, 3)) for r, x in zip(default, ratios)]
    assert abs(np.median(ratios) - 1) < 0.03
    measured = [r for r in rows if np.isfinite(r["cpu_per_tap"])]
    assert len(measured) >= 25 and all(r["cpu_per_tap"] > 0 for r in measured)
    assert any(r["setting"] == "change 1e-5" for r in measured)
    for r in measured:
        if r["setting"] == "change 1e-5":
            assert abs(r["cpu_per_tap_predicted"] / r["cpu_per_tap"] - 1) < 0.10, r


def _tapmc_paper(*args):
    env = dict(os.environ, PYTHONPATH=str(SOURCE / "tools" / "python"))
    return subprocess.run([sys.executable, "-m", "tapmc.paper", *args], env=env,
                          capture_output=True, text=True, timeout=120)


def test_wall_hours_schedule_the_longest_runs_first():
    assert cost.wall_hours([2.9], 8) == 2.9                     # one run: its own time
    assert cost.wall_hours([1.0] * 4, 2) == 2.0                 # even: total / jobs
    assert cost.wall_hours([3.0, 1.0, 1.0, 1.0], 2) == 3.0      # the long run bounds it
    assert cost.wall_hours([2.0, 2.0, 1.0, 1.0, 1.0, 1.0], 2) == 4.0
    assert cost.wall_hours([], 4) == 0.0


def test_plan_prints_the_cost_of_each_purpose_and_the_line_to_paste():
    done = _tapmc_paper("plan", "--N", "4096", "--taps", "4000", "--eps", "0.0225", "0.1",
                        "--seeds", "3", "--jobs", "2")
    assert done.returncode == 0, done.stderr
    rule = cost.CostRule.from_summary()
    each = [rule.cpu_hours(4096, 4000, e, cost.tier_setting(p, rule, 4096))
            for p in cost.TIERS for e in (0.0225, 0.1)] * 3
    total = sum(each)
    assert f"total: {total:.1f} CPU hours, about {cost.wall_hours(each, 2):.1f} h of wall time " \
        "on 2 cores" in done.stdout
    # one run on 8 cores takes its own time, not an eighth of it
    one = _tapmc_paper("plan", "--N", "4096", "--taps", "4000", "--eps", "0.1", "--setting",
                       "publication", "--jobs", "8")
    hours = float(one.stdout.split("total: ")[1].split(" CPU hours")[0])
    assert f"about {hours:.1f} h of wall time on 8 cores" in one.stdout, one.stdout
    assert "fix settle all mc/settle SEED floor 0.0" in done.stdout
    bad = _tapmc_paper("plan", "--N", "4096", "--taps", "10", "--eps", "0.01", "--setting", "change 1e-12")
    assert bad.returncode == 2 and "change 1e-12" in bad.stderr and "Traceback" not in bad.stderr


def test_dry_run_prices_every_run(tmp_path):
    done = _tapmc_paper("fig4", "--quick", "--dry-run", "--campaign", str(tmp_path / "c"))
    assert done.returncode == 0, done.stderr
    lines = [line for line in done.stdout.splitlines() if line.startswith("  ")]
    assert lines and all("CPU h, to run]" in line for line in lines)
    assert "left to run: about" in done.stdout
    assert not (tmp_path / "c").exists()
    # the wall time of the --jobs asked for (it took the cores available), and a quick
    # campaign's seconds as seconds (it read '0.0 CPU hours ... 0.0 h of wall time')
    one = _tapmc_paper("fig4", "--quick", "--dry-run", "--jobs", "1", "--campaign",
                       str(tmp_path / "c"))
    last = one.stdout.splitlines()[-1]
    assert one.returncode == 0 and last.endswith("of wall time on 1 core)"), last
    assert " s of CPU" in last or " min of CPU" in last, last


def test_the_campaign_weighs_only_the_runs_whose_taps_differ_in_cost():
    """tapmc-paper campaign passes the rule's seconds per tap of the ramps to the runner (their
    ETA), not of the constant-eps runs, whose rate so far says as much."""
    from tapmc.paper import cli, plan
    specs = plan.runs(8, jobs=2)
    costs = cli._tap_costs(specs)
    ramps = {s.name for s in specs if "nlev" in s.variables}
    assert set(costs) == ramps and "paperramp0.2_pbc_s1" in costs
    by_name = {s.name: s for s in specs}
    for name, seconds in costs.items():
        assert seconds.shape == (by_name[name].taps,) and seconds.min() > 0
