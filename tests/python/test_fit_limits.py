# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# Fits that know their limits (tapmc.laws): profile-likelihood intervals that close around the
# truth at their nominal rate when the data determine a parameter and stay open when they do
# not (no curvature error shown then); refits over several tap ranges that agree for a correct
# law and disagree for a wrong one (section III.B: "depends strongly on the range of taps");
# the exponential dependence of B on sqrt(eps) (section III.A) accepted for a straight ln B and
# rejected for a curved one. Synthetic data with known answers; a few seconds.
import os
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.laws import (AgeingLaw, InverseLogLaw, RANGE_Z_LIMIT, ZLaw,  # noqa: E402
                        default_tap_ranges, exponential_dependence, range_refits)
from tapmc.fluctuations import PowerSpectrum  # noqa: E402

TAPS = np.unique(np.round(np.concatenate([[0], np.geomspace(1, 4000, 200)])))
TRUE_EQ3 = np.array([0.64, 0.05, 0.4, 8.0])
SEEDS = 30


def test_profile_intervals_cover_the_truth_at_their_nominal_rate():
    # 30 seeds: a 68.3 % interval holds the truth Binomial(30, 0.683) times (mean 20.5, sd 2.5,
    # i.e. a fraction 0.683 +- 0.085); the four parameters move together, so their mean
    # scatters almost as much: bounds about 3 sd away (150 seeds give 0.71, 0.71, 0.71, 0.67)
    inside = np.zeros(4)
    for seed in range(SEEDS):
        rng = np.random.default_rng(2000 + seed)
        y = InverseLogLaw.function(TAPS, *TRUE_EQ3) + rng.normal(0, 1e-3, TAPS.size)
        res = InverseLogLaw().fit(TAPS, y, sigma=1e-3)
        assert res.determined_params == list(res.names), (seed, res)
        lo = np.array([res.intervals[k].lo for k in res.names])
        hi = np.array([res.intervals[k].hi for k in res.names])
        inside += (lo <= TRUE_EQ3) & (TRUE_EQ3 <= hi)
    frac = inside / SEEDS
    assert np.all(frac >= 0.4) and np.all(frac <= 0.95), frac
    assert 0.45 <= frac.mean() <= 0.92, frac


def test_short_range_leaves_tau_undetermined_and_shows_no_curvature_error():
    # tau far beyond the data (the early regime of a slow run): only B/tau is seen
    t = np.arange(0.0, 100.0)
    rng = np.random.default_rng(7)
    y = InverseLogLaw.function(t, 0.64, 0.06, 0.3, 1e4) + rng.normal(0, 1e-3, t.size)
    res = InverseLogLaw().fit(t, y, sigma=1e-3)
    tau = res.intervals["tau"]
    assert not tau.determined and np.isnan(tau.hi)  # open above: any longer tau fits
    assert "tau" in res.undetermined_params and not res.determined
    assert np.isnan(res.errors["tau"]) and np.isfinite(res.curvature_errors["tau"])
    assert "undetermined" in repr(res)
    # the profile's chi2 stays within the threshold up to the allowed limit (last tap x 10^3)
    assert tau.limits[1] == pytest.approx(99.0 * 1e3)
    assert np.all(tau.delta_chi2[tau.grid >= tau.value] <= 1.0)


def test_profile_rescaled_by_the_reduced_chi2():
    # errors given 3x too small: the reduced chi2 (~9) widens the intervals back to the
    # width of a fit with the right errors; an unweighted fit uses the residual scatter
    rng = np.random.default_rng(11)
    y = InverseLogLaw.function(TAPS, *TRUE_EQ3) + rng.normal(0, 3e-3, TAPS.size)
    right = InverseLogLaw().fit(TAPS, y, sigma=3e-3)
    small = InverseLogLaw().fit(TAPS, y, sigma=1e-3)
    plain = InverseLogLaw().fit(TAPS, y)
    assert small.reduced_chi2 > 5
    for k in right.names:
        w = right.intervals[k].hi - right.intervals[k].lo
        for other in (small, plain):
            assert other.intervals[k].hi - other.intervals[k].lo == pytest.approx(w, rel=0.15)


@pytest.mark.parametrize("law,true,noise", [
    (ZLaw(), [7.0, 7.4, 0.4, 3.0], 5e-3),
    (AgeingLaw(), [0.02, 0.5, 10.0], 3e-4),
])
def test_every_law_gets_intervals(law, true, noise):
    rng = np.random.default_rng(5)
    y = law.function(TAPS, *true) + rng.normal(0, noise, TAPS.size)
    res = law.fit(TAPS, y, sigma=noise)
    for k, v in zip(res.names, true):
        iv = res.intervals[k]
        assert iv.method == "profile" and iv.determined
        assert iv.lo < res.params[k] < iv.hi
        # within 4 half-widths of the truth
        assert abs(res.params[k] - v) < 4 * max(iv.hi - iv.value, iv.value - iv.lo)
    assert res.profile_delta_chi2(res.names[0], res.intervals[res.names[0]].hi) == \
        pytest.approx(1.0, abs=0.1)


def test_results_built_from_a_covariance_keep_curvature_intervals():
    rng = np.random.default_rng(0)
    ps = PowerSpectrum(rng.normal(size=2000)).compute()
    iv = ps.fit.intervals["slope"]
    assert iv.method == "curvature" and iv.determined
    assert iv.hi - iv.value == pytest.approx(ps.slope_error)


def test_range_refits_consistent_for_the_right_law():
    taps = np.arange(0.0, 4001.0)
    assert default_tap_ranges(taps) == [(1.0, 1000.0), (1.0, 2000.0), (1.0, 4000.0),
                                        (400.0, 4000.0)]
    worst = []
    for seed in range(2):
        rng = np.random.default_rng(300 + seed)
        y = InverseLogLaw.function(taps, *TRUE_EQ3) + rng.normal(0, 2e-3, taps.size)
        r = range_refits(InverseLogLaw(), taps, y, 2e-3)
        assert r.range_dependent == [], r
        worst.append(max(r.deviation.values()))
        assert all(np.isfinite(list(r.spread.values())))
    assert max(worst) < RANGE_Z_LIMIT


def test_range_refits_detect_a_wrong_law():
    # a stretched exponential fitted by eq. 3: the full-range fit looks acceptable (reduced
    # chi2 about 1.03 on 4000 points) but each tap range wants other parameters
    taps = np.arange(0.0, 4001.0)
    rng = np.random.default_rng(1)
    y = 0.64 - 0.06 * np.exp(-np.sqrt(taps / 200.0)) + rng.normal(0, 2e-3, taps.size)
    r = range_refits(InverseLogLaw(), taps, y, 2e-3)
    assert r.reference.reduced_chi2 < 1.1
    assert set(r.range_dependent) == set(InverseLogLaw.names), r
    assert min(r.deviation.values()) > 2 * RANGE_Z_LIMIT


def test_range_refits_validation():
    with pytest.raises(ValueError, match="must be a tapmc.laws.Law"):
        range_refits("eq3", TAPS, TAPS)
    with pytest.raises(ValueError, match="first < last"):
        range_refits(InverseLogLaw(), TAPS, TAPS, ranges=[(10, 1)])
    # ranges beyond the run: every parameter read "consistent" from no fit at all; now none
    # is decided (a short run's fit of all taps is still made)
    taps = np.arange(0.0, 2001.0)
    beyond = range_refits(InverseLogLaw(), taps, 0.6 - 0.05 / (1 + np.log1p(taps / 10)),
                          ranges=[(3e3, 5e5), (2e5, 2e6)])
    assert beyond.fits == [None, None] and beyond.range_dependent == []
    assert all(ok is None for ok in beyond.consistent.values())
    # a run of 3 taps: the default [1, T/4] would be (1, 0.75)
    with pytest.raises(ValueError, match=r"t ends at tap 3: the default ranges start with"):
        range_refits(InverseLogLaw(), [0, 1, 2, 3], [0.5, 0.51, 0.52, 0.53])


def test_range_refits_without_a_fit_to_compare_decide_nothing():
    """A range whose fit did not converge is left out; with none left, the deviation is nan
    and no parameter is called consistent or range dependent (they were all "consistent")."""
    taps = np.arange(0.0, 4001.0)
    rng = np.random.default_rng(1)
    y = 0.64 - 0.06 * np.exp(-np.sqrt(taps / 200.0)) + rng.normal(0, 2e-3, taps.size)
    r = range_refits(InverseLogLaw(), taps, y, 2e-3)
    for f in r.fits:
        f.converged = False
    r._deviation = None
    assert all(np.isnan(v) for v in r.deviation.values())
    assert all(ok is None for ok in r.consistent.values()) and r.range_dependent == []


def test_exponential_dependence_of_b():
    sqrt_eps = np.array([0.07, 0.12, 0.2, 0.3, 0.39])
    rel = 0.1  # 10 % intervals on B
    rng = np.random.default_rng(4)
    # ln B linear in sqrt(eps): accepted, slope within its interval
    B = np.exp(-1.0 + 8.0 * sqrt_eps + rng.normal(0, rel, sqrt_eps.size))
    res = exponential_dependence(sqrt_eps, B, B * np.exp(-rel), B * np.exp(rel))
    iv = res.slope_interval
    assert res.linear and res.dof == 3 and iv.lo < 8.0 < iv.hi
    # ln B quadratic in sqrt(eps): rejected
    Bq = np.exp(-1.0 + 60.0 * (sqrt_eps - 0.2) ** 2)
    bad = exponential_dependence(sqrt_eps, Bq, Bq * np.exp(-rel), Bq * np.exp(rel))
    assert bad.linear is False and bad.p_value < 1e-6
    # undetermined B (open interval) are left out; two points: a slope, no test
    lo = B * np.exp(-rel)
    lo[2:] = np.nan
    two = exponential_dependence(sqrt_eps, B, lo, B * np.exp(rel))
    assert list(two.excluded) == list(sqrt_eps[2:]) and two.linear is None
    assert np.isfinite(two.slope) and two.slope_interval.determined
    none = exponential_dependence(sqrt_eps[:1], B[:1], [np.nan], B[:1])
    assert none.fit is None and np.isnan(none.slope) and "not testable" in repr(none)
    # two seeds of one eps: two determined B, no slope (was an infinite one)
    seeds = exponential_dependence([0.1, 0.1], [1.0, 2.0], [0.9, 1.8], [1.1, 2.2])
    assert seeds.fit is None and np.isnan(seeds.slope) and "not testable" in repr(seeds)
    assert list(seeds.used) == [0.1, 0.1]


# ---- Fig. 2: every statistic from the figure's CSV alone -------------------------------------

def _fig2_table(tmp_path, law_is_right=True):
    """A Fig. 2 CSV written by FigureTable: Phi_b (eq. 3) and <Z> (eq. 4) at three eps, B
    exponential in sqrt(eps), three seeds' standard errors."""
    from tapmc.paper import _plotting as P

    t = np.arange(0.0, 1001.0)
    rng = np.random.default_rng(8)
    table = P.FigureTable()
    for eps in (0.005, 0.05, 0.15):
        B = 0.1 * np.exp(5.0 * np.sqrt(eps))
        phi = InverseLogLaw.function(t, 0.62, 0.05, B, 20.0)
        z = ZLaw.function(t, 7.0, 7.4, B, 20.0)
        for panel, y, noise in (("a", phi, 2e-3), ("c", z, 5e-3)):
            sem = np.full(t.size, noise)
            table.add(panel, f"eps={P.fmt_eps(eps)}", t, y + rng.normal(0, noise, t.size), sem, 3)
    path = tmp_path / "fig2.csv"
    table.write(path)
    return P.read_table(path)


def test_fig2_statistics_from_a_csv(tmp_path):
    from tapmc.paper import fig2

    stats = fig2.statistics(_fig2_table(tmp_path))
    assert sorted(stats) == ["eq3", "eq4"]
    for tag, truth in (("eq3", InverseLogLaw.names), ("eq4", ZLaw.names)):
        for eps, refits in stats[tag]["curves"].items():
            assert refits.reference.determined_params == list(truth), (tag, eps)
            assert refits.range_dependent == [], (tag, eps, refits)
        dep = stats[tag]["B"]
        iv = dep.slope_interval
        assert dep.linear and iv.lo - 3 * (iv.hi - iv.lo) < 5.0 < iv.hi + 3 * (iv.hi - iv.lo)


def test_pooled_sem_tames_a_chance_agreement_of_the_seeds():
    from tapmc.paper.fig2 import pooled_sem

    sem = np.full(200, 1e-3)
    sem[100] = 1e-7  # two seeds crossing at one tap
    pooled = pooled_sem(sem, window=51)
    assert pooled[100] == pytest.approx(1e-3, rel=0.02)
    assert np.allclose(pooled[:75], 1e-3)  # beyond the half window of tap 100
    assert pooled_sem(np.full(5, np.nan)) is None
    with pytest.raises(ValueError, match="window"):
        pooled_sem(sem, window=0)


# ---- Fig. 5: the scaling variable of A(t, t_W) -------------------------------------------------

WAITING = (10.0, 30.0, 100.0, 300.0)


def _ageing_curves(mu, kappa, seed, shapes=None, rel=0.05):
    """A(t, t_W) = r^kappa eq6(t / r^mu), r = t_W / t_ref, with 5 % noise; ``shapes`` (B_A
    per curve) breaks the scaling."""
    from tapmc.laws import AgeingLaw

    t = np.arange(0.0, 751.0)
    t_ref = np.exp(np.mean(np.log(WAITING)))
    rng = np.random.default_rng(seed)
    out = {}
    for k, tw in enumerate(WAITING):
        r = tw / t_ref
        B = 0.5 if shapes is None else shapes[k]
        A = r ** kappa * AgeingLaw.function(t / r ** mu, 0.02, B, 10.0)
        sem = rel * A + 1e-12
        out[tw] = (t, A + rng.normal(0, 1, t.size) * sem, sem)
    return out


def test_collapse_recovers_a_known_scaling_exponent():
    from tapmc.ageing import scaling_collapse

    hits = 0
    for seed in range(3):
        col = scaling_collapse(_ageing_curves(0.7, 0.3, seed))
        mu, kappa = col.interval("mu"), col.interval("kappa")
        assert mu.determined and kappa.determined
        hits += mu.lo <= 0.7 <= mu.hi
        assert abs(col.mu - 0.7) < 0.05 and abs(col.kappa - 0.3) < 0.05
        assert col.reduced_chi2 < 2 and col.unscaled_reduced_chi2 > 10 * col.reduced_chi2
        s, a = col.rescale(30.0, *_ageing_curves(0.7, 0.3, seed)[30.0][:2])
        assert np.all(np.isfinite(s)) and np.all(np.isfinite(a))
    assert hits >= 2
    # the law-free dispersion agrees: about 1 at the exponents, large without rescaling, and
    # its own minimum is at the exponents of the curves
    assert col.dispersion() < 1.5 and col.dispersion(0.0, 0.0) > 10
    mu_free, kappa_free = col.dispersion_exponents
    assert abs(mu_free - 0.7) < 0.05 and abs(kappa_free - 0.3) < 0.05
    # time alone cannot absorb the amplitude factor: a worse collapse
    only_time = scaling_collapse(_ageing_curves(0.7, 0.3, 0), fit_amplitude=False)
    assert "kappa" not in only_time.fit.names and only_time.kappa == 0.0
    assert only_time.reduced_chi2 > 5 * col.reduced_chi2


def test_curves_without_a_scaling_collapse_poorly():
    from tapmc.ageing import scaling_collapse

    # curves of different shapes (B_A from 0.05 to 50): no exponents make them one curve; the
    # collapse stays far above the reduced chi2 of about 1 of curves that do scale, and mu
    # runs to a limit of its allowed range (its interval stays open there)
    col = scaling_collapse(_ageing_curves(0.0, 0.0, 1, shapes=(0.05, 0.5, 5.0, 50.0)))
    assert col.reduced_chi2 > 5
    assert not col.interval("mu").determined
    assert col.dispersion(*col.dispersion_exponents) > 5


def test_fig5_statistics_from_a_csv(tmp_path):
    from tapmc.paper import _plotting as P
    from tapmc.paper import fig5

    table = P.FigureTable()
    for tw, (t, a, sem) in _ageing_curves(0.7, 0.3, 4).items():
        table.add("a", f"tw={tw:g}", t, a, sem, 10)
    table.write(tmp_path / "fig5.csv")
    curves = fig5.curves_from_table(P.read_table(tmp_path / "fig5.csv"))
    assert sorted(curves) == list(WAITING)
    stats = fig5.scaling_statistics(curves)
    assert fig5.drawn_collapse(stats) is stats["scaling"]
    assert stats["scaling"].interval("mu").lo <= 0.7 + 0.05


def test_fig5_test_rows_from_the_realizations(tmp_path):
    # the rows the claim ageing-scaling reads: the drawn collapse tested across 10
    # realizations of curves that collapse (eq. 6 for every t_w), and the threshold alone
    # with fewer realizations than the test needs
    from tapmc.ageing import Ageing
    from tapmc.paper import _plotting as P
    from tapmc.paper import fig5

    sys.path.insert(0, str(HERE))
    from test_hysteresis_ageing import stationary_realizations

    z = stationary_realizations(np.random.default_rng(0), 10)
    for realizations, tested in ((10, True), (6, False)):
        result = Ageing(z[:realizations], [10, 30, 100]).compute()
        stats = {"scaling": result.scaling(True), "scaling_time": result.scaling(False)}
        table = P.FigureTable()
        test = fig5.add_test_rows(table, result, stats["scaling"], True)
        table.write(tmp_path / "fig5.csv")
        rows = P.read_table(tmp_path / "fig5.csv")
        assert rows[("params", "scaling_test:needed")]["mean"][0] == 7
        assert (("params", "scaling_test:T2") in rows) == tested
        if tested:
            assert rows[("params", "scaling_test:p_value")]["mean"][0] == pytest.approx(
                test.p_value) and test.compatible
            assert rows[("params", "scaling_test:bins")]["mean"][0] == 9
            assert rows[("params", "scaling_test:dof")]["mean"][0] == 4


def test_scaling_collapse_validation():
    from tapmc.ageing import scaling_collapse

    curves = _ageing_curves(0.5, 0.0, 0)
    with pytest.raises(ValueError, match="at least 2"):
        scaling_collapse({10.0: curves[10.0]})
    with pytest.raises(ValueError, match="must be > 0"):
        scaling_collapse({0.0: curves[10.0], 30.0: curves[30.0]})


def test_interval_widened_by_an_error_found_otherwise():
    from tapmc.laws import Interval

    iv = Interval(1.0, 0.9, 1.2, (0.0, 10.0), "profile")
    wide = iv.widened(0.5)
    assert (wide.lo, wide.hi) == (0.5, 1.5) and wide.determined
    assert iv.widened(0.05).lo == 0.9 and iv.widened(0.05).hi == 1.2  # never narrowed
    assert not iv.widened(2.0).determined and np.isnan(iv.widened(2.0).lo)  # below limit 0
    opened = Interval(1.0, 0.9, None, (0.0, 10.0), "profile").widened(0.5)
    assert np.isnan(opened.hi) and opened.lo == 0.5
