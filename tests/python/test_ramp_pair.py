# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The ramp pair of section III.B (Fig. 4): the statistics of tapmc.hysteresis that decide the
# reversible and irreversible branches, each on synthetic branch data with a known answer and
# on data where it must fail; the second ramp's run (Scale.ramp_below_top, its name, its
# levels), Fig. 4's CSV rows from a written campaign, and tier 4 of the paper-scale plan.
import csv
import json
import os
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from paper_fakes import FakeCampaign, write_ramp  # noqa: E402
from tapmc.hysteresis import (CRITICAL_SQRT_EPS, Z_DECIDE, BranchData,  # noqa: E402
                              BranchStatistic, Hysteresis, RampBranches, branch_change,
                              branch_difference, branch_slope)
from tapmc.paper import _runs, claims, fig4, plan  # noqa: E402
from tapmc.paper.scales import FULL, MEDIUM, QUICK, Scale  # noqa: E402

SEM = 0.001


def branch(sqrt_eps, mean, sem=SEM):
    return BranchData(sqrt_eps, mean, np.full(len(sqrt_eps), sem))


# -- the statistics, each with a known answer and a failure ---------------------------------

def test_branch_difference_known_answer():
    a = branch([0.05, 0.1, 0.15], [0.60, 0.61, 0.62])
    b = branch([0.2, 0.15, 0.1, 0.05], [0.0, 0.615, 0.60, 0.59])
    d = branch_difference(a, b)
    # common sqrt(eps) 0.05, 0.1, 0.15: differences 0.01, 0.01, 0.005
    assert d.value == pytest.approx(0.025 / 3) and d.n == 3
    assert d.sem == pytest.approx(np.sqrt(6 * SEM**2) / 3)
    assert d.positive and not d.within_noise
    same = branch_difference(a, a)
    assert same.value == 0 and same.within_noise and not same.positive
    with pytest.raises(ValueError, match="share no sqrt"):
        branch_difference(branch([0.3], [0.6]), a)


def test_branch_slope_known_answer_and_scatter():
    x = np.array([0.05, 0.1, 0.15, 0.2])
    s = branch_slope(branch(x, 0.63 - 0.05 * x))
    assert s.value == pytest.approx(-0.05) and s.n == 4
    # exact line: the error bars alone; weighted least squares of equal weights
    assert s.sem == pytest.approx(SEM / np.sqrt(np.sum((x - x.mean()) ** 2)))
    assert s.negative
    flat = branch_slope(branch(x, [0.6, 0.6005, 0.5995, 0.6]))
    assert flat.within_noise and not flat.negative
    # scatter beyond the error bars widens the error (reduced chi2 > 1)
    wild = branch_slope(branch(x, 0.63 - 0.05 * x + np.array([0.02, -0.02, 0.02, -0.02])))
    assert wild.sem > 10 * s.sem
    two = branch_slope(branch([0.05, 0.1], [0.62, 0.61]))
    assert two.value == pytest.approx(-0.2) and two.sem == pytest.approx(np.hypot(SEM, SEM) / 0.05)
    with pytest.raises(ValueError, match="two levels"):
        branch_slope(branch([0.05], [0.6]))


def test_branch_change_known_answer():
    c = branch_change(branch([0.1, 0.05], [0.604, 0.606]), 0.6, SEM)
    assert c.value == pytest.approx(0.005) and c.n == 2
    assert c.sem == pytest.approx(np.sqrt(2 * SEM**2 / 4 + SEM**2))
    assert c.positive
    assert branch_change(branch([0.1, 0.05], [0.6005, 0.5995]), 0.6, SEM).within_noise
    with pytest.raises(ValueError, match="start_sem"):
        branch_change(branch([0.1], [0.6]), 0.6, 0.0)


def test_statistic_decisions_at_z_decide():
    assert BranchStatistic(Z_DECIDE * 1.01, 1.0, 3).positive
    assert BranchStatistic(Z_DECIDE * 0.99, 1.0, 3).within_noise
    assert BranchStatistic(-Z_DECIDE * 1.01, 1.0, 3).negative


def reversible_ramp(gap=0.02, slope=-0.05, retrace_offset=0.0):
    """A ramp up to 0.2 > (sqrt eps)*: the first increase on the bell, the decrease `gap` above
    it at its lowest point and falling with sqrt(eps) by `slope`, the second increase on the
    decrease plus `retrace_offset`."""
    up = np.array([0.05, 0.1, 0.15, 0.2])
    down = up[-2::-1]
    up1 = branch(up, 0.58 + 0.1 * up)
    top = 0.58 + 0.1 * 0.2
    down_mean = top + gap + slope * (down - 0.2)
    return up1, branch(down, down_mean), branch(down[::-1][1:], (top + gap + slope * (
        down[::-1][1:] - 0.2)) + retrace_offset)


def test_reversible_branch_decided():
    r = RampBranches(*reversible_ramp()).compute()
    assert r.top_sqrt_eps == 0.2 and r.went_above_critical
    assert r.reversible and r.falls_with_sqrt_eps and r.retraced and not r.frozen
    assert r.down_slope.value == pytest.approx(-0.05)
    assert r.up2_minus_down.value == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("kwargs, verdict", [
    (dict(gap=-0.035), "reversible"),           # the decrease below the first increase
    (dict(slope=+0.05), "falls_with_sqrt_eps"),  # <Phi^c> rises with sqrt(eps) on the decrease
    (dict(retrace_offset=0.01), "retraced"),    # the second increase 10 sem above the decrease
])
def test_reversible_branch_failures(kwargs, verdict):
    r = RampBranches(*reversible_ramp(**kwargs)).compute()
    assert not getattr(r, verdict)


def test_reversible_needs_the_ramp_above_critical():
    up1, down, up2 = reversible_ramp()
    r = RampBranches(up1, down, up2, critical=0.25).compute()
    assert not r.went_above_critical and not r.reversible


def test_irreversible_branch_frozen_and_not():
    up1 = branch([0.05, 0.1], [0.58, 0.585])
    frozen = RampBranches(up1, branch([0.05], [0.5853]), branch([0.1], [0.5851])).compute()
    assert frozen.top_sqrt_eps == 0.1 and not frozen.went_above_critical
    assert frozen.down_change.value == pytest.approx(0.0003) and frozen.frozen
    assert frozen.down_slope is None           # one decreasing level
    assert frozen.up2_minus_down is None       # no sqrt(eps) common to up2 and down
    moved = RampBranches(up1, branch([0.05], [0.595])).compute()
    assert moved.down_change.positive and not moved.frozen
    # a ramp that went beyond (sqrt eps)* is never "frozen", however little it moved
    above = RampBranches(branch([0.1, 0.2], [0.58, 0.585]), branch([0.1], [0.585])).compute()
    assert above.down_change.within_noise and not above.frozen


def test_ramp_branches_from_hysteresis():
    """From the per-tap series of a ramp: the levels' means over their last taps and the
    batch-means errors decide the same as the branch data."""
    rng = np.random.default_rng(7)
    levels = np.array([0.05, 0.1, 0.15, 0.2, 0.15, 0.1, 0.05, 0.1, 0.15, 0.2])
    truth = np.array([0.585, 0.59, 0.595, 0.6, 0.61, 0.615, 0.62, 0.615, 0.61, 0.6])
    per_level = 200
    x = np.repeat(truth, per_level) + rng.normal(0, 1e-3, levels.size * per_level)
    h = Hysteresis(np.repeat(levels, per_level), x, taps_per_level=per_level, last=100).compute()
    r = RampBranches.from_hysteresis(h).compute()
    assert r.down_minus_up1.value == pytest.approx(0.025, abs=1e-3)
    assert r.down_slope.value == pytest.approx(-0.1, abs=0.02)
    assert r.reversible and r.falls_with_sqrt_eps and r.retraced


@pytest.mark.parametrize("args, message", [
    (dict(up1=([0.05], [0.6], [0.0]), down=([0.05], [0.6], [SEM])), r"up1: sem\[0\] = 0.0"),
    (dict(up1=42, down=([0.05], [0.6], [SEM])), "up1 must be BranchData"),
    (dict(up1=([0.05], [0.6], [SEM]), down=([0.05, 0.1], [0.6], [SEM])), "down: sqrt_eps has 2"),
    (dict(up1=([0.05], [0.6], [SEM]), down=([0.05], [0.6], [SEM]), critical=1.5),
     r"critical = 1.5 must lie in \(0.0, 1.0\]"),
])
def test_ramp_branches_validation(args, message):
    with pytest.raises(ValueError, match=message):
        RampBranches(**args)


def test_ramp_branches_results_need_compute():
    from tapmc._validate import NotComputedError

    r = RampBranches(*reversible_ramp())
    for name in ("top_sqrt_eps", "down_minus_up1", "down_slope", "up2_minus_down",
                 "down_change"):
        with pytest.raises(NotComputedError, match="compute"):
            getattr(r, name)
    assert r.compute() is r


def test_plot_marks_the_critical_value():
    import matplotlib
    matplotlib.use("Agg")
    ax = RampBranches(*reversible_ramp()).compute().plot()
    assert any(np.allclose(line.get_xdata(), CRITICAL_SQRT_EPS) for line in ax.get_lines())


# -- the second ramp's run, Fig. 4's CSV rows, tier 4 ---------------------------------------

def test_ramp_below_run_and_scale():
    for scale in (QUICK, MEDIUM, FULL):
        below = _runs.ramp_below_run(scale, "pbc", 3)
        top = scale.ramp_sqrt0 + (below.variables["nlev"] - 1) * scale.ramp_dsqrt
        assert below.name == "ramplow_pbc_s3" and below.seed == 3
        assert top < CRITICAL_SQRT_EPS < scale.ramp_top
        assert top + scale.ramp_dsqrt > scale.ramp_below_top   # the highest level below the top
        assert below.taps == below.variables["P"] * (3 * below.variables["nlev"] - 2)
    assert FULL.ramp_below_levels == 5 and QUICK.ramp_below_levels == 2
    with pytest.raises(ValueError, match=r"Scale.ramp_below_top = 0.2: must be in \[ramp_sqrt0, 0.15\)"):
        QUICK.replace(ramp_below_top=0.2)
    with pytest.raises(ValueError, match=r"Scale.ramp_below_top = 0.01"):
        QUICK.replace(ramp_below_top=0.01)
    names = [s.name for s in fig4.runs(QUICK, 2)]
    assert {"ramp_pbc_s1", "ramp_pbc_s2", "ramplow_pbc_s1", "ramplow_pbc_s2"} <= set(names)
    # the prefix of the ramp beyond (sqrt eps)* does not select the one below it
    camp = FakeCampaign("unused", fig4.runs(QUICK, 1))
    assert [s.name for s in _runs.select(camp, "ramp_")] == ["ramp_pbc_s1"]


def test_ramp_near_run_turns_at_the_first_level_beyond_critical():
    for scale in (QUICK, MEDIUM, FULL):
        near = _runs.ramp_near_run(scale, "pbc", 2)
        top = scale.ramp_sqrt0 + (near.variables["nlev"] - 1) * scale.ramp_dsqrt
        assert near.name == "rampnear_pbc_s2" and near.seed == 2
        assert CRITICAL_SQRT_EPS < top <= CRITICAL_SQRT_EPS + scale.ramp_dsqrt + 1e-12
        assert {k: v for k, v in near.variables.items() if k != "nlev"} == \
            {k: v for k, v in _runs.ramp_run(scale, "pbc", 2).variables.items() if k != "nlev"}
    assert FULL.ramp_near_levels == 7
    # a level exactly at (sqrt eps)* is not beyond it; a grid that straddles it takes the next
    assert FULL.replace(ramp_sqrt0=0.05, ramp_dsqrt=0.05).ramp_near_levels == 4     # 0.2
    assert FULL.replace(ramp_sqrt0=0.04, ramp_dsqrt=0.05).ramp_near_levels == 4     # 0.19
    # the prefix of the ramp beyond (sqrt eps)* does not select it
    camp = FakeCampaign("unused", [_runs.ramp_near_run(QUICK, "pbc", 1),
                                   _runs.ramp_run(QUICK, "pbc", 1)])
    assert [s.name for s in _runs.select(camp, "ramp_")] == ["ramp_pbc_s1"]


def test_scale_record_without_the_new_fields_reads_with_defaults(tmp_path):
    """A scale.json written before fbc_start and ramp_below_top existed is today's FULL."""
    record = FULL.as_dict()
    del record["fbc_start"], record["ramp_below_top"]
    (tmp_path / "scale.json").write_text(json.dumps(record))
    assert _runs.recorded_scale(tmp_path) == FULL
    _runs.check_scale(tmp_path, FULL)


def ramp_series(levels, truth, per_level, rng, noise=5e-4):
    sq = np.repeat(levels, per_level)
    return sq, np.repeat(truth, per_level) + rng.normal(0, noise, sq.size)


def test_fig4_csv_of_the_pair(tmp_path):
    """Fig. 4 from a written campaign: two seeds of each ramp with known level values; the
    CSV holds both ramps' branches and the statistics with their known values."""
    scale = Scale(**dict(QUICK.as_dict(), N=64, L=8.0, eta=1e-4, ramp_taps_per_level=40))
    runs = fig4.runs(scale, 2) + [_runs.ramp_near_run(scale, "pbc", 1)]
    camp = FakeCampaign(tmp_path, runs)
    rng = np.random.default_rng(11)
    for spec in runs:
        if spec.name.startswith("const_"):
            x = 0.58 + spec.variables["eps"] + rng.normal(0, 1e-4, scale.taps)
            (camp.result(spec.name) / "taps.dat").write_text(
                "# step phi_b phi_c Z z_top lateral central h_s sweeps accept capped\n"
                + "".join(f"{t} 0.55 {v:.8f} 5 9 0.5 0.5 10 100 0.1 0\n"
                          for t, v in enumerate(np.r_[0.55, x])))
        elif spec.name.startswith(("ramp_", "rampnear_")):   # 0.05 .. 0.2: reversible
            levels = np.array([0.05, 0.1, 0.15, 0.2, 0.15, 0.1, 0.05, 0.1, 0.15, 0.2])
            truth = np.array([0.58, 0.585, 0.59, 0.595, 0.605, 0.61, 0.615, 0.61, 0.605, 0.595])
            write_ramp(camp, spec, *ramp_series(levels, truth, 40, rng))
        else:                                 # 0.05, 0.1: frozen
            levels = np.array([0.05, 0.1, 0.05, 0.1])
            truth = np.array([0.58, 0.585, 0.585, 0.585])
            write_ramp(camp, spec, *ramp_series(levels, truth, 40, rng))
    png, path = fig4.draw(camp, tmp_path / "figs")
    rows = {(r["panel"], r["series"]): r for r in csv.DictReader(open(path))}
    series = {s for p, s in rows if p == "a"}
    assert {"steady", "up1", "down", "up2", "low:up1", "low:down", "low:up2"} <= series

    def param(name):
        r = rows[("params", name)]
        return float(r["x"]), float(r["mean"]), float(r["sem"] or "nan"), int(r["n"])

    assert param("critical_sqrt_eps")[1] == 0.15
    assert param("ramp:top_sqrt_eps")[1] == pytest.approx(0.2)
    assert param("low:top_sqrt_eps")[1] == pytest.approx(0.1)
    x, gap, sem, n = param("ramp:down_minus_up1")
    assert x == pytest.approx(0.2) and n == 2
    assert gap == pytest.approx(np.mean([0.015, 0.025, 0.035]), abs=1e-3) and gap > 2 * sem
    slope = param("ramp:down_slope")
    assert slope[1] == pytest.approx(-0.1, abs=0.02) and slope[1] < -2 * slope[2]
    retrace = param("ramp:up2_minus_down")
    assert abs(retrace[1]) < 1e-3
    low = param("low:down_change")
    assert abs(low[1]) < 2 * low[2] + 1e-3 and low[1] == pytest.approx(0.0, abs=1e-3)
    assert ("params", "low:down_slope") not in rows      # a single decreasing level
    assert ("params", "low:up2_minus_down") not in rows  # up2 and down share no sqrt(eps)
    # each seed's own differences of levels, whose mean is the statistic of the mean levels
    # (levels shared by the seeds), with the error that seed's levels give it
    table = claims.FigureData.read(path)
    for name in ("ramp:down_minus_up1", "ramp:up2_minus_down", "ramp:down_change",
                 "low:down_change"):
        x, values, errors, n = table.get("params", f"{name}:seeds")
        assert len(values) == 2 and np.all(n == 1) and np.all(errors > 0), name
        assert np.mean(values) == pytest.approx(param(name)[1], abs=1e-9), name
    one = fig4.per_seed_ramp_branches(camp, prefix=_runs.RAMP_BELOW_PREFIX)[0]
    assert table.get("params", "low:down_change:seeds")[2][0] == pytest.approx(one.down_change.sem)
    assert ("params", "ramp:down_slope:seeds") not in rows          # not a mean of levels
    # each seed's first increase at the steady squares' sqrt(eps) (0.05, 0.1, 0.2 of QUICK):
    # their mean is the up1 curve's mean there, near the true 0.58667
    x, values, errors, n = table.get("params", "ramp:up1_at_steady:seeds")
    up_sq, up_mean = table.get("a", "up1")[:2]
    at = np.isin(np.round(up_sq, 9), [0.05, 0.1, 0.2])
    assert len(values) == 2 and np.all(errors > 0) and np.all(errors < 2e-4)
    assert np.mean(values) == pytest.approx(np.mean(up_mean[at]), abs=1e-12)
    assert np.mean(values) == pytest.approx(np.mean([0.58, 0.585, 0.595]), abs=3e-4)
    assert ("params", "low:up1_at_steady:seeds") not in rows        # the squares' claim: ramp
    assert ("params", "near:down_change:seeds") not in rows         # one seed
    # the ramp just beyond (sqrt eps)* (one seed; QUICK's first level beyond 0.15 is 0.2) and
    # the claim it decides with the ramp below, read from the CSV as the report reads it
    assert {"near:up1", "near:down", "near:up2"} <= series
    assert param("near:top_sqrt_eps")[1] == pytest.approx(0.2)
    data = claims.ReportData({}, {"fig4": claims.FigureData.read(path)})
    claim = {c.id: c for c in claims.load_register()}["critical-sqrt-eps"]
    (m,) = claims.critical_separation(data, claim)
    assert str(claims.verdict(claim, m)) == "agrees" and "(0.1, 0.2]" in m.shown


def test_plan_tier4_completes_ageing_then_the_ramp_pair_and_tiers_1_to_3_unchanged():
    tier3 = plan.runs(3)
    assert not any(s.name.startswith("ramplow_") for s in tier3)
    everything = plan.tier_runs(4)
    ageing = [s for s in everything if s.name.startswith("ageing_")]
    # the paper's 10 realizations (section III.C) with tier 3's four, from the same packing
    assert [s.seed for s in ageing] == [5, 6, 7, 8, 9, 10]
    all_ageing = [s for s in plan.runs(4) if s.name.startswith("ageing_")]
    assert len({s.name for s in all_ageing}) == 10
    assert len({tuple(sorted(s.variables.items())) for s in all_ageing}) == 1
    tier4 = everything[len(ageing):]
    assert everything[:len(ageing)] == ageing
    assert [s.name for s in tier4] == ["ramplow_pbc_s1", "rampnear_pbc_s1", "ramp_pbc_s2",
                                       "ramplow_pbc_s2"]
    assert all(s.variables["P"] == plan.TIER3_RAMP_TAPS_PER_LEVEL for s in tier4)
    (tier3_ramp,) = [s for s in tier3 if s.name == "ramp_pbc_s1"]
    assert tier3_ramp.variables == dict(tier4[2].variables)          # the same ramp, seed 2
    assert tier4[0].variables["nlev"] == 5                           # 0.025 .. 0.125
    assert tier4[1].variables["nlev"] == 7                           # 0.025 .. 0.175
    everything = [s.name for s in plan.runs(4)]
    assert everything[:len(tier3)] == [s.name for s in tier3]
    assert len(everything) == len(set(everything))


@pytest.mark.parametrize("tier, eps, seed1_tier", [(5, "0.02", 2), (6, "0.1", 1)])
def test_plan_fbc_tiers_add_seeds_that_group_with_seed_1(tier, eps, seed1_tier):
    """Tiers 5 and 6: seeds 2 and 3 of an F.B.C. constant-eps run whose seed 1 an earlier tier
    runs (Fig. 8's eps = 0.02, Figs. 6-7's eps = 0.1), the same run but its seed, so that
    realization-scatter finds a group of three F.B.C. realizations; the tiers before unchanged,
    and none beyond the last."""
    added = plan.tier_runs(tier)
    assert [s.name for s in added] == [f"const_fbc_eps{eps}_s2", f"const_fbc_eps{eps}_s3"]
    (seed1,) = [s for s in plan.tier_runs(seed1_tier) if s.name == f"const_fbc_eps{eps}_s1"]
    for spec in added:
        assert dict(spec.variables) == dict(seed1.variables) and spec.taps == seed1.taps
    everything = [s.name for s in plan.runs(tier)]
    assert everything == [s.name for s in plan.runs(tier - 1)] + [s.name for s in added]
    with pytest.raises(ValueError, match=f"tier = {plan.TIERS[-1] + 1}"):
        plan.runs(plan.TIERS[-1] + 1)


def test_fig4_errors_survive_a_chance_agreement_of_the_seeds(tmp_path):
    """Two seeds whose ramps are the same series (their sem over seeds is 0): the statistics
    keep the error the levels' batch-means standard errors give, instead of vanishing (or of
    leaving the ramp undecided)."""
    scale = Scale(**dict(QUICK.as_dict(), N=64, L=8.0, eta=1e-4, ramp_taps_per_level=40))
    runs = [_runs.ramp_below_run(scale, "pbc", s) for s in (1, 2)]
    camp = FakeCampaign(tmp_path, runs)
    levels = np.array([0.05, 0.1, 0.05, 0.1])
    truth = np.array([0.58, 0.585, 0.585, 0.585])
    for spec in runs:
        write_ramp(camp, spec, *ramp_series(levels, truth, 40, np.random.default_rng(3),
                                            noise=1e-3))
    found = fig4.ramp_branches(camp, prefix=_runs.RAMP_BELOW_PREFIX)
    assert found is not None
    stats, seeds = found
    assert seeds == 2
    # one level's batch-means error is about 1e-3 / sqrt(10) per seed; over two identical
    # seeds the error of the mean is that / sqrt(2), never 0
    assert 1e-4 < stats.down_change.sem < 2e-3
    assert stats.frozen


def test_one_seed_ramp_branches_carry_the_levels_errors_and_decide(tmp_path):
    """The campaign's ramp has one seed (tier 3): the branch series of Fig. 4 carry each
    level's batch-means error (n = 1), so the branch claims are decided by the run's own
    errors, not left without error bars."""
    scale = Scale(**dict(QUICK.as_dict(), N=64, L=8.0, eta=1e-4, ramp_taps_per_level=40))
    (spec,) = [_runs.ramp_run(scale, "pbc", 1)]
    camp = FakeCampaign(tmp_path, [spec])
    levels = np.array([0.05, 0.1, 0.15, 0.2, 0.15, 0.1, 0.05, 0.1, 0.15, 0.2])
    truth = np.array([0.58, 0.585, 0.59, 0.595, 0.605, 0.61, 0.615, 0.61, 0.605, 0.595])
    write_ramp(camp, spec, *ramp_series(levels, truth, 40, np.random.default_rng(5)))
    branches = fig4.hysteresis_branches(camp)
    for name in ("up1", "down", "up2"):
        sq, mean, sem, n = branches[name]
        assert np.all(n == 1) and np.all(np.isfinite(sem)) and np.all(sem > 0), name
        assert np.all(sem < 1e-3)          # 5e-4 noise over the level's last 10 taps
    table = claims.FigureData({("a", b): {"x": list(v[0]), "mean": list(v[1]),
                                          "sem": list(v[2]), "n": list(v[3])}
                               for b, v in branches.items()})
    data = claims.ReportData({}, {"fig4": table})
    BY_ID = {c.id: c for c in claims.load_register()}
    (m,) = claims.ramp_down_minus_up(data, BY_ID["reversible-above"])
    assert m.dof == claims.WITHIN_RUN_DOF and str(claims.verdict(BY_ID["reversible-above"],
                                                             m)) == "agrees"


def test_a_resumed_ramps_restart_step_row_takes_its_levels_sqrt_eps(tmp_path):
    """A ramp resumed from a restart file without fix tapdilate's latest eps (TAPMC before the
    fix kept it) printed sqrt(eps) = 0 in the row of the restart step, before its first tap;
    that row takes its level's value, so Fig. 4's levels are those of an uninterrupted run
    (the rows inside a level's averaging window would otherwise be refused)."""
    scale = Scale(**dict(QUICK.as_dict(), N=64, L=8.0, eta=1e-4, ramp_taps_per_level=40))
    spec = _runs.ramp_run(scale, "pbc", 1)
    camp = FakeCampaign(tmp_path, [spec])
    levels = np.array([0.05, 0.1, 0.15, 0.2, 0.15, 0.1, 0.05])
    truth = np.array([0.58, 0.585, 0.59, 0.595, 0.605, 0.61, 0.615])
    write_ramp(camp, spec, *ramp_series(levels, truth, 40, np.random.default_rng(7)))
    before = fig4.hysteresis_branches(camp)
    path = camp.result(spec.name) / "taps.dat"
    lines = path.read_text().splitlines()
    for step in (75, 200):   # inside level 1's window (taps 65..80); level 4's last tap
        fields = lines[step + 1].split()
        assert int(fields[0]) == step
        lines[step + 1] = " ".join(fields[:3] + ["0.000000"] + fields[4:])
    path.write_text("\n".join(lines) + "\n")
    table = _runs.taps_table(camp, spec)
    repaired = _runs.ramp_sqrt_eps(table)
    assert repaired[0] == 0.0                      # step 0, before any tap, stays
    np.testing.assert_allclose(repaired[1:], np.repeat(levels, 40))
    after = fig4.hysteresis_branches(camp)
    assert before.keys() == after.keys()
    for name in before:
        for a, b in zip(before[name], after[name]):
            np.testing.assert_array_equal(a, b)
