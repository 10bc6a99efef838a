# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# tapmc.hysteresis: per-level steady states and the up/down/up branches of a synthetic ramp
# with known level values; tapmc.ageing: A(t, t_w) exactly on a hand-made example, and on a
# Gaussian process whose increments have the variogram of eq. 6 (the collapse must recover
# its parameters within the reported errors).
import os
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc._validate import NotComputedError  # noqa: E402
from tapmc.ageing import Ageing, ScalingRealizationTest  # noqa: E402
from tapmc.hysteresis import BranchStatistic, Hysteresis, seeds_together  # noqa: E402
from tapmc.laws import AgeingLaw  # noqa: E402


def ramp(taps_per_level, rng, noise=1e-3):
    up = np.round(np.arange(1, 9) * 0.025, 6)       # 0.025 .. 0.2
    down = up[-2::-1]                               # 0.175 .. 0.025
    up2 = up[1:]                                    # 0.05 .. 0.2
    levels = np.concatenate([up, down, up2])
    bell = lambda s: 0.60 + 0.1 * s - 0.3 * s * s   # noqa: E731
    truth = np.concatenate([bell(up), 0.63 - 0.05 * down, 0.63 - 0.05 * up2])
    sqrt_eps = np.repeat(levels, taps_per_level)
    x = np.repeat(truth, taps_per_level) + rng.normal(0, noise, sqrt_eps.size)
    return levels, truth, sqrt_eps, x


def test_ramp_levels_and_branches():
    rng = np.random.default_rng(4)
    levels, truth, sqrt_eps, x = ramp(400, rng)
    h = Hysteresis(sqrt_eps, x, taps_per_level=400, last=100).compute()
    lv = h.levels
    assert len(lv) == len(levels)
    np.testing.assert_allclose(lv["sqrt_eps"], levels)
    assert list(lv["branch"]) == ["up1"] * 8 + ["down"] * 7 + ["up2"] * 7
    np.testing.assert_array_equal(lv["first_tap"], 1 + 400 * np.arange(len(levels)))
    z = (lv["mean"] - truth) / lv["sem"]
    assert np.mean(np.abs(z) <= 2) >= 0.8
    assert np.all(np.abs(lv["std"] - 1e-3) < 3e-4)
    assert len(h.branch("down")) == 7 and h.branch("up2")["sqrt_eps"][0] == 0.05


def test_branches_follow_the_turns_not_the_highest_level():
    """A loop whose second increase goes higher than the first (0.05-0.15, down to 0.05, up to
    0.2): the first increase ends at its own turn, not at the highest level; a ramp that turns
    down again after the second increase is refused, naming the level; a flat top (a level
    repeated) stays on the first increase until the ramp falls."""
    levels = [0.05, 0.10, 0.15, 0.10, 0.05, 0.10, 0.15, 0.20]
    x = np.repeat(np.arange(len(levels), dtype=float), 10)
    h = Hysteresis(np.repeat(levels, 10), x, taps_per_level=10, last=5).compute()
    assert list(h.levels["branch"]) == ["up1"] * 3 + ["down"] * 2 + ["up2"] * 3
    np.testing.assert_allclose(h.branch("down")["sqrt_eps"], [0.10, 0.05])
    np.testing.assert_allclose(h.branch("up2")["mean"], [5, 6, 7])
    twice = levels + [0.15]
    with pytest.raises(ValueError, match=r"level 8 \(taps 81..90\): sqrt\(eps\) turns down "
                       r"again, from 0.2 to 0.15, .* pass the taps up to 80"):
        Hysteresis(np.repeat(twice, 10), np.zeros(90), 10, 5).compute()
    flat = [0.05, 0.10, 0.10, 0.05]
    h = Hysteresis(np.repeat(flat, 10), np.zeros(40), 10, 5).compute()
    assert list(h.levels["branch"]) == ["up1", "up1", "up1", "down"]


def test_ramp_incomplete_level_and_errors():
    rng = np.random.default_rng(1)
    _, _, sqrt_eps, x = ramp(400, rng)
    h = Hysteresis(sqrt_eps[:-350], x[:-350], taps_per_level=400, last=100)
    with pytest.raises(NotComputedError):
        h.incomplete_taps
    h.compute()
    assert len(h.levels) == 21 and h.incomplete_taps == 50
    with pytest.raises(ValueError, match="varies"):
        Hysteresis(sqrt_eps[200:], x[200:], taps_per_level=400, last=300).compute()
    with pytest.raises(ValueError, match="last = 500 exceeds taps_per_level"):
        Hysteresis(sqrt_eps, x, taps_per_level=400, last=500)
    with pytest.raises(ValueError, match="same length"):
        Hysteresis(sqrt_eps, x[:-1])
    with pytest.raises(ValueError, match="branch"):
        Hysteresis(sqrt_eps, x, 400, 100).compute().branch("sideways")


def test_ageing_exact_small_example():
    z = np.array([[0.0, 1.0, 3.0, 6.0],
                  [0.0, 2.0, 2.0, 2.0]])
    ag = Ageing(z, waiting_times=[0, 1]).compute()
    np.testing.assert_array_equal(ag.t, [0, 1, 2])
    # t_w = 0: (z(t) - z(0))^2 averaged: t=1: (1 + 4)/2, t=2: (9 + 4)/2
    np.testing.assert_allclose(ag.A[0], [0.0, 2.5, 6.5])
    # t_w = 1: (z(1 + t) - z(1))^2: t=1: (4 + 0)/2, t=2: (25 + 0)/2
    np.testing.assert_allclose(ag.A[1], [0.0, 2.0, 12.5])
    np.testing.assert_allclose(ag.A_sem[1], np.std([[0, 4, 25], [0, 0, 0]], axis=0, ddof=1)
                               / np.sqrt(2))
    with pytest.raises(ValueError, match="waiting time 3"):
        Ageing(z, waiting_times=[3])
    with pytest.raises(ValueError, match="z_series"):
        Ageing(z[:1], waiting_times=[0])


def test_ageing_collapse_recovers_eq6():
    # stationary Gaussian process with covariance (A_inf/2) g(|i - j|), g = 1/(1 + B ln(1+t/tau))
    # (decreasing and convex, so a valid covariance): the mean of (Z(t_w+t) - Z(t_w))^2 is
    # exactly eq. 6 for every t_w, i.e. the curves collapse.
    A_inf, B, tau = 4e-3, 0.6, 5.0
    n = 241
    lag = np.abs(np.subtract.outer(np.arange(n), np.arange(n)))
    cov = 0.5 * A_inf / (1.0 + B * np.log1p(lag / tau))
    chol = np.linalg.cholesky(cov + 1e-12 * np.eye(n))
    rng = np.random.default_rng(9)
    z = 7.0 + (chol @ rng.normal(size=(n, 1000))).T
    ag = Ageing(z, waiting_times=[0, 20, 80], t=np.unique(np.geomspace(1, 160, 40).round()))
    ag.compute()
    expected = AgeingLaw.function(ag.t, A_inf, B, tau)
    for tw in ag.waiting_times:
        # the points of one curve share the realizations (strongly correlated along t), so the
        # check is per point at 4 standard errors, not a coverage fraction
        chi = (ag.A[tw] - expected) / ag.A_sem[tw]
        assert np.all(np.abs(chi) < 4), (tw, chi)
    res = ag.collapse()
    assert res.determined, res
    for name, true in zip(res.names, (A_inf, B, tau)):
        # points of different t_w share realizations (correlated), so allow 3 sigma
        assert abs(res.params[name] - true) <= 3 * res.errors[name] + 0.05 * true, res
    assert ag.fit(20).params["A_inf"] == pytest.approx(A_inf, rel=0.3)


def test_plots():
    import matplotlib
    matplotlib.use("Agg")
    rng = np.random.default_rng(0)
    _, _, sqrt_eps, x = ramp(200, rng)
    ax = Hysteresis(sqrt_eps, x, 200, 100).compute().plot()
    assert len(ax.containers) == 3
    z = np.cumsum(rng.normal(size=(5, 60)), axis=1)
    ax = Ageing(z, [0, 10]).compute().plot(fit=False)
    assert len(ax.containers) == 2


def test_ageing_undetermined_cases_are_reported():
    # three random walks: A grows linearly (eq. 6 in its t << tau_A regime) and three
    # realizations are too few for bootstrap errors; both must show in the verdict
    rng = np.random.default_rng(0)
    z = 7.0 + np.cumsum(rng.normal(0, 1e-3, (3, 101)), axis=1)
    ag = Ageing(z, [1, 10, 30]).compute()
    for tw in (1, 10, 30):
        res = ag.fit(tw, bootstrap=12)
        assert not res.determined and res.note
    assert "too few" in ag.collapse(bootstrap=12).note
    with pytest.raises(ValueError, match="bootstrap"):
        ag.fit(1, bootstrap=-1)


def stationary_realizations(rng, realizations, taps=400, A_inf=4e-3, B=0.6, tau=5.0):
    """Realizations of <Z> whose A(t, t_w) is exactly eq. 6 for every t_w (the stationary
    Gaussian process of test_ageing_collapse_recovers_eq6): curves that collapse."""
    lag = np.abs(np.subtract.outer(np.arange(taps + 1), np.arange(taps + 1)))
    cov = 0.5 * A_inf / (1.0 + B * np.log1p(lag / tau))
    chol = np.linalg.cholesky(cov + 1e-12 * np.eye(taps + 1))
    return 7.0 + (chol @ rng.normal(size=(taps + 1, realizations))).T


def test_scaling_test_accepts_curves_that_collapse_and_rejects_a_ramp():
    z = stationary_realizations(np.random.default_rng(0), 10)
    test = Ageing(z, [0, 10, 30, 100]).compute().scaling_test(True)
    # 10 realizations: 9 bins of delays shared by the three curves, 5 parameters
    assert test.realizations == 10 and test.bins == {10: 3, 30: 3, 100: 3} and test.dof == 4
    assert test.compatible, test
    # a compaction that stops at tap 200 whatever the age: the curves of different t_w
    # have different shapes, which no rescaling of t and A makes one
    ramp = -0.3 * np.minimum(np.arange(401.0), 200) / 200
    bent = Ageing(z + ramp, [10, 30, 100]).compute().scaling_test(True)
    assert bent.p_value < 1e-3 and not bent.compatible, bent


def test_eq6_test_and_drift_share_tell_fluctuations_from_a_drift():
    # fluctuations whose A is eq. 6 exactly: eq. 6 compatible, no drift
    z = stationary_realizations(np.random.default_rng(2), 7)
    ageing = Ageing(z, [10, 100]).compute()
    for tw in (10, 100):
        test = ageing.eq6_test(tw)
        assert test.realizations == 7 and test.dof == 3 and test.compatible, test
        assert abs(ageing.drift_share(tw)) < 0.25
    # the same plus a compaction that goes on at a constant rate: A is the drift's square, t^2
    # at every delay, which eq. 6 (linear in t at short delays, then slower) cannot follow
    drifting = Ageing(z - 2e-3 * np.arange(401.0), [10, 100]).compute()
    for tw in (10, 100):
        assert drifting.drift_share(tw) > 0.95
        assert drifting.eq6_test(tw).p_value < 1e-3
    # a drift alone, the same in every realization: its share is 1 exactly
    same = Ageing(np.tile(-1e-3 * np.arange(401.0), (5, 1)) + 1e-9 * z[:5], [10]).compute()
    assert same.drift_share(10) == pytest.approx(1.0, abs=1e-6)
    with pytest.raises(ValueError, match="t_w = 30 is not one of the waiting times"):
        ageing.eq6_test(30)


def test_scaling_test_names_what_it_needs():
    z = stationary_realizations(np.random.default_rng(1), 6)
    with pytest.raises(ValueError, match="6 realizations: the test of the collapse of 3 curves "
                                         "needs at least 7"):
        Ageing(z, [10, 30, 100]).compute().scaling_test(True)
    in_time = Ageing(z, [10, 30, 100]).compute().scaling_test(False)   # 4 parameters: 6 do
    assert in_time.dof == 1 and sum(in_time.bins.values()) == 5
    with pytest.raises(ValueError, match="must be integers > 0"):
        ScalingRealizationTest().compute(z, [0, 10])
    with pytest.raises(RuntimeError, match="compute"):
        ScalingRealizationTest().p_value


def test_seeds_together_pools_the_seeds_and_weighs_their_scatter():
    """Three seeds: the pooled mean and its error are those of a mean of independent seeds;
    the scatter is the chi2 about the inverse-variance mean, brute force; seeds beyond their
    errors are not consistent; seeds that scatter more than their errors (chi2 > dof) but
    are not rejected widen the pooled error by sqrt(chi2 / dof), below that it stays; one
    seed or an error of 0 is refused."""
    from scipy.stats import chi2
    values, sems = np.array([0.001, 0.002, 0.0045]), np.array([0.0005, 0.001, 0.0008])
    together = seeds_together(BranchStatistic(v, s, 3) for v, s in zip(values, sems))
    assert together.pooled.value == pytest.approx(values.mean())
    w = 1 / sems ** 2
    reduced = np.sum(w * (values - np.sum(w * values) / np.sum(w)) ** 2) / 2
    assert reduced > 1
    assert together.pooled.sem == pytest.approx(np.sqrt(reduced * np.sum(sems ** 2)) / 3)
    assert together.pooled.n == 9 and together.dof == 2
    w = 1 / sems ** 2
    mean = np.sum(w * values) / np.sum(w)
    assert together.chi2 == pytest.approx(np.sum(((values - mean) / sems) ** 2))
    assert together.p == pytest.approx(chi2.sf(together.chi2, 2))
    assert together.p < 0.01 and not together.consistent      # 0.0045 lies apart
    close = seeds_together([BranchStatistic(0.001, 0.001, 1), BranchStatistic(0.002, 0.001, 1)])
    assert close.chi2 == pytest.approx(0.5) and close.consistent
    assert close.pooled.sem == pytest.approx(np.sqrt(2) * 0.001 / 2)  # chi2 < dof: unscaled
    # the two default-eta seeds of the committed paper ramps (second increase minus descent):
    # chi2 = 2.9 for 1 dof is not rejected (p = 0.09), and the error of their mean widens
    apart = seeds_together([BranchStatistic(0.0001, 0.0004, 3), BranchStatistic(0.0012, 0.0005, 3)])
    assert apart.consistent and apart.chi2 > 1
    assert apart.pooled.sem == pytest.approx(np.sqrt(apart.chi2) * np.hypot(0.0004, 0.0005) / 2)
    for bad in ([BranchStatistic(0.001, 0.001, 1)],
                [BranchStatistic(0.001, 0.001, 1), BranchStatistic(0.002, 0.0, 1)]):
        with pytest.raises(ValueError, match="needs 2 or more"):
            seeds_together(bad)
